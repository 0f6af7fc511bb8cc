// J2Plasticity: tangent vs. finite differences, frame indifference.
#include <densify/material/j2_plasticity.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace densify;

namespace
{
  bool all_ok = true;

  /// Rotation by @p angle about the axis @p axis (Rodrigues).
  Tensor<2, 3>
  rotation(Tensor<1, 3> axis, const double angle)
  {
    axis /= axis.norm();
    Tensor<2, 3> W;
    W[0][1] = -axis[2];
    W[0][2] = axis[1];
    W[1][0] = axis[2];
    W[1][2] = -axis[0];
    W[2][0] = -axis[1];
    W[2][1] = axis[0];
    return Tensor<2, 3>(unit_symmetric_tensor<3>()) + std::sin(angle) * W +
           (1. - std::cos(angle)) * W * W;
  }

  Tensor<2, 3>
  diag(const double a, const double b, const double c)
  {
    Tensor<2, 3> F;
    F[0][0] = a;
    F[1][1] = b;
    F[2][2] = c;
    return F;
  }

  double
  max_abs(const Tensor<2, 3> &T)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        m = std::max(m, std::abs(T[i][j]));
    return m;
  }

  double
  max_abs(const Tensor<4, 3> &T)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            m = std::max(m, std::abs(T[i][j][k][l]));
    return m;
  }

  /// Relative max-norm error of the tangent against central differences.
  double
  tangent_error(const J2Plasticity  &material,
                const Tensor<2, 3>  &F,
                const MaterialState &committed)
  {
    MaterialState trial;
    Tensor<2, 3>  P;
    Tensor<4, 3>  A;
    material.evaluate(F, &committed, &trial, P, A);

    const double h = 1e-7;
    Tensor<4, 3> A_fd;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = 0; l < 3; ++l)
        {
          Tensor<2, 3> Fp = F, Fm = F, Pp, Pm;
          Tensor<4, 3> dummy;
          Fp[k][l] += h;
          Fm[k][l] -= h;
          material.evaluate(Fp, &committed, &trial, Pp, dummy);
          material.evaluate(Fm, &committed, &trial, Pm, dummy);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              A_fd[i][j][k][l] = (Pp[i][j] - Pm[i][j]) / (2. * h);
        }
    return max_abs(A - A_fd) / max_abs(A);
  }

  /// Print a pass/fail line for @p error against @p limit, with a
  /// robust error band instead of the raw number.
  void
  report(const std::string &what, const double error, const double limit)
  {
    if (error < limit)
      std::cout << "  " << what << " ok (error < " << limit << ")\n";
    else
      {
        std::cout << "  " << what << " FAILED (error " << error << ")\n";
        all_ok = false;
      }
  }

  void
  check(const std::string   &title,
        const J2Plasticity  &material,
        const Tensor<2, 3>  &F,
        const MaterialState &committed)
  {
    MaterialState trial;
    Tensor<2, 3>  P;
    Tensor<4, 3>  A;
    material.evaluate(F, &committed, &trial, P, A);
    const double       J     = determinant(F);
    const Tensor<2, 3> sigma = P * transpose(F) / J;
    const Tensor<2, 3> dev_sigma =
      sigma - trace(sigma) / 3. * Tensor<2, 3>(unit_symmetric_tensor<3>());
    const double mises = std::sqrt(1.5 * scalar_product(dev_sigma, dev_sigma));
    const bool   plastic = trial.eps_p > committed.eps_p;

    std::cout << title << ": " << (plastic ? "plastic" : "elastic")
              << ", von Mises " << mises << " MPa, pressure "
              << -trace(sigma) / 3. + 0. << " MPa, eps_p " << trial.eps_p
              << "\n";

    report("tangent", tangent_error(material, F, committed), 1e-6);

    // The residual-only path (stress(), no tangent) gives the same stress
    // and state as evaluate().
    {
      MaterialState trial_s;
      Tensor<2, 3>  P_s;
      material.stress(F, &committed, &trial_s, P_s);
      const double scale =
        std::max(max_abs(P), material.get_parameters().sigma0);
      report("stress without tangent = evaluate()",
             std::max({max_abs(P_s - P) / scale,
                       max_abs(trial_s.Cp_inv - trial.Cp_inv),
                       std::abs(trial_s.eps_p - trial.eps_p)}),
             1e-14);
    }

    // Frame indifference: P(QF) = Q P(F), A(QF) = Q A(F), same state.
    const Tensor<2, 3> R = rotation(Tensor<1, 3>({0.3, -0.8, 0.5}), 1.234);
    MaterialState      trial_R;
    Tensor<2, 3>       P_R;
    Tensor<4, 3>       A_R, A_rot;
    material.evaluate(R * F, &committed, &trial_R, P_R, A_R);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J_ = 0; J_ < 3; ++J_)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            for (unsigned int p = 0; p < 3; ++p)
              for (unsigned int q = 0; q < 3; ++q)
                A_rot[i][J_][k][L] += R[i][p] * R[k][q] * A[p][J_][q][L];
    const double scale_P =
      std::max(max_abs(P), material.get_parameters().sigma0);
    double objectivity_error = std::max(max_abs(P_R - R * P) / scale_P,
                                        max_abs(A_R - A_rot) / max_abs(A));
    objectivity_error =
      std::max(objectivity_error, max_abs(trial_R.Cp_inv - trial.Cp_inv));
    objectivity_error =
      std::max(objectivity_error, std::abs(trial_R.eps_p - trial.eps_p));
    report("frame indifference", objectivity_error, 1e-10);

    report("Cauchy symmetry",
           max_abs(sigma - transpose(sigma)) / std::max(max_abs(sigma), 1.),
           1e-12);

    // The plastic update keeps det Cp^{-1} (isochoric flow).
    report("det Cp_inv preserved",
           std::abs(determinant(trial.Cp_inv) - determinant(committed.Cp_inv)),
           1e-12);
  }

  /// Committed state after @p steps load steps linearly towards @p F_end
  /// (from the identity).
  MaterialState
  history(const J2Plasticity &material,
          const Tensor<2, 3> &F_end,
          const unsigned int  steps)
  {
    MaterialState state;
    for (unsigned int s = 1; s <= steps; ++s)
      {
        const Tensor<2, 3> F =
          Tensor<2, 3>(unit_symmetric_tensor<3>()) +
          (double(s) / steps) * (F_end - unit_symmetric_tensor<3>());
        MaterialState trial;
        Tensor<2, 3>  P;
        Tensor<4, 3>  A;
        material.evaluate(F, &state, &trial, P, A);
        state = trial;
      }
    return state;
  }
} // namespace



int
main()
{
  std::cout << std::setprecision(6);

  J2Parameters sn = material_preset("Sn");

  J2Parameters lin = sn;
  lin.hardening    = Hardening::linear;
  lin.H            = 800.;
  lin.label        = "Sn linear";

  J2Parameters pow_soft = sn;
  pow_soft.hardening    = Hardening::power_law;
  pow_soft.K            = 120.;
  pow_soft.n            = 0.3;
  pow_soft.label        = "Sn power 0.3";

  J2Parameters pow_hard = sn;
  pow_hard.hardening    = Hardening::power_law;
  pow_hard.K            = 2000.;
  pow_hard.n            = 1.5;
  pow_hard.label        = "Sn power 1.5";

  const J2Plasticity none(sn), linear(lin), power_soft(pow_soft),
    power_hard(pow_hard);
  const MaterialState virgin;

  // Identity: zero stress, tangent = small-strain elasticity.
  {
    MaterialState trial;
    Tensor<2, 3>  P;
    Tensor<4, 3>  A;
    none.evaluate(unit_symmetric_tensor<3>(), &virgin, &trial, P, A);
    const double E = sn.E, nu = sn.nu;
    const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu)),
                 mu     = E / (2. * (1. + nu));
    Tensor<4, 3> C;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            C[i][j][k][l] = lambda * (i == j) * (k == l) +
                            mu * ((i == k) * (j == l) + (i == l) * (j == k));
    std::cout << "F = I:\n";
    report("zero stress", max_abs(P), 1e-12);
    report("tangent = small-strain elasticity",
           max_abs(A - C) / max_abs(C),
           1e-12);
  }
  check("F = I", none, unit_symmetric_tensor<3>(), virgin);

  const Tensor<2, 3> R0 = rotation(Tensor<1, 3>({1., 2., 3.}), 0.7);

  // Elastic: small general deformation with rotation.
  {
    Tensor<2, 3> H;
    H[0][0] = 1.2e-4;
    H[0][1] = -0.8e-4;
    H[1][2] = 2.1e-4;
    H[2][0] = 0.5e-4;
    H[2][2] = -1.0e-4;
    check("elastic, rotated",
          none,
          R0 * (unit_symmetric_tensor<3>() + H),
          virgin);
  }

  // Just beyond first yield in uniaxial compression (yield strain
  // sigma0/E = 7.2e-4), for each hardening law.
  {
    const Tensor<2, 3> F = diag(1. - 8.0e-4, 1. + 2.0e-4, 1. + 2.5e-4);
    check("first yield, none", none, F, virgin);
    check("first yield, linear", linear, F, virgin);
    check("first yield, power n = 0.3", power_soft, F, virgin);
    check("first yield, power n = 1.5", power_hard, F, virgin);
  }

  // Large plastic deformation with shear and rotation.
  Tensor<2, 3> F_big = diag(0.7, 1.1, 1.25);
  F_big[0][1]        = 0.2;
  F_big[2][0]        = -0.15;
  F_big              = R0 * F_big;
  check("large strain, none", none, F_big, virgin);
  check("large strain, linear", linear, F_big, virgin);
  check("large strain, power n = 0.3", power_soft, F_big, virgin);
  check("large strain, power n = 1.5", power_hard, F_big, virgin);

  // Repeated principal stretches.
  check("diag(a, b, b) elastic",
        none,
        diag(1. - 3e-4, 1. + 1e-4, 1. + 1e-4),
        virgin);
  check("diag(a, b, b) plastic, none", none, diag(0.6, 1.25, 1.25), virgin);
  check("diag(a, b, b) plastic, linear", linear, diag(0.6, 1.25, 1.25), virgin);
  check("diag(a, b, b) plastic, power n = 0.3",
        power_soft,
        diag(0.6, 1.25, 1.25),
        virgin);
  check("diag(a, b, b(1 + 1e-9)) plastic",
        linear,
        diag(0.6, 1.25, 1.25 * (1. + 1e-9)),
        virgin);
  check("rotated diag(a, b, b) plastic",
        linear,
        R0 * diag(0.6, 1.25, 1.25),
        virgin);
  check("diag(a, a, a)", none, diag(0.98, 0.98, 0.98), virgin);

  // Pre-existing plastic history (compression, then shear on top).
  {
    const MaterialState state_none =
      history(none, R0 * diag(0.75, 1.12, 1.18), 10);
    const MaterialState state_lin =
      history(linear, R0 * diag(0.75, 1.12, 1.18), 10);
    const MaterialState state_pow =
      history(power_soft, R0 * diag(0.75, 1.12, 1.18), 10);
    Tensor<2, 3> F = diag(0.72, 1.12, 1.2);
    F[1][2]        = 0.08;
    F              = R0 * F;
    check("history, plastic, none", none, F, state_none);
    check("history, plastic, linear", linear, F, state_lin);
    check("history, plastic, power n = 0.3", power_soft, F, state_pow);
    // Elastic unloading from the plastic state.
    const Tensor<2, 3> F_unload = R0 * diag(0.7505, 1.1198, 1.1797);
    check("history, elastic unloading", linear, F_unload, state_lin);
  }

  // An inverted element is reported, not silently evaluated.
  try
    {
      MaterialState trial;
      Tensor<2, 3>  P;
      Tensor<4, 3>  A;
      none.evaluate(diag(-0.9, 1., 1.), &virgin, &trial, P, A);
      std::cout << "det F < 0: no exception\n";
      all_ok = false;
    }
  catch (const std::domain_error &)
    {
      std::cout << "det F < 0: std::domain_error\n";
    }

  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED") << "\n";
  return all_ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
