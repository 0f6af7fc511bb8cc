// Coulomb friction: stick below mu p, slip at mu p, by an elastic predictor
// and a return map with a penalty stick stiffness.
#pragma once

#include <densify/contact/friction_law.h>

namespace densify
{
  /**
   * Coulomb's rule: the trial traction P t_c - eps_t s sticks while
   * |trial| <= mu p and is returned to the cone mu p trial / |trial| when
   * it slips.
   */
  class CoulombSlip : public SlipRule
  {
  public:
    std::string
    name() const override;

    bool
    respond(const FrictionLaw  &law,
            const Tensor<2, 3> &P,
            const Tensor<1, 3> &s,
            const Tensor<1, 3> &committed_traction,
            const double        eps_t,
            const double        limit,
            ContactResponse    &r) const override;

    void
    derivatives(const FrictionLaw     &law,
                const ContactResponse &r,
                const Tensor<2, 3>    &P,
                const Tensor<1, 3>    &s,
                const Tensor<1, 3>    &committed_traction,
                const double           eps_t,
                FrictionTerms         &terms) const override;

    bool
    has_stick_spring() const override;
  };
} // namespace densify
