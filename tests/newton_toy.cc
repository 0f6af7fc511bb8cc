// The Newton solver and the load stepper on a toy problem without a scene: a
// chain of n nonlinear springs (stiffness k (1 + c s^2) for a stretch s),
// fixed at its left end and pulled at its right end by a force f(t) = F t,
// with a rigid stop that the last node touches through an
// augmented-Lagrangian penalty. Checked against the exact solution:
// - Newton (residual and energy line search, with and without the step
//   limiter) converges to the spring chain's equilibrium, quadratically;
// - too few iterations throw, naming the step;
// - the load stepper reaches the end load through a cut-back after a failed
//   increment, and its augmentations bring the penetration of the stop
//   below the tolerance, with the stop's force equal to F - k (1 + c s^2) s;
// - the iterations of the solves that fail are counted apart from those
//   of the converged ones (StepCounts::failed_newton_iterations);
// - an increment whose predicted state fails before any Newton iteration
//   (the last increment extrapolated beyond a state that fails, as a cell
//   inverted by the extrapolation) is retried from the last converged
//   state, without a cut-back;
// - after a hold whose load travel is round-off but whose solution still
//   moved (a relaxation), the next step's predictor does not extrapolate
//   that move by the ratio of the travels (about 1e14): the step starts
//   from a residual below twice its load change (the exit code) and ends at
//   the exact chain;
// - a stop with two facets whose facet each Newton solve keeps from its
//   start (as contact points keep their master facets): the step that
//   carries the last node across the facets' edge ends in equilibrium with
//   the facet it ends on (the stepper's consistency solves, asked for by
//   LoadStepperControl::max_consistency_solves), so a hold at
//   the same load takes no Newton iteration and stays there.
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <densify/drivers/load_stepper.h>
#include <densify/solvers/newton_solver.h>

#include "toy_problem.h"

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>

namespace
{
  using namespace dealii;
  using namespace densify;

  /// The spring force of a stretch s.
  double
  spring(const double s, const double k, const double c)
  {
    return k * (1. + c * s * s) * s;
  }

  /// The spring chain with a stop at x = gap for the last node.
  class SpringChain : public testing::DirectToy<IncrementalProblem>
  {
  public:
    SpringChain(const unsigned int n, const double gap)
      : DirectToy(n, 1)
      , n(n)
      , gap(gap)
    {}

    /// Scale of the springs' nonlinearity, and the force F at t = 1.
    const double k = 100., c = 50., F_max = 300.;
    /// Penalty of the stop, its multiplier, and failures to simulate.
    double       eps = 1e5, lambda = 0., saved_lambda = 0.;
    unsigned int fail_above_increment = 0;
    double       increment            = 0.;
    /// A last node beyond this fails every assembly (as a cell inverted by
    /// an extrapolated state).
    double fail_beyond = std::numeric_limits<double>::infinity();
    /// The pulling force against time (default F t) and the travel that
    /// set_loads() reports for an increment (default F dt / k).
    std::function<double(double)>         load;
    std::function<double(double, double)> travel;
    /// A faceted stop: beyond x = facet_edge its surface recedes as
    /// gap + facet_slope (x - facet_edge) (continuous at the edge); each
    /// solve keeps the facet of the last node's place at its start, the
    /// first one extended beyond the edge. Off while facet_slope = 0.
    double       facet_slope = 0., facet_edge = 0.;
    unsigned int kept_facet = 0;

    /// The stop's surface by the kept facet at the last node's place.
    double
    stop_position(const double x) const
    {
      return gap + (kept_facet == 1 ? facet_slope * (x - facet_edge) : 0.);
    }

    void
    begin_solve() override
    {
      kept_facet = (facet_slope != 0. && u[n - 1] > facet_edge) ? 1 : 0;
    }

    bool
    start_dependent() const override
    {
      return facet_slope != 0.;
    }

    Evaluation
    assemble(const bool with_tangent,
             const double /*tangent_margin*/,
             const bool /*search*/) override
    {
      if (fail_above_increment > 0 && increment > 0.2)
        {
          --fail_above_increment;
          throw std::runtime_error("simulated failure of a long increment");
        }
      if (u[n - 1] > fail_beyond)
        throw std::runtime_error("simulated inverted cell");
      r = 0;
      if (with_tangent)
        K = 0;
      // springs: node i-1 (or the wall) to node i
      for (unsigned int i = 0; i < n; ++i)
        {
          const double left = (i > 0 ? u[i - 1] : 0.);
          const double s    = u[i] - left;
          const double f    = spring(s, k, c);
          const double dk   = k * (1. + 3. * c * s * s);
          r[i] += f;
          if (i > 0)
            r[i - 1] -= f;
          if (with_tangent)
            {
              K.add(i, i, dk);
              if (i > 0)
                {
                  K.add(i - 1, i - 1, dk);
                  K.add(i, i - 1, -dk);
                  K.add(i - 1, i, -dk);
                }
            }
        }
      // the pulling force and the stop: p = max(0, lambda + eps (u - gap))
      r[n - 1] -= load ? load(time) : F_max * time;
      const double x = u[n - 1];
      const double p = std::max(0., lambda + eps * (x - stop_position(x)));
      r[n - 1] += p;
      if (with_tangent && p > 0)
        K.add(n - 1, n - 1, eps * (1. - (kept_facet == 1 ? facet_slope : 0.)));
      r.compress(VectorOperation::insert);
      if (with_tangent)
        K.compress(VectorOperation::add);
      Evaluation e;
      e.residual_norm  = r.l2_norm();
      e.reference_norm = F_max * std::max(time, 1e-3);
      e.description    = "stop force " + std::to_string(p);
      return e;
    }

    double
    set_loads(const double t, const double dt) override
    {
      time      = t;
      increment = dt;
      return travel ? travel(t, dt) : F_max * dt / k;
    }

    double
    evaluate_constraints() override
    {
      return std::max(0., u[n - 1] - stop_position(u[n - 1]));
    }

    void
    update_multipliers() override
    {
      lambda =
        std::max(0., lambda + eps * (u[n - 1] - stop_position(u[n - 1])));
    }

    void
    save_state() override
    {
      saved_lambda = lambda;
    }

    void
    restore_state() override
    {
      lambda = saved_lambda;
    }

    void
    commit() override
    {
      ++commits;
    }

    const unsigned int n;
    const double       gap;
    double             time    = 0.;
    unsigned int       commits = 0;
  };

  /// The exact free chain: every spring carries the force f, s solves
  /// k (1 + c s^2) s = f (Newton on the scalar equation).
  double
  exact_stretch(const double f, const double k, const double c)
  {
    double s = 0.;
    for (unsigned int i = 0; i < 100; ++i)
      s -= (spring(s, k, c) - f) / (k * (1. + 3. * c * s * s));
    return s;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               silent(std::cout, false);
  bool                             ok = true;
  std::cout << std::boolalpha;

  // Newton alone at the full load, no stop in reach
  for (const LineSearch search : {LineSearch::residual, LineSearch::energy})
    for (const double limit : {1e10, 0.5})
      {
        SpringChain chain(8, 1e10);
        chain.set_loads(1., 1.);
        NewtonControl control;
        control.tolerance      = 1e-12;
        control.line_search    = search;
        control.step_limit     = limit;
        control.max_iterations = 50;
        NewtonSolver newton(control, silent);
        const auto [iterations, linear] = newton.solve(chain, 1, 0.);
        const double s     = exact_stretch(chain.F_max, chain.k, chain.c);
        double       error = 0.;
        for (unsigned int i = 0; i < chain.n; ++i)
          error = std::max(error, std::abs(chain.u[i] - (i + 1) * s));
        // quadratic convergence at the end: once the residual is below
        // 1e-3 of the first, the next one is at most 10 times its square
        // (relative to the first), or at round-off
        const std::vector<double> &h         = newton.residuals();
        const double               r0        = h.front();
        bool                       quadratic = false;
        for (unsigned int k = 0; k + 1 < h.size(); ++k)
          if (h[k] / r0 < 1e-3)
            {
              quadratic =
                h[k + 1] / r0 < std::max(10. * std::pow(h[k] / r0, 2), 1e-13);
              break;
            }
        std::cout << (search == LineSearch::energy ? "energy" : "residual")
                  << " line search, step limit " << limit
                  << ": converged to the exact chain (error < 1e-10 mm): "
                  << (error < 1e-10) << ", quadratic at the end: " << quadratic
                  << ", linear solves = iterations: " << (linear == iterations)
                  << ", limited takes more iterations: "
                  << (limit < 1 ? iterations > 5 : true) << std::endl;
      }

  // too few iterations: an error naming the step
  {
    SpringChain chain(8, 1e10);
    chain.set_loads(1., 1.);
    NewtonControl control;
    control.tolerance      = 1e-12;
    control.max_iterations = 2;
    NewtonSolver newton(control, silent);
    bool         thrown = false;
    try
      {
        newton.solve(chain, 7, 0.);
      }
    catch (const std::runtime_error &e)
      {
        thrown = std::string(e.what()).find("step 7: Newton did not "
                                            "converge in 2 iterations") == 0;
      }
    std::cout << "two iterations: throws, naming the step: " << thrown
              << std::endl;
  }

  // the load stepper: four steps, the stop reached in the third; the first
  // increment of the step after the first fails twice and is cut back
  {
    // the free chain's end would reach 3.0 mm at F_max: the stop engages in
    // the first step
    const double  gap = 1.1;
    SpringChain   chain(8, gap);
    NewtonControl control;
    control.tolerance = 1e-12;
    NewtonSolver       newton(control, silent);
    LoadStepperControl steps;
    steps.step_length   = 0.25;
    steps.gap_tolerance = 1e-8;
    LoadStepper stepper(steps, newton, silent);
    stepper.setup(chain.u);
    double     t = 0.;
    StepCounts counts;
    chain.fail_above_increment = 0;
    for (unsigned int step = 1; step <= 4; ++step)
      {
        // a long increment fails twice in the second step: from the
        // predictor, then from the last converged state; it is cut back
        chain.fail_above_increment = (step == 2 ? 2 : 0);
        chain.increment            = 0.;
        stepper.advance_to(chain, t, 0.25 * step, step, counts);
      }
    // at the end the stop holds the last node at the gap: the springs carry
    // the force of a uniform stretch gap / n, the stop the rest
    const double s          = gap / chain.n;
    const double stop_force = chain.F_max - spring(s, chain.k, chain.c);
    std::cout
      << "load stepper: end time reached: " << (std::abs(t - 1.) < 1e-14)
      << ", cut back after the failure: " << (counts.cutbacks == 1)
      << ", increments " << counts.increments << " (commits " << chain.commits
      << ")"
      << ", augmentations made: " << (counts.augmentations > 0) << std::endl
      << "penetration below the tolerance: "
      << (chain.u[chain.n - 1] - gap < 1e-8)
      << ", stop force = F - spring force (within 1e-6 of F): "
      << (std::abs(
            std::max(0.,
                     chain.lambda + chain.eps * (chain.u[chain.n - 1] - gap)) -
            stop_force) < 1e-6 * chain.F_max)
      << std::endl;
  }

  // one Newton iteration a solve cannot reach the full load's equilibrium,
  // nor those of its two cut-backs: three failed solves of one iteration
  // each, none converged
  {
    SpringChain   chain(8, 1e10);
    NewtonControl control;
    control.tolerance      = 1e-12;
    control.max_iterations = 1;
    NewtonSolver       newton(control, silent);
    LoadStepperControl steps;
    steps.max_cutbacks = 2;
    LoadStepper stepper(steps, newton, silent);
    stepper.setup(chain.u);
    double     t = 0.;
    StepCounts counts;
    bool       thrown = false;
    try
      {
        stepper.advance_to(chain, t, 1., 1, counts);
      }
    catch (const ConvergenceError &)
      {
        thrown = true;
      }
    // the solver path (the iterations counted) goes to stderr and into
    // the exit code, not into the compared output
    std::cerr << "failed solves: " << counts.cutbacks << " cut-backs, "
              << counts.failed_newton_iterations << " failed and "
              << counts.newton_iterations << " converged iterations"
              << std::endl;
    if (!(counts.cutbacks == 2 && counts.failed_newton_iterations == 3 &&
          counts.newton_iterations == 0))
      ok = false;
    std::cout << "failed solves: the step fails, reporting the failure: "
              << thrown << std::endl;
  }

  // the load rises to F_max / 2 in the first step and by 1 % of that in
  // the second, whose reported travel is the first's: the predictor
  // extrapolates the whole first increment again (the last node from
  // about 2.2 to 4.4 mm), beyond 3 mm, where every assembly fails
  {
    SpringChain chain(8, 1e10);
    chain.load = [&chain](const double t) {
      return chain.F_max * (t <= 0.5 ? t : 0.5 + 0.01 * (t - 0.5));
    };
    chain.travel = [&chain](const double, const double dt) {
      return chain.F_max * dt / chain.k;
    };
    chain.fail_beyond = 3.;
    NewtonControl control;
    control.tolerance = 1e-12;
    NewtonSolver       newton(control, silent);
    LoadStepperControl steps;
    steps.step_length = 0.5;
    LoadStepper stepper(steps, newton, silent);
    stepper.setup(chain.u);
    double     t = 0.;
    StepCounts counts;
    for (unsigned int step = 1; step <= 2; ++step)
      stepper.advance_to(chain, t, 0.5 * step, step, counts);
    const double s = exact_stretch(chain.load(1.), chain.k, chain.c);
    std::cerr << "a predicted state that fails: " << counts.cutbacks
              << " cut-backs, " << counts.increments << " increments"
              << std::endl;
    if (!(counts.cutbacks == 0 && counts.increments == 2))
      ok = false;
    std::cout << "a predicted state that fails: the loading ends at the "
                 "exact chain (error < 1e-10 mm): "
              << (std::abs(chain.u[chain.n - 1] - chain.n * s) < 1e-10)
              << std::endl;
  }

  // a hold: the load drops by 1 % over the second step (a relaxation) while
  // the reported travel is round-off, then rises again in the third
  {
    SpringChain chain(8, 1e10);
    chain.load = [&chain](const double t) {
      return chain.F_max * (t <= 0.25 ? t :
                            t <= 0.5  ? 0.25 - 0.01 * (t - 0.25) :
                                        t - 0.2525);
    };
    chain.travel = [&chain](const double t, const double dt) {
      return t > 0.25 && t <= 0.5 ? 1e-16 : chain.F_max * dt / chain.k;
    };
    NewtonControl control;
    control.tolerance = 1e-12;
    NewtonSolver       newton(control, silent);
    LoadStepperControl steps;
    steps.step_length = 0.25;
    LoadStepper stepper(steps, newton, silent);
    stepper.setup(chain.u);
    double     t = 0.;
    StepCounts counts;
    for (unsigned int step = 1; step <= 3; ++step)
      stepper.advance_to(chain, t, 0.25 * step, step, counts);
    // the third step's load change: F_max * 0.25
    const double first = newton.residuals().front();
    const double s     = exact_stretch(chain.load(0.75), chain.k, chain.c);
    // the start's residual is bounded (the exit code), not compared: the
    // path (residuals, cut-backs) goes to stderr
    std::cerr << "after a hold: first residual of the next step " << first
              << " N (bound 2 F dt = " << 2 * chain.F_max * 0.25
              << " N), cut-backs " << counts.cutbacks << std::endl;
    if (!(first < 2 * chain.F_max * 0.25))
      ok = false;
    std::cout << "after a hold: the next step ends at the exact chain "
                 "(error < 1e-10 mm): "
              << (std::abs(chain.u[chain.n - 1] - chain.n * s) < 1e-10)
              << std::endl;
  }

  // the faceted stop at 1 mm whose second facet starts at 0.99 mm and
  // recedes with slope 1/2, loaded to F_max / 2 in the first step (the free
  // chain's end would reach beyond 2 mm) and held in the second; the gap
  // tolerance (0.01 mm) takes the penalty's penetration (about 2e-3 mm)
  // without augmentation. The first facet, extended, holds the node at
  // 1.0015 mm, past the edge; the consistent equilibrium is on the second
  // facet: F = spring(x / n) + eps (x - 1 - (x - 0.99) / 2), x = 1.013 mm.
  {
    const double gap = 1.;
    SpringChain  chain(8, gap);
    chain.facet_slope = 0.5;
    chain.facet_edge  = 0.99;
    chain.load        = [&chain](const double t) {
      return chain.F_max * std::min(t, 0.5);
    };
    chain.travel = [&chain](const double t, const double dt) {
      return t > 0.5 ? 1e-16 : chain.F_max * dt / chain.k;
    };
    // the consistent equilibrium by bisection
    double lo = chain.facet_edge, hi = 1.1;
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double x = 0.5 * (lo + hi);
        const double excess =
          spring(x / chain.n, chain.k, chain.c) +
          chain.eps * (x - gap - chain.facet_slope * (x - chain.facet_edge)) -
          chain.F_max * 0.5;
        (excess > 0 ? hi : lo) = x;
      }
    const double  consistent = 0.5 * (lo + hi);
    NewtonControl control;
    control.tolerance = 1e-12;
    NewtonSolver       newton(control, silent);
    LoadStepperControl steps;
    steps.step_length            = 0.5;
    steps.gap_tolerance          = 1e-2;
    steps.max_consistency_solves = 4;
    LoadStepper stepper(steps, newton, silent);
    stepper.setup(chain.u);
    double     t = 0.;
    StepCounts loading, hold;
    stepper.advance_to(chain, t, 0.5, 1, loading);
    const double loaded = chain.u[chain.n - 1];
    stepper.advance_to(chain, t, 1., 2, hold);
    const double held = chain.u[chain.n - 1];
    std::cerr << "faceted stop: the node at " << std::setprecision(12) << loaded
              << " mm after the loading (" << loading.newton_iterations
              << " Newton iterations), " << held << " mm after the hold ("
              << hold.newton_iterations << ")" << std::endl;
    std::cout << "faceted stop: the loading ends in equilibrium with the "
                 "second facet (within 1e-9 mm): "
              << (std::abs(loaded - consistent) < 1e-9)
              << ", the hold takes no Newton iteration and stays there: "
              << (hold.newton_iterations == 0 &&
                  std::abs(held - loaded) < 1e-12)
              << std::endl;
  }
  return ok ? 0 : 1;
}
