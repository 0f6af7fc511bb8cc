// The element's health: the smallest volume ratio V/V0 of any cell.
#pragma once

#include <deal.II/base/point.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

namespace densify
{
  using namespace dealii;

  /// The cell with the smallest own volume ratio, on every rank.
  struct SmallestCellVolume
  {
    /// V / V0 of the cell (its own det F, averaged over the cell).
    double ratio = 1.;
    /// The particle (material id) the cell belongs to.
    unsigned int particle = 0;
    /// The cell's centre in the reference configuration (mm).
    Point<3> centre;
  };

  /**
   * The smallest ratio of deformed to initial volume of any cell at the
   * displacement @p solution (ghosted: the values of the locally owned
   * cells' DoFs): per cell the integral of det(I + grad u) over the
   * integral of 1, which is the cell's det F for linear tetrahedra. The
   * nodal-averaged F-bar hands the material each vertex patch's volume
   * change, so this is the measure of a cell's own volume, which that
   * element can let collapse (doc/theory.md, "Volumetric locking"). The
   * same result on every rank.
   */
  SmallestCellVolume
  smallest_cell_volume(const DoFHandler<3>                 &dof_handler,
                       const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution);
} // namespace densify
