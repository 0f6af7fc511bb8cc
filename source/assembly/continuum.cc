// The continuum force term: internal forces and tangent of every cell.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/continuum.h>
#include <densify/assembly/nodal_averaging.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <stdexcept>

namespace densify
{
  Continuum::Continuum(
    const DoFHandler<3>                                &dof_handler,
    const std::vector<std::shared_ptr<const Material>> &materials,
    std::unique_ptr<NodalAveraging>                     nodal_averaging,
    const unsigned int                                  degree)
    : dof_handler(dof_handler)
    , materials(materials)
    , nodal_averaging(std::move(nodal_averaging))
    , degree(degree)
  {
    // quadrature-point history only where a material needs it: one state
    // per quadrature point, or per cell corner with the nodal-averaged F-bar
    // (NodalAveraging's layout)
    for (const auto &m : materials)
      history = history || m->needs_history();
    if (history)
      {
        per_cell =
          this->nodal_averaging ? 4 : QGaussSimplex<3>(degree + 1).size();
        committed_history.assign(
          dof_handler.get_triangulation().n_active_cells() * per_cell,
          MaterialState());
        trial_history = committed_history;
      }
  }



  Continuum::~Continuum() = default;



  void
  Continuum::add_couplings(TrilinosWrappers::SparsityPattern &pattern)
  {
    if (nodal_averaging)
      nodal_averaging->add_sparsity(pattern);
  }



  void
  Continuum::assemble(const AssemblyContext          &context,
                      TrilinosWrappers::MPI::Vector  &forces,
                      TrilinosWrappers::SparseMatrix *tangent)
  {
    const TrilinosWrappers::MPI::Vector &solution    = *context.solution;
    const bool                           with_matrix = tangent != nullptr;
    std::string                          material_failure;
    // with the locking remedy, its own assembly replaces the cell loop
    // explicit dynamics: the F-bar's force path on plain arrays
    const bool plain = nodal_averaging && tangent == nullptr &&
                       context.explicit_dynamics && context.values != nullptr &&
                       context.plain_forces != nullptr;
    // each explicit step is accepted: its force path updates the committed
    // states in place (commit() has nothing left to do)
    in_place = plain && history;
    if (!plain)
      fill_corners();
    if (plain)
      {
        context.plain_forces->start(forces);
        material_failure =
          nodal_averaging->forces(*context.values,
                                  materials,
                                  history ? &committed_history : nullptr,
                                  history ? &committed_history : nullptr,
                                  *context.plain_forces);
        context.plain_forces->finish(forces);
        corners_pending = in_place;
      }
    else if (nodal_averaging)
      material_failure =
        nodal_averaging->assemble(solution,
                                  materials,
                                  history ? &committed_history : nullptr,
                                  history ? &trial_history : nullptr,
                                  forces,
                                  tangent,
                                  context.explicit_dynamics);
    else
      {
        // the plain cell loop: a state per quadrature point
        const FiniteElement<3>              &fe = dof_handler.get_fe();
        const QGaussSimplex<3>               quadrature(degree + 1);
        FEValues<3>                          fe_values(*context.mapping,
                              fe,
                              quadrature,
                              update_gradients | update_JxW_values);
        const unsigned int                   n   = fe.n_dofs_per_cell();
        const unsigned int                   n_q = quadrature.size();
        FullMatrix<double>                   cell_matrix(n, n);
        Vector<double>                       cell_residual(n);
        std::vector<types::global_dof_index> dofs(n);
        std::vector<Tensor<2, 3>>            grad_u(n_q);
        std::vector<Tensor<1, 3>>            grad_phi(n);
        std::vector<Tensor<2, 3>>            A_grad(n);
        std::vector<unsigned int>            component(n);
        for (unsigned int i = 0; i < n; ++i)
          component[i] = fe.system_to_component_index(i).first;
        const FEValuesExtractors::Vector u(0);
        Tensor<2, 3>                     P;
        Tensor<4, 3>                     A;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && material_failure.empty())
            {
              fe_values.reinit(cell);
              fe_values[u].get_function_gradients(solution, grad_u);
              const Material &material = *materials[cell->material_id()];
              cell_matrix              = 0;
              cell_residual            = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
                  const unsigned int k = cell->active_cell_index() * n_q + q;
                  try
                    {
                      const MaterialState *old =
                        history ? &committed_history[k] : nullptr;
                      MaterialState *now =
                        history ? &trial_history[k] : nullptr;
                      // a residual alone needs no tangent
                      if (with_matrix)
                        material.evaluate(F, old, now, P, A);
                      else
                        material.stress(F, old, now, P);
                    }
                  catch (const std::exception &e)
                    {
                      // e.g. an inverted element; reported on every rank below
                      material_failure = e.what();
                      break;
                    }
                  const double JxW = fe_values.JxW(q);
                  // each shape function of the FESystem has one nonzero
                  // component c_i: grad phi_i = e_{c_i} (x) g_i
                  for (unsigned int i = 0; i < n; ++i)
                    {
                      grad_phi[i] = fe_values.shape_grad(i, q);
                      cell_residual(i) += (P[component[i]] * grad_phi[i]) * JxW;
                    }
                  if (!with_matrix)
                    continue;
                  // A_grad[j][k][J] = A[k][J][c_j][L] g_j[L]
                  for (unsigned int j = 0; j < n; ++j)
                    for (unsigned int k = 0; k < 3; ++k)
                      for (unsigned int J = 0; J < 3; ++J)
                        A_grad[j][k][J] = A[k][J][component[j]] * grad_phi[j];
                  for (unsigned int i = 0; i < n; ++i)
                    for (unsigned int j = 0; j < n; ++j)
                      cell_matrix(i, j) +=
                        (A_grad[j][component[i]] * grad_phi[i]) * JxW;
                }
              cell->get_dof_indices(dofs);
              forces.add(dofs, cell_residual);
              if (with_matrix)
                tangent->add(dofs, cell_matrix);
            }
      }
    forces.compress(VectorOperation::add);
    // every rank reports the failure of the lowest failing rank, with that
    // rank's own text (rank 0 writes the message the user reads)
    const MPI_Comm     comm    = dof_handler.get_communicator();
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int failing = Utilities::MPI::min(
      material_failure.empty() ? numbers::invalid_unsigned_int : rank, comm);
    if (failing != numbers::invalid_unsigned_int)
      {
        if (with_matrix)
          tangent->compress(VectorOperation::add);
        const std::string text =
          Utilities::MPI::broadcast(comm, material_failure, failing);
        throw std::runtime_error("material: " + text + " (on rank " +
                                 std::to_string(failing) + ")");
      }
  }



  void
  Continuum::commit(const AssemblyContext &context)
  {
    if (!history || in_place)
      return;
    if (context.explicit_dynamics)
      committed_history.swap(trial_history);
    else
      committed_history = trial_history;
  }



  void
  Continuum::fill_corners() const
  {
    if (corners_pending)
      nodal_averaging->fill_shared_corners(committed_history);
    corners_pending = false;
  }



  double
  Continuum::plastic_work(const Mapping<3> &mapping) const
  {
    fill_corners();
    if (!history)
      return 0.;
    // the integration weights of the history slots: V/4 at the corners of
    // the nodal-averaged F-bar, else the quadrature weights
    const QGaussSimplex<3> quadrature(degree + 1);
    FEValues<3>            fe_values(mapping,
                          dof_handler.get_fe(),
                          quadrature,
                          update_JxW_values);
    double                 work = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Material   &m = *materials[cell->material_id()];
          const std::size_t k0 =
            std::size_t(cell->active_cell_index()) * per_cell;
          if (nodal_averaging)
            for (unsigned int q = 0; q < 4; ++q)
              work += cell->measure() / 4. *
                      m.plastic_work(committed_history[k0 + q]);
          else
            {
              fe_values.reinit(cell);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                work +=
                  fe_values.JxW(q) * m.plastic_work(committed_history[k0 + q]);
            }
        }
    return Utilities::MPI::sum(work, dof_handler.get_communicator());
  }


  void
  Continuum::write_checkpoint(boost::archive::binary_oarchive &archive) const
  {
    // the history of this rank's cells, in the order of the cells
    fill_corners();
    std::vector<MaterialState> states;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (history && cell->is_locally_owned())
        for (unsigned int k = 0; k < per_cell; ++k)
          states.push_back(
            committed_history[cell->active_cell_index() * per_cell + k]);
    archive << states;
  }



  void
  Continuum::read_checkpoint(boost::archive::binary_iarchive &archive)
  {
    std::vector<MaterialState> states;
    archive >> states;
    unsigned int k = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (history && cell->is_locally_owned())
        for (unsigned int q = 0; q < per_cell; ++q, ++k)
          {
            if (k >= states.size())
              throw std::runtime_error(
                "the checkpoint's material history is incomplete");
            committed_history[cell->active_cell_index() * per_cell + q] =
              states[k];
          }
    if (k != states.size())
      throw std::runtime_error(
        "the checkpoint's material history does not fit the mesh");
    trial_history   = committed_history;
    corners_pending = false;
  }
} // namespace densify
