// Material presets: parameters of Sn, Fe, Cu and the error for unknown names.
#include <densify/material/j2_plasticity.h>

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

  std::cout << (ok ? "all checks passed" : "SOME CHECKS FAILED") << "\n";
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
