// The implicit method's driver: the multi-body system as the problem of
// the LoadStepper (Newton per increment): residual and tangent, linear
// solves, loads, contact augmentation, commit and roll-back.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <densify/drivers/driver.h>
#include <densify/drivers/load_stepper.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/solvers/linear_solver.h>
#include <densify/solvers/newton_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace densify
{
  /**
   * The quasi-static method (Solver/Method = implicit, doc/theory.md
   * sections 4-5): advances the MultiBodySystem to the end of each load step
   * with the LoadStepper, whose IncrementalProblem it is: the residual and
   * tangent of the system's force terms (MultiBodySystem::assemble_terms()),
   * the linear solves (LinearSolver), the loads, the contact multipliers'
   * augmentation, and the commit and roll-back of an increment.
   */
  class ImplicitDriver : public Driver, public IncrementalProblem
  {
  public:
    /// The driver of @p system.
    ImplicitDriver(const Parameters   &parameters,
                   MultiBodySystem    &system,
                   ConditionalOStream &pcout,
                   TimerOutput        &timer);

    /// Nothing to set up before the force terms; their contact penalty is
    /// MultiBodySystem::contact_penalty().
    std::vector<double>
    prepare() override
    {
      return system.contact_penalty();
    }

    /// The tangent's pattern, Newton's method, the load stepper and the
    /// linear solver, once the system's force terms are built.
    void
    setup() override;

    /// (Re)build the sparsity pattern (cells plus the couplings of the force
    /// terms), the tangent and the stabilisation matrix.
    void
    setup_matrix();

    /// Advance to @p time, the end of load step @p step, from the last
    /// accepted state (LoadStepper::advance_to()); returns the contact
    /// forces there and fills the iteration counts and the stabilisation's
    /// force of @p s. Throws ConvergenceError if the step fails.
    ContactResults
    advance(const double       time,
            const unsigned int step,
            StepStatistics    &s) override;

    /// l2 norm of the residual after each Newton iteration of the last
    /// Newton solve (N), starting with the initial residual.
    const std::vector<double> &
    newton_residuals() const
    {
      return newton->residuals();
    }

    /// What a checkpoint keeps of the driver: the load stepper's last
    /// increment (locally owned entries, the predictor of the next step),
    /// its next increment and the punch's last travel.
    struct Saved
    {
      std::vector<double> increment;
      double              next_increment = 0.;
      double              last_travel    = 0.;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &increment &next_increment &last_travel;
      }
    };

    /// The driver's state for a checkpoint.
    Saved
    saved() const;

    /// Continue from @p saved.
    void
    restore(const Saved &saved);

    /// Write saved().
    void
    write_checkpoint(boost::archive::binary_oarchive &archive) const override;

    /// Read what write_checkpoint() wrote.
    void
    read_checkpoint(boost::archive::binary_iarchive &archive) override;

    /// restore() what read_checkpoint() read, and set up the matrix pattern
    /// of the system's contact search at the checkpoint's state.
    void
    resume() override;

    // IncrementalProblem
    Evaluation
    assemble(const bool   with_tangent,
             const double tangent_margin,
             const bool   search) override;
    TrilinosWrappers::MPI::Vector &
    solution_vector() override
    {
      return system.solution;
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
      return system.particle_contact != nullptr;
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

  private:
    /// The state read by read_checkpoint(), until resume() takes it up.
    std::unique_ptr<Saved> loaded;

    /// The contact results of the last evaluate_constraints().
    ContactResults last_contact;
    /// Output/Verbose: which history points yielded at the last iterate.
    std::vector<char> was_plastic;

    const Parameters   &prm;
    MultiBodySystem    &system;
    ConditionalOStream &pcout;
    TimerOutput        &timer;

    TrilinosWrappers::SparseMatrix tangent;
    TrilinosWrappers::MPI::Vector  residual;
    std::unique_ptr<NewtonSolver>  newton;
    std::unique_ptr<LoadStepper>   stepper;
    std::unique_ptr<LinearSolver>  linear_solver;
    /// How often the tangent's sparsity pattern was made.
    unsigned int n_matrix_setups          = 0;
    double       last_stabilisation_force = 0.;
  };
} // namespace densify
