// Coulomb friction: an elastic sphere pressed between two punches (friction
// 0.2 on both) and pulled sideways by a body force b through its centre.
// By symmetry each punch holds half of b V. Below the friction limit the
// sphere sticks: at b V / 2 = 0.97 mu N it is in equilibrium with a friction
// force of 0.97 mu N on each punch and moves sideways by an elastic amount
// only; at b V / 2 = 1.01 mu N no static equilibrium exists -- it slides --
// and the run stops with a clear error. The same by CG with the symmetric
// friction tangent and the secant start (Contact/Friction tangent =
// symmetric-secant-start, auto's choice with cg-amg): the same equations, so
// the same limit.
#include <deal.II/base/mpi.h>

#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
  using namespace densify;

  /// The coarse sphere pressed by 0.03 mm in t = 0..1, then pulled by the
  /// body force ramped from 0 to @p b in t = 1..2.
  std::unique_ptr<Simulator>
  make(Parameters       &parameters,
       ParameterHandler &prm,
       const double      b,
       const bool        cg)
  {
    testing::read_scene(
      parameters,
      prm,
      "hertz.prm",
      testing::pulled_sphere("output_b" + std::to_string(b),
                             b,
                             {cg ? "Contact/Friction tangent=auto" :
                                   "Contact/Friction tangent=consistent",
                              cg ? "Solver/Linear solver=cg-amg" :
                                   "Solver/Linear solver=gmres-amg"}));
    return std::make_unique<Simulator>(parameters, MPI_COMM_WORLD, false);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool   root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const double mu   = 0.2;

  // the normal force and the volume, without the pull
  double N = 0, V = 0;
  {
    Parameters       parameters;
    ParameterHandler prm;
    auto             simulator = make(parameters, prm, 0., false);
    // the body force acts on the reference volume
    simulator->setup();
    for (const double v : simulator->particle_volumes())
      V += v;
    simulator->run();
    N = simulator->statistics().back().lower_punch_force;
  }
  std::ostringstream out;
  out << "pressed: N = " << std::setprecision(5) << N << " N" << std::endl;

  for (const bool cg : {false, true})
    {
      const std::string law = cg ? "CG: " : "";
      // just below the limit: sticks
      {
        const double     b = 2 * 0.97 * mu * N / V;
        Parameters       parameters;
        ParameterHandler prm;
        auto             simulator = make(parameters, prm, b, cg);
        simulator->run();
        const StepStatistics &s = simulator->statistics().back();
        const double x = simulator->particle_mean_displacements()[0][0];
        // the sideways displacement to two digits: at 0.97 of the friction
        // limit most contact points slip and the sphere's sideways stiffness is
        // small, so residuals within the Newton tolerance move it by a few 1e-4
        // relative (2.2e-4 between Solver/Line search = energy and residual)
        // the two punches hold the pull together, each below its limit
        // (statistics give the magnitudes of the friction forces; their small
        // components across the pull, from the sphere's slight twist, make the
        // magnitudes add up to a little more than b V: 4.5e-4 measured)
        const double total = s.lower_punch_friction + s.upper_punch_friction;
        out << law << "b V / 2 = 0.97 mu N: friction of the punches / (b V) = "
            << std::setprecision(6) << total / (b * V) << " (1 to 1e-3: "
            << testing::yes(total / (b * V) > 1 - 1e-9 &&
                            total / (b * V) < 1 + 1e-3)
            << "), lower punch friction / (mu N) = " << std::setprecision(3)
            << s.lower_punch_friction / (mu * s.lower_punch_force) << ", upper "
            << s.upper_punch_friction / (mu * s.upper_punch_force)
            << " (both below 1: "
            << testing::yes(s.lower_punch_friction < mu * s.lower_punch_force &&
                            s.upper_punch_friction < mu * s.upper_punch_force)
            << "), sideways displacement " << std::setprecision(2) << x << " mm"
            << std::endl;
      }

      // just above the limit: slides, so no static equilibrium
      {
        const double     b = 2 * 1.01 * mu * N / V;
        Parameters       parameters;
        ParameterHandler prm;
        auto             simulator = make(parameters, prm, b, cg);
        bool             failed    = false;
        try
          {
            simulator->run();
          }
        catch (const std::exception &)
          {
            failed = true;
          }
        out << law
            << "b V / 2 = 1.01 mu N: slides (no equilibrium, the run stops): "
            << testing::yes(failed) << std::endl;
      }
    }
  if (root)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
