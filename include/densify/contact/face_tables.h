// The slave faces' quadrature data in the reference configuration, made once:
// points, weights and shape-value tables per reference face.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/assembly/all_values.h>

#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * What FEFaceValues (values, quadrature points, JxW) gives on a fixed list
   * of boundary faces, made once by FEFaceValues itself: the points and JxW
   * of each face (the mapping is that of the undeformed mesh, so they do
   * not change), its DoF indices, and the shape values of its reference
   * face (one table per distinct set of values, i.e. per reference face and
   * orientation). values() sums the displacement at the points in the order
   * of FEValuesViews::Vector::get_function_values(), so the results are
   * bit-identical to FEFaceValues' while a face costs no reinit().
   * Primitive vector elements only (each shape function one component).
   */
  class FaceTables
  {
  public:
    /// Made for @p faces (cell, face number) with @p mapping, @p fe and the
    /// face quadrature @p quadrature.
    void
    reinit(const Mapping<3>                           &mapping,
           const FiniteElement<3>                     &fe,
           const Quadrature<2>                        &quadrature,
           const std::vector<std::pair<DoFHandler<3>::active_cell_iterator,
                                       unsigned int>> &faces);

    /// Made already?
    bool
    ready() const
    {
      return made;
    }

    /// Quadrature point @p q of face @p k in the reference configuration.
    const Point<3> &
    point(const unsigned int k, const unsigned int q) const
    {
      return points[k * n_q + q];
    }

    /// JxW at quadrature point @p q of face @p k.
    double
    JxW(const unsigned int k, const unsigned int q) const
    {
      return weights[k * n_q + q];
    }

    /// The DoF indices of face @p k's cell.
    const types::global_dof_index *
    dofs(const unsigned int k) const
    {
      return &dof_indices[k * n_dofs];
    }

    /// The nonzero component of shape function @p i.
    unsigned int
    component(const unsigned int i) const
    {
      return components[i];
    }

    /// The nonzero component of shape function @p i at point @p q of face
    /// @p k.
    double
    shape(const unsigned int k,
          const unsigned int i,
          const unsigned int q) const
    {
      return tables[table_of[k]][i * n_q + q];
    }

    /**
     * The vector field with DoF values @p values (indexed by global DoF
     * index) at the points of face @p k, into @p u (n_q entries), summed as
     * FEFaceValues' get_function_values() does.
     */
    void
    values(const unsigned int         k,
           const AllValues           &values,
           std::vector<Tensor<1, 3>> &u) const;

  private:
    bool                                 made   = false;
    unsigned int                         n_q    = 0;
    unsigned int                         n_dofs = 0;
    std::vector<unsigned int>            components;
    std::vector<Point<3>>                points;
    std::vector<double>                  weights;
    std::vector<types::global_dof_index> dof_indices;
    /// Per face: its shape-value table; per table: values [i * n_q + q].
    std::vector<unsigned int>        table_of;
    std::vector<std::vector<double>> tables;
  };
} // namespace densify
