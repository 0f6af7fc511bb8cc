// The Simulator's watch over explicit runs: the quasi-static guard's limits
// and its stop, and the warning about penetration.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <densify/postprocess/quasi_static_guard.h>
#include <densify/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <type_traits>

namespace densify
{
  QuasiStaticLimits
  Simulator::quasi_static_limits() const
  {
    QuasiStaticLimits limits;
    // high-speed compaction (no mass scaling) has inertia by intent
    if (system.effects.method != Method::explicit_dynamics ||
        system.effects.mass_scaling == MassScaling::none)
      return limits;
    limits.kinetic_ratio       = prm.explicit_dynamics.max_kinetic_ratio;
    limits.force_imbalance     = prm.explicit_dynamics.max_force_imbalance;
    limits.force_control_error = prm.explicit_dynamics.max_force_control_error;
    // the guard judges from the force that gives the compact a mean axial
    // stress of a tenth of the weakest particle's initial yield stress (for
    // laws that do not yield, the stress of an elastic strain of 1e-3) over
    // the die's bore (without a die, over the particles' cross-sections):
    // below it a loose bed rearranges, and mass scaling makes that inertial
    // (the inertial number grows as the square root of the scaled density
    // over the pressure)
    double stress = std::numeric_limits<double>::infinity();
    for (const auto &material : system.particle_material)
      stress = std::min({stress,
                         material->initial_yield_stress(),
                         1e-3 * material->youngs_modulus()});
    limits.load_floor = 0.1 * stress * system.pressed_area();
    return limits;
  }



  void
  Simulator::check_quasi_static(const StepStatistics &s,
                                QuasiStaticGuard     &guard)
  {
    std::string breach = guard.add(s);
    std::string advice = "raise Explicit/Number of steps (now " +
                         std::to_string(prm.explicit_dynamics.n_steps) + ")";
    // a loose bed that settles dynamically in the first stations: a slower
    // start gives them more explicit steps at the same total (the paper
    // scene at 10,000 steps stops at step 9 with the default ramp and runs
    // within the limits with 0.2, doc/performance.md)
    if (s.time <= 0.2 * prm.time.end_time &&
        prm.explicit_dynamics.ramp_fraction < 0.2)
      {
        std::ostringstream ramp;
        ramp << " or Explicit/Ramp fraction (now "
             << prm.explicit_dynamics.ramp_fraction
             << "; 0.2 starts the punch slower while a loose bed settles)";
        advice += ramp.str();
      }
    // a punch under force control that misses its target
    const double limit = prm.explicit_dynamics.max_force_control_error;
    for (const auto &[control, punch] :
         {std::make_pair(&system.punch_control, "upper"),
          std::make_pair(&system.lower_control, "lower")})
      if (breach.empty() && limit > 0. && control->miss() > limit)
        {
          std::ostringstream text;
          text << "the " << punch << " punch's force missed its target by "
               << std::setprecision(3) << 100. * control->miss()
               << " % of the larger of the target and the largest force so "
                  "far, above Explicit/Maximum force control error = "
               << 100. * limit << " %";
          breach = text.str();
          advice += ", or let the target change slowly (the punch presses "
                    "the compact with the target as a load, and a compact "
                    "that has too little time per station to follow it "
                    "lags or rings), or use Solver/Method = implicit";
        }
    if (breach.empty())
      return;
    std::ostringstream text;
    text << "the explicit run is no longer quasi-static at step " << s.step
         << " (punch " << s.punch_displacement << " mm): " << breach << "; "
         << advice;
    if (guard_snapshot.bytes.empty())
      text << "; no earlier station of this run was judged within the "
              "limits, so "
              "no checkpoint is written";
    else
      {
        store_checkpoint(guard_snapshot);
        text << "; the last station within them that was kept (step "
             << guard_snapshot.step << ") is in " << prm.output.directory
             << "/checkpoint/: continue from it with --resume and more steps";
      }
    throw std::runtime_error(text.str());
  }



  void
  Simulator::warn_penetration(const StepStatistics &s)
  {
    // once per run: an explicit run's penalty leaves the same penetration
    // station after station
    if (penetration_warned || !(s.max_penetration > prm.contact.gap_tolerance))
      return;
    penetration_warned = true;
    pcout << "  warning: penetration " << std::setprecision(3)
          << s.max_penetration
          << " mm above Contact/Gap tolerance = " << prm.contact.gap_tolerance
          << " mm at step " << s.step
          << " (printed once; statistics.csv has max_penetration of every "
             "step): ";
    // the multipliers remove a lasting penetration over about their number
    // of steps, not a passing one
    if (prm.explicit_dynamics.multiplier_steps == 0)
      pcout << "raise Explicit/Contact multiplier steps from 0 (e.g. 200) or "
               "Explicit/Contact stiffness";
    else
      pcout << "raise Explicit/Contact stiffness (Explicit/Contact multiplier "
               "steps = "
            << prm.explicit_dynamics.multiplier_steps
            << " removes a lasting penetration over about as many explicit "
               "steps)";
    pcout << std::endl;
  }
} // namespace densify
