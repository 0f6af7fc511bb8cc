// The subsection Contact of the parameters, declared by the contact
// component that reads it.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <densify/parameters.h>

namespace densify
{
  using namespace dealii;

  /// Declare the subsection Contact in @p prm, its entries bound to
  /// @p contact (Parameters::declare() calls it).
  void
  declare_contact_parameters(ParameterHandler &prm, ContactParameters &contact);
} // namespace densify
