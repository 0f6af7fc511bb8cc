// The direct solver (MUMPS) on a sequence of matrices whose nonzero pattern
// changes as a contact tangent's does, within a pattern that reserves more
// couplings (zeros): a nonsymmetric, diagonally dominant band plus
// "contact" couplings between rows i and i + 10 that close and open.
// Checked, for sequential MUMPS (Solver/Reproducible = true) and MUMPS on
// all ranks (false):
// - every solve meets |A x - b| < 1e-12 |b| with the matrix of that solve;
// - MUMPS's analysis is kept exactly where the nonzeros lie in the analysed
//   pattern: for new values in the same pattern, for a contact that opened
//   and closes again (the union of patterns), for fewer nonzeros; a new
//   analysis for closing contacts, on the union of the patterns while it is
//   at most 5 % larger than the matrix's own, else on the latter.
// The same lines on 1 and 2 ranks.
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <densify/solvers/linear_solver.h>

#include <iostream>
#include <sstream>
#include <vector>

namespace
{
  using namespace dealii;

  constexpr unsigned int n = 60, offset = 10;

  /// The band with its values scaled by @p scale, and contact couplings of
  /// value -0.3 between i and i + offset for every i in @p contacts.
  void
  fill(TrilinosWrappers::SparseMatrix  &A,
       const IndexSet                  &owned,
       const double                     scale,
       const std::vector<unsigned int> &contacts)
  {
    A = 0;
    for (const auto i : owned)
      {
        A.set(i, i, 4. * scale);
        if (i > 0)
          A.set(i, i - 1, -0.5 * scale);
        if (i + 1 < n)
          A.set(i, i + 1, -1. * scale);
      }
    for (const unsigned int i : contacts)
      {
        if (owned.is_element(i))
          A.set(i, i + offset, -0.3);
        if (owned.is_element(i + offset))
          A.set(i + offset, i, -0.3);
      }
    A.compress(VectorOperation::insert);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned int size = Utilities::MPI::n_mpi_processes(comm);

  IndexSet owned(n);
  owned.add_range(rank * n / size, (rank + 1) * n / size);
  TrilinosWrappers::SparsityPattern sp(owned, comm);
  for (const auto i : owned)
    for (const auto j : {i - 1, i, i + 1, i - offset, i + offset})
      if (j < n) // unsigned: also i - 1 < 0
        sp.add(i, j);
  sp.compress();

  // contacts between i and i + offset for i = 5, for every even and for
  // every odd i
  std::vector<unsigned int> one = {5}, even, odd;
  for (unsigned int i = 0; i + offset < n; ++i)
    (i % 2 == 0 ? even : odd).push_back(i);
  const std::vector<std::pair<double, std::vector<unsigned int>>> sequence = {
    {1., {}},   // first analysis
    {1.1, {}},  // new values, same pattern: kept
    {1., one},  // a contact closes: the union
    {1.2, {}},  // it opens: kept
    {1., one},  // and closes again: kept
    {1., even}, // many close: the union is within 5 %
    {1.3, {}},  // all open: kept
    {1., odd},  // others close: the union 22 % larger, their own pattern
    {1., even}, // so these need a new analysis
    {1.4, one}, // and this one too (i = 5 is odd)
  };

  bool ok = true;
  for (const bool reproducible : {true, false})
    {
      TimerOutput                    timer(comm,
                        std::cerr,
                        TimerOutput::never,
                        TimerOutput::wall_times);
      densify::LinearSolver          solver(densify::LinearSolverType::direct,
                                   1e-12,
                                   100,
                                   false,
                                   reproducible,
                                   timer);
      TrilinosWrappers::SparseMatrix A;
      A.reinit(sp);
      TrilinosWrappers::MPI::Vector x(owned, comm), b(owned, comm),
        r(owned, comm);
      for (const auto i : owned)
        b[i] = 1. + 0.01 * i;
      b.compress(VectorOperation::insert);

      if (rank == 0)
        std::cout << "Reproducible = " << (reproducible ? "true" : "false")
                  << '\n';
      for (const auto &[scale, contacts] : sequence)
        {
          fill(A, owned, scale, contacts);
          solver.solve(A, x, b);
          A.vmult(r, x);
          r -= b;
          const bool        solved     = r.l2_norm() < 1e-12 * b.l2_norm();
          const std::string statistics = solver.factorization_statistics();
          const bool        kept =
            statistics.find("analysis reused") != std::string::npos;
          ok = ok && solved;
          if (rank == 0)
            std::cout << "  scale " << scale << ", " << contacts.size()
                      << " contacts: analysis " << (kept ? "kept" : "new")
                      << ", |Ax - b| < 1e-12 |b|: " << (solved ? "yes" : "no")
                      << '\n';
        }
    }
  return ok ? 0 : 1;
}
