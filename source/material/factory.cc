// Creation of the material law of a particle from its material name.
#include <densify/material/factory.h>

#include <stdexcept>

namespace densify
{
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &custom)
  {
    // Elastic constants (MPa, -); sources in doc/materials.md.
    if (name == "Sn")
      return std::make_shared<LinearElastic>(43120., 0.3, name);
    if (name == "Fe")
      return std::make_shared<LinearElastic>(211000., 0.29, name);
    if (name == "Cu")
      return std::make_shared<LinearElastic>(117000., 0.34, name);
    if (name == "custom")
      return std::make_shared<LinearElastic>(custom.youngs_modulus,
                                             custom.poissons_ratio,
                                             name);
    throw std::runtime_error("unknown material '" + name +
                             "' (Particles/Materials or the particle file): "
                             "use Sn, Fe, Cu or custom");
  }
} // namespace densify
