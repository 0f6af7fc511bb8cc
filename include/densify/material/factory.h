// Creation of the material law of a particle from its material name.
#pragma once

#include <densify/material/j2_plasticity.h>
#include <densify/material/material.h>
#include <densify/parameters.h>

#include <memory>
#include <string>

namespace densify
{
  /// The constitutive model of every particle (Material/Model).
  enum class MaterialModel
  {
    /// "elastic": small-strain linear or finite-strain Hencky elasticity.
    elastic,
    /// "J2 plasticity": finite-strain J2Plasticity.
    j2_plasticity
  };

  /// The model named by the value @p model of Material/Model ("elastic" or
  /// "J2 plasticity"); throws std::runtime_error for any other text.
  MaterialModel
  parse_material_model(const std::string &model);

  /// The hardening law named by the value @p hardening of Material/Hardening
  /// ("none", "linear" or "power law"); throws std::runtime_error for any
  /// other text.
  Hardening
  parse_hardening(const std::string &hardening);

  /**
   * The law for material @p name (a preset of material_presets() or
   * "custom", whose constants come from @p prm) under the model, kinematics
   * and hardening of @p prm: small-strain LinearElastic, finite-strain
   * Hencky elasticity (J2 with infinite yield stress, no history) or
   * J2Plasticity. Throws std::runtime_error naming the entry to fix.
   */
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &prm);
} // namespace densify
