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

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Teuchos_ParameterList.hpp>
#include <dmumps_c.h>
#include <ml_MultiLevelPreconditioner.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace densify
{
  namespace
  {
    /// Throw the error of a failed MUMPS @p phase (MUMPS's error code).
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

  } // namespace



  /**
   * The MUMPS factors of the latest matrix, and solves with them. Either
   * sequential MUMPS on rank 0 with the matrix and the right-hand sides
   * gathered there (@p on_one_rank, and always on one rank), or MUMPS on all
   * ranks, each giving its own rows: MUMPS on several ranks schedules its
   * work asynchronously, so its round-off, and with it a run's result,
   * changes from one run to the next; on one rank it does not.
   *
   * Only the nonzero entries go to MUMPS: the tangent's pattern reserves the
   * couplings of every contact candidate (the cells of all facets within a
   * margin of each other, kept while the pattern lasts), most of which carry
   * no value, and MUMPS orders and factorizes the structure it is given, so
   * each reserved pair of cells would join the two particles' fronts as if
   * they were in contact.
   *
   * MUMPS's analysis (fill-reducing order, symbolic factors) is kept for the
   * next matrix whose nonzero entries all lie in the analysed pattern: then
   * only the numerical factorization runs, with the pattern's other entries
   * as zeros. A matrix with an entry outside it is analysed on the union of
   * both patterns (a contact that opens and closes again keeps its place),
   * or on its own nonzeros once the union would hold more than
   * max_pattern_growth times as many entries.
   */
  class MumpsFactorization
  {
  public:
    explicit MumpsFactorization(const bool on_one_rank)
      : on_one_rank(on_one_rank)
    {}

    ~MumpsFactorization()
    {
      if (initialised)
        {
          mumps.job = -2;
          dmumps_c(&mumps);
        }
    }

    /// Factorize @p matrix (collective).
    void
    factorize(const TrilinosWrappers::SparseMatrix &matrix)
    {
      const Epetra_CrsMatrix &A    = matrix.trilinos_matrix();
      const MPI_Comm          comm = communicator(A);
      const bool              root = A.Comm().MyPID() == 0;
      const bool sequential        = on_one_rank || A.Comm().NumProc() == 1;
      if (!row_map || !row_map->SameAs(A.RowMap()))
        {
          const int n = A.NumGlobalRows();
          row_map     = std::make_unique<Epetra_Map>(A.RowMap());
          root_map = std::make_unique<Epetra_Map>(n, root ? n : 0, 0, A.Comm());
          gather   = std::make_unique<Epetra_Import>(*root_map, A.RowMap());
          scatter  = std::make_unique<Epetra_Import>(A.RowMap(), *root_map);
          pattern_start.clear();
        }
      // the nonzeros of this rank's rows, for sequential MUMPS gathered on
      // rank 0 (the order of the rows does not matter to MUMPS)
      read_nonzeros(A);
      if (sequential && A.Comm().NumProc() > 1)
        gather_nonzeros(comm);
      const bool takes_part = !sequential || root;

      int error = 0;
      if (takes_part && !initialised)
        error = initialise(sequential ? MPI_COMM_SELF : comm,
                           A.NumGlobalRows(),
                           !sequential);
      bool reuse = takes_part && fits_analysed_pattern();
      if (!sequential)
        reuse = Utilities::MPI::min(static_cast<int>(reuse), comm) == 1;
      if (takes_part && error == 0)
        {
          error = reuse ? 0 : analyse();
          if (reuse)
            analysis_seconds = -1.;
          if (error == 0)
            error = numerical_factorization();
          // e.g. more delayed pivots than the kept analysis made room for:
          // a new analysis of the same pattern with these values (MUMPS's
          // error code is the same on all its ranks)
          if (error < 0 && reuse)
            {
              error = analyse();
              if (error == 0)
                error = numerical_factorization();
            }
        }
      // every rank throws, or none
      error = std::min(Utilities::MPI::min(error, comm), 0);
      check_mumps(error, "factorization");
    }

    /// MUMPS's statistics of the factorization (INFOG(9), INFOG(11),
    /// RINFOG(3)) and rank 0's wall times of its analysis and numerical
    /// factorization, the same on all ranks (collective).
    std::string
    statistics() const
    {
      // factor entries (negative: millions), largest front, flops, the
      // wall times of analysis and factorization (on rank 0)
      double info[5] = {0., 0., 0., analysis_seconds, factorization_seconds};
      if (initialised)
        {
          info[0] = mumps.infog[8];
          info[1] = mumps.infog[10];
          info[2] = mumps.rinfog[2];
        }
      root_map->Comm().Broadcast(info, 5, 0);
      const double       entries = info[0] < 0 ? -1e6 * info[0] : info[0];
      std::ostringstream out;
      out << std::setprecision(3) << info[2] / 1e9 << " GFlop, "
          << entries / 1e6 << " M factor entries, largest front "
          << static_cast<long>(info[1]) << "; analysis ";
      if (info[3] >= 0.)
        out << info[3] << " s";
      else
        out << "reused";
      out << ", factorization " << info[4] << " s";
      return out.str();
    }

    /// x = A^{-1} b with the factors (collective).
    void
    solve(TrilinosWrappers::MPI::Vector       &x,
          const TrilinosWrappers::MPI::Vector &b)
    {
      // right-hand side and solution on rank 0, MUMPS's host
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
      error = std::min(Utilities::MPI::min(error, x.get_mpi_communicator()), 0);
      check_mumps(error, "solve");
      x.trilinos_vector().Import(on_root, *scatter, Insert);
    }

  private:
    /// The MPI communicator of @p A.
    static MPI_Comm
    communicator(const Epetra_CrsMatrix &A)
    {
      return dynamic_cast<const Epetra_MpiComm &>(A.Comm()).Comm();
    }

    /// Start MUMPS on @p comm for a matrix of @p n rows, given by rows on
    /// each rank (@p distributed) or all on the host. Returns MUMPS's error.
    int
    initialise(const MPI_Comm comm, const int n, const bool distributed)
    {
      mumps.comm_fortran = MPI_Comm_c2f(comm);
      mumps.par          = 1;
      mumps.sym          = 0;
      mumps.job          = -1;
      dmumps_c(&mumps);
      if (mumps.infog[0] < 0)
        return mumps.infog[0];
      initialised = true;
      // no printing; MUMPS chooses ordering and scaling
      mumps.icntl[0]  = -1;
      mumps.icntl[1]  = -1;
      mumps.icntl[2]  = -1;
      mumps.icntl[3]  = 0;
      mumps.icntl[13] = 20;
      mumps.icntl[17] = distributed ? 3 : 0;
      mumps.n         = n;
      return 0;
    }

    /// The nonzero entries of @p M's rows on this rank, row by row, 1-based
    /// columns ascending.
    void
    read_nonzeros(const Epetra_CrsMatrix &M)
    {
      const int n = M.NumMyRows();
      new_rows.resize(n);
      new_start.assign(n + 1, 0);
      new_columns.clear();
      new_values.clear();
      std::vector<std::pair<int, double>> row;
      for (int i = 0; i < n; ++i)
        {
          int     length;
          double *values;
          int    *columns;
          M.ExtractMyRowView(i, length, values, columns);
          row.clear();
          for (int k = 0; k < length; ++k)
            if (values[k] != 0.)
              row.emplace_back(M.GCID(columns[k]) + 1, values[k]);
          std::sort(row.begin(), row.end());
          for (const auto &[column, value] : row)
            {
              new_columns.push_back(column);
              new_values.push_back(value);
            }
          new_rows[i]      = M.GRID(i) + 1;
          new_start[i + 1] = new_columns.size();
        }
    }

    /// Rank 0: the nonzeros read on all ranks, theirs after its own.
    void
    gather_nonzeros(const MPI_Comm comm)
    {
      const int        n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const int        root    = Utilities::MPI::this_mpi_process(comm) == 0;
      std::vector<int> row_lengths(new_rows.size());
      for (std::size_t i = 0; i < new_rows.size(); ++i)
        row_lengths[i] = new_start[i + 1] - new_start[i];
      // each rank's number of rows and of entries
      const int        counts[2] = {static_cast<int>(new_rows.size()),
                                    static_cast<int>(new_columns.size())};
      std::vector<int> all_counts(root ? 2 * n_ranks : 0);
      MPI_Gather(counts, 2, MPI_INT, all_counts.data(), 2, MPI_INT, 0, comm);
      std::vector<int> sizes[2], offsets[2];
      for (unsigned int c = 0; c < 2 && root; ++c)
        for (int r = 0; r < n_ranks; ++r)
          {
            offsets[c].push_back(r == 0 ? 0 :
                                          offsets[c].back() + sizes[c].back());
            sizes[c].push_back(all_counts[2 * r + c]);
          }
      const auto collect = [&](auto &local, const unsigned int c) {
        using Vector = std::decay_t<decltype(local)>;
        const MPI_Datatype type =
          std::is_same_v<typename Vector::value_type, int> ? MPI_INT :
                                                             MPI_DOUBLE;
        Vector all(root ? offsets[c].back() + sizes[c].back() : 0);
        MPI_Gatherv(local.data(),
                    local.size(),
                    type,
                    all.data(),
                    sizes[c].data(),
                    offsets[c].data(),
                    type,
                    0,
                    comm);
        local.swap(all);
      };
      collect(new_rows, 0);
      collect(row_lengths, 0);
      collect(new_columns, 1);
      collect(new_values, 1);
      new_start.assign(new_rows.size() + 1, 0);
      for (std::size_t i = 0; i < new_rows.size(); ++i)
        new_start[i + 1] = new_start[i] + row_lengths[i];
    }

    /**
     * Whether every nonzero entry read lies in the analysed pattern (of the
     * same rows); if so, entries gets their values in the pattern's order,
     * with zeros for the pattern's other entries.
     */
    bool
    fits_analysed_pattern()
    {
      if (pattern_rows != new_rows)
        return false;
      entries.assign(columns.size(), 0.);
      for (std::size_t i = 0; i < new_rows.size(); ++i)
        {
          unsigned int p = pattern_start[i];
          for (unsigned int k = new_start[i]; k < new_start[i + 1]; ++k)
            {
              while (p < pattern_start[i + 1] && columns[p] < new_columns[k])
                ++p;
              if (p == pattern_start[i + 1] || columns[p] != new_columns[k])
                return false;
              entries[p] = new_values[k];
            }
        }
      return true;
    }

    /**
     * MUMPS's analysis of the union of the analysed pattern and the nonzero
     * entries read, or of the latter alone when the union would hold more
     * than max_pattern_growth times as many entries; entries gets the values
     * in that pattern's order. Returns MUMPS's error.
     */
    int
    analyse()
    {
      const std::size_t         n = new_rows.size();
      std::vector<unsigned int> start(n + 1, 0);
      std::vector<int>          merged;
      std::vector<double>       values;
      const bool                union_possible = pattern_rows == new_rows;
      for (std::size_t i = 0; i < n && union_possible; ++i)
        {
          unsigned int p = pattern_start[i], k = new_start[i];
          while (p < pattern_start[i + 1] || k < new_start[i + 1])
            if (k == new_start[i + 1] ||
                (p < pattern_start[i + 1] && columns[p] < new_columns[k]))
              {
                merged.push_back(columns[p++]);
                values.push_back(0.);
              }
            else
              {
                if (p < pattern_start[i + 1] && columns[p] == new_columns[k])
                  ++p;
                merged.push_back(new_columns[k]);
                values.push_back(new_values[k++]);
              }
          start[i + 1] = merged.size();
        }
      if (union_possible &&
          merged.size() <= max_pattern_growth * new_columns.size())
        {
          pattern_start.swap(start);
          columns.swap(merged);
          entries.swap(values);
        }
      else
        {
          pattern_rows  = new_rows;
          pattern_start = new_start;
          columns       = new_columns;
          entries       = new_values;
        }
      rows.resize(columns.size());
      for (std::size_t i = 0; i < n; ++i)
        std::fill(rows.begin() + pattern_start[i],
                  rows.begin() + pattern_start[i + 1],
                  pattern_rows[i]);

      Timer timer;
      if (mumps.icntl[17] == 3)
        {
          mumps.nnz_loc = rows.size();
          mumps.irn_loc = rows.data();
          mumps.jcn_loc = columns.data();
          mumps.a_loc   = entries.data();
        }
      else
        {
          mumps.nnz = rows.size();
          mumps.irn = rows.data();
          mumps.jcn = columns.data();
          mumps.a   = entries.data();
        }
      mumps.job = 1;
      dmumps_c(&mumps);
      analysis_seconds = timer.wall_time();
      return mumps.infog[0] < 0 ? mumps.infog[0] : 0;
    }

    /// MUMPS's numerical factorization of entries. Returns MUMPS's error.
    int
    numerical_factorization()
    {
      Timer timer;
      mumps.job = 2;
      dmumps_c(&mumps);
      factorization_seconds = timer.wall_time();
      return mumps.infog[0] < 0 ? mumps.infog[0] : 0;
    }

    /// The analysed pattern may hold at most this many times the nonzero
    /// entries of the matrix it is used for.
    static constexpr double max_pattern_growth = 1.05;

    /// Whether MUMPS runs on rank 0 alone.
    const bool on_one_rank;

    /// The distributed rows, all rows on rank 0, and the maps between them.
    std::unique_ptr<Epetra_Map>    row_map, root_map;
    std::unique_ptr<Epetra_Import> gather, scatter;

    /// The analysed pattern of the rows this rank gives MUMPS (1-based rows
    /// and the start of each in the entries, 1-based row and column of each
    /// entry) with the latest matrix's values; and that matrix's nonzero
    /// entries in the same form.
    std::vector<int>          pattern_rows, new_rows;
    std::vector<unsigned int> pattern_start, new_start;
    std::vector<int>          rows, columns, new_columns;
    std::vector<double>       entries, new_values;

    DMUMPS_STRUC_C mumps{};
    bool           initialised = false;

    /// Wall times of MUMPS's latest analysis (-1 if the factorization
    /// reused an earlier one) and numerical factorization (s).
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
    // the analysis of the factorization stays for the new matrix's pattern
    factors_current = false;
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
    if (factors_current)
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
    if (!factorization)
      factorization = std::make_unique<MumpsFactorization>(reproducible);
    factorization->factorize(matrix);
    factors_current = true;
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
