// The barrier against crushed cells of the nodal-averaged F-bar.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

namespace densify
{
  /**
   * The barrier that stops a cell's own volume ratio J_e = V/V0 from
   * leaving [limit, 1/limit] (Mesh/Cell volume barrier; doc/theory.md,
   * "The cells' own volume"). Inside the band the cell is untouched; beyond
   * it the cell stores the energy
   *
   *   V0 k / 2 (ln J_e - ln J_lim)^2,   J_lim = limit or 1/limit,
   *
   * with k the material's bulk modulus, so the excess volume change meets
   * the stiffness of a plain element. Its forces are V0 k e d(ln J_e)/du with
   * e = excess(ln J_e) and its tangent V0 k (t t^T - e h_i[c_j] h_j[c_i]),
   * t = d(ln J_e)/du, h_i = F^{-T} grad N_i (NodalAveraging, both methods;
   * LumpedMass::stiffness_product for the stable step). Finite-strain
   * materials only: a small-strain law is not meant for such volume changes.
   * A metal's elastic volume change under the pressures of compaction is
   * below a per cent and its plastic flow keeps the volume, so a cell beyond
   * the band is an artefact of the element, and the barrier leaves every
   * cell inside it alone: the answer changes only where cells would crush.
   */
  struct CellVolumeBarrier
  {
    /// ln of the smallest free volume ratio (< 0); -infinity: off.
    double log_limit = -std::numeric_limits<double>::infinity();
    /// The stiffness k (MPa) per material id; 0: the material has no
    /// barrier (small strain).
    std::vector<double> stiffness;

    /// True if some material has a barrier.
    bool
    on() const
    {
      for (const double k : stiffness)
        if (k > 0.)
          return true;
      return false;
    }

    /// The excess e of @p log_j beyond the band [log_limit, -log_limit],
    /// 0 inside it.
    double
    excess(const double log_j) const
    {
      if (log_j < log_limit)
        return log_j - log_limit;
      if (log_j > -log_limit)
        return log_j + log_limit;
      return 0.;
    }

    /// The stiffness k of material id @p material (0 if none).
    double
    modulus(const unsigned int material) const
    {
      return material < stiffness.size() ? stiffness[material] : 0.;
    }
  };
} // namespace densify
