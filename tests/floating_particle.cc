// A particle with no contact at all (next to one pressed between punches)
// does not break the solve: it neither moves nor deforms, and the pressed
// one still balances.
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
  // particle 1 (d = 1.5) floats between the punches without touching them
  testing::read_scene(parameters,
                      prm,
                      "hertz.prm",
                      testing::coarse_sphere("output",
                                             testing::floating_scene()));
  Simulator                 simulator(parameters, MPI_COMM_WORLD, false);
  const std::vector<double> v0 = [&] {
    simulator.setup();
    return simulator.particle_volumes();
  }();
  simulator.run();

  const std::vector<Tensor<1, 3>> drift =
    simulator.particle_mean_displacements();
  const std::vector<double> v1    = simulator.particle_volumes();
  const StepStatistics     &last  = simulator.statistics().back();
  const bool                still = drift[1].norm() < 1e-12;
  const bool same_volume          = std::abs(v1[1] - v0[1]) < 1e-12 * v0[1];
  const bool balanced =
    std::abs(last.upper_punch_force - last.lower_punch_force) <
    1e-6 * last.upper_punch_force;
  if (root)
    std::cout << "pressed particle carries " << std::setprecision(4)
              << last.upper_punch_force
              << " N, balanced: " << (balanced ? "yes" : "NO") << std::endl
              << "floating particle stays put (|mean u| < 1e-12 mm): "
              << (still ? "yes" : "NO") << std::endl
              << "floating particle keeps its volume: "
              << (same_volume ? "yes" : "NO") << std::endl;
  return (still && same_volume && balanced) ? 0 : 1;
}
