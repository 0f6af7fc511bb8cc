// The quasi-static guard of explicit runs.
#include <densify/postprocess/quasi_static_guard.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace densify
{
  double
  force_imbalance(const StepStatistics &s)
  {
    if (!(std::abs(s.upper_punch_force) > 0.))
      return 0.;
    return std::abs(s.upper_punch_force - s.lower_punch_force -
                    s.die_wall_force) /
           std::abs(s.upper_punch_force);
  }



  std::string
  quasi_static_breach(const StepStatistics &s, const QuasiStaticLimits &limits)
  {
    std::ostringstream text;
    text << std::setprecision(3);
    const double ratio = s.kinetic_energy / s.internal_work;
    if (limits.kinetic_ratio > 0. && s.internal_work > limits.work_floor &&
        !(ratio <= limits.kinetic_ratio))
      text << "KE/IE " << 100. * ratio
           << " % above Explicit/Maximum kinetic energy ratio = "
           << 100. * limits.kinetic_ratio << " %";
    const double imbalance = force_imbalance(s);
    if (limits.force_imbalance > 0. &&
        std::abs(s.upper_punch_force) > limits.force_floor &&
        !(imbalance <= limits.force_imbalance))
      text << (text.tellp() > 0 ? " and " : "") << "F_upper "
           << s.upper_punch_force << " N against F_lower + F_die "
           << s.lower_punch_force + s.die_wall_force << " N ("
           << 100. * imbalance
           << " % apart, above Explicit/Maximum force imbalance = "
           << 100. * limits.force_imbalance << " %)";
    return text.str();
  }
} // namespace densify
