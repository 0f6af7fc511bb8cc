// Particle data (centre, diameter, material) from the .prm or a CSV file, and
// its checks.
#pragma once

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// One powder particle before meshing: a sphere (mm) made of a named
  /// material.
  struct Particle
  {
    /// Centre (mm).
    Point<3> centre;
    /// Diameter (mm), > 0.
    double diameter = 0.;
    /// Material name, e.g. "Sn" (a preset or "custom").
    std::string material = "Sn";
  };

  /**
   * Read particles from a CSV file with columns x, y, z, diameter and an
   * optional fifth column material. Lines starting with '#' and a header
   * line starting with a non-numeric field are skipped. @p default_material
   * is used where the material column is missing. Throws std::runtime_error
   * with a one-line message naming the file and line on any error (missing
   * file, wrong column count, non-numeric value).
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
                    const std::string &default_material);

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
   * overlapping (by more than @p tolerance mm; touching is allowed), every
   * particle inside the container (again up to @p tolerance). Throws
   * std::runtime_error with a one-line message that names the particle(s),
   * the parameter to change and by how much it is off.
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
