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
   * constants come from @p prm) under the model, kinematics and hardening of
   * @p prm: small-strain LinearElastic, finite-strain Hencky elasticity (J2
   * with infinite yield stress, no history) or J2Plasticity. Throws
   * std::runtime_error naming the entry to fix.
   */
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &prm);
} // namespace densify
