// Creation of the material law of a particle from its material name.
#pragma once

#include <densify/material/j2_plasticity.h>
#include <densify/material/material.h>
#include <densify/parameters.h>

#include <functional>
#include <memory>
#include <string>

namespace densify
{
  /**
   * A constitutive model, a value of Material/Model: its name, whether it
   * flows plastically (isochoric flow: the P1 locking remedy's auto choice
   * and the plastic history in the effects line), and how it builds the law
   * of one particle from the particle's constants (a preset's row or the
   * 'custom' entries: E, nu, yield stress, density, label) and the
   * subsection Material.
   */
  struct MaterialModel
  {
    /// The value of Material/Model.
    std::string name;
    /// Plastic, isochoric flow.
    bool plastic = false;
    /// The law of a particle; throws std::runtime_error naming the entry to
    /// fix where the subsection does not fit the model.
    std::function<std::shared_ptr<const Material>(const J2Parameters &,
                                                  const MaterialParameters &)>
      create;
  };

  /// The model named by the value @p model of Material/Model (one of
  /// material_model_names()); throws std::runtime_error for any other text.
  const MaterialModel &
  parse_material_model(const std::string &model);

  /**
   * Add @p model to the models parse_material_model() knows, under its name
   * (which must be new), so that a law defined outside Densify's sources (a
   * test, a program that links Densify) is a value of Material/Model in
   * parameters declared after this call.
   */
  void
  register_material_model(const MaterialModel &model);

  /// The names of the models, joined by @p separator.
  std::string
  material_model_names(const std::string &separator = "|");

  /// The hardening law named by the value @p hardening of Material/Hardening
  /// ("none", "linear" or "power law"); throws std::runtime_error for any
  /// other text.
  Hardening
  parse_hardening(const std::string &hardening);

  /**
   * The law for material @p name (a preset of material_presets() or
   * "custom", whose constants come from @p prm) under the model, kinematics
   * and hardening of @p prm: for the model elastic small-strain
   * LinearElastic or finite-strain Hencky elasticity (J2 with infinite
   * yield stress, no history), for J2 plasticity J2Plasticity, for a model
   * of register_material_model() what it creates. Throws
   * std::runtime_error naming the entry to fix.
   */
  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &prm);
} // namespace densify
