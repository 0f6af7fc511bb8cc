// The linear solver of each Newton step: CG (or GMRES) with ML AMG fed the
// rigid-body modes, a direct solver, or GMRES preconditioned by the
// factorization of an earlier tangent.
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_solver.h>

#include <deal.II/fe/fe_values.h>

#include <densify/solvers/linear_solver.h>

#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Teuchos_ParameterList.hpp>
#include <dmumps_c.h>
#include <ml_MultiLevelPreconditioner.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// Throw the error of a failed MUMPS @p phase (Amesos or MUMPS code).
    void
    check_mumps(const int error, const char *phase)
    {
      if (error != 0)
        throw std::runtime_error(
          "the direct solver (MUMPS) failed in its " + std::string(phase) +
          " (error " + std::to_string(error) +
          "); the tangent may be singular: check that every particle is "
          "held (Tools, Particles/Hold poles on axis)");
    }

    /**
     * A copy of @p A without the entries that are exactly zero. The tangent's
     * pattern reserves the couplings of every contact candidate (the cells
     * of all facets within a margin of each other, kept while the pattern
     * lasts), most of which carry no value; MUMPS orders and factorizes the
     * structure it is given, so each reserved pair of cells would join the
     * two particles' fronts as if they were in contact.
     */
    std::unique_ptr<Epetra_CrsMatrix>
    without_zeros(const Epetra_CrsMatrix &A)
    {
      const int        n_rows = A.NumMyRows();
      std::vector<int> counts(n_rows, 0);
      for (int i = 0; i < n_rows; ++i)
        {
          int     length;
          double *values;
          int    *columns;
          A.ExtractMyRowView(i, length, values, columns);
          for (int k = 0; k < length; ++k)
            counts[i] += (values[k] != 0.);
        }
      auto B = std::make_unique<Epetra_CrsMatrix>(
        Copy, A.RowMap(), A.ColMap(), counts.data(), true);
      std::vector<int>    kept_columns;
      std::vector<double> kept_values;
      for (int i = 0; i < n_rows; ++i)
        {
          int     length;
          double *values;
          int    *columns;
          A.ExtractMyRowView(i, length, values, columns);
          kept_columns.clear();
          kept_values.clear();
          for (int k = 0; k < length; ++k)
            if (values[k] != 0.)
              {
                kept_columns.push_back(columns[k]);
                kept_values.push_back(values[k]);
              }
          B->InsertMyValues(i,
                            kept_columns.size(),
                            kept_values.data(),
                            kept_columns.data());
        }
      B->FillComplete(A.DomainMap(), A.RangeMap());
      return B;
    }
  } // namespace



  /**
   * The MUMPS factors of one matrix, and solves with them (the factors stay
   * valid after the matrix's values change). Either MUMPS on all ranks
   * through Amesos_Mumps, or (@p on_one_rank) sequential MUMPS on rank 0 with
   * the matrix and the right-hand sides gathered there: MUMPS on several
   * ranks schedules its work asynchronously, so its round-off, and with it a
   * run's result, changes from one run to the next; on one rank it does not.
   */
  class MumpsFactorization
  {
  public:
    /// Analyse and factorize @p matrix, which must stay alive (its maps are
    /// used by solve()) while this object is used.
    MumpsFactorization(const TrilinosWrappers::SparseMatrix &matrix,
                       const bool                            on_one_rank)
    {
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      if (!on_one_rank || A.Comm().NumProc() == 1)
        {
          nonzeros = without_zeros(A);
          problem.SetOperator(nonzeros.get());
          solver = std::make_unique<Amesos_Mumps>(problem);
          Timer timer;
          check_mumps(solver->SymbolicFactorization(), "analysis");
          analysis_seconds = timer.wall_time();
          timer.restart();
          check_mumps(solver->NumericFactorization(), "factorization");
          factorization_seconds = timer.wall_time();
          return;
        }
      const bool root = A.Comm().MyPID() == 0;
      const int  n    = A.NumGlobalRows();
      root_map = std::make_unique<Epetra_Map>(n, root ? n : 0, 0, A.Comm());
      gather   = std::make_unique<Epetra_Import>(*root_map, A.RowMap());
      scatter  = std::make_unique<Epetra_Import>(A.RowMap(), *root_map);
      Epetra_CrsMatrix gathered(Copy, *root_map, 0);
      gathered.Import(A, *gather, Insert);
      gathered.FillComplete();

      int error = 0;
      if (root)
        {
          // the triplets, 1-based, of the whole matrix
          for (int i = 0; i < gathered.NumMyRows(); ++i)
            {
              int     length;
              double *values;
              int    *columns;
              gathered.ExtractMyRowView(i, length, values, columns);
              for (int k = 0; k < length; ++k)
                if (values[k] != 0.) // see without_zeros()
                  {
                    rows.push_back(gathered.GRID(i) + 1);
                    cols.push_back(gathered.GCID(columns[k]) + 1);
                    entries.push_back(values[k]);
                  }
            }
          mumps.comm_fortran = MPI_Comm_c2f(MPI_COMM_SELF);
          mumps.par          = 1;
          mumps.sym          = 0;
          mumps.job          = -1;
          dmumps_c(&mumps);
          error = mumps.infog[0];
          if (error >= 0)
            {
              initialised = true;
              // no printing; MUMPS chooses ordering and scaling, as Amesos
              mumps.icntl[0]  = -1;
              mumps.icntl[1]  = -1;
              mumps.icntl[2]  = -1;
              mumps.icntl[3]  = 0;
              mumps.icntl[13] = 20;
              mumps.n         = n;
              mumps.nnz       = rows.size();
              mumps.irn       = rows.data();
              mumps.jcn       = cols.data();
              mumps.a         = entries.data();
              for (const int job : {1, 2})
                if (error >= 0)
                  {
                    Timer timer;
                    mumps.job = job;
                    dmumps_c(&mumps);
                    error = mumps.infog[0];
                    (job == 1 ? analysis_seconds : factorization_seconds) =
                      timer.wall_time();
                  }
            }
        }
      // every rank throws, or none
      error = std::min(dealii::Utilities::MPI::min(error, comm(A)), 0);
      check_mumps(error, "factorization (on rank 0)");
    }

    /// MUMPS's statistics of the factorization (INFOG(9), INFOG(11),
    /// RINFOG(3)) and rank 0's wall times of its analysis and numerical
    /// factorization, the same on all ranks (collective).
    std::string
    statistics() const
    {
      const Epetra_Comm &comm = problem.GetOperator() ?
                                  problem.GetOperator()->Comm() :
                                  root_map->Comm();
      // factor entries (negative: millions), largest front, flops, the
      // wall times of analysis and factorization (on rank 0)
      double info[5] = {0., 0., 0., analysis_seconds, factorization_seconds};
      if (solver)
        {
          info[0] = solver->GetINFOG()[8];
          info[1] = solver->GetINFOG()[10];
          info[2] = solver->GetRINFOG()[2];
        }
      else if (initialised)
        {
          info[0] = mumps.infog[8];
          info[1] = mumps.infog[10];
          info[2] = mumps.rinfog[2];
        }
      comm.Broadcast(info, 5, 0);
      const double       entries = info[0] < 0 ? -1e6 * info[0] : info[0];
      std::ostringstream out;
      out << std::setprecision(3) << info[2] / 1e9 << " GFlop, "
          << entries / 1e6 << " M factor entries, largest front "
          << static_cast<long>(info[1]) << "; analysis " << info[3]
          << " s, factorization " << info[4] << " s";
      return out.str();
    }

    ~MumpsFactorization()
    {
      if (initialised)
        {
          mumps.job = -2;
          dmumps_c(&mumps);
        }
    }

    /// x = A^{-1} b with the factors.
    void
    solve(TrilinosWrappers::MPI::Vector       &x,
          const TrilinosWrappers::MPI::Vector &b)
    {
      if (solver)
        {
          problem.SetLHS(&x.trilinos_vector());
          problem.SetRHS(
            const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
          check_mumps(solver->Solve(), "solve");
          return;
        }
      Epetra_Vector on_root(*root_map);
      on_root.Import(b.trilinos_vector(), *gather, Insert);
      int error = 0;
      if (initialised)
        {
          mumps.job = 3;
          mumps.rhs = on_root.Values();
          dmumps_c(&mumps);
          error = mumps.infog[0];
        }
      error =
        std::min(dealii::Utilities::MPI::min(error, x.get_mpi_communicator()),
                 0);
      check_mumps(error, "solve (on rank 0)");
      x.trilinos_vector().Import(on_root, *scatter, Insert);
    }

  private:
    /// The MPI communicator of @p A.
    static MPI_Comm
    comm(const Epetra_CrsMatrix &A)
    {
      return dynamic_cast<const Epetra_MpiComm &>(A.Comm()).Comm();
    }

    /// MUMPS on all ranks, given the matrix without its zero entries.
    std::unique_ptr<Epetra_CrsMatrix> nonzeros;
    Epetra_LinearProblem              problem;
    std::unique_ptr<Amesos_Mumps>     solver;

    /// Sequential MUMPS on rank 0: all rows there, the maps between the
    /// distributed vectors and those, and MUMPS's data (rank 0 only).
    std::unique_ptr<Epetra_Map>    root_map;
    std::unique_ptr<Epetra_Import> gather, scatter;
    std::vector<int>               rows, cols;
    std::vector<double>            entries;
    DMUMPS_STRUC_C                 mumps{};
    bool                           initialised = false;

    /// Wall times of MUMPS's analysis and numerical factorization (s).
    double analysis_seconds = 0., factorization_seconds = 0.;
  };



  /**
   * The solver control of GMRES with old factors: besides the iteration
   * limit, it gives up as soon as the residual's mean reduction per
   * iteration so far, extrapolated, would not reach the tolerance within
   * the limit. A new factorization costs about as much as 15 such
   * iterations; an attempt that is bound to fail should not use them all.
   */
  class ReuseControl : public SolverControl
  {
  public:
    using SolverControl::SolverControl;

    State
    check(const unsigned int step, const double value) override
    {
      if (step == 0)
        initial_residual = value;
      const State state = SolverControl::check(step, value);
      if (state != iterate || step < min_steps || !(initial_residual > 0.))
        return state;
      const double rate = std::pow(value / initial_residual, 1. / step);
      if (rate < 1. &&
          step + std::log(tolerance() / value) / std::log(rate) <= max_steps())
        return iterate;
      lcheck = failure;
      return failure;
    }

  private:
    /// Iterations before the first extrapolation.
    static constexpr unsigned int min_steps        = 5;
    double                        initial_residual = 0.;
  };



  LinearSolver::~LinearSolver() = default;



  void
  LinearSolver::rebuild_preconditioner()
  {
    amg.reset();
    factorization.reset();
  }



  LinearSolver::LinearSolver(const LinearSolverType type,
                             const double           tolerance,
                             const unsigned int     max_iterations,
                             const bool             reuse_amg,
                             const bool             reproducible,
                             TimerOutput           &timer)
    : type(type)
    , tolerance(tolerance)
    , max_iterations(max_iterations)
    , reuse_amg(reuse_amg)
    , reproducible(reproducible)
    , timer(timer)
  {}



  void
  LinearSolver::setup_null_space(const DoFHandler<3> &dof_handler,
                                 const Mapping<3>    &mapping,
                                 const IndexSet      &locally_owned)
  {
    const FiniteElement<3> &fe      = dof_handler.get_fe();
    const unsigned int      n_local = locally_owned.n_elements();
    null_space.assign(6 * n_local, 0.);

    // centre of the owned support points, to keep the rotation modes O(size)
    FEValues<3>                          fe_values(mapping,
                          fe,
                          Quadrature<3>(fe.get_unit_support_points()),
                          update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    std::vector<bool>                    done(n_local, false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              if (!locally_owned.is_element(dofs[i]))
                continue;
              const unsigned int row = locally_owned.index_within_set(dofs[i]);
              if (done[row])
                continue;
              done[row]            = true;
              const unsigned int c = fe.system_to_component_index(i).first;
              const Point<3>    &x = fe_values.quadrature_point(i);
              // translations
              null_space[c * n_local + row] = 1.;
              // rotations about x, y, z: u = e_a x x
              const double rot[3][3] = {{0., -x[2], x[1]},
                                        {x[2], 0., -x[0]},
                                        {-x[1], x[0], 0.}};
              for (unsigned int a = 0; a < 3; ++a)
                null_space[(3 + a) * n_local + row] = rot[a][c];
            }
        }
  }



  unsigned int
  LinearSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                      TrilinosWrappers::MPI::Vector        &x,
                      const TrilinosWrappers::MPI::Vector  &b,
                      const double                          relative_tolerance)
  {
    SolverControl control(
      max_iterations,
      std::max((relative_tolerance > 0 ? relative_tolerance : tolerance) *
                 b.l2_norm(),
               1e-300));
    if (type == LinearSolverType::direct)
      {
        TimerOutput::Scope t(timer, "Solve: direct");
        factorize(matrix);
        factorization->solve(x, b);
        return 1;
      }

    if (type == LinearSolverType::gmres_lu)
      return solve_with_factorization(matrix, x, b, control);

    const bool stale =
      !reuse_amg || !amg || last_iterations > 2 * iterations_after_setup + 10;
    if (stale)
      setup_amg(matrix);
    else
      {
        // a reused hierarchy gets a bounded number of iterations; if that
        // is not enough, it is rebuilt and the solve repeated
        SolverControl      short_control(std::min(max_iterations,
                                             3 * iterations_after_setup + 20),
                                    control.tolerance());
        TimerOutput::Scope t(timer, "Solve: Krylov");
        try
          {
            krylov(short_control, matrix, x, b);
            last_iterations = short_control.last_step();
            return last_iterations;
          }
        catch (const SolverControl::NoConvergence &)
          {}
        catch (const dealii::ExceptionBase &)
          {}
        x = 0;
        setup_amg(matrix);
      }

    {
      TimerOutput::Scope t(timer, "Solve: Krylov");
      try
        {
          krylov(control, matrix, x, b);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          throw std::runtime_error(
            "the Krylov solver did not converge in " +
            std::to_string(e.last_step) + " iterations (residual " +
            std::to_string(e.last_residual) +
            "); raise Solver/Maximum linear iterations or try "
            "Solver/Linear solver = direct");
        }
      catch (const dealii::ExceptionBase &e)
        {
          // AztecOO stops with "loss of precision" when the tolerance is
          // below what round-off allows; its iterate is the best there is,
          // and Newton's own check decides whether that suffices
          std::ostringstream info;
          e.print_info(info);
          if (info.str().find("loss of precision") != std::string::npos)
            ;
          else if (info.str().find("breakdown") != std::string::npos)
            {
              // an indefinite tangent (finite-strain geometric stiffness
              // under compression): GMRES does not need definiteness
              TimerOutput::Scope            t(timer, "Solve: GMRES fallback");
              TrilinosWrappers::SolverGMRES gmres(
                control,
                TrilinosWrappers::SolverGMRES::AdditionalData(false, 100));
              x = 0;
              try
                {
                  gmres.solve(matrix, x, b, *amg);
                }
              catch (const SolverControl::NoConvergence &e)
                {
                  throw std::runtime_error(
                    "CG broke down (indefinite tangent) and GMRES did not "
                    "converge in " +
                    std::to_string(e.last_step) + " iterations");
                }
              catch (const dealii::ExceptionBase &e)
                {
                  std::ostringstream gmres_info;
                  e.print_info(gmres_info);
                  if (gmres_info.str().find("loss of precision") ==
                      std::string::npos)
                    throw std::runtime_error(
                      "CG broke down and GMRES failed: " + gmres_info.str());
                }
              ++n_gmres;
            }
          else
            throw std::runtime_error("CG failed: " + info.str());
        }
    }
    last_iterations        = control.last_step();
    iterations_after_setup = last_iterations;
    return last_iterations;
  }



  void
  LinearSolver::krylov(SolverControl                        &control,
                       const TrilinosWrappers::SparseMatrix &matrix,
                       TrilinosWrappers::MPI::Vector        &x,
                       const TrilinosWrappers::MPI::Vector  &b)
  {
    if (type == LinearSolverType::gmres_amg)
      {
        TrilinosWrappers::SolverGMRES gmres(
          control, TrilinosWrappers::SolverGMRES::AdditionalData(false, 100));
        gmres.solve(matrix, x, b, *amg);
      }
    else
      {
        TrilinosWrappers::SolverCG cg(control);
        cg.solve(matrix, x, b, *amg);
      }
  }



  unsigned int
  LinearSolver::solve_with_factorization(
    const TrilinosWrappers::SparseMatrix &matrix,
    TrilinosWrappers::MPI::Vector        &x,
    const TrilinosWrappers::MPI::Vector  &b,
    SolverControl                        &control)
  {
    if (factorization)
      {
        // the old factors as a right preconditioner: the residual GMRES
        // measures is the true one
        TimerOutput::Scope t(timer, "Solve: GMRES with old factors");
        struct OldFactors
        {
          MumpsFactorization *direct;
          void
          vmult(TrilinosWrappers::MPI::Vector       &dst,
                const TrilinosWrappers::MPI::Vector &src) const
          {
            direct->solve(dst, src);
          }
        } preconditioner{factorization.get()};
        ReuseControl short_control(max_reuse_iterations, control.tolerance());
        SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
          short_control,
          SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(
            max_reuse_iterations + 2, true));
        try
          {
            x = 0;
            gmres.solve(matrix, x, b, preconditioner);
            last_iterations = short_control.last_step();
            return last_iterations;
          }
        catch (const SolverControl::NoConvergence &)
          {}
      }
    TimerOutput::Scope t(timer, "Solve: direct");
    factorize(matrix);
    factorization->solve(x, b);
    last_iterations = 1;
    return 1;
  }



  void
  LinearSolver::factorize(const TrilinosWrappers::SparseMatrix &matrix)
  {
    // a new analysis every time, as deal.II's SolverDirect does: MUMPS picks
    // its pivot order and scaling from the values (keeping the analysis of
    // the first matrix of a pattern was tried; seven_spheres.mpirun=2 then
    // failed twice in the parallel ctest, and its gain was not measurable)
    factorization.reset();
    factorization = std::make_unique<MumpsFactorization>(matrix, reproducible);
    ++n_factorized;
  }



  std::string
  LinearSolver::factorization_statistics() const
  {
    return factorization ? factorization->statistics() : std::string();
  }



  void
  LinearSolver::setup_amg(const TrilinosWrappers::SparseMatrix &matrix)
  {
    TimerOutput::Scope     t(timer, "Solve: AMG setup");
    Teuchos::ParameterList list;
    ML_Epetra::SetDefaults("SA", list);
    list.set("ML output", 0);
    list.set("max levels", 10);
    list.set("aggregation: type", "Uncoupled");
    list.set("aggregation: threshold", 0.);
    list.set("smoother: type", "Chebyshev");
    list.set("smoother: sweeps", 2);
    list.set("coarse: type", "Amesos-KLU");
    list.set("coarse: max size", 2000);
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", 6);
    list.set("null space: vectors", null_space.data());
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(matrix.trilinos_matrix(), list);
    ++n_setups;
  }
} // namespace densify
