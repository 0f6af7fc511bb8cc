// The quasi-static guard of explicit runs: at each station, the kinetic
// energy against the internal work and the upper punch force against the
// lower punch's and the die wall's.
#pragma once

#include <densify/postprocess/statistics.h>

#include <deque>
#include <string>

namespace densify
{
  /// The limits of Explicit/Maximum kinetic energy ratio and Explicit/Maximum
  /// force imbalance (0: that limit is not checked).
  struct QuasiStaticLimits
  {
    /// Largest kinetic energy as a fraction of the internal work.
    double kinetic_ratio = 0.;
    /// Largest mean of F_upper - F_lower - F_die over the last
    /// QuasiStaticGuard::window stations as a fraction of their mean F_upper.
    double force_imbalance = 0.;
    /// Internal work (mJ) below which the kinetic energy is not compared
    /// with it (a scene at rest has neither).
    double work_floor = 0.;
    /// Mean upper punch force (N) below which the forces are not compared.
    double force_floor = 0.;
  };

  /**
   * Checks the stations of an explicit run against QuasiStaticLimits. The
   * kinetic energy is compared at each station; the force balance as a mean
   * over the last stations, so that the vibrations of a loose packing,
   * which move the lower punch force above and below the upper one from
   * station to station, cancel, and a lasting imbalance (a compact that
   * accelerates, or a lower punch that carries nothing) does not.
   */
  class QuasiStaticGuard
  {
  public:
    /// Stations in the mean of the force balance.
    static constexpr unsigned int window = 10;

    /// A guard with @p limits.
    explicit QuasiStaticGuard(const QuasiStaticLimits &limits);

    /// Whether any limit is checked.
    bool
    active() const;

    /**
     * Add station @p s; returns what it breaks, as the start of an error
     * line ("KE/IE 55 % above Explicit/Maximum kinetic energy ratio =
     * 25 %"), or an empty string when it keeps the limits.
     */
    std::string
    add(const StepStatistics &s);

  private:
    const QuasiStaticLimits limits;
    /// F_upper and F_lower + F_die of the last stations.
    std::deque<std::pair<double, double>> forces;
  };
} // namespace densify
