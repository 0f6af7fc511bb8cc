// What the Simulator asks of a solution method's driver.
#pragma once

#include <densify/assembly/force_term.h>
#include <densify/multi_body_system.h>
#include <densify/postprocess/statistics.h>

#include <vector>

namespace densify
{
  /**
   * The driver of a solution method over a MultiBodySystem, chosen once by
   * Effects::method: the ImplicitDriver (Newton per increment) or the
   * ExplicitDriver (explicit dynamics). The Simulator sets it up around the
   * system's force terms, starts it, and lets it advance the system from
   * station to station (the load steps' ends); the driver reports its own
   * columns of each station's statistics.
   */
  class Driver
  {
  public:
    virtual ~Driver() = default;

    /// Set up what the method needs before the force terms are built and
    /// return the contact penalty of each particle they take (MPa/mm).
    virtual std::vector<double>
    prepare() = 0;

    /// Set up what the method needs once the force terms are built.
    virtual void
    setup()
    {}

    /// Start the run (at rest, or at a checkpoint's state that is then
    /// restored).
    virtual void
    start()
    {}

    /**
     * Advance the system to @p time, the end of load step @p step, from the
     * last accepted state; return the contact forces there and fill this
     * method's columns of @p s (iterations and increments, or explicit steps
     * and the energy account). Throws ConvergenceError if the step fails.
     */
    virtual ContactResults
    advance(const double time, const unsigned int step, StepStatistics &s) = 0;

    /// The time the method integrates at scene time @p scene_time (s): the
    /// scene time itself unless the method maps it.
    virtual double
    physical_time(const double scene_time) const
    {
      return scene_time;
    }

    /// The contact record of the last station's evaluation, where the
    /// method keeps one (else null: the Simulator evaluates anew).
    virtual const ContactRecord *
    station_record() const
    {
      return nullptr;
    }

    /// Write the method's own state at a station (this rank's part) into a
    /// checkpoint.
    virtual void
    write_checkpoint(boost::archive::binary_oarchive &archive) const = 0;

    /// Read what write_checkpoint() wrote; resume() takes it up once the
    /// system holds the checkpoint's state.
    virtual void
    read_checkpoint(boost::archive::binary_iarchive &archive) = 0;

    /// Continue from the state read by read_checkpoint(), the system being
    /// at the checkpoint's state. Throws InputError if the state does not
    /// fit this run.
    virtual void
    resume() = 0;
  };
} // namespace densify
