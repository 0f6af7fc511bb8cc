// The run log: log.txt in the output directory, a stream writing to the
// console and the log at once, and the wall times it reports.
#pragma once

#include <densify/postprocess/statistics.h>

#include <mpi.h>

#include <fstream>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>

namespace densify
{
  /**
   * An ostream writing everything to two others (e.g. the console and
   * log.txt); either may be nullptr.
   */
  class TeeStream : public std::ostream
  {
  public:
    /// Write to @p a and @p b (either may be nullptr); neither is owned.
    TeeStream(std::ostream *a, std::ostream *b);

    /// Destructor.
    ~TeeStream() override;

  private:
    /// The stream buffer passing each character to both.
    std::unique_ptr<std::streambuf> buffer;
  };

  /// Format seconds as "1h02m", "3m05s" or "4.2s".
  std::string
  format_seconds(const double s);

  /**
   * Create the output directory @p directory (rank 0) and open its log.txt
   * (rank 0; the stream of the other ranks is not open); a fresh run (not
   * @p append) removes the checkpoint of an earlier run there, which
   * --resume would otherwise take for its own. Every rank throws InputError
   * if rank 0 fails. Collective over @p comm.
   */
  std::ofstream
  open_log(const std::string &directory,
           const MPI_Comm     comm,
           const bool         append);
  /**
   * The console's line of a finished load step @p s of @p n_steps: time,
   * punch, forces (the pole springs' with @p poles), the relative density
   * (with @p density), the explicit steps or the Newton counts
   * (@p explicit_dynamics), the wall time and the time @p left (s).
   */
  std::string
  progress_line(const StepStatistics &s,
                const unsigned int    n_steps,
                const bool            poles,
                const bool            density,
                const bool            explicit_dynamics,
                const double          left);
} // namespace densify
