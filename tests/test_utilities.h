// Helpers shared by the test programs: reading a scene from prm/ with
// overrides.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <densify/parameters.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace densify
{
  namespace testing
  {
    /// Set when any check fails, so that the test also fails by exit code.
    inline bool all_passed = true;

    /// "yes" or "no", remembering a "no" in all_passed.
    inline std::string
    yes(const bool ok)
    {
      all_passed = all_passed && ok;
      return ok ? "yes" : "no";
    }

    /// The source directory (from the DENSIFY_SOURCE_DIR environment variable).
    inline std::string
    source_dir()
    {
      const char *dir = std::getenv("DENSIFY_SOURCE_DIR");
      return dir != nullptr ? dir : ".";
    }

    /// Read prm/@p scene from the source tree into @p parameters, then apply
    /// @p overrides ("Sub/Name=value").
    inline void
    read_scene(Parameters                     &parameters,
               ParameterHandler               &prm,
               const std::string              &scene,
               const std::vector<std::string> &overrides)
    {
      parameters.declare(prm);
      read_parameters(prm, source_dir() + "/prm/" + scene, overrides);
    }
  } // namespace testing
} // namespace densify
