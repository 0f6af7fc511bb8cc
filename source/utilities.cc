// Small helpers shared by the executable and the library.
#include <deal.II/base/mpi.h>

#include <densify/utilities.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace densify
{
  std::string
  one_line(const std::string &text)
  {
    std::string line;
    for (char c : text)
      {
        if (c == '\n' || c == '\t' || c == '\r')
          c = ' ';
        if (c == ' ' && (line.empty() || line.back() == ' '))
          continue;
        line += c;
      }
    while (!line.empty() && line.back() == ' ')
      line.pop_back();
    return line;
  }



  std::string
  first_error(const std::string &local_error, const MPI_Comm comm)
  {
    if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
      return local_error;
    const int any_error =
      dealii::Utilities::MPI::max(local_error.empty() ? 0 : 1, comm);
    if (any_error == 0)
      return "";
    for (const std::string &e :
         dealii::Utilities::MPI::all_gather(comm, local_error))
      if (!e.empty())
        return e;
    return "";
  }



  std::string
  write_error(const std::string &filename)
  {
    const int cause = errno;
    return "cannot write '" + filename + "'" +
           (cause != 0 ? " (" + std::string(std::strerror(cause)) + ")" :
                         std::string());
  }



  std::string
  append_or_roll_back(std::ofstream     &file,
                      const std::string &filename,
                      const std::string &text)
  {
    namespace fs = std::filesystem;
    std::error_code      no_size;
    const std::uintmax_t before = fs::file_size(filename, no_size);
    errno                       = 0;
    file << text;
    file.flush();
    if (file)
      return "";
    const std::string error = write_error(filename);
    file.close();
    std::error_code ignored;
    if (!no_size)
      fs::resize_file(filename, before, ignored);
    return error;
  }



  void
  extend_csv_columns(const std::string &filename, const std::string &header)
  {
    std::vector<std::string> lines;
    {
      std::ifstream in(filename);
      for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    }
    if (lines.empty() || lines[0] == header ||
        header.compare(0, lines[0].size() + 1, lines[0] + ",") != 0)
      return;
    const auto fields = [](const std::string &line) {
      return std::count(line.begin(), line.end(), ',') + 1;
    };
    const long    added = fields(header) - fields(lines[0]);
    std::ofstream out(filename, std::ios::trunc);
    out << header << '\n';
    for (std::size_t i = 1; i < lines.size(); ++i)
      {
        out << lines[i];
        for (long k = 0; k < added; ++k)
          out << ",nan";
        out << '\n';
      }
    if (!out)
      throw std::runtime_error("Output/Directory: " + write_error(filename));
  }
} // namespace densify
