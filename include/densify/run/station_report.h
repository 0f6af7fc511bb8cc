// The report of a run at each station (the end of a load step): the
// measures of statistics.csv and particles.csv, the graphics, the progress
// line and the run's warnings, and the summaries at its end.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <densify/drivers/driver.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/postprocess/cell_volume.h>
#include <densify/postprocess/graphics.h>
#include <densify/postprocess/statistics.h>

#include <memory>
#include <string>
#include <vector>

namespace densify
{
  /**
   * What a run reports of the MultiBodySystem at each station: the forces,
   * stresses, densities and contact measures of a row of statistics.csv
   * (StepStatistics; the driver fills its own columns), the particles' rows
   * of particles.csv, the graphics every Output/Interval steps, the
   * progress line, and the warnings about cells that collapse and, for
   * explicit runs, about penetration. It reads the system and writes files;
   * it changes no state of the system.
   */
  class StationReport
  {
  public:
    /// The report of @p system, written to Output/Directory.
    StationReport(const Parameters   &parameters,
                  MultiBodySystem    &system,
                  ConditionalOStream &pcout,
                  TimerOutput        &timer);

    /// Print the run's opening lines (size, effects, fidelity, initial
    /// density) and measure the particles' initial volumes.
    void
    start();

    /// Open statistics.csv and particles.csv (rank 0), for a resumed run
    /// (@p resume) keeping their rows up to load step @p first_step - 1 and
    /// appending after them. Throws std::runtime_error on every rank if rank
    /// 0 cannot.
    void
    open(const bool resume, const unsigned int first_step);

    /**
     * Complete the statistics @p s of a station whose driver gave the
     * contact forces @p results (with @p driver's contact record where it
     * keeps one), the punches having been at @p upper_before and
     * @p lower_before at the load step's start: measure the particles,
     * write the rows and the graphics, and warn. @p s.wall_seconds holds
     * the run's wall time at the load step's start, to which record() adds
     * the step's, @p step_timer (started with the step), measures and
     * graphics included, also as @p s.step_seconds. Throws
     * std::runtime_error on every rank if a file cannot be written.
     */
    void
    record(StepStatistics       &s,
           const ContactResults &results,
           const Driver         &driver,
           const double          upper_before,
           const double          lower_before,
           const Timer          &step_timer);

    /// Print the progress line of station @p s, with @p seconds_left the
    /// estimate of the run time left.
    void
    progress(const StepStatistics &s, const double seconds_left) const;

    /// Print the summaries of the whole loading curve (the rows of earlier
    /// runs of a resumed one included).
    void
    summarise() const;

    /// contact_partners() and the die wall's particle_tool_forces() at the
    /// station just reached: from the driver's record of that station where
    /// it keeps one (the same state), else by passes of their own.
    std::pair<std::vector<unsigned int>, std::vector<double>>
    station_contacts(const Driver &driver) const;

    /// Statistics of the steps done so far.
    const std::vector<StepStatistics> &
    statistics() const
    {
      return step_statistics;
    }

    /// The graphics and the records of the .pvd.
    GraphicsWriter graphics;

  private:
    /// Write the .pvtu of this step and rewrite the .pvd, with the
    /// particles' mean stresses of @p measures.
    void
    write_graphics(const unsigned int                  step,
                   const double                        time,
                   const std::vector<ParticleMeasure> &measures);

    /// Warn once per run when the smallest cell volume ratio at step
    /// @p step falls below 0.2 (the run goes on).
    void
    warn_cell_volume(const unsigned int        step,
                     const SmallestCellVolume &smallest);

    /// Warn once per run when station @p s penetrates by more than
    /// Contact/Gap tolerance (explicit runs; the implicit load stepper warns
    /// at each step it cannot meet it).
    void
    warn_penetration(const StepStatistics &s);

    /// The relative density of the particles' volume @p volume between
    /// punches @p gap apart (NaN without a die and both punches).
    double
    density(const double volume, const double gap) const;

    const Parameters   &prm;
    MultiBodySystem    &system;
    ConditionalOStream &pcout;
    TimerOutput        &timer;
    MPI_Comm            comm;
    const unsigned int  this_rank;
    /// Whether the scene has a die and both punches (a density).
    const bool has_density;

    std::vector<StepStatistics>       step_statistics;
    std::unique_ptr<StatisticsWriter> statistics_writer;
    /// particles.csv: per particle and step, volume and mean displacement
    /// (rank 0).
    std::unique_ptr<ParticleTableWriter> particle_writer;
    /// Volume of each particle's mesh at the start (mm^3).
    std::vector<double> initial_volumes;
    /// Whether warn_cell_volume() and warn_penetration() have warned.
    bool cell_volume_warned = false, penetration_warned = false;
  };
} // namespace densify
