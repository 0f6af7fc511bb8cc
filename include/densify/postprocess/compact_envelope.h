// The compact's current envelope: how high and how wide the deformed
// particles are, for springback and the envelope density; and the particles'
// current surface area.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

namespace densify
{
  using namespace dealii;

  /**
   * The bounding cylinder about the die axis (the z axis) of all particles'
   * deformed vertices (mm).
   */
  struct CompactEnvelope
  {
    /// Lowest and highest z of a deformed vertex.
    double bottom = 0., top = 0.;
    /// Largest distance of a deformed vertex from the z axis.
    double radius = 0.;
  };

  /**
   * The envelope at the displacement @p solution (ghosted: the values of the
   * locally owned cells' DoFs), over the vertices of the locally owned cells
   * of @p dof_handler (the vector element's vertex DoFs); the same result on
   * every rank. A quadratic element's sides may bulge beyond their vertices
   * by a fraction of the element's curvature; that is not counted.
   */
  CompactEnvelope
  compact_envelope(const DoFHandler<3>                 &dof_handler,
                   const TrilinosWrappers::MPI::Vector &solution);

  /**
   * The particles' total current surface area (mm^2): every boundary face of
   * the locally owned cells of @p dof_handler as the flat triangle through
   * its deformed vertices (the vector element's vertex DoFs of the ghosted
   * @p solution), summed over the ranks; the same result on every rank.
   */
  double
  particle_surface_area(const DoFHandler<3>                 &dof_handler,
                        const TrilinosWrappers::MPI::Vector &solution);
} // namespace densify
