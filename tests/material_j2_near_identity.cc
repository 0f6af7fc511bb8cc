// J2Plasticity at deformation gradients within round-off of the identity,
// as the far field of an explicit run has them in its first steps (the
// displacement gradient of a cell the first waves barely reached is
// 1e-131 there): the stress is finite and equals the linear-elastic stress
// C : sym(grad u) to 1e-6 relative, down to gradients of 1e-300 and at the
// identity itself, for the stress alone and for the stress with its tangent.
// The law resolves strains to the round-off of the logarithm of a stretch
// (1e-16), so the stress is compared to 1e-6 of the linear one plus 1e-16 E.
#include <densify/material/j2_plasticity.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

using namespace densify;

int
main()
{
  J2Parameters prm = material_preset("Sn");
  J2Plasticity material(prm);
  const double lambda = prm.E * prm.nu / ((1. + prm.nu) * (1. - 2. * prm.nu));
  const double mu     = prm.E / (2. * (1. + prm.nu));
  // a gradient with unequal entries, as in the explicit run's cell
  Tensor<2, 3> M;
  const double entries[3][3] = {{1.0, 2.16632, -3.58148},
                                {-4.11261, -0.7, -16.1238},
                                {2.57092, -6.09677, 0.4}};
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      M[i][j] = entries[i][j];
  bool all_ok = true;
  for (const double delta :
       {1e-8, 1e-50, 1e-100, 1e-131, 1e-150, 1e-200, 1e-300, 0.})
    for (const bool with_tangent : {false, true})
      {
        const Tensor<2, 3> F =
          Tensor<2, 3>(unit_symmetric_tensor<3>()) + delta * M;
        Tensor<2, 3>  P;
        Tensor<4, 3>  A;
        J2State       trial;
        const J2State committed;
        if (with_tangent)
          material.evaluate(F, &committed, &trial, P, A);
        else
          material.stress(F, &committed, &trial, P);
        // linear elasticity: sigma = lambda tr(eps) I + 2 mu eps
        const Tensor<2, 3> eps = 0.5 * (M + transpose(M));
        const Tensor<2, 3> linear =
          delta *
          (lambda * trace(eps) * Tensor<2, 3>(unit_symmetric_tensor<3>()) +
           2. * mu * eps);
        const bool finite =
          std::isfinite(P.norm()) && std::isfinite(trial.eps_p);
        double error = 0., size = 0.;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              error = std::max(error, std::abs(P[i][j] - linear[i][j]));
              size  = std::max(size, std::abs(linear[i][j]));
            }
        const bool close = finite && error <= 1e-6 * size + 1e-16 * prm.E;
        all_ok           = all_ok && close;
        std::cout << "grad u = " << std::setw(6) << delta << " M"
                  << (with_tangent ? ", with tangent" : ", stress alone")
                  << ": finite " << (finite ? "yes" : "NO")
                  << ", linear-elastic stress: " << (close ? "yes" : "NO")
                  << std::endl;
      }
  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_ok ? 0 : 1;
}
