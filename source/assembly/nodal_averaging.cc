// F-bar with nodal averaging of the volume ratio for linear tetrahedra:
// vertex patches, internal forces and their exact tangent.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/material/factory.h>
#include <densify/material/j2_plasticity.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /**
     * The index of @p column in a row's @p indices (of @p length), for the
     * columns of a block visited in increasing order: @p k is where the
     * merge with the row's sorted indices stands (start it at 0 for each
     * row); an index the merge misses is searched for in the whole row.
     */
    int
    position_in_row(const int *indices,
                    const int  length,
                    const int  column,
                    int       &k)
    {
      while (k < length && indices[k] < column)
        ++k;
      if (k < length && indices[k] == column)
        return k;
      const int *found = std::find(indices, indices + length, column);
      if (found == indices + length)
        throw std::runtime_error("nodal averaging: an entry is missing from "
                                 "the sparsity pattern (internal error)");
      return found - indices;
    }



    /**
     * A += M on the rows and columns @p dofs. Locally owned rows are added
     * straight into the Epetra row storage by merging the block's columns,
     * sorted by local column index, with the row's sorted indices: the patch
     * matrices of the F-bar are dense blocks of about 60 x 60, and deal.II's
     * add() (one binary search per entry) took a third of their assembly
     * time (Epetra sorts each row's indices when the matrix is filled; an
     * index not found by the merge is searched for in the whole row). Rows
     * owned elsewhere go through deal.II.
     */
    void
    add_merged(TrilinosWrappers::SparseMatrix             &A,
               const std::vector<types::global_dof_index> &dofs,
               const FullMatrix<double>                   &M,
               std::vector<std::pair<int, unsigned int>>  &columns)
    {
      Epetra_CrsMatrix &E = const_cast<Epetra_CrsMatrix &>(A.trilinos_matrix());
      const unsigned int n = dofs.size();
      columns.resize(n);
      bool fast = E.Filled();
      for (unsigned int j = 0; j < n && fast; ++j)
        {
          columns[j] = {E.ColMap().LID(static_cast<int>(dofs[j])), j};
          fast       = columns[j].first >= 0;
        }
      if (!fast)
        {
          A.add(dofs, M);
          return;
        }
      std::sort(columns.begin(), columns.end());
      for (unsigned int i = 0; i < n; ++i)
        {
          const int row = E.RowMap().LID(static_cast<int>(dofs[i]));
          if (row < 0)
            {
              A.add(dofs[i], n, dofs.data(), &M(i, 0), false);
              continue;
            }
          int     length;
          double *values;
          int    *indices;
          E.ExtractMyRowView(row, length, values, indices);
          int k = 0;
          for (const auto &[column, j] : columns)
            values[position_in_row(indices, length, column, k)] += M(i, j);
        }
    }
  } // namespace



  NodalAveraging::NodalAveraging(const DoFHandler<3>       &dof_handler,
                                 const Mapping<3>          &mapping,
                                 const std::vector<double> &cell_volume_weights)
    : weights(cell_volume_weights)
  {
    for (const double alpha : weights)
      if (!(alpha >= 0. && alpha <= 1.))
        throw std::runtime_error(
          "nodal averaging: a cell volume weight outside [0, 1]");
    const FiniteElement<3> &fe = dof_handler.get_fe();
    if (fe.n_dofs_per_cell() != 12 || fe.n_components() != 3)
      throw std::runtime_error(
        "nodal averaging needs linear tetrahedra (Mesh/Polynomial degree = 1)");
    const Triangulation<3> &tria = dof_handler.get_triangulation();
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_artificial())
        throw std::runtime_error(
          "nodal averaging needs every cell on every MPI rank");
    {
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      if (relevant.n_elements() != dof_handler.n_dofs())
        throw std::runtime_error(
          "nodal averaging needs the values of all DoFs on every MPI rank");
    }

    // P1 gradients are constant: one point at the centroid, weight = volume
    const QGaussSimplex<3> centroid(1);
    FEValues<3>            fe_values(mapping,
                          fe,
                          centroid,
                          update_gradients | update_JxW_values);
    cells.resize(tria.n_active_cells());
    patches.resize(tria.n_vertices());
    std::vector<types::global_dof_index> dofs(12);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const unsigned int e = cell->active_cell_index();
        Cell              &c = cells[e];
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < 12; ++i)
          {
            // the element's DoF i: component r of the shape function of
            // vertex v (P1: base function v is that of vertex v)
            const auto [r, v] = fe.system_to_component_index(i);
            c.grad[v]         = fe_values.shape_grad(i, 0);
            c.dofs[3 * v + r] = dofs[i];
          }
        c.volume   = fe_values.JxW(0);
        c.material = cell->material_id();
        c.centre   = cell->center();
        c.owned    = cell->is_locally_owned();
        for (unsigned int v = 0; v < 4; ++v)
          {
            Patch &patch = patches[cell->vertex_index(v)];
            c.vertex[v]  = cell->vertex_index(v);
            c.slot[v]    = patch.cells.size();
            patch.cells.push_back(e);
            patch.volume += c.volume;
            patch.touched = patch.touched || c.owned;
          }
      }

    for (Cell &c : cells)
      for (unsigned int v = 0; v < 4; ++v)
        {
          const Patch &patch = patches[c.vertex[v]];
          c.patch_share[v]   = patch.touched ? c.volume / patch.volume : 0.;
        }

    unsigned int offset = 0;
    for (Patch &patch : patches)
      {
        for (const unsigned int f : patch.cells)
          patch.dofs.insert(patch.dofs.end(),
                            cells[f].dofs.begin(),
                            cells[f].dofs.end());
        std::sort(patch.dofs.begin(), patch.dofs.end());
        patch.dofs.erase(std::unique(patch.dofs.begin(), patch.dofs.end()),
                         patch.dofs.end());
        patch.position.resize(patch.cells.size());
        for (unsigned int slot = 0; slot < patch.cells.size(); ++slot)
          for (unsigned int i = 0; i < 12; ++i)
            patch.position[slot][i] =
              std::lower_bound(patch.dofs.begin(),
                               patch.dofs.end(),
                               cells[patch.cells[slot]].dofs[i]) -
              patch.dofs.begin();
        patch.offset = offset;
        offset += patch.dofs.size();
      }
    U.resize(offset);
    U_prime.resize(offset);
    std::vector<bool> needed(cells.size(), false);
    for (const Cell &c : cells)
      if (c.owned)
        for (const unsigned int a : c.vertex)
          for (const unsigned int f : patches[a].cells)
            needed[f] = true;
    for (unsigned int f = 0; f < cells.size(); ++f)
      if (needed[f])
        needed_cells.push_back(f);
    for (unsigned int e = 0; e < cells.size(); ++e)
      if (cells[e].owned)
        owned_cells.push_back(e);
  }



  void
  NodalAveraging::add_sparsity(TrilinosWrappers::SparsityPattern &sparsity)
  {
    // a new pattern: the placement of the blocks is made anew
    placement.valid = false;
    for (const Patch &patch : patches)
      if (patch.touched)
        for (const types::global_dof_index row : patch.dofs)
          sparsity.add_entries(row, patch.dofs.begin(), patch.dofs.end(), true);
  }



  bool
  NodalAveraging::place(const TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &E = A.trilinos_matrix();
    placement.valid           = false;
    if (!E.Filled())
      return false;
    placement.row_start.assign(1, 0);
    placement.entry_start.assign(1, 0);
    placement.rows.clear();
    placement.entries.clear();
    std::vector<std::pair<int, unsigned int>> columns;
    // one block: its rows and, by merging its sorted columns with each row's
    // indices, the index of each entry in its row
    const auto place_block = [&](const types::global_dof_index *dofs,
                                 const unsigned int             n) {
      columns.resize(n);
      bool local = true;
      for (unsigned int j = 0; j < n; ++j)
        {
          columns[j] = {E.ColMap().LID(static_cast<int>(dofs[j])), j};
          local      = local && columns[j].first >= 0;
        }
      std::sort(columns.begin(), columns.end());
      const std::size_t base = placement.entries.size();
      placement.entries.resize(base + std::size_t(n) * n, 0);
      for (unsigned int i = 0; i < n; ++i)
        {
          // rows owned elsewhere (or a column this rank does not hold) go
          // through deal.II's add()
          const int row =
            local ? E.RowMap().LID(static_cast<int>(dofs[i])) : -1;
          placement.rows.push_back(row);
          if (row < 0)
            continue;
          int     length;
          double *values;
          int    *indices;
          E.ExtractMyRowView(row, length, values, indices);
          if (length > std::numeric_limits<std::uint16_t>::max() + 1)
            return false;
          int k = 0;
          for (const auto &[column, j] : columns)
            placement.entries[base + std::size_t(i) * n + j] =
              position_in_row(indices, length, column, k);
        }
      placement.row_start.push_back(placement.rows.size());
      placement.entry_start.push_back(placement.entries.size());
      return true;
    };
    const auto empty_block = [&]() {
      placement.row_start.push_back(placement.rows.size());
      placement.entry_start.push_back(placement.entries.size());
    };
    for (const Cell &c : cells)
      if (!c.owned)
        empty_block();
      else if (!place_block(c.dofs.data(), 12))
        return false;
    for (const Patch &patch : patches)
      if (!patch.touched)
        empty_block();
      else if (!place_block(patch.dofs.data(), patch.dofs.size()))
        return false;
    placement.valid = true;
    return true;
  }



  template <typename Value>
  void
  NodalAveraging::add_through_placement(TrilinosWrappers::SparseMatrix &A,
                                        const unsigned int              block,
                                        const types::global_dof_index  *dofs,
                                        const Value                    &value,
                                        std::vector<double> &row) const
  {
    Epetra_CrsMatrix  &E = const_cast<Epetra_CrsMatrix &>(A.trilinos_matrix());
    const std::size_t  first = placement.row_start[block];
    const unsigned int n     = placement.row_start[block + 1] - first;
    const std::uint16_t *entry =
      &placement.entries[placement.entry_start[block]];
    for (unsigned int i = 0; i < n; ++i, entry += n)
      {
        const int placed_row = placement.rows[first + i];
        if (placed_row < 0)
          {
            row.resize(n);
            for (unsigned int j = 0; j < n; ++j)
              row[j] = value(i, j);
            A.add(dofs[i], n, dofs, row.data(), false);
            continue;
          }
        int     length;
        double *values;
        int    *indices;
        E.ExtractMyRowView(placed_row, length, values, indices);
        for (unsigned int j = 0; j < n; ++j)
          values[entry[j]] += value(i, j);
      }
  }



  void
  NodalAveraging::add_placed(TrilinosWrappers::SparseMatrix &A,
                             const unsigned int              block,
                             const types::global_dof_index  *dofs,
                             const FullMatrix<double>       &M,
                             std::vector<double>            &row) const
  {
    add_through_placement(
      A,
      block,
      dofs,
      [&M](const unsigned int i, const unsigned int j) { return M(i, j); },
      row);
  }



  void
  NodalAveraging::add_rank_two(TrilinosWrappers::SparseMatrix &A,
                               const unsigned int              block,
                               const types::global_dof_index  *dofs,
                               const double                   *u,
                               const double                   *v,
                               const double                   *y,
                               const double                   *z,
                               std::vector<double>            &row) const
  {
    add_through_placement(
      A,
      block,
      dofs,
      [=](const unsigned int i, const unsigned int j) {
        return u[i] * v[j] + y[i] * z[j];
      },
      row);
  }



  void
  NodalAveraging::add_block(TrilinosWrappers::SparseMatrix             &A,
                            const std::vector<types::global_dof_index> &dofs,
                            const FullMatrix<double>                   &M)
  {
    add_merged(A, dofs, M, columns);
  }



  void
  NodalAveraging::add_cell_block(TrilinosWrappers::SparseMatrix &A,
                                 const bool                      placed,
                                 const unsigned int              e,
                                 const FullMatrix<double>       &M,
                                 std::vector<double>            &row)
  {
    const Cell &c = cells[e];
    if (placed)
      add_placed(A, e, c.dofs.data(), M, row);
    else
      {
        cell_dofs.assign(c.dofs.begin(), c.dofs.end());
        add_block(A, cell_dofs, M);
      }
  }



  Tensor<2, 3>
  NodalAveraging::deformation_gradient(const unsigned int e,
                                       const AllValues   &solution) const
  {
    const Cell  &c = cells[e];
    Tensor<2, 3> F = unit_symmetric_tensor<3>();
    for (unsigned int i = 0; i < 12; ++i)
      F[c.component(i)] += solution[c.dofs[i]] * c.gradient(i);
    return F;
  }



  std::string
  NodalAveraging::inverted(const Cell &c, const double j)
  {
    std::ostringstream text;
    text << "nodal averaging: inverted cell (det F = " << j
         << " <= 0) in particle " << c.material << " at (" << c.centre
         << ") mm (reference position)";
    return text.str();
  }



  double
  blended_volume_measure(const double j_bar,
                         const double j_cell,
                         const double alpha,
                         const bool   finite_strain)
  {
    if (alpha == 0.)
      return j_bar;
    if (finite_strain)
      return j_cell * std::pow(j_bar / j_cell, 1. - alpha);
    return (1. - alpha) * j_bar + alpha * j_cell;
  }



  double
  fbar_scale(const double j_bar,
             const double j_cell,
             const double alpha,
             double      &j_used)
  {
    if (alpha == 0.)
      {
        j_used = j_bar;
        return std::cbrt(j_bar / j_cell);
      }
    // (j_used / j_cell)^(1/3) = (j_bar / j_cell)^((1 - alpha) / 3): one
    // power instead of the blend's power and a cube root
    const double sc = std::pow(j_bar / j_cell, (1. - alpha) / 3.);
    j_used          = j_cell * sc * sc * sc;
    return sc;
  }



  Tensor<2, 3>
  fbar_deformation(const Tensor<2, 3> &F,
                   const double        j_bar,
                   const bool          finite_strain,
                   double             *scale)
  {
    if (finite_strain)
      {
        const double sc = std::cbrt(j_bar / determinant(F));
        if (scale != nullptr)
          *scale = sc;
        return sc * F;
      }
    if (scale != nullptr)
      *scale = 1.;
    return F + (j_bar - (trace(F) - 2.)) / 3. *
                 Tensor<2, 3>(unit_symmetric_tensor<3>());
  }



  std::vector<double>
  NodalAveraging::vertex_volume_measures(
    const AllValues                                    &solution,
    const std::vector<std::shared_ptr<const Material>> &materials) const
  {
    std::vector<double> averaged(patches.size(), 0.);
    for (const unsigned int e : needed_cells)
      {
        const Cell        &c = cells[e];
        const Tensor<2, 3> F = deformation_gradient(e, solution);
        const double       j = materials[c.material]->finite_strain() ?
                                 determinant(F) :
                                 trace(F) - 2.;
        for (unsigned int v = 0; v < 4; ++v)
          averaged[c.vertex[v]] += c.volume * j;
      }
    for (unsigned int a = 0; a < patches.size(); ++a)
      if (patches[a].volume > 0.)
        averaged[a] /= patches[a].volume;
    return averaged;
  }
} // namespace densify
