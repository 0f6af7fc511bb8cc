// Names of the rigid tools.
#include <densify/contact/rigid_tools.h>

namespace densify
{
  std::string
  tool_name(const ToolKind kind)
  {
    switch (kind)
      {
        case ToolKind::lower_punch:
          return "lower punch";
        case ToolKind::upper_punch:
          return "upper punch";
        default:
          return "die wall";
      }
  }
} // namespace densify
