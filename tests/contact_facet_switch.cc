// Particle contact while one surface slides over the other's facets. Two
// spheres (P1, h = 0.3) stacked on the z axis overlap by 0.15 mm, and the
// upper one slides sideways by 0.08 mm, sampled at N = 400 and 2N points.
// - The master facets assigned once (ParticleContact::update_projections,
//   kept between two calls as within one Newton iteration): the contact
//   residual is continuous in the displacement, so its largest change
//   between samples halves when the spacing halves.
// - Every point projected onto its closest facet at every evaluation (the
//   behaviour before the hysteresis): where a point crosses a master facet
//   edge the facet normal, and with it the residual, jumps; the largest
//   change does not shrink with the spacing. This made Newton stall with
//   thousands of sliding points (the light paper scene at 1.25 mm).
// - A small further slide (0.002 mm) keeps every assignment.
// - A slide far beyond the assigned facets (1.5 mm; the spheres are then
//   0.29 mm apart) with the facets kept: a point beside its facet, below
//   the facet's plane, is not in contact. The residual falls continuously to
//   exactly zero (its largest change halves with the spacing). Before the
//   gap counted the distance beside the facet, such points kept pressing on
//   the facet's plane: at high density, between particles flattened against
//   the same punch, this made Newton cycle (the 43-sphere layer on the
//   0.5 mm mesh at step 243).
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

  /// The displacement that moves particle 1 by @p shift (fully ghosted).
  TrilinosWrappers::MPI::Vector
  shifted(const DoFHandler<3> &dof_handler, const Tensor<1, 3> &shift)
  {
    TrilinosWrappers::MPI::Vector owned(dof_handler.locally_owned_dofs(),
                                        MPI_COMM_WORLD);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == 1)
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            owned(cell->vertex_dof_index(v, d)) = shift[d];
    owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector all(dof_handler.locally_owned_dofs(),
                                      complete_index_set(dof_handler.n_dofs()),
                                      MPI_COMM_WORLD);
    all = owned;
    return all;
  }

  /// Largest change of the contact residual between consecutive samples of
  /// the slide, and the largest residual, with @p n samples.
  std::pair<double, double>
  slide(ParticleContact     &contact,
        const DoFHandler<3> &dof_handler,
        const Mapping<3>    &mapping,
        const unsigned int   n,
        const bool           closest_every_time,
        const double         distance = 0.08)
  {
    const double                  overlap = 0.15;
    TrilinosWrappers::MPI::Vector residual(dof_handler.locally_owned_dofs(),
                                           MPI_COMM_WORLD),
      previous(residual), change(residual);
    contact.reset_projections();
    contact.update_projections(mapping,
                               shifted(dof_handler,
                                       Tensor<1, 3>({0., 0., -overlap})));
    double largest_change = 0, largest = 0;
    for (unsigned int k = 0; k <= n; ++k)
      {
        const TrilinosWrappers::MPI::Vector u =
          shifted(dof_handler, Tensor<1, 3>({distance * k / n, 0., -overlap}));
        if (closest_every_time)
          contact.reset_projections();
        residual = 0;
        contact.assemble(mapping, u, residual, nullptr);
        residual.compress(VectorOperation::add);
        largest = std::max(largest, residual.l2_norm());
        if (k > 0)
          {
            change = residual;
            change -= previous;
            largest_change = std::max(largest_change, change.l2_norm());
          }
        previous = residual;
      }
    return {largest_change, largest};
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

  // frictionless, contact at the facet corners as for P1 in densify
  ParticleContact contact;
  contact.setup(dof_handler,
                {1e5, 1e5},
                FrictionLaw(),
                testing::facet_corners());
  contact.update_search(shifted(dof_handler, Tensor<1, 3>({0.04, 0, -0.15})),
                        0.2);

  std::ostringstream out;
  for (const bool closest : {false, true})
    {
      const auto [coarse, largest] =
        slide(contact, dof_handler, mapping, 400, closest);
      const auto   fine  = slide(contact, dof_handler, mapping, 800, closest);
      const double ratio = coarse / fine.first;
      out << (closest ? "closest facet at every evaluation" :
                        "facets kept (hysteresis)")
          << ": largest residual " << std::setprecision(3) << largest
          << " N, largest change between samples " << coarse << " N (N = 400), "
          << fine.first << " N (2N), ratio " << std::setprecision(2) << ratio
          << (closest ? ", a jump (ratio < 1.3): " :
                        ", continuous (ratio > 1.8): ")
          << testing::yes(closest ? ratio < 1.3 : ratio > 1.8) << std::endl;
    }

  // a slide far beyond the assigned facets, which stay kept: the residual
  // is continuous and ends at zero, the spheres being apart
  {
    const double far = 1.5;
    const auto [coarse, largest] =
      slide(contact, dof_handler, mapping, 400, false, far);
    const auto   fine  = slide(contact, dof_handler, mapping, 800, false, far);
    const double ratio = coarse / fine.first;
    TrilinosWrappers::MPI::Vector residual(dof_handler.locally_owned_dofs(),
                                           MPI_COMM_WORLD);
    contact.assemble(mapping,
                     shifted(dof_handler, Tensor<1, 3>({far, 0., -0.15})),
                     residual,
                     nullptr);
    residual.compress(VectorOperation::add);
    out << "facets kept over a slide of " << far
        << " mm: largest change between samples " << std::setprecision(3)
        << coarse << " N (N = 400), " << fine.first << " N (2N), ratio "
        << std::setprecision(2) << ratio
        << ", continuous (ratio > 1.8): " << testing::yes(ratio > 1.8)
        << "; residual at the end (spheres 0.29 mm apart) "
        << residual.l2_norm()
        << " N, zero: " << testing::yes(residual.l2_norm() == 0.) << std::endl;
  }

  // a small further slide changes no assignment
  contact.reset_projections();
  contact.update_projections(mapping,
                             shifted(dof_handler,
                                     Tensor<1, 3>({0.04, 0., -0.15})));
  const bool changed =
    0 < contact.update_projections(mapping,
                                   shifted(dof_handler,
                                           Tensor<1, 3>({0.042, 0., -0.15})));
  out << "a further slide of 0.002 mm keeps every master facet: "
      << testing::yes(!changed) << std::endl;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
