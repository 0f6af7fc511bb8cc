// Creation of the material law of a particle from its material name.
#include <densify/material/factory.h>
#include <densify/material/j2_plasticity.h>

#include <stdexcept>

namespace densify
{
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &custom)
  {
    if (name == "custom")
      return std::make_shared<LinearElastic>(custom.youngs_modulus,
                                             custom.poissons_ratio,
                                             name);
    try
      {
        // the elastic constants of the presets (sources in doc/materials.md)
        const J2Parameters preset = material_preset(name);
        return std::make_shared<LinearElastic>(preset.E, preset.nu, name);
      }
    catch (const std::invalid_argument &)
      {
        throw std::runtime_error(
          "unknown material '" + name +
          "' (Particles/Materials or the particle file): use Sn, Fe, Cu or "
          "custom");
      }
  }
} // namespace densify
