// The material presets: the constants of named metals, one table.
#pragma once

#include <deal.II/base/array_view.h>

#include <string>

namespace densify
{
  using namespace dealii;

  /**
   * One row of the preset table (source/material/presets.cc,
   * doc/materials.md): the constants of a named metal. Presets are perfectly
   * plastic; Material/Hardening adds hardening to them. Units mm, N, MPa.
   */
  struct MaterialPreset
  {
    /// Name in Particles/Materials or a particle file, e.g. "Sn".
    const char *name;
    /// Young's modulus E (MPa).
    double E;
    /// Poisson's ratio nu (-).
    double nu;
    /// Initial yield stress sigma0 (MPa).
    double sigma0;
    /// Mass density (t/mm^3).
    double density;
    /// Where E, nu, sigma0 and the density come from.
    const char *source;
  };

  /// Name of the material whose constants come from subsection Material.
  inline constexpr char custom_material_name[] = "custom";

  /// The rows of the preset table, in the order of the table.
  ArrayView<const MaterialPreset>
  material_presets();

  /// The row named @p name (case-sensitive), or nullptr if the table has
  /// none ("custom" included).
  const MaterialPreset *
  find_material_preset(const std::string &name);

  /**
   * The names a particle's material may take, for error messages: the
   * presets in table order, then "custom", separated by ", " except for
   * @p last_separator before "custom". E.g. "Sn, Fe, Cu or custom" for
   * " or ".
   */
  std::string
  material_names(const std::string &last_separator = ", ");
} // namespace densify
