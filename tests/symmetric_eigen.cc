// The closed-form eigen decomposition of J2Plasticity (symmetric_eigen.h)
// against deal.II's QL iteration with implicit shifts, on states of the
// kinds a compaction meets: random elastic left Cauchy-Green tensors with
// displacement gradients from 1e-300 to 1, principal stretches of 10 and
// 0.1, exactly and nearly equal eigenvalues (the identity, axisymmetric
// states, pairs 1e-12 apart), and signed matrices. Checked for each:
// Q diag(x) Q^T reconstructs the matrix and Q^T Q = I to 1e-14 of its
// size, the eigenvalues equal QL's to 1e-13 of the size, the matrix
// logarithm (the Hencky strain of J2Plasticity) equals QL's to 1e-12 of
// its size plus the round-off of the smallest eigenvalue's logarithm. Then
// J2Plasticity's Kirchhoff stress on plastic and elastic trial states
// equals the radial return computed here with QL to 1e-12 of sigma0 +
// |tau| plus 1e-14 E x_max / x_min (the round-off of the logarithmic
// strains, 1e-16 x_max / x_a each, times the moduli).
#include <deal.II/base/symmetric_tensor.h>

#include <densify/material/j2_plasticity.h>
#include <densify/material/symmetric_eigen.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>

using namespace densify;

namespace
{
  using testing::uniform;

  /// A random rotation (Rodrigues, angle up to pi about a random axis).
  Tensor<2, 3>
  rotation(std::uint64_t &state)
  {
    Tensor<1, 3> axis;
    for (unsigned int i = 0; i < 3; ++i)
      axis[i] = uniform(state);
    axis /= axis.norm();
    const double angle = M_PI * uniform(state);
    Tensor<2, 3> K;
    K[0][1] = -axis[2];
    K[0][2] = axis[1];
    K[1][0] = axis[2];
    K[1][2] = -axis[0];
    K[2][0] = -axis[1];
    K[2][1] = axis[0];
    return Tensor<2, 3>(unit_symmetric_tensor<3>()) + std::sin(angle) * K +
           (1. - std::cos(angle)) * K * K;
  }

  /// R diag(d) R^T.
  SymmetricTensor<2, 3>
  rotated_diagonal(const Tensor<2, 3> &R,
                   const double        d0,
                   const double        d1,
                   const double        d2)
  {
    Tensor<2, 3> D;
    D[0][0] = d0;
    D[1][1] = d1;
    D[2][2] = d2;
    return symmetrize(R * D * transpose(R));
  }

  /// sum_a f(x_a) n_a (x) n_a from eigenpairs in either layout.
  template <typename Function>
  Tensor<2, 3>
  isotropic(const double x[3], const double Q[3][3], const Function &f)
  {
    Tensor<2, 3> result;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          result[i][j] += f(x[a]) * Q[i][a] * Q[j][a];
    return result;
  }

  double
  max_abs(const Tensor<2, 3> &t)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        m = std::max(m, std::abs(t[i][j]));
    return m;
  }

  /// The QL decomposition of deal.II in the layout of symmetric_eigen().
  void
  ql(const SymmetricTensor<2, 3> &A, double x[3], double Q[3][3])
  {
    const auto eig =
      eigenvectors(A, SymmetricTensorEigenvectorMethod::ql_implicit_shifts);
    for (unsigned int a = 0; a < 3; ++a)
      {
        x[a] = eig[a].first;
        for (unsigned int i = 0; i < 3; ++i)
          Q[i][a] = eig[a].second[i];
      }
  }

  struct Tally
  {
    unsigned int cases = 0, failed = 0;
  };

  /// Checks the decomposition of A; positive: A is positive definite.
  void
  check(const SymmetricTensor<2, 3> &A, const bool positive, Tally &tally)
  {
    double a[3][3], x[3], Q[3][3], xq[3], Qq[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        a[i][j] = A[i][j];
    symmetric_eigen(a, x, Q);
    double size = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        size = std::max(size, std::abs(a[i][j]));

    Tensor<2, 3> orthogonality, reconstruction;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          orthogonality[i][j]  = -(i == j);
          reconstruction[i][j] = -a[i][j];
          for (unsigned int k = 0; k < 3; ++k)
            {
              orthogonality[i][j] += Q[k][i] * Q[k][j];
              reconstruction[i][j] += Q[i][k] * x[k] * Q[j][k];
            }
        }
    bool ok = max_abs(orthogonality) <= 1e-14 &&
              max_abs(reconstruction) <= 1e-14 * size;
    ok = ok && x[0] >= x[1] && x[1] >= x[2];

    // deal.II's QL returns infinite values and NaN vectors for off-diagonal
    // entries between
    // about 1e-150 and 1e-100 of the diagonal (doc/theory.md): compare only
    // where it is defined
    ql(A, xq, Qq);
    bool ql_defined = true;
    for (unsigned int a_ = 0; a_ < 3; ++a_)
      {
        ql_defined = ql_defined && std::isfinite(xq[a_]);
        for (unsigned int i = 0; i < 3; ++i)
          ql_defined = ql_defined && std::isfinite(Qq[i][a_]);
      }
    if (ql_defined)
      {
        for (unsigned int k = 0; k < 3; ++k)
          ok = ok && std::abs(x[k] - xq[k]) <= 1e-13 * size;
        if (positive)
          {
            const auto log_of     = [](const double v) { return std::log(v); };
            const Tensor<2, 3> L  = isotropic(x, Q, log_of);
            const Tensor<2, 3> Lq = isotropic(xq, Qq, log_of);
            // round-off of x_min is 1e-16 size, of its logarithm that over
            // x_min
            ok = ok &&
                 max_abs(L - Lq) <= 1e-12 * max_abs(Lq) + 1e-14 * size / x[2];
          }
      }
    ++tally.cases;
    if (!ok)
      {
        ++tally.failed;
        std::cerr << "failed on " << A << ": " << x[0] << ' ' << x[1] << ' '
                  << x[2] << " QL " << xq[0] << ' ' << xq[1] << ' ' << xq[2]
                  << " vectors " << Qq[0][0] << ' ' << Qq[1][0] << ' '
                  << Qq[2][0] << std::endl;
      }
  }

  /// J2Plasticity's Kirchhoff stress tau = P F^T for F from a virgin state
  /// against the radial return of perfect plasticity computed with QL.
  void
  check_stress(const J2Plasticity &material,
               const J2Parameters &prm,
               const Tensor<2, 3> &F,
               Tally              &tally)
  {
    const double  kappa = prm.E / (3. * (1. - 2. * prm.nu));
    const double  mu    = prm.E / (2. * (1. + prm.nu));
    const J2State committed;
    J2State       trial;
    Tensor<2, 3>  P;
    material.stress(F, &committed, &trial, P);
    const Tensor<2, 3> tau = P * transpose(F);

    double     x[3], Q[3][3];
    const auto be = symmetrize(F * transpose(F));
    ql(be, x, Q);
    double eps[3], tr = 0.;
    for (unsigned int a = 0; a < 3; ++a)
      {
        eps[a] = 0.5 * std::log(x[a]);
        tr += eps[a];
      }
    double s[3], s2 = 0.;
    for (unsigned int a = 0; a < 3; ++a)
      {
        s[a] = 2. * mu * (eps[a] - tr / 3.);
        s2 += s[a] * s[a];
      }
    const double q      = std::sqrt(1.5 * s2);
    const double factor = q > prm.sigma0 ? prm.sigma0 / q : 1.;
    double       t[3];
    for (unsigned int a = 0; a < 3; ++a)
      t[a] = kappa * tr + factor * s[a];
    Tensor<2, 3> tau_ql;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          tau_ql[i][j] += t[a] * Q[i][a] * Q[j][a];
    ++tally.cases;
    // both resolve each principal logarithmic strain to the round-off of
    // its stretch, 1e-16 x_max / x_a, which the moduli carry into the
    // stress: 1e-14 E x_max / x_min bounds that
    if (!(max_abs(tau - tau_ql) <=
          1e-12 * (prm.sigma0 + max_abs(tau_ql)) + 1e-14 * prm.E * x[0] / x[2]))
      {
        ++tally.failed;
        std::cerr << "stress differs for F = " << F << ": "
                  << max_abs(tau - tau_ql) << std::endl;
      }
  }
} // namespace



int
main()
{
  std::uint64_t state  = 2024;
  bool          all_ok = true;
  const auto    report = [&](const std::string &what, const Tally &tally) {
    std::cout << what << ": " << tally.cases << " cases, "
              << (tally.failed == 0 ? "all agree" : "SOME DIFFER") << std::endl;
    all_ok = all_ok && tally.failed == 0;
  };

  // be = F F^T for F = I + g M, M random with entries in [-1, 1]
  for (const double g : {1e-300,
                         1e-200,
                         1e-131,
                         1e-100,
                         1e-50,
                         1e-16,
                         1e-12,
                         1e-8,
                         1e-4,
                         1e-2,
                         0.1,
                         0.5,
                         1.})
    {
      Tally tally;
      for (unsigned int n = 0; n < 200; ++n)
        {
          Tensor<2, 3> F = unit_symmetric_tensor<3>();
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              F[i][j] += g * uniform(state);
          if (determinant(F) > 0.)
            check(symmetrize(F * transpose(F)), true, tally);
        }
      std::ostringstream what;
      what << "be of random gradients of size " << g;
      report(what.str(), tally);
    }

  {
    Tally tally;
    for (unsigned int n = 0; n < 200; ++n)
      {
        const Tensor<2, 3> R = rotation(state);
        check(rotated_diagonal(R, 100., 1., 0.01), true, tally); // stretches
        check(rotated_diagonal(R, 100., 100., 0.01), true, tally);
        check(rotated_diagonal(R, 0.01, 0.01, 100.), true, tally);
        check(rotated_diagonal(R, 2., 2., 2.), true, tally); // equal
        check(rotated_diagonal(R, 1., 1., 1.3), true, tally);
        check(rotated_diagonal(R, 1., 1. + 1e-12, 1.3), true, tally);
        check(rotated_diagonal(R, 1., 1. + 1e-12, 1. - 1e-12), true, tally);
        check(rotated_diagonal(R, 1., 1. + 1e-8, 1. + 2e-8), true, tally);
      }
    report("rotated stretches of 10 and 0.1, equal and nearly equal "
           "eigenvalues",
           tally);
  }

  {
    Tally tally;
    for (unsigned int n = 0; n < 500; ++n)
      {
        SymmetricTensor<2, 3> A;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            A[i][j] = uniform(state);
        check(A, false, tally);
      }
    check(SymmetricTensor<2, 3>(), false, tally); // zero
    report("signed random matrices and zero", tally);
  }

  {
    J2Parameters       prm = material_preset("Sn");
    const J2Plasticity material(prm);
    Tally              tally;
    for (const double g : {1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5})
      for (unsigned int n = 0; n < 100; ++n)
        {
          Tensor<2, 3> F = unit_symmetric_tensor<3>();
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              F[i][j] += g * uniform(state);
          if (determinant(F) > 0.1)
            check_stress(material, prm, F, tally);
        }
    for (unsigned int n = 0; n < 100; ++n)
      {
        const Tensor<2, 3> R = rotation(state);
        Tensor<2, 3>       D;
        D[0][0] = 10.;
        D[1][1] = 1.;
        D[2][2] = 0.1;
        check_stress(material, prm, R * D * transpose(R), tally);
        D[1][1] = 10.;
        check_stress(material, prm, R * D * transpose(R), tally);
      }
    report("J2 stress (Sn, elastic and plastic trial states) against QL",
           tally);
  }

  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_ok ? 0 : 1;
}
