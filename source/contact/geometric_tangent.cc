// The geometric part of the particle contact's tangent.
#include <densify/contact/geometric_tangent.h>

namespace densify
{
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
                        FullMatrix<double>              &pair_matrix)
  {
    const unsigned int n_dofs = component.size();
    const Tensor<1, 3> e1 = c[1] - c[0], e2 = c[2] - c[0];
    const Tensor<1, 3> normal_dir = cross_product_3d(e1, e2);
    const double       length     = normal_dir.norm();
    // n = sign c/|c|: dn = sign (I - n n) dc / |c|
    const double       sign = (normal_dir * n > 0) ? 1. : -1.;
    const Tensor<2, 3> P_n  = unit_symmetric_tensor<3>() - outer_product(n, n);
    const double       m11 = e1 * e1, m12 = e1 * e2, m22 = e2 * e2;
    const double       det = m11 * m22 - m12 * m12;
    std::vector<Tensor<1, 3>> dn(2 * n_dofs), dxi(2 * n_dofs);
    std::vector<double>       dg(2 * n_dofs);
    // a point held beside the facet: its gap adds |t|, t = (I - n n)(x_s -
    // y), which changes by t/|t| . (dx_s - dy) - ((x_s - y) . n) t/|t| . dn
    // with y at fixed b (held at an edge, y slides along it, normal to t,
    // which leaves |t| unchanged to first order)
    Tensor<1, 3> beside;
    double       normal_offset = 0.;
    // held at an edge (one barycentric coordinate at its bound, the
    // smallest), y slides along the edge from corner edge[0] to edge[1],
    // where (x_s - y) . (c_1 - c_0) = 0 gives its motion
    std::array<int, 2> edge = {{-1, -1}};
    if (!sliding)
      {
        normal_offset        = x_s_minus_y * n;
        const Tensor<1, 3> t = x_s_minus_y - normal_offset * n;
        if (t.norm() > 0.)
          beside = t / t.norm();
        const double lowest = std::min({bary[0], bary[1], bary[2]});
        unsigned int n_free = 0;
        for (unsigned int a = 0; a < 3; ++a)
          if (bary[a] > lowest + 1e-12)
            {
              if (n_free < 2)
                edge[n_free] = a;
              ++n_free;
            }
        if (n_free != 2)
          edge = {{-1, -1}};
      }
    const Tensor<1, 3> edge_dir =
      edge[0] >= 0 ? Tensor<1, 3>(c[edge[1]] - c[edge[0]]) : Tensor<1, 3>();
    for (unsigned int j = 0; j < 2 * n_dofs; ++j)
      {
        // the motion of the slave point relative to the flat facet's
        // point at fixed b: the slave's shape functions, minus b_a for the
        // corner DoFs (for P1 psi itself)
        const int    a = j < n_dofs ? -1 : corner[j - n_dofs];
        Tensor<1, 3> relative;
        if (j < n_dofs)
          relative = psi[j];
        else if (a >= 0)
          relative[component[j - n_dofs]] = -bary[a];
        double r1 = e1 * relative, r2 = e2 * relative;
        if (a >= 0)
          {
            Tensor<1, 3> e_d;
            e_d[component[j - n_dofs]] = 1.;
            const Tensor<1, 3> dc =
              a == 1 ? cross_product_3d(e_d, e2) :
              a == 2 ? cross_product_3d(e1, e_d) :
                       -cross_product_3d(e_d, e2) - cross_product_3d(e1, e_d);
            dn[j] = sign / length * (P_n * dc);
            // de1 = dc1 - dc0, de2 = dc2 - dc0
            const double n_e = x_s_minus_y * e_d;
            r1 += a == 1 ? n_e : (a == 0 ? -n_e : 0.);
            r2 += a == 2 ? n_e : (a == 0 ? -n_e : 0.);
          }
        if (sliding)
          {
            const double db1 = (m22 * r1 - m12 * r2) / det,
                         db2 = (m11 * r2 - m12 * r1) / det;
            dxi[j]           = db1 * (ref_corner[1] - ref_corner[0]) +
                     db2 * (ref_corner[2] - ref_corner[0]);
          }
        else if (edge[0] >= 0)
          {
            // (dx_s - dy) . e + (x_s - y) . de = 0 with de = dc_1 - dc_0
            double turn = 0.;
            if (a >= 0)
              turn = x_s_minus_y[component[j - n_dofs]] *
                     ((a == edge[1] ? 1. : 0.) - (a == edge[0] ? 1. : 0.));
            const double ds =
              (edge_dir * relative + turn) / (edge_dir * edge_dir);
            dxi[j] = ds * (ref_corner[edge[1]] - ref_corner[edge[0]]);
          }
        dg[j] = x_s_minus_x_m * dn[j] - n * (dx_m_dxi * dxi[j]) +
                beside * relative - normal_offset * (beside * dn[j]);
      }
    // the friction traction's change dt[j] by the same motion
    std::vector<Tensor<1, 3>> dt(friction != nullptr ? 2 * n_dofs : 0);
    if (friction != nullptr)
      for (unsigned int j = 0; j < 2 * n_dofs; ++j)
        dt[j] = friction_traction_change(
          *friction, n, dn[j], -(grad_delta_m * dxi[j]), -eps * dg[j]);
    for (unsigned int i = 0; i < 2 * n_dofs; ++i)
      for (unsigned int j = 0; j < 2 * n_dofs; ++j)
        {
          // dp = -eps dg
          double value = p * (psi[i] * dn[j]) - eps * (n * psi[i]) * dg[j];
          if (friction != nullptr)
            value += psi[i] * dt[j];
          // psi_i = -N_i(xi) e_k on the master: d psi_i = -(grad N_i . dxi)
          if (i >= n_dofs)
            value -=
              T[component[i - n_dofs]] * (master_grad[i - n_dofs] * dxi[j]);
          pair_matrix(i, j) -= factor * value;
        }
  }
} // namespace densify
