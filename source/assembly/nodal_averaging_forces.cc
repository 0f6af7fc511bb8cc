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
    // the operations of assemble() without a tangent and with shared
    // corners, in the same order up to the patch terms, which are gathered
    // per cell (the same sums in another order: forces equal to round-off);
    // what only the tangent needs is left out

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
                const Tensor<1, 3> h = F_inv_T * c.grad[i];
                dj[i]                = j * h[c.component[i]];
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
    // with a cell volume weight, each corner's F-bar factor is one
    // exponential of logarithms taken once per vertex and once per cell
    // (the same value as fbar_scale()'s power, to round-off, at a third of
    // its cost)
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
        const double log_j = (finite && alpha_e != 0.) ? std::log(j) : 0.;
        for (unsigned int i = 0; i < 12; ++i)
          t[i] = (finite ? dj[i] / j : dj[i]);
        cell_residual.fill(0.);
        // one return mapping per cell: the deviator of the first corner's
        // Kirchhoff stress, shared by all four (see assemble())
        double     p_dummy;
        const bool shared = finite && material.kirchhoff_pressure(1., p_dummy);
        Tensor<2, 3> tau_dev;
        for (unsigned int v = 0; v < 4; ++v)
          {
            const unsigned int a = c.vertex[v];
            // fbar_scale() with the cell's det F computed once
            double j_a = 0., sc = 1.;
            if (finite && alpha_e != 0.)
              {
                // (j_a / j)^(1/3) = (j_bar / j)^((1 - alpha) / 3)
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
            if (shared && v > 0)
              {
                double p_a;
                material.kirchhoff_pressure(j_a, p_a);
                Tensor<2, 3> tau = tau_dev;
                for (unsigned int d = 0; d < 3; ++d)
                  tau[d][d] += p_a;
                P = (1. / sc) * tau * inverse_transpose[e];
                if (trial)
                  (*trial)[k] = (*trial)[k - v];
              }
            else
              try
                {
                  const MaterialState *old =
                    committed ? &(*committed)[k] : nullptr;
                  MaterialState *now = trial ? &(*trial)[k] : nullptr;
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
            const double p = theta * (sc * scalar_product(P, N) / 3.);
            for (unsigned int i = 0; i < 12; ++i)
              {
                const double r = P[c.component[i]] * c.grad[i];
                cell_residual[i] += w * (sc * r - p * t[i]);
              }
            S[a] += w * p / D;
          }
        for (unsigned int i = 0; i < 12; ++i)
          residual.add(c.dofs[i], cell_residual[i]);
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
