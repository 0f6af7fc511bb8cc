// Material presets: parameters of Sn, Fe, Cu and the error for unknown names;
// the preset table and the parsing of Material/Model and Material/Hardening.
#include <densify/material/factory.h>
#include <densify/material/j2_plasticity.h>
#include <densify/material/presets.h>

#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>

using namespace densify;

int
main()
{
  std::cout << std::setprecision(6);
  bool ok = true;

  for (const std::string name : {"Sn", "Fe", "Cu"})
    {
      const J2Parameters p = material_preset(name);
      const J2Plasticity material(p);
      std::cout << name << ": E = " << p.E << " MPa, nu = " << p.nu
                << ", sigma0 = " << p.sigma0 << " MPa, "
                << hardening_name(p.hardening) << ", label '" << p.label
                << "'\n"
                << "  " << material.name()
                << (material.needs_history() ? ", needs history" : "")
                << (material.is_linear() ? ", linear" : ", nonlinear")
                << ", youngs_modulus() = " << material.youngs_modulus() << "\n";
      if (p.label != name || material.youngs_modulus() != p.E)
        ok = false;
    }

  for (const std::string name : {"Pb", "sn", "custom", ""})
    try
      {
        material_preset(name);
        std::cout << "'" << name << "': no exception\n";
        ok = false;
      }
    catch (const std::invalid_argument &e)
      {
        std::cout << "'" << name << "': " << e.what() << "\n";
      }

  // Parameters out of range are rejected by the constructor.
  J2Parameters bad = material_preset("Sn");
  bad.nu           = 0.5;
  try
    {
      const J2Plasticity material(bad);
      std::cout << "nu = 0.5: no exception\n";
      ok = false;
    }
  catch (const std::invalid_argument &e)
    {
      std::cout << "nu = 0.5: " << e.what() << "\n";
    }

  // Every row of the table is found by its name and gives its constants.
  std::cout << "table:";
  for (const MaterialPreset &row : material_presets())
    {
      const J2Parameters p = material_preset(row.name);
      std::cout << " " << row.name;
      if (find_material_preset(row.name) != &row || p.E != row.E ||
          p.nu != row.nu || p.sigma0 != row.sigma0 ||
          p.density != row.density || p.label != row.name)
        {
          std::cout << " (MISMATCH)";
          ok = false;
        }
    }
  std::cout << "; custom in the table: "
            << (find_material_preset(custom_material_name) ? "yes" : "no")
            << "; names: " << material_names(" or ") << "\n";

  // Material/Model and Material/Hardening, as text, to their models.
  const bool parsed = !parse_material_model("elastic").plastic &&
                      parse_material_model("J2 plasticity").plastic &&
                      parse_hardening("none") == Hardening::none &&
                      parse_hardening("linear") == Hardening::linear &&
                      parse_hardening("power law") == Hardening::power_law;
  std::cout << "model and hardening parsed: " << (parsed ? "yes" : "no")
            << "\n";
  ok = ok && parsed;
  try
    {
      parse_material_model("J2");
      std::cout << "Model 'J2': no exception\n";
      ok = false;
    }
  catch (const std::runtime_error &e)
    {
      std::cout << e.what() << "\n";
    }
  try
    {
      parse_hardening("Linear");
      std::cout << "Hardening 'Linear': no exception\n";
      ok = false;
    }
  catch (const std::runtime_error &e)
    {
      std::cout << e.what() << "\n";
    }

  std::cout << (ok ? "all checks passed" : "SOME CHECKS FAILED") << "\n";
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
