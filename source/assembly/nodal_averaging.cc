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
    add_block(TrilinosWrappers::SparseMatrix             &A,
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
            c.grad[i]      = fe_values.shape_grad(i, 0);
            c.component[i] = fe.system_to_component_index(i).first;
            c.dofs[i]      = dofs[i];
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
    state.resize(cells.size());
    std::vector<bool> needed(cells.size(), false);
    for (const Cell &c : cells)
      if (c.owned)
        for (const unsigned int a : c.vertex)
          for (const unsigned int f : patches[a].cells)
            needed[f] = true;
    for (unsigned int f = 0; f < cells.size(); ++f)
      if (needed[f])
        needed_cells.push_back(f);
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



  Tensor<2, 3>
  NodalAveraging::deformation_gradient(
    const Cell                          &c,
    const TrilinosWrappers::MPI::Vector &solution)
  {
    Tensor<2, 3> F = unit_symmetric_tensor<3>();
    for (unsigned int i = 0; i < 12; ++i)
      F[c.component[i]] += solution(c.dofs[i]) * c.grad[i];
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
    const TrilinosWrappers::MPI::Vector                &solution,
    const std::vector<std::shared_ptr<const Material>> &materials) const
  {
    std::vector<double> averaged(patches.size(), 0.);
    for (const unsigned int e : needed_cells)
      {
        const Cell        &c = cells[e];
        const Tensor<2, 3> F = deformation_gradient(c, solution);
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



  std::string
  NodalAveraging::assemble(
    const TrilinosWrappers::MPI::Vector                &solution,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *committed,
    std::vector<MaterialState>                         *trial,
    TrilinosWrappers::MPI::Vector                      &residual,
    TrilinosWrappers::SparseMatrix                     *tangent,
    const bool                                          shared_corners)
  {
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    // scatter the blocks through their placement in the tangent's pattern
    const bool placed =
      tangent != nullptr && (placement.valid || place(*tangent));

    // 1. kinematics of the cells around the vertices of owned cells and
    //    their vertex averages j_a = sum_f V_f j_f / sum_f V_f (complete
    //    at those vertices, the only ones used below)
    j_bar.assign(patches.size(), 0.);
    for (const unsigned int e : needed_cells)
      {
        const Cell &c      = cells[e];
        CellState  &s      = state[e];
        const bool  finite = materials[c.material]->finite_strain();
        s.F                = deformation_gradient(c, solution);
        if (finite)
          {
            s.j = determinant(s.F);
            if (!(s.j > 0.))
              return inverted(c, s.j);
            const Tensor<2, 3> F_inv_T = transpose(invert(s.F));
            for (unsigned int i = 0; i < 12; ++i)
              {
                s.h[i]  = F_inv_T * c.grad[i];
                s.dj[i] = s.j * s.h[i][c.component[i]];
              }
          }
        else
          {
            s.j = trace(s.F) - 2.;
            for (unsigned int i = 0; i < 12; ++i)
              s.dj[i] = c.grad[i][c.component[i]];
          }
        for (unsigned int v = 0; v < 4; ++v)
          j_bar[c.vertex[v]] += c.volume * s.j;
      }
    for (unsigned int a = 0; a < patches.size(); ++a)
      if (patches[a].volume > 0.)
        j_bar[a] /= patches[a].volume;

    // 2. owned cells: the material at each corner a with Fbar(j_a); the
    //    cell-local parts of residual and tangent, and per vertex the
    //    pieces of the patch terms (see doc/theory.md for the derivation).
    //    The shape gradients are constant in a P1 cell, so the four
    //    corners' terms of the cell matrix are summed first (the material
    //    tangents weighted by w sc^2, the vectors of the rank-one terms by
    //    w) and contracted with the gradients once per cell.
    S.assign(patches.size(), 0.);
    beta.assign(patches.size(), 0.);
    std::fill(U.begin(), U.end(), 0.);
    std::fill(U_prime.begin(), U_prime.end(), 0.);
    FullMatrix<double>                        cell_matrix(12, 12);
    Vector<double>                            cell_residual(12);
    std::vector<types::global_dof_index>      dofs(12);
    std::array<double, 12>                    t, r, x, x_prime, X, X_prime;
    std::array<Tensor<2, 3>, 12>              A_grad;
    std::vector<std::pair<int, unsigned int>> columns;
    // work space for the rows of a placed block owned elsewhere
    std::vector<double> row;
    Tensor<2, 3>        P;
    Tensor<4, 3>        A, A_sum;
    for (unsigned int e = 0; e < cells.size(); ++e)
      {
        const Cell &c = cells[e];
        if (!c.owned)
          continue;
        const CellState &s        = state[e];
        const Material  &material = *materials[c.material];
        const bool       finite   = material.finite_strain();
        const double     w        = c.volume / 4.;
        // the stabilisation: the corner's volume measure depends on j_a
        // with the weight theta = 1 - alpha, so every term that came from
        // d(ln j_a - ln j_e) carries theta (and the second-order ones
        // theta^2)
        const double alpha_e = cell_volume_weight(c.material);
        const double theta   = 1. - alpha_e;
        // t_i = d(ln J)/du_i (finite strain) or d(div u)/du_i
        for (unsigned int i = 0; i < 12; ++i)
          t[i] = (finite ? s.dj[i] / s.j : s.dj[i]);
        cell_residual = 0;
        A_sum         = 0;
        X.fill(0.);
        X_prime.fill(0.);
        // the corners' sums of w gamma and of w p
        double gamma_sum = 0., p_sum = 0.;
        // one return mapping per cell: the deviator of the first corner's
        // Kirchhoff stress, shared by all four (see the declaration)
        double     p_dummy;
        const bool shared = shared_corners && tangent == nullptr && finite &&
                            material.kirchhoff_pressure(0., p_dummy);
        Tensor<2, 3> tau_dev, F_inv_T;
        if (shared)
          F_inv_T = transpose(invert(s.F));
        for (unsigned int v = 0; v < 4; ++v)
          {
            const unsigned int a = c.vertex[v];
            // Fbar = sc F (finite strain), D the denominator of d(ln j_a)
            double sc = 1., D = 1., j_a = 0.;
            if (finite)
              sc = fbar_scale(j_bar[a], s.j, alpha_e, j_a);
            else
              j_a = blended_volume_measure(j_bar[a], s.j, alpha_e, false);
            const Tensor<2, 3> F_bar =
              finite ? sc * s.F : fbar_deformation(s.F, j_a, false);
            Tensor<2, 3> N;
            if (finite)
              {
                N = s.F;
                D = j_bar[a];
              }
            else
              N = I;
            const std::size_t k = std::size_t(e) * 4 + v;
            if (shared && v > 0)
              {
                // tau = dev tau + p(j_a) I, P = tau Fbar^-T
                double p_a;
                material.kirchhoff_pressure(std::log(j_a), p_a);
                Tensor<2, 3> tau = tau_dev;
                for (unsigned int d = 0; d < 3; ++d)
                  tau[d][d] += p_a;
                P = (1. / sc) * tau * F_inv_T;
                if (trial)
                  (*trial)[k] = (*trial)[k - v];
              }
            else
              try
                {
                  const MaterialState *old =
                    committed ? &(*committed)[k] : nullptr;
                  MaterialState *now = trial ? &(*trial)[k] : nullptr;
                  if (tangent != nullptr)
                    material.evaluate(F_bar, old, now, P, A);
                  else
                    material.stress(F_bar, old, now, P);
                  if (shared)
                    {
                      tau_dev          = P * transpose(F_bar);
                      const double p_0 = trace(tau_dev) / 3.;
                      for (unsigned int d = 0; d < 3; ++d)
                        tau_dev[d][d] -= p_0;
                    }
                }
              catch (const std::exception &error)
                {
                  return error.what();
                }
            // p_F: Kirchhoff pressure of Fbar (finite) or tr P / 3; p its
            // part conjugate to ln j_a - ln j_e
            const double p_F = sc * scalar_product(P, N) / 3.;
            const double p   = theta * p_F;
            for (unsigned int i = 0; i < 12; ++i)
              {
                r[i] = P[c.component[i]] * c.grad[i];
                cell_residual(i) += w * (sc * r[i] - p * t[i]);
              }
            S[a] += w * p / D;
            if (tangent == nullptr)
              continue;

            // A:N, N:A and N:A:N
            Tensor<2, 3> AN, NA;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int J = 0; J < 3; ++J)
                for (unsigned int k2 = 0; k2 < 3; ++k2)
                  for (unsigned int L = 0; L < 3; ++L)
                    {
                      AN[i][J] += A[i][J][k2][L] * N[k2][L];
                      NA[k2][L] += N[i][J] * A[i][J][k2][L];
                    }
            const double n_a_n = scalar_product(NA, N);
            const double gamma =
              theta * theta *
              (finite ? sc * sc * n_a_n / 9. + p_F / 3. : n_a_n / 9.);
            for (unsigned int i = 0; i < 12; ++i)
              {
                const double a_i = AN[c.component[i]] * c.grad[i];
                const double b_i = NA[c.component[i]] * c.grad[i];
                x[i] = theta * (finite ? sc * sc / 3. * a_i + sc / 3. * r[i] :
                                         a_i / 3.);
                x_prime[i] =
                  theta *
                  (finite ? sc * sc / 3. * b_i + sc / 3. * r[i] : b_i / 3.);
                X[i] += w * x[i];
                X_prime[i] += w * x_prime[i];
              }
            // sum_v w sc^2 A_v
            const double weight = w * sc * sc;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int J = 0; J < 3; ++J)
                for (unsigned int k2 = 0; k2 < 3; ++k2)
                  for (unsigned int L = 0; L < 3; ++L)
                    A_sum[i][J][k2][L] += weight * A[i][J][k2][L];
            gamma_sum += w * gamma;
            p_sum += w * p;
            const Patch &patch = patches[a];
            for (unsigned int i = 0; i < 12; ++i)
              {
                const unsigned int m =
                  patch.offset + patch.position[c.slot[v]][i];
                U[m] += w * (x[i] - gamma * t[i]) / D;
                U_prime[m] += w * (x_prime[i] - gamma * t[i]) / D;
              }
            beta[a] += w * (gamma - (finite ? p : 0.)) / (D * D);
          }
        // the barrier against crushed cells (CellVolumeBarrier): the force
        // V k e t_i, its derivative V k (t_i t_j - e h_i[c_j] h_j[c_i])
        const double k_barrier =
          finite ? c.volume * volume_barrier.modulus(c.material) : 0.;
        const double e_barrier =
          k_barrier > 0. ? volume_barrier.excess(std::log(s.j)) : 0.;
        if (e_barrier != 0.)
          for (unsigned int i = 0; i < 12; ++i)
            cell_residual(i) += k_barrier * e_barrier * t[i];
        std::copy(c.dofs.begin(), c.dofs.end(), dofs.begin());
        residual.add(dofs, cell_residual);
        if (tangent == nullptr)
          continue;

        // the cell matrix: sum_v w [sc^2 g_i A g_j - x_i t_j - t_i x'_j +
        // gamma t_i t_j + p h_i[c_j] h_j[c_i]]
        for (unsigned int j = 0; j < 12; ++j)
          for (unsigned int k2 = 0; k2 < 3; ++k2)
            for (unsigned int J = 0; J < 3; ++J)
              A_grad[j][k2][J] = A_sum[k2][J][c.component[j]] * c.grad[j];
        for (unsigned int i = 0; i < 12; ++i)
          for (unsigned int j = 0; j < 12; ++j)
            {
              double kij = A_grad[j][c.component[i]] * c.grad[i] - X[i] * t[j] -
                           t[i] * X_prime[j] + gamma_sum * t[i] * t[j];
              if (finite)
                kij += (p_sum - k_barrier * e_barrier) *
                       s.h[i][c.component[j]] * s.h[j][c.component[i]];
              if (e_barrier != 0.)
                kij += k_barrier * t[i] * t[j];
              cell_matrix(i, j) = kij;
            }
        if (placed)
          add_placed(*tangent, e, c.dofs.data(), cell_matrix, row);
        else
          add_block(*tangent, dofs, cell_matrix, columns);
      }

    // 3. patch terms: with b = d j_a / du (nonzero on all DoFs of the
    //    patch), the residual gets S_a b and the tangent
    //    U b^T + b U'^T + beta b b^T + S_a sum_f c_f d^2 J_f. The last sum
    //    is gathered per cell below; the rank-three rest is added row by
    //    row, u_i b^T + b_i (U' + beta b)^T, straight into the placement.
    std::vector<double> b, b_shifted;
    Vector<double>      patch_residual;
    FullMatrix<double>  patch_matrix;
    for (unsigned int a = 0; a < patches.size(); ++a)
      {
        const Patch &patch = patches[a];
        if (!patch.touched)
          continue;
        const unsigned int n = patch.dofs.size();
        b.assign(n, 0.);
        for (unsigned int slot = 0; slot < patch.cells.size(); ++slot)
          {
            const unsigned int f   = patch.cells[slot];
            const double       c_f = cells[f].volume / patch.volume;
            for (unsigned int i = 0; i < 12; ++i)
              b[patch.position[slot][i]] += c_f * state[f].dj[i];
          }
        patch_residual.reinit(n);
        for (unsigned int i = 0; i < n; ++i)
          patch_residual(i) = S[a] * b[i];
        residual.add(patch.dofs, patch_residual);
        if (tangent == nullptr)
          continue;

        const double *u  = &U[patch.offset];
        const double *up = &U_prime[patch.offset];
        b_shifted.resize(n);
        for (unsigned int j = 0; j < n; ++j)
          b_shifted[j] = up[j] + beta[a] * b[j];
        if (placed)
          add_rank_two(*tangent,
                       cells.size() + a,
                       patch.dofs.data(),
                       u,
                       b.data(),
                       b.data(),
                       b_shifted.data(),
                       row);
        else
          {
            patch_matrix.reinit(n, n);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                patch_matrix(i, j) = u[i] * b[j] + b[i] * b_shifted[j];
            add_block(*tangent, patch.dofs, patch_matrix, columns);
          }
      }
    if (tangent == nullptr)
      return "";

    // 4. the second derivative of the vertex averages (finite strain):
    //    sum_a S_a sum_{f in patch a} V_f / V_a d^2 J_f, gathered per cell
    //    f as C_f d^2 J_f with C_f = V_f sum_{a of f} S_a / V_a and
    //    d^2 J_f = J_f (t t^T - T), T_ij = h_i[c_j] h_j[c_i]. S_a holds
    //    this rank's part, so a cell owned elsewhere next to an owned one
    //    contributes here too.
    for (const unsigned int f : needed_cells)
      {
        const Cell &cf = cells[f];
        if (!materials[cf.material]->finite_strain())
          continue;
        double C = 0.;
        for (unsigned int v = 0; v < 4; ++v)
          {
            const Patch &patch = patches[cf.vertex[v]];
            if (patch.touched && S[cf.vertex[v]] != 0.)
              C += S[cf.vertex[v]] / patch.volume;
          }
        if (C == 0.)
          continue;
        C *= cf.volume;
        const CellState &sf = state[f];
        for (unsigned int i = 0; i < 12; ++i)
          for (unsigned int j = 0; j < 12; ++j)
            cell_matrix(i, j) =
              C * (sf.dj[i] * sf.dj[j] / sf.j -
                   sf.j * sf.h[i][cf.component[j]] * sf.h[j][cf.component[i]]);
        std::copy(cf.dofs.begin(), cf.dofs.end(), dofs.begin());
        if (placed && cf.owned)
          add_placed(*tangent, f, cf.dofs.data(), cell_matrix, row);
        else
          add_block(*tangent, dofs, cell_matrix, columns);
      }
    return "";
  }
} // namespace densify
