// The friction law of a contact pair: its coefficient, stick penalty and
// tangent options, and the slip rule (how the traction follows the slip) as
// a class of its own, so that a new law adds files and touches none of the
// contact code.
#pragma once

#include <deal.II/base/tensor.h>

#include <memory>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

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

  struct FrictionLaw;

  /**
   * A slip rule: the tangential traction of a pressed contact point as a
   * function of its slip, and the traction's derivatives. One object per
   * rule, shared by the contact pairs that use it (FrictionLaw::slip); the
   * rules are listed in slip_rule().
   */
  class SlipRule
  {
  public:
    /// Destructor.
    virtual ~SlipRule() = default;

    /// The rule's name in Contact/Friction model and in the effects line.
    virtual std::string
    name() const = 0;

    /**
     * Set the traction and the status of @p r and add the traction's
     * derivative to @p r.stiffness, at a point with the pressure
     * @p r.pressure > 0 and the friction limit @p limit = mu p. @p P: the
     * tangential projector I - n n, @p s: the tangential slip since the
     * committed state, @p committed_traction: the traction there, @p eps_t:
     * the stick penalty, @p law: the pair's law (its tangent options).
     * Returns whether the traction is proportional to the pressure, so that
     * the consistent tangent couples the two.
     */
    virtual bool
    respond(const FrictionLaw  &law,
            const Tensor<2, 3> &P,
            const Tensor<1, 3> &s,
            const Tensor<1, 3> &committed_traction,
            const double        eps_t,
            const double        limit,
            ContactResponse    &r) const = 0;

    /**
     * Set FrictionTerms::dt_ds and FrictionTerms::dt_ds_committed of
     * @p terms for the response @p r (arguments as in respond()).
     */
    virtual void
    derivatives(const FrictionLaw     &law,
                const ContactResponse &r,
                const Tensor<2, 3>    &P,
                const Tensor<1, 3>    &s,
                const Tensor<1, 3>    &committed_traction,
                const double           eps_t,
                FrictionTerms         &terms) const = 0;

    /// Whether the traction is held by an elastic stick spring, which stores
    /// |t|^2 / (2 eps_t) (false: all the slip work is dissipated).
    virtual bool
    has_stick_spring() const = 0;
  };

  /// The slip rule named @p name (one of slip_rule_names()); throws for an
  /// unknown name.
  std::shared_ptr<const SlipRule>
  slip_rule(const std::string &name);

  /**
   * Add @p rule to the rules slip_rule() knows, under its name (which must
   * be new), so that a rule defined outside Densify's sources (a test, a
   * program that links Densify) is a value of Contact/Friction model in
   * parameters declared after this call.
   */
  void
  register_slip_rule(std::shared_ptr<const SlipRule> rule);

  /// The names of the slip rules, as a Patterns::Selection lists them.
  std::string
  slip_rule_names();

  /// The friction of one kind of contact.
  struct FrictionLaw
  {
    /// Coulomb coefficient mu (0: frictionless, every friction term skipped).
    double mu = 0.;
    /// How the traction follows the slip (Coulomb by default).
    std::shared_ptr<const SlipRule> slip = slip_rule("Coulomb");
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

    /**
     * The elastic energy of a contact point per unit area: the potential
     * p^2 / 2 eps of p = max(0, lambda - eps g) and, where friction acts
     * (@p rough) and the rule has one, the stick spring's
     * |t|^2 / (2 eps_t) with eps_t = #tangential_ratio eps.
     */
    double
    elastic_energy(const ContactResponse &r,
                   const double           eps,
                   const bool             rough) const
    {
      const double p = r.pressure;
      return 0.5 *
             (p * p + (rough && slip->has_stick_spring() ?
                         r.traction.norm_square() / tangential_ratio :
                         0.)) /
             eps;
    }

    /**
     * The slip against which the traction @p traction works irreversibly:
     * the tangential slip @p tangential_slip less the stick spring's elastic
     * part (t - t_c) / eps_t where the rule has a spring, with the committed
     * traction @p committed and eps_t = #tangential_ratio @p eps.
     */
    Tensor<1, 3>
    dissipating_slip(const Tensor<1, 3> &tangential_slip,
                     const Tensor<1, 3> &traction,
                     const Tensor<1, 3> &committed,
                     const double        eps) const
    {
      return slip->has_stick_spring() ?
               Tensor<1, 3>(tangential_slip +
                            (traction - committed) / (tangential_ratio * eps)) :
               tangential_slip;
    }
  };
} // namespace densify
