// The one element kernel of the nodal-averaged F-bar: internal forces, and
// with them their exact tangent when Newton asks for it. Both methods run
// the same code on plain arrays; the tangent's terms are compiled only into
// the instance that produces them (kernel<true>).
#include <deal.II/lac/full_matrix.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/material/j2_plasticity.h>

#include <cmath>
#include <string>

namespace densify
{
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
    solution_values.gather(solution);
    residual_forces.start(residual);
    const std::string failure = tangent != nullptr ?
                                  kernel<true>(solution_values,
                                               materials,
                                               committed,
                                               trial,
                                               residual_forces,
                                               tangent,
                                               false) :
                                  kernel<false>(solution_values,
                                                materials,
                                                committed,
                                                trial,
                                                residual_forces,
                                                nullptr,
                                                shared_corners);
    residual_forces.finish(residual);
    return failure;
  }



  std::string
  NodalAveraging::forces(
    const AllValues                                    &solution,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *committed,
    std::vector<MaterialState>                         *trial,
    LocalForces                                        &residual)
  {
    return kernel<false>(
      solution, materials, committed, trial, residual, nullptr, true);
  }



  void
  NodalAveraging::fill_shared_corners(std::vector<MaterialState> &states) const
  {
    for (const unsigned int e : owned_cells)
      if (cells[e].material < shared_law.size() &&
          shared_law[cells[e].material])
        {
          const std::size_t k0 = std::size_t(e) * 4;
          for (unsigned int v = 1; v < 4; ++v)
            states[k0 + v] = states[k0];
        }
  }



  std::string
  NodalAveraging::shared_deviators(
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *committed,
    std::vector<MaterialState>                         *trial)
  {
    cell_tau_dev.resize(cells.size());
    // batches of one material's cells
    constexpr unsigned int                          batch_size = 64;
    std::array<const Tensor<2, 3> *, batch_size>    F;
    std::array<const MaterialState *, batch_size>   old;
    std::array<MaterialState *, batch_size>         now;
    std::array<SymmetricTensor<2, 3> *, batch_size> tau_dev;
    unsigned int                                    n = 0, material = 0;
    const MaterialState *const *old_of = committed ? old.data() : nullptr;
    MaterialState *const       *now_of = trial ? now.data() : nullptr;
    const auto                  flush  = [&]() {
      if (n > 0)
        materials[material]->kirchhoff_deviators(
          n, F.data(), old_of, now_of, tau_dev.data());
      n = 0;
    };
    try
      {
        for (const unsigned int e : owned_cells)
          {
            const Cell &c = cells[e];
            if (!shared_law[c.material])
              continue;
            if (n > 0 && (c.material != material || n == batch_size))
              flush();
            const std::size_t k0 = std::size_t(e) * 4;
            material             = c.material;
            F[n]                 = &cell_F[e];
            old[n]               = committed ? &(*committed)[k0] : nullptr;
            now[n]               = trial ? &(*trial)[k0] : nullptr;
            tau_dev[n]           = &cell_tau_dev[e];
            ++n;
          }
        flush();
      }
    catch (const std::exception &error)
      {
        return error.what();
      }
    return "";
  }



  template <bool with_tangent>
  std::string
  NodalAveraging::kernel(
    const AllValues                                    &solution,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *committed,
    std::vector<MaterialState>                         *trial,
    LocalForces                                        &residual,
    TrilinosWrappers::SparseMatrix                     *tangent,
    const bool                                          shared_corners)
  {
    // explicit steps update the states in place (see forces())
    const bool in_place = trial != nullptr && trial == committed;
    Assert(!(with_tangent && in_place),
           ExcMessage("Newton needs the committed states kept"));
    // scatter the tangent's blocks through their placement in its pattern
    bool placed = false;
    if constexpr (with_tangent)
      placed = placement.valid || place(*tangent);

    // 1. kinematics of the cells around the vertices of owned cells and
    //    their vertex averages j_a = sum_f V_f j_f / sum_f V_f (complete
    //    at those vertices, the only ones used below)
    //    Per law, resolved once: finite strain, and whether the corners of
    //    its cells share the deviator (forces alone, laws with
    //    Material::kirchhoff_pressure(); see the declaration of assemble())
    finite_law.resize(materials.size());
    shared_law.resize(materials.size());
    for (unsigned int m = 0; m < materials.size(); ++m)
      {
        double p_dummy;
        finite_law[m] = materials[m]->finite_strain();
        shared_law[m] = !with_tangent && shared_corners && finite_law[m] &&
                        materials[m]->kirchhoff_pressure(0., p_dummy);
      }
    j_bar.assign(patches.size(), 0.);
    inverse_transpose.resize(cells.size());
    cell_F.resize(cells.size());
    cell_j.resize(cells.size());
    cell_dj.resize(cells.size());
    for (const unsigned int e : needed_cells)
      {
        const Cell             &c      = cells[e];
        const bool              finite = finite_law[c.material];
        std::array<double, 12> &dj     = cell_dj[e];
        Tensor<2, 3>            F      = unit_symmetric_tensor<3>();
        for (unsigned int i = 0; i < 12; ++i)
          F[c.component(i)] += solution[c.dofs[i]] * c.gradient(i);
        cell_F[e] = F;
        double j;
        if (finite)
          {
            j = determinant(F);
            if (!(j > 0.))
              return inverted(c, j);
            const Tensor<2, 3> F_inv_T = transpose(invert(F));
            inverse_transpose[e]       = F_inv_T;
            for (unsigned int i = 0; i < 12; ++i)
              {
                // j (F^{-T} grad N_i)[c_i]
                const Tensor<1, 3> &g = c.gradient(i);
                const Tensor<1, 3> &f = F_inv_T[c.component(i)];
                dj[i] = j * (f[0] * g[0] + f[1] * g[1] + f[2] * g[2]);
              }
          }
        else
          {
            j = trace(F) - 2.;
            for (unsigned int i = 0; i < 12; ++i)
              dj[i] = c.gradient(i)[c.component(i)];
          }
        cell_j[e] = j;
        for (unsigned int v = 0; v < 4; ++v)
          j_bar[c.vertex[v]] += c.volume * j;
      }
    // the logarithms of the vertex averages, once per vertex: each corner's
    // F-bar factor and pressure come from them and the cell's ln j
    log_j_bar.resize(patches.size());
    for (unsigned int a = 0; a < patches.size(); ++a)
      if (patches[a].volume > 0.)
        {
          j_bar[a] /= patches[a].volume;
          log_j_bar[a] = j_bar[a] > 0. ? std::log(j_bar[a]) : 0.;
        }

    // forces alone: the Kirchhoff deviators of the cells whose corners
    // share them (see below), a material's cells side by side
    // (Material::kirchhoff_deviators())
    if constexpr (!with_tangent)
      if (shared_corners)
        {
          const std::string failure =
            shared_deviators(materials, committed, trial);
          if (!failure.empty())
            return failure;
        }

    // 2. owned cells: the material at each corner with Fbar(j_a), the
    //    cell's forces, and per vertex the pressure sum S_a; with the
    //    tangent the cell-local parts of the matrix and per vertex the
    //    pieces of the patch terms (doc/theory.md for the derivation). The
    //    shape gradients are constant in a P1 cell, so the four corners'
    //    terms of the cell matrix are summed first (the material tangents
    //    weighted by w sc^2, the vectors of the rank-one terms by w) and
    //    contracted with the gradients once per cell.
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    S.assign(patches.size(), 0.);
    std::array<double, 12> t, cell_residual;
    Tensor<2, 3>           P;
    // the tangent's work space
    FullMatrix<double>           cell_matrix;
    std::array<double, 12>       r, x, x_prime, X, X_prime;
    std::array<Tensor<2, 3>, 12> A_grad;
    std::array<Tensor<1, 3>, 12> h;
    Tensor<4, 3>                 A, A_sum;
    // rows of a placed block owned elsewhere
    std::vector<double> row;
    if constexpr (with_tangent)
      {
        beta.assign(patches.size(), 0.);
        std::fill(U.begin(), U.end(), 0.);
        std::fill(U_prime.begin(), U_prime.end(), 0.);
        cell_matrix.reinit(12, 12);
      }
    for (const unsigned int e : owned_cells)
      {
        const Cell                   &c        = cells[e];
        const Tensor<2, 3>           &F        = cell_F[e];
        const double                  j        = cell_j[e];
        const std::array<double, 12> &dj       = cell_dj[e];
        const Material               &material = *materials[c.material];
        const bool                    finite   = finite_law[c.material];
        const double                  w        = c.volume / 4.;
        // the stabilisation: the corner's volume measure depends on j_a
        // with the weight theta = 1 - alpha, so every term that came from
        // d(ln j_a - ln j_e) carries theta (and the second-order ones
        // theta^2)
        const double alpha_e = cell_volume_weight(c.material);
        const double theta   = 1. - alpha_e;
        const double log_j   = finite ? std::log(j) : 0.;
        // the barrier against crushed cells (CellVolumeBarrier): the force
        // V k e t_i per unit d(ln j)/du_i, its derivative
        // V k (t_i t_j - e h_i[c_j] h_j[c_i])
        const double k_barrier =
          finite ? c.volume * volume_barrier.modulus(c.material) : 0.;
        const double e_barrier =
          k_barrier > 0. ? volume_barrier.excess(log_j) : 0.;
        const double barrier = k_barrier * e_barrier;

        // forces alone: one return mapping per cell for laws whose corners
        // share the Kirchhoff deviator (see the declaration of assemble())
        if (shared_law[c.material])
          {
            // The corners' stresses tau_a = tau_dev + p_a I differ in the
            // pressure alone, p_a at ln j_a = ln j + theta (ln j_bar_a -
            // ln j). With h_i = F^{-T} grad N_i and t_i = h_i[c_i], the
            // corner terms w (sc P_a[c_i] . grad N_i - theta p_a t_i) of the
            // general path below sum to
            //   V tau_dev[c_i] . h_i + w alpha (sum_a p_a) h_i[c_i]
            //   = (M grad N_i)[c_i],  M = (V tau_dev + w alpha sum_a p_a I)
            //   F^{-T}
            // (P_a = tau_a (sc F)^{-T}, P_a : F = tr tau_a / sc): one return
            // mapping, four pressures and one 3x3 product a cell.
            const std::size_t            k0      = std::size_t(e) * 4;
            const SymmetricTensor<2, 3> &tau_dev = cell_tau_dev[e];
            // in place, fill_shared_corners() copies them when read
            if (trial && !in_place)
              for (unsigned int v = 1; v < 4; ++v)
                (*trial)[k0 + v] = (*trial)[k0];
            double p_corners = 0.;
            for (unsigned int v = 0; v < 4; ++v)
              {
                const unsigned int a = c.vertex[v];
                double             p_a;
                material.kirchhoff_pressure(log_j +
                                              theta * (log_j_bar[a] - log_j),
                                            p_a);
                p_corners += p_a;
                S[a] += w * theta * p_a / j_bar[a];
              }
            const Tensor<2, 3> &F_inv_T = inverse_transpose[e];
            double              M[3][3];
            for (unsigned int r_ = 0; r_ < 3; ++r_)
              for (unsigned int J_ = 0; J_ < 3; ++J_)
                M[r_][J_] =
                  c.volume * (tau_dev[r_][0] * F_inv_T[0][J_] +
                              tau_dev[r_][1] * F_inv_T[1][J_] +
                              tau_dev[r_][2] * F_inv_T[2][J_]) +
                  (w * alpha_e * p_corners + barrier) * F_inv_T[r_][J_];
            for (unsigned int i = 0; i < 12; ++i)
              {
                const double       *m = M[c.component(i)];
                const Tensor<1, 3> &g = c.gradient(i);
                residual.add(c.dofs[i],
                             m[0] * g[0] + m[1] * g[1] + m[2] * g[2]);
              }
            continue;
          }

        // the general path: a return mapping at each corner;
        // t_i = d(ln J)/du_i (finite strain) or d(div u)/du_i
        for (unsigned int i = 0; i < 12; ++i)
          t[i] = (finite ? dj[i] / j : dj[i]);
        cell_residual.fill(0.);
        // the corners' sums of w gamma and of w p
        double gamma_sum = 0., p_sum = 0.;
        if constexpr (with_tangent)
          {
            A_sum = 0;
            X.fill(0.);
            X_prime.fill(0.);
            if (finite)
              for (unsigned int i = 0; i < 12; ++i)
                h[i] = inverse_transpose[e] * c.gradient(i);
          }
        for (unsigned int v = 0; v < 4; ++v)
          {
            const unsigned int a = c.vertex[v];
            // Fbar = sc F (finite strain), D the denominator of d(ln j_a);
            // fbar_scale() with the cell's ln j computed once
            double j_a = 0., sc = 1.;
            if (finite && alpha_e != 0.)
              {
                sc  = std::exp(theta / 3. * (log_j_bar[a] - log_j));
                j_a = j * sc * sc * sc;
              }
            else if (finite)
              sc = fbar_scale(j_bar[a], j, alpha_e, j_a);
            else
              j_a = blended_volume_measure(j_bar[a], j, alpha_e, false);
            const Tensor<2, 3> F_bar =
              finite ? sc * F : fbar_deformation(F, j_a, false);
            const Tensor<2, 3> &N = finite ? F : I;
            const double        D = finite ? j_bar[a] : 1.;
            const std::size_t   k = std::size_t(e) * 4 + v;
            try
              {
                const MaterialState *old =
                  committed ? &(*committed)[k] : nullptr;
                MaterialState *now = trial ? &(*trial)[k] : nullptr;
                if constexpr (with_tangent)
                  material.evaluate(F_bar, old, now, P, A);
                else if (in_place)
                  {
                    // a law need not read and write one state
                    MaterialState updated;
                    material.stress(F_bar, old, &updated, P);
                    *now = updated;
                  }
                else
                  material.stress(F_bar, old, now, P);
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
                r[i] = P[c.component(i)] * c.gradient(i);
                cell_residual[i] += w * (sc * r[i] - p * t[i]);
              }
            S[a] += w * p / D;
            if constexpr (!with_tangent)
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
                const double a_i = AN[c.component(i)] * c.gradient(i);
                const double b_i = NA[c.component(i)] * c.gradient(i);
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
        for (unsigned int i = 0; i < 12; ++i)
          residual.add(c.dofs[i], cell_residual[i] + barrier * t[i]);
        if constexpr (!with_tangent)
          continue;

        // the cell matrix: sum_v w [sc^2 g_i A g_j - x_i t_j - t_i x'_j +
        // gamma t_i t_j + p h_i[c_j] h_j[c_i]] and the barrier's terms
        for (unsigned int j_ = 0; j_ < 12; ++j_)
          for (unsigned int k2 = 0; k2 < 3; ++k2)
            for (unsigned int J = 0; J < 3; ++J)
              A_grad[j_][k2][J] =
                A_sum[k2][J][c.component(j_)] * c.gradient(j_);
        for (unsigned int i = 0; i < 12; ++i)
          for (unsigned int j_ = 0; j_ < 12; ++j_)
            {
              double kij = A_grad[j_][c.component(i)] * c.gradient(i) -
                           X[i] * t[j_] - t[i] * X_prime[j_] +
                           gamma_sum * t[i] * t[j_];
              if (finite)
                kij += (p_sum - barrier) * h[i][c.component(j_)] *
                       h[j_][c.component(i)];
              if (e_barrier != 0.)
                kij += k_barrier * t[i] * t[j_];
              cell_matrix(i, j_) = kij;
            }
        add_cell_block(*tangent, placed, e, cell_matrix, row);
      }

    // 3. patch terms of the forces: S_a b_a with b_a = d j_a / du = sum
    //    over the cells f of the patch of (V_f / V_a) d j_f / du, gathered
    //    per cell: each cell adds (sum over its vertices a of S_a V_f / V_a)
    //    d j_f / du, 12 entries a cell instead of 12 for each of its four
    //    patches
    for (const unsigned int e : needed_cells)
      {
        const Cell &c           = cells[e];
        double      coefficient = 0.;
        for (unsigned int v = 0; v < 4; ++v)
          coefficient += S[c.vertex[v]] * c.patch_share[v];
        if (coefficient == 0.)
          continue;
        const std::array<double, 12> &dj = cell_dj[e];
        for (unsigned int i = 0; i < 12; ++i)
          residual.add(c.dofs[i], coefficient * dj[i]);
      }
    if constexpr (!with_tangent)
      return "";

    // 4. the patch terms of the tangent, U b^T + b U'^T + beta b b^T, added
    //    row by row as u_i b^T + b_i (U' + beta b)^T straight into the
    //    placement
    std::vector<double> b, b_shifted;
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
              b[patch.position[slot][i]] += c_f * cell_dj[f][i];
          }
        const double *u  = &U[patch.offset];
        const double *up = &U_prime[patch.offset];
        b_shifted.resize(n);
        for (unsigned int j_ = 0; j_ < n; ++j_)
          b_shifted[j_] = up[j_] + beta[a] * b[j_];
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
              for (unsigned int j_ = 0; j_ < n; ++j_)
                patch_matrix(i, j_) = u[i] * b[j_] + b[i] * b_shifted[j_];
            add_block(*tangent, patch.dofs, patch_matrix);
          }
      }

    // 5. the second derivative of the vertex averages (finite strain):
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
        const double                  jf  = cell_j[f];
        const std::array<double, 12> &djf = cell_dj[f];
        for (unsigned int i = 0; i < 12; ++i)
          h[i] = inverse_transpose[f] * cf.gradient(i);
        for (unsigned int i = 0; i < 12; ++i)
          for (unsigned int j_ = 0; j_ < 12; ++j_)
            cell_matrix(i, j_) =
              C * (djf[i] * djf[j_] / jf -
                   jf * h[i][cf.component(j_)] * h[j_][cf.component(i)]);
        add_cell_block(*tangent, placed && cf.owned, f, cell_matrix, row);
      }
    return "";
  }
} // namespace densify
