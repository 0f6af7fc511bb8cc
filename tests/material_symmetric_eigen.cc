// The closed-form eigen decomposition symmetric_eigenvectors() against the
// definition: for tensors with distinct, close (relative gaps 1e-3 to 1e-12)
// and equal eigenvalues, near and far from the identity (the elastic left
// Cauchy-Green tensors of J2Plasticity), at scales 1e-10 to 1e10, each pair
// satisfies |A v - lambda v| <= 1e-14 |A|, the vectors are orthonormal to
// 1e-14, the eigenvalues descend and agree with the spectrum the tensor was
// made with (or deal.II's QL iteration) to 1e-13 |A|. A tensor with a NaN entry
// gives NaN eigenvalues.
#include <deal.II/base/symmetric_tensor.h>

#include <densify/material/symmetric_eigen.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>

using namespace densify;

namespace
{
  /// A Q diag(l) Q^T with Q a rotation from the axis-angle (n, angle).
  SymmetricTensor<2, 3>
  with_spectrum(const std::array<double, 3> &l,
                Tensor<1, 3>                 n,
                const double                 angle)
  {
    n /= n.norm();
    Tensor<2, 3> K, Q = unit_symmetric_tensor<3>();
    K[0][1] = -n[2];
    K[0][2] = n[1];
    K[1][2] = -n[0];
    K[1][0] = n[2];
    K[2][0] = -n[1];
    K[2][1] = n[0];
    Q += std::sin(angle) * K + (1. - std::cos(angle)) * K * K;
    Tensor<2, 3> D;
    for (unsigned int a = 0; a < 3; ++a)
      D[a][a] = l[a];
    return symmetrize(Q * D * transpose(Q));
  }
} // namespace

int
main()
{
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  double       residual = 0., orthogonality = 0., eigenvalue = 0.;
  bool         descending = true;
  unsigned int n_tensors  = 0;
  // A and its eigenvalues in descending order
  const auto check = [&](const SymmetricTensor<2, 3> &A,
                         std::array<double, 3>        ref) {
    std::sort(ref.begin(), ref.end(), std::greater<double>());
    const auto   eig  = symmetric_eigenvectors(A);
    const double norm = std::max(A.norm(), 1e-300);
    for (unsigned int a = 0; a < 3; ++a)
      {
        const Tensor<1, 3> &v = eig[a].second;
        residual = std::max(residual, (A * v - eig[a].first * v).norm() / norm);
        eigenvalue =
          std::max(eigenvalue, std::abs(eig[a].first - ref[a]) / norm);
        for (unsigned int b = 0; b < 3; ++b)
          orthogonality =
            std::max(orthogonality,
                     std::abs(v * eig[b].second - (a == b ? 1. : 0.)));
        if (a > 0 && eig[a].first > eig[a - 1].first)
          descending = false;
      }
    ++n_tensors;
  };

  for (const double scale : {1e-10, 1., 1e10})
    for (const double shift : {0., 1., 1e3})
      for (const double gap : {1., 1e-3, 1e-6, 1e-9, 1e-12, 0.})
        for (unsigned int k = 0; k < 20; ++k)
          {
            const Tensor<1, 3> n(
              {uniform(random), uniform(random), uniform(random)});
            const double angle = 3. * uniform(random);
            const double x     = uniform(random);
            // a pair of eigenvalues gap apart, the third distinct; with the
            // shift, tensors near a multiple of the identity
            const std::array<double, 3> first  = {{x, x + gap, x - 1.5}};
            const std::array<double, 3> second = {{x + 1.5, x, x + gap}};
            for (const auto &l : {first, second})
              {
                std::array<double, 3> expected;
                for (unsigned int a = 0; a < 3; ++a)
                  expected[a] = scale * (shift + l[a]);
                check(scale * (shift * unit_symmetric_tensor<3>() +
                               with_spectrum(l, n, angle)),
                      expected);
              }
          }
  // the identity, a diagonal tensor and a general one
  check(unit_symmetric_tensor<3>(), {{1., 1., 1.}});
  SymmetricTensor<2, 3> diagonal;
  diagonal[0][0] = 2.;
  diagonal[1][1] = 3.;
  diagonal[2][2] = 1.;
  check(diagonal, {{2., 3., 1.}});
  SymmetricTensor<2, 3> general;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      general[i][j] = uniform(random);
  // against deal.II's QL iteration
  const auto ql = eigenvectors(general);
  check(general, {{ql[0].first, ql[1].first, ql[2].first}});

  SymmetricTensor<2, 3> broken = general;
  broken[0][1]                 = std::nan("");
  const bool nan_out = std::isnan(symmetric_eigenvectors(broken)[0].first);

  std::cerr << n_tensors << " tensors: residual " << residual
            << ", orthogonality " << orthogonality << ", eigenvalues "
            << eigenvalue << std::endl;
  const auto yes = [](const bool ok) { return ok ? "yes" : "NO"; };
  std::cout << "A v = lambda v to 1e-14 |A|: " << yes(residual < 1e-14)
            << std::endl
            << "orthonormal to 1e-14: " << yes(orthogonality < 1e-14)
            << std::endl
            << "eigenvalues as made to 1e-13 |A|: " << yes(eigenvalue < 1e-13)
            << std::endl
            << "descending: " << yes(descending) << std::endl
            << "NaN in, NaN out: " << yes(nan_out) << std::endl;
  return (residual < 1e-14 && orthogonality < 1e-14 && eigenvalue < 1e-13 &&
          descending && nan_out) ?
           0 :
           1;
}
