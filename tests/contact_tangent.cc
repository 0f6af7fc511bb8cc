// The particle contact tangent against central finite differences of the
// contact residual. Two spheres (h = 0.3) stacked on the z axis overlap by
// 0.15 mm, the upper one shifted sideways by 0.04 mm, both deformed by a
// smooth field so that no symmetry hides a term; the master facets are
// assigned once (as within a Newton iteration). P1 with contact at the facet
// corners and P2 with contact at the Gauss points, as densify uses them.
// Along random directions v, |K v - (R(u + h v) - R(u - h v)) / 2h| / |K v|:
// - frictionless with the geometric terms (ParticleContact::
//   set_geometric_tangent: rotation of the master normal, sliding of the
//   projection point, and for P2 the curved master facet): below 1e-5, the
//   finite-difference error, for h = 1e-6 and h = 1e-7 mm;
// - without them (the default symmetric tangent eps n n^T): above 1e-3, the
//   size of the neglected terms, which the first check shows to be all of
//   the error.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/contact/particle_contact.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>

namespace
{
  using namespace densify;

  /// A fully ghosted copy of @p owned.
  TrilinosWrappers::MPI::Vector
  ghosted(const DoFHandler<3>                 &dof_handler,
          const TrilinosWrappers::MPI::Vector &owned)
  {
    TrilinosWrappers::MPI::Vector all(dof_handler.locally_owned_dofs(),
                                      complete_index_set(dof_handler.n_dofs()),
                                      MPI_COMM_WORLD);
    all = owned;
    return all;
  }

  /**
   * The largest relative difference of the contact tangent to finite
   * differences for polynomial @p degree, with and without the geometric
   * terms, written to @p out.
   */
  void
  check(const unsigned int degree, std::ostream &out)
  {
    Parameters       parameters;
    ParameterHandler prm;
    testing::read_scene(parameters,
                        prm,
                        "hertz.prm",
                        testing::two_stacked_spheres(degree));
    Simulator simulator(parameters, MPI_COMM_WORLD, false);
    simulator.setup();
    const DoFHandler<3> &dof_handler = simulator.get_dof_handler();
    const MappingFE<3>   mapping(FE_SimplexP<3>(1));
    const IndexSet      &owned_dofs = dof_handler.locally_owned_dofs();

    // the state: particle 1 pressed into particle 0 and shifted, both
    // deformed (a smooth field of the support points)
    TrilinosWrappers::MPI::Vector u_owned(owned_dofs, MPI_COMM_WORLD);
    const FiniteElement<3>       &fe = dof_handler.get_fe();
    const Quadrature<3>           support(fe.get_unit_support_points());
    FEValues<3> fe_values(mapping, fe, support, update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              const unsigned int d = fe.system_to_component_index(i).first;
              const Point<3>    &x = fe_values.quadrature_point(i);
              double             value =
                0.004 * std::sin(2 * x[0] + 3 * x[1] + 1.5 * x[2] + d);
              if (cell->material_id() == 1)
                value += (d == 0 ? 0.04 : d == 2 ? -0.15 : 0.);
              u_owned(dofs[i]) = value;
            }
        }
    u_owned.compress(VectorOperation::insert);
    const TrilinosWrappers::MPI::Vector u = ghosted(dof_handler, u_owned);

    TrilinosWrappers::SparsityPattern pattern(owned_dofs, MPI_COMM_WORLD);
    DoFTools::make_sparsity_pattern(dof_handler, pattern);
    const Quadrature<2> points = degree == 1 ?
                                   testing::facet_corners() :
                                   Quadrature<2>(QGaussSimplex<2>(degree + 1));

    for (const bool geometric : {true, false})
      {
        // frictionless
        ParticleContact contact;
        contact.setup(dof_handler, {1e5, 1e5}, FrictionLaw(), points);
        contact.set_geometric_tangent(geometric);
        contact.update_search(u, 0.2);
        if (geometric)
          {
            contact.add_couplings(pattern);
            pattern.compress();
          }
        contact.reset_projections();
        contact.update_projections(mapping, u);

        TrilinosWrappers::SparseMatrix matrix(pattern);
        TrilinosWrappers::MPI::Vector  residual(owned_dofs, MPI_COMM_WORLD),
          plus(residual), minus(residual), direction(residual), Kv(residual);
        const ParticleContactResult r =
          contact.assemble(mapping, u, residual, &matrix);
        matrix.compress(VectorOperation::add);

        std::mt19937                           random(42);
        std::uniform_real_distribution<double> uniform(-1., 1.);
        double                                 worst = 0;
        for (const double h : {1e-6, 1e-7})
          for (unsigned int trial = 0; trial < 3; ++trial)
            {
              for (const auto i : owned_dofs)
                direction(i) = uniform(random);
              direction.compress(VectorOperation::insert);
              matrix.vmult(Kv, direction);
              for (const double sign : {1., -1.})
                {
                  TrilinosWrappers::MPI::Vector moved = u_owned;
                  moved.add(sign * h, direction);
                  TrilinosWrappers::MPI::Vector &target =
                    sign > 0 ? plus : minus;
                  target = 0;
                  contact.assemble(mapping,
                                   ghosted(dof_handler, moved),
                                   target,
                                   nullptr);
                  target.compress(VectorOperation::add);
                }
              plus -= minus;
              plus /= 2 * h;
              plus -= Kv;
              worst = std::max(worst, plus.l2_norm() / Kv.l2_norm());
            }
        out << "P" << degree << ", "
            << (geometric ? "with the geometric terms" :
                            "normal stiffness eps n n^T only")
            << " (" << r.n_active << " points in contact, force "
            << std::setprecision(4) << r.normal_force
            << " N): largest relative difference to finite differences "
            << std::setprecision(2) << worst
            << (geometric ? ", below 1e-5: " : ", above 1e-3: ")
            << testing::yes(geometric ? worst < 1e-5 : worst > 1e-3)
            << std::endl;
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ostringstream               out;
  for (const unsigned int degree : {1u, 2u})
    check(degree, out);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
