// The material presets: the constants of named metals, one table.
#include <densify/material/presets.h>

#include <iterator>

namespace densify
{
  namespace
  {
    /**
     * The presets, one row each: name, E (MPa), nu, sigma0 (MPa), density
     * (t/mm^3), source. All are perfectly plastic, as in the reference
     * paper's comparison of Sn, Fe and Cu. doc/materials.md states this
     * table; a new preset is one more row here and there.
     */
    // clang-format off
    constexpr MaterialPreset presets[] = {
      // Tin as in the reference paper of the compaction benchmark. Density:
      // beta tin at room temperature, 7.29 g/cm^3 (CRC Handbook).
      {"Sn",  43120., 0.3,  31., 7.29e-9,
       "E, nu, sigma0: the reference paper (../shared/seeds/); density: CRC "
       "Handbook (beta tin)"},
      // Annealed high-purity iron. E and nu: room-temperature values of
      // pure iron (ASM Handbook Vol. 2 / MatWeb "Iron, Fe": 211 GPa,
      // 0.29). Yield stress: Callister, "Materials Science and
      // Engineering" (Wiley), pure iron: sigma_y = 50 MPa (E = 208 GPa).
      // Real yield stresses of pure iron depend strongly on purity and
      // grain size. Density: 7.874 g/cm^3 (CRC Handbook).
      {"Fe", 211000., 0.29, 50., 7.874e-9,
       "E, nu: ASM Handbook Vol. 2 / MatWeb \"Iron, Fe\"; sigma0: Callister, "
       "Materials Science and Engineering (pure iron); density: CRC Handbook"},
      // Annealed high-purity (99.99 %) copper. E = 117 GPa: Smithells
      // Metals Reference Book, 8th ed., Table 22.7 (annealed OFHC strip);
      // nu = 0.34 (typical polycrystal value). Yield stress 33 MPa:
      // MatWeb "Copper, Cu; Annealed" (33.3 MPa); Smithells lists a 0.2 %
      // proof stress of 48 MPa for annealed OFHC strip, so the value
      // depends on purity and grain size. Density: 8.96 g/cm^3 (CRC
      // Handbook).
      {"Cu", 117000., 0.34, 33., 8.96e-9,
       "E: Smithells Metals Reference Book, 8th ed., Table 22.7 (annealed "
       "OFHC); nu: typical polycrystal value; sigma0: MatWeb \"Copper, Cu; "
       "Annealed\" (33.3 MPa); density: CRC Handbook"},
    };
    // clang-format on
  } // namespace



  ArrayView<const MaterialPreset>
  material_presets()
  {
    return ArrayView<const MaterialPreset>(presets, std::size(presets));
  }



  const MaterialPreset *
  find_material_preset(const std::string &name)
  {
    for (const MaterialPreset &preset : presets)
      if (name == preset.name)
        return &preset;
    return nullptr;
  }



  std::string
  material_names(const std::string &last_separator)
  {
    std::string names;
    for (const MaterialPreset &preset : presets)
      names += preset.name + std::string(", ");
    // the last ", " gives way to last_separator
    return names.substr(0, names.size() - 2) + last_separator +
           custom_material_name;
  }
} // namespace densify
