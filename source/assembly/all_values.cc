// Plain arrays of a Trilinos vector's values and of forces on the way into
// one.
#include <deal.II/lac/trilinos_index_access.h>

#include <densify/assembly/all_values.h>

#include <algorithm>

namespace densify
{
  const std::vector<types::global_dof_index> &
  LocalIndices::operator()(const Epetra_BlockMap &from)
  {
    if (!map || from.DataPtr() != map->DataPtr())
      {
        map = std::make_unique<Epetra_BlockMap>(from);
        global.resize(from.NumMyElements());
        for (int k = 0; k < from.NumMyElements(); ++k)
          global[k] = TrilinosWrappers::global_index(from, k);
        ++layouts;
      }
    return global;
  }



  void
  AllValues::gather(const TrilinosWrappers::MPI::Vector &vector)
  {
    const Epetra_MultiVector                   &v = vector.trilinos_vector();
    const std::vector<types::global_dof_index> &global = indices(v.Map());
    values.resize(vector.size());
    const double *local = v[0];
    for (std::size_t k = 0; k < global.size(); ++k)
      values[global[k]] = local[k];
  }



  void
  GhostImport::operator()(const TrilinosWrappers::MPI::Vector &owned,
                          TrilinosWrappers::MPI::Vector       &ghosted)
  {
    const Epetra_BlockMap &from = owned.trilinos_vector().Map();
    const Epetra_BlockMap &to   = ghosted.trilinos_vector().Map();
    if (!importer || from.DataPtr() != source->DataPtr() ||
        to.DataPtr() != target->DataPtr())
      {
        source   = std::make_unique<Epetra_BlockMap>(from);
        target   = std::make_unique<Epetra_BlockMap>(to);
        importer = std::make_unique<Epetra_Import>(to, from);
      }
    const int error = ghosted.trilinos_vector().Import(owned.trilinos_vector(),
                                                       *importer,
                                                       Insert);
    AssertThrow(error == 0, ExcTrilinosError(error));
  }



  void
  LocalForces::start(const TrilinosWrappers::MPI::Vector &vector)
  {
    const Epetra_MultiVector                   &v = vector.trilinos_vector();
    const std::vector<types::global_dof_index> &global = indices(v.Map());
    if (forces.size() != vector.size() || owned_layout != indices.n_layouts())
      {
        forces.resize(vector.size());
        owned.assign(vector.size(), false);
        for (const types::global_dof_index i : global)
          owned[i] = true;
        owned_layout = indices.n_layouts();
      }
    std::fill(forces.begin(), forces.end(), 0.);
    const double *local = v[0];
    for (std::size_t k = 0; k < global.size(); ++k)
      forces[global[k]] = local[k];
  }



  void
  LocalForces::finish(TrilinosWrappers::MPI::Vector &vector)
  {
    Epetra_MultiVector                         &v = vector.trilinos_vector();
    const std::vector<types::global_dof_index> &global = indices(v.Map());
    double                                     *local  = v[0];
    for (std::size_t k = 0; k < global.size(); ++k)
      local[k] = forces[global[k]];
    other_indices.clear();
    other_values.clear();
    for (types::global_dof_index i = 0; i < forces.size(); ++i)
      if (!owned[i] && forces[i] != 0.)
        {
          other_indices.push_back(i);
          other_values.push_back(forces[i]);
        }
    if (!other_indices.empty())
      vector.add(other_indices, other_values);
  }
} // namespace densify
