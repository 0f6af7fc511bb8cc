// A force term added from outside Densify's sources, through the extension
// point of doc/architecture.md ("An effect with a new force term"):
// a class derived from ForceTerm, handed to the Simulator with
// add_force_term(), which the system builds after its own terms. The toy
// term is a uniform pull b(t) on every particle, -int b . phi dV in the
// residual, with the factor read from the system's load time. The sphere of
// friction_sliding, pressed between two punches and pulled sideways below
// the friction limit, ends in the same state whether the pull comes from
// the built-in body force (Particles/Body force) or from the toy term: the
// punches' friction, the normal force and the sideways displacement agree
// to 1e-6 (the two runs differ only in the order of the residual's sums).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/simulator.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
  using namespace densify;

  /// The pull b(t) = clamp(t - 1, 0, 1) b0 on every particle.
  class ToyPull : public ForceTerm
  {
  public:
    ToyPull(const MultiBodySystem &system, const Tensor<1, 3> &b0)
      : system(system)
      , b0(b0)
    {}

    std::string
    name() const override
    {
      return "Toy pull";
    }

    void
    assemble(const AssemblyContext         &context,
             TrilinosWrappers::MPI::Vector &residual,
             TrilinosWrappers::SparseMatrix * /*tangent*/) override
    {
      const DoFHandler<3>             &dof_handler = system.dof_handler;
      const FiniteElement<3>          &fe          = dof_handler.get_fe();
      const QGaussSimplex<3>           quadrature(fe.degree + 1);
      FEValues<3>                      fe_values(*context.mapping,
                            fe,
                            quadrature,
                            update_values | update_JxW_values);
      const FEValuesExtractors::Vector u(0);
      const Tensor<1, 3> b = std::clamp(system.load_time - 1., 0., 1.) * b0;
      Vector<double>     cell_residual(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_residual = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              for (unsigned int i = 0; i < dofs.size(); ++i)
                cell_residual(i) -=
                  (b * fe_values[u].value(i, q)) * fe_values.JxW(q);
            cell->get_dof_indices(dofs);
            residual.add(dofs, cell_residual);
          }
    }

  private:
    const MultiBodySystem &system;
    const Tensor<1, 3>     b0;
  };



  /// What the two runs are compared by.
  struct End
  {
    double lower_friction, upper_friction, normal, sideways, volume;
  };



  /// The sphere of friction_sliding pressed by 0.03 mm in t = 0..1, then
  /// pulled by b in t = 1..2: by the body force (@p toy false) or by the
  /// toy term.
  End
  run(const double b, const bool toy)
  {
    Parameters       parameters;
    ParameterHandler prm;
    testing::read_scene(
      parameters,
      prm,
      "hertz.prm",
      testing::pulled_sphere(toy ? "output_toy" : "output_body_force",
                             toy ? 0. : b,
                             {"Contact/Friction tangent=consistent",
                              "Solver/Linear solver=gmres-amg"}));
    Simulator simulator(parameters, MPI_COMM_WORLD, false);
    if (toy)
      simulator.add_force_term([b](const MultiBodySystem &system) {
        return std::make_unique<ToyPull>(system, Tensor<1, 3>({b, 0., 0.}));
      });
    simulator.run();
    const StepStatistics &s = simulator.statistics().back();
    return {s.lower_punch_friction,
            s.upper_punch_friction,
            s.lower_punch_force,
            simulator.particle_mean_displacements()[0][0],
            simulator.particle_volumes()[0]};
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  // 0.9 of the friction limit: b V / 2 = 0.9 mu N, mu = 0.2
  const End    pressed = run(0., false);
  const double b       = 2 * 0.9 * 0.2 * pressed.normal / pressed.volume;
  const End    body    = run(b, false);
  const End    toy     = run(b, true);
  const auto   agree   = [](const double x, const double y) {
    return std::abs(x - y) <= 1e-6 * std::max(std::abs(x), std::abs(y));
  };
  std::ostringstream out;
  out << "toy pull against the body force: lower punch friction "
      << testing::yes(agree(toy.lower_friction, body.lower_friction))
      << ", upper "
      << testing::yes(agree(toy.upper_friction, body.upper_friction))
      << ", normal force " << testing::yes(agree(toy.normal, body.normal))
      << ", sideways displacement "
      << testing::yes(agree(toy.sideways, body.sideways))
      << "; the pull is held: "
      << testing::yes(body.sideways > 0. &&
                      body.lower_friction + body.upper_friction > 0.)
      << std::endl;
  if (root)
    std::cout << out.str();
  std::cerr << std::setprecision(10) << "body force: " << body.lower_friction
            << " " << body.upper_friction << " " << body.normal << " "
            << body.sideways << "\ntoy: " << toy.lower_friction << " "
            << toy.upper_friction << " " << toy.normal << " " << toy.sideways
            << std::endl;
  return testing::all_passed ? 0 : 1;
}
