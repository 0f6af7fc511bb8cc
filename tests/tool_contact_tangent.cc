// The tool contact tangent against central finite differences of the tool
// contact residual. One sphere (d = 2.5, h = 0.3) pressed 0.04 mm into the
// lower punch and 0.03 mm into the die wall (radius 1.27 mm about the
// sphere's axis, so the wall's curvature matters), deformed by a smooth
// field so that no symmetry hides a term. P1 with contact at the facet
// corners and P2 with contact at the Gauss points, as densify uses them.
// Along random directions v, |K v - (R(u + h v) - R(u - h v)) / 2h| / |K v|
// for h = 1e-6 and 1e-7 mm must stay below 1e-5 (the finite-difference
// error): frictionless, where the wall's curvature turns the pressure
// (p/r (I_h - e_r e_r)); and with Coulomb friction (mu = 0.2, consistent
// tangent) from a committed state with its own traction 0.0005 mm behind
// (mostly stick) and 0.02 mm behind (mostly slip), and the arctangent law,
// where the friction traction also turns with the wall's normal.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/contact/tool_contact.h>
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
   * The largest relative difference of the tool contact tangent to finite
   * differences for polynomial @p degree, each friction case, written to
   * @p out.
   */
  void
  check(const unsigned int degree, std::ostream &out)
  {
    Parameters       parameters;
    ParameterHandler prm;
    testing::read_scene(parameters,
                        prm,
                        "hertz.prm",
                        {"Output/Directory=output",
                         "Output/Interval=0",
                         "Mesh/Polynomial degree=" + std::to_string(degree),
                         "Mesh/Element size=0.3",
                         "Mesh/Refinement directions=",
                         "Particles/Centres=0,0,1.25",
                         "Particles/Diameters=2.5"});
    Simulator simulator(parameters, MPI_COMM_WORLD, false);
    simulator.setup();
    const DoFHandler<3> &dof_handler = simulator.get_dof_handler();
    const MappingFE<3>   mapping(FE_SimplexP<3>(1));
    const IndexSet      &owned_dofs = dof_handler.locally_owned_dofs();

    // a state: the sphere moved by @p shift and deformed by a smooth field
    // of amplitude @p field
    const FiniteElement<3> &fe = dof_handler.get_fe();
    const Quadrature<3>     support(fe.get_unit_support_points());
    FEValues<3> fe_values(mapping, fe, support, update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    const auto state = [&](const Tensor<1, 3> &shift, const double field) {
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
                v(dofs[i]) = shift[d] + field * std::sin(2 * x[0] + 3 * x[1] +
                                                         1.5 * x[2] + d);
              }
          }
      v.compress(VectorOperation::insert);
      return v;
    };
    const Tensor<1, 3>                  shift({0.05, 0.01, -0.04});
    const TrilinosWrappers::MPI::Vector u_owned = state(shift, 0.004);

    TrilinosWrappers::SparsityPattern pattern(owned_dofs, MPI_COMM_WORLD);
    DoFTools::make_sparsity_pattern(dof_handler, pattern);
    pattern.compress();
    const Quadrature<2>    points = degree == 1 ?
                                      testing::facet_corners() :
                                      Quadrature<2>(QGaussSimplex<2>(degree + 1));
    std::vector<RigidTool> tools(2);
    tools[0].kind     = ToolKind::lower_punch;
    tools[0].position = 0.;
    tools[1].kind     = ToolKind::die_wall;
    tools[1].position = 1.27;

    // the largest relative difference |K v - FD| / |K v| of @p contact at
    // u_owned
    const auto fd_error = [&](const ToolContact &contact) {
      return testing::contact_tangent_error(
        dof_handler, pattern, u_owned, mapping, contact);
    };
    const auto report = [&](const std::string       &what,
                            const double             worst,
                            const ToolContactResult &r) {
      out << "P" << degree << ", " << what << " (" << r.n_active
          << " points in contact, " << r.n_slip << " slipping, punch "
          << std::setprecision(4) << r.normal_force[0] << " N, die wall "
          << r.normal_force[2]
          << " N): largest relative difference to finite differences "
          << std::setprecision(2) << worst
          << ", below 1e-5: " << testing::yes(worst < 1e-5) << std::endl;
    };

    {
      ToolContact contact;
      contact.setup(
        dof_handler, tools, {FrictionLaw(), FrictionLaw()}, {1e5}, points);
      const auto [worst, r] = fd_error(contact);
      report("frictionless", worst, r);
    }

    // the committed state: the sphere back by @p back along (0, 1, -1)/sqrt2
    // (tangential to the wall, into the punch), the field 0.8 times as
    // large; its traction from a further 0.001 mm of motion before that
    for (const std::string model : {"Coulomb", "arctangent"})
      for (const double back : {0.0005, 0.02})
        {
          if (model == "arctangent" && back < 0.01)
            continue;
          const Tensor<1, 3> along(
            {0., 1. / std::sqrt(2.), -1. / std::sqrt(2.)});
          const TrilinosWrappers::MPI::Vector committed =
            testing::ghosted(dof_handler, state(shift - back * along, 0.0032));
          const TrilinosWrappers::MPI::Vector before =
            testing::ghosted(dof_handler,
                             state(shift - (back + 0.001) * along, 0.0032));
          FrictionLaw law;
          law.mu             = 0.2;
          law.slip           = slip_rule(model);
          law.regularisation = 0.01;
          law.consistent     = true;
          ToolContact contact;
          contact.setup(dof_handler, tools, {law, law}, {1e5}, points);
          contact.set_committed_solution(before);
          contact.commit(mapping, committed);
          contact.set_committed_solution(committed);
          const auto [worst, r] = fd_error(contact);
          report(std::string(model == "Coulomb" ? "Coulomb friction" :
                                                  "arctangent friction") +
                   ", committed state " + std::to_string(back) + " mm behind",
                 worst,
                 r);
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
