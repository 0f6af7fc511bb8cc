// Checkpoints of a run: the state at the end of a load step written to
// Output/Directory/checkpoint/, and read back to resume (densify --resume).
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <densify/drivers/driver.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>
#include <densify/postprocess/graphics.h>

#include <string>

namespace densify
{
  /**
   * The checkpoint of a run in Output/Directory/checkpoint/: one file per
   * rank with what identifies the mesh and the parameters, the load step,
   * the run's wall time and the graphics' records, then the system's state
   * (MultiBodySystem::write_checkpoint(): the solution, the punches and each
   * force term's state) and the driver's (Driver::write_checkpoint()). Each
   * part writes and reads its own state; this class owns the file layout,
   * the checks that a checkpoint fits the scene, and the replacement of the
   * previous checkpoint only once the new one is complete. It reads the
   * layouts of earlier densify versions too (format 6 to 9).
   *
   * The mesh is not stored: it is rebuilt from the same parameters (gmsh
   * and the METIS partition are deterministic for the same scene and number
   * of ranks), and the checkpoint records what identifies it (cells, DoFs, a
   * sum of the vertex coordinates, the ranks) to refuse one of another mesh.
   */
  class Checkpoint
  {
  public:
    /// The checkpoints of @p system advanced by @p driver, with the
    /// graphics' records of @p graphics.
    Checkpoint(const Parameters   &parameters,
               MultiBodySystem    &system,
               Driver             &driver,
               GraphicsWriter     &graphics,
               ConditionalOStream &pcout,
               TimerOutput        &timer);

    /// This rank's part of a checkpoint, held in memory.
    struct Snapshot
    {
      /// The load step it ends.
      unsigned int step = 0;
      /// Its scene time.
      double time = 0.;
      /// The serialized state, as write() stores it.
      std::string bytes;
    };

    /// The state at the end of load step @p step, with the run's wall time
    /// @p wall_seconds, serialized in memory (what write() writes).
    Snapshot
    snapshot(const unsigned int step, const double wall_seconds) const;

    /// Write @p snapshot (every rank its own), replacing the previous
    /// checkpoint only once the new one is complete.
    void
    store(const Snapshot &snapshot) const;

    /// store() the snapshot() of load step @p step.
    void
    write(const unsigned int step, const double wall_seconds) const
    {
      store(snapshot(step, wall_seconds));
    }

    /// What read() found.
    struct Resumed
    {
      /// The load step the checkpoint ends.
      unsigned int step = 0;
      /// The run's wall time up to it (s).
      double wall_seconds = 0.;
    };

    /**
     * Load the checkpoint written by write() into the set-up system and
     * driver, and rewrite solution.pvd with the graphics up to it. Throws
     * InputError if there is none or it belongs to another scene, mesh or
     * number of ranks.
     */
    Resumed
    read();

    /// Keep the rows of the CSV file @p filename up to load step @p step
    /// (first column), so that a resumed run appends after them.
    static void
    truncate_rows(const std::string &filename, const unsigned int step);

  private:
    /// Read the rest of a checkpoint of format 6 to 9, whose header
    /// @p version is read, from @p archive into the system and the driver;
    /// returns the load step and wall time, and the graphics' records in
    /// @p records.
    Resumed
    read_earlier_format(boost::archive::binary_iarchive &archive,
                        const unsigned int               version,
                        GraphicsWriter::Records         &records);

    /// Throw InputError if the checkpoint of load step @p step written with
    /// the parameters of @p stored_fingerprint cannot continue in this run
    /// (at the system's time, read from the checkpoint).
    void
    check_schedule(const std::string &stored_fingerprint,
                   const unsigned int step) const;

    const Parameters   &prm;
    MultiBodySystem    &system;
    Driver             &driver;
    GraphicsWriter     &graphics;
    ConditionalOStream &pcout;
    TimerOutput        &timer;
    MPI_Comm            comm;
    const unsigned int  this_rank;
  };
} // namespace densify
