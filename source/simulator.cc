// The Simulator: builds the multi-body system and the driver of its method,
// and runs the load steps with their statistics and output.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/contact/broad_search.h>
#include <densify/geometry/multi_body_mesh.h>
#include <densify/material/factory.h>
#include <densify/postprocess/compact_envelope.h>
#include <densify/postprocess/compaction_curve.h>
#include <densify/postprocess/quasi_static_guard.h>
#include <densify/postprocess/run_log.h>
#include <densify/scene.h>
#include <densify/simulator.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>
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
  }



  std::pair<std::vector<unsigned int>, std::vector<double>>
  Simulator::station_contacts() const
  {
    const ContactRecord *record = driver->station_record();
    if (record == nullptr)
      return {contact_partners(), particle_tool_forces(ToolKind::die_wall)};
    std::vector<double> die_force = record->die_force;
    Utilities::MPI::sum(die_force, comm, die_force);
    return {system.particle_contact ?
              system.particle_contact->partners_of(record->pairs) :
              std::vector<unsigned int>(system.particles.size(), 0),
            die_force};
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



  bool
  Simulator::run()
  {
    Timer wall;
    setup();

    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    pcout << "Densify: " << system.particles.size() << " particle(s), "
          << system.triangulation.n_active_cells() << " tetrahedra, "
          << n_dofs() << " DoFs (P" << prm.mesh.degree << "), " << n_ranks
          << " MPI rank(s)" << std::endl;
    {
      // every distinct material law once, then the tools and the solver
      std::vector<std::string> laws;
      for (const auto &m : system.particle_material)
        if (std::find(laws.begin(), laws.end(), m->name()) == laws.end())
          laws.push_back(m->name());
      pcout << "Active effects: " << describe_effects(system.effects, laws, prm)
            << std::endl;
      if (!prm.fidelity_summary.empty())
        pcout << "Fidelity: " << prm.fidelity_summary << std::endl;
    }

    const double die_area =
      numbers::PI * std::pow(prm.tools.die_diameter / 2, 2);
    const bool has_density = prm.tools.die_enabled && prm.tools.lower_enabled &&
                             prm.tools.upper_enabled;
    auto density = [&](const double volume, const double gap) {
      return has_density ? volume / (die_area * gap) :
                           std::numeric_limits<double>::quiet_NaN();
    };
    {
      double v0 = 0;
      for (const double v : particle_volumes())
        v0 += v;
      if (has_density)
        pcout << "Initial relative density " << std::fixed
              << std::setprecision(2)
              << 100 * density(v0, system.upper_initial - system.lower_initial)
              << " % (particle volume of the mesh " << std::setprecision(4)
              << v0 << " mm^3)" << std::defaultfloat << std::endl;
    }

    for (const ParticleMeasure &m : system.measure_particles())
      initial_volumes.push_back(m.volume);
    // a resumed run continues after the checkpoint's step, appending to the
    // files' rows up to that step
    // at rest at the start (or at the checkpoint's state, which
    // read_checkpoint() then restores)
    driver->start();
    const unsigned int first_step = control.resume ? read_checkpoint() + 1 : 1;
    const std::string  statistics_name =
      prm.output.directory + "/statistics.csv";
    const std::string particle_name = prm.output.directory + "/particles.csv";
    // what rank 0 cannot write ends the run on every rank
    std::string open_error;
    if (this_rank == 0)
      try
        {
          const bool append = control.resume &&
                              std::filesystem::exists(statistics_name) &&
                              std::filesystem::exists(particle_name);
          if (append)
            {
              truncate_rows(statistics_name, first_step - 1);
              truncate_rows(particle_name, first_step - 1);
            }
          statistics_writer =
            std::make_unique<StatisticsWriter>(statistics_name, append);
          particle_writer =
            std::make_unique<ParticleTableWriter>(particle_name, append);
        }
      catch (const std::exception &e)
        {
          open_error = e.what();
        }
    open_error = first_error(open_error, comm);
    if (!open_error.empty())
      throw std::runtime_error(open_error);

    // the quasi-static guard of explicit runs whose mass scaling sets the
    // step (Explicit/Maximum kinetic energy ratio, Maximum force imbalance)
    QuasiStaticGuard guard(quasi_static_limits());
    guard_snapshot      = CheckpointSnapshot();
    guard_snapshot_wall = guard_snapshot_cost = 0.;

    const unsigned int n_steps = prm.time.n_steps;
    for (unsigned int step = first_step; step <= n_steps; ++step)
      {
        Timer          step_timer;
        const double   time         = prm.time.end_time * step / n_steps;
        const double   before       = prm.time.end_time * (step - 1) / n_steps;
        const double   upper_before = system.upper_punch_position(before);
        const double   lower_before = system.lower_punch_position(before);
        StepStatistics s;
        s.step = step;
        s.time = time;
        ContactResults results;
        try
          {
            results = driver->advance(time, step, s);
          }
        catch (const ConvergenceError &e)
          {
            // every rank failed alike, back at the last converged increment:
            // keep it for a resumption with other solver settings
            if (step == first_step && system.current_time == 0)
              throw;
            try
              {
                write_checkpoint(step - 1, wall_before + wall.wall_time());
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
        const ToolContactResult &contact = results.tools;
        // where the step left the punches (a force-controlled punch is
        // where its force took it)
        const double upper         = system.upper_punch_position(time);
        const double lower         = system.lower_punch_position(time);
        s.punch_displacement       = system.upper_initial - upper;
        s.lower_punch_displacement = lower - system.lower_initial;
        s.die_displacement         = interpolate(system.die_table, time) -
                             interpolate(system.die_table, 0.);
        {
          // the lower punch's rise in the die (a die lowered past a held
          // compact ejects it too); a lower punch under force control
          // presses: its rise closes the gap as the upper punch's advance
          // does
          const double rise = lower - lower_before -
                              (interpolate(system.die_table, time) -
                               interpolate(system.die_table, before));
          const bool pressing = system.lower_control.force_controlled(time);
          double     advance  = upper_before - upper + (pressing ? rise : 0.);
          // under force control the target's trend decides: a flat target
          // holds, whatever the punch's creep or elastic relaxation
          const PunchControl *controlled =
            system.punch_control.force_controlled(time) ?
              &system.punch_control :
            pressing ? &system.lower_control :
                       nullptr;
          if (controlled != nullptr)
            {
              const double a = controlled->target(before),
                           b = controlled->target(time);
              const double still =
                1e-9 * std::max({std::abs(a), std::abs(b), 1.});
              advance = b - a > still ? 1. : b - a < -still ? -1. : 0.;
            }
          s.phase = static_cast<unsigned int>(
            press_phase(advance, pressing ? 0. : rise));
        }

        const auto upper_kind =
          static_cast<unsigned int>(ToolKind::upper_punch);
        const auto lower_kind =
          static_cast<unsigned int>(ToolKind::lower_punch);
        const auto die_kind     = static_cast<unsigned int>(ToolKind::die_wall);
        s.upper_punch_force     = contact.normal_force[upper_kind];
        s.lower_punch_force     = contact.normal_force[lower_kind];
        s.die_wall_force        = contact.axial_force[die_kind];
        s.die_wall_radial_force = contact.normal_force[die_kind];
        s.max_penetration =
          std::max(contact.max_penetration, results.particles.max_penetration);
        s.particle_contact_force = results.particles.normal_force;
        s.upper_punch_friction   = contact.friction_force[upper_kind].norm();
        s.lower_punch_friction   = contact.friction_force[lower_kind].norm();
        s.slipping_points        = contact.n_slip + results.particles.n_slip;
        system.update_ghosts();
        const auto [partners, die_force] = station_contacts();
        for (const unsigned int n : partners)
          s.contact_pairs += n;
        s.contact_pairs /= 2;
        s.coordination_number = 2. * s.contact_pairs / system.particles.size();
        s.contact_area_fraction =
          2. * results.particles.contact_area /
          particle_surface_area(system.dof_handler, system.solution_ghosted);
        s.pole_force = system.pole_springs ? system.pole_springs->force() : 0.;
        std::vector<ParticleMeasure> measures;
        {
          TimerOutput::Scope t(timer, "Output: particle measures");
          measures = system.measure_particles(true);
        }
        for (const ParticleMeasure &m : measures)
          s.particle_volume += m.volume;
        // what rank 0 cannot write (e.g. a full disk) ends the run on every
        // rank; the rows written before stay complete
        std::string write_failure;
        if (this_rank == 0)
          write_failure = particle_writer->write(step,
                                                 system.particles,
                                                 measures,
                                                 initial_volumes,
                                                 partners,
                                                 die_force);
        s.relative_density = density(s.particle_volume, upper - lower);
        {
          const DieStresses stress =
            die_stresses(s.upper_punch_force,
                         s.lower_punch_force,
                         s.die_wall_radial_force,
                         prm.tools.die_enabled ? prm.tools.die_diameter : 0.,
                         prm.tools.lower_enabled && prm.tools.upper_enabled ?
                           upper - lower :
                           0.);
          s.upper_punch_stress = stress.upper_punch;
          s.lower_punch_stress = stress.lower_punch;
          s.die_wall_pressure  = stress.die_wall;
          s.radial_axial_ratio = stress.radial_axial_ratio;
          const CompactEnvelope envelope =
            compact_envelope(system.dof_handler, system.solution_ghosted);
          s.compact_height   = envelope.top - envelope.bottom;
          s.compact_diameter = 2 * envelope.radius;
          s.envelope_density =
            s.particle_volume / (numbers::PI * envelope.radius *
                                 envelope.radius * s.compact_height);
        }
        s.plastic_work = system.continuum->plastic_work(*system.mapping);
        const SmallestCellVolume smallest =
          smallest_cell_volume(system.dof_handler,
                               *system.mapping,
                               system.solution_ghosted);
        s.min_cell_volume_ratio = smallest.ratio;

        if (prm.output.interval > 0 &&
            (step % prm.output.interval == 0 || step == n_steps))
          write_graphics(step, time, measures);

        s.step_seconds = step_timer.wall_time();
        s.wall_seconds = wall_before + wall.wall_time();
        step_statistics.push_back(s);
        if (statistics_writer && write_failure.empty())
          write_failure = statistics_writer->write(s);
        write_failure = first_error(write_failure, comm);
        if (!write_failure.empty())
          throw std::runtime_error(write_failure);
        if (system.effects.method == Method::explicit_dynamics)
          warn_penetration(s);
        warn_cell_volume(s.step, smallest);
        // the station's rows are written, so that they show why it stops
        if (guard.active())
          check_quasi_static(s, guard);

        // the share of the work done since the start of this process: the
        // stations, or for explicit runs the physical time, whose steps
        // are equal while a station's are not (Explicit/End speed fraction)
        const auto work = [&](const unsigned int k) {
          const double tau = prm.time.end_time * k / n_steps;
          return driver->physical_time(tau);
        };
        const double done = work(step) - work(first_step - 1);
        const double left =
          (s.wall_seconds - wall_before) / done * (work(n_steps) - work(step));
        pcout << progress_line(s,
                               n_steps,
                               system.pole_springs != nullptr,
                               has_density,
                               system.effects.method ==
                                 Method::explicit_dynamics,
                               left)
              << std::endl;

        // stop on request (every rank must agree) or write the periodic
        // checkpoint
        const bool signalled =
          Utilities::MPI::max(control.stop_request != nullptr &&
                                  *control.stop_request != 0 ?
                                1 :
                                0,
                              comm) > 0;
        const bool stop =
          step < n_steps && (signalled || step == control.stop_after);
        // the snapshot for the guard's checkpoint at most every 50 times
        // its own cost in run time (every station of the light layer, every
        // few of the paper scene), so that it costs at most 2 %. Each rank
        // reads its own clock, so the ranks agree on it: taking a snapshot
        // is collective (its timer section synchronises the ranks), and a
        // rank that took one alone would wait there forever
        if (guard.judging() && step < n_steps &&
            Utilities::MPI::max(s.wall_seconds - guard_snapshot_wall >=
                                    50. * guard_snapshot_cost ?
                                  1 :
                                  0,
                                comm) > 0)
          {
            Timer snapshot;
            guard_snapshot      = checkpoint_snapshot(step, s.wall_seconds);
            guard_snapshot_cost = snapshot.wall_time();
            guard_snapshot_wall = s.wall_seconds;
          }
        // the last step's too where it is a multiple of the interval: a
        // finished run can be pressed further
        if (stop || (prm.output.checkpoint_interval > 0 &&
                     step % prm.output.checkpoint_interval == 0))
          {
            if (guard_snapshot.step == step)
              store_checkpoint(guard_snapshot);
            else
              write_checkpoint(step, s.wall_seconds);
          }
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
    // the field's constants of the whole loading curve and the springback
    // (the rows of earlier runs of a resumed one included)
    if (statistics_writer)
      try
        {
          if (has_density)
            pcout << compaction_summary(
              read_loading_curve(statistics_name,
                                 system.upper_initial -
                                   prm.tools.lower_position));
          pcout << contact_summary(statistics_name)
                << springback_summary(statistics_name)
                << ejection_summary(statistics_name);
        }
      catch (const std::exception &)
        {
          // a statistics.csv of an older version: no summary
        }
    pcout << "Finished " << n_steps << " steps in "
          << format_seconds(wall_before + wall.wall_time()) << "; results in "
          << prm.output.directory << "/" << std::endl;
    timer.print_summary();
    return true;
  }
} // namespace densify
