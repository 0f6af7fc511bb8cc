// J2Plasticity: a rigid rotation of a pre-stressed point changes nothing.
#include <densify/material/j2_plasticity.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>

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

  double
  max_abs(const Tensor<2, 3> &T)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        m = std::max(m, std::abs(T[i][j]));
    return m;
  }

  /// Cauchy stress at F from the committed state; updates @p state.
  Tensor<2, 3>
  step(const J2Plasticity &material,
       const Tensor<2, 3> &F,
       MaterialState      &state)
  {
    MaterialState trial;
    Tensor<2, 3>  P;
    Tensor<4, 3>  A;
    material.evaluate(F, &state, &trial, P, A);
    state = trial;
    return P * transpose(F) / determinant(F);
  }

  double
  von_mises(const Tensor<2, 3> &sigma)
  {
    const Tensor<2, 3> s =
      sigma - trace(sigma) / 3. * Tensor<2, 3>(unit_symmetric_tensor<3>());
    return std::sqrt(1.5 * scalar_product(s, s));
  }

  void
  report(const char *what, const double error, const double limit)
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
  run(const J2Parameters &parameters)
  {
    const J2Plasticity material(parameters);
    std::cout << material.name() << "\n";

    // Plastic pre-stress: compression with shear, 10 committed steps.
    Tensor<2, 3> F_end;
    F_end[0][0] = 0.8;
    F_end[1][1] = 1.08;
    F_end[2][2] = 1.15;
    F_end[0][1] = 0.12;
    F_end[1][2] = -0.07;
    MaterialState state;
    Tensor<2, 3>  sigma0, F;
    for (unsigned int s = 1; s <= 10; ++s)
      {
        F = Tensor<2, 3>(unit_symmetric_tensor<3>()) +
            (s / 10.) * (F_end - unit_symmetric_tensor<3>());
        sigma0 = step(material, F, state);
      }
    const MaterialState prestressed = state;
    const double        q0 = von_mises(sigma0), p0 = -trace(sigma0) / 3.;
    std::cout << "  pre-stressed: von Mises " << q0 << " MPa, pressure " << p0
              << " MPa, eps_p " << prestressed.eps_p << "\n";

    // 90 degrees about an oblique axis in 10 increments: F <- R_inc F.
    const Tensor<1, 3> axis({1., -2., 0.7});
    const Tensor<2, 3> R_inc = rotation(axis, M_PI / 20.);
    double q_error = 0., p_error = 0., eps_p_error = 0., Cp_error = 0.,
           sigma_error   = 0.;
    Tensor<2, 3> R_total = unit_symmetric_tensor<3>();
    for (unsigned int s = 1; s <= 10; ++s)
      {
        F                        = R_inc * F;
        R_total                  = R_inc * R_total;
        const Tensor<2, 3> sigma = step(material, F, state);
        q_error = std::max(q_error, std::abs(von_mises(sigma) - q0) / q0);
        p_error = std::max(p_error,
                           std::abs(-trace(sigma) / 3. - p0) /
                             std::max(std::abs(p0), q0));
        eps_p_error =
          std::max(eps_p_error, std::abs(state.eps_p - prestressed.eps_p));
        Cp_error =
          std::max(Cp_error, max_abs(state.Cp_inv - prestressed.Cp_inv));
        sigma_error =
          std::max(sigma_error,
                   max_abs(sigma - R_total * sigma0 * transpose(R_total)) /
                     max_abs(sigma0));
      }
    std::cout << "  total rotation angle "
              << std::acos(0.5 * (trace(R_total) - 1.)) * 180. / M_PI
              << " degrees\n";
    report("von Mises unchanged", q_error, 1e-10);
    report("pressure unchanged", p_error, 1e-10);
    report("eps_p unchanged", eps_p_error, 1e-14);
    report("Cp_inv unchanged", Cp_error, 1e-12);
    report("sigma = R sigma0 R^T", sigma_error, 1e-10);
  }
} // namespace



int
main()
{
  std::cout << std::setprecision(6);

  J2Parameters sn = material_preset("Sn");
  run(sn);

  J2Parameters lin = sn;
  lin.hardening    = Hardening::linear;
  lin.H            = 800.;
  run(lin);

  J2Parameters pw = material_preset("Fe");
  pw.hardening    = Hardening::power_law;
  pw.K            = 400.;
  pw.n            = 0.4;
  run(pw);

  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED") << "\n";
  return all_ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
