// The vectors, tangent and direct linear solve of a small serial problem for
// the Newton tests without a scene (newton_toy, newton_secant_start).
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>

namespace testing
{
  /**
   * A @p Problem (NonlinearProblem or IncrementalProblem) with @p n unknowns
   * on one process: the solution u, the residual r and the tangent K, whose
   * pattern couples each entry to those within @p bandwidth, solved
   * directly. The derived toy assembles r and K.
   */
  template <class Problem>
  class DirectToy : public Problem
  {
  public:
    DirectToy(const unsigned int n, const unsigned int bandwidth)
      : owned(dealii::complete_index_set(n))
    {
      u.reinit(owned, MPI_COMM_WORLD);
      r.reinit(owned, MPI_COMM_WORLD);
      dealii::TrilinosWrappers::SparsityPattern sp(owned, MPI_COMM_WORLD);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = (i > bandwidth ? i - bandwidth : 0);
             j < std::min(n, i + bandwidth + 1);
             ++j)
          sp.add(i, j);
      sp.compress();
      K.reinit(sp);
    }

    dealii::TrilinosWrappers::MPI::Vector &
    solution_vector() override
    {
      return u;
    }

    dealii::TrilinosWrappers::MPI::Vector &
    residual_vector() override
    {
      return r;
    }

    /// Solve K du = rhs directly (one "iteration").
    unsigned int
    solve_linear(const dealii::TrilinosWrappers::MPI::Vector &rhs,
                 dealii::TrilinosWrappers::MPI::Vector       &du,
                 const double /*relative_tolerance*/) override
    {
      dealii::SolverControl                  control(1, 0);
      dealii::TrilinosWrappers::SolverDirect direct(control);
      direct.solve(K, du, rhs);
      return 1;
    }

    dealii::IndexSet                       owned;
    dealii::TrilinosWrappers::MPI::Vector  u, r;
    dealii::TrilinosWrappers::SparseMatrix K;
  };
} // namespace testing
