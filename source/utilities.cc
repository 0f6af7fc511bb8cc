// Small helpers shared by the executable and the library.
#include <densify/utilities.h>

namespace densify
{
  std::string
  one_line(const std::string &text)
  {
    std::string line;
    for (char c : text)
      {
        if (c == '\n' || c == '\t' || c == '\r')
          c = ' ';
        if (c == ' ' && (line.empty() || line.back() == ' '))
          continue;
        line += c;
      }
    while (!line.empty() && line.back() == ' ')
      line.pop_back();
    return line;
  }
} // namespace densify
