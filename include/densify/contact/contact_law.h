// The contact law at one contact point: augmented-Lagrangian normal pressure
// and Coulomb friction (return map or arctangent regularisation), shared by
// the tool contact and the particle-particle contact.
#pragma once

#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>

namespace densify
{
  using namespace dealii;

  /// How the tangential traction follows the slip.
  enum class FrictionModel
  {
    /// Coulomb stick/slip by an elastic-predictor / return map (penalty
    /// stick stiffness).
    coulomb,
    /// The paper's law: t = -mu p (2/pi) atan(|s| / delta) s/|s|, no stick.
    arctangent
  };

  /// Friction at one kind of contact.
  struct FrictionLaw
  {
    /// Coulomb coefficient mu (0: frictionless, every friction term skipped).
    double mu = 0.;
    /// Model.
    FrictionModel model = FrictionModel::coulomb;
    /// Regularisation slip delta of the arctangent law (mm per increment).
    double regularisation = 1e-4;
    /// Tangential (stick) penalty as a fraction of the normal penalty.
    double tangential_ratio = 1.;
    /// The exact tangent of the slip traction (no stiffness along the slip)
    /// and, with #pressure_coupling, its nonsymmetric coupling with the
    /// pressure (which needs a nonsymmetric linear solver).
    bool consistent = false;
    /// With #consistent: keep the coupling of the slip traction with the
    /// pressure (false: the symmetric rest of the consistent tangent, which
    /// CG can take; Contact/Friction tangent = symmetric-secant-start).
    bool pressure_coupling = true;
    /// With #consistent: along the slip direction the secant stiffness
    /// eps_t mu p / |trial| instead of the exact tangent's none (set for the
    /// first iterations of a Newton solve, NewtonControl::secant_start). The
    /// traction is the same either way.
    bool slip_secant = false;
  };

  /// Stick/slip state of a contact point (for output).
  enum class ContactStatus : unsigned char
  {
    open  = 0,
    stick = 1,
    slip  = 2
  };

  /// Response of the contact law at one point.
  struct ContactResponse
  {
    /// Normal pressure (MPa, >= 0).
    double pressure = 0.;
    /// Tangential traction on the slave side (MPa; orthogonal to n).
    Tensor<1, 3> traction;
    /// Stiffness: the derivative of -(p n + t) with respect to the relative
    /// displacement of the slave point against its partner (MPa/mm).
    Tensor<2, 3> stiffness;
    /// Open, stick or slip.
    ContactStatus status = ContactStatus::open;
  };

  /**
   * Evaluate the contact law. @p lambda: normal multiplier, @p gap: signed
   * normal gap (mm, negative when penetrating), @p eps: normal penalty,
   * @p n: unit normal pointing from the partner to the slave point,
   * @p committed_traction: tangential traction at the end of the last
   * accepted increment, @p slip_increment: relative displacement of the slave
   * point against its partner since then (mm; its tangential part is used),
   * @p eps_t: tangential (stick) penalty. The traction on the slave is
   * p n + t; Newton's residual gets -(p n + t) . phi.
   */
  inline ContactResponse
  evaluate_contact_law(const double        lambda,
                       const double        gap,
                       const double        eps,
                       const Tensor<1, 3> &n,
                       const Tensor<1, 3> &committed_traction,
                       const Tensor<1, 3> &slip_increment,
                       const double        eps_t,
                       const FrictionLaw  &friction)
  {
    ContactResponse r;
    r.pressure = std::max(0., lambda - eps * gap);
    if (r.pressure <= 0.)
      return r;
    // frictionless contact slides freely
    r.status    = ContactStatus::slip;
    r.stiffness = eps * outer_product(n, n);
    if (friction.mu <= 0.)
      return r;

    const Tensor<2, 3> P     = unit_symmetric_tensor<3>() - outer_product(n, n);
    const Tensor<1, 3> s     = P * slip_increment;
    const double       limit = friction.mu * r.pressure;
    if (friction.model == FrictionModel::coulomb)
      {
        const Tensor<1, 3> trial = P * committed_traction - eps_t * s;
        const double       norm  = trial.norm();
        if (norm <= limit)
          {
            r.status   = ContactStatus::stick;
            r.traction = trial;
            r.stiffness += eps_t * P;
            return r;
          }
        const Tensor<1, 3> t_hat = trial / norm;
        r.traction               = limit * t_hat;
        if (friction.consistent && !friction.slip_secant)
          r.stiffness +=
            eps_t * limit / norm * (P - outer_product(t_hat, t_hat));
        else
          // secant: t = (limit / |trial|) trial with the factor frozen; keeps
          // stiffness along the slip (the exact tangent has none there,
          // which lets a nearly free particle take huge sideways steps)
          r.stiffness += eps_t * limit / norm * P;
      }
    else
      {
        const double delta = friction.regularisation;
        const double slip  = s.norm();
        const double c     = limit * 2. / numbers::PI;
        if (slip <= 1e-14 * delta)
          {
            // the limit slip -> 0 of the law below
            r.stiffness += c / delta * P;
            return r;
          }
        const Tensor<1, 3> s_hat = s / slip;
        const double       a     = std::atan(slip / delta);
        r.traction               = -c * a * s_hat;
        r.stiffness +=
          c * (1. / delta / (1. + (slip / delta) * (slip / delta)) *
                 outer_product(s_hat, s_hat) +
               a / slip * (P - outer_product(s_hat, s_hat)));
      }
    // t is proportional to p, and dp = -eps dg: the coupling (eps/p) t n^T
    // of the consistent tangent is not symmetric
    if (friction.consistent && friction.pressure_coupling)
      r.stiffness += eps / r.pressure * outer_product(r.traction, n);
    return r;
  }



  /**
   * How the friction traction t at a contact point depends on the
   * tangential slip s = P delta (P = I - n n) and the pressure p, for the
   * geometric tangent terms: dt = dt_ds ds + dt_ds_committed dP t_c
   * + dt_dp dp.
   */
  struct FrictionTerms
  {
    /// Derivative of t by s (a 3D s: also its part along n).
    Tensor<2, 3> dt_ds;
    /// Derivative of t by the projected committed traction P t_c (Coulomb's
    /// trial P t_c - eps_t s; zero for the arctangent law).
    Tensor<2, 3> dt_ds_committed;
    /// Derivative of t by p (t/p where slipping and consistent, else 0).
    Tensor<1, 3> dt_dp;
    /// The committed traction t_c.
    Tensor<1, 3> committed;
    /// The relative displacement delta since the committed state.
    Tensor<1, 3> delta;
  };



  /**
   * The derivatives of the friction traction of evaluate_contact_law()
   * (response @p r with a pressure > 0, normal @p n, committed traction
   * @p committed, relative displacement @p delta, stick penalty @p eps_t,
   * law @p law) that friction_traction_change() needs.
   */
  inline FrictionTerms
  friction_terms(const ContactResponse &r,
                 const Tensor<1, 3>    &n,
                 const Tensor<1, 3>    &committed,
                 const Tensor<1, 3>    &delta,
                 const double           eps_t,
                 const FrictionLaw     &law)
  {
    FrictionTerms      terms;
    const double       p = r.pressure;
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    const Tensor<2, 3> P = I - outer_product(n, n);
    const Tensor<1, 3> s = P * delta;
    terms.committed      = committed;
    terms.delta          = delta;
    if (law.model == FrictionModel::coulomb)
      {
        // t = trial (stick) or mu p trial / |trial| (slip), with
        // trial = P t_c - eps_t s
        Tensor<2, 3> A = I;
        if (r.status == ContactStatus::slip)
          {
            const Tensor<1, 3> trial = P * committed - eps_t * s;
            const double       norm  = trial.norm();
            const Tensor<1, 3> t_hat = trial / norm;
            A                        = law.mu * p / norm *
                (law.consistent && !law.slip_secant ?
                   I - outer_product(t_hat, t_hat) :
                   I);
          }
        terms.dt_ds_committed = A;
        terms.dt_ds           = -eps_t * A;
      }
    else
      {
        // t = -c atan(|s| / delta) s / |s|, c = 2 mu p / pi
        const double c     = law.mu * p * 2. / numbers::PI;
        const double slip  = s.norm();
        const double scale = law.regularisation;
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
    if (law.consistent && law.pressure_coupling &&
        r.status == ContactStatus::slip)
      terms.dt_dp = r.traction / p;
    return terms;
  }



  /**
   * The change of the friction traction described by @p terms when the
   * normal @p n turns by @p dn, the relative displacement changes by
   * @p ddelta beyond the motion of the two points themselves (which the
   * law's stiffness covers; for particle contact the sliding of the master
   * point) and the pressure by @p dp beyond -eps n . (that motion). With
   * P = I - n n: dP v = -(dn (n . v) + n (dn . v)),
   * ds = dP delta + P ddelta, dt = dt_ds ds + dt_ds_committed dP t_c
   * + dt_dp dp (doc/theory.md section 9).
   */
  inline Tensor<1, 3>
  friction_traction_change(const FrictionTerms &terms,
                           const Tensor<1, 3>  &n,
                           const Tensor<1, 3>  &dn,
                           const Tensor<1, 3>  &ddelta,
                           const double         dp)
  {
    const auto dP = [&](const Tensor<1, 3> &v) {
      return -(dn * (n * v) + n * (dn * v));
    };
    const Tensor<1, 3> ds = dP(terms.delta) + (ddelta - (ddelta * n) * n);
    return terms.dt_ds * ds + terms.dt_ds_committed * dP(terms.committed) +
           terms.dt_dp * dp;
  }
} // namespace densify
