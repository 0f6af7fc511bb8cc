// Closed-form eigen decomposition of a symmetric 3x3 tensor.
#include <densify/material/symmetric_eigen.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace densify
{
  std::array<std::pair<double, Tensor<1, 3>>, 3>
  symmetric_eigenvectors(const SymmetricTensor<2, 3> &A)
  {
    std::array<std::pair<double, Tensor<1, 3>>, 3> result;
    const double                                   mean = trace(A) / 3.;
    double                                         c[3][3];
    double                                         scale  = 0.;
    bool                                           finite = std::isfinite(mean);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          c[i][j] = A[i][j] - (i == j ? mean : 0.);
          finite  = finite && std::isfinite(c[i][j]);
          scale   = std::max(scale, std::abs(c[i][j]));
        }
    if (!finite || !(scale > 0.))
      {
        // a multiple of the identity (any basis), or not finite
        const double value =
          finite ? mean : std::numeric_limits<double>::quiet_NaN();
        for (unsigned int a = 0; a < 3; ++a)
          {
            result[a].first     = value;
            result[a].second    = Tensor<1, 3>();
            result[a].second[a] = 1.;
          }
        return result;
      }
    for (auto &row : c)
      for (double &entry : row)
        entry /= scale;

    // eigenvalues of the traceless c: 2 p cos(phi + 2 pi k / 3)
    const double p2 =
      (c[0][0] * c[0][0] + c[1][1] * c[1][1] + c[2][2] * c[2][2] +
       2. * (c[0][1] * c[0][1] + c[0][2] * c[0][2] + c[1][2] * c[1][2])) /
      6.;
    const double p   = std::sqrt(p2);
    const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                       c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                       c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
    const double r   = std::clamp(det / (2. * p2 * p), -1., 1.);
    const double phi = std::acos(r) / 3.;
    const double l1  = 2. * p * std::cos(phi);
    const double l3  = 2. * p * std::cos(phi + 2. * M_PI / 3.);
    const double l2  = -l1 - l3;
    // the eigenvalue farthest from the other two
    const double isolated = (l1 - l2 >= l2 - l3) ? l1 : l3;

    // its eigenvector: the longest cross product of two rows of c - l I
    Tensor<1, 3> rows[3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        rows[i][j] = c[i][j] - (i == j ? isolated : 0.);
    Tensor<1, 3> v      = cross_product_3d(rows[0], rows[1]);
    double       length = v.norm_square();
    for (const auto &[i, j] : {std::pair<int, int>{0, 2}, {1, 2}})
      {
        const Tensor<1, 3> w = cross_product_3d(rows[i], rows[j]);
        if (w.norm_square() > length)
          {
            v      = w;
            length = w.norm_square();
          }
      }
    v /= std::sqrt(length);

    // an orthonormal pair (u, w) of the plane orthogonal to v, from the axis
    // along which v is shortest
    unsigned int axis = 0;
    for (unsigned int k = 1; k < 3; ++k)
      if (std::abs(v[k]) < std::abs(v[axis]))
        axis = k;
    Tensor<1, 3> u = -v[axis] * v;
    u[axis] += 1.;
    u /= u.norm();
    const Tensor<1, 3> w = cross_product_3d(v, u);

    const auto quadratic = [&c](const Tensor<1, 3> &x, const Tensor<1, 3> &y) {
      double sum = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          sum += x[i] * c[i][j] * y[j];
      return sum;
    };
    // the 2x2 block of c in (u, w), diagonalised by one Jacobi rotation
    const double a = quadratic(u, u), b = quadratic(u, w), d = quadratic(w, w);
    double       t = 0.;
    if (b != 0.)
      {
        const double theta = (d - a) / (2. * b);
        t                  = (theta >= 0. ? 1. : -1.) /
            (std::abs(theta) + std::sqrt(theta * theta + 1.));
      }
    const double cs = 1. / std::sqrt(t * t + 1.), sn = t * cs;

    result[0] = {mean + scale * quadratic(v, v), v};
    result[1] = {mean + scale * (a - t * b), cs * u - sn * w};
    result[2] = {mean + scale * (d + t * b), sn * u + cs * w};
    std::sort(result.begin(), result.end(), [](const auto &x, const auto &y) {
      return x.first > y.first;
    });
    return result;
  }
} // namespace densify
