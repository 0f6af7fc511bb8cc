// The rigid tools as analytic surfaces: lower punch, upper punch (planes) and
// die wall (cylinder).
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <limits>
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
    /// Height of the die wall's top edge (mm; infinity: a die without end).
    double top = std::numeric_limits<double>::infinity();

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
              const Tensor<1, 3> e_r =
                (r > 0 ? Tensor<1, 3>({x[0] / r, x[1] / r, 0.}) :
                         Tensor<1, 3>({1., 0., 0.}));
              if (x[2] > top)
                {
                  // above the die: the distance to its top edge (the ring
                  // r = position, z = top), continuous with the wall's gap
                  // and normal at z = top; no curvature term in the tangent
                  const double dr = r - position, dz = x[2] - top;
                  const double d = std::sqrt(dr * dr + dz * dz);
                  normal         = (dr / d) * e_r;
                  normal[2]      = dz / d;
                  curvature      = 0.;
                  return d;
                }
              normal    = -e_r;
              curvature = (r > 0 ? 1. / r : 0.);
              return position - r;
            }
        }
    }
  };
} // namespace densify
