// Newton's method with step limiter and line search.
#include <densify/solvers/newton_solver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace densify
{
  NewtonSolver::NewtonSolver(const NewtonControl &control,
                             ConditionalOStream  &out)
    : control(control)
    , out(out)
  {}



  std::pair<unsigned int, unsigned int>
  NewtonSolver::solve(NonlinearProblem  &problem,
                      const unsigned int step,
                      const double       margin,
                      const bool         pseudo_transient,
                      const bool         check_first)
  {
    TrilinosWrappers::MPI::Vector &solution = problem.solution_vector();
    TrilinosWrappers::MPI::Vector &residual = problem.residual_vector();
    TrilinosWrappers::MPI::Vector  increment(solution);
    const double                   tol = control.tolerance;

    unsigned int linear_iterations = 0;
    history.clear();
    // the secant start: secant tangents until a correction is small
    bool secant = control.secant_start;
    if (secant)
      problem.set_secant_tangent(true);
    problem.begin_solve();
    NonlinearProblem::Evaluation current =
      problem.assemble(!check_first, margin, check_first);
    if (problem.after_update() > 0)
      current = problem.assemble(!check_first, margin, check_first);
    double line_search_step = 1.;
    // the first trial of a line search is assembled with the tangent, which
    // serves the next Newton iteration if the trial is kept; it is wasted if
    // the line search goes on or the problem changes after the update (e.g.
    // contact points change their master facet). So after an iteration
    // whose first trial was not kept, the next first trial is assembled
    // without it (the late steps of the paper scene keep fewer than half of
    // their first trials)
    bool first_trial_kept = true;
    // inexact Newton (Solver/Adaptive linear tolerance): the forcing term
    // eta of Eisenstat and Walker (1996), choice 2 with gamma = 0.9 (their
    // safeguard acts only above 0.1, beyond eta_max here)
    constexpr double eta_max = 1e-2;
    double           eta     = eta_max;
    // the pseudo-transient continuation's factor of the pseudo mass
    const double       beta_start = control.continuation_start;
    double             beta       = pseudo_transient ? beta_start : 0.;
    const unsigned int max_iterations =
      check_first ? std::max(5u, control.max_iterations / 4) :
                    (pseudo_transient ? 4 : 1) * control.max_iterations;
    for (unsigned int it = 0; it <= max_iterations; ++it)
      {
        history.push_back(current.residual_norm);
        const double target =
          std::max(tol * current.reference_norm, control.floor);
        if (control.verbose)
          out << "    newton " << it << ": |R| = " << std::scientific
              << std::setprecision(3) << current.residual_norm << " (target "
              << target << "), " << current.description
              << problem.iteration_details() << ", line search "
              << std::defaultfloat << line_search_step;
        if (control.verbose && beta > 0)
          out << ", pseudo mass " << beta;
        if (control.verbose)
          out << std::endl;
        if (current.residual_norm <= target)
          return {it, linear_iterations};
        if (it == max_iterations)
          break;
        if (it == 0 && check_first)
          current = problem.assemble(true, margin, false);
        if (control.adaptive_linear_tolerance && it > 0)
          {
            const double ratio = current.residual_norm / history[it - 1];
            eta                = 0.9 * ratio * ratio;
            // no more accuracy than the Newton target can use
            eta = std::max(eta, 0.1 * target / current.residual_norm);
            eta = std::min(eta, eta_max);
          }
        double phi0;
        {
          residual *= -1.;
          // the continuation: the pseudo mass on the tangent; where K +
          // beta M is not positive along the correction (a tipping mode
          // whose negative stiffness beta M does not outweigh), more pseudo
          // mass, else the correction would lead back to the unstable state
          double beta_added = 0.;
          for (unsigned int tries = 0;; ++tries)
            {
              if (beta > beta_added)
                problem.add_pseudo_mass(beta - beta_added);
              beta_added = beta;
              increment  = 0;
              linear_iterations +=
                problem.solve_linear(residual,
                                     increment,
                                     control.adaptive_linear_tolerance ?
                                       std::max(eta, control.linear_tolerance) :
                                       0.);
              // R.du, with residual = -R here
              phi0 = -(residual * increment);
              if (beta == 0 || phi0 < 0 || tries == 8)
                break;
              beta *= 4;
            }
        }

        // step limiter: no entry moves by more than the limit in one
        // iteration (nearly free rigid-body modes would otherwise take huge,
        // at finite strain distorting, steps)
        const double max_step = increment.linfty_norm();
        const double limit    = control.step_limit;
        // the exact tangent from the next assembly on (the line search's
        // first trial assembles the next iteration's tangent)
        if (secant && max_step <= control.secant_switch * limit)
          {
            secant = false;
            problem.set_secant_tangent(false);
            if (control.verbose)
              out << "      the exact tangent from here" << std::endl;
          }
        // line search: "residual" backtracks until |R| falls; "energy" looks
        // for the step where phi(s) = R(u + s du).du, the derivative of the
        // incremental energy along du, has fallen to half of |phi(0)|
        // (regula falsi with the Illinois modification in a bracket of phi's
        // sign change). phi(0) = -du.K.du < 0 unless du is no descent
        // direction; then the residual search is used.
        const double r0    = current.residual_norm;
        const double s_max = (max_step > limit ? limit / max_step : 1.);
        // the continuation takes the whole step
        const bool energy =
          control.line_search == LineSearch::energy && phi0 < 0 && beta == 0;
        double s = s_max, s_applied = 0;
        double lo = 0, phi_lo = phi0, hi = s_max;
        double phi_hi = std::numeric_limits<double>::infinity();
        int    kept   = 0; // Illinois: the bracket end moved last
        NonlinearProblem::Evaluation trial;
        bool                         have_matrix = true;
        unsigned int                 n_trials    = 0;
        double                       phi_trial   = 0.;
        for (unsigned int ls = 0;; ++ls)
          {
            solution.add(s - s_applied, increment);
            s_applied   = s;
            have_matrix = (ls == 0 && first_trial_kept);
            n_trials    = ls + 1;
            bool failed = false;
            try
              {
                // the first trial refreshes the search, with or without the
                // tangent, so that its residual is the same
                trial = problem.assemble(have_matrix, 0., ls == 0);
              }
            catch (const std::runtime_error &)
              {
                // e.g. an element inverted by the full step: try a shorter
                // one (the failure is collective, so all ranks agree)
                if (ls == 8)
                  throw;
                trial.residual_norm = std::numeric_limits<double>::infinity();
                failed              = true;
              }
            const double phi =
              ((energy || beta > 0) && !failed) ? residual * increment : 0.;
            // a NaN in the residual: a failed trial (thrown below if the
            // last)
            failed = failed || !std::isfinite(phi);
            if (ls == 0)
              phi_trial =
                failed ? std::numeric_limits<double>::infinity() : phi;
            if (control.verbose)
              {
                out << "        trial step " << s
                    << ": |R| = " << trial.residual_norm;
                if (energy)
                  out << ", R.du/|R0.du| = " << phi / std::abs(phi0);
                out << ", " << trial.description << std::endl;
              }
            if (!energy)
              {
                if ((beta > 0 && !failed) ||
                    trial.residual_norm < (1. - 1e-4 * s) * r0 || ls == 8)
                  break;
                // back to u, then the shorter step
                solution.add(-s, increment);
                s_applied = 0;
                s *= 0.5;
                continue;
              }
            if (ls == 8 || (!failed && (std::abs(phi) <= 0.5 * std::abs(phi0) ||
                                        (phi < 0 && s == s_max))))
              break;
            if (failed || phi > 0)
              {
                hi     = s;
                phi_hi = failed ? std::numeric_limits<double>::infinity() : phi;
                if (kept == 1)
                  phi_lo *= 0.5;
                kept = 1;
              }
            else
              {
                lo     = s;
                phi_lo = phi;
                if (kept == -1)
                  phi_hi *= 0.5;
                kept = -1;
              }
            s = std::isfinite(phi_hi) ?
                  lo + (hi - lo) * phi_lo / (phi_lo - phi_hi) :
                  0.5 * (lo + hi);
            s = std::min(std::max(s, lo + 0.01 * (hi - lo)),
                         hi - 0.01 * (hi - lo));
          }
        s = s_applied;
        if (beta > 0)
          {
            // the continuation's pseudo mass follows the energy's slope
            // along the step, R(u + du).du / R(u).du: near 1 the step was
            // far too short (the pseudo mass dominates, e.g. while the
            // iterate leaves an unstable state), between 0 and 1 it
            // contracts like a convergent iteration; below 0 it overshot
            // the minimum along du, and far below (a closing contact, or a
            // failed trial) it was too long
            const double ratio = (n_trials > 1 || !std::isfinite(phi_trial)) ?
                                   -std::numeric_limits<double>::infinity() :
                                   phi_trial / phi0;
            beta *= ratio > 0.5 ? 0.25 :
                    ratio >= 0  ? 0.5 :
                    ratio >= -1 ? 1. :
                                  4.;
            // but no less than in proportion to the out-of-balance force
            // relative to the forces of the scene: small pseudo masses far
            // from equilibrium let soft modes take steps that close many
            // contacts at once
            beta = std::max(beta,
                            beta_start * trial.residual_norm /
                              std::max(current.reference_norm,
                                       std::numeric_limits<double>::min()));
          }
        if (!std::isfinite(trial.residual_norm))
          throw std::runtime_error(
            "step " + std::to_string(step) +
            ": the residual became NaN or infinite; try more steps "
            "(Time stepping/Number of steps) or a smaller Contact/Penalty "
            "factor");
        if (control.verbose)
          out << "      line search: max|du| " << std::setprecision(3)
              << max_step << ", step " << s << std::endl;
        const unsigned int n_changed = problem.after_update();
        if (control.verbose && n_changed > 0)
          out << "      " << n_changed
              << " changes after the update need a new assembly" << std::endl;
        current          = (have_matrix && n_changed == 0) ?
                             trial :
                             problem.assemble(true, 0., false);
        first_trial_kept = n_trials == 1 && n_changed == 0;
        line_search_step = s;
      }
    std::ostringstream msg;
    msg << "step " << step << ": Newton did not converge in " << max_iterations
        << (pseudo_transient ? " iterations with the continuation" :
                               " iterations")
        << " (residual " << std::scientific << std::setprecision(2)
        << current.residual_norm << " N, target "
        << std::max(tol * current.reference_norm, control.floor)
        << " N); try more steps (Time stepping/Number of steps) or raise "
           "Solver/Maximum Newton iterations";
    throw std::runtime_error(msg.str());
  }
} // namespace densify
