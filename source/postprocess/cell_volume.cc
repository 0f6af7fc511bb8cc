// The element's health: the smallest volume ratio V/V0 of any cell.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <densify/postprocess/cell_volume.h>

#include <array>
#include <vector>

namespace densify
{
  SmallestCellVolume
  smallest_cell_volume(const DoFHandler<3>                 &dof_handler,
                       const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution)
  {
    const FiniteElement<3> &fe = dof_handler.get_fe();
    // det(I + grad u) is a polynomial of degree 3 (degree - 1) on a cell
    const QGaussSimplex<3>           quadrature(fe.degree == 1 ? 1 : 3);
    FEValues<3>                      fe_values(mapping,
                          fe,
                          quadrature,
                          update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, 3>>        grad_u(quadrature.size());
    SmallestCellVolume               smallest;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(solution, grad_u);
          double volume = 0., reference = 0.;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              volume += determinant(unit_symmetric_tensor<3>() + grad_u[q]) *
                        fe_values.JxW(q);
              reference += fe_values.JxW(q);
            }
          const double ratio = volume / reference;
          if (ratio < smallest.ratio)
            {
              smallest.ratio    = ratio;
              smallest.particle = cell->material_id();
              smallest.centre   = cell->center();
            }
        }
    // the smallest over the ranks, with its cell's particle and centre
    const MPI_Comm     comm  = dof_handler.get_communicator();
    const double       min   = Utilities::MPI::min(smallest.ratio, comm);
    const unsigned int rank  = Utilities::MPI::this_mpi_process(comm);
    const unsigned int owner = Utilities::MPI::min(
      smallest.ratio == min ? rank : numbers::invalid_unsigned_int, comm);
    std::array<double, 5> packed{{smallest.ratio,
                                  double(smallest.particle),
                                  smallest.centre[0],
                                  smallest.centre[1],
                                  smallest.centre[2]}};
    packed            = Utilities::MPI::broadcast(comm, packed, owner);
    smallest.ratio    = packed[0];
    smallest.particle = static_cast<unsigned int>(packed[1]);
    smallest.centre   = Point<3>(packed[2], packed[3], packed[4]);
    return smallest;
  }
} // namespace densify
