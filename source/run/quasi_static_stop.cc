// The stop of an explicit run that is no longer quasi-static: the guard's
// limits, the snapshot of the last station within them, and the error.
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <densify/run/quasi_static_stop.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace densify
{
  QuasiStaticStop::QuasiStaticStop(const Parameters      &parameters,
                                   const MultiBodySystem &system,
                                   const Checkpoint      &checkpoint)
    : prm(parameters)
    , system(system)
    , checkpoint(checkpoint)
    , guard(limits(parameters, system))
  {}



  QuasiStaticLimits
  QuasiStaticStop::limits(const Parameters &prm, const MultiBodySystem &system)
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
  QuasiStaticStop::write_checkpoint(const unsigned int step,
                                    const double       wall_seconds) const
  {
    if (snapshot.step == step && !snapshot.bytes.empty())
      checkpoint.store(snapshot);
    else
      checkpoint.write(step, wall_seconds);
  }



  void
  QuasiStaticStop::check(const StepStatistics &s, const unsigned int n_steps)
  {
    if (!guard.active())
      return;
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
      {
        // the snapshot for the checkpoint of a stop at most every 50 times
        // its own cost in run time (every station of the light layer, every
        // few of the paper scene), so that it costs at most 2 %. Each rank
        // reads its own clock, so the ranks agree on it: taking a snapshot
        // is collective (its timer section synchronises the ranks), and a
        // rank that took one alone would wait there forever
        if (guard.judging() && s.step < n_steps &&
            Utilities::MPI::max(
              s.wall_seconds - snapshot_wall >= 50. * snapshot_cost ? 1 : 0,
              system.comm) > 0)
          {
            Timer taking;
            snapshot      = checkpoint.snapshot(s.step, s.wall_seconds);
            snapshot_cost = taking.wall_time();
            snapshot_wall = s.wall_seconds;
          }
        return;
      }
    std::ostringstream text;
    text << "the explicit run is no longer quasi-static at step " << s.step
         << " (punch " << s.punch_displacement << " mm): " << breach << "; "
         << advice;
    if (snapshot.bytes.empty())
      text << "; no earlier station of this run was judged within the "
              "limits, so "
              "no checkpoint is written";
    else
      {
        checkpoint.store(snapshot);
        text << "; the last station within them that was kept (step "
             << snapshot.step << ") is in " << prm.output.directory
             << "/checkpoint/: continue from it with --resume and more steps";
      }
    throw std::runtime_error(text.str());
  }
} // namespace densify
