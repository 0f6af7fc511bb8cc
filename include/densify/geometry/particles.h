// Particle data (centre, diameter, material) from the .prm or a CSV file, and
// its checks.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// The shape of a particle.
  enum class ParticleShape
  {
    /// A sphere of the particle's diameter.
    sphere,
    /// An ellipsoid with the semi-axes Particle::semi_axes.
    ellipsoid,
    /// The solid enclosed by the closed triangulated Particle::surface.
    surface
  };

  /// A closed triangulated surface (mm), triangles numbered
  /// counter-clockwise seen from outside.
  struct SurfaceMesh
  {
    /// Vertex coordinates.
    std::vector<Point<3>> vertices;
    /// Three vertex indices per triangle.
    std::vector<std::array<unsigned int, 3>> triangles;
  };

  /**
   * One powder particle before meshing, made of a named material: a sphere
   * (mm), an ellipsoid or the solid of a closed surface mesh. Everything a
   * bounding sphere is enough for (the broad contact search, the grid of the
   * overlap check, the scales of floors and stabilisation) uses the
   * diameter, which for an ellipsoid or a surface is that of the smallest
   * sphere about the centre that holds the particle.
   */
  struct Particle
  {
    /// A sphere of diameter 0 at the origin, made of "Sn".
    Particle() = default;

    /// A sphere at @p centre (mm) of @p diameter (mm) made of @p material.
    Particle(const Point<3>    &centre,
             const double       diameter,
             const std::string &material = "Sn")
      : centre(centre)
      , diameter(diameter)
      , material(material)
    {}

    /// Centre (mm); of a surface particle, its solid's centroid.
    Point<3> centre;
    /// Diameter (mm), > 0; of an ellipsoid or a surface particle, the
    /// diameter of its bounding sphere about the centre.
    double diameter = 0.;
    /// Material name, e.g. "Sn" (a preset or "custom").
    std::string material = "Sn";
    /// The shape; the fields below are used by the shapes that need them.
    ParticleShape shape = ParticleShape::sphere;
    /// Ellipsoid: the semi-axes along the body axes x, y, z (mm).
    Tensor<1, 3> semi_axes;
    /// Ellipsoid or surface: the rotation from the body frame to the global
    /// frame (global = centre + rotation * body).
    Tensor<2, 3> rotation = Tensor<2, 3>(unit_symmetric_tensor<3>());
    /// Surface: the file it was read from, for messages.
    std::string surface_file;
    /// Surface: the closed surface in the body frame, centroid at the
    /// origin; shared by the particles read from one file.
    std::shared_ptr<const SurfaceMesh> surface;
  };

  /**
   * Read particles from a CSV file with columns x, y, z, diameter and an
   * optional fifth column material. An optional sixth column gives the
   * shape: 'sphere'; 'ellipsoid' followed by the diameters along the body
   * axes y and z (the diameter column is the one along x); or the name of a
   * closed surface mesh file ending in '.stl' (mm, relative to the working
   * directory; its centroid is placed at x, y, z; the diameter column is
   * empty). Ellipsoids and surfaces take three optional angles in degrees
   * (rotations about the global x, y, then z axis); without them, their
   * orientation is drawn uniformly at random from @p orientation_seed, one
   * particle after the other in the file's order. Lines starting with '#' and a
   * header line starting with a non-numeric field are skipped. @p
   * default_material is used where the material column is missing. Throws
   * std::runtime_error with a one-line message naming the file and line on any
   * error (missing file, wrong column count, non-numeric value).
   *
   * Only the first non-comment line may be a header; fields are trimmed and
   * a trailing '\r' is ignored. Values are not checked here (see
   * check_particles()).
   *
   * A file whose first line that is not blank starts with "ITEM:" is a
   * LIGGGHTS/LAMMPS text dump instead: its last snapshot is read by
   * read_liggghts_dump() (metres to mm; @p default_material is then
   * Particles/Materials, the name of each atom type).
   */
  std::vector<Particle>
  read_particle_csv(const std::string &filename,
                    const std::string &default_material,
                    const unsigned int orientation_seed = 1);

  /// The axisymmetric container the particles must fit in (die along z).
  struct Container
  {
    /// Die present? If so, particles must lie within radius die_radius.
    bool has_die = false;
    /// Inner die radius (mm).
    double die_radius = 0.;
    /// Lower punch present? If so particles must lie above z = lower_z.
    bool has_lower = false;
    /// Lower punch face position (mm).
    double lower_z = 0.;
    /// Upper punch present? If so particles must lie below z = upper_z.
    bool has_upper = false;
    /// Upper punch face position (mm) at the start.
    double upper_z = 0.;
  };

  /**
   * Check a particle set: every diameter positive, no two particles
   * overlapping by more than @p tolerance mm (touching is allowed; a pair of
   * which one is not a sphere is tested on points of its surfaces, see
   * shape_overlap()), every particle inside the container by its exact extent
   * (again up to @p tolerance). Throws std::runtime_error with a one-line
   * message that names the particle(s), the parameter to change and by how
   * much it is off.
   *
   * The first failure is reported, in this order: diameters (and finite
   * centres), then the container per particle in index order (die wall,
   * lower punch, upper punch), then overlaps (the pair i < j with the
   * smallest i, then the smallest j; found with a cell grid in O(N log N)).
   * The lower punch message names "Tools/Lower punch/Position".
   */
  void
  check_particles(const std::vector<Particle> &particles,
                  const Container             &container,
                  const double                 tolerance);
} // namespace densify
