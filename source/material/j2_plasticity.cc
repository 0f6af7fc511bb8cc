// Finite-strain J2 plasticity: return mapping and consistent tangent.
#include <deal.II/base/symmetric_tensor.h>

#include <densify/material/j2_plasticity.h>
#include <densify/material/symmetric_eigen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace densify
{
  namespace
  {
    /// A symmetric 3x3 matrix as its entries 00, 11, 22, 01, 02, 12.
    using Sym = std::array<double, 6>;

    /// The product A B of two commuting symmetric matrices (polynomials in
    /// one matrix), which is symmetric.
    inline Sym
    commuting_product(const Sym &A, const Sym &B)
    {
      return {{A[0] * B[0] + A[3] * B[3] + A[4] * B[4],
               A[3] * B[3] + A[1] * B[1] + A[5] * B[5],
               A[4] * B[4] + A[5] * B[5] + A[2] * B[2],
               A[0] * B[3] + A[3] * B[1] + A[4] * B[5],
               A[0] * B[4] + A[3] * B[5] + A[4] * B[2],
               A[3] * B[4] + A[1] * B[5] + A[5] * B[2]}};
    }

    /// ln(I + E) for a symmetric E whose Frobenius norm @p rho (a bound of
    /// its eigenvalues) is at most 0.1: the power series sum_k (-1)^(k+1)
    /// E^k / k, cut where the rest is below 1e-17 of the first term, in
    /// Horner form.
    Sym
    log_series(const Sym &E, const double rho)
    {
      unsigned int n = 1;
      for (double t = rho; t / (n + 1) > 1e-17; t *= rho)
        ++n;
      const auto coefficient = [](const unsigned int k) {
        return (k % 2 == 1 ? 1. : -1.) / k;
      };
      Sym P = {{coefficient(n), coefficient(n), coefficient(n), 0., 0., 0.}};
      for (unsigned int k = n - 1; k >= 1; --k)
        {
          P = commuting_product(E, P);
          for (unsigned int d = 0; d < 3; ++d)
            P[d] += coefficient(k);
        }
      return commuting_product(E, P);
    }

    /// exp(M) for a symmetric M of Frobenius norm @p rho at most 0.1: the
    /// power series cut where the rest is below 1e-17, in Horner form.
    Sym
    exp_series(const Sym &M, const double rho)
    {
      unsigned int n    = 1;
      double       term = rho; // rho^n / n!
      while (term * rho / (n + 1) > 1e-17)
        {
          ++n;
          term *= rho / n;
        }
      Sym P = {{1., 1., 1., 0., 0., 0.}};
      for (unsigned int k = n; k >= 1; --k)
        {
          P = commuting_product(M, P);
          for (unsigned int d = 0; d < 6; ++d)
            P[d] /= k;
          for (unsigned int d = 0; d < 3; ++d)
            P[d] += 1.;
        }
      return P;
    }

    /// The Frobenius norm of a symmetric matrix.
    double
    frobenius(const Sym &A)
    {
      return std::sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2] +
                       2. * (A[3] * A[3] + A[4] * A[4] + A[5] * A[5]));
    }

    /// z / (exp(z) - 1), accurate also for z -> 0 (where it is 1).
    double
    z_over_expm1(const double z)
    {
      if (std::abs(z) < 1e-3)
        return 1. - z / 2. + z * z / 12. - z * z * z * z / 720.;
      return z / std::expm1(z);
    }
  } // namespace



  std::string
  hardening_name(const Hardening hardening)
  {
    switch (hardening)
      {
        case Hardening::none:
          return "perfectly plastic";
        case Hardening::linear:
          return "linear hardening";
        case Hardening::power_law:
          return "power-law hardening";
      }
    return "unknown hardening";
  }



  J2Parameters
  material_preset(const MaterialPreset &preset)
  {
    J2Parameters p;
    p.E         = preset.E;
    p.nu        = preset.nu;
    p.sigma0    = preset.sigma0;
    p.density   = preset.density;
    p.hardening = Hardening::none;
    p.label     = preset.name;
    return p;
  }



  J2Parameters
  material_preset(const std::string &name)
  {
    if (const MaterialPreset *preset = find_material_preset(name))
      return material_preset(*preset);
    if (name == custom_material_name)
      throw std::invalid_argument(
        "material 'custom' has no preset: give E, nu and sigma0 explicitly");
    throw std::invalid_argument("unknown material '" + name + "': use one of " +
                                material_names());
  }



  J2Plasticity::J2Plasticity(const J2Parameters &parameters)
    : parameters(parameters)
    , kappa(parameters.E / (3. * (1. - 2. * parameters.nu)))
    , mu(parameters.E / (2. * (1. + parameters.nu)))
  {
    const auto fail = [&](const std::string &what) {
      throw std::invalid_argument("J2 plasticity (" + parameters.label +
                                  "): " + what);
    };
    if (!(parameters.E > 0.))
      fail("Young's modulus E must be > 0");
    if (!(parameters.nu > -1. && parameters.nu < 0.5))
      fail("Poisson's ratio must lie in (-1, 0.5)");
    if (!(parameters.sigma0 >= 0.))
      fail("yield stress sigma0 must be >= 0");
    if (parameters.hardening == Hardening::none && !(parameters.sigma0 > 0.))
      fail("yield stress sigma0 must be > 0 without hardening");
    if (parameters.hardening == Hardening::linear && !(parameters.H >= 0.))
      fail("hardening modulus H must be >= 0");
    if (parameters.hardening == Hardening::power_law &&
        !(parameters.K >= 0. && parameters.n > 0.))
      fail("power-law hardening needs K >= 0 and n > 0");
  }



  std::string
  J2Plasticity::name() const
  {
    if (!std::isfinite(parameters.sigma0))
      return "Hencky hyperelastic, finite strain (" + parameters.label + ")";
    return "J2 finite strain (" + parameters.label + ", " +
           hardening_name(parameters.hardening) + ")";
  }



  double
  J2Plasticity::yield_stress(const double eps_p) const
  {
    const double e = std::max(eps_p, 0.);
    switch (parameters.hardening)
      {
        case Hardening::none:
          return parameters.sigma0;
        case Hardening::linear:
          return parameters.sigma0 + parameters.H * e;
        case Hardening::power_law:
          return parameters.sigma0 + parameters.K * std::pow(e, parameters.n);
      }
    return parameters.sigma0;
  }



  double
  J2Plasticity::plastic_work(const MaterialState &state) const
  {
    // int_0^e sigma_y: isotropic hardening, so the Kirchhoff stress power
    // tau : d_p per reference volume is sigma_y d(eps_p)
    const double e = std::max(state.eps_p, 0.);
    switch (parameters.hardening)
      {
        case Hardening::none:
          return parameters.sigma0 * e;
        case Hardening::linear:
          return parameters.sigma0 * e + 0.5 * parameters.H * e * e;
        case Hardening::power_law:
          return parameters.sigma0 * e + parameters.K *
                                           std::pow(e, parameters.n + 1.) /
                                           (parameters.n + 1.);
      }
    return parameters.sigma0 * e;
  }



  double
  J2Plasticity::hardening_modulus(const double eps_p) const
  {
    switch (parameters.hardening)
      {
        case Hardening::none:
          return 0.;
        case Hardening::linear:
          return parameters.H;
        case Hardening::power_law:
          {
            const double e = std::max(eps_p, 1e-12);
            return parameters.n * parameters.K * std::pow(e, parameters.n - 1.);
          }
      }
    return 0.;
  }



  double
  J2Plasticity::plastic_increment(const double q_trial,
                                  const double eps_p_old) const
  {
    switch (parameters.hardening)
      {
        case Hardening::none:
          return (q_trial - parameters.sigma0) / (3. * mu);
        case Hardening::linear:
          return (q_trial - yield_stress(eps_p_old)) / (3. * mu + parameters.H);
        case Hardening::power_law:
          break;
      }

    // Power law: r(dg) = q_trial - 3 mu dg - sigma_y(eps_p_old + dg) = 0.
    // r is strictly decreasing, r(0) > 0 and r(hi) <= 0 since
    // sigma_y >= sigma0; Newton safeguarded by bisection on [lo, hi].
    double lo = 0., hi = (q_trial - parameters.sigma0) / (3. * mu);
    double dg = 0.;
    for (unsigned int it = 0; it < 200; ++it)
      {
        const double r = q_trial - 3. * mu * dg - yield_stress(eps_p_old + dg);
        if (std::abs(r) <= 1e-13 * q_trial)
          return dg;
        if (r > 0.)
          lo = dg;
        else
          hi = dg;
        if (hi - lo <= 1e-15 * hi)
          return dg;
        double next = dg + r / (3. * mu + hardening_modulus(eps_p_old + dg));
        if (!(next > lo && next <= hi))
          next = 0.5 * (lo + hi);
        dg = next;
      }
    throw std::runtime_error("J2 plasticity (" + parameters.label +
                             "): power-law return mapping did not converge");
  }



  void
  J2Plasticity::evaluate(const Tensor<2, 3>  &F,
                         const MaterialState *committed,
                         MaterialState       *trial,
                         Tensor<2, 3>        &P,
                         Tensor<4, 3>        &A) const
  {
    compute(F, committed, trial, P, &A);
  }



  void
  J2Plasticity::stress(const Tensor<2, 3>  &F,
                       const MaterialState *committed,
                       MaterialState       *trial,
                       Tensor<2, 3>        &P) const
  {
    compute(F, committed, trial, P, nullptr);
  }



  J2Plasticity::TrialReturn
  J2Plasticity::trial_return(const Tensor<2, 3>  &F,
                             const MaterialState *committed) const
  {
    const double J = determinant(F);
    if (!(J > 0.))
      throw std::domain_error("J2 plasticity: det F = " + std::to_string(J) +
                              " <= 0 (inverted element)");

    static const J2State virgin;
    TrialReturn          r;
    r.old = committed ? committed : &virgin;

    // Trial elastic left Cauchy-Green tensor be_tr = F Cp^{-1} F^T and its
    // spectral decomposition be_tr = sum_a x_a n_a (x) n_a in closed form
    // (symmetric_eigen.h): orthonormal eigenvectors also for equal
    // eigenvalues (be = I at rest); off-diagonal entries below 1e-20 of the
    // diagonal are taken as zero, which changes the stress by less than
    // 1e-20 E, far below the law's own round-off (the logarithmic strain of
    // a stretch resolves 1e-16) and keeps gradients down to 1e-300 exact
    // (tests/material_j2_near_identity.cc, tests/symmetric_eigen.cc)
    r.G = F * r.old->Cp_inv;
    {
      double be[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          {
            be[i][j] =
              r.G[i][0] * F[j][0] + r.G[i][1] * F[j][1] + r.G[i][2] * F[j][2];
            if (j > i)
              {
                // symmetrised as deal.II's symmetrize() does
                const double other = r.G[j][0] * F[i][0] + r.G[j][1] * F[i][1] +
                                     r.G[j][2] * F[i][2];
                be[i][j] = 0.5 * (be[i][j] + other);
                be[j][i] = be[i][j];
              }
          }
      symmetric_eigen(be, r.x, r.Q);
    }
    for (unsigned int a = 0; a < 3; ++a)
      {
        if (!(r.x[a] > 0.))
          throw std::domain_error("J2 plasticity: be is not positive "
                                  "definite (extreme distortion)");
        r.eps[a] = 0.5 * std::log(r.x[a]);
      }

    // Trial Kirchhoff stress in principal logarithmic space.
    r.tr_eps = r.eps[0] + r.eps[1] + r.eps[2];
    for (unsigned int a = 0; a < 3; ++a)
      {
        r.e_dev[a]   = r.eps[a] - r.tr_eps / 3.;
        r.s_trial[a] = 2. * mu * r.e_dev[a];
        r.s_norm2 += r.s_trial[a] * r.s_trial[a];
      }
    r.q_trial           = std::sqrt(1.5 * r.s_norm2);
    const double sy_old = yield_stress(r.old->eps_p);
    r.plastic           = (r.q_trial - sy_old > 1e-10 * sy_old + 1e-14 * mu);

    // Radial return: s = (1 - 3 mu dg / q_trial) s_trial.
    if (r.plastic)
      {
        r.dg     = plastic_increment(r.q_trial, r.old->eps_p);
        r.factor = 1. - 3. * mu * r.dg / r.q_trial;
      }
    return r;
  }



  void
  J2Plasticity::update_state(const Tensor<2, 3> &F,
                             const TrialReturn  &r,
                             MaterialState      &trial) const
  {
    if (!r.plastic)
      {
        trial = *r.old;
        return;
      }
    // Cp^{-1} = F^{-1} be F^{-T} with be = sum_a exp(2 eps_e_a) n_a (x) n_a
    const Tensor<2, 3> Finv = invert(F);
    double             V[3][3]; // V[a] = F^{-1} n_a
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int I = 0; I < 3; ++I)
        V[a][I] = Finv[I][0] * r.Q[0][a] + Finv[I][1] * r.Q[1][a] +
                  Finv[I][2] * r.Q[2][a];
    double be_a[3];
    for (unsigned int a = 0; a < 3; ++a)
      be_a[a] = std::exp(2. * (r.tr_eps / 3. + r.factor * r.e_dev[a]));
    for (unsigned int I = 0; I < 3; ++I)
      for (unsigned int J_ = I; J_ < 3; ++J_)
        {
          const double c = be_a[0] * V[0][I] * V[0][J_] +
                           be_a[1] * V[1][I] * V[1][J_] +
                           be_a[2] * V[2][I] * V[2][J_];
          trial.Cp_inv[I][J_] = c;
          trial.Cp_inv[J_][I] = c;
        }
    trial.eps_p = r.old->eps_p + r.dg;
  }



  bool
  J2Plasticity::kirchhoff_deviator(const Tensor<2, 3>    &F,
                                   const MaterialState   *committed,
                                   MaterialState         *trial,
                                   SymmetricTensor<2, 3> &tau_dev) const
  {
    // The same law as compute() without the spectral decomposition where
    // the trial state allows: with be_tr = F Cp^{-1} F^T = d^(1/3) bbar
    // (d = det be_tr), the deviatoric Hencky strain is 1/2 dev ln bbar and
    // bbar = I + E is close to I wherever the law yields (its elastic
    // deviatoric strain is about sigma_y / 2 mu). ln(I + E) and the
    // exponential of the returned strain are power series then; trial
    // states with |E| > 0.1 take the spectral path (compute()).
    const double J = determinant(F);
    if (!(J > 0.))
      throw std::domain_error("J2 plasticity: det F = " + std::to_string(J) +
                              " <= 0 (inverted element)");
    static const J2State virgin;
    const J2State       &old = committed ? *committed : virgin;
    const Tensor<2, 3>   G   = F * old.Cp_inv;
    Sym                  be;
    {
      const auto entry = [&](const unsigned int i, const unsigned int j) {
        return G[i][0] * F[j][0] + G[i][1] * F[j][1] + G[i][2] * F[j][2];
      };
      be = {{entry(0, 0),
             entry(1, 1),
             entry(2, 2),
             0.5 * (entry(0, 1) + entry(1, 0)),
             0.5 * (entry(0, 2) + entry(2, 0)),
             0.5 * (entry(1, 2) + entry(2, 1))}};
    }
    const double d = be[0] * (be[1] * be[2] - be[5] * be[5]) -
                     be[3] * (be[3] * be[2] - be[5] * be[4]) +
                     be[4] * (be[3] * be[5] - be[1] * be[4]);
    const double scale = d > 0. ? std::cbrt(d) : 0.;
    Sym          E;
    for (unsigned int k = 0; k < 6; ++k)
      E[k] = be[k] / scale - (k < 3 ? 1. : 0.);
    const double rho = frobenius(E);
    if (!(d > 0.) || !(rho <= 0.1))
      {
        // the spectral path
        const TrialReturn r = trial_return(F, committed);
        double            s[3];
        for (unsigned int a = 0; a < 3; ++a)
          s[a] = r.factor * r.s_trial[a];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            tau_dev[i][j] = s[0] * r.Q[i][0] * r.Q[j][0] +
                            s[1] * r.Q[i][1] * r.Q[j][1] +
                            s[2] * r.Q[i][2] * r.Q[j][2];
        if (trial)
          update_state(F, r, *trial);
        return true;
      }

    // s_trial = 2 mu dev(1/2 ln bbar)
    Sym          L       = log_series(E, rho);
    const double tr_L    = (L[0] + L[1] + L[2]) / 3.;
    double       s_norm2 = 0.;
    for (unsigned int k = 0; k < 6; ++k)
      {
        if (k < 3)
          L[k] -= tr_L;
        s_norm2 += (k < 3 ? 1. : 2.) * mu * mu * L[k] * L[k];
      }
    const double q_trial = std::sqrt(1.5 * s_norm2);
    const double sy_old  = yield_stress(old.eps_p);
    const bool   plastic = (q_trial - sy_old > 1e-10 * sy_old + 1e-14 * mu);
    double       dg = 0., factor = 1.;
    if (plastic)
      {
        dg     = plastic_increment(q_trial, old.eps_p);
        factor = 1. - 3. * mu * dg / q_trial;
      }
    const unsigned int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
    for (unsigned int k = 0; k < 6; ++k)
      tau_dev[row[k]][col[k]] = factor * mu * L[k];

    if (trial)
      {
        if (!plastic)
          *trial = old;
        else
          {
            // be = d^(1/3) exp(2 eps_e_dev), 2 eps_e_dev = factor dev L,
            // = d^(1/3) (I + E) exp(-tr L / 3) exp((factor - 1) dev L)
            // (all are functions of E and commute): the last exponential
            // is that of the step's plastic strain, a few terms;
            // Cp^{-1} = F^{-1} be F^{-T}
            Sym M;
            for (unsigned int k = 0; k < 6; ++k)
              M[k] = (factor - 1.) * L[k];
            Sym bbar = E;
            for (unsigned int k = 0; k < 3; ++k)
              bbar[k] += 1.;
            Sym b = commuting_product(
              bbar, exp_series(M, std::abs(factor - 1.) * frobenius(L)));
            const double volumetric = scale * std::exp(-tr_L);
            for (unsigned int k = 0; k < 6; ++k)
              b[k] *= volumetric;
            // entry (i, j) of a Sym
            constexpr unsigned int index[3][3] = {{0, 3, 4},
                                                  {3, 1, 5},
                                                  {4, 5, 2}};
            const Tensor<2, 3>     Finv        = invert(F);
            double                 FB[3][3]; // F^{-1} be
            for (unsigned int I = 0; I < 3; ++I)
              for (unsigned int j = 0; j < 3; ++j)
                FB[I][j] = Finv[I][0] * b[index[0][j]] +
                           Finv[I][1] * b[index[1][j]] +
                           Finv[I][2] * b[index[2][j]];
            for (unsigned int I = 0; I < 3; ++I)
              for (unsigned int J_ = I; J_ < 3; ++J_)
                {
                  const double c = FB[I][0] * Finv[J_][0] +
                                   FB[I][1] * Finv[J_][1] +
                                   FB[I][2] * Finv[J_][2];
                  trial->Cp_inv[I][J_] = c;
                  trial->Cp_inv[J_][I] = c;
                }
            trial->eps_p = old.eps_p + dg;
          }
      }
    return true;
  }



  void
  J2Plasticity::compute(const Tensor<2, 3>  &F,
                        const MaterialState *committed,
                        MaterialState       *trial,
                        Tensor<2, 3>        &P,
                        Tensor<4, 3>        *A) const
  {
    const TrialReturn   r    = trial_return(F, committed);
    const Tensor<2, 3>  Finv = invert(F);
    const Tensor<2, 3> &G    = r.G;
    const double(&x)[3]      = r.x;
    const double(&eps)[3]    = r.eps;
    const double(&Q)[3][3]   = r.Q;
    const double factor      = r.factor;
    const double p           = kappa * r.tr_eps;

    // D is the principal (3x3) consistent tangent d tau_a / d eps_trial_c.
    double D[3][3];
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 3; ++c)
        D[a][c] = kappa + 2. * mu * ((a == c) - 1. / 3.);
    if (r.plastic)
      {
        const double Hp = hardening_modulus(r.old->eps_p + r.dg);
        const double beta =
          6. * mu * mu * (r.dg / r.q_trial - 1. / (3. * mu + Hp));
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            D[a][c] = kappa + 2. * mu * factor * ((a == c) - 1. / 3.) +
                      beta * r.s_trial[a] * r.s_trial[c] / r.s_norm2;
      }
    const double mu_bar = mu * factor;

    double tau[3];
    for (unsigned int a = 0; a < 3; ++a)
      tau[a] = p + factor * r.s_trial[a];

    // V = Q^T F^{-T}, U = Cp^{-1} F^T Q = G^T Q.
    double V[3][3], U[3][3];
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int J_ = 0; J_ < 3; ++J_)
        {
          double v = 0., u = 0.;
          for (unsigned int j = 0; j < 3; ++j)
            {
              v += Q[j][a] * Finv[J_][j];
              u += G[j][J_] * Q[j][a];
            }
          V[a][J_] = v;
          U[J_][a] = u;
        }

    // P = tau F^{-T} = sum_a tau_a n_a (x) (F^{-1} n_a).
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J_ = 0; J_ < 3; ++J_)
        P[i][J_] = tau[0] * Q[i][0] * V[0][J_] + tau[1] * Q[i][1] * V[1][J_] +
                   tau[2] * Q[i][2] * V[2][J_];

    // the tangent only where it is asked for (not for a residual alone)
    if (A != nullptr)
      {
        // Derivative of the isotropic function tau(be_tr) in the principal
        // basis: d tau'_aa = sum_c D_ac / (2 x_c) d be'_cc and, for a != b,
        // d tau'_ab = theta_ab d be'_ab with theta_ab = (tau_a - tau_b) /
        // (x_a - x_b) = 2 mu_bar (eps_a - eps_b) / (x_a - x_b), evaluated
        // without cancellation (limit mu_bar / x_b for equal stretches).
        // With d be' = Q^T (dF G^T + G dF^T) Q the six distinct derivatives
        // T^{ab}_kL = d tau'_ab / dF_kL are assembled, then
        // A_iJkL = sum_ab Q_ia V_bJ T^{ab}_kL - P_iL F^{-1}_Jk.
        constexpr unsigned int pair_a[6] = {0, 1, 2, 0, 0, 1};
        constexpr unsigned int pair_b[6] = {0, 1, 2, 1, 2, 2};
        double                 T[6][3][3], W[6][3][3];
        for (unsigned int m = 0; m < 6; ++m)
          {
            const unsigned int a = pair_a[m], b = pair_b[m];
            if (a == b)
              {
                double c[3];
                for (unsigned int d = 0; d < 3; ++d)
                  c[d] = D[a][d] / x[d];
                for (unsigned int k = 0; k < 3; ++k)
                  for (unsigned int L = 0; L < 3; ++L)
                    T[m][k][L] = c[0] * Q[k][0] * U[L][0] +
                                 c[1] * Q[k][1] * U[L][1] +
                                 c[2] * Q[k][2] * U[L][2];
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int J_ = 0; J_ < 3; ++J_)
                    W[m][i][J_] = Q[i][a] * V[a][J_];
              }
            else
              {
                const double theta =
                  mu_bar * z_over_expm1(2. * (eps[a] - eps[b])) / x[b];
                for (unsigned int k = 0; k < 3; ++k)
                  for (unsigned int L = 0; L < 3; ++L)
                    T[m][k][L] =
                      theta * (Q[k][a] * U[L][b] + Q[k][b] * U[L][a]);
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int J_ = 0; J_ < 3; ++J_)
                    W[m][i][J_] = Q[i][a] * V[b][J_] + Q[i][b] * V[a][J_];
              }
          }

        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int J_ = 0; J_ < 3; ++J_)
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int L = 0; L < 3; ++L)
                {
                  double v = -P[i][L] * Finv[J_][k];
                  for (unsigned int m = 0; m < 6; ++m)
                    v += W[m][i][J_] * T[m][k][L];
                  (*A)[i][J_][k][L] = v;
                }
      }

    if (trial)
      update_state(F, r, *trial);
  }
} // namespace densify
