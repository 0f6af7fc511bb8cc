// Small helpers shared by the executable and the library.
#pragma once

#include <stdexcept>
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

  /**
   * An error in what the user gave (parameters, files, command line) found
   * while running; the executable exits with code 2 for it, as for a bad
   * parameter file.
   */
  struct InputError : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };
} // namespace densify
