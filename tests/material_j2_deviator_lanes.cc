// J2Plasticity::kirchhoff_deviators(), four points side by side in SIMD
// lanes, against kirchhoff_deviator() point by point, for Sn, Fe and Cu
// perfectly plastic (the presets), with linear and with power-law hardening:
// a list of 1,003 points (not a multiple of the lanes) that mixes virgin and
// committed plastic states, gradients from 1e-300 to 0.5 (elastic and
// plastic trial states, the series path) and stretches of 10 (the spectral
// path), shuffled so that the lanes of one batch take different paths. The
// deviators agree to 1e-13 of sigma0 + |tau_dev| (the lanes run the series
// with the largest number of terms any lane needs, whose extra terms are
// below 1e-17), the updated states to 1e-13 (Cp^{-1}) and 1e-13 of eps_p plus
// 1e-16; a point without a state to update (trial nullptr) gets the same
// deviator.
#include <densify/material/j2_plasticity.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

using namespace densify;
using testing::random_gradient;
using testing::uniform;



int
main()
{
  std::uint64_t state  = 11;
  bool          all_ok = true;
  for (const std::string name : {"Sn", "Fe", "Cu"})
    for (const Hardening hardening :
         {Hardening::none, Hardening::linear, Hardening::power_law})
      {
        J2Parameters prm = material_preset(name);
        prm.hardening    = hardening;
        prm.H            = 0.01 * prm.E;
        prm.K            = 2. * prm.sigma0;
        prm.n            = 0.4;
        const J2Plasticity material(prm);

        // the points: gradients and committed states
        std::vector<Tensor<2, 3>> F;
        std::vector<J2State>      committed;
        const unsigned int        n_points = 1003;
        const double              sizes[]  = {
                        1e-300, 1e-100, 1e-12, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5};
        while (F.size() < n_points)
          {
            const double r = 0.5 * (uniform(state) + 1.);
            Tensor<2, 3> G;
            if (r < 0.05)
              {
                // a stretch of 10 and of 0.1
                G[0][0] = 10.;
                G[1][1] = 0.1 + 0.01 * uniform(state);
                G[2][2] = 1.;
                G[0][1] = 0.5 * uniform(state);
              }
            else
              G = random_gradient(
                state, sizes[std::min<unsigned int>(8, 9 * (r - 0.05) / 0.95)]);
            J2State old;
            if (uniform(state) > 0.)
              {
                // a committed plastic state, and F on from it
                Tensor<2, 3>       P;
                const Tensor<2, 3> F0 = random_gradient(state, 0.3);
                material.stress(F0, nullptr, &old, P);
                G += F0 - Tensor<2, 3>(unit_symmetric_tensor<3>());
              }
            if (!(determinant(G) > 0.2))
              continue;
            F.push_back(G);
            committed.push_back(old);
          }

        // point by point, and in lanes (with and without the states)
        std::vector<J2State>               one(n_points), lanes(n_points);
        std::vector<SymmetricTensor<2, 3>> tau_one(n_points),
          tau_lanes(n_points), tau_stateless(n_points);
        std::vector<const Tensor<2, 3> *>    F_of(n_points);
        std::vector<const MaterialState *>   old_of(n_points);
        std::vector<MaterialState *>         lanes_of(n_points);
        std::vector<SymmetricTensor<2, 3> *> tau_lanes_of(n_points),
          tau_stateless_of(n_points);
        unsigned int plastic = 0;
        for (unsigned int k = 0; k < n_points; ++k)
          {
            material.kirchhoff_deviator(F[k],
                                        &committed[k],
                                        &one[k],
                                        tau_one[k]);
            F_of[k]             = &F[k];
            old_of[k]           = &committed[k];
            lanes_of[k]         = &lanes[k];
            tau_lanes_of[k]     = &tau_lanes[k];
            tau_stateless_of[k] = &tau_stateless[k];
            plastic += (one[k].eps_p > committed[k].eps_p);
          }
        material.kirchhoff_deviators(n_points,
                                     F_of.data(),
                                     old_of.data(),
                                     lanes_of.data(),
                                     tau_lanes_of.data());
        material.kirchhoff_deviators(n_points,
                                     F_of.data(),
                                     old_of.data(),
                                     nullptr,
                                     tau_stateless_of.data());

        unsigned int failed = 0;
        for (unsigned int k = 0; k < n_points; ++k)
          {
            const double bound       = 1e-13 * (prm.sigma0 + tau_one[k].norm());
            const double error       = (tau_lanes[k] - tau_one[k]).norm();
            double       state_error = 0.;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                state_error = std::max(state_error,
                                       std::abs(lanes[k].Cp_inv[i][j] -
                                                one[k].Cp_inv[i][j]));
            const bool ok = error <= bound &&
                            tau_stateless[k] == tau_lanes[k] &&
                            state_error <= 1e-13 &&
                            std::abs(lanes[k].eps_p - one[k].eps_p) <=
                              1e-13 * one[k].eps_p + 1e-16;
            if (!ok)
              {
                ++failed;
                std::cerr << name << ": point " << k << " differs: deviator "
                          << error << " (bound " << bound << "), Cp^-1 "
                          << state_error << ", eps_p " << lanes[k].eps_p
                          << " against " << one[k].eps_p << std::endl;
              }
          }
        std::cout << name << ", " << hardening_name(hardening) << ": "
                  << n_points << " points, plastic in more than a third: "
                  << (3 * plastic > n_points ? "yes" : "NO")
                  << ", lanes equal the point-by-point return: "
                  << (failed == 0 ? "yes" : "NO") << std::endl;
        all_ok = all_ok && failed == 0 && 3 * plastic > n_points;
      }
  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_ok ? 0 : 1;
}
