// The stress at the material points of a cell, as the assembly sees it, for
// the graphics and the particles' mean stresses.
#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <densify/assembly/all_values.h>
#include <densify/material/material.h>

#include <cmath>
#include <memory>
#include <vector>

namespace densify
{
  using namespace dealii;

  class NodalAveraging;

  /// Von Mises stress of the Cauchy stress @p sigma (MPa).
  inline double
  von_mises(const Tensor<2, 3> &sigma)
  {
    const Tensor<2, 3> s =
      sigma - trace(sigma) / 3. * unit_symmetric_tensor<3>();
    return std::sqrt(1.5 * scalar_product(s, s));
  }

  /// The state at one material point of a cell.
  struct MaterialPointValues
  {
    /// Cauchy stress (MPa).
    Tensor<2, 3> sigma;
    /// Von Mises stress of sigma (MPa).
    double von_mises = 0.;
    /// Equivalent plastic strain of the committed history (0 without one).
    double plastic_strain = 0.;
    /// Reference volume the point carries (mm^3).
    double JxW = 0.;
    /// The cell's own det F at the point (current over reference volume).
    double volume_ratio = 1.;
  };

  /**
   * Evaluates the material at the points of a cell from the displacement and
   * the committed history, as the assembly does: with the nodal-averaged
   * F-bar the history and Fbar live at a cell's four corners, which carry
   * V/4 each in the residual, so the points are those of the symmetric
   * four-point rule (point k nearest corner k, weight V/4) with corner k's
   * Fbar and history; otherwise the points of the Gauss rule of degree + 1
   * with their own history.
   */
  class MaterialPoints
  {
  public:
    /**
     * @param dof_handler The displacement (FESystem(FE_SimplexP(@p degree),
     *   3)).
     * @param mapping The mapping of the cells.
     * @param degree The polynomial degree of the displacement.
     * @param solution The displacement, ghosted (the locally owned cells'
     *   DoFs); it must outlive this object.
     * @param materials The material of each particle (index: material id).
     * @param history The committed history (index: active cell index *
     *   @p history_per_cell + point or corner), or nullptr without one.
     * @param history_per_cell Material states per cell in @p history.
     * @param nodal_averaging The nodal-averaged F-bar, or nullptr.
     */
    MaterialPoints(
      const DoFHandler<3>                                &dof_handler,
      const Mapping<3>                                   &mapping,
      const unsigned int                                  degree,
      const TrilinosWrappers::MPI::Vector                &solution,
      const std::vector<std::shared_ptr<const Material>> &materials,
      const std::vector<MaterialState>                   *history,
      const unsigned int                                  history_per_cell,
      const NodalAveraging                               *nodal_averaging);

    /// The rule whose points reinit() evaluates.
    const Quadrature<3> &
    quadrature() const
    {
      return rule;
    }

    /// The values at the points of the locally owned @p cell (valid until
    /// the next call).
    const std::vector<MaterialPointValues> &
    reinit(const typename DoFHandler<3>::active_cell_iterator &cell);

  private:
    const TrilinosWrappers::MPI::Vector                &solution;
    const std::vector<std::shared_ptr<const Material>> &materials;
    const std::vector<MaterialState>                   *history;
    const unsigned int                                  history_per_cell;
    const NodalAveraging                               *nodal_averaging;
    Quadrature<3>                                       rule;
    FEValues<3>                                         fe_values;
    /// The reference-cell corner of largest barycentric weight at each point.
    std::vector<unsigned int> nearest_corner;
    /// The nodal-averaged volume measure of each vertex and the values of
    /// all DoFs (with F-bar).
    std::vector<double>              j_bar;
    AllValues                        values_of_dofs;
    std::vector<Tensor<2, 3>>        grad_u;
    std::vector<MaterialPointValues> values;
  };
} // namespace densify
