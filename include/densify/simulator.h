// The run of one scene: the multi-body system, the driver of its solution
// method, the load steps with their statistics, checkpoints and output.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_vector.h>

#include <densify/drivers/implicit_driver.h>
#include <densify/effects.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/run/checkpoint.h>
#include <densify/run/station_report.h>
#include <densify/scene.h>

#include <csignal>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  /**
   * How a run may stop early and continue: the command line's --resume and
   * --stop-after, and a signal handler's flag.
   */
  struct RunControl
  {
    /// Continue from the checkpoint in Output/Directory/checkpoint/.
    bool resume = false;
    /// Stop after this load step with a checkpoint (0: run to the end).
    unsigned int stop_after = 0;
    /// Set to non-zero by a signal handler: stop after the current load step
    /// with a checkpoint. Not owned; may be null.
    const volatile std::sig_atomic_t *stop_request = nullptr;
  };

  /**
   * Runs one scene: resolves the scene's effects (Effects), builds the
   * MultiBodySystem (the multi-body mesh, DoFs, and a force term for each
   * effect that is on: ForceTerm) and the Driver of its method, the
   * ImplicitDriver (Newton per increment through the LoadStepper) or the
   * ExplicitDriver (explicit dynamics), chosen once. For each load step it
   * lets the driver advance the system to the step's end, then the
   * StationReport measures and writes it (statistics.csv, particles.csv,
   * graphics), the QuasiStaticStop judges an explicit run, and the
   * Checkpoint writes the state when due; log.txt has the run's lines.
   */
  class Simulator
  {
  public:
    /// Prepare a run: create the output directory and its log.txt (nothing
    /// is computed yet). The log goes to the console too if @p console.
    Simulator(const Parameters &parameters,
              const MPI_Comm    comm,
              const bool        console = true,
              const RunControl &control = RunControl());

    /// Destructor; resets the timer so that an exception cannot deadlock.
    ~Simulator();

    /**
     * Check the input, build the mesh and run every load step (from the
     * checkpoint's next step with RunControl::resume). Writes a checkpoint
     * every Output/Checkpoint interval steps. Returns false if it stopped
     * early on request (RunControl), after writing a checkpoint; true when
     * every step is done. Throws std::runtime_error with a one-line message
     * on a failed solve, InputError on bad input (e.g. a checkpoint that
     * does not fit the scene); what was written before stays valid.
     */
    bool
    run();

    /// Use @p scene, built by build_scene() from the same parameters, and
    /// its effects @p scene_effects, resolved by resolve_effects(), instead
    /// of building and resolving them again in setup().
    void
    set_scene(Scene scene, const Effects &scene_effects)
    {
      given_scene   = std::make_unique<Scene>(std::move(scene));
      given_effects = std::make_unique<Effects>(scene_effects);
    }

    /// Add a force term of the caller's to the system before setup()
    /// (MultiBodySystem::add_force_term()).
    void
    add_force_term(MultiBodySystem::ForceTermFactory factory)
    {
      system.add_force_term(std::move(factory));
    }

    /// Set up particles, mesh and system without solving; run() calls it
    /// unless it was called before.
    void
    setup();

    /// Append a line to log.txt only (e.g. the error that ended a run).
    void
    write_to_log_file(const std::string &line)
    {
      if (log_file.is_open())
        log_file << line << std::endl;
    }

    /// l2 norm of the residual after each Newton iteration of the last
    /// Newton solve (N), starting with the initial residual.
    const std::vector<double> &
    newton_residuals() const
    {
      return implicit_driver()->newton_residuals();
    }

    /// The DoF handler of the displacement.
    const DoFHandler<3> &
    get_dof_handler() const
    {
      return system.dof_handler;
    }

    /// The displacement vector (mm; locally owned entries).
    const TrilinosWrappers::MPI::Vector &
    displacement() const
    {
      return system.solution;
    }

    /// Statistics of the steps done so far.
    const std::vector<StepStatistics> &
    statistics() const
    {
      return report.statistics();
    }

    /// Current volume of each particle (mm^3), on every rank.
    std::vector<double>
    particle_volumes() const
    {
      return system.particle_volumes();
    }

    /// The particles of the scene.
    const std::vector<Particle> &
    get_particles() const
    {
      return system.particles;
    }

    /// Number of degrees of freedom.
    types::global_dof_index
    n_dofs() const
    {
      return system.dof_handler.n_dofs();
    }

    /// Normal force (N) of the tool @p kind on each particle now.
    std::vector<double>
    particle_tool_forces(const ToolKind kind) const
    {
      return system.particle_tool_forces(kind);
    }

    /// Number of particles each particle touches now.
    std::vector<unsigned int>
    contact_partners() const
    {
      return system.contact_partners();
    }

    /// contact_partners() and the die wall's particle_tool_forces() at the
    /// station just reached (StationReport::station_contacts()).
    std::pair<std::vector<unsigned int>, std::vector<double>>
    station_contacts() const
    {
      return report.station_contacts(*driver);
    }

    /// Rigid translation of each particle: its mean displacement (mm).
    std::vector<Tensor<1, 3>>
    particle_mean_displacements() const
    {
      return system.particle_mean_displacements();
    }

  private:
    /// The DoFs, the driver of the method, the force terms with the contact
    /// penalty the driver gives, and the checkpoints.
    void
    setup_system();

    /// Write the checkpoint of load step @p step after a failed step
    /// (@p e) and throw @p e with where it is.
    [[noreturn]] void
    keep_failed_run(const ConvergenceError &e,
                    const unsigned int      step,
                    const double            wall_seconds) const;

    const Parameters &prm;
    /// How the run may stop early and continue.
    const RunControl control;
    /// Wall time of the run before the checkpoint it resumed from (s).
    double                        wall_before = 0.;
    MPI_Comm                      comm;
    const unsigned int            this_rank;
    std::ofstream                 log_file;
    std::unique_ptr<std::ostream> tee;
    ConditionalOStream            pcout;
    TimerOutput                   timer;

    /// The scene and its effects given by set_scene(), until setup() takes
    /// them.
    std::unique_ptr<Scene>   given_scene;
    std::unique_ptr<Effects> given_effects;
    /// The multi-body system both methods advance.
    MultiBodySystem system;

    /// The driver of the scene's method, chosen once in setup_system().
    std::unique_ptr<Driver> driver;

    /// The driver as the implicit one (null with another method), for
    /// what only it has (Newton's residuals).
    ImplicitDriver *
    implicit_driver() const
    {
      return dynamic_cast<ImplicitDriver *>(driver.get());
    }

    /// The report at each station: statistics, particles' rows, graphics.
    StationReport report;
    /// The checkpoints of the system and the driver, made with the driver.
    std::unique_ptr<Checkpoint> checkpoint;
  };
} // namespace densify
