// Conservation check: for small-strain linear elasticity the volume change of
// the particles follows from the virial of the contact forces,
// int tr(sigma) dV = sum over contacts of X . f, so with punches only
// Delta V = -F H / (3 K), H the (reference) punch gap and K the bulk modulus.
#include <deal.II/base/conditional_ostream.h>
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
  ConditionalOStream               out(std::cout,
                         Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  Parameters                       parameters;
  ParameterHandler                 prm;
  testing::read_scene(parameters,
                      prm,
                      "default.prm",
                      {"Output/Directory=output",
                       "Output/Interval=0",
                       "Time stepping/Number of steps=2",
                       // the identity below is for frictionless punches
                       "Contact/Friction coefficient=0"});
  Simulator simulator(parameters, MPI_COMM_WORLD, false);
  simulator.setup();
  double V0 = 0;
  for (const double v : simulator.particle_volumes())
    V0 += v;
  simulator.run();

  const double E = 43120., nu = 0.3, K = E / (3. * (1. - 2. * nu));
  const double H  = 2.5; // reference punch gap: the test function is X
  bool         ok = true;
  for (const StepStatistics &s : simulator.statistics())
    {
      const double dV        = s.particle_volume - V0;
      const double predicted = -s.upper_punch_force * H / (3. * K);
      const double error     = std::abs(dV - predicted) / std::abs(predicted);
      const bool   step_ok   = error < 5e-3 && s.die_wall_radial_force == 0.;
      ok                     = ok && step_ok;
      out << "step " << s.step << ": dV = " << std::setprecision(5) << dV
          << " mm^3, -F H / (3K) = " << predicted
          << " mm^3, within 0.5 %: " << (step_ok ? "yes" : "NO") << std::endl;
    }
  return ok ? 0 : 1;
}
