// The load stepper of the implicit method: each load step in one or more
// increments, each solved by Newton inside an augmentation loop, with a
// predictor and cut-backs.
#pragma once

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/trilinos_vector.h>

#include <densify/solvers/newton_solver.h>
#include <densify/utilities.h>

#include <string>

namespace densify
{
  /**
   * What the load stepper needs of a problem besides Newton's: loads at a
   * time, the constraints' augmentation, and the state to commit or roll
   * back.
   */
  class IncrementalProblem : public NonlinearProblem
  {
  public:
    /**
     * Set the loads for time @p time, reached by an increment of duration
     * @p increment; returns the travel of the load (e.g. of the punch) over
     * the increment (mm), the scale of the predictor.
     */
    virtual double
    set_loads(const double time, const double increment) = 0;

    /**
     * After a converged solve of an increment: true if every load that is
     * controlled by its result (e.g. a punch that must carry a target force)
     * has it; otherwise move that load for another solve of the same
     * increment and return false, with @p scale the new load travel over
     * the solved one (from the increment's start), which scales the
     * increment of the solution into the next solve's start. Displacement
     * control alone: true.
     */
    virtual bool
    loads_reached(double &scale)
    {
      scale = 1.;
      return true;
    }

    /**
     * After set_loads(): a rigid motion that the increment's loads impose on
     * the whole system (e.g. a compact that both punches carry along), to
     * start the solve from instead of the last increment extrapolated. Adds
     * it to @p increment (zero on entry) and returns true, or returns false
     * if the loads impose none.
     */
    virtual bool
    rigid_predictor(TrilinosWrappers::MPI::Vector &increment)
    {
      (void)increment;
      return false;
    }

    /// Evaluate the constraints at the current solution (e.g. the contact
    /// forces); returns their largest violation (e.g. penetration, mm).
    virtual double
    evaluate_constraints() = 0;

    /// Update the multipliers of the constraints (augmentation).
    virtual void
    update_multipliers() = 0;

    /**
     * True if a converged Newton solve depends on the state it started from
     * beyond the solution (e.g. contact points that keep their master facets
     * within a solve): then the stepper may solve an increment again from
     * a fresh start (LoadStepperControl::max_consistency_solves).
     */
    virtual bool
    start_dependent() const
    {
      return false;
    }

    /// Keep the committed state for a roll-back.
    virtual void
    save_state() = 0;

    /// Go back to the state kept by save_state() (the solution is restored
    /// by the stepper).
    virtual void
    restore_state() = 0;

    /// Accept the current solution as the end of an increment.
    virtual void
    commit() = 0;
  };

  /// Settings of the load stepper.
  struct LoadStepperControl
  {
    /// Duration of a load step (s).
    double step_length = 1.;
    /// Halvings of an increment in a row before giving up.
    unsigned int max_cutbacks = 8;
    /// Constraint violation accepted without another augmentation.
    double gap_tolerance = 1e-4;
    /// Most augmentations per increment.
    unsigned int max_augmentations = 20;
    /// Most solves of one increment for a load control (loads_reached()).
    unsigned int max_control_solves = 20;
    /// Most solves from a fresh start after the augmentations of one
    /// increment (IncrementalProblem::start_dependent()); 0: none, the
    /// default of the scenes (doc/roadmap.md, "A displacement hold").
    unsigned int max_consistency_solves = 0;
    /// Newton iterations up to which an increment counts as easy (the next
    /// one may be twice as long, up to a step).
    unsigned int easy_newton_iterations = 10;
  };

  /// Counts of one load step.
  struct StepCounts
  {
    unsigned int newton_iterations = 0, linear_iterations = 0,
                 augmentations = 0, cutbacks = 0, increments = 0;
    /// Increments retried with the pseudo-transient continuation.
    unsigned int continuations = 0;
    /// Consistency solves (IncrementalProblem::start_dependent()) that did
    /// not converge: their increments kept the state converged before.
    unsigned int failed_checks = 0;
    /// Newton iterations of the solves that did not converge, whose
    /// increments were retried with the continuation or cut back (not in
    /// newton_iterations, which counts the converged solves).
    unsigned int failed_newton_iterations = 0;
  };

  /**
   * Advances an IncrementalProblem from load step to load step. Each
   * increment starts from a predictor (the last increment extrapolated in
   * proportion to the load's travel), then solves by Newton and updates the
   * multipliers until the constraint violation is below the tolerance; a
   * problem whose solves depend on their start may be solved again from a
   * fresh start until such a solve takes no iteration (at most
   * max_consistency_solves times; a check that does not converge leaves the
   * state converged before it). A
   * failed increment is rolled back and retried with half the size (at most
   * max_cutbacks times in a row); increments grow again after easy ones.
   * An increment whose predicted state fails before any Newton iteration
   * (the extrapolation inverts a cell) is first retried from the last
   * converged state. With Continuation::fallback a failed increment is
   * then retried at the same size with the pseudo-transient continuation;
   * with Continuation::always every increment uses it.
   */
  class LoadStepper
  {
  public:
    LoadStepper(const LoadStepperControl &control,
                NewtonSolver             &newton,
                ConditionalOStream       &out);

    /// Allocate the vectors like @p solution; the first increment is a
    /// whole step.
    void
    setup(const TrilinosWrappers::MPI::Vector &solution);

    /**
     * Advance from @p current_time, the time of the last accepted increment,
     * to @p time (the end of load step @p step); @p current_time follows the
     * accepted increments. Throws ConvergenceError if an increment fails
     * after every cut-back (the problem is back at the last converged
     * increment).
     */
    void
    advance_to(IncrementalProblem &problem,
               double             &current_time,
               const double        time,
               const unsigned int  step,
               StepCounts         &counts);

    /// Size of the next increment (s).
    double next_increment = 0.;
    /// The converged increment of the solution, and the load travel that
    /// caused it (the predictor).
    TrilinosWrappers::MPI::Vector last_increment;
    double                        last_travel = 0.;

  private:
    /// One increment to @p time: predictor (unless @p predict is false),
    /// then Newton (with the pseudo-transient continuation if
    /// @p pseudo_transient) inside the multiplier updates. Throws
    /// std::runtime_error on failure; predictor_failed tells whether the
    /// predicted state itself failed (before any Newton iteration).
    void
    solve_increment(IncrementalProblem &problem,
                    const double        current_time,
                    const double        time,
                    const unsigned int  step,
                    const bool          pseudo_transient,
                    const bool          predict,
                    StepCounts         &counts);

    /// Whether the last failed increment failed at its predicted state
    /// (e.g. a cell inverted by the extrapolation) before any Newton
    /// iteration.
    bool predictor_failed = false;

    /// Newton iterations of the last solve, converged or not.
    unsigned int
    last_solve_iterations() const
    {
      return newton.residuals().empty() ?
               0 :
               static_cast<unsigned int>(newton.residuals().size() - 1);
    }

    const LoadStepperControl control;
    NewtonSolver            &newton;
    ConditionalOStream      &out;
  };
} // namespace densify
