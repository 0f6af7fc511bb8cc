// The quasi-static compaction driver: mesh, DoFs, Newton per load step,
// contact, output.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>

#include <deal.II/distributed/shared_tria.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/body_force.h>
#include <densify/assembly/continuum.h>
#include <densify/assembly/lumped_mass.h>
#include <densify/assembly/pole_springs.h>
#include <densify/assembly/stabilisation.h>
#include <densify/contact/particle_contact.h>
#include <densify/contact/tool_contact.h>
#include <densify/drivers/explicit_dynamics.h>
#include <densify/drivers/load_stepper.h>
#include <densify/drivers/punch_control.h>
#include <densify/effects.h>
#include <densify/geometry/particles.h>
#include <densify/material/j2_plasticity.h>
#include <densify/material/material.h>
#include <densify/parameters.h>
#include <densify/postprocess/cell_volume.h>
#include <densify/postprocess/graphics.h>
#include <densify/postprocess/particle_measures.h>
#include <densify/postprocess/quasi_static_guard.h>
#include <densify/postprocess/statistics.h>
#include <densify/scene.h>
#include <densify/solvers/linear_solver.h>

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
   * Runs one scene: builds the multi-body mesh of all particles, resolves
   * the scene's effects (Effects) and builds a force term for each effect
   * that is on (the continuum, body force, stabilisation, pole springs, tool
   * and particle contact: ForceTerm). For each load step it moves the upper
   * punch and either advances the quasi-static equilibrium with the
   * LoadStepper (Newton per increment, NewtonSolver) or integrates the same
   * force terms with ExplicitDynamics (source/simulator_explicit.cc). Writes
   * statistics.csv, log.txt and graphics into the output directory. Every
   * MPI rank holds the whole mesh (parallel::shared::Triangulation, METIS
   * partition) and assembles its own cells.
   */
  class Simulator : private ExplicitSystem, private IncrementalProblem
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

    /// Use @p scene, built by build_scene() from the same parameters,
    /// instead of building it again in setup().
    void
    set_scene(Scene scene)
    {
      given_scene = std::make_unique<Scene>(std::move(scene));
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
      return newton->residuals();
    }

    /// The DoF handler of the displacement.
    const DoFHandler<3> &
    get_dof_handler() const
    {
      return dof_handler;
    }

    /// The displacement vector (mm; locally owned entries).
    const TrilinosWrappers::MPI::Vector &
    displacement() const
    {
      return solution;
    }

    /// Statistics of the steps done so far.
    const std::vector<StepStatistics> &
    statistics() const
    {
      return step_statistics;
    }

    /// Current volume of each particle (mm^3), on every rank.
    std::vector<double>
    particle_volumes() const;

    /// The particles of the scene.
    const std::vector<Particle> &
    get_particles() const
    {
      return particles;
    }

    /// Number of degrees of freedom.
    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }

    /// Normal force (N) of the tool @p kind on each particle now.
    std::vector<double>
    particle_tool_forces(const ToolKind kind) const
    {
      return tool_contact ?
               tool_contact->particle_forces(*mapping, solution_ghosted, kind) :
               std::vector<double>(particles.size(), 0.);
    }

    /// Number of particles each particle touches now.
    std::vector<unsigned int>
    contact_partners() const
    {
      return particle_contact ?
               particle_contact->contact_partners(*mapping, solution_ghosted) :
               std::vector<unsigned int>(particles.size(), 0);
    }

    /// contact_partners() and the die wall's particle_tool_forces() at the
    /// station just reached: from the explicit pass that recorded them there
    /// (the same state), else by passes of their own.
    std::pair<std::vector<unsigned int>, std::vector<double>>
    station_contacts() const;

    /// Rigid translation of each particle: its mean displacement (mm).
    std::vector<Tensor<1, 3>>
    particle_mean_displacements() const;

  private:
    /// Measure every particle (one pass over the cells; on every rank),
    /// @p with_stress its mean stresses too (a second pass, which evaluates
    /// the material).
    std::vector<ParticleMeasure>
    measure_particles(const bool with_stress = false) const;

    void
    setup_particles();
    void
    setup_mesh();
    void
    setup_system();
    /// Build the force terms the effects call for, in the order they add
    /// to the residual.
    void
    setup_force_terms(const std::vector<double> &penalty);
    /// (Re)build the sparsity pattern (cells plus the couplings of the force
    /// terms), the tangent and the stabilisation matrix.
    void
    setup_matrix();

    /// Contact forces of the tools and between particles.
    struct ContactResults
    {
      ToolContactResult     tools;
      ParticleContactResult particles;
    };

    /// Every force term that is on: the bulk terms, then the others.
    std::vector<ForceTerm *>
    force_terms() const
    {
      std::vector<ForceTerm *> all = bulk_terms;
      all.insert(all.end(), other_terms.begin(), other_terms.end());
      return all;
    }

    /// The contact results of the last assembly.
    ContactResults
    contact_results() const;
    /// The contact results of the last evaluate_constraints().
    ContactResults last_contact;
    /// Output/Verbose: which history points yielded at the last iterate.
    std::vector<char> was_plastic;

    /// The context of an assembly at solution_ghosted.
    AssemblyContext
    context(const double tangent_margin = 0.) const;

    /**
     * Add every force term at solution_ghosted to @p forces (and the
     * tangent if @p with_matrix), compressed; returns the reference norm of
     * the relative Newton criterion: the larger of the bulk forces' norm and
     * the total contact force (N).
     */
    double
    assemble_terms(TrilinosWrappers::MPI::Vector &forces,
                   const bool                     with_matrix,
                   const double                   tangent_margin);

    // IncrementalProblem (the implicit method)
    Evaluation
    assemble(const bool   with_tangent,
             const double tangent_margin,
             const bool   search) override;
    TrilinosWrappers::MPI::Vector &
    solution_vector() override
    {
      return solution;
    }
    TrilinosWrappers::MPI::Vector &
    residual_vector() override
    {
      return residual;
    }
    unsigned int
    solve_linear(const TrilinosWrappers::MPI::Vector &rhs,
                 TrilinosWrappers::MPI::Vector       &du,
                 const double relative_tolerance) override;
    void
    add_pseudo_mass(const double factor) override;
    void
    begin_solve() override;
    void
    set_secant_tangent(const bool on) override;
    unsigned int
    after_update() override;
    bool
    start_dependent() const override
    {
      return particle_contact != nullptr;
    }
    std::string
    iteration_details() override;
    double
    set_loads(const double time, const double increment) override;
    bool
    loads_reached(double &scale) override;
    bool
    rigid_predictor(TrilinosWrappers::MPI::Vector &increment) override;
    double
    evaluate_constraints() override;
    void
    update_multipliers() override;
    void
    save_state() override;
    void
    restore_state() override;
    void
    commit() override;

    /// Plan both punches' moves from @p before to @p time (PunchControl::
    /// plan() with @p gain): a force-controlled punch gives back the other,
    /// displacement-controlled punch's travel over the move.
    void
    plan_punches(const double time, const double before, const double gain);

    /// Set the tools, body force and friction scale for time @p time,
    /// reached by an increment of @p increment (both methods; the upper
    /// punch where punch_control has it); returns the larger punch travel
    /// over the increment (mm).
    double
    apply_loads(const double time, const double increment);

    /// A punch's largest speed under force control (mm/s): its Maximum
    /// speed @p max_speed if positive, or from its displacement history
    /// @p table.
    double
    force_control_speed(const std::vector<std::pair<double, double>> &table,
                        const double max_speed) const;

    /// Position of the upper punch face at time @p t (mm).
    double
    upper_punch_position(const double t) const;

    /// Position of the lower punch face at time @p t (mm).
    double
    lower_punch_position(const double t) const;

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

    /// Copy solution into the ghosted vector.
    void
    update_ghosts();

    /// How often the tangent's sparsity pattern was made.
    unsigned int n_matrix_setups = 0;

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

    /// The scene given by set_scene(), until setup() takes it.
    std::unique_ptr<Scene>                       given_scene;
    std::vector<Particle>                        particles;
    std::vector<std::shared_ptr<const Material>> particle_material;
    /// Per particle: the F-bar's weight of the cell's own volume change
    /// (Mesh/Cell volume stabilisation, NodalAveraging).
    std::vector<double> cell_volume_weights;
    /// The barrier against crushed cells (Mesh/Cell volume barrier), per
    /// particle the material's bulk modulus; off without nodal averaging.
    CellVolumeBarrier cell_volume_barrier;
    double            upper_initial = 0.;
    /// Where the upper punch is: its displacement and force histories.
    PunchControl punch_control;
    /// Where the lower punch is (its rise): its histories likewise.
    PunchControl lower_control;
    /// Height of the lower punch face at t = 0 (mm).
    double lower_initial = 0.;
    double h_min         = 0.;

    parallel::shared::Triangulation<3> triangulation;
    std::unique_ptr<FESystem<3>>       fe;
    std::unique_ptr<MappingFE<3>>      mapping;
    DoFHandler<3>                      dof_handler;
    IndexSet                           locally_owned, locally_relevant;
    /// The ghost entries of solution_ghosted: every DoF when particles can
    /// touch (masters may lie anywhere), else the locally relevant ones.
    IndexSet ghosted_dofs;

    TrilinosWrappers::SparseMatrix tangent;
    TrilinosWrappers::MPI::Vector  solution, solution_ghosted, residual;
    /// solution_ghosted = solution with the communication plan kept.
    GhostImport ghost_import;
    /// The solution of the last accepted increment, with ghost entries
    /// (friction measures slip from it).
    TrilinosWrappers::MPI::Vector committed_ghosted;

    /// Time and upper punch position of the last accepted increment.
    double current_time = 0., current_upper = 0.;
    /// The time of the load being solved for (s).
    double load_time = 0.;
    /// The axial (z) translation of the whole compact that the planned
    /// move imposes (mm): the travel of the punch that moves by its history
    /// while the other follows it by force control (plan_punches()); 0
    /// otherwise.
    double rigid_shift = 0.;

    /// The effects of the scene, resolved once.
    Effects effects;
    /// The force terms, each built only if its effect is on (else null).
    std::unique_ptr<Continuum>       continuum;
    std::unique_ptr<BodyForce>       body_force;
    std::unique_ptr<ToolContact>     tool_contact;
    std::unique_ptr<ParticleContact> particle_contact;
    std::unique_ptr<PoleSprings>     pole_springs;
    std::unique_ptr<Stabilisation>   stabilisation;
    /// The force terms that are on, in the order they add to the residual:
    /// the bulk (continuum, body force), then the others.
    std::vector<ForceTerm *> bulk_terms, other_terms;
    /// Search margin of the particle contact (mm).
    double search_margin = 0.;
    /// The scene's body force and its factor against time, and the
    /// sideways upper punch displacement against time.
    Tensor<1, 3>                           scene_body_force;
    std::vector<std::pair<double, double>> body_force_table;
    std::vector<std::pair<double, double>> lateral_table;
    /// The die's top edge at t = 0 (infinity: none), and its upward
    /// displacement against time.
    double die_top = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, double>> die_table;

    /// The implicit method: Newton's method, the load stepper, the linear
    /// solver; null with explicit dynamics.
    std::unique_ptr<NewtonSolver> newton;
    std::unique_ptr<LoadStepper>  stepper;
    std::unique_ptr<LinearSolver> linear_solver;
    double                        last_stabilisation_force = 0.;

    /**
     * Explicit dynamics: the lumped mass, the integrator and the contact
     * penalty that fits its stable step; returns the penalty per particle.
     * @p tangential_ratio as for LumpedMass.
     */
    std::vector<double>
    setup_explicit(const double tangential_ratio);

    /// The explicit counterpart of advance_to(): integrate to @p time (the
    /// end of load step @p step); forces are the means over the interval.
    ContactResults
    advance_explicit(const double       time,
                     const unsigned int step,
                     StepStatistics    &s);

    /// The largest squared frequency of the elements (elastic, at the
    /// current state) with the lumped mass @p mass, by power iteration.
    double
    largest_frequency2(const TrilinosWrappers::MPI::Vector &mass);

    // ExplicitSystem
    double
    update_mass(const double                   required_step,
                TrilinosWrappers::MPI::Vector &mass) override;
    void
    forces(const TrilinosWrappers::MPI::Vector &u,
           const double                         scene_time,
           const double                         scene_increment,
           const double                         dt,
           TrilinosWrappers::MPI::Vector       &internal,
           TrilinosWrappers::MPI::Vector       &external) override;
    double
    external_work() const override
    {
      return explicit_work.tools + explicit_work.body;
    }

    std::unique_ptr<LumpedMass> lumped_mass;
    /// Margin of the measured largest frequency over the power iteration's
    /// estimate (which approaches it from below).
    static constexpr double calibration_margin = 1.25;
    /// Stations between two measurements of the largest frequency at most.
    static constexpr unsigned int recalibration_interval = 10;
    /// Mass updates so far (one per station), and the raw cell bound at the
    /// last measurement of the largest frequency (1/s^2).
    unsigned int mass_updates     = 0;
    double       calibrated_bound = 0.;
    /// The calibration factor of the last measurement. A rise within
    /// calibration_margin (the mass before it still gives a stable step) is
    /// approached by at most calibration_rise a station, so that the mass of
    /// nodes that move with the compact grows over stations, not at once.
    double calibration_target = 0.;
    /// The largest growth of the applied calibration factor from one station
    /// to the next, about calibration_margin^(1 / recalibration_interval).
    static constexpr double calibration_rise = 1.0226;
    /// The power iteration's last vector, the start of the next one.
    TrilinosWrappers::MPI::Vector frequency_mode;
    /// The explicit run's contact penalty per particle (MPa/mm).
    std::vector<double> explicit_penalty;
    /// An upper bound of the contact stiffness a punch meets (N/mm): the
    /// stiffest particle's penalty over the die's bore, for the mass of a
    /// punch under force control (PunchControl::drive()).
    double                            punch_stiffness = 0.;
    std::unique_ptr<ExplicitDynamics> explicit_dynamics;
    /// Energy account of the explicit run kept by the system (mJ): work of
    /// the moving tools and of the body force, friction work, the contact
    /// springs' elastic energy now, and the energy the multiplier updates
    /// put into them.
    struct ExplicitWork
    {
      double tools = 0., body = 0., friction = 0., contact_energy = 0.,
             multipliers = 0.;
      /// Upper punch force and position, friction and lateral position at
      /// the last evaluation (for the trapezoidal tool work).
      double       upper_force = 0., upper_position = 0., lateral = 0.;
      Tensor<1, 3> upper_friction;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &tools &body &friction &contact_energy &multipliers &upper_force
          &upper_position &lateral &upper_friction;
      }
    } explicit_work;
    /// Time-weighted sums of the contact forces over the current interval
    /// between stations, of the forces times scene time, and of the
    /// weights times 1, t and t^2 (the least-squares line at the station).
    ContactResults        interval_sum, interval_moment;
    std::array<double, 3> interval_weight = {{0., 0., 0.}};
    /// Body force vector of the last evaluation and the displacement then
    /// (body work); the displacement at the last contact search.
    TrilinosWrappers::MPI::Vector body_forces, body_solution, search_solution;
    /// The explicit step's plain arrays: the solution's and the committed
    /// solution's values, and the forces on their way into a residual.
    AllValues   explicit_values, explicit_committed;
    LocalForces explicit_forces;
    /// The contact record of the explicit pass at the station (the scene
    /// time record_time; negative: no pass records), and whether the last
    /// station's pass filled it.
    ContactRecord station_record;
    double        record_time      = -1.;
    bool          station_recorded = false;
    /// The explicit run's last station account.
    ExplicitDynamics::Account         explicit_account;
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
