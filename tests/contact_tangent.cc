// The particle contact tangent against central finite differences of the
// contact residual. Two spheres (h = 0.3) stacked on the z axis overlap by
// 0.15 mm, the upper one shifted sideways by 0.04 mm, both deformed by a
// smooth field so that no symmetry hides a term; the master facets are
// assigned once (as within a Newton iteration). P1 with contact at the facet
// corners and P2 with contact at the Gauss points, as densify uses them.
// Along random directions v, |K v - (R(u + h v) - R(u - h v)) / 2h| / |K v|:
// - with the geometric terms (ParticleContact::set_geometric_tangent:
//   rotation of the master normal, sliding of the projection point, for P2
//   the curved master facet, and with friction how the tangent plane and the
//   slip increment follow them): below 1e-5, the finite-difference error,
//   for h = 1e-6 and h = 1e-7 mm;
// - without them (normal stiffness eps n n^T and the friction law's own
//   stiffness): above 1e-3, the size of the neglected terms, which the first
//   check shows to be all of the error.
// Each for frictionless contact; Coulomb friction (mu = 0.2, consistent
// tangent) from a committed state with its own traction 0.0005 mm behind
// (mostly stick) and 0.02 mm behind (mostly slip); and the arctangent law.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/contact/particle_contact.h>
#include <densify/simulator.h>

#include "tangent_check.h"
#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>

namespace
{
  using namespace densify;

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

    // a state: particle 1 pressed into particle 0 and shifted, both
    // deformed (a smooth field of the support points)
    const FiniteElement<3> &fe = dof_handler.get_fe();
    const Quadrature<3>     support(fe.get_unit_support_points());
    FEValues<3> fe_values(mapping, fe, support, update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    const auto state = [&](const double shift_x, const double field) {
      TrilinosWrappers::MPI::Vector v(owned_dofs, MPI_COMM_WORLD);
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
                  field * std::sin(2 * x[0] + 3 * x[1] + 1.5 * x[2] + d);
                if (cell->material_id() == 1)
                  value += (d == 0 ? shift_x : d == 2 ? -0.15 : 0.);
                v(dofs[i]) = value;
              }
          }
      v.compress(VectorOperation::insert);
      return v;
    };
    const TrilinosWrappers::MPI::Vector u_owned = state(0.04, 0.004);
    const TrilinosWrappers::MPI::Vector u =
      testing::ghosted(dof_handler, u_owned);

    TrilinosWrappers::SparsityPattern pattern(owned_dofs, MPI_COMM_WORLD);
    DoFTools::make_sparsity_pattern(dof_handler, pattern);
    const Quadrature<2> points  = degree == 1 ?
                                    testing::facet_corners() :
                                    Quadrature<2>(QGaussSimplex<2>(degree + 1));
    bool                coupled = false;

    // the largest relative difference |K v - FD| / |K v| of @p contact at u
    const auto fd_error = [&](ParticleContact &contact) {
      contact.update_search(u, 0.2);
      if (!coupled)
        {
          contact.add_couplings(pattern);
          pattern.compress();
          coupled = true;
        }
      contact.reset_projections();
      contact.update_projections(mapping, u);

      return testing::contact_tangent_error(
        dof_handler, pattern, u_owned, mapping, contact);
    };
    const auto report = [&](const std::string           &what,
                            const bool                   geometric,
                            const double                 worst,
                            const ParticleContactResult &r) {
      out << "P" << degree << ", " << what << ", "
          << (geometric ? "with the geometric terms" :
                          "without the geometric terms")
          << " (" << r.n_active << " points in contact, " << r.n_slip
          << " slipping, force " << std::setprecision(4) << r.normal_force
          << " N): largest relative difference to finite differences "
          << std::setprecision(2) << worst
          << (geometric ? ", below 1e-5: " : ", above 1e-3: ")
          << testing::yes(geometric ? worst < 1e-5 : worst > 1e-3) << std::endl;
    };

    for (const bool geometric : {true, false})
      {
        ParticleContact contact;
        contact.setup(dof_handler, {1e5, 1e5}, FrictionLaw(), points);
        contact.set_geometric_tangent(geometric);
        const auto [worst, r] = fd_error(contact);
        report("frictionless", geometric, worst, r);
      }

    // Coulomb friction (mu = 0.2, consistent), from a committed state with
    // its own traction: the particle shifted back by 0.0005 mm (most points
    // stick) or by 0.02 mm (most slip), the field scaled by 0.8 (so the
    // master displacement increment varies along the facet); the committed
    // traction from the stick of a further 0.001 mm before that; and the
    // arctangent law
    for (const std::string model : {"Coulomb", "arctangent"})
      for (const double back : {0.0005, 0.02})
        {
          if (model == "arctangent" && back < 0.01)
            continue;
          const TrilinosWrappers::MPI::Vector committed =
            testing::ghosted(dof_handler, state(0.04 - back, 0.0032));
          const TrilinosWrappers::MPI::Vector before =
            testing::ghosted(dof_handler, state(0.04 - back - 0.001, 0.0032));
          for (const bool geometric : {true, false})
            {
              FrictionLaw law;
              law.mu             = 0.2;
              law.slip           = slip_rule(model);
              law.regularisation = 0.01;
              law.consistent     = true;
              ParticleContact contact;
              contact.setup(dof_handler, {1e5, 1e5}, law, points);
              contact.set_geometric_tangent(geometric);
              contact.set_committed_solution(before);
              contact.update_search(committed, 0.2);
              contact.reset_projections();
              contact.update_projections(mapping, committed);
              contact.commit(mapping, committed);
              contact.set_committed_solution(committed);
              const auto [worst, r] = fd_error(contact);
              report(std::string(model == "Coulomb" ? "Coulomb friction" :
                                                      "arctangent friction") +
                       ", committed state " + std::to_string(back) +
                       " mm behind",
                     geometric,
                     worst,
                     r);
            }
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
