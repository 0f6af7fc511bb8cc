// Newton's method with a step limiter, a residual or energy line search and
// an adaptive linear tolerance, on any problem that gives a residual and a
// tangent.
#pragma once

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/trilinos_vector.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// The Newton line search (Solver/Line search).
  enum class LineSearch
  {
    /// Backtrack until the residual norm falls.
    residual,
    /// Find the step where the energy's derivative along the direction
    /// has fallen to half.
    energy
  };

  /// Pseudo-transient continuation (Solver/Pseudo-transient continuation).
  enum class Continuation
  {
    /// Newton with its line search only.
    off,
    /// Retry an increment whose Newton solve failed with the continuation,
    /// before cutting it back.
    fallback,
    /// Every Newton solve with the continuation.
    always
  };

  /**
   * What Newton's method needs of a problem: the residual R(u) (and its
   * tangent) at the current solution, a linear solve with the tangent, and
   * hooks before a solve and after each update.
   */
  class NonlinearProblem
  {
  public:
    /// An assembly's norms, and a description for the verbose log.
    struct Evaluation
    {
      /// l2 norm of the residual.
      double residual_norm = 0.;
      /// Scale of the relative convergence criterion (same unit).
      double reference_norm = 0.;
      /// For the verbose log, e.g. the number of contact points.
      std::string description;
    };

    virtual ~NonlinearProblem() = default;

    /// Called at the start of every Newton solve.
    virtual void
    begin_solve()
    {}

    /**
     * From the next assembly on, assemble the tangent with a secant
     * stiffness where the exact tangent has none (@p on; e.g. along the slip
     * of Coulomb friction, FrictionLaw::slip_secant), or the exact tangent
     * again. The residual is the same either way. Called only with
     * NewtonControl::secant_start.
     */
    virtual void
    set_secant_tangent(const bool on)
    {
      (void)on;
    }

    /**
     * Assemble the residual (and the tangent if @p with_tangent) at the
     * current solution. @p tangent_margin: a predictor for constraints about
     * to become active (tangent only). @p search: refresh what the assembly
     * searches (e.g. contact candidates) even without a tangent. Throws
     * std::runtime_error where the residual cannot be evaluated (e.g. an
     * inverted element), on every rank.
     */
    virtual Evaluation
    assemble(const bool   with_tangent,
             const double tangent_margin,
             const bool   search) = 0;

    /// The solution u (locally owned entries).
    virtual TrilinosWrappers::MPI::Vector &
    solution_vector() = 0;

    /// The residual of the last assemble().
    virtual TrilinosWrappers::MPI::Vector &
    residual_vector() = 0;

    /**
     * Solve K du = @p rhs with the tangent of the last assembly with one,
     * to the relative tolerance @p relative_tolerance (0: the problem's
     * own); returns the number of linear iterations.
     */
    virtual unsigned int
    solve_linear(const TrilinosWrappers::MPI::Vector &rhs,
                 TrilinosWrappers::MPI::Vector       &du,
                 const double                         relative_tolerance) = 0;

    /// Called after each accepted update of the solution; returns the
    /// number of changes that need a new assembly (e.g. contact points that
    /// changed their master facet).
    virtual unsigned int
    after_update()
    {
      return 0;
    }

    /**
     * Add @p factor times the problem's pseudo mass (a positive definite
     * matrix, the same in every call) to the tangent of the last assembly:
     * the pseudo-transient continuation. Only problems that give a pseudo
     * mass are solved with the continuation.
     */
    virtual void
    add_pseudo_mass(const double factor)
    {
      (void)factor;
      throw std::logic_error("this problem has no pseudo mass");
    }

    /// More of the state for the verbose log of an iteration.
    virtual std::string
    iteration_details()
    {
      return "";
    }
  };

  /// Settings of Newton's method (subsection Solver).
  struct NewtonControl
  {
    /// Converged once |R| <= max(tolerance * reference, floor).
    double tolerance = 1e-9;
    double floor     = 0.;
    /// Most iterations.
    unsigned int max_iterations = 30;
    /// The line search.
    LineSearch line_search = LineSearch::residual;
    /// Inexact Newton: the linear tolerance follows the residual's decrease
    /// (Eisenstat-Walker), never below linear_tolerance.
    bool   adaptive_linear_tolerance = false;
    double linear_tolerance          = 1e-8;
    /// Largest change of any entry of u in one iteration (step limiter).
    double step_limit = std::numeric_limits<double>::max();
    /// The secant start: each solve assembles its tangents with
    /// NonlinearProblem::set_secant_tangent(true) until a correction's
    /// largest entry is at most secant_switch times step_limit, then the
    /// exact tangent to the end of the solve.
    bool   secant_start  = false;
    double secant_switch = 1e-2;
    /// The pseudo-transient continuation: when it is used, and the factor
    /// of the pseudo mass in its first iteration.
    Continuation continuation       = Continuation::off;
    double       continuation_start = 1.;
    /// Print every iteration.
    bool verbose = false;
  };

  /**
   * Newton's method with line search on a NonlinearProblem. The step limiter
   * scales each correction so that no entry changes by more than
   * NewtonControl::step_limit; the line search is a residual backtracking or
   * the energy search (regula falsi with the Illinois modification on
   * R(u + s du) . du). The first trial of a line search is assembled with
   * the tangent, which serves the next iteration if the trial is kept.
   */
  class NewtonSolver
  {
  public:
    NewtonSolver(const NewtonControl &control, ConditionalOStream &out);

    /**
     * Solve R(u) = 0 from the problem's current solution; the first tangent
     * uses the predictor margin @p margin. Returns the numbers of Newton and
     * linear iterations. Throws std::runtime_error (naming @p step) if it
     * does not converge or the residual becomes NaN.
     *
     * With @p pseudo_transient, the pseudo-transient continuation of Kelley
     * and Keyes (1998): each correction solves (K + beta M) du = -R with the
     * problem's pseudo mass M and takes the whole step (up to the step
     * limiter), so the iterates follow an overdamped motion towards a
     * stable equilibrium rather than the nearest root. beta starts at
     * NewtonControl::continuation_start; it is raised fourfold while
     * R.du >= 0 (K + beta M not positive along du); after each step it
     * follows the energy's slope along the step, r = R(u + du).du / R(u).du
     * (r > 0.5: x0.25, 0 <= r <= 0.5: x0.5, -1 <= r < 0: unchanged, else
     * x4), and it never falls below its start times |R| over the scene's
     * reference force, so it vanishes as R does. The residual is never
     * changed, so the converged state solves R(u) = 0 as without the
     * continuation. It gets four times the iterations.
     *
     * With NewtonControl::secant_start, the tangents of the first
     * iterations are secant where the exact one has no stiffness (the slip
     * of Coulomb friction): there a correction of the exact tangent can move
     * the surface of a pore, held only by slipping points and plastic flow,
     * by millimetres, which the line search then cuts to a fraction of a
     * per cent. Once a correction is small (NewtonControl::secant_switch)
     * the exact tangent takes over and the last iterations converge
     * quadratically again.
     *
     * With @p check_first, the first residual is assembled without the
     * tangent, which is assembled only if that residual is not converged: a
     * solve expected to take no iteration (a check) costs one residual. Such
     * a check gets a quarter of the iterations (at least 5).
     */
    std::pair<unsigned int, unsigned int>
    solve(NonlinearProblem  &problem,
          const unsigned int step,
          const double       margin,
          const bool         pseudo_transient = false,
          const bool         check_first      = false);

    /// When the pseudo-transient continuation is used.
    Continuation
    continuation() const
    {
      return control.continuation;
    }

    /// l2 norm of the residual after each iteration of the last solve,
    /// starting with the initial residual.
    const std::vector<double> &
    residuals() const
    {
      return history;
    }

  private:
    const NewtonControl control;
    ConditionalOStream &out;
    std::vector<double> history;
  };
} // namespace densify
