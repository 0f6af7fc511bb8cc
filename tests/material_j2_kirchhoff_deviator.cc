// J2Plasticity::kirchhoff_deviator(), the explicit kernel's return mapping
// (power series of the isochoric trial strain where it is small, the
// spectral decomposition elsewhere), against the spectral return mapping of
// stress() (P F^T, its deviator) for Sn, Fe and Cu with linear hardening:
// from the virgin state and on from committed plastic states, for gradients
// from 1e-300 to 0.5 (elastic and plastic trial states, series and
// spectral paths) and stretches of 10. The deviators agree to 1e-12 of
// sigma0 + |tau| plus the round-off of the logarithmic strain (1e-14 E
// x_max / x_min), the updated states to 1e-12 (Cp^{-1}) and 1e-12 of eps_p
// plus 1e-15 (a plastic increment is the trial strain's excess over the
// yield strain, which carries the strain's round-off of about 1e-16).
#include <densify/material/j2_plasticity.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>

using namespace densify;

namespace
{
  using testing::random_gradient;
  using testing::uniform;

  struct Tally
  {
    unsigned int cases = 0, failed = 0, plastic = 0;
  };

  void
  check(const J2Plasticity &material,
        const J2Parameters &prm,
        const Tensor<2, 3> &F,
        const J2State      &committed,
        Tally              &tally)
  {
    J2State      spectral_state, series_state;
    Tensor<2, 3> P;
    material.stress(F, &committed, &spectral_state, P);
    const Tensor<2, 3>    tau = P * transpose(F);
    SymmetricTensor<2, 3> tau_dev;
    material.kirchhoff_deviator(F, &committed, &series_state, tau_dev);

    // the spectral deviator; the stretches for the round-off bound
    const double p     = trace(tau) / 3.;
    double       error = 0., size = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          const double reference = 0.5 * (tau[i][j] + tau[j][i]) - (i == j) * p;
          error = std::max(error, std::abs(tau_dev[i][j] - reference));
          size  = std::max(size, std::abs(tau[i][j]));
        }
    const auto be          = symmetrize(F * committed.Cp_inv * transpose(F));
    const auto x           = eigenvalues(be);
    double     state_error = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        state_error = std::max(state_error,
                               std::abs(series_state.Cp_inv[i][j] -
                                        spectral_state.Cp_inv[i][j]));
    const bool ok =
      error <= 1e-12 * (prm.sigma0 + size) + 1e-14 * prm.E * x[0] / x[2] &&
      state_error <= 1e-12 &&
      std::abs(series_state.eps_p - spectral_state.eps_p) <=
        1e-12 * spectral_state.eps_p + 1e-15;
    ++tally.cases;
    tally.plastic += (spectral_state.eps_p > committed.eps_p);
    if (!ok)
      {
        ++tally.failed;
        std::cerr << "differs for F = " << F << ": deviator " << error
                  << ", Cp^-1 " << state_error << ", eps_p "
                  << series_state.eps_p << " against " << spectral_state.eps_p
                  << std::endl;
      }
  }
} // namespace



int
main()
{
  std::uint64_t state  = 7;
  bool          all_ok = true;
  for (const std::string name : {"Sn", "Fe", "Cu"})
    {
      J2Parameters prm = material_preset(name);
      prm.hardening    = Hardening::linear;
      prm.H            = 0.01 * prm.E;
      const J2Plasticity material(prm);
      Tally              tally;
      for (const double g :
           {1e-300, 1e-100, 1e-12, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5})
        for (unsigned int n = 0; n < 50; ++n)
          {
            const Tensor<2, 3> F = random_gradient(state, g);
            if (!(determinant(F) > 0.2))
              continue;
            // from the virgin state
            check(material, prm, F, J2State(), tally);
            // from a committed plastic state (a large plastic step F0
            // first), on to F0 + (F - I), as a compaction goes on
            J2State            committed;
            Tensor<2, 3>       P;
            const Tensor<2, 3> F0 = random_gradient(state, 0.3);
            material.stress(F0, nullptr, &committed, P);
            const Tensor<2, 3> F1 =
              F0 + F - Tensor<2, 3>(unit_symmetric_tensor<3>());
            if (determinant(F1) > 0.2)
              check(material, prm, F1, committed, tally);
          }
      // stretches of 10 and 0.1: the spectral path
      for (unsigned int n = 0; n < 20; ++n)
        {
          Tensor<2, 3> F;
          F[0][0] = 10.;
          F[1][1] = 0.1 + 0.01 * uniform(state);
          F[2][2] = 1.;
          F[0][1] = 0.5 * uniform(state);
          check(material, prm, F, J2State(), tally);
        }
      std::cout << name << " with linear hardening: " << tally.cases
                << " states, plastic in more than a third: "
                << (3 * tally.plastic > tally.cases ? "yes" : "NO")
                << ", deviator and state equal the spectral return's: "
                << (tally.failed == 0 ? "yes" : "NO") << std::endl;
      all_ok = all_ok && tally.failed == 0 && 3 * tally.plastic > tally.cases;
    }
  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_ok ? 0 : 1;
}
