// Particles from a LIGGGHTS (LAMMPS) text dump: the last snapshot of a DEM
// die fill, and the DEM contact overlaps moved apart.
#pragma once

#include <densify/geometry/particles.h>

#include <string>
#include <vector>

namespace densify
{
  /**
   * Whether @p filename is a LIGGGHTS/LAMMPS text dump: its first line that
   * is not blank starts with "ITEM:". False if the file cannot be opened.
   */
  bool
  is_liggghts_dump(const std::string &filename);

  /**
   * Read the last snapshot of the LIGGGHTS/LAMMPS text dump @p filename
   * ("dump custom": blocks "ITEM: TIMESTEP", "ITEM: NUMBER OF ATOMS",
   * "ITEM: BOX BOUNDS", "ITEM: ATOMS id type x y z radius ...", other items
   * skipped). The columns are found by the names on the ATOMS line: x, y, z
   * (or the unwrapped xu, yu, zu), radius (or diameter), and optionally id
   * (the particles are returned in the order of their ids) and type.
   *
   * Units: the dump is in SI units (metres, LIGGGHTS' "units si"); centres
   * and diameters are returned in mm (times 1000). Coordinates are kept:
   * Densify's die axis is the z axis through x = y = 0 and its lower punch
   * lies at Tools/Lower punch/Position.
   *
   * Materials: @p materials is Particles/Materials, one name or a
   * comma-separated list; one name is every particle's material, a list
   * gives atom type t the t-th name (type 1 the first).
   *
   * Throws std::runtime_error with a one-line message "Particles/Particle
   * file: FILE:LINE: ..." that says what to change: no ATOMS item or no
   * atoms in the last snapshot, a missing column (x, y, z, radius), scaled
   * coordinates (xs), a row with too few fields or a field that is not a
   * number, a radius that is not > 0, a type < 1 or beyond the list of
   * Particles/Materials, a snapshot cut short, two atoms with one id.
   */
  std::vector<Particle>
  read_liggghts_dump(const std::string &filename, const std::string &materials);

  /// What separate_overlaps() did.
  struct OverlapSeparation
  {
    /// The largest overlap found, of two particles or of a particle and the
    /// container, as a fraction of the (smaller) diameter.
    double largest_overlap = 0.;
    /// The largest distance a particle was moved (mm).
    double largest_shift = 0.;
    /// Jacobi sweeps taken.
    unsigned int sweeps = 0;
  };

  /**
   * Move the particles of a DEM bed apart where their contacts overlap (DEM
   * contacts are soft: a settled bed overlaps by about 0.1 % of a diameter)
   * until no two overlap and none crosses the die wall or lies below the
   * lower punch of @p container (its upper punch is ignored). Diameters are
   * kept. Jacobi sweeps: every pair closer than 1e-6 of the smallest
   * diameter is pushed apart along its centre line to that gap, half each;
   * a particle moves by the sum of its pushes, then is put back inside the
   * die and onto or above the lower punch; until no pair overlaps (at most
   * 100000 sweeps). Most contacts of the DEM bed end with a gap below 1e-5
   * of the diameter (they count for mean_coordination()), a few open
   * further. scripts/packing/liggghts_fill.py does the same for the CSV it
   * writes.
   *
   * An overlap beyond @p limit (fraction of the smaller diameter) is not a
   * DEM contact but a wrong unit, origin or die: then nothing is moved and
   * std::runtime_error is thrown with a one-line message that starts with
   * @p what and names the particle(s) and the parameter to check.
   */
  OverlapSeparation
  separate_overlaps(std::vector<Particle> &particles,
                    const Container       &container,
                    const std::string     &what,
                    const double           limit = 0.05);
} // namespace densify
