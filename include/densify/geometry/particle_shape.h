// The shapes of particles that are not spheres (ellipsoids, closed surface
// meshes from STL files): their extent, volume, inside test and overlaps.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <densify/geometry/particles.h>

#include <array>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * Read a closed triangulated surface from an STL file (ASCII or binary),
   * coordinates in mm. Vertices that coincide exactly are merged. Throws
   * std::runtime_error with a one-line message naming the file if it cannot
   * be read, has no triangles, or is not closed (an edge not shared by
   * exactly two triangles) or encloses no volume.
   */
  SurfaceMesh
  read_stl(const std::string &filename);

  /// The volume enclosed by a closed, consistently oriented surface (mm^3;
  /// positive for outward normals, negative for inward).
  double
  enclosed_volume(const SurfaceMesh &surface);

  /// The centroid of the solid a closed surface encloses.
  Point<3>
  enclosed_centroid(const SurfaceMesh &surface);

  /**
   * Rotation (body to global frame) by @p angles (degrees) about the global
   * x axis, then the global y axis, then the global z axis:
   * Rz(angles[2]) Ry(angles[1]) Rx(angles[0]).
   */
  Tensor<2, 3>
  rotation_from_angles(const std::array<double, 3> &angles);

  /**
   * A rotation drawn uniformly over all orientations (a random unit
   * quaternion) from three numbers @p u uniform in [0, 1).
   */
  Tensor<2, 3>
  uniform_rotation(const std::array<double, 3> &u);

  /**
   * Make @p particle an ellipsoid with the diameters @p diameters along its
   * body axes x, y, z (mm, > 0) and the orientation @p rotation; its
   * diameter becomes that of its bounding sphere. Throws std::runtime_error
   * if a diameter is not > 0.
   */
  void
  make_ellipsoid(Particle                    &particle,
                 const std::array<double, 3> &diameters,
                 const Tensor<2, 3>          &rotation);

  /**
   * Make @p particle the solid of the closed surface in the STL file
   * @p filename (mm), turned by @p rotation about the solid's centroid,
   * which is placed at the particle's centre; its diameter becomes that of
   * the bounding sphere about the centre (from the vertices).
   */
  void
  make_surface_particle(Particle           &particle,
                        const std::string  &filename,
                        const Tensor<2, 3> &rotation);

  /**
   * The support function: the largest n.(x - centre) over the points x of
   * the particle, for a unit vector @p n (sphere: the radius; ellipsoid:
   * sqrt(n.M n) with M = R diag(a^2) R^T; surface: over its vertices).
   */
  double
  support(const Particle &particle, const Tensor<1, 3> &n);

  /**
   * The point of the particle's surface farthest along the unit vector
   * @p n, relative to the centre, in the particle's body frame (the frame
   * it is meshed in).
   */
  Tensor<1, 3>
  body_support_point(const Particle &particle, const Tensor<1, 3> &n);

  /// The largest distance from the die axis (x = y = 0) of the particle's
  /// points (ellipsoids: to 1e-6 of their size, from below).
  double
  axis_distance_extent(const Particle &particle);

  /// The particle's volume (the exact shape, not its mesh), mm^3.
  double
  particle_volume(const Particle &particle);

  /// The particle's smallest width over its body axes (sphere: diameter).
  double
  smallest_width(const Particle &particle);

  /// Whether @p x lies inside the particle (the exact shape; for a surface,
  /// by its winding number).
  bool
  contains(const Particle &particle, const Point<3> &x);

  /**
   * The overlap of two particles of which at least one is not a sphere,
   * tested on points of their surfaces: the points of a closed
   * triangulation of each surface (an ellipsoid's or a sphere's: 2562
   * points of a subdivided icosahedron; a surface's: its vertices) that lie
   * inside the other particle. Returns the largest depth of such a point
   * below the other's surface (mm; 0 if there is none) and, in
   * @p inside / @p deepest, which particle's point (0: @p a's, 1: @p b's)
   * and where. An overlap smaller than the spacing of the points can be
   * missed (for ellipsoids, one shallower than about 1e-3 of the radius).
   */
  double
  shape_overlap(const Particle &a,
                const Particle &b,
                unsigned int   &inside,
                Point<3>       &deepest);
} // namespace densify
