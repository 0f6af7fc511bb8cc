// Plain arrays of a Trilinos vector's values and of forces on the way into
// one.
#include <deal.II/lac/trilinos_index_access.h>

#include <densify/assembly/all_values.h>

#include <algorithm>

namespace densify
{
  void
  AllValues::gather(const TrilinosWrappers::MPI::Vector &vector)
  {
    const Epetra_MultiVector &v = vector.trilinos_vector();
    values.resize(vector.size());
    const int     n     = v.Map().NumMyElements();
    const double *local = v[0];
    for (int k = 0; k < n; ++k)
      values[TrilinosWrappers::global_index(v.Map(), k)] = local[k];
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
    const Epetra_MultiVector &v = vector.trilinos_vector();
    const int                 n = v.Map().NumMyElements();
    if (forces.size() != vector.size())
      {
        forces.resize(vector.size());
        owned.assign(vector.size(), false);
        for (int k = 0; k < n; ++k)
          owned[TrilinosWrappers::global_index(v.Map(), k)] = true;
      }
    std::fill(forces.begin(), forces.end(), 0.);
    const double *local = v[0];
    for (int k = 0; k < n; ++k)
      forces[TrilinosWrappers::global_index(v.Map(), k)] = local[k];
  }



  void
  LocalForces::finish(TrilinosWrappers::MPI::Vector &vector)
  {
    Epetra_MultiVector &v     = vector.trilinos_vector();
    const int           n     = v.Map().NumMyElements();
    double             *local = v[0];
    for (int k = 0; k < n; ++k)
      local[k] = forces[TrilinosWrappers::global_index(v.Map(), k)];
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
