// Checkpoints of a run: the file layout, the checks that a checkpoint fits
// the scene, and the replacement of the previous checkpoint only once the
// new one is complete. Each rank writes what it owns (vectors, and each
// force term's state: the quadrature-point history of its cells, the contact
// state of its contact points) into its own file with a boost binary
// archive, as deal.II serializes its own classes.
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <densify/drivers/explicit_driver.h>
#include <densify/drivers/implicit_driver.h>
#include <densify/parameters.h>
#include <densify/run/checkpoint.h>
#include <densify/utilities.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace densify
{
  namespace
  {
    /// Increment when the layout of a checkpoint file changes. Format 10
    /// has each part's state in a piece of its own (the system's, then the
    /// driver's); 6 to 9 interleaved them (read_earlier_format()).
    constexpr unsigned int checkpoint_version = 10;

    /// What identifies the mesh and the run a checkpoint belongs to.
    struct CheckpointHeader
    {
      unsigned int            version  = checkpoint_version;
      unsigned int            n_ranks  = 0;
      unsigned int            rank     = 0;
      unsigned int            n_cells  = 0;
      types::global_dof_index n_dofs   = 0;
      double                  vertices = 0.;
      std::string             fingerprint;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &version &n_ranks &rank &n_cells &n_dofs &vertices &fingerprint;
      }
    };

    /// The first line of @p a that @p b lacks ("no such entry" if none),
    /// for an error message.
    std::string
    first_difference(const std::string &a, const std::string &b)
    {
      std::set<std::string> lines_b;
      std::istringstream    in_b(b);
      for (std::string line; std::getline(in_b, line);)
        lines_b.insert(line);
      std::istringstream in_a(a);
      for (std::string line; std::getline(in_a, line);)
        if (lines_b.count(line) == 0)
          return "'" + line + "'";
      return "no other entry";
    }

    /// The fingerprint @p stored as this densify would have written it, in
    /// the order of @p current: a checkpoint of an earlier densify may hold
    /// entries that are now free to change on --resume (dropped), and lack
    /// entries added since, which that densify in effect had at their
    /// defaults (the default taken).
    std::string
    checked_entries(const std::string &stored, const std::string &current)
    {
      const auto by_key = [](const std::string &text) {
        std::map<std::string, std::string> lines;
        std::istringstream                 in(text);
        for (std::string line; std::getline(in, line);)
          lines[line.substr(0, line.find(" = "))] = line;
        return lines;
      };
      Parameters       defaults;
      ParameterHandler prm;
      defaults.declare(prm);
      const auto         old_lines     = by_key(stored);
      const auto         default_lines = by_key(parameter_fingerprint(prm));
      std::string        result;
      std::istringstream in_current(current);
      for (std::string line; std::getline(in_current, line);)
        {
          const std::string key = line.substr(0, line.find(" = "));
          const auto        old = old_lines.find(key);
          const auto        def = default_lines.find(key);
          if (old != old_lines.end())
            result += old->second + '\n';
          else if (def != default_lines.end())
            result += def->second + '\n';
        }
      return result;
    }

    /// Whether the fingerprint line @p line belongs to the load schedule,
    /// which a resumed implicit run may extend: the end time, the number of
    /// steps and the load histories.
    bool
    schedule_entry(const std::string &line)
    {
      const std::string key    = line.substr(0, line.find(" = "));
      const std::string suffix = " history";
      return key == "Time stepping/End time" ||
             key == "Time stepping/Number of steps" ||
             (key.size() > suffix.size() &&
              key.compare(key.size() - suffix.size(), suffix.size(), suffix) ==
                0);
    }

    /// @p fingerprint without its schedule entries, which go to
    /// @p schedule (entry name to value).
    std::string
    split_schedule(const std::string                  &fingerprint,
                   std::map<std::string, std::string> &schedule)
    {
      std::string        rest;
      std::istringstream in(fingerprint);
      for (std::string line; std::getline(in, line);)
        if (schedule_entry(line))
          {
            const std::size_t eq = line.find(" = ");
            schedule[line.substr(0, eq)] =
              eq == std::string::npos ? std::string() : line.substr(eq + 3);
          }
        else
          rest += line + '\n';
      return rest;
    }

    /// Empty if the schedule @p current continues @p stored from a
    /// checkpoint at time @p t: the same load step (End time / Number of
    /// steps), an end time not before @p t, and every load history equal on
    /// [0, t]. Otherwise what breaks it, for an error message.
    std::string
    schedule_break(const std::map<std::string, std::string> &stored,
                   const std::map<std::string, std::string> &current,
                   const double                              t)
    {
      const auto value = [](const std::map<std::string, std::string> &s,
                            const std::string                        &key) {
        const auto entry = s.find(key);
        return entry == s.end() ? std::string() : entry->second;
      };
      const auto load_step = [&](const std::map<std::string, std::string> &s) {
        return Utilities::string_to_double(value(s, "Time stepping/End time")) /
               Utilities::string_to_int(
                 value(s, "Time stepping/Number of steps"));
      };
      const auto seconds = [](const double x) {
        std::ostringstream text;
        text << std::setprecision(8) << x << " s";
        return text.str();
      };
      if (std::abs(load_step(stored) - load_step(current)) >
          1e-12 * load_step(stored))
        return "a load step End time / Number of steps of " +
               seconds(load_step(current)) + " instead of " +
               seconds(load_step(stored));
      if (Utilities::string_to_double(
            value(current, "Time stepping/End time")) < t * (1. - 1e-12))
        return "an End time before the checkpoint's time " + seconds(t);
      for (const auto &[key, old_text] : stored)
        {
          const std::string new_text = value(current, key);
          if (!schedule_entry(key) || key.rfind("Time stepping/", 0) == 0 ||
              new_text == old_text)
            continue;
          const std::string broken =
            "'" + key + " = " + new_text + "', which differs from '" +
            old_text + "' before the checkpoint's time " + seconds(t);
          if (Utilities::trim(old_text).empty() ||
              Utilities::trim(new_text).empty())
            return broken;
          const auto          old_table = parse_table(old_text, key);
          const auto          new_table = parse_table(new_text, key);
          std::vector<double> times     = {0., t};
          for (const auto *table : {&old_table, &new_table})
            for (const auto &[time, v] : *table)
              if (time < t)
                times.push_back(time);
          for (const double time : times)
            {
              const double a = interpolate(old_table, time);
              if (std::abs(interpolate(new_table, time) - a) >
                  1e-12 * (1. + std::abs(a)))
                return broken;
            }
        }
      return std::string();
    }
  } // namespace



  Checkpoint::Checkpoint(const Parameters   &parameters,
                         MultiBodySystem    &system,
                         Driver             &driver,
                         GraphicsWriter     &graphics,
                         ConditionalOStream &pcout,
                         TimerOutput        &timer)
    : prm(parameters)
    , system(system)
    , driver(driver)
    , graphics(graphics)
    , pcout(pcout)
    , timer(timer)
    , comm(system.comm)
    , this_rank(Utilities::MPI::this_mpi_process(system.comm))
  {}



  Checkpoint::Snapshot
  Checkpoint::snapshot(const unsigned int step, const double wall_seconds) const
  {
    TimerOutput::Scope t(timer, "Checkpoint");
    CheckpointHeader   header;
    header.n_ranks     = Utilities::MPI::n_mpi_processes(comm);
    header.rank        = this_rank;
    header.n_cells     = system.triangulation.n_active_cells();
    header.n_dofs      = system.dof_handler.n_dofs();
    header.fingerprint = prm.fingerprint;
    for (const Point<3> &v : system.triangulation.get_vertices())
      header.vertices += v[0] + v[1] + v[2];

    Snapshot snapshot;
    snapshot.step = step;
    snapshot.time = system.current_time;
    std::ostringstream out(std::ios::binary);
    {
      boost::archive::binary_oarchive archive(out);
      unsigned int                    last_step = step;
      double                          wall      = wall_seconds;
      // the .pvd's records of the graphics written so far
      const GraphicsWriter::Records    &records = graphics.records();
      archive &header &last_step &wall &records;
      system.write_checkpoint(archive);
      driver.write_checkpoint(archive);
    }
    snapshot.bytes = out.str();
    return snapshot;
  }



  void
  Checkpoint::store(const Snapshot &snapshot) const
  {
    TimerOutput::Scope t(timer, "Checkpoint");
    namespace fs         = std::filesystem;
    const fs::path dir   = prm.output.directory;
    const fs::path fresh = dir / "checkpoint.new";
    std::string    error;
    if (this_rank == 0)
      {
        std::error_code failed;
        fs::remove_all(fresh, failed);
        if (!failed)
          fs::create_directories(fresh, failed);
        if (failed)
          error = "checkpoint: cannot create '" + fresh.string() + "' (" +
                  failed.message() + ")";
      }
    error = first_error(error, comm);
    if (!error.empty())
      throw std::runtime_error(error);

    const fs::path file =
      fresh / ("rank_" + std::to_string(this_rank) + ".bin");
    errno = 0;
    {
      std::ofstream out(file, std::ios::binary);
      out.write(snapshot.bytes.data(), snapshot.bytes.size());
      // complete on disk only once the stream is flushed and closed
      out.close();
      if (out.fail())
        error = "checkpoint: " + write_error(file.string());
    }
    error = first_error(error, comm);

    // replace the previous checkpoint only now that the new one is complete
    if (this_rank == 0 && error.empty())
      {
        const fs::path info_name = fresh / "info.txt";
        errno                    = 0;
        std::ofstream info(info_name);
        info << "load step " << snapshot.step << " of " << prm.time.n_steps
             << ", time " << std::setprecision(10) << snapshot.time
             << ", written by " << Utilities::MPI::n_mpi_processes(comm)
             << " MPI rank(s); "
             << (snapshot.step < prm.time.n_steps ?
                   "continue with: densify FILE.prm --resume\n" :
                   "press further with densify FILE.prm --resume and a "
                   "longer Time stepping/End time, Number of steps and load "
                   "history\n");
        info.close();
        if (info.fail())
          error = "checkpoint: " + write_error(info_name.string());
        else
          try
            {
              const fs::path current = dir / "checkpoint",
                             old     = dir / "checkpoint.old";
              fs::remove_all(old);
              if (fs::exists(current))
                fs::rename(current, old);
              fs::rename(fresh, current);
              fs::remove_all(old);
            }
          catch (const std::exception &e)
            {
              error = "checkpoint: " + one_line(e.what());
            }
      }
    error = first_error(error, comm);
    if (!error.empty())
      {
        // the previous checkpoint, if any, stays
        std::error_code ignored;
        if (this_rank == 0)
          fs::remove_all(fresh, ignored);
        throw std::runtime_error(error);
      }
    pcout << "  checkpoint written after step " << snapshot.step << std::endl;
  }



  Checkpoint::Resumed
  Checkpoint::read()
  {
    namespace fs       = std::filesystem;
    const fs::path dir = prm.output.directory;
    // a run stopped between the two renames of store() left its last
    // complete checkpoint in checkpoint.old
    fs::path from = dir / "checkpoint";
    if (!fs::exists(from / "info.txt") && fs::exists(dir / "checkpoint.old"))
      from = dir / "checkpoint.old";
    const fs::path file = from / ("rank_" + std::to_string(this_rank) + ".bin");
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);

    std::ifstream in(file, std::ios::binary);
    if (Utilities::MPI::min(in ? 1 : 0, comm) == 0)
      {
        // a checkpoint of another number of ranks, or none
        unsigned int n_files = 0;
        if (this_rank == 0 && fs::is_directory(from))
          for (const auto &entry : fs::directory_iterator(from))
            if (entry.path().filename().string().rfind("rank_", 0) == 0)
              ++n_files;
        n_files = Utilities::MPI::broadcast(comm, n_files, 0);
        if (n_files > 0 && n_files != n_ranks)
          throw InputError(
            "--resume: the checkpoint in '" + from.string() +
            "' was written by " + std::to_string(n_files) +
            " MPI rank(s), this run has " + std::to_string(n_ranks) +
            "; resume with mpirun -np " + std::to_string(n_files));
        throw InputError(
          "--resume: no checkpoint '" + file.string() +
          "' (Output/Directory holds none for this number of ranks); run "
          "without --resume to start from the beginning");
      }

    // the .pvd's records of the graphics up to the checkpoint
    GraphicsWriter::Records records;
    CheckpointHeader        header;
    Resumed                 resumed;
    try
      {
        boost::archive::binary_iarchive archive(in);
        archive                        &header;
        if (header.version != checkpoint_version &&
            (header.version < 6 || header.version > 9))
          throw InputError(
            "--resume: checkpoint '" + file.string() + "' has format version " +
            std::to_string(header.version) +
            ", this densify "
            "reads 6 to " +
            std::to_string(checkpoint_version) + "; run without --resume");
        if (header.n_ranks != n_ranks)
          throw InputError(
            "--resume: the checkpoint was written by " +
            std::to_string(header.n_ranks) + " MPI rank(s), this run has " +
            std::to_string(n_ranks) + "; resume with mpirun -np " +
            std::to_string(header.n_ranks));
        if (!header.fingerprint.empty())
          header.fingerprint =
            checked_entries(header.fingerprint, prm.fingerprint);
        // the load schedule may go on beyond the stopped run's end (a
        // compact pressed further): compared apart, once the checkpoint's
        // time is known (check_schedule())
        std::map<std::string, std::string> stored_schedule, schedule;
        const std::string                  stored_rest =
          split_schedule(header.fingerprint, stored_schedule);
        const std::string rest = split_schedule(prm.fingerprint, schedule);
        if (!prm.fingerprint.empty() && !header.fingerprint.empty() &&
            stored_rest != rest)
          throw InputError(
            "--resume: the checkpoint was written with other parameters (it "
            "has " +
            first_difference(stored_rest, rest) + ", this run " +
            first_difference(rest, stored_rest) +
            "); resume with the parameters of the stopped run");
        double vertices = 0;
        for (const Point<3> &v : system.triangulation.get_vertices())
          vertices += v[0] + v[1] + v[2];
        if (header.n_cells != system.triangulation.n_active_cells() ||
            header.n_dofs != system.dof_handler.n_dofs() ||
            std::abs(header.vertices - vertices) >
              1e-9 * (1 + std::abs(vertices)))
          throw InputError("--resume: the checkpoint's mesh (" +
                           std::to_string(header.n_cells) + " cells, " +
                           std::to_string(header.n_dofs) +
                           " DoFs) is not the one this scene makes; run "
                           "without --resume");
        if (header.version == checkpoint_version)
          {
            archive &resumed.step &resumed.wall_seconds &records;
            system.read_checkpoint(archive);
            driver.read_checkpoint(archive);
          }
        else
          resumed = read_earlier_format(archive, header.version, records);
        check_schedule(header.fingerprint, resumed.step);
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const std::exception &e)
      {
        throw InputError("--resume: cannot read the checkpoint '" +
                         file.string() + "' (" + e.what() +
                         "); run without --resume");
      }
    driver.resume();

    // the .pvd lists the graphics up to the checkpoint only, also when the
    // resumed run writes none
    graphics.set_records(records);
    std::string error;
    if (this_rank == 0 &&
        (!records.empty() || fs::exists(dir / "solution.pvd")))
      {
        const fs::path tmp = dir / "solution.pvd.tmp";
        errno              = 0;
        std::ofstream pvd(tmp);
        DataOutBase::write_pvd_record(pvd, records);
        pvd.close();
        if (pvd.fail())
          error = "--resume: " + write_error(tmp.string());
        else
          fs::rename(tmp, dir / "solution.pvd");
      }
    error = first_error(error, comm);
    if (!error.empty())
      throw std::runtime_error(error);
    pcout << "Resumed from the checkpoint after step " << resumed.step
          << " (time " << system.current_time << ") in " << from.string() << "/"
          << std::endl;
    return resumed;
  }



  void
  Checkpoint::check_schedule(const std::string &stored_fingerprint,
                             const unsigned int step) const
  {
    if (step >= prm.time.n_steps)
      throw InputError(
        "--resume: the checkpoint is of the run's last step " +
        std::to_string(step) +
        "; to press further, resume with a longer Time stepping/End "
        "time, Number of steps (the same load step) and load history");
    if (stored_fingerprint.empty() || prm.fingerprint.empty())
      return;
    std::map<std::string, std::string> stored_schedule, schedule;
    split_schedule(stored_fingerprint, stored_schedule);
    split_schedule(prm.fingerprint, schedule);
    if (stored_schedule == schedule)
      return;
    const std::string broken =
      schedule_break(stored_schedule, schedule, system.current_time);
    if (!broken.empty())
      throw InputError(
        "--resume: this run has " + broken +
        "; a resumed run may only go on beyond the stopped run's "
        "schedule (the same load step, the load histories unchanged "
        "up to the checkpoint)");
    if (system.effects.method != Method::implicit)
      throw InputError(
        "--resume: Time stepping/End time, Number of steps and the "
        "load histories may change on resume only with Solver/Method "
        "= implicit (an explicit run maps the schedule onto "
        "Explicit/Loading time); resume with the stopped run's "
        "schedule");
  }



  Checkpoint::Resumed
  Checkpoint::read_earlier_format(boost::archive::binary_iarchive &archive,
                                  const unsigned int               version,
                                  GraphicsWriter::Records         &records)
  {
    // formats 6 to 9 interleave the system's, the load stepper's and the
    // explicit driver's state; each method's fields were written by both
    Resumed               resumed;
    std::vector<double>   solution_values;
    ImplicitDriver::Saved implicit;
    ExplicitDriver::Saved saved;
    archive &resumed.step &system.current_time &system.current_upper &implicit
      .next_increment &implicit.last_travel &resumed
      .wall_seconds &solution_values &implicit.increment &records &saved
      .dynamics &saved.work &saved.factors &saved.calibration &saved
      .bound &saved.updates &saved.mode &saved.n_explicit;
    // format 6 lacks the punch controls' state, format 7 the lower punch's,
    // which a run of that densify (displacement control only) left at their
    // start; format 8 the calibration's target (its explicit runs raised
    // the calibration at once)
    if (version >= 7)
      archive &system.punch_control;
    if (version >= 8)
      archive &system.lower_control;
    saved.target = saved.calibration;
    if (version >= 9)
      archive &saved.target;
    for (ForceTerm *term : system.force_terms())
      term->read_checkpoint(archive);
    system.take_up_solution(solution_values);

    // the driver's part as format 10 has it
    std::ostringstream out(std::ios::binary);
    {
      boost::archive::binary_oarchive driver_archive(out);
      if (dynamic_cast<ImplicitDriver *>(&driver) != nullptr)
        driver_archive &implicit;
      else
        driver_archive &saved;
    }
    std::istringstream              in(out.str(), std::ios::binary);
    boost::archive::binary_iarchive driver_archive(in);
    driver.read_checkpoint(driver_archive);
    return resumed;
  }



  void
  Checkpoint::truncate_rows(const std::string &filename,
                            const unsigned int step)
  {
    std::ifstream            in(filename);
    std::vector<std::string> kept;
    for (std::string line; std::getline(in, line);)
      {
        // the header, and rows whose step (first column) is at most step
        const std::string first = line.substr(0, line.find(','));
        const bool        is_row =
          !first.empty() &&
          first.find_first_not_of("0123456789") == std::string::npos;
        if (!is_row || std::stoul(first) <= step)
          kept.push_back(line);
      }
    in.close();
    const std::string tmp = filename + ".tmp";
    errno                 = 0;
    std::ofstream out(tmp);
    for (const std::string &line : kept)
      out << line << '\n';
    out.close();
    if (out.fail())
      {
        // the file stays as it was
        const std::string error = "--resume: " + write_error(tmp);
        std::error_code   ignored;
        std::filesystem::remove(tmp, ignored);
        throw std::runtime_error(error);
      }
    std::filesystem::rename(tmp, filename);
  }
} // namespace densify
