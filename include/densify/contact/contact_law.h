// The contact law at one contact point: augmented-Lagrangian normal pressure
// and the friction of the pair's slip rule (friction_law.h), shared by the
// tool contact and the particle-particle contact.
#pragma once

#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <densify/contact/friction_law.h>

#include <algorithm>
#include <cmath>

namespace densify
{
  using namespace dealii;

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
    if (!friction.slip->respond(
          friction, P, s, committed_traction, eps_t, limit, r))
      return r;
    // t is proportional to p, and dp = -eps dg: the coupling (eps/p) t n^T
    // of the consistent tangent is not symmetric
    if (friction.consistent && friction.pressure_coupling)
      r.stiffness += eps / r.pressure * outer_product(r.traction, n);
    return r;
  }



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
    law.slip->derivatives(law, r, P, s, committed, eps_t, terms);
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
