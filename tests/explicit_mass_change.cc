// Explicit dynamics: mass added during a run keeps each node's velocity
// (ExplicitDynamics::renew_mass(), doc/theory.md section 10). A toy system of
// free points (two unknowns a rank, no internal force) is pushed by a unit
// force over the first station (scene time 0..1) with mass 1, then coasts
// over two more stations with mass 4 (the mass renewed at the start of the
// second). The points must keep the velocity they had at the end of the
// push: the displacement over each coasting station is that velocity times
// the station's duration (1e-12), the kinetic energy four times the push's,
// the damping work minus the kinetic energy added (1e-12), and the three
// stations' energy identity (external work = kinetic energy + internal work +
// damping work) holds to h^2 of the external work (the central differences'
// order, at the end of the push within a step; 8.1e-5 with h = 0.018).
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_vector.h>

#include <densify/drivers/explicit_dynamics.h>
#include <densify/parameters.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace densify;

namespace
{
  using Vec = TrilinosWrappers::MPI::Vector;

  /// Free points: mass 1 up to scene time 1, 4 after; a unit force before.
  class FreePoints : public ExplicitSystem
  {
  public:
    double
    update_mass(const double /*required_step*/, Vec &mass) override
    {
      if (mass.size() != points.size())
        mass.reinit(points);
      // start() and the first station: 1; from the second station on: 4
      mass = (n_updates++ < 2 ? 1. : 4.);
      return 0.02;
    }

    void
    forces(const Vec   &u,
           const double scene_time,
           const double /*scene_increment*/,
           const double /*dt*/,
           Vec &internal,
           Vec &external) override
    {
      internal = 0.;
      // the force of the push acts until the end of the first station; its
      // work is booked by the integrator (external_on_mesh)
      external = (scene_time < 1. - 1e-12 ? -1. : 0.);
      (void)u;
    }

    double
    external_work() const override
    {
      return 0.;
    }

    Vec          points;
    unsigned int n_updates = 0;
  };
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int n_ranks            = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);

  IndexSet owned(2 * n_ranks);
  owned.add_range(2 * rank, 2 * rank + 2);
  FreePoints system;
  system.points.reinit(owned, comm);

  ExplicitParameters prm;
  prm.loading_time  = 3.;
  prm.ramp_fraction = 0.;
  prm.mass_scaling  = "none";
  ExplicitDynamics dynamics(prm, 3., comm);
  Vec              u(owned, comm);
  dynamics.start(system, u, false);

  // the push: ends with velocity v at scene time 1
  const ExplicitDynamics::Account push = dynamics.advance(system, u, 1.);
  const double                    u1   = u.mean_value();
  const double v = std::sqrt(2. * push.kinetic / (2. * n_ranks));
  // coasting with mass 4
  const ExplicitDynamics::Account coast = dynamics.advance(system, u, 2.);
  const double                    u2    = u.mean_value();
  const ExplicitDynamics::Account end   = dynamics.advance(system, u, 3.);
  const double                    u3    = u.mean_value();

  const double velocity_2 = (u2 - u1) / (coast.time - push.time);
  const double velocity_3 = (u3 - u2) / (end.time - coast.time);
  const double identity =
    end.external_on_mesh - end.kinetic - end.internal - end.damping;
  const bool ok =
    std::abs(velocity_2 / v - 1.) < 1e-12 &&
    std::abs(velocity_3 / v - 1.) < 1e-12 &&
    std::abs(end.kinetic / push.kinetic - 4.) < 1e-12 &&
    std::abs(end.damping + 3. * push.kinetic) < 1e-12 * push.kinetic &&
    std::abs(identity) < end.step * end.step * end.external_on_mesh;
  if (rank == 0)
    {
      std::cout << std::setprecision(10)
                << "velocity at the end of the push: " << v << '\n'
                << "coasting with four times the mass, velocity over the "
                   "second and third stations / v: "
                << velocity_2 / v << ' ' << velocity_3 / v << '\n'
                << "kinetic energy / the push's: " << end.kinetic / push.kinetic
                << '\n'
                << "damping work / the push's kinetic energy: "
                << end.damping / push.kinetic << '\n'
                << "energy identity / external work: " << std::setprecision(3)
                << std::abs(identity) / end.external_on_mesh << " (h^2 "
                << end.step * end.step << ")\n"
                << (ok ? "OK" : "FAILED") << std::endl;
    }
  return ok ? 0 : 1;
}
