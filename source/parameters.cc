// Reading and overriding of Densify's parameters, their fingerprint and checks
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <densify/fidelity.h>
#include <densify/ignored_parameters.h>
#include <densify/parameters.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// The additional-information text of a deal.II exception, on one line.
    std::string
    one_line(const ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      return densify::one_line(info.str());
    }
  } // namespace



  void
  read_parameters(ParameterHandler               &prm,
                  const std::string              &filename,
                  const std::vector<std::string> &overrides,
                  std::string                    *fidelity_summary)
  {
    if (std::filesystem::is_directory(filename))
      throw std::runtime_error("parameter file '" + filename +
                               "' is a directory: give a .prm file");
    std::string text;
    {
      // C stdio, whose error flag tells a file that cannot be read (such as
      // /proc/self/mem) from an empty one
      std::FILE *in = std::fopen(filename.c_str(), "rb");
      if (in == nullptr)
        throw std::runtime_error("cannot open parameter file '" + filename +
                                 "': " + std::strerror(errno));
      char        buffer[4096];
      std::size_t n;
      while ((n = std::fread(buffer, 1, sizeof(buffer), in)) > 0)
        text.append(buffer, n);
      const bool failed = std::ferror(in) != 0;
      const int  code   = errno;
      std::fclose(in);
      if (failed)
        throw std::runtime_error("cannot read parameter file '" + filename +
                                 "': " + std::strerror(code) +
                                 ": give a readable .prm file");
    }
    // a UTF-8 byte-order mark, as some editors write
    if (text.rfind("\xEF\xBB\xBF", 0) == 0)
      text.erase(0, 3);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
      throw std::runtime_error(
        "parameter file '" + filename +
        "' is empty: give a scene (e.g. a copy of prm/default.prm; densify "
        "--print-parameters lists every entry)");
    try
      {
        std::istringstream in(text);
        prm.parse_input(in, filename, "", false);
      }
    catch (const ExceptionBase &e)
      {
        throw std::runtime_error(one_line(e) +
                                 " (densify --print-parameters lists every "
                                 "entry)");
      }

    for (const std::string &o : overrides)
      {
        const auto eq = o.find('=');
        if (eq == std::string::npos)
          throw std::runtime_error("--set '" + o +
                                   "': expected 'Subsection/Name=value'");
        const std::vector<std::string> path =
          Utilities::split_string_list(o.substr(0, eq), '/');
        const std::string value = Utilities::trim(o.substr(eq + 1));
        if (path.empty())
          throw std::runtime_error("--set '" + o + "': no entry name");
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          if (!prm.subsection_path_exists(
                std::vector<std::string>(path.begin(), path.begin() + i + 1)))
            {
              std::string sub;
              for (unsigned int j = 0; j <= i; ++j)
                sub += (j > 0 ? "/" : "") + path[j];
              throw std::runtime_error("--set '" + o + "': no subsection '" +
                                       sub +
                                       "' (densify --print-parameters lists "
                                       "every entry)");
            }
        unsigned int depth = 0;
        try
          {
            for (unsigned int i = 0; i + 1 < path.size(); ++i, ++depth)
              prm.enter_subsection(path[i]);
            prm.set(path.back(), value);
          }
        catch (const ExceptionBase &e)
          {
            for (; depth > 0; --depth)
              prm.leave_subsection();
            throw std::runtime_error("--set '" + o + "': " + one_line(e) +
                                     " (densify --print-parameters lists "
                                     "every entry)");
          }
        for (; depth > 0; --depth)
          prm.leave_subsection();
      }

    // one warning line for each entry set in the file or by --set that the
    // scene does not use
    std::set<std::string> set = entries_set_in_file(filename);
    for (const std::string &o : overrides)
      {
        std::string entry;
        for (const std::string &part :
             Utilities::split_string_list(o.substr(0, o.find('=')), '/'))
          entry += (entry.empty() ? "" : "/") + part;
        set.insert(entry);
      }
    const std::string fidelity = resolve_fidelity(prm, set);
    if (fidelity_summary != nullptr)
      *fidelity_summary = fidelity;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      for (const std::string &line : ignored_parameters(prm, set))
        std::cerr << "densify: warning: " << line << std::endl;
  }



  std::string
  parameter_fingerprint(const ParameterHandler &prm)
  {
    // the short PRM text ("subsection", "set Name = value", "end" lines),
    // flattened to "Sub/Sub/Name = value"; Output, Solver and the friction
    // and geometric tangents may change between a run and its resumption (how
    // to write, how to solve)
    std::ostringstream prm_text;
    prm.print_parameters(prm_text, ParameterHandler::ShortPRM);
    std::istringstream       in(prm_text.str());
    std::vector<std::string> path;
    std::ostringstream       text;
    for (std::string line; std::getline(in, line);)
      {
        line = Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0 &&
                 (path.empty() ||
                  (path[0] != "Output" &&
                   (path[0] != "Solver" ||
                    Utilities::trim(line.substr(4, line.find('=') - 4)) ==
                      "Method"))))
          {
            const std::string entry = line.substr(4);
            const auto        eq    = entry.find('=');
            // the fidelity level stands for the entries it set, which are
            // in the fingerprint themselves
            if (path.size() == 1 && path[0] == "Scene")
              continue;
            // the friction tangent is a choice of how to solve too
            if (path.size() == 1 && path[0] == "Contact" &&
                (Utilities::trim(entry.substr(0, eq)) == "Friction tangent" ||
                 Utilities::trim(entry.substr(0, eq)) == "Geometric tangent"))
              continue;
            // so are the cut-backs (a failed run resumes with more), the
            // explicit step's fraction of the stable step and the number of
            // explicit steps (an unstable run or one that left the
            // quasi-static guard resumes with less or more; the step and the
            // mass are set anew at every station), the guard's limits, and
            // the size limit only guards the start
            const std::string name = Utilities::trim(entry.substr(0, eq));
            if (path.size() == 1 &&
                ((path[0] == "Time stepping" &&
                  Utilities::trim(entry.substr(0, eq)) ==
                    "Maximum cut-backs") ||
                 (path[0] == "Explicit" &&
                  (name == "Time step safety" || name == "Number of steps" ||
                   name == "Maximum kinetic energy ratio" ||
                   name == "Maximum force imbalance")) ||
                 (path[0] == "Mesh" &&
                  Utilities::trim(entry.substr(0, eq)) == "Maximum elements")))
              continue;
            for (const std::string &p : path)
              text << p << '/';
            text << Utilities::trim(entry.substr(0, eq)) << " = "
                 << (eq == std::string::npos ?
                       std::string() :
                       Utilities::trim(entry.substr(eq + 1)))
                 << '\n';
          }
      }
    return text.str();
  }



  void
  check_parameters(const Parameters &parameters)
  {
    {
      const std::string k =
        Utilities::trim(parameters.explicit_dynamics.contact_stiffness);
      bool valid = k == "auto";
      if (!valid)
        try
          {
            const double value = Utilities::string_to_double(k);
            valid              = value >= 1e-6 && value <= 100.;
          }
        catch (...)
          {}
      if (!valid)
        throw std::runtime_error(
          "Explicit/Contact stiffness = '" + k +
          "' is neither 'auto' nor a number from 1e-6 to 100; give e.g. 1 or "
          "auto");
    }
    for (const auto &[t, f] :
         parse_table(parameters.explicit_dynamics.step_profile,
                     "Explicit/Step profile"))
      if (!(f > 0. && f <= 1.))
        {
          std::ostringstream message;
          message << "Explicit/Step profile = '"
                  << parameters.explicit_dynamics.step_profile
                  << "': the factor " << f << " at " << t
                  << " s is not in (0, 1]; give factors above 0 and at most "
                     "1, e.g. '0:1, 0.78:1, 0.8:0.4'";
          throw std::runtime_error(message.str());
        }
    if (Utilities::trim(parameters.output.directory).empty())
      throw std::runtime_error(
        "Output/Directory is empty: give a directory for the results, e.g. "
        "'output' ('.' for the working directory)");
    // in MPa: beyond any solid (diamond: about 1.2e6 MPa), e.g. a value
    // given in Pa, which would make the contact penalty overflow
    if (parameters.material.youngs_modulus > 1e7)
      {
        std::ostringstream message;
        message << "Material/Young's modulus = "
                << parameters.material.youngs_modulus
                << " MPa is beyond any solid (diamond: 1.2e6 MPa); give it "
                   "in MPa (<= 1e7)";
        throw std::runtime_error(message.str());
      }
    for (const Point<3> &d : parse_points(parameters.mesh.refinement_directions,
                                          "Mesh/Refinement directions"))
      if (d.norm() == 0)
        throw std::runtime_error(
          "Mesh/Refinement directions: a direction must not be zero");
  }
} // namespace densify
