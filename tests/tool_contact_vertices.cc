// The explicit pass of tool contact evaluated once per surface vertex
// (ToolContact::vertex_pass) against the evaluation of every slave point of
// every face (each vertex is a slave point of about six faces). Two spheres
// (P1, h = 0.3, contact points at the facet corners as densify uses for
// P1) stacked on the z axis between two punches that reach 0.02 mm into
// them and in a die wall 0.02 mm narrower than the spheres, all with
// Coulomb friction 0.2; in 200 passes both spheres slide sideways by
// 0.05 mm in x and 0.02 mm in y (each pass's start is the last pass's end,
// so points stick and slip), and the upper punch moves down by 0.01 mm.
// Checked at every pass: the same forces to 1e-12 of the largest (the
// copies' tractions are added in another order), the same normal, axial
// and friction forces of each tool and friction work to 1e-12, and the same
// numbers of points in contact and slipping.
#include <deal.II/base/mpi.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/assembly/all_values.h>
#include <densify/contact/tool_contact.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <iomanip>
#include <iostream>

namespace
{
  using namespace densify;

  /// |a - b| relative to @p scale.
  double
  relative(const double a, const double b, const double scale)
  {
    return std::abs(a - b) / std::max(scale, 1e-300);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Parameters                       parameters;
  ParameterHandler                 prm;
  testing::read_scene(parameters,
                      prm,
                      "hertz.prm",
                      testing::two_stacked_spheres(1));
  Simulator simulator(parameters, MPI_COMM_WORLD, false);
  simulator.setup();
  const DoFHandler<3> &dof_handler = simulator.get_dof_handler();
  const MappingFE<3>   mapping(FE_SimplexP<3>(1));

  const double           reach = 0.02;
  std::vector<RigidTool> tools(3);
  tools[0].kind     = ToolKind::lower_punch;
  tools[0].position = reach;
  tools[1].kind     = ToolKind::upper_punch;
  tools[1].position = 5. - reach;
  tools[2].kind     = ToolKind::die_wall;
  tools[2].position = 1.25 - reach;
  FrictionLaw coulomb;
  coulomb.mu = 0.2;
  ToolContact by_vertex, every_point;
  every_point.set_vertex_evaluation(false);
  for (ToolContact *contact : {&by_vertex, &every_point})
    contact->setup(dof_handler,
                   tools,
                   std::vector<FrictionLaw>(3, coulomb),
                   {1e5, 1e5},
                   testing::facet_corners());

  const unsigned int n = 200;
  double largest = 0., largest_difference = 0., largest_sum_difference = 0.;
  unsigned int most_active = 0, most_slipping = 0, count_differences = 0;
  TrilinosWrappers::MPI::Vector last =
    testing::smooth_displacement(dof_handler, Tensor<1, 3>());
  for (unsigned int k = 1; k <= n; ++k)
    {
      const TrilinosWrappers::MPI::Vector u = testing::smooth_displacement(
        dof_handler, Tensor<1, 3>({0.05 * k / n, 0.02 * k / n, 0.}));
      AllValues values, committed;
      values.gather(u);
      committed.gather(last);
      const auto forces = [&](ToolContact &contact) {
        contact.set_tool_position(ToolKind::upper_punch,
                                  5. - reach - 0.01 * k / n);
        contact.set_committed_solution(last);
        TrilinosWrappers::MPI::Vector f(dof_handler.locally_owned_dofs(),
                                        MPI_COMM_WORLD);
        LocalForces                   local;
        local.start(f);
        ContactOutputs plain;
        plain.values           = &values;
        plain.committed_values = &committed;
        plain.plain_residual   = &local;
        const ToolContactResult result =
          contact.assemble_and_commit(mapping, u, f, 0., &plain);
        local.finish(f);
        f.compress(VectorOperation::add);
        return std::make_pair(f, result);
      };
      auto [difference, a]      = forces(by_vertex);
      const auto [reference, b] = forces(every_point);
      largest                   = std::max(largest, reference.l2_norm());
      difference -= reference;
      largest_difference = std::max(largest_difference, difference.l2_norm());
      double scale       = 0.;
      for (unsigned int t = 0; t < n_tool_kinds; ++t)
        scale = std::max(scale, b.normal_force[t]);
      for (unsigned int t = 0; t < n_tool_kinds; ++t)
        largest_sum_difference = std::max(
          {largest_sum_difference,
           relative(a.normal_force[t], b.normal_force[t], scale),
           relative(a.axial_force[t], b.axial_force[t], scale),
           (a.friction_force[t] - b.friction_force[t]).norm() / scale});
      largest_sum_difference = std::max(largest_sum_difference,
                                        relative(a.friction_work,
                                                 b.friction_work,
                                                 std::abs(b.friction_work)));
      most_active            = std::max(most_active, b.n_active);
      most_slipping          = std::max(most_slipping, b.n_slip);
      count_differences += (a.n_active != b.n_active || a.n_slip != b.n_slip);
      last = u;
    }
  std::ostringstream out;
  out << "tool contact over " << n
      << " passes, each surface vertex evaluated once = every point of "
         "every face: the same forces to 1e-12: "
      << testing::yes(largest > 0. && largest_difference <= 1e-12 * largest)
      << std::endl
      << "the same tool forces and friction work to 1e-12, the same points "
         "in contact and slipping: "
      << testing::yes(largest_sum_difference <= 1e-12 && most_active > 0 &&
                      most_slipping > 0 && count_differences == 0)
      << std::endl;
  std::cerr << "largest force " << largest << " N, largest difference "
            << largest_difference << " N, sums " << largest_sum_difference
            << " relative; up to " << most_active << " points in contact, "
            << most_slipping << " slipping" << std::endl;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
