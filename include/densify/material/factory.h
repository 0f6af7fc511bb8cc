// Creation of the material law of a particle from its material name.
#pragma once

#include <densify/material/material.h>
#include <densify/parameters.h>

#include <memory>
#include <string>

namespace densify
{
  /**
   * The law for material @p name ("Sn", "Fe", "Cu" or "custom", whose
   * constants come from @p custom). Throws std::runtime_error naming the
   * allowed names for anything else.
   */
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &custom);
} // namespace densify
