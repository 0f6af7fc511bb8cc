// The explicit pass of particle contact with its near lists (Verlet lists,
// ParticleContact::NearLists) against the search over all candidate facets.
// Two spheres (P1, h = 0.3) stacked on the z axis overlap by 0.04 mm, and
// the upper one slides by 0.12 mm in x and 0.03 mm in y in 600 passes, so
// that slave points cross master facet edges between two builds of the
// lists; the candidates come from one search with a 0.05 mm margin, more
// than the overlap (as in a run, where the margin is a quarter of the
// smallest element and penetrations are microns), so the closest facet of
// each slave point is among its face's candidates, and the
// lists are rebuilt every 0.011 mm of motion. Each pass is made three times
// on plain arrays, the explicit method's path: with the near lists and each
// surface vertex evaluated once for its slave points on all its facets (the
// default), with the near lists and every slave point on its own
// (ParticleContact::set_vertex_evaluation), and without the lists
// (ParticleContact::set_near_lists), which searches every candidate at
// every evaluation. Checked: the lists give the same forces as the search
// over all candidates to the last bit at every pass (they find the same
// facets; a point whose closest point lies on an edge shared by two facets
// is where a different order of operations would pick the other); the
// evaluation per vertex gives them to round-off (1e-12 of the largest
// force: the copies' tractions are added in another order), the same
// contact area, points in contact and normal force; and the lists were
// built far fewer times than there were passes.
#include <deal.II/base/mpi.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/assembly/all_values.h>
#include <densify/contact/particle_contact.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <iomanip>
#include <iostream>

using namespace densify;

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

  // frictionless, contact at the facet corners as for P1 in densify
  ParticleContact by_vertex, with_lists, every_candidate;
  with_lists.set_vertex_evaluation(false);
  every_candidate.set_near_lists(false);
  const double overlap = 0.04;
  for (ParticleContact *contact : {&by_vertex, &with_lists, &every_candidate})
    {
      contact->setup(dof_handler,
                     {1e5, 1e5},
                     FrictionLaw(),
                     testing::facet_corners());
      contact->update_search(testing::smooth_displacement(dof_handler,
                                                          Tensor<1, 3>(
                                                            {0., 0., -overlap}),
                                                          1),
                             0.05);
    }

  const unsigned int n = 600;
  double largest = 0., largest_difference = 0., largest_vertex_difference = 0.,
         largest_measure_difference = 0.;
  unsigned int active = 0, active_differences = 0;
  for (unsigned int k = 0; k <= n; ++k)
    {
      const TrilinosWrappers::MPI::Vector u = testing::smooth_displacement(
        dof_handler, Tensor<1, 3>({0.12 * k / n, 0.03 * k / n, -overlap}), 1);
      AllValues values;
      values.gather(u);
      const auto forces = [&](ParticleContact &contact) {
        TrilinosWrappers::MPI::Vector f(dof_handler.locally_owned_dofs(),
                                        MPI_COMM_WORLD);
        LocalForces                   local;
        local.start(f);
        ContactOutputs plain;
        plain.values           = &values;
        plain.committed_values = &values;
        plain.plain_residual   = &local;
        const ParticleContactResult result =
          contact.assemble_and_commit(mapping, u, f, 0., &plain);
        local.finish(f);
        f.compress(VectorOperation::add);
        return std::make_pair(f, result);
      };
      TrilinosWrappers::MPI::Vector difference = forces(with_lists).first;
      auto [vertex_difference, a]              = forces(by_vertex);
      const auto [reference, b]                = forces(every_candidate);
      largest = std::max(largest, reference.l2_norm());
      difference -= reference;
      largest_difference = std::max(largest_difference, difference.l2_norm());
      vertex_difference -= reference;
      largest_vertex_difference =
        std::max(largest_vertex_difference, vertex_difference.l2_norm());
      largest_measure_difference =
        std::max({largest_measure_difference,
                  std::abs(a.normal_force - b.normal_force) /
                    std::max(b.normal_force, 1e-300),
                  std::abs(a.contact_area - b.contact_area) /
                    std::max(b.contact_area, 1e-300)});
      active = std::max(active, b.n_active);
      active_differences += (a.n_active != b.n_active);
    }
  const unsigned int builds = with_lists.near_list_builds();
  std::ostringstream out;
  out << "contact forces over " << n + 1
      << " passes: with the near lists = searching every candidate, to the "
         "last bit: "
      << testing::yes(largest > 0. && largest_difference == 0.) << std::endl
      << "each surface vertex evaluated once: the same forces to 1e-12, "
         "the same normal force, contact area and points in contact: "
      << testing::yes(largest_vertex_difference <= 1e-12 * largest &&
                      largest_measure_difference <= 1e-12 && active > 0 &&
                      active_differences == 0)
      << std::endl
      << "near lists built fewer than " << (n + 1) / 20
      << " times and more than once: "
      << testing::yes(builds > 1 && builds < (n + 1) / 20) << std::endl;
  std::cerr << "largest force " << largest << " N, largest difference "
            << largest_difference << " N (by vertex "
            << largest_vertex_difference << " N, measures "
            << largest_measure_difference << " relative), points in contact "
            << active << ", lists built " << builds << " times" << std::endl;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
