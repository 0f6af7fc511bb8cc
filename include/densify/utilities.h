// Small helpers shared by the executable and the library.
#pragma once

#include <mpi.h>

#include <fstream>
#include <stdexcept>
#include <string>

namespace densify
{
  /**
   * @p text on one line: newlines and tabs become blanks, runs of blanks one
   * blank, no blanks at either end. For error messages, which must be one
   * line whatever a library put into them.
   */
  std::string
  one_line(const std::string &text);

  /**
   * An error in what the user gave (parameters, files, command line) found
   * while running; the executable exits with code 2 for it, as for a bad
   * parameter file.
   */
  struct InputError : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  /**
   * A load step that could not be solved (Newton failed after every
   * cut-back); raised on every MPI rank alike, with the state restored to
   * the last converged increment.
   */
  struct ConvergenceError : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  /**
   * The first non-empty @p local_error over the ranks of @p comm (rank
   * order), on every rank; empty if no rank has one. Collective: for errors
   * found on some ranks only (e.g. a file one rank cannot write), so that
   * every rank stops with the same message.
   */
  std::string
  first_error(const std::string &local_error, const MPI_Comm comm);

  /**
   * "cannot write 'FILE' (CAUSE)" for a failed output stream, with the cause
   * from errno (e.g. "No space left on device") where the C library set it.
   */
  std::string
  write_error(const std::string &filename);

  /**
   * Append @p text to @p file (open on @p filename) and flush it. Returns ""
   * or, if that fails (e.g. a full disk), write_error(@p filename) after
   * closing @p file and cutting @p filename back to its size before, so that
   * what was written earlier stays complete.
   */
  std::string
  append_or_roll_back(std::ofstream     &file,
                      const std::string &filename,
                      const std::string &text);

  /**
   * A resumed run appends to the table @p filename (comma-separated, a
   * header line first): if its header is an older one (a prefix of
   * @p header: columns are only ever appended), rewrite the file with
   * @p header and its rows padded with "nan" for the new columns, so that
   * every row has the header's fields. Throws std::runtime_error
   * ("Output/Directory: " and write_error()) if it cannot be rewritten.
   */
  void
  extend_csv_columns(const std::string &filename, const std::string &header);
} // namespace densify
