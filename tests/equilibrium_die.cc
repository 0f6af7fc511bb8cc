// Equilibrium: a sphere pressed between punches bulges against a frictionless
// die wall; upper punch force = lower punch force to 1e-6 relative, and the
// die wall takes a radial but no axial force.
#include <deal.II/base/mpi.h>

#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>

int
main(int argc, char **argv)
{
  using namespace densify;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool       root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  Parameters       parameters;
  ParameterHandler prm;
  // a sphere of d = 2.5 touching the wall of a die of diameter 2.5
  testing::read_scene(parameters,
                      prm,
                      "hertz.prm",
                      testing::coarse_sphere(
                        "output",
                        {"Tools/Die wall/Enabled=true",
                         "Tools/Die wall/Diameter=2.5",
                         "Tools/Upper punch/Displacement history=0:0, 1:0.25",
                         "Time stepping/Number of steps=3"}));
  Simulator simulator(parameters, MPI_COMM_WORLD, false);
  simulator.run();

  bool ok = true;
  for (const StepStatistics &s : simulator.statistics())
    {
      const double imbalance =
        std::abs(s.upper_punch_force - s.lower_punch_force) /
        s.upper_punch_force;
      // the bulging equator reaches the faceted die wall in the last step
      const bool last    = (s.step == simulator.statistics().size());
      const bool step_ok = imbalance < 1e-6 &&
                           (!last || s.die_wall_radial_force > 0) &&
                           std::abs(s.die_wall_force) < 1e-9;
      ok = ok && step_ok;
      if (root)
        std::cout << "step " << s.step << ": F_upper " << std::setprecision(5)
                  << s.upper_punch_force << " N, upper = lower to 1e-6: "
                  << (imbalance < 1e-6 ? "yes" : "NO")
                  << ", die wall radial force > 0: "
                  << (s.die_wall_radial_force > 0 ? "yes" : "no")
                  << ", axial = 0: "
                  << (std::abs(s.die_wall_force) < 1e-9 ? "yes" : "NO")
                  << std::endl;
    }
  return ok ? 0 : 1;
}
