// Small-strain isotropic linear elasticity.
#include <densify/material/material.h>

namespace densify
{
  LinearElastic::LinearElastic(const double       E,
                               const double       nu,
                               const std::string &label,
                               const double       density)
    : E(E)
    , nu(nu)
    , lambda(E * nu / ((1. + nu) * (1. - 2. * nu)))
    , mu(E / (2. * (1. + nu)))
    , rho(density)
    , label(label)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            C[i][j][k][l] = lambda * (i == j) * (k == l) +
                            mu * ((i == k) * (j == l) + (i == l) * (j == k));
  }



  std::string
  LinearElastic::name() const
  {
    return "linear elastic, small strain (" + label + ")";
  }



  void
  LinearElastic::evaluate(const Tensor<2, 3> &F,
                          const MaterialState *,
                          MaterialState *,
                          Tensor<2, 3> &P,
                          Tensor<4, 3> &A) const
  {
    const Tensor<2, 3> H   = F - unit_symmetric_tensor<3>();
    const double       tr  = trace(H);
    const Tensor<2, 3> eps = 0.5 * (H + transpose(H));
    P                      = 2. * mu * eps;
    for (unsigned int i = 0; i < 3; ++i)
      P[i][i] += lambda * tr;
    A = C;
  }
} // namespace densify
