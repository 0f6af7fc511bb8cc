// The paper's regularised friction: t = -mu p (2/pi) atan(|s| / delta) s/|s|,
// no stick state and no stick spring.
#pragma once

#include <densify/contact/friction_law.h>

namespace densify
{
  /**
   * The arctangent rule of the reference paper: the traction opposes the
   * slip s with the magnitude mu p (2/pi) atan(|s| / delta), delta the
   * regularisation slip of the increment (FrictionLaw::regularisation); it
   * approaches Coulomb's mu p for |s| >> delta.
   */
  class ArctangentSlip : public SlipRule
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
