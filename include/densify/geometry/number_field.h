// Parsing one field of a particle file as a number.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace densify
{
  /// Parse a whole field as a finite number; false if it is not one.
  inline bool
  parse_number(const std::string &field, double &value)
  {
    if (field.empty())
      return false;
    char *end = nullptr;
    errno     = 0;
    value     = std::strtod(field.c_str(), &end);
    return end == field.c_str() + field.size() && errno == 0 &&
           std::isfinite(value);
  }
} // namespace densify
