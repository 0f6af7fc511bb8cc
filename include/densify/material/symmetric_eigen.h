// Closed-form eigen decomposition of a symmetric 3x3 matrix.
#pragma once

#include <algorithm>
#include <cmath>

namespace densify
{
  /**
   * Eigenvalues and orthonormal eigenvectors of the symmetric 3x3 matrix
   * @p a in closed form, without iterations (doc/theory.md, "The J2
   * return"):
   * 1. the deviator d = a - tr(a)/3 I scaled by p = sqrt(tr(d^2)/6); its
   *    eigenvalues are 2 p cos(phi + 2 pi k / 3) with 3 phi = acos(det(d /
   *    p) / 2) (trigonometric solution of the characteristic cubic);
   * 2. the eigenvector of the eigenvalue farthest from the other two (its
   *    gap is at least 1.5 p, so the vector is well conditioned) as the
   *    longest cross product of two rows of d - mu I;
   * 3. the other two in the plane normal to it by one Jacobi rotation of
   *    d projected on that plane, which stays orthonormal and accurate
   *    also for equal or nearly equal eigenvalues.
   * Off-diagonal entries below 1e-20 of the largest diagonal magnitude are
   * taken as zero (they move an eigenvalue by less than 1e-40 of it): the
   * identity and gradients down to the smallest doubles take that path.
   *
   * @param a the entries a[i][j], symmetric (only the upper triangle is read).
   * @param values the eigenvalues, in descending order.
   * @param vectors vectors[i][k] is component i of the eigenvector of
   *   values[k].
   */
  inline void
  symmetric_eigen(const double a[3][3], double values[3], double vectors[3][3])
  {
    const double scale =
      std::max({std::abs(a[0][0]), std::abs(a[1][1]), std::abs(a[2][2])});
    const double off2 =
      a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    unsigned int order[3] = {0, 1, 2};
    double       lambda[3];
    double       n[3][3]; // n[k] is the k-th eigenvector

    const auto diagonal = [&]() {
      for (unsigned int k = 0; k < 3; ++k)
        {
          lambda[k] = a[k][k];
          for (unsigned int i = 0; i < 3; ++i)
            n[k][i] = (i == k);
        }
    };
    const double q       = (a[0][0] + a[1][1] + a[2][2]) / 3.;
    const double d[3][3] = {{a[0][0] - q, a[0][1], a[0][2]},
                            {a[0][1], a[1][1] - q, a[1][2]},
                            {a[0][2], a[1][2], a[2][2] - q}};
    const double p       = std::sqrt(
      (d[0][0] * d[0][0] + d[1][1] * d[1][1] + d[2][2] * d[2][2] + 2. * off2) /
      6.);
    if ((std::abs(a[0][1]) <= 1e-20 * scale &&
         std::abs(a[0][2]) <= 1e-20 * scale &&
         std::abs(a[1][2]) <= 1e-20 * scale) ||
        !(p > 0.))
      diagonal();
    else
      {
        // det(d / p) / 2, within [-1, 1] up to round-off
        const double inv_p = 1. / p;
        double       b[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            b[i][j] = d[i][j] * inv_p;
        const double det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[1][2]) -
                           b[0][1] * (b[0][1] * b[2][2] - b[1][2] * b[0][2]) +
                           b[0][2] * (b[0][1] * b[1][2] - b[1][1] * b[0][2]);
        const double r   = std::clamp(det / 2., -1., 1.);
        const double phi = std::acos(r) / 3.;
        // the largest (k = 0) and smallest (k = 2) eigenvalue of d; the one
        // farther from the middle one is separated from both others
        const double mu_max = 2. * p * std::cos(phi);
        const double mu_min = 2. * p * std::cos(phi + 2.0943951023931957);
        const double mu_mid = -mu_max - mu_min;
        const double mu_s =
          (mu_max - mu_mid >= mu_mid - mu_min) ? mu_max : mu_min;

        // 2. its eigenvector: the longest cross product of rows of d - mu_s I
        const double m[3][3] = {{d[0][0] - mu_s, d[0][1], d[0][2]},
                                {d[0][1], d[1][1] - mu_s, d[1][2]},
                                {d[0][2], d[1][2], d[2][2] - mu_s}};
        double       best = -1., v[3] = {0., 0., 0.};
        for (unsigned int r0 = 0; r0 < 3; ++r0)
          {
            const unsigned int r1 = (r0 + 1) % 3;
            const double c[3]     = {m[r0][1] * m[r1][2] - m[r0][2] * m[r1][1],
                                     m[r0][2] * m[r1][0] - m[r0][0] * m[r1][2],
                                     m[r0][0] * m[r1][1] - m[r0][1] * m[r1][0]};
            const double c2       = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
            if (c2 > best)
              {
                best = c2;
                for (unsigned int i = 0; i < 3; ++i)
                  v[i] = c[i];
              }
          }
        const double inv_norm = 1. / std::sqrt(best);
        for (unsigned int i = 0; i < 3; ++i)
          n[0][i] = v[i] * inv_norm;

        // 3. an orthonormal basis (u, w) of the plane normal to n[0]: u
        //    normal to n[0] and to the axis n[0] is least aligned with
        unsigned int axis = 0;
        for (unsigned int i = 1; i < 3; ++i)
          if (std::abs(n[0][i]) < std::abs(n[0][axis]))
            axis = i;
        double u[3] = {0., 0., 0.};
        {
          const unsigned int i1 = (axis + 1) % 3, i2 = (axis + 2) % 3;
          // u = e_axis x n[0], normalised
          u[i1]                 = -n[0][i2];
          u[i2]                 = n[0][i1];
          const double inv_norm = 1. / std::sqrt(u[i1] * u[i1] + u[i2] * u[i2]);
          u[i1] *= inv_norm;
          u[i2] *= inv_norm;
        }
        const double w[3] = {n[0][1] * u[2] - n[0][2] * u[1],
                             n[0][2] * u[0] - n[0][0] * u[2],
                             n[0][0] * u[1] - n[0][1] * u[0]};
        double       du[3], dw[3], dn[3];
        for (unsigned int i = 0; i < 3; ++i)
          {
            du[i] = d[i][0] * u[0] + d[i][1] * u[1] + d[i][2] * u[2];
            dw[i] = d[i][0] * w[0] + d[i][1] * w[1] + d[i][2] * w[2];
            dn[i] = d[i][0] * n[0][0] + d[i][1] * n[0][1] + d[i][2] * n[0][2];
          }
        const double m_uu = u[0] * du[0] + u[1] * du[1] + u[2] * du[2];
        const double m_ww = w[0] * dw[0] + w[1] * dw[1] + w[2] * dw[2];
        const double m_uw = u[0] * dw[0] + u[1] * dw[1] + u[2] * dw[2];
        // Jacobi rotation of the 2x2 block (the smaller rotation angle)
        double c = 1., s = 0., t = 0.;
        if (m_uw != 0.)
          {
            const double theta = (m_ww - m_uu) / (2. * m_uw);
            t                  = (theta >= 0. ? 1. : -1.) /
                (std::abs(theta) + std::sqrt(1. + theta * theta));
            c = 1. / std::sqrt(1. + t * t);
            s = t * c;
          }
        for (unsigned int i = 0; i < 3; ++i)
          {
            n[1][i] = c * u[i] - s * w[i];
            n[2][i] = s * u[i] + c * w[i];
          }
        // the separated eigenvalue as a Rayleigh quotient, the pair as the
        // rotated diagonal
        lambda[0] = q + (n[0][0] * dn[0] + n[0][1] * dn[1] + n[0][2] * dn[2]);
        lambda[1] = q + (m_uu - t * m_uw);
        lambda[2] = q + (m_ww + t * m_uw);
      }

    // descending order
    if (lambda[order[0]] < lambda[order[1]])
      std::swap(order[0], order[1]);
    if (lambda[order[1]] < lambda[order[2]])
      std::swap(order[1], order[2]);
    if (lambda[order[0]] < lambda[order[1]])
      std::swap(order[0], order[1]);
    for (unsigned int k = 0; k < 3; ++k)
      {
        values[k] = lambda[order[k]];
        for (unsigned int i = 0; i < 3; ++i)
          vectors[i][k] = n[order[k]][i];
      }
  }
} // namespace densify
