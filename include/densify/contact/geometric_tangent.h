// The geometric part of the particle contact's tangent: the rotation of the
// master facet's normal and the sliding of the projection point.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <densify/contact/contact_law.h>

#include <array>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * Add to @p pair_matrix (slave DoFs, then master DoFs) the tangent terms
   * of the traction @p T = p n + t that come from the motion of the master
   * facet with corners @p c (current positions): the rotation of the
   * normal @p n, which turns the pressure @p p, and, if @p sliding, the
   * motion of the projection point (barycentric @p bary on the flat facet,
   * @p x_s_minus_y from there to the slave point), which moves @p T to
   * other master shape functions. For the flat facet y = c0 + b1 e1 + b2 e2
   * the projection condition (x_s - y) . e_a = 0 gives
   * M db = e_a . (dx_s - b_k dc_k) + (x_s - y) . de_a with the metric
   * M = e_a . e_b.
   * @p psi: slave shape functions and minus the master ones at the
   * projection; @p corner[i]: which facet corner the master DoF i moves
   * (-1: none); @p master_grad[i]: gradient of the master shape function i
   * in reference coordinates; @p ref_corner: the corners in reference
   * coordinates of the master cell. For P2 the master point
   * x_m (given by the master cell's shape functions) lies off the flat facet
   * through the corners: the gap g = (x_s - x_m) . n then also changes by
   * @p x_s_minus_x_m . dn - n . (@p dx_m_dxi dxi), which the pressure
   * p = lambda - @p eps g follows (both vanish for P1).
   * Unless @p sliding, the projection is held at the facet's edge or corner:
   * the gap then adds the distance |t| beside the facet, t = (I - n n)
   * (x_s - y), whose change t/|t| . (dx_s - dy) - ((x_s - y) . n) t/|t| . dn
   * is added, and y held at an edge (one barycentric coordinate, the
   * smallest, at its bound) slides along it as (x_s - y) . (c_1 - c_0) = 0
   * requires.
   * With friction (@p friction not null), the tangential traction t
   * follows the same motion: the tangent plane P = I - n n turns with n,
   * and the slip increment delta = du_s - du_m(xi) changes with the
   * projection point by -(@p grad_delta_m) dxi, with @p grad_delta_m the
   * gradient of the master's displacement increment by the master cell's
   * reference coordinates (FrictionTerms, friction_traction_change()).
   */
  void
  add_geometric_tangent(const std::array<Point<3>, 3>   &c,
                        const Tensor<1, 3>              &n,
                        const Tensor<1, 3>              &x_s_minus_y,
                        const std::array<double, 3>     &bary,
                        const double                     p,
                        const Tensor<1, 3>              &T,
                        const bool                       sliding,
                        const std::vector<Tensor<1, 3>> &psi,
                        const std::vector<int>          &corner,
                        const std::vector<unsigned int> &component,
                        const std::vector<Tensor<1, 3>> &master_grad,
                        const std::array<Point<3>, 3>   &ref_corner,
                        const double                     eps,
                        const Tensor<1, 3>              &x_s_minus_x_m,
                        const Tensor<2, 3>              &dx_m_dxi,
                        const double                     factor,
                        const FrictionTerms             *friction,
                        const Tensor<2, 3>              &grad_delta_m,
                        FullMatrix<double>              &pair_matrix);
} // namespace densify
