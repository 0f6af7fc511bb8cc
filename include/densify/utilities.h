// Small helpers shared by the executable and the library.
#pragma once

#include <string>

namespace densify
{
  /**
   * @p text on one line: newlines and tabs become blanks, runs of blanks one
   * blank, no blanks at either end. For error messages, which must be one
   * line whatever a library put into them.
   */
  std::string
  one_line(const std::string &text);
} // namespace densify
