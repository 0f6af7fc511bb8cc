// The subsection Material: the constitutive model, its hardening and the
// constants of the material 'custom'.
#include <densify/material/factory.h>
#include <densify/material/material_parameters.h>

namespace densify
{
  void
  declare_material_parameters(ParameterHandler   &prm,
                              MaterialParameters &material)
  {
    prm.enter_subsection("Material");
    {
      prm.add_parameter(
        "Model",
        material.model,
        "Constitutive model of every particle: elastic (isotropic, "
        "small-strain linear or finite-strain Hencky) or J2 plasticity "
        "(finite-strain von Mises elastoplasticity, Simo 1992; "
        "doc/theory.md). The material of each particle (Sn, Fe, Cu, custom) "
        "gives E, nu and the yield stress. J2 plasticity (needs Finite "
        "strain = true) is for compaction: single particles and layers of "
        "touching particles in a die (prm/single_layer_sn.prm); elastic for "
        "small deformations and verification (prm/hertz.prm).",
        Patterns::Selection(material_model_names()));
      prm.add_parameter(
        "Finite strain",
        material.finite_strain,
        "true: finite-strain kinematics (large rotations, Hencky strain), "
        "needed by J2 plasticity and by any large deformation. false: "
        "small-strain linear elasticity (Model = elastic only), for small "
        "deformations such as checks against linear theory.");
      prm.add_parameter(
        "Hardening",
        material.hardening,
        "Isotropic hardening of every J2 material, presets included: none "
        "(perfectly plastic, as the presets' data), linear (sigma_y = "
        "sigma0 + H eps_p, Hardening modulus) or power law (sigma_y = "
        "sigma0 + K eps_p^n, Hardening coefficient and exponent); for a "
        "powder that work-hardens.",
        Patterns::Selection("none|linear|power law"));
      prm.add_parameter("Yield stress",
                        material.yield_stress,
                        "Initial yield stress sigma0 of the material 'custom', "
                        "in MPa (> 0); the presets carry their own "
                        "(doc/materials.md).",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening modulus",
                        material.hardening_modulus,
                        "Linear hardening modulus H, in MPa (>= 0); "
                        "Hardening = linear only.",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening coefficient",
                        material.hardening_coefficient,
                        "Power-law hardening coefficient K, in MPa (>= 0); "
                        "Hardening = power law only.",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening exponent",
                        material.hardening_exponent,
                        "Power-law hardening exponent n (dimensionless, > 0); "
                        "Hardening = power law only.",
                        Patterns::Double(1e-6));
      prm.add_parameter(
        "Young's modulus",
        material.youngs_modulus,
        "Young's modulus of the material 'custom', in MPa (> 0, at most "
        "1e7). The presets Sn, Fe and Cu carry their own values "
        "(doc/materials.md).",
        Patterns::Double(1e-12));
      prm.add_parameter("Poisson's ratio",
                        material.poissons_ratio,
                        "Poisson's ratio of the material 'custom' "
                        "(dimensionless, -1 < nu < 0.5); the presets carry "
                        "their own.",
                        Patterns::Double(-0.999, 0.499));
      prm.add_parameter(
        "Density",
        material.density,
        "Mass density of the material 'custom', in t/mm^3 (7.29e-9 is tin); "
        "used by Solver/Method = explicit only. The presets carry their own "
        "values (doc/materials.md).",
        Patterns::Double(1e-15, 1e-3));
    }
    prm.leave_subsection();
  }
} // namespace densify
