// The subsection Material of the parameters, declared by the material
// component that reads it.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <densify/parameters.h>

namespace densify
{
  using namespace dealii;

  /// Declare the subsection Material in @p prm, its entries bound to
  /// @p material (Parameters::declare() calls it).
  void
  declare_material_parameters(ParameterHandler   &prm,
                              MaterialParameters &material);
} // namespace densify
