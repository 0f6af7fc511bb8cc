// The stop of an explicit run that is no longer quasi-static: the guard's
// limits, the snapshot of the last station within them, and the error.
#pragma once

#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/postprocess/quasi_static_guard.h>
#include <densify/postprocess/statistics.h>
#include <densify/run/checkpoint.h>

namespace densify
{
  /**
   * Watches the stations of an explicit run whose mass scaling sets the
   * step (Explicit/Maximum kinetic energy ratio, Maximum force imbalance,
   * Maximum force control error; QuasiStaticGuard) and stops it at the first
   * station beyond the limits, with the checkpoint of a recent station
   * within them. Inactive for other runs.
   */
  class QuasiStaticStop
  {
  public:
    /// The watch over the run of @p system, whose checkpoints @p checkpoint
    /// writes.
    QuasiStaticStop(const Parameters      &parameters,
                    const MultiBodySystem &system,
                    const Checkpoint      &checkpoint);

    /**
     * Judge station @p s (its rows written, so that they show why it
     * stops): if it breaks the limits, store the kept snapshot as the
     * checkpoint (if there is one) and throw std::runtime_error naming the
     * breach and Explicit/Number of steps. Otherwise keep the station's
     * snapshot for such a stop, at most every 50 times its own cost in run
     * time, where @p s is not the last of @p n_steps.
     */
    void
    check(const StepStatistics &s, const unsigned int n_steps);

    /// Write the checkpoint of load step @p step, with the run's wall time
    /// @p wall_seconds: the kept snapshot if it is of that step.
    void
    write_checkpoint(const unsigned int step, const double wall_seconds) const;

    /// The limits of the guard: those of subsection Explicit for an
    /// explicit run whose mass scaling sets the step, else none.
    static QuasiStaticLimits
    limits(const Parameters &parameters, const MultiBodySystem &system);

  private:
    const Parameters      &prm;
    const MultiBodySystem &system;
    const Checkpoint      &checkpoint;
    QuasiStaticGuard       guard;
    /// A recent station within the limits, kept for the checkpoint of a
    /// run that leaves them.
    Checkpoint::Snapshot snapshot;
    /// Wall time of the run when the snapshot was taken, and what taking it
    /// cost (s).
    double snapshot_wall = 0., snapshot_cost = 0.;
  };
} // namespace densify
