// The densify executable: command line, parameter handling and error reporting.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <densify/effects.h>
#include <densify/geometry/deposition.h>
#include <densify/geometry/packing.h>
#include <densify/parameters.h>
#include <densify/scene.h>
#include <densify/simulator.h>
#include <densify/utilities.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
  const char *usage =
    "Usage:\n"
    "  densify FILE.prm [--set \"Subsection/Name=value\"]...   run a scene\n"
    "  densify --validate FILE.prm [--set ...]              check a scene "
    "without running it\n"
    "  densify FILE.prm --resume [--set ...]                continue a "
    "stopped run from its checkpoint\n"
    "  densify --print-parameters                            print every "
    "parameter with its documentation\n"
    "  densify --help                                        this text\n"
    "\n"
    "Run in parallel with: mpirun -np N densify FILE.prm\n"
    "Options of a run: --stop-after N stops after load step N with a "
    "checkpoint (as SIGINT or SIGTERM does after the current step); "
    "--resume continues from Output/Directory/checkpoint/ with the same "
    "parameters and number of ranks (a run without --resume removes the "
    "checkpoint of an earlier run in its directory).\n"
    "--set overrides an entry of FILE.prm (repeatable); nested subsections "
    "are separated by '/', e.g.\n"
    "  densify prm/hertz.prm --set \"Tools/Upper punch/Displacement "
    "history=0:0, 1:0.02\"\n"
    "Exit codes: 0 success, 1 the run failed (e.g. Newton did not "
    "converge), 2 bad input, 3 stopped early with a checkpoint (--stop-after, "
    "SIGINT, SIGTERM).\n";

  /// Set by the first SIGINT or SIGTERM: stop after the current load step.
  volatile std::sig_atomic_t stop_requested = 0;

  /// The handler of the first SIGINT/SIGTERM; a second one acts as usual.
  extern "C" void
  request_stop(int signal_number)
  {
    stop_requested = 1;
    std::signal(signal_number, SIG_DFL);
  }

  /**
   * A process started without an MPI launcher (no mpirun, srun or hydra
   * variables) is a singleton: Open MPI would start a helper daemon for it
   * and probe every network transport, about 0.4 s of a 0.8 s start. Such a
   * process talks to nobody, so it is told to do neither: an isolated
   * singleton that sends only to itself (Open MPI's MCA variables; other
   * MPI libraries ignore them). Isolated singletons all name their session
   * directory jf.0 under one directory per user and host, and one that
   * ends removes what another that starts is creating (Open MPI issue
   * 3818; seen as "orte_init failed" under ctest -j2): each gets a
   * directory of its own for it, removed when the process ends. A
   * variable the user has set is left alone.
   */
  class LeanSingletonStart
  {
  public:
    LeanSingletonStart()
    {
      for (const char *launcher : {"OMPI_COMM_WORLD_SIZE",
                                   "PMIX_RANK",
                                   "PMI_RANK",
                                   "PMI_SIZE",
                                   "MPI_LOCALNRANKS"})
        if (std::getenv(launcher) != nullptr)
          return;
      setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
      setenv("OMPI_MCA_pml", "ob1", 0);
      setenv("OMPI_MCA_btl", "self", 0);
      if (std::getenv("OMPI_MCA_orte_tmpdir_base") == nullptr)
        {
          const char *tmp  = std::getenv("TMPDIR");
          std::string base = (tmp != nullptr && *tmp != '\0') ? tmp : "/tmp";
          std::string name = base + "/densify-mpi-XXXXXX";
          if (mkdtemp(name.data()) != nullptr)
            {
              directory = name;
              setenv("OMPI_MCA_orte_tmpdir_base", directory.c_str(), 1);
            }
        }
    }

    ~LeanSingletonStart()
    {
      if (!directory.empty())
        {
          std::error_code ignored;
          std::filesystem::remove_all(directory, ignored);
        }
    }

  private:
    /// The session directory's base of this process (empty if none).
    std::string directory;
  };



  /// Whether every rank of @p comm reaches this call within @p seconds: a
  /// non-blocking barrier on a communicator used for nothing else, so that it
  /// cannot match a collective operation another rank waits in.
  bool
  all_ranks_arrive(const MPI_Comm comm, const double seconds)
  {
    MPI_Request request;
    MPI_Ibarrier(comm, &request);
    const auto start = std::chrono::steady_clock::now();
    for (;;)
      {
        int done = 0;
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done != 0)
          return true;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                          start)
              .count() > seconds)
          return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
  }

  /// MPI_COMM_WORLD duplicated for all_ranks_arrive(), freed at the end.
  struct ErrorCommunicator
  {
    ErrorCommunicator()
    {
      MPI_Comm_dup(MPI_COMM_WORLD, &comm);
    }
    ~ErrorCommunicator()
    {
      MPI_Comm_free(&comm);
    }
    MPI_Comm comm;
  };
} // namespace

int
main(int argc, char **argv)
{
  using namespace densify;
  // destroyed after mpi: the session directory goes after MPI_Finalize
  const LeanSingletonStart         lean_start;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const bool         root = rank == 0;
  auto               fail = [&](const std::string &message, const int code) {
    if (root)
      std::cerr << "densify: error: " << one_line(message) << std::endl;
    return code;
  };
  // An error of a run is usually found by every rank alike (bad input, a
  // failed solve), and rank 0 reports it. An error found on some ranks only
  // leaves the others waiting in a collective operation: the rank that found
  // it reports it and ends every rank.
  const ErrorCommunicator error_comm;
  auto stop = [&](const std::string &message, const int code) {
    if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1 &&
        !all_ranks_arrive(error_comm.comm, 3.))
      {
        std::cerr << "densify: error: " << one_line(message) << " (on MPI rank "
                  << rank << " only; every rank stopped)" << std::endl;
        MPI_Abort(MPI_COMM_WORLD, code);
      }
    return fail(message, code);
  };


  std::string              filename;
  std::vector<std::string> overrides;
  bool                     validate_only = false, print_parameters = false;
  RunControl               control;
  for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h")
        {
          if (root)
            std::cout << usage;
          return 0;
        }
      else if (arg == "--print-parameters")
        print_parameters = true;
      else if (arg == "--validate")
        validate_only = true;
      else if (arg == "--resume")
        control.resume = true;
      else if (arg == "--stop-after")
        {
          if (i + 1 == argc)
            return fail("--stop-after needs a load step number N >= 1", 2);
          const std::string n = argv[++i];
          if (n.empty() || n.find_first_not_of("0123456789") != n.npos ||
              n.size() > 9 || std::stoul(n) == 0)
            return fail("--stop-after '" + n +
                          "': expected a load step number N >= 1",
                        2);
          control.stop_after = std::stoul(n);
        }
      else if (arg == "--set")
        {
          if (i + 1 == argc)
            return fail("--set needs an argument \"Subsection/Name=value\"", 2);
          overrides.emplace_back(argv[++i]);
        }
      else if (arg.rfind("--set=", 0) == 0)
        overrides.push_back(arg.substr(6));
      else if (arg.rfind("-", 0) == 0)
        return fail("unknown option '" + arg + "' (densify --help)", 2);
      else if (filename.empty())
        filename = arg;
      else
        return fail("more than one parameter file ('" + filename + "', '" +
                      arg + "')",
                    2);
    }

  Parameters       parameters;
  ParameterHandler prm;
  parameters.declare(prm);
  if (print_parameters)
    {
      if (root)
        prm.print_parameters(std::cout,
                             ParameterHandler::OutputStyle(
                               ParameterHandler::PRM |
                               ParameterHandler::KeepDeclarationOrder));
      return 0;
    }
  if (filename.empty())
    {
      if (root)
        std::cerr << usage;
      return fail("no parameter file given", 2);
    }

  std::string summary;
  Scene       scene;
  Effects     effects;
  try
    {
      read_parameters(prm, filename, overrides, &parameters.fidelity_summary);
      check_parameters(parameters);
      parameters.fingerprint = parameter_fingerprint(prm);
      scene                  = build_scene(parameters);
      // options that do not fit together are input errors too
      effects = resolve_effects(parameters, scene);
      check_element_size(parameters, scene.particles);
      const MeshEstimate estimate = estimate_mesh(parameters, scene.particles);
      check_mesh_size(parameters, estimate);
      std::ostringstream what;
      what << scene.particles.size() << " particle(s)";
      bool all_spheres = true;
      for (const Particle &p : scene.particles)
        all_spheres = all_spheres && p.shape == ParticleShape::sphere;
      if (parameters.tools.die_enabled && parameters.tools.lower_enabled &&
          scene.upper_initial > parameters.tools.lower_position)
        what << ", relative density " << std::fixed << std::setprecision(2)
             << 100 * layer_relative_density(scene.particles,
                                             parameters.tools.die_diameter,
                                             scene.upper_initial -
                                               parameters.tools.lower_position)
             << " % of the die up to the upper punch at "
             << std::setprecision(3) << scene.upper_initial << " mm ("
             << (all_spheres ? "spheres" : "the exact shapes' volumes") << ")"
             << std::defaultfloat;
      // contacts from centre distances: spheres only
      if (all_spheres)
        what << ", mean coordination number " << std::fixed
             << std::setprecision(2) << mean_coordination(scene.particles)
             << std::defaultfloat;
      what << "; about " << format_count(estimate.elements) << " tetrahedra, "
           << format_count(std::ceil(estimate.bytes / 1e8) / 10)
           << " GB of memory";
      summary = what.str();
    }
  catch (const std::exception &e)
    {
      return stop(e.what(), 2);
    }
  if (validate_only)
    {
      if (root)
        {
          std::cout << filename << ": valid (" << summary << ")" << std::endl;
          if (!parameters.fidelity_summary.empty())
            std::cout << "Fidelity: " << parameters.fidelity_summary
                      << std::endl;
        }
      return 0;
    }

  // the simulator outlives the catch blocks, so that it is not destroyed
  // while an exception is in flight (its timer would then skip its summary
  // and print a warning)
  std::unique_ptr<Simulator> simulator;
  std::string                error;
  int                        error_code = 1;
  bool                       finished   = false;
  control.stop_request                  = &stop_requested;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  try
    {
      simulator =
        std::make_unique<Simulator>(parameters, MPI_COMM_WORLD, true, control);
      // the scene and its effects checked above, not built again
      simulator->set_scene(std::move(scene), effects);
      finished = simulator->run();
    }
  catch (const InputError &e)
    {
      error      = e.what();
      error_code = 2;
    }
  catch (const ExceptionBase &e)
    {
      // its message without deal.II's stack trace
      std::ostringstream info;
      e.print_info(info);
      error = one_line(info.str());
      if (error.empty())
        error = e.get_exc_name();
    }
  catch (const std::exception &e)
    {
      error = e.what();
    }
  catch (const std::string &e) // gmsh throws strings
    {
      error = "gmsh: " + e;
    }
  catch (...)
    {
      error = "unknown exception";
    }
  if (!error.empty())
    {
      if (simulator)
        simulator->write_to_log_file("densify: error: " + error);
      return stop(error, error_code);
    }
  return finished ? 0 : 3;
}
