// Cut-back: a load step too large for the Newton iteration limit is rolled
// back and retried in smaller increments, and the run still ends exactly at
// the requested load with the forces of an uncut run. With the
// pseudo-transient continuation as fallback (the default) the failed
// increment is first retried at its size with the continuation (four times
// the iterations): the run counts the retry and ends at the same force.
#include <deal.II/base/mpi.h>

#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>

namespace
{
  /// Run the one-step scene with the given Newton iteration limit and
  /// Solver/Pseudo-transient continuation.
  densify::StepStatistics
  run(const std::string &max_newton, const std::string &continuation)
  {
    using namespace densify;
    Parameters       parameters;
    ParameterHandler prm;
    testing::read_scene(parameters,
                        prm,
                        "hertz.prm",
                        {"Output/Directory=output_" + max_newton,
                         "Output/Interval=0",
                         "Mesh/Polynomial degree=1",
                         "Mesh/Element size=0.4",
                         "Mesh/Refined element size=0.1",
                         "Tools/Upper punch/Displacement history=0:0, 1:0.1",
                         "Time stepping/Number of steps=1",
                         "Solver/Maximum Newton iterations=" + max_newton,
                         "Solver/Pseudo-transient continuation=" +
                           continuation});
    Simulator simulator(parameters, MPI_COMM_WORLD, false);
    simulator.run();
    return simulator.statistics().back();
  }
} // namespace

int
main(int argc, char **argv)
{
  using namespace densify;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const StepStatistics             reference = run("30", "off");
  const StepStatistics             cut       = run("3", "off");
  const StepStatistics             retried   = run("3", "fallback");

  const bool was_cut = cut.cutbacks > 0 && cut.increments > 1;
  const bool reached = std::abs(cut.punch_displacement - 0.1) < 1e-14;
  const bool same_force =
    std::abs(cut.upper_punch_force - reference.upper_punch_force) <
    2e-3 * reference.upper_punch_force;
  const bool retried_ok =
    retried.continuations > 0 &&
    std::abs(retried.punch_displacement - 0.1) < 1e-14 &&
    std::abs(retried.upper_punch_force - reference.upper_punch_force) <
      2e-3 * reference.upper_punch_force;
  const bool balanced =
    std::abs(cut.upper_punch_force - cut.lower_punch_force) <
    1e-6 * cut.upper_punch_force;
  std::cout << "uncut run: " << reference.increments << " increment, "
            << reference.cutbacks << " cut-backs" << std::endl
            << "limited Newton: cut back and retried: "
            << (was_cut ? "yes" : "NO") << std::endl
            << "final punch displacement 0.1 mm reached: "
            << (reached ? "yes" : "NO") << std::endl
            << "force equals the uncut run within 0.2 %: "
            << (same_force ? "yes" : "NO") << std::endl
            << "upper = lower punch force: " << (balanced ? "yes" : "NO")
            << std::endl
            << "with the continuation as fallback: retried with it, 0.1 mm "
               "reached, force within 0.2 %: "
            << (retried_ok ? "yes" : "NO") << std::endl;
  return (was_cut && reached && same_force && balanced && retried_ok) ? 0 : 1;
}
