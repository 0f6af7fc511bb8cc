// The run of one scene: the multi-body system, the driver of its solution
// method, the load steps with their statistics, checkpoints and output.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_vector.h>

#include <densify/drivers/explicit_driver.h>
#include <densify/drivers/implicit_driver.h>
#include <densify/effects.h>
#include <densify/material/j2_plasticity.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/postprocess/cell_volume.h>
#include <densify/postprocess/graphics.h>
#include <densify/postprocess/particle_measures.h>
#include <densify/postprocess/quasi_static_guard.h>
#include <densify/postprocess/statistics.h>
#include <densify/scene.h>

#include <array>
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
   * effect that is on: ForceTerm) and the driver of its method, the
   * ImplicitDriver (Newton per increment through the LoadStepper) or the
   * ExplicitDriver (explicit dynamics), chosen once. For each load step it
   * lets the driver advance the system to the step's end, then measures,
   * reports and checkpoints: statistics.csv, particles.csv, log.txt,
   * graphics and checkpoints in the output directory.
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
      return step_statistics;
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
    /// station just reached: from the explicit pass that recorded them there
    /// (the same state), else by passes of their own.
    std::pair<std::vector<unsigned int>, std::vector<double>>
    station_contacts() const;

    /// Rigid translation of each particle: its mean displacement (mm).
    std::vector<Tensor<1, 3>>
    particle_mean_displacements() const
    {
      return system.particle_mean_displacements();
    }

  private:
    /// The DoFs, the driver of the method, and the force terms with the
    /// contact penalty the driver gives.
    void
    setup_system();


    /// Write the .pvtu of this step and rewrite the .pvd, with the
    /// particles' mean stresses of @p measures.
    void
    write_graphics(const unsigned int                  step,
                   const double                        time,
                   const std::vector<ParticleMeasure> &measures);

    /**
     * Write the state at the end of load step @p step (solution, last
     * increment, quadrature-point history, contact multipliers and friction
     * history, time and step control, graphics records) to
     * Output/Directory/checkpoint/, one file per rank, replacing the previous
     * checkpoint only once the new one is complete.
     */
    void
    write_checkpoint(const unsigned int step, const double wall_seconds);

    /// This rank's part of a checkpoint, held in memory.
    struct CheckpointSnapshot
    {
      /// The load step it ends.
      unsigned int step = 0;
      /// Its scene time.
      double time = 0.;
      /// The serialized state, as write_checkpoint() stores it.
      std::string bytes;
    };

    /// The state at the end of load step @p step, serialized in memory (what
    /// write_checkpoint() writes).
    CheckpointSnapshot
    checkpoint_snapshot(const unsigned int step, const double wall_seconds);

    /// Write @p snapshot (every rank its own) to Output/Directory/checkpoint/,
    /// replacing the previous checkpoint only once the new one is complete.
    void
    store_checkpoint(const CheckpointSnapshot &snapshot);

    /// The limits of the quasi-static guard: those of subsection Explicit
    /// for an explicit run whose mass scaling sets the step, else none.
    QuasiStaticLimits
    quasi_static_limits() const;

    /**
     * Stop the run if station @p s breaks the limits of @p guard: store the
     * snapshot of the last station within them as the checkpoint (if there
     * is one) and throw an error that names the breach and Explicit/Number
     * of steps.
     */
    void
    check_quasi_static(const StepStatistics &s, QuasiStaticGuard &guard);

    /// Warn once per run when station @p s penetrates by more than
    /// Contact/Gap tolerance (explicit runs; the implicit load stepper warns
    /// at each step it cannot meet it).
    void
    warn_penetration(const StepStatistics &s);

    /// A recent station of an explicit run within the quasi-static limits,
    /// kept for the checkpoint of a run that leaves them.
    CheckpointSnapshot guard_snapshot;
    /// Wall time of the run when guard_snapshot was taken, and what taking
    /// it cost (s).
    double guard_snapshot_wall = 0., guard_snapshot_cost = 0.;
    /// Whether warn_penetration() has warned.
    bool penetration_warned = false;

    /// Warn once per run when the smallest cell volume ratio at step
    /// @p step falls below 0.2 (the run goes on).
    void
    warn_cell_volume(const unsigned int        step,
                     const SmallestCellVolume &smallest);
    /// Whether warn_cell_volume() has warned.
    bool cell_volume_warned = false;

    /**
     * Load the checkpoint written by write_checkpoint() into the set-up
     * system; returns its load step. Throws InputError if there is none or it
     * belongs to another scene, mesh or number of ranks.
     */
    unsigned int
    read_checkpoint();

    /// Keep the rows of the CSV file @p filename up to load step @p step
    /// (first column), so that a resumed run appends after them.
    void
    truncate_rows(const std::string &filename, const unsigned int step) const;

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
    /// what only it has (its checkpoint state, Newton's residuals).
    ImplicitDriver *
    implicit_driver() const
    {
      return dynamic_cast<ImplicitDriver *>(driver.get());
    }

    /// The driver as the explicit one (null with another method).
    ExplicitDriver *
    explicit_driver() const
    {
      return dynamic_cast<ExplicitDriver *>(driver.get());
    }
    std::vector<StepStatistics>       step_statistics;
    std::unique_ptr<StatisticsWriter> statistics_writer;
    /// particles.csv: per particle and step, volume and mean displacement
    /// (rank 0).
    std::unique_ptr<ParticleTableWriter> particle_writer;
    /// Volume of each particle's mesh at the start (mm^3).
    std::vector<double> initial_volumes;
    /// The graphics and the records of the .pvd.
    GraphicsWriter graphics;
  };
} // namespace densify
