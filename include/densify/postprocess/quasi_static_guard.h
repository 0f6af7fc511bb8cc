// The quasi-static guard of explicit runs: at each station, the kinetic
// energy against the internal work and the upper punch force against the
// lower punch's and the die wall's.
#pragma once

#include <densify/postprocess/statistics.h>

#include <string>

namespace densify
{
  /// The limits of Explicit/Maximum kinetic energy ratio and Explicit/Maximum
  /// force imbalance (0: that limit is not checked).
  struct QuasiStaticLimits
  {
    /// Largest kinetic energy as a fraction of the internal work.
    double kinetic_ratio = 0.;
    /// Largest |F_upper - F_lower - F_die| as a fraction of F_upper.
    double force_imbalance = 0.;
    /// Internal work (mJ) below which the kinetic energy is not compared
    /// with it (a scene at rest has neither).
    double work_floor = 0.;
    /// Upper punch force (N) below which the forces are not compared.
    double force_floor = 0.;
  };

  /**
   * What station @p s breaks of @p limits, as the start of an error line
   * ("KE/IE 55 % above Explicit/Maximum kinetic energy ratio = 5 %"), or
   * an empty string when it keeps both.
   */
  std::string
  quasi_static_breach(const StepStatistics &s, const QuasiStaticLimits &limits);

  /// |F_upper - F_lower - F_die| / F_upper of station @p s (0 without an
  /// upper punch force).
  double
  force_imbalance(const StepStatistics &s);
} // namespace densify
