// Coulomb friction: the elastic predictor and the return map.
#include <deal.II/base/symmetric_tensor.h>

#include <densify/contact/coulomb_slip.h>

namespace densify
{
  std::string
  CoulombSlip::name() const
  {
    return "Coulomb";
  }



  bool
  CoulombSlip::respond(const FrictionLaw  &law,
                       const Tensor<2, 3> &P,
                       const Tensor<1, 3> &s,
                       const Tensor<1, 3> &committed_traction,
                       const double        eps_t,
                       const double        limit,
                       ContactResponse    &r) const
  {
    const Tensor<1, 3> trial = P * committed_traction - eps_t * s;
    const double       norm  = trial.norm();
    if (norm <= limit)
      {
        r.status   = ContactStatus::stick;
        r.traction = trial;
        r.stiffness += eps_t * P;
        return false;
      }
    const Tensor<1, 3> t_hat = trial / norm;
    r.traction               = limit * t_hat;
    if (law.consistent && !law.slip_secant)
      r.stiffness += eps_t * limit / norm * (P - outer_product(t_hat, t_hat));
    else
      // secant: t = (limit / |trial|) trial with the factor frozen; keeps
      // stiffness along the slip (the exact tangent has none there, which
      // lets a nearly free particle take huge sideways steps)
      r.stiffness += eps_t * limit / norm * P;
    return true;
  }



  void
  CoulombSlip::derivatives(const FrictionLaw     &law,
                           const ContactResponse &r,
                           const Tensor<2, 3>    &P,
                           const Tensor<1, 3>    &s,
                           const Tensor<1, 3>    &committed_traction,
                           const double           eps_t,
                           FrictionTerms         &terms) const
  {
    // t = trial (stick) or mu p trial / |trial| (slip), with
    // trial = P t_c - eps_t s
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    Tensor<2, 3>       A = I;
    if (r.status == ContactStatus::slip)
      {
        const Tensor<1, 3> trial = P * committed_traction - eps_t * s;
        const double       norm  = trial.norm();
        const Tensor<1, 3> t_hat = trial / norm;
        A                        = law.mu * r.pressure / norm *
            (law.consistent && !law.slip_secant ?
               I - outer_product(t_hat, t_hat) :
               I);
      }
    terms.dt_ds_committed = A;
    terms.dt_ds           = -eps_t * A;
  }



  bool
  CoulombSlip::has_stick_spring() const
  {
    return true;
  }
} // namespace densify
