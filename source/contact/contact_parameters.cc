// The subsection Contact: the normal penalty and its multipliers, the
// friction law and its tangent, where contact is evaluated.
#include <densify/contact/contact_parameters.h>
#include <densify/contact/friction_law.h>

namespace densify
{
  void
  declare_contact_parameters(ParameterHandler &prm, ContactParameters &contact)
  {
    prm.enter_subsection("Contact");
    {
      prm.add_parameter(
        "Penalty factor",
        contact.penalty_factor,
        "Augmented-Lagrangian penalty as a multiple of E/h (E the particle's "
        "Young's modulus in MPa, h the smallest element size in mm); "
        "dimensionless, > 0. The multiplier updates remove the penetration "
        "whatever its value. Larger: fewer multiplier updates, worse "
        "conditioned systems; change it when the updates do not reach Gap "
        "tolerance or Newton struggles.",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Gap tolerance",
        contact.gap_tolerance,
        "Largest penetration of a particle into a tool or another particle "
        "accepted at the end of a step, in mm (> 0, well below the element "
        "size); multipliers are updated until it is met. Smaller: more "
        "accurate contact, more updates. Explicit runs (no multiplier "
        "updates) print one warning at the first station above it.",
        Patterns::Double(1e-15));
      prm.add_parameter(
        "Maximum augmentations",
        contact.max_augmentations,
        "Maximum number of multiplier updates per load step (integer 0 to "
        "1000; 0: pure penalty). A step that ends above Gap tolerance prints "
        "a warning; raise it then.",
        Patterns::Integer(0, 1000));
      prm.add_parameter(
        "Friction coefficient",
        contact.friction_coefficient,
        "Coulomb friction coefficient mu between particles, and of every tool "
        "whose own Friction coefficient is 'default' (dimensionless, >= 0; "
        "the paper's scenes: 0.2). 0 switches friction off and costs "
        "nothing.",
        Patterns::Double(0.));
      prm.add_parameter(
        "Friction model",
        contact.friction_model,
        "'Coulomb': stick below mu p, slip at mu p (return map, penalty "
        "stick stiffness); 'arctangent': the paper's regularised law "
        "t = mu p (2/pi) atan(v/v0) against the sliding velocity v, for "
        "comparisons with the paper.",
        Patterns::Selection(slip_rule_names()));
      prm.add_parameter("Slip velocity",
                        contact.slip_velocity,
                        "v0 of the arctangent law, in mm/s (> 0): below it "
                        "the traction grows linearly with the velocity. "
                        "Smaller: closer to Coulomb, harder for Newton.",
                        Patterns::Double(1e-300));
      prm.add_parameter(
        "Tangential penalty factor",
        contact.tangential_penalty_factor,
        "Stick stiffness of Coulomb friction as a multiple of E/h "
        "(dimensionless, > 0): a sticking point slips elastically by "
        "t h / (factor E). Much stiffer than needed slows Newton where "
        "points slip.",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Friction tangent",
        contact.friction_tangent,
        "'symmetric': the slip tangent without its nonsymmetric coupling to "
        "the pressure and with the secant stiffness along the slip (CG "
        "works; Newton converges only linearly where points slip); "
        "'consistent': the exact one (quadratic Newton near slip, "
        "needs Solver/Linear solver = gmres-amg, gmres-lu, direct or auto); "
        "'secant-start': consistent, but each Newton solve's first "
        "iterations take the secant stiffness along the slip (where the "
        "exact tangent has none) until a correction moves no entry by more "
        "than a hundredth of half the smallest element size, which keeps a "
        "pore's slipping, yielding surface from huge corrections in dense "
        "packings; 'symmetric-secant-start': secant-start without the "
        "coupling to the pressure, symmetric for CG; 'auto' (keep it): "
        "secant-start, or symmetric-secant-start with Solver/Linear solver "
        "= cg-amg.",
        Patterns::Selection(
          "auto|symmetric|consistent|secant-start|symmetric-secant-start"));
      prm.add_parameter(
        "Geometric tangent",
        contact.geometric_tangent,
        "Whether the Newton tangent of particle-particle contact includes "
        "the rotation of the master facet's normal and the sliding of the "
        "projection point over the facet (doc/theory.md section 9). true: "
        "exact for P1 and P2 contact, quadratic Newton where contacts slide "
        "over facets, but nonsymmetric (needs Solver/Linear solver = "
        "gmres-amg, gmres-lu or direct); false: only eps n n^T and the "
        "friction law's stiffness; auto: true for frictionless particle "
        "contact unless the linear solver is cg-amg, false with friction. "
        "It changes how Newton converges, not the equations the converged "
        "state solves; where several equilibria lie near (the path of "
        "friction, an unstable frictionless packing) it can reach another "
        "one. Change it when Newton stalls on sliding contacts.",
        Patterns::Selection("auto|true|false"));
      prm.add_parameter(
        "Contact points",
        contact.contact_points,
        "Where contact with tools and other particles is evaluated on a "
        "particle's surface facets. 'vertices': at the facet corners (node "
        "to surface, weights area/3; a faceted sphere's pole touches first, "
        "so it is pressed without a spurious moment); 'Gauss points': at "
        "the facet's Gauss points (needed for P2, whose vertex weights "
        "vanish); 'auto' (keep it): vertices for P1, Gauss points for P2.",
        Patterns::Selection("auto|vertices|Gauss points"));
      prm.add_parameter(
        "Hold poles on axis",
        contact.hold_poles,
        "Springs (stiffness Penalty factor * E * h) against the free motions "
        "that frictionless contact leaves to a faceted sphere, which make "
        "Newton stall (doc/theory.md). true: the top and bottom pole "
        "vertices stay on the vertical line through the initial centre, "
        "for one sphere or a vertical stack between frictionless punches "
        "(in a stack one more spring per particle holds its spin about the "
        "vertical axis). vertical: the axis through each particle's poles "
        "stays vertical, the particle may move sideways, for frictionless "
        "layers symmetric about each particle's mid-plane. false: no "
        "springs. The springs' force is "
        "pole_force in statistics.csv; it vanishes for a state with that "
        "symmetry.",
        Patterns::Selection("false|true|vertical"));
    }
    prm.leave_subsection();
  }
} // namespace densify
