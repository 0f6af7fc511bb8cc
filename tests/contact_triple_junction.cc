// Particle contact where three particles meet. Sphere A (d = 2.5, P1,
// h = 0.3) is pressed 0.15 mm into sphere B below it; a third sphere C is
// placed either far away or beside the two, deep in B and 0.04 mm clear of
// A (as at a triple junction of a dense compact, where every pair
// overlaps). Near C, some points of A lie inside B and yet closer to C's
// surface, outside which they lie (about 70 of the 500 points of A inside
// B, by the exact spheres). No point lies inside both A and C, so the
// contact force on A is the same with C far and near: each point of A
// inside B presses on B whatever else is close. A point that took the
// closest facet of any particle would take C's, find itself outside it and
// press on nothing: its penetration of B went unseen, and grew unresisted
// (the iron paper scene by explicit dynamics: a point of one particle found
// 0.07 mm inside its neighbour at 1.18 mm of stroke, when the neighbour's
// facet became the closer one, and the punch force rang by 20 %).
#include <deal.II/base/mpi.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/contact/particle_contact.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <iomanip>
#include <iostream>

namespace
{
  using namespace densify;

  /// The displacement that moves particle p by @p shift[p] (fully ghosted).
  TrilinosWrappers::MPI::Vector
  shifted(const DoFHandler<3>             &dof_handler,
          const std::vector<Tensor<1, 3>> &shift)
  {
    TrilinosWrappers::MPI::Vector owned(dof_handler.locally_owned_dofs(),
                                        MPI_COMM_WORLD);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            owned(cell->vertex_dof_index(v, d)) = shift[cell->material_id()][d];
    owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector all(dof_handler.locally_owned_dofs(),
                                      complete_index_set(dof_handler.n_dofs()),
                                      MPI_COMM_WORLD);
    all = owned;
    return all;
  }

  /// The net contact force on particle @p p: minus its residual.
  Tensor<1, 3>
  net_force(const DoFHandler<3>                 &dof_handler,
            const TrilinosWrappers::MPI::Vector &residual,
            const unsigned int                   p)
  {
    std::vector<bool> counted(dof_handler.n_dofs(), false);
    Tensor<1, 3>      force;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == p)
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            {
              const types::global_dof_index i = cell->vertex_dof_index(v, d);
              if (!counted[i] &&
                  residual.locally_owned_elements().is_element(i))
                {
                  counted[i] = true;
                  force[d] -= residual(i);
                }
            }
    for (unsigned int d = 0; d < 3; ++d)
      force[d] = Utilities::MPI::sum(force[d], MPI_COMM_WORLD);
    return force;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Parameters                       parameters;
  ParameterHandler                 prm;
  // B, A above it, C far to the side (reference configuration)
  std::vector<std::string> scene = testing::two_stacked_spheres(1);
  scene.push_back("Particles/Centres=0,0,1.25; 0,0,3.75; 5,0,1.25");
  testing::read_scene(parameters, prm, "hertz.prm", scene);
  Simulator simulator(parameters, MPI_COMM_WORLD, false);
  simulator.setup();
  const DoFHandler<3> &dof_handler = simulator.get_dof_handler();
  const MappingFE<3>   mapping(FE_SimplexP<3>(1));

  // frictionless, contact at the facet corners as for P1 in densify
  ParticleContact contact;
  contact.setup(dof_handler,
                {1e5, 1e5, 1e5},
                FrictionLaw(),
                testing::facet_corners());

  const Tensor<1, 3> press({0., 0., -0.15});
  Tensor<1, 3>       force[2];
  for (const bool near : {false, true})
    {
      // C beside the pair: its centre at (0.7, 0, -0.1) from B's
      const Tensor<1, 3> c_shift =
        near ? Tensor<1, 3>({-4.3, 0., -0.1}) : Tensor<1, 3>();
      const TrilinosWrappers::MPI::Vector u =
        shifted(dof_handler, {Tensor<1, 3>(), press, c_shift});
      contact.update_search(u, 0.2);
      contact.reset_projections();
      TrilinosWrappers::MPI::Vector residual(dof_handler.locally_owned_dofs(),
                                             MPI_COMM_WORLD);
      contact.assemble(mapping, u, residual, nullptr);
      residual.compress(VectorOperation::add);
      force[near] = net_force(dof_handler, residual, 1);
    }
  const double difference = (force[1] - force[0]).norm() / force[0].norm();
  std::ostringstream out;
  out << "contact force on A, C far: " << std::setprecision(6) << force[0][2]
      << " N along z; upward, B pushes A out: "
      << testing::yes(force[0][2] > 1.) << std::endl
      << "C beside A and B: the force on A is unchanged (relative difference "
      << "below 1e-9): " << testing::yes(difference < 1e-9) << std::endl;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << out.str();
  std::cerr << "relative difference " << difference << ", force C near "
            << force[1] << ", C far " << force[0] << std::endl;
  return testing::all_passed ? 0 : 1;
}
