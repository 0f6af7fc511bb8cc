// Parameters that a scene sets but does not use, and the warning for each.
#include <deal.II/base/utilities.h>

#include <densify/ignored_parameters.h>

#include <algorithm>
#include <fstream>

namespace densify
{
  std::set<std::string>
  entries_set_in_file(const std::string &filename)
  {
    std::set<std::string> entries;
    std::ifstream         in(filename);
    if (!in)
      return entries;
    std::vector<std::string> path;
    std::string              line;
    for (bool first = true; std::getline(in, line); first = false)
      {
        // a UTF-8 byte-order mark, as read_parameters() skips it
        if (first && line.rfind("\xEF\xBB\xBF", 0) == 0)
          line.erase(0, 3);
        // a '\' at the end joins the next line, as in deal.II
        while (!line.empty() && line.back() == '\\')
          {
            line.pop_back();
            std::string next;
            if (!std::getline(in, next))
              break;
            line += next;
          }
        // '#' starts a comment unless escaped as '\#'
        for (std::size_t i = line.find('#'); i != std::string::npos;
             i             = line.find('#', i + 1))
          if (i == 0 || line[i - 1] != '\\')
            {
                          line.erase(i);
                          break;
            }
        line = Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            const std::string entry = line.substr(4);
            std::string       name =
              Utilities::trim(entry.substr(0, entry.find('=')));
            for (auto p = path.rbegin(); p != path.rend(); ++p)
              name = *p + "/" + name;
            entries.insert(name);
          }
      }
    return entries;
  }



  std::vector<std::string>
  ignored_parameters(const ParameterHandler      &prm,
                     const std::set<std::string> &set)
  {
    // the value of "Sub/Sub/Name"
    const auto get = [&prm](const std::string &entry) {
      std::vector<std::string> path = Utilities::split_string_list(entry, '/');
      const std::string        name = path.back();
      path.pop_back();
      return prm.get(path, name);
    };
    const auto on = [&get](const std::string &entry) {
      return get(entry) == "true";
    };
    const auto number = [&get](const std::string &entry) {
      try
        {
          return Utilities::string_to_double(get(entry));
        }
      catch (...)
        {
          return -1.; // not a number (e.g. 'default'): counted as used
        }
    };

    const std::string packing  = get("Particles/Packing");
    const std::string fraction = get("Particles/Material fractions");
    const bool        list     = packing == "list";
    const bool has_file = list && !get("Particles/Particle file").empty();

    // may a particle be of the material 'custom'? Unknown (so yes) where a
    // particle file may name it in its material column
    std::vector<std::string> names;
    for (const std::string &item : Utilities::split_string_list(
           fraction.empty() ? get("Particles/Materials") : fraction, ','))
      names.push_back(Utilities::trim(
        item.substr(0, fraction.empty() ? item.npos : item.find(':'))));
    if (!list && fraction.empty() && !names.empty())
      names.resize(1); // a generated layer takes the first material
    const bool custom =
      (has_file && fraction.empty()) ||
      std::find(names.begin(), names.end(), "custom") != names.end();
    const std::string materials =
      fraction.empty() ? "Particles/Materials = " + get("Particles/Materials") :
                         "Particles/Material fractions = " + fraction;

    const bool elastic = get("Material/Model") == "elastic";
    const bool die     = on("Tools/Die wall/Enabled");
    const bool lower   = on("Tools/Lower punch/Enabled");
    const bool upper   = on("Tools/Upper punch/Enabled");

    // friction acts where a coefficient of a tool in the scene, or between
    // particles, is not 0 ('default' stands for Contact/Friction coefficient)
    const double mu       = number("Contact/Friction coefficient");
    bool         friction = mu != 0.;
    for (const auto &[tool, enabled] :
         {std::pair<std::string, bool>{"Lower punch", lower},
          {"Upper punch", upper},
          {"Die wall", die}})
      if (enabled)
        {
          const std::string entry = "Tools/" + tool + "/Friction coefficient";
          friction |= get(entry) == "default" ? mu != 0. : number(entry) != 0.;
        }

    bool no_body_force = true;
    for (const std::string &b :
         Utilities::split_string_list(get("Particles/Body force"), ','))
      try
        {
          no_body_force &= Utilities::string_to_double(b) == 0.;
        }
      catch (...)
        {
          no_body_force = false;
        }

    const std::string solver = get("Solver/Linear solver");
    const bool        direct = solver == "direct" || solver == "gmres-lu";

    // entries of one solution method only
    const bool explicit_method = get("Solver/Method") == "explicit";

    // why an entry has no effect in this scene; empty where it has one
    const auto why = [&](const std::string &entry) -> std::string {
      if (!explicit_method &&
          (entry.rfind("Explicit/", 0) == 0 || entry == "Material/Density"))
        return "only Solver/Method = explicit uses it";
      if (explicit_method &&
          ((entry.rfind("Solver/", 0) == 0 && entry != "Solver/Method") ||
           entry == "Contact/Penalty factor" ||
           entry == "Contact/Maximum augmentations" ||
           entry == "Contact/Friction tangent" ||
           entry == "Contact/Geometric tangent" ||
           entry == "Time stepping/Maximum cut-backs"))
        return "Solver/Method = explicit has no Newton solver, linear "
               "solver or multipliers (subsection Explicit sets its contact "
               "penalty)";
      if (entry == "Material/Density" && !custom)
        return "only the material 'custom' uses it, and no particle is "
               "'custom' (" +
               materials + "; the presets carry their own density)";
      if ((entry == "Material/Young's modulus" ||
           entry == "Material/Poisson's ratio" ||
           entry == "Material/Yield stress") &&
          !custom)
        return "only the material 'custom' uses it, and no particle is "
               "'custom' (" +
               materials + "; the presets carry their own constants)";
      if (entry == "Material/Yield stress" ||
          entry.rfind("Material/Hardening", 0) == 0)
        {
          if (elastic)
            return "Material/Model = elastic has no plasticity";
          const std::string hardening = get("Material/Hardening");
          if (entry == "Material/Hardening modulus" && hardening != "linear")
            return "Material/Hardening = " + hardening + ", not linear";
          if ((entry == "Material/Hardening coefficient" ||
               entry == "Material/Hardening exponent") &&
              hardening != "power law")
            return "Material/Hardening = " + hardening + ", not power law";
        }
      if (!die && (entry == "Tools/Die wall/Friction coefficient" ||
                   entry == "Tools/Die wall/Top" ||
                   entry == "Tools/Die wall/Displacement history"))
        return "the die wall is off (Tools/Die wall/Enabled = false)";
      if (!die && list && entry == "Tools/Die wall/Diameter")
        return "the die wall is off (Tools/Die wall/Enabled = false) and "
               "Particles/Packing = list places no layer in it";
      if (!lower && (entry == "Tools/Lower punch/Friction coefficient" ||
                     entry == "Tools/Lower punch/Displacement history"))
        return "the lower punch is off (Tools/Lower punch/Enabled = false)";
      if (!lower && list && entry == "Tools/Lower punch/Position")
        return "the lower punch is off (Tools/Lower punch/Enabled = false) "
               "and Particles/Packing = list places no layer on it";
      if (!upper && entry.rfind("Tools/Upper punch/", 0) == 0 &&
          entry != "Tools/Upper punch/Enabled")
        return "the upper punch is off (Tools/Upper punch/Enabled = false)";
      if (entry == "Contact/Slip velocity" &&
          get("Contact/Friction model") != "arctangent")
        return "only the arctangent friction law uses it (Contact/Friction "
               "model = " +
               get("Contact/Friction model") + ")";
      if (!friction && (entry == "Contact/Friction model" ||
                        entry == "Contact/Slip velocity" ||
                        entry == "Contact/Tangential penalty factor" ||
                        entry == "Contact/Friction tangent"))
        return "there is no friction (every friction coefficient in the "
               "scene is 0)";
      if (entry == "Particles/Number of particles" ||
          entry == "Particles/Packing seed")
        if (packing != "random layer" && packing != "deposited")
          return "only Particles/Packing = random layer or deposited uses it "
                 "(Packing = " +
                 packing + ")";
      if ((entry == "Particles/Size distribution" ||
           entry == "Particles/Diameter spread" ||
           entry == "Particles/Fill height") &&
          packing != "deposited")
        return "only Particles/Packing = deposited uses it (Packing = " +
               packing + ")";
      if (entry == "Particles/Diameter spread" &&
          get("Particles/Size distribution") != "log-normal")
        return "only Particles/Size distribution = log-normal uses it";
      if (entry == "Particles/Hexagonal placement" &&
          packing != "hexagonal layer")
        return "only Particles/Packing = hexagonal layer uses it (Packing = " +
               packing + ")";
      if (entry == "Particles/Centres" && (!list || has_file))
        return list ?
                 "the particles come from Particles/Particle file" :
                 "Particles/Packing = " + packing + " generates the particles";
      if (entry == "Particles/Particle file" && !list)
        return "Particles/Packing = " + packing + " generates the particles";
      if (entry == "Particles/Material seed" && fraction.empty())
        return "only Particles/Material fractions uses it, and it is empty";
      if (entry == "Particles/Body force history" && no_body_force)
        return "Particles/Body force is 0";
      if ((entry == "Mesh/Refined element size" ||
           entry == "Mesh/Refinement growth") &&
          get("Mesh/Refinement directions").empty())
        return "Mesh/Refinement directions is empty (a uniform mesh)";
      if (entry == "Solver/Reuse AMG" && direct)
        return "Solver/Linear solver = " + solver + " builds no AMG";
      if (entry == "Solver/Reproducible" && !direct)
        return "only the solvers direct and gmres-lu use it (Solver/Linear "
               "solver = " +
               solver + ")";
      if (entry == "Solver/Adaptive linear tolerance" && solver == "direct")
        return "Solver/Linear solver = direct solves exactly";
      return "";
    };

    std::vector<std::string> lines;
    for (const std::string &entry : set)
      {
        const std::string reason = why(entry);
        if (!reason.empty())
          lines.push_back(entry + " = " + get(entry) +
                          " has no effect: " + reason);
      }
    return lines;
  }
} // namespace densify
