// The internal forces of the nodal-averaged F-bar alone, for explicit
// dynamics: plain arrays in and out, no tangent.
#include <densify/assembly/all_values.h>
#include <densify/assembly/nodal_averaging.h>
#include <densify/material/j2_plasticity.h>

#include <cmath>
#include <string>

namespace densify
{
  std::string
  NodalAveraging::forces(
    const AllValues                                    &solution,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const std::vector<MaterialState>                   *committed,
    std::vector<MaterialState>                         *trial,
    LocalForces                                        &residual)
  {
    // the operations of assemble() without a tangent: the same kinematics
    // and patch terms; for laws whose corners share the Kirchhoff deviator
    // (J2) the corner terms summed in closed form (step 2), so the forces
    // equal assemble()'s residual to round-off
    // (tests/nodal_averaging_consistency.cc)

    // 1. kinematics of the cells around the vertices of owned cells and
    //    their vertex averages
    j_bar.assign(patches.size(), 0.);
    inverse_transpose.resize(cells.size());
    cell_F.resize(cells.size());
    cell_j.resize(cells.size());
    cell_dj.resize(cells.size());
    for (const unsigned int e : needed_cells)
      {
        const Cell             &c      = cells[e];
        const bool              finite = materials[c.material]->finite_strain();
        std::array<double, 12> &dj     = cell_dj[e];
        Tensor<2, 3>            F      = unit_symmetric_tensor<3>();
        for (unsigned int i = 0; i < 12; ++i)
          F[c.component[i]] += solution[c.dofs[i]] * c.grad[i];
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
                const Tensor<1, 3> &g = c.grad[i];
                const Tensor<1, 3> &f = F_inv_T[c.component[i]];
                dj[i] = j * (f[0] * g[0] + f[1] * g[1] + f[2] * g[2]);
              }
          }
        else
          {
            j = trace(F) - 2.;
            for (unsigned int i = 0; i < 12; ++i)
              dj[i] = c.grad[i][c.component[i]];
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

    // 2. owned cells: the material at each corner with Fbar(j_a), the
    //    cell's forces, and per vertex the pressure sum S_a
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    S.assign(patches.size(), 0.);
    std::array<double, 12> t, cell_residual;
    Tensor<2, 3>           P;
    for (unsigned int e = 0; e < cells.size(); ++e)
      {
        const Cell &c = cells[e];
        if (!c.owned)
          continue;
        const Tensor<2, 3>           &F        = cell_F[e];
        const double                  j        = cell_j[e];
        const std::array<double, 12> &dj       = cell_dj[e];
        const Material               &material = *materials[c.material];
        const bool                    finite   = material.finite_strain();
        const double                  w        = c.volume / 4.;
        const double                  alpha_e  = cell_volume_weight(c.material);
        const double                  theta    = 1. - alpha_e;
        const double                  log_j    = finite ? std::log(j) : 0.;
        // the barrier against crushed cells: V k e per unit d(ln j)/du
        const double barrier = finite ?
                                 c.volume * volume_barrier.modulus(c.material) *
                                   volume_barrier.excess(log_j) :
                                 0.;
        // one return mapping per cell: the deviator of the Kirchhoff stress,
        // shared by all four corners (see assemble())
        double     p_dummy;
        const bool shared = finite && material.kirchhoff_pressure(0., p_dummy);
        if (shared)
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
            const std::size_t     k0 = std::size_t(e) * 4;
            SymmetricTensor<2, 3> tau_dev;
            try
              {
                material.kirchhoff_deviator(F,
                                            committed ? &(*committed)[k0] :
                                                        nullptr,
                                            trial ? &(*trial)[k0] : nullptr,
                                            tau_dev);
              }
            catch (const std::exception &error)
              {
                return error.what();
              }
            if (trial)
              for (unsigned int v = 1; v < 4; ++v)
                (*trial)[k0 + v] = (*trial)[k0];
            double p_sum = 0.;
            for (unsigned int v = 0; v < 4; ++v)
              {
                const unsigned int a = c.vertex[v];
                double             p_a;
                material.kirchhoff_pressure(log_j +
                                              theta * (log_j_bar[a] - log_j),
                                            p_a);
                p_sum += p_a;
                S[a] += w * theta * p_a / j_bar[a];
              }
            const Tensor<2, 3> &F_inv_T = inverse_transpose[e];
            double              M[3][3];
            for (unsigned int r = 0; r < 3; ++r)
              for (unsigned int J_ = 0; J_ < 3; ++J_)
                M[r][J_] = c.volume * (tau_dev[r][0] * F_inv_T[0][J_] +
                                       tau_dev[r][1] * F_inv_T[1][J_] +
                                       tau_dev[r][2] * F_inv_T[2][J_]) +
                           (w * alpha_e * p_sum + barrier) * F_inv_T[r][J_];
            for (unsigned int i = 0; i < 12; ++i)
              {
                const double       *m = M[c.component[i]];
                const Tensor<1, 3> &g = c.grad[i];
                residual.add(c.dofs[i],
                             m[0] * g[0] + m[1] * g[1] + m[2] * g[2]);
              }
            continue;
          }

        // the general path: a return mapping at each corner
        for (unsigned int i = 0; i < 12; ++i)
          t[i] = (finite ? dj[i] / j : dj[i]);
        cell_residual.fill(0.);
        for (unsigned int v = 0; v < 4; ++v)
          {
            const unsigned int a = c.vertex[v];
            // fbar_scale() with the cell's det F computed once
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
                material.stress(F_bar, old, now, P);
              }
            catch (const std::exception &error)
              {
                return error.what();
              }
            const double p = theta * (sc * scalar_product(P, N) / 3.);
            for (unsigned int i = 0; i < 12; ++i)
              {
                const double r = P[c.component[i]] * c.grad[i];
                cell_residual[i] += w * (sc * r - p * t[i]);
              }
            S[a] += w * p / D;
          }
        for (unsigned int i = 0; i < 12; ++i)
          residual.add(c.dofs[i], cell_residual[i] + barrier * t[i]);
      }

    // 3. patch terms: S_a b_a with b_a = d j_a / du = sum over the cells f
    //    of the patch of (V_f / V_a) d j_f / du, gathered per cell: each
    //    cell adds (sum over its vertices a of S_a V_f / V_a) d j_f / du,
    //    12 entries a cell instead of 12 for each of its four patches
    for (const unsigned int e : needed_cells)
      {
        const Cell &c           = cells[e];
        double      coefficient = 0.;
        for (unsigned int v = 0; v < 4; ++v)
          {
            const Patch &patch = patches[c.vertex[v]];
            if (patch.touched)
              coefficient += S[c.vertex[v]] * c.volume / patch.volume;
          }
        if (coefficient == 0.)
          continue;
        const std::array<double, 12> &dj = cell_dj[e];
        for (unsigned int i = 0; i < 12; ++i)
          residual.add(c.dofs[i], coefficient * dj[i]);
      }
    return "";
  }
} // namespace densify
