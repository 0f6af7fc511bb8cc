// The internal forces of the nodal-averaged F-bar alone, for explicit
// dynamics: plain arrays in and out, no tangent.
#include <densify/assembly/all_values.h>
#include <densify/assembly/nodal_averaging.h>
#include <densify/material/j2_plasticity.h>

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
    // the same operations, in the same order, as assemble() without a
    // tangent and with shared corners, so that the forces are the same to
    // the last bit; what only the tangent needs is left out

    // 1. kinematics of the cells around the vertices of owned cells and
    //    their vertex averages
    j_bar.assign(patches.size(), 0.);
    inverse_transpose.resize(cells.size());
    cell_F.resize(cells.size());
    cell_j.resize(cells.size());
    cell_dj.resize(cells.size());
    // the weights V_f / V_a of the patches' cells, fixed with the mesh
    if (slot_weight.empty())
      {
        slot_start.assign(1, 0);
        for (const Patch &patch : patches)
          {
            for (const unsigned int f : patch.cells)
              slot_weight.push_back(cells[f].volume / patch.volume);
            slot_start.push_back(slot_weight.size());
          }
      }
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
              return "nodal averaging: det F = " + std::to_string(j) +
                     " <= 0 (inverted element)";
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
    for (unsigned int a = 0; a < patches.size(); ++a)
      if (patches[a].volume > 0.)
        j_bar[a] /= patches[a].volume;

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
            const unsigned int a  = c.vertex[v];
            double             sc = 1.;
            const Tensor<2, 3> F_bar =
              fbar_deformation(F, j_bar[a], finite, &sc);
            const Tensor<2, 3> &N = finite ? F : I;
            const double        D = finite ? j_bar[a] : 1.;
            const std::size_t   k = std::size_t(e) * 4 + v;
            if (shared && v > 0)
              {
                double p_a;
                material.kirchhoff_pressure(j_bar[a], p_a);
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
            const double p = sc * scalar_product(P, N) / 3.;
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

    // 3. patch terms: S_a b with b = d j_a / du on all DoFs of the patch
    for (unsigned int a = 0; a < patches.size(); ++a)
      {
        const Patch &patch = patches[a];
        if (!patch.touched)
          continue;
        const unsigned int n = patch.dofs.size();
        patch_work.assign(n, 0.);
        const double *c = &slot_weight[slot_start[a]];
        for (unsigned int slot = 0; slot < patch.cells.size(); ++slot)
          {
            const std::array<double, 12>       &dj = cell_dj[patch.cells[slot]];
            const std::array<unsigned int, 12> &position = patch.position[slot];
            for (unsigned int i = 0; i < 12; ++i)
              patch_work[position[i]] += c[slot] * dj[i];
          }
        for (unsigned int i = 0; i < n; ++i)
          residual.add(patch.dofs[i], S[a] * patch_work[i]);
      }
    return "";
  }
} // namespace densify
