// The body force term.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/body_force.h>
#include <densify/parameters.h>

namespace densify
{
  BodyForce::BodyForce(const DoFHandler<3> &dof_handler,
                       const Tensor<1, 3>  &force,
                       const std::vector<std::pair<double, double>> &table,
                       const unsigned int                            degree)
    : dof_handler(dof_handler)
    , force(force)
    , table(table)
    , degree(degree)
  {}



  void
  BodyForce::assemble(const AssemblyContext         &context,
                      TrilinosWrappers::MPI::Vector &forces,
                      TrilinosWrappers::SparseMatrix * /*tangent*/)
  {
    const FiniteElement<3>              &fe = dof_handler.get_fe();
    const QGaussSimplex<3>               quadrature(degree + 1);
    FEValues<3>                          fe_values(*context.mapping,
                          fe,
                          quadrature,
                          update_values | update_JxW_values);
    const FEValuesExtractors::Vector     u(0);
    const Tensor<1, 3>                   b = interpolate(table, time) * force;
    Vector<double>                       cell_residual(fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_residual = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < dofs.size(); ++i)
              cell_residual(i) -=
                (b * fe_values[u].value(i, q)) * fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          forces.add(dofs, cell_residual);
        }
    forces.compress(VectorOperation::add);
  }
} // namespace densify
