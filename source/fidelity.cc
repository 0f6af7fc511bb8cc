// Scene/Fidelity: one knob that sets the accuracy levers (doc/accuracy.md).
#include <deal.II/base/utilities.h>

#include <densify/fidelity.h>

#include <stdexcept>

namespace densify
{
  std::vector<FidelitySetting>
  fidelity_settings(const std::string &level)
  {
    // the measured fronts and what each lever buys: doc/accuracy.md, whose
    // table tests/cli/fidelity.sh compares with these. standard is the light
    // scene's settings (prm/single_layer_sn_light.prm), reference the
    // paper's scene's (prm/single_layer_sn.prm), which name these levels.
    if (level == "as set")
      return {};
    if (level == "draft")
      return {{"Mesh/Element size", "0.6"},
              {"Time stepping/Number of steps", "32"},
              {"Solver/Newton tolerance", "1e-4"},
              {"Contact/Penalty factor", "100"},
              {"Solver/Linear solver", "gmres-lu"},
              {"Solver/Line search", "energy"},
              {"Solver/Maximum Newton iterations", "60"}};
    if (level == "standard")
      return {{"Mesh/Element size", "0.5"},
              {"Time stepping/Number of steps", "128"},
              {"Solver/Newton tolerance", "1e-6"},
              {"Contact/Penalty factor", "100"},
              {"Solver/Linear solver", "gmres-lu"},
              {"Solver/Line search", "energy"},
              {"Solver/Maximum Newton iterations", "60"}};
    if (level == "reference")
      return {{"Mesh/Element size", "0.3"},
              {"Time stepping/Number of steps", "250"},
              {"Solver/Newton tolerance", "1e-6"},
              {"Contact/Penalty factor", "100"},
              {"Solver/Linear solver", "gmres-lu"},
              {"Solver/Line search", "energy"},
              {"Solver/Maximum Newton iterations", "60"},
              {"Solver/Adaptive linear tolerance", "true"},
              {"Solver/Reproducible", "false"}};
    throw std::runtime_error("Scene/Fidelity = '" + level +
                             "': expected as set, draft, standard or "
                             "reference");
  }



  std::string
  resolve_fidelity(ParameterHandler &prm, const std::set<std::string> &set)
  {
    prm.enter_subsection("Scene");
    const std::string level = prm.get("Fidelity");
    prm.leave_subsection();
    const std::vector<FidelitySetting> settings = fidelity_settings(level);
    if (settings.empty())
      return "";
    std::string applied, kept;
    for (const FidelitySetting &s : settings)
      {
        if (set.count(s.entry) > 0)
          {
            kept += (kept.empty() ? "" : ", ") + s.entry;
            continue;
          }
        std::vector<std::string> path =
          Utilities::split_string_list(s.entry, '/');
        const std::string name = path.back();
        path.pop_back();
        for (const std::string &p : path)
          prm.enter_subsection(p);
        prm.set(name, s.value);
        for (unsigned int i = 0; i < path.size(); ++i)
          prm.leave_subsection();
        applied += (applied.empty() ? "" : ", ") + s.entry + " = " + s.value;
      }
    return level + " (" + (applied.empty() ? "nothing" : applied) +
           (kept.empty() ? "" : "; as set: " + kept) + ")";
  }
} // namespace densify
