// Tetrahedral meshes of single spheres through the gmsh C++ API.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <densify/geometry/particles.h>

#include <array>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// A tetrahedral mesh as plain arrays (vertex coordinates in mm).
  struct TetMesh
  {
    /// Vertex coordinates.
    std::vector<Point<3>> vertices;
    /// Four vertex indices per tetrahedron, ordered so that the deal.II
    /// Jacobian is positive.
    std::vector<std::array<unsigned int, 4>> cells;
  };

  /// How to mesh a sphere.
  struct SphereMeshSpec
  {
    /// Sphere radius (mm), > 0.
    double radius = 1.;
    /// Target element size away from refinement points (mm), > 0.
    double element_size = 0.3;
    /// Directions (need not be unit) from the centre to surface points
    /// towards which the mesh is refined, e.g. (0,0,1) and (0,0,-1) for the
    /// poles.
    std::vector<Tensor<1, 3>> refinement_directions;
    /// Element size at the refinement points (mm); ignored if there are none.
    double refined_element_size = 0.1;
    /// Growth of the element size with distance d from the nearest refinement
    /// point: h(d) = min(element_size, refined_element_size + growth * d).
    double growth = 0.5;
  };

  /**
   * Mesh a sphere centred at the origin with linear tetrahedra (gmsh OCC
   * sphere, Delaunay 3D). Vertices on the surface lie on the sphere; the two
   * poles (0,0,+-R) are vertices. Deterministic for equal input. Throws
   * std::runtime_error with a one-line message if gmsh fails.
   *
   * Not thread-safe (gmsh is not). Initialises gmsh silently on first use
   * (and again if somebody finalised it), sets gmsh's global mesh options on
   * every call, meshes in a model of its own that is removed afterwards, and
   * leaves the caller's current gmsh model current.
   */
  TetMesh
  mesh_sphere(const SphereMeshSpec &spec);

  /**
   * Mesh one particle with linear tetrahedra, vertices relative to its
   * centre (global = centre + vertex), in its orientation. A sphere is
   * mesh_sphere() of its radius. An ellipsoid is an OCC unit sphere dilated
   * to its semi-axes, a surface particle its closed triangulation split at
   * edges sharper than 40 degrees into patches that gmsh meshes again with
   * the element size; both are meshed in their body frame and turned by
   * their rotation. The refinement directions of @p spec (global) refine the
   * mesh towards the points where the particle reaches farthest along them
   * (the poles of a sphere). @p spec.radius is ignored. Throws
   * std::runtime_error with a one-line message if gmsh fails.
   */
  TetMesh
  mesh_particle(const Particle &particle, const SphereMeshSpec &spec);
} // namespace densify
