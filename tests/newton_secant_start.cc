// Newton's secant start (NewtonControl::secant_start) on a toy problem
// without a scene: a block u0 held by a friction-like force T tanh(u0 / delta)
// (it saturates at T, as Coulomb friction at mu p: far in the slip its exact
// stiffness (T / delta) / cosh^2(u0 / delta) is almost zero) and pulled by a
// force F < T through a spring k to a node u1. Starting with the block far in
// the slip, the exact tangent is nearly singular along the rigid motion of
// both (a body held only by a slipping contact), its corrections are huge and
// the step limiter and the line search cut them; with the secant start the
// first tangents take the secant T tanh(u0 / delta) / u0 there instead.
// Checked, for the exact tangent throughout and for the secant start:
// - both reach the exact equilibrium, u0 = delta atanh(F / T), u1 = u0 + F / k;
// - with the secant start the exact tangent takes over before the end, so
//   that the last iterations converge quadratically, as with the exact
//   tangent throughout.
// The iteration counts go to stderr, not compared: on this toy the energy
// line search copes with the exact tangent's huge correction (6 iterations
// against 8); what the secant start saves in a dense packing, where the soft
// direction is not the one the solve needs, is measured on the paper's scene
// (doc/performance.md, "The secant start").
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <densify/solvers/newton_solver.h>

#include "toy_problem.h"

#include <cmath>
#include <iostream>

namespace
{
  using namespace dealii;
  using namespace densify;

  /// The block and the node (entries 0 and 1).
  class SlippingBlock : public testing::DirectToy<NonlinearProblem>
  {
  public:
    SlippingBlock()
      : DirectToy(2, 1)
    {}

    /// The saturation force, its slip scale, the spring and the pull.
    const double T = 1., delta = 0.1, k = 10., F = 0.5;

    void
    set_secant_tangent(const bool on) override
    {
      secant = on;
      ++switches;
    }

    Evaluation
    assemble(const bool with_tangent,
             const double /*tangent_margin*/,
             const bool /*search*/) override
    {
      const double u0 = u[0], u1 = u[1];
      const double friction = T * std::tanh(u0 / delta);
      const double spring   = k * (u1 - u0);
      r[0]                  = friction - spring;
      r[1]                  = spring - F;
      r.compress(VectorOperation::insert);
      if (with_tangent)
        {
          const double exact = T / delta / std::pow(std::cosh(u0 / delta), 2);
          const double k00 =
            (secant && std::abs(u0) > 0.) ? friction / u0 : exact;
          K = 0;
          K.set(0, 0, k00 + k);
          K.set(0, 1, -k);
          K.set(1, 0, -k);
          K.set(1, 1, k);
          K.compress(VectorOperation::insert);
        }
      Evaluation e;
      e.residual_norm  = r.l2_norm();
      e.reference_norm = F;
      return e;
    }

    bool         secant   = false;
    unsigned int switches = 0;
  };
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               quiet(std::cout, false);
  std::cout << std::boolalpha;
  bool         ok         = true;
  unsigned int iterations = 0, iterations_exact = 0;
  for (const bool secant_start : {false, true})
    {
      NewtonControl control;
      control.tolerance      = 1e-12;
      control.max_iterations = 200;
      control.line_search    = LineSearch::energy;
      control.step_limit     = 1.;
      control.secant_start   = secant_start;
      NewtonSolver  newton(control, quiet);
      SlippingBlock block;
      // far in the slip: the exact stiffness there is about 2.5e-4 of T /
      // delta
      block.u[0] = 0.6;
      block.u[1] = 0.6;
      block.u.compress(VectorOperation::insert);
      const unsigned int n  = newton.solve(block, 1, 0.).first;
      const double       u0 = block.delta * std::atanh(block.F / block.T);
      const double       u1 = u0 + block.F / block.k;
      const bool         exact =
        std::abs(block.u[0] - u0) < 1e-10 && std::abs(block.u[1] - u1) < 1e-10;
      const std::vector<double> &h = newton.residuals();
      // quadratic at the end: the last reduction beats the one before
      const bool quadratic =
        h.size() >= 3 && h[h.size() - 1] / h[h.size() - 2] <
                           std::max(1e-3, h[h.size() - 2] / h[h.size() - 3]);
      std::cout << (secant_start ? "secant start:  " : "exact tangent: ")
                << "the exact equilibrium (within 1e-10): " << exact
                << ", quadratic at the end: " << quadratic;
      ok = ok && exact && quadratic;
      if (secant_start)
        {
          // switched on at the start and off before the end
          const bool switched = block.switches == 2 && !block.secant;
          std::cout << ", the exact tangent took over: " << switched;
          ok         = ok && switched;
          iterations = n;
        }
      else
        iterations_exact = n;
      std::cout << std::endl;
    }
  std::cerr << "iterations: exact tangent " << iterations_exact
            << ", secant start " << iterations << std::endl;
  return ok ? 0 : 1;
}
