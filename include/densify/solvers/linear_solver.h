// The linear solver of each Newton step: CG with ML AMG fed the rigid-body
// modes, or a direct solver.
#pragma once

#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <memory>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  class MumpsFactorization;

  /// The linear solvers (Solver/Linear solver with 'auto' resolved).
  enum class LinearSolverType
  {
    /// CG with ML AMG (symmetric tangents).
    cg_amg,
    /// GMRES with ML AMG (nonsymmetric tangents).
    gmres_amg,
    /// GMRES preconditioned by the MUMPS factors of an earlier tangent.
    gmres_lu,
    /// MUMPS.
    direct
  };

  /**
   * Solves K x = b for the Newton tangent K.
   * "cg-amg": Trilinos CG preconditioned by ML smoothed-aggregation AMG whose
   * near-null space is the six rigid-body modes of 3D elasticity, given
   * through ML's parameter list ("null space: type" = "pre-computed"), since
   * deal.II 9.4 has no DoFTools::extract_rigid_body_modes (K symmetric
   * positive definite). "gmres-amg": GMRES with the same AMG, for
   * nonsymmetric tangents. "direct": MUMPS (sequential on rank 0 with
   * @p reproducible or on one rank, else on all ranks, each giving its own
   * rows). "gmres-lu": GMRES preconditioned by the MUMPS factors of an earlier
   * tangent.
   */
  class LinearSolver
  {
  public:
    /**
     * @p type the solver; tolerance
     * relative to |b|. With
     * @p reuse_amg, the AMG hierarchy is kept across solves until CG needs
     * more than twice the iterations it needed right after the last setup
     * (plus 10), or rebuild_preconditioner() is called. With
     * @p reproducible, "direct" and "gmres-lu" factorize on rank 0 alone
     * (sequential MUMPS), so that runs on several ranks repeat exactly.
     * Times go into @p timer.
     */
    LinearSolver(const LinearSolverType type,
                 const double           tolerance,
                 const unsigned int     max_iterations,
                 const bool             reuse_amg,
                 const bool             reproducible,
                 TimerOutput           &timer);

    /// Out of line: MumpsFactorization is complete only there.
    ~LinearSolver();

    /// Build the AMG hierarchy (or the factors of gmres-lu; MUMPS's analysis
    /// is kept where it holds the new pattern) anew at the next solve;
    /// needed whenever the matrix is reinitialised.
    void
    rebuild_preconditioner();

    /// Number of factorizations of gmres-lu so far.
    unsigned int
    n_factorizations() const
    {
      return n_factorized;
    }

    /// MUMPS's statistics of the last factorization (flops, factor entries,
    /// largest front, wall times of analysis and factorization), or an empty
    /// string if there is none. Collective.
    std::string
    factorization_statistics() const;
    /// Number of solves that needed the GMRES fallback.
    unsigned int
    n_gmres_fallbacks() const
    {
      return n_gmres;
    }

    /// Number of AMG setups so far.
    unsigned int
    n_amg_setups() const
    {
      return n_setups;
    }

    /**
     * Compute the rigid-body modes at the support points of the locally
     * owned DoFs (call after every change of the DoF numbering).
     */
    void
    setup_null_space(const DoFHandler<3> &dof_handler,
                     const Mapping<3>    &mapping,
                     const IndexSet      &locally_owned);

    /// Solve; returns the number of linear iterations (1 for direct).
    /// @p relative_tolerance > 0 replaces the constructor's tolerance for
    /// this solve. Throws std::runtime_error if CG does not converge.
    unsigned int
    solve(const TrilinosWrappers::SparseMatrix &matrix,
          TrilinosWrappers::MPI::Vector        &x,
          const TrilinosWrappers::MPI::Vector  &b,
          const double                          relative_tolerance = 0.);

  private:
    /// CG (or GMRES for "gmres-amg") with the AMG preconditioner.
    void
    krylov(SolverControl                        &control,
           const TrilinosWrappers::SparseMatrix &matrix,
           TrilinosWrappers::MPI::Vector        &x,
           const TrilinosWrappers::MPI::Vector  &b);

    /// gmres-lu: GMRES preconditioned by the stored factorization, or a new
    /// factorization of @p matrix and a direct solve.
    unsigned int
    solve_with_factorization(const TrilinosWrappers::SparseMatrix &matrix,
                             TrilinosWrappers::MPI::Vector        &x,
                             const TrilinosWrappers::MPI::Vector  &b,
                             SolverControl                        &control);

    /// Numerical factorization of @p matrix, after MUMPS's analysis of its
    /// pattern unless an earlier analysis holds it.
    void
    factorize(const TrilinosWrappers::SparseMatrix &matrix);

    /// Build the ML hierarchy of @p matrix with the rigid-body modes.
    void
    setup_amg(const TrilinosWrappers::SparseMatrix &matrix);

    const LinearSolverType type;
    const double           tolerance;
    const unsigned int     max_iterations;
    const bool             reuse_amg;
    const bool             reproducible;
    TimerOutput           &timer;
    unsigned int           iterations_after_setup = 0;
    unsigned int           last_iterations        = 0;
    unsigned int           n_setups               = 0;
    unsigned int           n_gmres                = 0;
    /// Column-major: mode k of local row i at [k * n_local + i].
    std::vector<double>                                null_space;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    /// gmres-lu: the factorization of an earlier tangent, its solver
    /// control, and the number of factorizations.
    std::unique_ptr<MumpsFactorization> factorization;
    unsigned int                        n_factorized = 0;
    /// Whether the factors are those of a tangent of the current matrix
    /// pattern (gmres-lu uses them for GMRES only then).
    bool factors_current = false;
    /// gmres-lu: GMRES iterations beyond which the tangent is factorized
    /// anew.
    static constexpr unsigned int max_reuse_iterations = 20;
  };
} // namespace densify
