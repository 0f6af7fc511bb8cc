// J2Plasticity::kirchhoff_deviators(): the series path of
// kirchhoff_deviator() for four points side by side in SIMD lanes (GCC's
// vector extension; deal.II's VectorizedArray is one lane wide in a build
// without vector instructions), for the explicit force kernel.
#include <densify/material/j2_plasticity.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace densify
{
  namespace
  {
    /// Points evaluated side by side.
    constexpr unsigned int n_lanes = 4;
    /// One double per lane; arithmetic acts lane by lane (without vector
    /// instructions of that width the compiler splits it into narrower
    /// ones).
    using Lanes = double __attribute__((vector_size(n_lanes * sizeof(double))));
    /// A symmetric 3x3 matrix per lane as its entries 00, 11, 22, 01, 02, 12.
    using SymLanes = std::array<Lanes, 6>;

    /// The lanes @p x (built whole: writing single lanes of a vector in
    /// memory and reading it back stalls the store forwarding).
    __attribute__((always_inline)) inline Lanes
    lanes(const double (&x)[n_lanes])
    {
      static_assert(n_lanes == 4, "lanes() lists four values");
      return Lanes{x[0], x[1], x[2], x[3]};
    }

    /// C = A B for commuting symmetric A and B (polynomials in one matrix;
    /// then the product is symmetric), lane by lane.
    __attribute__((always_inline)) inline void
    commuting_product(const SymLanes &A, const SymLanes &B, SymLanes &C)
    {
      C[0] = A[0] * B[0] + A[3] * B[3] + A[4] * B[4];
      C[1] = A[3] * B[3] + A[1] * B[1] + A[5] * B[5];
      C[2] = A[4] * B[4] + A[5] * B[5] + A[2] * B[2];
      C[3] = A[0] * B[3] + A[3] * B[1] + A[4] * B[5];
      C[4] = A[0] * B[4] + A[3] * B[5] + A[4] * B[2];
      C[5] = A[3] * B[4] + A[1] * B[5] + A[5] * B[2];
    }

    /// The squared Frobenius norm, lane by lane.
    __attribute__((always_inline)) inline void
    frobenius_squared(const SymLanes &A, Lanes &result)
    {
      result = A[0] * A[0] + A[1] * A[1] + A[2] * A[2] +
               2. * (A[3] * A[3] + A[4] * A[4] + A[5] * A[5]);
    }

    /// The number of terms kirchhoff_deviator()'s series of ln(I + E) takes
    /// for a matrix of Frobenius norm @p rho (<= 0.1).
    unsigned int
    log_terms(const double rho)
    {
      unsigned int n = 1;
      for (double t = rho; t / (n + 1) > 1e-17; t *= rho)
        ++n;
      return n;
    }

    /// The number of terms its series of exp(M) takes for a matrix of
    /// Frobenius norm @p rho (<= 0.1).
    unsigned int
    exp_terms(const double rho)
    {
      unsigned int n    = 1;
      double       term = rho;
      while (term * rho / (n + 1) > 1e-17)
        {
          ++n;
          term *= rho / n;
        }
      return n;
    }

    /// L = ln(I + E) by its power series with @p n terms in Horner form.
    __attribute__((always_inline)) inline void
    log_series(const SymLanes &E, const unsigned int n, SymLanes &L)
    {
      const auto coefficient = [](const unsigned int k) {
        return (k % 2 == 1 ? 1. : -1.) / k;
      };
      SymLanes P, Q;
      for (unsigned int d = 0; d < 6; ++d)
        P[d] = Lanes{} + (d < 3 ? coefficient(n) : 0.);
      for (unsigned int k = n - 1; k >= 1; --k)
        {
          commuting_product(E, P, Q);
          for (unsigned int d = 0; d < 3; ++d)
            Q[d] += coefficient(k);
          P = Q;
        }
      commuting_product(E, P, L);
    }

    /// X = exp(M) by its power series with @p n terms in Horner form.
    __attribute__((always_inline)) inline void
    exp_series(const SymLanes &M, const unsigned int n, SymLanes &X)
    {
      SymLanes Q;
      for (unsigned int d = 0; d < 6; ++d)
        X[d] = Lanes{} + (d < 3 ? 1. : 0.);
      for (unsigned int k = n; k >= 1; --k)
        {
          commuting_product(M, X, Q);
          for (unsigned int d = 0; d < 6; ++d)
            X[d] = Q[d] / double(k) + (d < 3 ? 1. : 0.);
        }
    }
  } // namespace



  bool
  J2Plasticity::kirchhoff_deviators(const unsigned int            n,
                                    const Tensor<2, 3> *const    *F_of,
                                    const MaterialState *const   *committed,
                                    MaterialState *const         *trial,
                                    SymmetricTensor<2, 3> *const *tau_dev) const
  {
    deviators_in_lanes(n, F_of, committed, trial, tau_dev);
    return true;
  }



  // compiled twice, for AVX2 (four lanes in one register) and without,
  // and chosen at the first call by the CPU found (GCC's function
  // multiversioning; the same operations, so the same results)
  __attribute__((target_clones("avx2", "default"))) void
  J2Plasticity::deviators_in_lanes(const unsigned int            n,
                                   const Tensor<2, 3> *const    *F_of,
                                   const MaterialState *const   *committed,
                                   MaterialState *const         *trial,
                                   SymmetricTensor<2, 3> *const *tau_dev) const
  {
    static const J2State   virgin;
    constexpr unsigned int row[6] = {0, 1, 2, 0, 0, 1},
                           col[6] = {0, 1, 2, 1, 2, 2};
    for (unsigned int first = 0; first < n; first += n_lanes)
      {
        const unsigned int m = std::min(n_lanes, n - first);
        // the lanes' points (the last one repeated into unused lanes)
        const J2State      *old[n_lanes];
        const Tensor<2, 3> *F_l[n_lanes];
        for (unsigned int l = 0; l < n_lanes; ++l)
          {
            const unsigned int k = first + std::min(l, m - 1);
            old[l] = committed && committed[k] ? committed[k] : &virgin;
            F_l[l] = F_of[k];
          }
        Lanes F[3][3], C[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              F[i][j] = Lanes{(*F_l[0])[i][j],
                              (*F_l[1])[i][j],
                              (*F_l[2])[i][j],
                              (*F_l[3])[i][j]};
              C[i][j] = Lanes{old[0]->Cp_inv[i][j],
                              old[1]->Cp_inv[i][j],
                              old[2]->Cp_inv[i][j],
                              old[3]->Cp_inv[i][j]};
            }

        // the trial be = F Cp^{-1} F^T (symmetrised), its determinant d and
        // bbar = I + E = be / d^(1/3), as kirchhoff_deviator()
        Lanes G[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            G[i][j] = F[i][0] * C[0][j] + F[i][1] * C[1][j] + F[i][2] * C[2][j];
        const auto entry = [&](const unsigned int i, const unsigned int j) {
          return G[i][0] * F[j][0] + G[i][1] * F[j][1] + G[i][2] * F[j][2];
        };
        SymLanes    be = {{entry(0, 0),
                           entry(1, 1),
                           entry(2, 2),
                           0.5 * (entry(0, 1) + entry(1, 0)),
                           0.5 * (entry(0, 2) + entry(2, 0)),
                           0.5 * (entry(1, 2) + entry(2, 1))}};
        const Lanes J  = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                        F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                        F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
        const Lanes d = be[0] * (be[1] * be[2] - be[5] * be[5]) -
                        be[3] * (be[3] * be[2] - be[5] * be[4]) +
                        be[4] * (be[3] * be[5] - be[1] * be[4]);
        double scale_l[n_lanes];
        for (unsigned int l = 0; l < n_lanes; ++l)
          scale_l[l] = d[l] > 0. ? std::cbrt(d[l]) : 1.;
        const Lanes scale = lanes(scale_l);
        SymLanes    E;
        for (unsigned int k = 0; k < 6; ++k)
          E[k] = be[k] / scale - (k < 3 ? 1. : 0.);
        Lanes rho2;
        frobenius_squared(E, rho2);
        // lanes whose trial state the series does not cover (or that fail)
        // take the point-by-point path; their series here runs on E = 0
        bool         spectral[n_lanes];
        double       keep[n_lanes];
        unsigned int terms = 1;
        for (unsigned int l = 0; l < n_lanes; ++l)
          {
            const double rho = std::sqrt(rho2[l]);
            spectral[l]      = !(J[l] > 0.) || !(d[l] > 0.) || !(rho <= 0.1);
            keep[l]          = spectral[l] ? 0. : 1.;
            if (!spectral[l])
              terms = std::max(terms, log_terms(rho));
          }
        const Lanes keep_lanes = lanes(keep);
        for (unsigned int k = 0; k < 6; ++k)
          E[k] *= keep_lanes;

        // s_trial = 2 mu dev(1/2 ln bbar), its von Mises value, the return
        SymLanes L;
        log_series(E, terms, L);
        const Lanes tr_L = (L[0] + L[1] + L[2]) / 3.;
        for (unsigned int k = 0; k < 3; ++k)
          L[k] -= tr_L;
        Lanes s_norm2;
        frobenius_squared(L, s_norm2);
        s_norm2 *= mu * mu;
        double       factor_l[n_lanes], dg[n_lanes];
        bool         plastic[n_lanes], any_plastic = false;
        unsigned int plastic_terms = 1;
        for (unsigned int l = 0; l < n_lanes; ++l)
          {
            const double q_trial = std::sqrt(1.5 * s_norm2[l]);
            const double sy_old  = yield_stress(old[l]->eps_p);
            plastic[l]           = !spectral[l] && l < m &&
                         (q_trial - sy_old > 1e-10 * sy_old + 1e-14 * mu);
            dg[l]       = 0.;
            factor_l[l] = 1.;
            if (!plastic[l])
              continue;
            any_plastic = true;
            dg[l]       = plastic_increment(q_trial, old[l]->eps_p);
            factor_l[l] = 1. - 3. * mu * dg[l] / q_trial;
          }
        const Lanes factor    = lanes(factor_l);
        const Lanes tau_scale = factor * mu;
        for (unsigned int l = 0; l < m; ++l)
          if (!spectral[l])
            for (unsigned int k = 0; k < 6; ++k)
              (*tau_dev[first + l])[row[k]][col[k]] = tau_scale[l] * L[k][l];

        // the updated state of the plastic lanes: be = d^(1/3) (I + E)
        // exp(-tr L / 3) exp((factor - 1) dev L), Cp^{-1} = F^{-1} be F^{-T}
        if (trial && any_plastic)
          {
            SymLanes M;
            for (unsigned int k = 0; k < 6; ++k)
              M[k] = (factor - 1.) * L[k];
            Lanes norm_L;
            frobenius_squared(L, norm_L);
            for (unsigned int l = 0; l < n_lanes; ++l)
              if (plastic[l])
                plastic_terms = std::max(plastic_terms,
                                         exp_terms(std::abs(factor[l] - 1.) *
                                                   std::sqrt(norm_L[l])));
            SymLanes X, bbar = E, b;
            exp_series(M, plastic_terms, X);
            for (unsigned int k = 0; k < 3; ++k)
              bbar[k] += 1.;
            commuting_product(bbar, X, b);
            double volumetric[n_lanes], J_inv_l[n_lanes];
            for (unsigned int l = 0; l < n_lanes; ++l)
              {
                volumetric[l] =
                  plastic[l] ? scale_l[l] * std::exp(-tr_L[l]) : 1.;
                J_inv_l[l] = J[l] > 0. ? 1. / J[l] : 0.;
              }
            const Lanes volumetric_lanes = lanes(volumetric);
            for (unsigned int k = 0; k < 6; ++k)
              b[k] *= volumetric_lanes;
            // F^{-1} by cofactors
            Lanes       Finv[3][3];
            const Lanes J_inv = lanes(J_inv_l);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                {
                  const unsigned int j1 = (j + 1) % 3, j2 = (j + 2) % 3,
                                     i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                  Finv[i][j] =
                    (F[j1][i1] * F[j2][i2] - F[j1][i2] * F[j2][i1]) * J_inv;
                }
            constexpr unsigned int index[3][3] = {{0, 3, 4},
                                                  {3, 1, 5},
                                                  {4, 5, 2}};
            Lanes                  FB[3][3]; // F^{-1} be
            for (unsigned int I = 0; I < 3; ++I)
              for (unsigned int j = 0; j < 3; ++j)
                FB[I][j] = Finv[I][0] * b[index[0][j]] +
                           Finv[I][1] * b[index[1][j]] +
                           Finv[I][2] * b[index[2][j]];
            Lanes Cp[6];
            for (unsigned int k = 0; k < 6; ++k)
              Cp[k] = FB[row[k]][0] * Finv[col[k]][0] +
                      FB[row[k]][1] * Finv[col[k]][1] +
                      FB[row[k]][2] * Finv[col[k]][2];
            for (unsigned int l = 0; l < m; ++l)
              if (plastic[l])
                {
                  J2State &now = *trial[first + l];
                  for (unsigned int k = 0; k < 6; ++k)
                    {
                      now.Cp_inv[row[k]][col[k]] = Cp[k][l];
                      now.Cp_inv[col[k]][row[k]] = Cp[k][l];
                    }
                  now.eps_p = old[l]->eps_p + dg[l];
                }
          }
        for (unsigned int l = 0; l < m; ++l)
          if (spectral[l])
            kirchhoff_deviator(*F_of[first + l],
                               old[l] == &virgin ? nullptr : old[l],
                               trial ? trial[first + l] : nullptr,
                               *tau_dev[first + l]);
          else if (trial && !plastic[l] && trial[first + l] != old[l])
            *trial[first + l] = *old[l];
      }
  }
} // namespace densify
