// J2Plasticity: uniaxial compression to 50 % true strain vs. exact result.
#include <densify/material/j2_plasticity.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <vector>

using namespace densify;

namespace
{
  bool all_ok = true;

  /// Exact axial Kirchhoff stress (negative in compression) of the Hencky
  /// J2 model in uniaxial stress at logarithmic strain @p eps <= 0: it is
  /// the 1D small-strain law in log strain, |tau| = sigma_y(eps_p),
  /// eps_p = |eps| - |tau| / E once yielded.
  double
  exact_tau(const J2Parameters &p, const double eps)
  {
    const double e = std::abs(eps);
    if (p.E * e <= p.sigma0)
      return p.E * eps;
    double s = 0.;
    switch (p.hardening)
      {
        case Hardening::none:
          s = p.sigma0;
          break;
        case Hardening::linear:
          s = (p.sigma0 + p.H * e) / (1. + p.H / p.E);
          break;
        case Hardening::power_law:
          {
            // s - sigma0 - K (e - s/E)^n = 0 on [sigma0, E e], bisection.
            double lo = p.sigma0, hi = p.E * e;
            for (unsigned int it = 0; it < 200; ++it)
              {
                const double mid = 0.5 * (lo + hi);
                const double g =
                  mid - p.sigma0 - p.K * std::pow(e - mid / p.E, p.n);
                (g > 0. ? hi : lo) = mid;
              }
            s = 0.5 * (lo + hi);
            break;
          }
      }
    return -s;
  }

  /// Solve P_22 = P_33 = 0 for the lateral stretch at axial stretch
  /// @p lambda (scalar Newton, starting from @p mu), return the final
  /// stress, tangent and trial state.
  double
  lateral_stretch(const J2Plasticity  &material,
                  const double         lambda,
                  double               mu,
                  const MaterialState &committed,
                  MaterialState       &trial,
                  Tensor<2, 3>        &P)
  {
    Tensor<4, 3> A;
    for (unsigned int it = 0; it < 50; ++it)
      {
        Tensor<2, 3> F;
        F[0][0] = lambda;
        F[1][1] = mu;
        F[2][2] = mu;
        material.evaluate(F, &committed, &trial, P, A);
        if (std::abs(P[1][1]) < 1e-9)
          return mu;
        mu -= P[1][1] / (A[1][1][1][1] + A[1][1][2][2]);
      }
    throw std::runtime_error("lateral Newton did not converge");
  }

  void
  run(const J2Parameters &parameters)
  {
    const J2Plasticity material(parameters);
    std::cout << material.name() << "\n";

    // One elastic step to half the yield strain, then 50 increments to a
    // true strain of 0.5.
    std::vector<double> strains = {-0.5 * parameters.sigma0 / parameters.E};
    for (unsigned int i = 1; i <= 50; ++i)
      strains.push_back(-0.5 * i / 50.);

    MaterialState state;
    double        mu               = 1.;
    double        max_stress_error = 0., max_eps_p_error = 0., max_J_error = 0.,
           max_lateral = 0.;
    for (unsigned int s = 0; s < strains.size(); ++s)
      {
        const double  eps    = strains[s];
        const double  lambda = std::exp(eps);
        MaterialState trial;
        Tensor<2, 3>  P;
        mu    = lateral_stretch(material, lambda, mu, state, trial, P);
        state = trial;

        const double J     = lambda * mu * mu;
        const double sigma = P[0][0] * lambda / J; // Cauchy = P F^T / J
        const double tau   = sigma * J;            // Kirchhoff

        const double tau_ex = exact_tau(parameters, eps);
        const double J_ex =
          std::exp((1. - 2. * parameters.nu) * tau_ex / parameters.E);
        const double sigma_ex = tau_ex / J_ex;
        const double eps_p_ex = std::abs(eps) - std::abs(tau_ex) / parameters.E;

        max_stress_error =
          std::max(max_stress_error,
                   std::abs(sigma - sigma_ex) / std::abs(sigma_ex));
        max_eps_p_error =
          std::max(max_eps_p_error,
                   std::abs(state.eps_p - std::max(eps_p_ex, 0.)));
        // ln J = tr eps_e = -p/K = (1 - 2 nu) tau_axial / E.
        max_J_error = std::max(max_J_error,
                               std::abs(J - std::exp((1. - 2. * parameters.nu) *
                                                     tau / parameters.E)));
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            if (i + j > 0)
              max_lateral = std::max(max_lateral, std::abs(P[i][j]));

        if (s == 0 || s % 10 == 0)
          std::cout << "  true strain " << std::abs(eps) << ": sigma_axial "
                    << sigma << " MPa (exact " << sigma_ex << "), eps_p "
                    << state.eps_p << ", J " << J << "\n";
      }

    const auto report =
      [](const char *what, const double error, const double limit) {
        if (error < limit)
          std::cout << "  " << what << " ok (error < " << limit << ")\n";
        else
          {
            std::cout << "  " << what << " FAILED (error " << error << ")\n";
            all_ok = false;
          }
      };
    report("axial Cauchy stress vs exact", max_stress_error, 1e-8);
    report("eps_p vs exact", max_eps_p_error, 1e-10);
    report("J vs exp((1 - 2 nu) tau / E)", max_J_error, 1e-8);
    report("lateral and shear stress free", max_lateral, 1e-8);
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

  J2Parameters pw = sn;
  pw.hardening    = Hardening::power_law;
  pw.K            = 120.;
  pw.n            = 0.3;
  run(pw);

  J2Parameters cu = material_preset("Cu");
  cu.hardening    = Hardening::power_law;
  cu.K            = 300.;
  cu.n            = 1.5;
  run(cu);

  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED") << "\n";
  return all_ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
