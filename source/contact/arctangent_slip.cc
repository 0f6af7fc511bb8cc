// The arctangent friction law of the reference paper.
#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>

#include <densify/contact/arctangent_slip.h>

#include <cmath>

namespace densify
{
  std::string
  ArctangentSlip::name() const
  {
    return "arctangent";
  }



  bool
  ArctangentSlip::respond(const FrictionLaw  &law,
                          const Tensor<2, 3> &P,
                          const Tensor<1, 3> &s,
                          const Tensor<1, 3> & /*committed_traction*/,
                          const double /*eps_t*/,
                          const double     limit,
                          ContactResponse &r) const
  {
    const double delta = law.regularisation;
    const double slip  = s.norm();
    const double c     = limit * 2. / numbers::PI;
    if (slip <= 1e-14 * delta)
      {
        // the limit slip -> 0 of the law below
        r.stiffness += c / delta * P;
        return false;
      }
    const Tensor<1, 3> s_hat = s / slip;
    const double       a     = std::atan(slip / delta);
    r.traction               = -c * a * s_hat;
    r.stiffness += c * (1. / delta / (1. + (slip / delta) * (slip / delta)) *
                          outer_product(s_hat, s_hat) +
                        a / slip * (P - outer_product(s_hat, s_hat)));
    return true;
  }



  void
  ArctangentSlip::derivatives(const FrictionLaw     &law,
                              const ContactResponse &r,
                              const Tensor<2, 3> & /*P*/,
                              const Tensor<1, 3> &s,
                              const Tensor<1, 3> & /*committed_traction*/,
                              const double /*eps_t*/,
                              FrictionTerms &terms) const
  {
    // t = -c atan(|s| / delta) s / |s|, c = 2 mu p / pi
    const Tensor<2, 3> I     = unit_symmetric_tensor<3>();
    const double       c     = law.mu * r.pressure * 2. / numbers::PI;
    const double       slip  = s.norm();
    const double       scale = law.regularisation;
    if (slip <= 1e-14 * scale)
      terms.dt_ds = -c / scale * I;
    else
      {
        const Tensor<1, 3> s_hat = s / slip;
        const double       a     = std::atan(slip / scale);
        const Tensor<2, 3> ss    = outer_product(s_hat, s_hat);
        terms.dt_ds =
          -c * (1. / scale / (1. + (slip / scale) * (slip / scale)) * ss +
                a / slip * (I - ss));
      }
  }



  bool
  ArctangentSlip::has_stick_spring() const
  {
    return false;
  }
} // namespace densify
