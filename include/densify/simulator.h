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

#include <densify/assembly/lumped_mass.h>
#include <densify/contact/particle_contact.h>
#include <densify/contact/tool_contact.h>
#include <densify/drivers/explicit_dynamics.h>
#include <densify/geometry/particles.h>
#include <densify/material/material.h>
#include <densify/parameters.h>
#include <densify/postprocess/graphics.h>
#include <densify/postprocess/particle_measures.h>
#include <densify/postprocess/statistics.h>
#include <densify/solvers/linear_solver.h>

#include <array>
#include <csignal>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  class NodalAveraging;

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
   * Runs one scene: builds the multi-body mesh of all particles, then for each
   * load step moves the upper punch and solves the quasi-static equilibrium
   * by Newton's method with line search inside an augmented-Lagrangian loop
   * for the tool contact. Writes statistics.csv, log.txt and graphics into
   * the output directory. Every MPI rank holds the whole mesh
   * (parallel::shared::Triangulation, METIS partition) and assembles its own
   * cells. With Solver/Method = explicit the same system is integrated by
   * ExplicitDynamics between the load steps (source/simulator_explicit.cc).
   */
  class Simulator : private ExplicitSystem
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
      return residual_history;
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
      return tool_contact.particle_forces(*mapping, solution_ghosted, kind);
    }

    /// Number of particles each particle touches now.
    std::vector<unsigned int>
    contact_partners() const
    {
      return has_particle_contact ?
               particle_contact.contact_partners(*mapping, solution_ghosted) :
               std::vector<unsigned int>(particles.size(), 0);
    }

    /// Rigid translation of each particle: its mean displacement (mm).
    std::vector<Tensor<1, 3>>
    particle_mean_displacements() const;

  private:
    /// Measure every particle (one pass over the cells; on every rank).
    std::vector<ParticleMeasure>
    measure_particles() const;

    /// Contact forces of the tools and between particles.
    struct ContactResults
    {
      ToolContactResult     tools;
      ParticleContactResult particles;
    };

    /// Result of assemble().
    struct AssemblyResult
    {
      ToolContactResult     contact;
      ParticleContactResult particle_contact;
      /// l2 norm of the out-of-balance force (N).
      double residual_norm = 0.;
      /// Scale for the relative Newton criterion (N).
      double reference_norm = 0.;
    };

    void
    setup_particles();
    void
    setup_mesh();
    void
    setup_system();
    void
    setup_stabilisation();
    /// (Re)build the sparsity pattern (cells plus the particle contact
    /// couplings), the tangent and the stabilisation matrix.
    void
    setup_matrix();

    /// Internal forces at solution_ghosted added into @p forces (and their
    /// tangent into the tangent matrix if @p with_matrix), compressed.
    /// Throws std::runtime_error on a material failure (on every rank).
    void
    assemble_internal(TrilinosWrappers::MPI::Vector &forces,
                      const bool                     with_matrix);

    /// Residual (and tangent if @p with_matrix) at the current solution;
    /// @p tangent_margin as in ToolContact::assemble(). The particle contact
    /// search is refreshed first if @p with_matrix or @p search (only a
    /// tangent needs a new matrix pattern for new couplings).
    AssemblyResult
    assemble(const bool   with_matrix,
             const double tangent_margin = 0.,
             const bool   search         = false);

    /// Newton with line search for fixed multipliers; the first tangent uses
    /// the contact predictor @p margin (mm). Returns the number of Newton and
    /// linear iterations; throws on failure.
    std::pair<unsigned int, unsigned int>
    solve_newton(const unsigned int step, const double margin);

    /**
     * Solve one increment to @p time: predictor, then Newton inside the
     * multiplier updates. Throws std::runtime_error on failure (the caller
     * restores the state).
     */
    ContactResults
    solve_increment(const double       time,
                    const unsigned int step,
                    StepStatistics    &s);

    /**
     * Advance from the current time to @p time (the end of load step
     * @p step) in one or more increments: a failed increment is rolled back
     * and retried with half the size (at most Time stepping/Maximum
     * cut-backs times in a row), and increments grow again after easy ones.
     * Commits the quadrature-point history of each accepted increment.
     */
    ContactResults
    advance_to(const double time, const unsigned int step, StepStatistics &s);

    /// Position of the upper punch face at time @p t (mm).
    double
    upper_punch_position(const double t) const;

    /// Write the .pvtu of this step and rewrite the .pvd.
    void
    write_graphics(const unsigned int step, const double time);

    /**
     * Write the state at the end of load step @p step (solution, last
     * increment, quadrature-point history, contact multipliers and friction
     * history, time and step control, graphics records) to
     * Output/Directory/checkpoint/, one file per rank, replacing the previous
     * checkpoint only once the new one is complete.
     */
    void
    write_checkpoint(const unsigned int step, const double wall_seconds);

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

    /// Find the horizontal DoFs of the pole vertices of every particle
    /// (Contact/Hold poles on axis); called by setup_matrix().
    void
    setup_pole_springs();

    /// Add the matrix entries of the springs between two poles.
    void
    add_pole_couplings(TrilinosWrappers::SparsityPattern &pattern);

    /// Add the pole springs to the residual (and to the tangent if
    /// @p with_matrix); returns the l2 norm of their forces (N), on every
    /// rank. Does nothing without Contact/Hold poles on axis.
    double
    add_pole_springs(const bool with_matrix);

    /// A pole spring: stiffness k (N/mm) on the horizontal DoF i, towards
    /// zero (Hold poles on axis = true) or towards DoF j (vertical, and the
    /// spin spring of a stack).
    struct PoleSpring
    {
      types::global_dof_index i = 0;
      types::global_dof_index j = numbers::invalid_dof_index;
      double                  k = 0.;
    };
    /// The pole springs this rank adds (each spring on one rank).
    std::vector<PoleSpring> pole_springs;
    /// How often the tangent's sparsity pattern was made.
    unsigned int n_matrix_setups = 0;
    /// Force of the pole springs at the last converged state (N).
    double last_pole_force = 0.;

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

    std::vector<Particle>                        particles;
    std::vector<std::shared_ptr<const Material>> particle_material;
    double                                       upper_initial = 0.;
    std::vector<std::pair<double, double>>       punch_table;
    double                                       h_min = 0.;

    parallel::shared::Triangulation<3> triangulation;
    std::unique_ptr<FESystem<3>>       fe;
    std::unique_ptr<MappingFE<3>>      mapping;
    DoFHandler<3>                      dof_handler;
    IndexSet                           locally_owned, locally_relevant;
    /// The ghost entries of solution_ghosted: every DoF when particles can
    /// touch (masters may lie anywhere), else the locally relevant ones.
    IndexSet ghosted_dofs;

    TrilinosWrappers::SparseMatrix tangent, stabilisation;
    TrilinosWrappers::MPI::Vector  solution, solution_ghosted, residual,
      increment;
    /// The solution of the last accepted increment, with ghost entries
    /// (friction measures slip from it).
    TrilinosWrappers::MPI::Vector committed_ghosted;

    /// Quadrature-point history (index: active cell index * n_q + q),
    /// allocated only if some material needs it.
    bool                       has_history = false;
    std::vector<MaterialState> committed_history, trial_history;
    /// Material states per cell in the histories: one per quadrature point,
    /// or one per corner with the nodal-averaged F-bar.
    unsigned int history_per_cell = 0;
    /// Time and upper punch position of the last accepted increment.
    double current_time = 0., current_upper = 0.;
    /// Size of the next increment (s).
    double next_increment = 0.;

    /// Converged displacement increment of the last step and the punch
    /// travel that caused it (for the extrapolating predictor).
    TrilinosWrappers::MPI::Vector last_increment;
    double                        last_punch_increment = 0.;

    /// F-bar with nodal averaging (P1 locking remedy); nullptr when off.
    std::unique_ptr<NodalAveraging> nodal_averaging;

    ToolContact tool_contact;
    /// Particle-particle contact, if there is more than one particle.
    bool has_particle_contact = false;
    /// Solver/Linear solver with 'auto' resolved (cg-amg, gmres-amg, direct).
    std::string linear_solver_type;
    /// Contact/Geometric tangent resolved: the particle contact tangent with
    /// the motion of the master facets.
    bool            geometric_tangent = false;
    ParticleContact particle_contact;
    /// Search margin of the particle contact (mm).
    double search_margin = 0.;
    /// Body force (N/mm^3), its factor against time, and the time of the
    /// load being solved for.
    Tensor<1, 3>                           body_force;
    std::vector<std::pair<double, double>> body_force_table;
    double                                 load_time = 0.;
    /// Add -int b . phi to @p forces (only called if b != 0).
    void
    add_body_force(TrilinosWrappers::MPI::Vector &forces);

    /// How the load steps are solved (Solver/Method, resolved once).
    enum class Method
    {
      implicit,
      explicit_dynamics
    } method;

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

    /// Set the tools and the body force for scene time @p time and the
    /// friction regularisation for the increment @p increment.
    void
    set_loads(const double time, const double increment);

    /// Plastic work of the committed history (mJ), on every rank.
    double
    plastic_work() const;

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
    /// The power iteration's last vector, the start of the next one.
    TrilinosWrappers::MPI::Vector frequency_mode;
    /// The explicit run's contact penalty per particle (MPa/mm).
    std::vector<double>               explicit_penalty;
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
    /// The explicit run's last station account.
    ExplicitDynamics::Account explicit_account;
    /// Sideways upper punch displacement against time.
    std::vector<std::pair<double, double>> lateral_table;
    /// Friction coefficient of each tool, by ToolKind.
    std::array<double, n_tool_kinds> tool_friction = {{0., 0., 0.}};
    std::unique_ptr<LinearSolver>    linear_solver;
    double                           last_stabilisation_force = 0.;

    std::vector<StepStatistics> step_statistics;
    /// See newton_residuals().
    std::vector<double>               residual_history;
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
