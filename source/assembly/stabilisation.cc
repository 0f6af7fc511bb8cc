// The stabilisation term of the Newton tangent.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/stabilisation.h>

namespace densify
{
  Stabilisation::Stabilisation(const DoFHandler<3>       &dof_handler,
                               const std::vector<double> &alpha,
                               const unsigned int         degree)
    : dof_handler(dof_handler)
    , alpha(alpha)
    , degree(degree)
  {}



  void
  Stabilisation::reinit(const TrilinosWrappers::SparsityPattern &pattern,
                        const Mapping<3>                        &mapping)
  {
    matrix.reinit(pattern);
    const FiniteElement<3>              &fe = dof_handler.get_fe();
    const QGaussSimplex<3>               quadrature(degree + 1);
    FEValues<3>                          fe_values(mapping,
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
          const double a = alpha[cell->material_id()];
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) += a * fe_values[u].value(i, q) *
                                     fe_values[u].value(j, q) *
                                     fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          matrix.add(dofs, cell_matrix);
        }
    matrix.compress(VectorOperation::add);
  }



  void
  Stabilisation::assemble(const AssemblyContext & /*context*/,
                          TrilinosWrappers::MPI::Vector & /*residual*/,
                          TrilinosWrappers::SparseMatrix * /*tangent*/)
  {}



  void
  Stabilisation::finish_tangent(TrilinosWrappers::SparseMatrix &tangent) const
  {
    tangent.add(1., matrix);
  }



  double
  Stabilisation::force(const TrilinosWrappers::MPI::Vector &du) const
  {
    TrilinosWrappers::MPI::Vector f(du.locally_owned_elements(),
                                    du.get_mpi_communicator());
    matrix.vmult(f, du);
    return f.l1_norm();
  }
} // namespace densify
