// The stabilisation term of the Newton tangent.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/stabilisation.h>

namespace densify
{
  Stabilisation::Stabilisation(const DoFHandler<3>       &dof_handler,
                               const std::vector<double> &alpha,
                               const double               beta,
                               const unsigned int         degree)
    : dof_handler(dof_handler)
    , alpha(alpha)
    , beta(beta)
    , degree(degree)
  {}



  void
  Stabilisation::reinit(const TrilinosWrappers::SparsityPattern &pattern,
                        const Mapping<3>                        &mapping)
  {
    this->mapping = &mapping;
    // the matrix is kept only where it is in every tangent; the continuation
    // adds it to the tangent directly, in the iterations that use it
    if (beta > 0)
      {
        matrix.reinit(pattern);
        add_mass(matrix, 1.);
      }
  }



  void
  Stabilisation::add_mass(TrilinosWrappers::SparseMatrix &target,
                          const double                    factor) const
  {
    Assert(mapping, ExcInternalError());
    const FiniteElement<3>              &fe = dof_handler.get_fe();
    const QGaussSimplex<3>               quadrature(degree + 1);
    FEValues<3>                          fe_values(*mapping,
                          fe,
                          quadrature,
                          update_values | update_JxW_values);
    const FEValuesExtractors::Vector     u(0);
    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double a = factor * alpha[cell->material_id()];
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) += a * fe_values[u].value(i, q) *
                                     fe_values[u].value(j, q) *
                                     fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          target.add(dofs, cell_matrix);
        }
    target.compress(VectorOperation::add);
  }



  void
  Stabilisation::assemble(const AssemblyContext & /*context*/,
                          TrilinosWrappers::MPI::Vector & /*residual*/,
                          TrilinosWrappers::SparseMatrix * /*tangent*/)
  {}



  void
  Stabilisation::finish_tangent(TrilinosWrappers::SparseMatrix &tangent) const
  {
    if (beta > 0)
      tangent.add(beta, matrix);
  }



  void
  Stabilisation::add_scaled(TrilinosWrappers::SparseMatrix &tangent,
                            const double                    factor) const
  {
    if (beta > 0)
      tangent.add(factor, matrix);
    else
      add_mass(tangent, factor);
  }



  double
  Stabilisation::force(const TrilinosWrappers::MPI::Vector &du) const
  {
    if (beta == 0)
      return 0.;
    TrilinosWrappers::MPI::Vector f(du.locally_owned_elements(),
                                    du.get_mpi_communicator());
    matrix.vmult(f, du);
    return beta * f.l1_norm();
  }
} // namespace densify
