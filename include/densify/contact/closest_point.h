// The closest point of a triangle, shared by the contact search and the
// overlap checks of particle shapes.
#pragma once

#include <deal.II/base/point.h>

#include <array>

namespace densify
{
  using namespace dealii;

  /**
   * Closest point of the triangle (a, b, c) to @p p as barycentric
   * coordinates (Ericson, Real-Time Collision Detection, 5.1.5).
   */
  inline std::array<double, 3>
  closest_on_triangle(const Point<3> &p,
                      const Point<3> &a,
                      const Point<3> &b,
                      const Point<3> &c)
  {
    const Tensor<1, 3> ab = b - a, ac = c - a, ap = p - a;
    const double       d1 = ab * ap, d2 = ac * ap;
    if (d1 <= 0 && d2 <= 0)
      return {{1., 0., 0.}};
    const Tensor<1, 3> bp = p - b;
    const double       d3 = ab * bp, d4 = ac * bp;
    if (d3 >= 0 && d4 <= d3)
      return {{0., 1., 0.}};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
      {
        const double v = d1 / (d1 - d3);
        return {{1 - v, v, 0.}};
      }
    const Tensor<1, 3> cp = p - c;
    const double       d5 = ab * cp, d6 = ac * cp;
    if (d6 >= 0 && d5 <= d6)
      return {{0., 0., 1.}};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
      {
        const double w = d2 / (d2 - d6);
        return {{1 - w, 0., w}};
      }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
      {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {{0., 1 - w, w}};
      }
    const double denominator = 1. / (va + vb + vc);
    const double v = vb * denominator, w = vc * denominator;
    return {{1 - v - w, v, w}};
  }
} // namespace densify
