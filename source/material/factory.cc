// Creation of the material law of a particle from its material name.
#include <densify/material/factory.h>
#include <densify/material/j2_plasticity.h>
#include <densify/material/presets.h>

#include <limits>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// Finite-strain J2Plasticity with the hardening of @p prm.
    std::shared_ptr<const Material>
    create_j2(J2Parameters j2, const MaterialParameters &prm)
    {
      if (!prm.finite_strain)
        throw std::runtime_error(
          "Material/Finite strain = false needs Material/Model = elastic: "
          "J2 plasticity is implemented at finite strain only");
      j2.hardening = parse_hardening(prm.hardening);
      switch (j2.hardening)
        {
          case Hardening::none:
            break;
          case Hardening::linear:
            j2.H = prm.hardening_modulus;
            break;
          case Hardening::power_law:
            j2.K = prm.hardening_coefficient;
            j2.n = prm.hardening_exponent;
            break;
        }
      try
        {
          return std::make_shared<J2Plasticity>(j2);
        }
      catch (const std::invalid_argument &e)
        {
          throw std::runtime_error(std::string(e.what()) +
                                   " (subsection Material)");
        }
    }



    /// Small-strain LinearElastic, or finite-strain Hencky elasticity (J2
    /// without yield).
    std::shared_ptr<const Material>
    create_elastic(J2Parameters j2, const MaterialParameters &prm)
    {
      if (!prm.finite_strain)
        return std::make_shared<LinearElastic>(j2.E,
                                               j2.nu,
                                               j2.label,
                                               j2.density);
      j2.sigma0 = std::numeric_limits<double>::infinity();
      try
        {
          return std::make_shared<J2Plasticity>(j2);
        }
      catch (const std::invalid_argument &e)
        {
          throw std::runtime_error(std::string(e.what()) +
                                   " (subsection Material)");
        }
    }



    /// Densify's models, then those register_material_model() adds.
    std::vector<MaterialModel> &
    all_models()
    {
      static std::vector<MaterialModel> models = {
        {"elastic", false, create_elastic}, {"J2 plasticity", true, create_j2}};
      return models;
    }
  } // namespace



  const MaterialModel &
  parse_material_model(const std::string &model)
  {
    for (const MaterialModel &known : all_models())
      if (known.name == model)
        return known;
    throw std::runtime_error("unknown Material/Model '" + model + "': use " +
                             material_model_names(" or "));
  }



  void
  register_material_model(const MaterialModel &model)
  {
    for (const MaterialModel &known : all_models())
      if (known.name == model.name)
        throw std::invalid_argument("a material model named '" + model.name +
                                    "' exists already");
    all_models().push_back(model);
  }



  std::string
  material_model_names(const std::string &separator)
  {
    std::string names;
    for (const MaterialModel &model : all_models())
      names += (names.empty() ? "" : separator) + model.name;
    return names;
  }



  Hardening
  parse_hardening(const std::string &hardening)
  {
    if (hardening == "none")
      return Hardening::none;
    if (hardening == "linear")
      return Hardening::linear;
    if (hardening == "power law")
      return Hardening::power_law;
    throw std::runtime_error("unknown Material/Hardening '" + hardening +
                             "': use none, linear or power law");
  }



  std::shared_ptr<const Material>
  create_material(const std::string &name, const MaterialParameters &prm)
  {
    J2Parameters j2;
    if (const MaterialPreset *preset = find_material_preset(name))
      j2 = material_preset(*preset); // the table in presets.cc
    else if (name == custom_material_name)
      {
        j2.E       = prm.youngs_modulus;
        j2.nu      = prm.poissons_ratio;
        j2.sigma0  = prm.yield_stress;
        j2.density = prm.density;
        j2.label   = name;
      }
    else
      throw std::runtime_error(
        "unknown material '" + name +
        "' (Particles/Materials or the particle file): use " +
        material_names(" or "));

    return parse_material_model(prm.model).create(j2, prm);
  }
} // namespace densify
