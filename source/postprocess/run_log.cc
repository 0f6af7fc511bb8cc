// The run log: log.txt, the stream to console and log, wall time formatting.
#include <deal.II/base/mpi.h>

#include <densify/postprocess/run_log.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace densify
{
  namespace
  {
    /// A stream buffer writing to two others (console and log file).
    class TeeBuffer : public std::streambuf
    {
    public:
      TeeBuffer(std::streambuf *a, std::streambuf *b)
        : a(a)
        , b(b)
      {}

    protected:
      int
      overflow(int c) override
      {
        if (c == EOF)
          return !EOF;
        const int ra = (a != nullptr ? a->sputc(c) : c);
        const int rb = (b != nullptr ? b->sputc(c) : c);
        return (ra == EOF || rb == EOF) ? EOF : c;
      }
      int
      sync() override
      {
        const int ra = (a != nullptr ? a->pubsync() : 0);
        const int rb = (b != nullptr ? b->pubsync() : 0);
        return (ra == 0 && rb == 0) ? 0 : -1;
      }

    private:
      std::streambuf *a, *b;
    };
  } // namespace



  TeeStream::TeeStream(std::ostream *a, std::ostream *b)
    : std::ostream(nullptr)
    , buffer(std::make_unique<TeeBuffer>(a != nullptr ? a->rdbuf() : nullptr,
                                         b != nullptr ? b->rdbuf() : nullptr))
  {
    rdbuf(buffer.get());
  }



  TeeStream::~TeeStream() = default;



  std::string
  format_seconds(const double s)
  {
    std::ostringstream out;
    if (s >= 3600)
      out << int(s / 3600) << "h" << std::setw(2) << std::setfill('0')
          << int(std::fmod(s, 3600) / 60) << "m";
    else if (s >= 60)
      out << int(s / 60) << "m" << std::setw(2) << std::setfill('0')
          << int(std::fmod(s, 60)) << "s";
    else
      out << std::fixed << std::setprecision(1) << s << "s";
    return out.str();
  }



  std::ofstream
  open_log(const std::string &directory, const MPI_Comm comm, const bool append)
  {
    std::ofstream log;
    std::string   error;
    if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      {
        namespace fs = std::filesystem;
        std::error_code ignored;
        fs::create_directories(directory, ignored);
        errno = 0;
        log.open(directory + "/log.txt",
                 append ? std::ios::app : std::ios::trunc);
        if (!log)
          error = "Output/Directory: " + write_error(directory + "/log.txt");
        else if (!append)
          for (const char *name :
               {"checkpoint", "checkpoint.old", "checkpoint.new"})
            {
              std::error_code removed;
              fs::remove_all(fs::path(directory) / name, removed);
              if (removed)
                error = "Output/Directory: cannot remove the earlier "
                        "run's '" +
                        (fs::path(directory) / name).string() + "' (" +
                        removed.message() + ")";
            }
      }
    error = first_error(error, comm);
    if (!error.empty())
      throw InputError(error);
    return log;
  }


  std::string
  progress_line(const StepStatistics &s,
                const unsigned int    n_steps,
                const bool            poles,
                const bool            density,
                const bool            explicit_dynamics,
                const double          left)
  {
    std::ostringstream out;
    out << "step " << s.step << "/" << n_steps << "  t=" << std::setprecision(4)
        << s.time << " s  punch " << s.punch_displacement << " mm  F_upper "
        << std::setprecision(5) << s.upper_punch_force << " N  F_lower "
        << s.lower_punch_force << " N  F_die " << s.die_wall_radial_force
        << " N  F_stab " << std::setprecision(2) << s.stabilisation_force
        << " N";
    if (poles)
      out << "  F_pole " << std::setprecision(2) << s.pole_force << " N";
    if (density)
      out << "  density " << std::setprecision(4) << 100 * s.relative_density
          << " %";
    out << "  V/V0 min " << std::setprecision(2) << s.min_cell_volume_ratio;
    if (s.phase != static_cast<unsigned int>(PressPhase::load))
      out << "  " << phase_name(static_cast<PressPhase>(s.phase));
    if (explicit_dynamics)
      out << "  explicit " << s.increments << " steps (dt "
          << std::setprecision(3) << s.time_step << " s)  KE/IE "
          << std::setprecision(2)
          << 100. * s.kinetic_energy / std::max(s.internal_work, 1e-300)
          << " %";
    else
      {
        out << "  newton " << s.newton_iterations << " (cg "
            << s.linear_iterations << ", aug " << s.augmentations;
        if (s.cutbacks > 0)
          out << ", " << s.cutbacks << " cut-back(s), " << s.increments
              << " increments";
        if (s.continuations > 0)
          out << ", " << s.continuations << " continuation(s)";
        if (s.failed_newton_iterations > 0)
          out << ", " << s.failed_newton_iterations << " in failed solves";
        if (s.failed_checks > 0)
          out << ", " << s.failed_checks << " unconverged check(s)";
        out << ")";
      }
    out << "  " << format_seconds(s.wall_seconds) << ", ~"
        << format_seconds(left) << " left";
    return out.str();
  }
} // namespace densify
