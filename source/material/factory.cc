// Creation of the material law of a particle from its material name.
#include <densify/material/factory.h>
#include <densify/material/j2_plasticity.h>

#include <limits>
#include <stdexcept>

namespace densify
{
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &prm)
  {
    J2Parameters j2;
    if (name == "custom")
      {
        j2.E       = prm.youngs_modulus;
        j2.nu      = prm.poissons_ratio;
        j2.sigma0  = prm.yield_stress;
        j2.density = prm.density;
        j2.label   = name;
      }
    else
      try
        {
          // the presets (sources in doc/materials.md)
          j2 = material_preset(name);
        }
      catch (const std::invalid_argument &)
        {
          throw std::runtime_error(
            "unknown material '" + name +
            "' (Particles/Materials or the particle file): use Sn, Fe, Cu or "
            "custom");
        }

    if (!prm.finite_strain)
      {
        if (prm.model != "elastic")
          throw std::runtime_error(
            "Material/Finite strain = false needs Material/Model = elastic: "
            "J2 plasticity is implemented at finite strain only");
        return std::make_shared<LinearElastic>(j2.E, j2.nu, name, j2.density);
      }
    if (prm.model == "elastic")
      j2.sigma0 = std::numeric_limits<double>::infinity();
    else if (prm.hardening == "linear")
      {
        j2.hardening = Hardening::linear;
        j2.H         = prm.hardening_modulus;
      }
    else if (prm.hardening == "power law")
      {
        j2.hardening = Hardening::power_law;
        j2.K         = prm.hardening_coefficient;
        j2.n         = prm.hardening_exponent;
      }
    try
      {
        return std::make_shared<J2Plasticity>(j2);
      }
    catch (const std::invalid_argument &e)
      {
        throw std::runtime_error(std::string(e.what()) +
                                 " (subsection Material)");
      }
  }
} // namespace densify
