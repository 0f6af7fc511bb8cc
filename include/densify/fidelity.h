// Scene/Fidelity: one knob that sets the accuracy levers (doc/accuracy.md).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <set>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// One entry that a fidelity level sets: "Subsection/Name" and its value.
  struct FidelitySetting
  {
    /// The entry, "Subsection/Name" as --set names it.
    std::string entry;
    /// The value the level gives it.
    std::string value;
  };

  /**
   * The entries that the fidelity level @p level ("draft", "standard" or
   * "reference") sets, in the order of the table in doc/accuracy.md; empty
   * for "as set". Throws std::runtime_error for any other name.
   */
  std::vector<FidelitySetting>
  fidelity_settings(const std::string &level);

  /**
   * Apply Scene/Fidelity of @p prm: every entry of its level that is not in
   * @p set (the entries the parameter file or --set gave, as
   * "Subsection/Name") gets the level's value; the entries in @p set keep
   * theirs. Returns the banner text "LEVEL (Entry = value, ...; as set:
   * Entry, ...)", or an empty string for Scene/Fidelity = as set (nothing
   * changed).
   */
  std::string
  resolve_fidelity(ParameterHandler &prm, const std::set<std::string> &set);
} // namespace densify
