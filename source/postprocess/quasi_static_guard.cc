// The quasi-static guard of explicit runs.
#include <densify/postprocess/quasi_static_guard.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace densify
{
  QuasiStaticGuard::QuasiStaticGuard(const QuasiStaticLimits &limits)
    : limits(limits)
  {}



  bool
  QuasiStaticGuard::active() const
  {
    return limits.kinetic_ratio > 0. || limits.force_imbalance > 0. ||
           limits.force_control_error > 0.;
  }



  bool
  QuasiStaticGuard::judging() const
  {
    return active() && loaded;
  }



  std::string
  QuasiStaticGuard::add(const StepStatistics &s)
  {
    forces.emplace_back(s.upper_punch_force,
                        s.lower_punch_force + s.die_wall_force);
    if (forces.size() > window)
      forces.pop_front();
    const bool at_floor = std::abs(s.upper_punch_force) >= limits.load_floor;
    if (at_floor && !loaded)
      {
        // the first station at the load floor: the energies count from here
        loaded          = true;
        loaded_step     = s.step;
        loaded_energies = {s.kinetic_energy, s.internal_work};
      }
    if (!loaded)
      return "";

    std::ostringstream text;
    text << std::setprecision(3);
    const double gained = s.kinetic_energy - loaded_energies.first;
    const double work   = s.internal_work - loaded_energies.second;
    if (limits.kinetic_ratio > 0. && work > 0. &&
        !(gained <= limits.kinetic_ratio * work))
      text << "kinetic energy gained since step " << loaded_step << " "
           << 100. * gained / work
           << " % of the internal work done since, above Explicit/Maximum "
              "kinetic energy ratio = "
           << 100. * limits.kinetic_ratio << " %";
    if (!at_floor)
      return text.str();

    double upper = 0., carried = 0.;
    for (const auto &[u, c] : forces)
      {
        upper += u;
        carried += c;
      }
    upper /= forces.size();
    carried /= forces.size();
    const double imbalance = std::abs(upper - carried) / std::abs(upper);
    if (limits.force_imbalance > 0. && !(imbalance <= limits.force_imbalance))
      text << (text.tellp() > 0 ? " and " : "") << "F_upper " << upper
           << " N against F_lower + F_die " << carried
           << " N (mean of the last " << forces.size()
           << " station(s): " << 100. * imbalance
           << " % apart, above Explicit/Maximum force imbalance = "
           << 100. * limits.force_imbalance << " %)";
    return text.str();
  }
} // namespace densify
