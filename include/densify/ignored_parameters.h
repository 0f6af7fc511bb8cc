// Parameters that a scene sets but does not use, and the warning for each.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <set>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * The entries that the parameter file @p filename sets, as
   * "Subsection/Subsection/Name" (the "set" lines, read with deal.II's
   * syntax: '#' comments, '\' continuation lines, subsection ... end).
   * An unreadable file gives an empty set.
   */
  std::set<std::string>
  entries_set_in_file(const std::string &filename);

  /**
   * One line for each entry of @p set (paths "Subsection/Name" as
   * entries_set_in_file() gives them) that the scene described by @p prm
   * does not use: "Subsection/Name = value has no effect: why". Examples:
   * the constants of the material 'custom' when every particle is a preset
   * (Sn, Fe, Cu), die friction with the die off, the arctangent law's slip
   * velocity under Coulomb friction. An entry whose use depends on the
   * contents of a particle file is never reported.
   */
  std::vector<std::string>
  ignored_parameters(const ParameterHandler      &prm,
                     const std::set<std::string> &set);
} // namespace densify
