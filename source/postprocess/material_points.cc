// The stress at the material points of a cell, as the assembly sees it.
#include <deal.II/base/quadrature_lib.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/material/j2_plasticity.h>
#include <densify/postprocess/material_points.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace densify
{
  namespace
  {
    /// The symmetric four-point rule of a tetrahedron (exact for quadratics):
    /// point k lies nearest corner k and carries a quarter of the volume, as
    /// the corners of the nodal-averaged F-bar do in the residual. (deal.II
    /// 9.4's QGaussSimplex<3>(2) has six points of unequal weight; their
    /// nearest corners carried 0.90 to 1.07 times V/4, which biased the
    /// projected fields: the pressure integral of tests/cli/plastic_field.sh
    /// by -4.7 %.)
    Quadrature<3>
    corner_quadrature()
    {
      const double a = (5. + 3. * std::sqrt(5.)) / 20.;
      const double b = (5. - std::sqrt(5.)) / 20.;
      return Quadrature<3>(std::vector<Point<3>>{Point<3>(b, b, b),
                                                 Point<3>(a, b, b),
                                                 Point<3>(b, a, b),
                                                 Point<3>(b, b, a)},
                           std::vector<double>(4, 1. / 24.));
    }
  } // namespace



  MaterialPoints::MaterialPoints(
    const DoFHandler<3>                                &dof_handler,
    const Mapping<3>                                   &mapping,
    const unsigned int                                  degree,
    const TrilinosWrappers::MPI::Vector                &solution,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *history,
    const unsigned int                                  history_per_cell,
    const NodalAveraging                               *nodal_averaging)
    : solution(solution)
    , materials(materials)
    , history(history)
    , history_per_cell(history_per_cell)
    , nodal_averaging(nodal_averaging)
    , rule(nodal_averaging ? corner_quadrature() :
                             Quadrature<3>(QGaussSimplex<3>(degree + 1)))
    , fe_values(mapping,
                dof_handler.get_fe(),
                rule,
                update_gradients | update_JxW_values)
    , nearest_corner(rule.size())
    , grad_u(rule.size())
    , values(rule.size())
  {
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        const Point<3>             &x = rule.point(q);
        const std::array<double, 4> weight{
          {1. - x[0] - x[1] - x[2], x[0], x[1], x[2]}};
        nearest_corner[q] =
          std::max_element(weight.begin(), weight.end()) - weight.begin();
      }
    if (nodal_averaging)
      {
        values_of_dofs.gather(solution);
        j_bar =
          nodal_averaging->vertex_volume_measures(values_of_dofs, materials);
      }
  }



  const std::vector<MaterialPointValues> &
  MaterialPoints::reinit(
    const typename DoFHandler<3>::active_cell_iterator &cell)
  {
    if (nodal_averaging)
      {
        // P1: F is constant in the cell and each corner point carries V/4;
        // from the F-bar's own cell data, without a mapping
        const unsigned int e = cell->active_cell_index();
        const Tensor<2, 3> F =
          nodal_averaging->deformation_gradient(e, values_of_dofs);
        const double JxW = nodal_averaging->reference_volume(e) / 4.;
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            grad_u[q]     = F - unit_symmetric_tensor<3>();
            values[q].JxW = JxW;
          }
      }
    else
      {
        const FEValuesExtractors::Vector u(0);
        fe_values.reinit(cell);
        fe_values[u].get_function_gradients(solution, grad_u);
        for (unsigned int q = 0; q < rule.size(); ++q)
          values[q].JxW = fe_values.JxW(q);
      }
    const Material &material = *materials[cell->material_id()];
    const bool      finite   = material.finite_strain();
    Tensor<2, 3>    P;
    // a law whose corners share the Kirchhoff deviator (J2): one return
    // mapping for the cell's F, whose isochoric part every corner's Fbar
    // shares, and each corner's pressure from its own volume ratio, as the
    // explicit force kernel evaluates them; the corners' committed states
    // are one state (up to round-off in implicit runs), that of corner 0
    double                p_a = 0.;
    SymmetricTensor<2, 3> tau_dev;
    bool                  shared =
      nodal_averaging && finite && material.kirchhoff_pressure(0., p_a);
    if (shared)
      shared = material.kirchhoff_deviator(
        unit_symmetric_tensor<3>() + grad_u[0],
        history != nullptr ?
          &(*history)[cell->active_cell_index() * history_per_cell] :
          nullptr,
        nullptr,
        tau_dev);
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        MaterialPointValues &v = values[q];
        Tensor<2, 3>         F = unit_symmetric_tensor<3>() + grad_u[q];
        v.volume_ratio = finite ? determinant(F) : 1. + trace(grad_u[q]);
        // with the nodal-averaged F-bar the material sees the corner's Fbar
        // (F alone would give the cell's own, locking volume change to the
        // pressure)
        double j_a = 1.;
        if (nodal_averaging)
          {
            j_a = blended_volume_measure(
              j_bar[cell->vertex_index(nearest_corner[q])],
              finite ? determinant(F) : trace(F) - 2.,
              nodal_averaging->cell_volume_weight(cell->material_id()),
              finite);
            F = fbar_deformation(F, j_a, finite);
          }
        const unsigned int k = cell->active_cell_index() * history_per_cell +
                               (nodal_averaging ? nearest_corner[q] : q);
        if (shared)
          {
            material.kirchhoff_pressure(std::log(j_a), p_a);
            v.sigma =
              (Tensor<2, 3>(tau_dev) + p_a * unit_symmetric_tensor<3>()) / j_a;
            v.von_mises = von_mises(v.sigma);
            v.plastic_strain =
              history != nullptr ?
                material.equivalent_plastic_strain((*history)[k]) :
                0.;
            continue;
          }
        MaterialState scratch;
        material.stress(F,
                        history != nullptr ? &(*history)[k] : nullptr,
                        history != nullptr ? &scratch : nullptr,
                        P);
        v.sigma          = P * transpose(F) / determinant(F);
        v.von_mises      = von_mises(v.sigma);
        v.plastic_strain = history != nullptr ?
                             material.equivalent_plastic_strain((*history)[k]) :
                             0.;
      }
    return values;
  }
} // namespace densify
