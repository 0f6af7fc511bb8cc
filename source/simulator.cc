// The Simulator: builds the multi-body system and the driver of its method,
// and runs the load steps with their report and checkpoints.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <densify/drivers/explicit_driver.h>
#include <densify/postprocess/run_log.h>
#include <densify/run/quasi_static_stop.h>
#include <densify/scene.h>
#include <densify/simulator.h>
#include <densify/utilities.h>

#include <stdexcept>

namespace densify
{
  Simulator::Simulator(const Parameters &parameters,
                       const MPI_Comm    comm,
                       const bool        console,
                       const RunControl &control)
    : prm(parameters)
    , control(control)
    , comm(comm)
    , this_rank(Utilities::MPI::this_mpi_process(comm))
    , log_file(open_log(parameters.output.directory, comm, control.resume))
    , tee(std::make_unique<TeeStream>(console ? &std::cout : nullptr,
                                      this_rank == 0 ? &log_file : nullptr))
    , pcout(*tee, this_rank == 0)
    , timer(comm, pcout, TimerOutput::never, TimerOutput::wall_times)
    , system(parameters, comm, pcout, timer)
    , report(parameters, system, pcout, timer)
  {}



  Simulator::~Simulator()
  {
    timer.reset();
  }



  void
  Simulator::setup_system()
  {
    system.setup_dofs();
    // the driver of the method; the force terms take the contact penalty
    // it gives (for explicit dynamics the one that fits the stable step of
    // the lumped mass)
    if (system.effects.method == Method::explicit_dynamics)
      driver = std::make_unique<ExplicitDriver>(
        prm, system, pcout, timer, this_rank == 0 ? &log_file : nullptr);
    else
      driver = std::make_unique<ImplicitDriver>(prm, system, pcout, timer);
    system.setup_force_terms(driver->prepare());
    driver->setup();
    checkpoint = std::make_unique<Checkpoint>(
      prm, system, *driver, report.graphics, pcout, timer);
  }



  void
  Simulator::setup()
  {
    if (system.dof_handler.has_active_dofs())
      return;
    TimerOutput::Scope t(timer, "Setup");
    Scene scene = given_scene ? std::move(*given_scene) : build_scene(prm);
    const Effects effects =
      given_effects ? *given_effects : resolve_effects(prm, scene);
    given_scene.reset();
    given_effects.reset();
    system.setup_particles(std::move(scene), effects);
    system.setup_mesh();
    setup_system();
  }



  void
  Simulator::keep_failed_run(const ConvergenceError &e,
                             const unsigned int      step,
                             const double            wall_seconds) const
  {
    // every rank failed alike, back at the last converged increment: keep
    // it for a resumption with other solver settings
    try
      {
        checkpoint->write(step, wall_seconds);
      }
    catch (const std::exception &c)
      {
        throw ConvergenceError(std::string(e.what()) + "; " + c.what());
      }
    throw ConvergenceError(
      std::string(e.what()) + "; the last converged state (time " +
      Utilities::to_string(system.current_time) + " s) is in " +
      prm.output.directory +
      "/checkpoint/: continue with --resume and other Solver or "
      "Time stepping/Maximum cut-backs settings");
  }



  bool
  Simulator::run()
  {
    Timer wall;
    setup();
    report.start();
    // at rest at the start (or at the checkpoint's state, which the
    // checkpoint then restores); a resumed run continues after the
    // checkpoint's step, appending to the files' rows up to that step
    driver->start();
    unsigned int first_step = 1;
    if (control.resume)
      {
        const Checkpoint::Resumed resumed = checkpoint->read();
        first_step                        = resumed.step + 1;
        wall_before                       = resumed.wall_seconds;
        if (control.stop_after > 0 && control.stop_after < first_step)
          throw InputError(
            "--stop-after " + std::to_string(control.stop_after) +
            ": the checkpoint is after step " + std::to_string(resumed.step) +
            ", so the run would never stop there; give a later load step, "
            "or no --stop-after");
      }
    report.open(control.resume, first_step);
    QuasiStaticStop quasi_static(prm, system, *checkpoint);

    const unsigned int n_steps = prm.time.n_steps;
    for (unsigned int step = first_step; step <= n_steps; ++step)
      {
        Timer          step_timer;
        const double   time   = prm.time.end_time * step / n_steps;
        const double   before = prm.time.end_time * (step - 1) / n_steps;
        StepStatistics s;
        s.step                      = step;
        s.time                      = time;
        s.wall_seconds              = wall_before + wall.wall_time();
        const double   upper_before = system.upper_punch_position(before);
        const double   lower_before = system.lower_punch_position(before);
        ContactResults results;
        try
          {
            results = driver->advance(time, step, s);
          }
        catch (const ConvergenceError &e)
          {
            if (step == first_step && system.current_time == 0)
              throw;
            keep_failed_run(e, step - 1, wall_before + wall.wall_time());
          }
        report.record(
          s, results, *driver, upper_before, lower_before, step_timer);
        quasi_static.check(s, n_steps);

        // the share of the work done since the start of this process: the
        // stations, or for explicit runs the physical time, whose steps
        // are equal while a station's are not (Explicit/End speed fraction)
        const auto work = [&](const unsigned int k) {
          return driver->physical_time(prm.time.end_time * k / n_steps);
        };
        report.progress(s,
                        (s.wall_seconds - wall_before) /
                          (work(step) - work(first_step - 1)) *
                          (work(n_steps) - work(step)));

        // stop on request (every rank must agree) or write the periodic
        // checkpoint, the last step's too where it is a multiple of the
        // interval: a finished run can be pressed further
        const bool signalled =
          Utilities::MPI::max(control.stop_request != nullptr &&
                                  *control.stop_request != 0 ?
                                1 :
                                0,
                              comm) > 0;
        const bool stop =
          step < n_steps && (signalled || step == control.stop_after);
        if (stop || (prm.output.checkpoint_interval > 0 &&
                     step % prm.output.checkpoint_interval == 0))
          quasi_static.write_checkpoint(step, s.wall_seconds);
        if (stop)
          {
            pcout << "Stopped after step " << step << "/" << n_steps
                  << (signalled ? " on a signal" : " (--stop-after)")
                  << "; checkpoint in " << prm.output.directory
                  << "/checkpoint/; continue with --resume" << std::endl;
            timer.print_summary();
            return false;
          }
      }
    report.summarise();
    pcout << "Finished " << n_steps << " steps in "
          << format_seconds(wall_before + wall.wall_time()) << "; results in "
          << prm.output.directory << "/" << std::endl;
    timer.print_summary();
    return true;
  }
} // namespace densify
