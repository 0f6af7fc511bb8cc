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
    /// Largest kinetic energy gained since the first station at load_floor
    /// as a fraction of the internal work done since.
    double kinetic_ratio = 0.;
    /// Largest mean of F_upper - F_lower - F_die over the last
    /// QuasiStaticGuard::window stations as a fraction of their mean F_upper.
    double force_imbalance = 0.;
    /**
     * Upper punch force (N) from which the guard judges: the force that
     * gives the compact a mean axial stress of a tenth of the weakest
     * particle's initial yield stress. Below it a loose bed rearranges,
     * which mass scaling makes inertial without a compact that carries the
     * punch; the limits speak of the compaction, not of the rearrangement.
     */
    double load_floor = 0.;
    /// Largest miss of a force-controlled punch's target
    /// (PunchControl::miss()); checked by the Simulator, which knows the
    /// punches.
    double force_control_error = 0.;
  };

  /**
   * Checks the stations of an explicit run against QuasiStaticLimits, from
   * the first station whose upper punch force reaches
   * QuasiStaticLimits::load_floor on. The kinetic energy gained since that
   * station is compared with the internal work done since, at each station:
   * what a loose bed's rearrangement left moving before it (the impacts of
   * rattling particles, whose kinetic energy and impact work grow together
   * whatever the punch speed) is not the compaction's inertia, and a
   * compaction that stays quasi-static gains little. The force balance is
   * compared as a mean over the last stations while the station's upper
   * punch force is at the floor, so that the vibrations of a loose packing,
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

    /// Whether the upper punch force has reached
    /// QuasiStaticLimits::load_floor at a station, from which on the limits
    /// are checked.
    bool
    judging() const;

    /**
     * Add station @p s; returns what it breaks, as the start of an error
     * line ("kinetic energy gained since step 3 55 % of the internal work
     * done since, above Explicit/Maximum kinetic energy ratio = 25 %"), or an
     * empty string when it keeps the limits.
     */
    std::string
    add(const StepStatistics &s);

  private:
    const QuasiStaticLimits limits;
    /// F_upper and F_lower + F_die of the last stations.
    std::deque<std::pair<double, double>> forces;
    /// See judging().
    bool loaded = false;
    /// The first station at the load floor, and its kinetic energy and
    /// internal work (mJ).
    unsigned int              loaded_step = 0;
    std::pair<double, double> loaded_energies;
  };
} // namespace densify
