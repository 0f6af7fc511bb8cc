// Small helpers shared by the executable and the library.
#include <deal.II/base/mpi.h>

#include <densify/utilities.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
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
} // namespace densify
