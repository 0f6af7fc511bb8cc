// The load stepper of the implicit method.
#include <densify/drivers/load_stepper.h>

#include <cmath>
#include <iomanip>
#include <stdexcept>
#include <string>

namespace densify
{
  namespace
  {
    /// The largest ratio of an increment's load travel to the last one's by
    /// which the predictor extrapolates the last increment (a cut-back's
    /// retry has 1/2; a full step after an increment cut back to 1/64 has
    /// 64).
    constexpr double max_extrapolation = 100.;
  } // namespace

  LoadStepper::LoadStepper(const LoadStepperControl &control,
                           NewtonSolver             &newton,
                           ConditionalOStream       &out)
    : control(control)
    , newton(newton)
    , out(out)
  {}



  void
  LoadStepper::setup(const TrilinosWrappers::MPI::Vector &solution)
  {
    last_increment.reinit(solution.locally_owned_elements(),
                          solution.get_mpi_communicator());
    last_travel    = 0.;
    next_increment = control.step_length;
  }



  void
  LoadStepper::solve_increment(IncrementalProblem &problem,
                               const double        current_time,
                               const double        time,
                               const unsigned int  step,
                               const bool          pseudo_transient,
                               const bool          predict,
                               StepCounts         &counts)
  {
    predictor_failed    = false;
    const double travel = problem.set_loads(time, time - current_time);
    // predictor: the rigid motion the loads impose, else the last increment
    // extrapolated in proportion to the load's travel, unless this travel is
    // far larger than the last one's (after a hold, whose increment is the
    // compact's relaxation and its travel round-off, the ratio would blow
    // that up by orders of magnitude)
    TrilinosWrappers::MPI::Vector      &solution = problem.solution_vector();
    const TrilinosWrappers::MPI::Vector start    = solution;
    TrilinosWrappers::MPI::Vector       rigid(solution);
    rigid          = 0.;
    bool predicted = false;
    if (predict && problem.rigid_predictor(rigid))
      {
        solution += rigid;
        predicted = true;
      }
    else if (predict && last_travel > 0 &&
             travel <= max_extrapolation * last_travel)
      {
        solution.add(travel / last_travel, last_increment);
        predicted = true;
      }

    double violation = 0.;
    for (unsigned int solve = 0;; ++solve)
      {
        // Newton solves with augmentations until the violation is below the
        // tolerance; then, where a converged state depends on the solve's
        // start (master facets kept within a solve, so the state balances
        // the kept facets), up to max_consistency_solves solves from a fresh
        // start until one takes no iteration: the increment ends in
        // equilibrium with the closest facets, as the next increment's first
        // solve will see it
        bool                          check = false;
        unsigned int                  aug = 0, n_checks = 0;
        TrilinosWrappers::MPI::Vector converged;
        for (bool first = true;; first = false)
          {
            std::pair<unsigned int, unsigned int> result;
            try
              {
                // predictor margin: constraints within this increment's
                // travel; the continuation is for the solves that must
                // converge, not for the checks
                result = newton.solve(problem,
                                      step,
                                      first ? travel : 0.,
                                      pseudo_transient && !check,
                                      check);
              }
            catch (const std::runtime_error &)
              {
                if (!check)
                  {
                    counts.failed_newton_iterations += last_solve_iterations();
                    predictor_failed = predicted && first && solve == 0 &&
                                       newton.residuals().empty();
                    throw;
                  }
                // a check that does not converge within its iterations
                // (points that switch facets back and forth in a dense
                // packing): the increment keeps the state converged with
                // the kept facets; its material and contact states are
                // evaluated again, from the closest facets
                counts.newton_iterations += last_solve_iterations();
                solution = converged;
                problem.begin_solve();
                problem.assemble(false, 0., false);
                violation = problem.evaluate_constraints();
                ++counts.failed_checks;
                break;
              }
            const auto [n_newton, n_linear] = result;
            counts.newton_iterations += n_newton;
            counts.linear_iterations += n_linear;
            violation = problem.evaluate_constraints();
            if (violation > control.gap_tolerance &&
                aug < control.max_augmentations)
              {
                problem.update_multipliers();
                ++aug;
                ++counts.augmentations;
                check = false;
                continue;
              }
            if (!problem.start_dependent() || n_newton == 0 ||
                n_checks == control.max_consistency_solves)
              break;
            ++n_checks;
            check     = true;
            converged = solution;
          }
        double scale = 1.;
        if (problem.loads_reached(scale))
          break;
        if (scale != 1.)
          {
            solution -= start;
            solution *= scale;
            solution += start;
          }
        if (solve + 1 == control.max_control_solves)
          throw std::runtime_error(
            "step " + std::to_string(step) +
            ": the controlled load was not reached in " +
            std::to_string(control.max_control_solves) +
            " solves; try more steps (Time stepping/Number of steps)");
      }
    if (violation > control.gap_tolerance)
      out << "  warning: penetration " << violation
          << " mm above Contact/Gap tolerance after "
          << control.max_augmentations
          << " augmentations; raise Contact/Maximum augmentations or "
             "Contact/Penalty factor"
          << std::endl;

    // the converged increment, for the next predictor
    last_increment = solution;
    last_increment -= start;
    last_travel = travel;
  }



  void
  LoadStepper::advance_to(IncrementalProblem &problem,
                          double             &current_time,
                          const double        time,
                          const unsigned int  step,
                          StepCounts         &counts)
  {
    const double       step_length       = control.step_length;
    double             dt                = next_increment;
    unsigned int       cutbacks_in_a_row = 0;
    const Continuation continuation      = newton.continuation();
    // the continuation for this increment
    bool pseudo_transient = continuation == Continuation::always;
    // whether this increment starts from the predictor
    bool predict = true;
    while (current_time < time - 1e-12 * step_length)
      {
        // the increment that reaches the end of the step ends exactly there:
        // a round-off remainder would make one more, tiny increment, and the
        // next step would start from it
        const bool   last  = dt >= (time - current_time) * (1. - 1e-9);
        const double t_end = last ? time : current_time + dt;
        // what a failed increment must restore
        const TrilinosWrappers::MPI::Vector saved_solution =
          problem.solution_vector();
        const TrilinosWrappers::MPI::Vector saved_increment = last_increment;
        const double                        saved_travel    = last_travel;
        problem.save_state();
        const unsigned int newton_before = counts.newton_iterations;
        try
          {
            solve_increment(problem,
                            current_time,
                            t_end,
                            step,
                            pseudo_transient,
                            predict,
                            counts);
          }
        catch (const std::runtime_error &e)
          {
            dt                        = t_end - current_time;
            problem.solution_vector() = saved_solution;
            last_increment            = saved_increment;
            last_travel               = saved_travel;
            problem.restore_state();
            if (predictor_failed)
              {
                // the same increment from the last converged state: the
                // extrapolated one was no state to start Newton from
                predict = false;
                out << "  step " << step
                    << ": increment retried from the last converged state, "
                       "without the predictor ("
                    << one_line(e.what()) << ")" << std::endl;
                continue;
              }
            if (continuation == Continuation::fallback && !pseudo_transient)
              {
                // the same increment again, with the continuation
                pseudo_transient = true;
                ++counts.continuations;
                out << "  step " << step
                    << ": increment retried with the pseudo-transient "
                       "continuation ("
                    << one_line(e.what()) << ")" << std::endl;
                continue;
              }
            // at most max_cutbacks halvings in a row, and never below
            // step_length / 2^max_cutbacks (a load that can only creep on in
            // ever smaller increments, e.g. beyond the friction limit, stops)
            const double smallest =
              step_length *
              std::ldexp(1., -static_cast<int>(control.max_cutbacks));
            if (cutbacks_in_a_row == control.max_cutbacks ||
                dt / 2 < smallest * (1 - 1e-9))
              throw ConvergenceError(
                std::string(e.what()) +
                (control.max_cutbacks > 0 ?
                   " (also after " + std::to_string(counts.cutbacks) +
                     " cut-backs, the increment down to " +
                     std::to_string(dt / step_length) +
                     " of a step; raise Time stepping/Maximum cut-backs)" :
                   " (no cut-back tried: Time stepping/Maximum cut-backs = "
                   "0)"));
            dt /= 2;
            predict = true;
            ++cutbacks_in_a_row;
            ++counts.cutbacks;
            out << "  step " << step << ": increment cut back to "
                << std::setprecision(3) << dt / step_length << " of a step ("
                << one_line(e.what()) << ")" << std::endl;
            continue;
          }
        // accepted: commit the history of the material and of friction
        problem.commit();
        current_time = t_end;
        ++counts.increments;
        cutbacks_in_a_row = 0;
        pseudo_transient  = continuation == Continuation::always;
        predict           = true;
        // easy increments let the increment grow again, up to a full step
        if (counts.newton_iterations - newton_before <=
            control.easy_newton_iterations)
          dt = std::min(2 * dt, step_length);
      }
    next_increment = dt;
  }
} // namespace densify
