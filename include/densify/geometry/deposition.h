// A powder bed poured into the die: spheres of a size distribution dropped
// one by one and rolled down onto the bed (Particles/Packing = deposited).
#pragma once

#include <densify/geometry/particles.h>

#include <string>
#include <vector>

namespace densify
{
  /// How the diameters of a deposited bed are distributed.
  enum class SizeDistribution
  {
    /// All equal.
    equal,
    /// Uniform between two diameters.
    uniform,
    /// Log-normal: ln d normal about ln d50 with a standard deviation
    /// (the spread), truncated at three spreads.
    log_normal
  };

  /// What to pour into the die.
  struct DepositionSpec
  {
    /// Inner diameter of the die (mm; its axis is the z axis).
    double die_diameter = 20.;
    /// Height of the floor, the lower punch's face (mm).
    double floor = 0.;
    /// The diameters' distribution and its two numbers: equal: the
    /// diameter (first); uniform: the smallest and the largest diameter;
    /// log-normal: the median diameter d50 and the spread (dimensionless).
    SizeDistribution sizes  = SizeDistribution::equal;
    double           first  = 2.5;
    double           second = 0.;
    /// Number of particles; with fill_height > 0 the most to pour.
    unsigned int n_particles = 43;
    /// Pour until the next particle would rest with its top above floor +
    /// fill_height (mm; that particle is not kept); 0: pour n_particles.
    double fill_height = 0.;
    /// Seed of the random numbers (drop positions and diameters).
    unsigned int seed = 1;
    /// Material of every particle (a mixture is drawn afterwards).
    std::string material = "Sn";
  };

  /**
   * Pour the particles of @p spec into the die: diameters drawn first (in
   * the order they are poured), then each sphere dropped at a random
   * position over the die's floor from above the bed and moved down by
   * steepest descent under the constraints of touching but not overlapping
   * the placed spheres, the floor and the die wall (each trial step down is
   * projected back onto those constraints; the step halves when no lower
   * position is found), until it rests: a local minimum of its height, the
   * frictionless sequential deposition of Visscher and Bolsterli (1972).
   * Placed spheres do not move. The result is the same for the same @p spec
   * on every machine (portable random numbers). Throws std::runtime_error
   * with a one-line message naming the parameter for sizes that do not fit
   * the die or are not positive.
   */
  std::vector<Particle>
  deposit(const DepositionSpec &spec);

  /**
   * The mean number of contacts per particle (2 x pairs / particles) of
   * @p particles, two spheres counting as in contact when their gap is at
   * most @p tolerance times the smaller diameter.
   */
  double
  mean_coordination(const std::vector<Particle> &particles,
                    const double                 tolerance = 1e-5);

  /**
   * The solid fraction of @p particles in the cylinder about the z axis of
   * radius @p radius between the heights @p bottom and @p top (mm), sampled
   * on a regular grid of @p n points per diameter of the cylinder (a
   * quadrature of the indicator function; its error falls like 1/n).
   */
  double
  solid_fraction(const std::vector<Particle> &particles,
                 const double                 radius,
                 const double                 bottom,
                 const double                 top,
                 const unsigned int           n = 100);
} // namespace densify
