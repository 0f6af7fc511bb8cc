// The rigid tools as analytic surfaces: lower punch, upper punch (planes) and
// die wall (cylinder).
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>

namespace densify
{
  using namespace dealii;

  /// Which tool (also the index into per-tool arrays).
  enum class ToolKind : unsigned int
  {
    lower_punch = 0,
    upper_punch = 1,
    die_wall    = 2
  };

  /// Number of tool kinds.
  constexpr unsigned int n_tool_kinds = 3;

  /// The name of a tool as used in the log and output.
  std::string
  tool_name(const ToolKind kind);

  /**
   * One rigid tool. The signed gap g(x) is positive where a point is free and
   * negative where it penetrates; the unit normal n points from the tool into
   * the particles, so the contact traction on a particle is p n with p >= 0
   * and dg/dx = n.
   */
  struct RigidTool
  {
    /// Which tool this is.
    ToolKind kind = ToolKind::lower_punch;
    /// Plane height (mm) for punches, radius (mm) for the die wall.
    double position = 0.;

    /// Signed gap of @p x (mm); writes the normal and, for the die wall, the
    /// curvature 1/r of the surface at the projection (0 for planes).
    double
    gap(const Point<3> &x, Tensor<1, 3> &normal, double &curvature) const
    {
      switch (kind)
        {
          case ToolKind::lower_punch:
            normal    = Tensor<1, 3>({0., 0., 1.});
            curvature = 0.;
            return x[2] - position;
          case ToolKind::upper_punch:
            normal    = Tensor<1, 3>({0., 0., -1.});
            curvature = 0.;
            return position - x[2];
          default:
            {
              const double r = std::sqrt(x[0] * x[0] + x[1] * x[1]);
              // on the axis any inward direction is as good as another
              normal    = (r > 0 ? Tensor<1, 3>({-x[0] / r, -x[1] / r, 0.}) :
                                   Tensor<1, 3>({-1., 0., 0.}));
              curvature = (r > 0 ? 1. / r : 0.);
              return position - r;
            }
        }
    }
  };
} // namespace densify
