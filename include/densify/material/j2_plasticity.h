// Finite-strain J2 elastoplasticity (Simo 1992) with Hencky elasticity.
#pragma once

#include <deal.II/base/symmetric_tensor.h>

#include <densify/material/material.h>
#include <densify/material/presets.h>

#include <cmath>
#include <string>

namespace densify
{
  /**
   * State of J2Plasticity at one quadrature point, kept between load steps
   * (the MaterialState of the history).
   */
  struct J2State
  {
    /// Inverse plastic right Cauchy-Green tensor C_p^{-1} (identity at start).
    Tensor<2, 3> Cp_inv = unit_symmetric_tensor<3>();
    /// Accumulated equivalent plastic strain (dimensionless).
    double eps_p = 0.;

    /// Write or read the state with a boost archive (checkpoints).
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &Cp_inv &eps_p;
    }
  };

  /// Isotropic hardening law of J2Plasticity.
  enum class Hardening
  {
    /// Perfectly plastic: sigma_y = sigma0.
    none,
    /// Linear: sigma_y = sigma0 + H eps_p.
    linear,
    /// Power law: sigma_y = sigma0 + K eps_p^n.
    power_law
  };

  /**
   * Parameters of J2Plasticity. Units mm, N, MPa. Only the fields of the
   * selected hardening law are used (H for linear, K and n for power_law).
   */
  struct J2Parameters
  {
    /// Young's modulus (MPa).
    double E = 0.;
    /// Poisson's ratio (-1 < nu < 0.5).
    double nu = 0.;
    /// Initial yield stress (MPa, Kirchhoff stress measure).
    double sigma0 = 0.;
    /// Linear hardening modulus (MPa).
    double H = 0.;
    /// Power-law hardening coefficient (MPa).
    double K = 0.;
    /// Power-law hardening exponent (> 0).
    double n = 1.;
    /// Hardening law.
    Hardening hardening = Hardening::none;
    /// Mass density (t/mm^3; 0: none given, explicit dynamics refuses it).
    double density = 0.;
    /// Short name shown in the log, e.g. "Sn".
    std::string label;
  };

  /// Parameters of the preset @p preset: its constants, no hardening, its
  /// name as the label.
  J2Parameters
  material_preset(const MaterialPreset &preset);

  /**
   * Parameters of the preset named @p name (the table in
   * source/material/presets.cc: "Sn", "Fe", "Cu"). Throws
   * std::invalid_argument for any other name (including "custom", whose
   * parameters the caller must give explicitly).
   */
  J2Parameters
  material_preset(const std::string &name);

  /// Name of a hardening law: "perfectly plastic", "linear hardening" or
  /// "power-law hardening".
  std::string
  hardening_name(const Hardening hardening);

  /**
   * Finite-strain J2 (von Mises) elastoplasticity after Simo (1992), see
   * also de Souza Neto, Peric & Owen, "Computational Methods for
   * Plasticity", ch. 14:
   * - multiplicative split F = Fe Fp, elastic left Cauchy-Green tensor
   *   be = F Cp^{-1} F^T with history Cp^{-1} = Fp^{-1} Fp^{-T};
   * - Hencky law in Kirchhoff stress: tau = K ln(J) I + 2 mu dev(eps_e),
   *   eps_e = 1/2 ln(be);
   * - von Mises yield f = sqrt(3/2) |dev tau| - sigma_y(eps_p), associative
   *   flow, isotropic hardening (none, linear, power law);
   * - exponential-map return = radial return in principal logarithmic
   *   strains;
   * - consistent algorithmic tangent A = dP/dF, exact also for repeated
   *   principal stretches.
   *
   * evaluate() throws std::domain_error if det F <= 0 (inverted element)
   * and std::runtime_error if the local Newton iteration of the power-law
   * return mapping fails.
   */
  class J2Plasticity : public Material
  {
  public:
    /// Construct from @p parameters; throws std::invalid_argument if they
    /// are out of range: E <= 0, nu outside (-1, 0.5), sigma0 < 0 (or
    /// sigma0 = 0 without hardening), H < 0, K < 0 or n <= 0.
    explicit J2Plasticity(const J2Parameters &parameters);

    /// E.g. "J2 finite strain (Sn, perfectly plastic)".
    std::string
    name() const override;

    /// True unless the yield stress is infinite (then the law is Hencky
    /// hyperelasticity and needs no history): the law keeps a J2State.
    bool
    needs_history() const override
    {
      return std::isfinite(parameters.sigma0);
    }

    /// sigma_y(0) (MPa); infinite for Hencky hyperelasticity.
    double
    initial_yield_stress() const override
    {
      return parameters.sigma0;
    }

    /// Always false.
    bool
    is_linear() const override
    {
      return false;
    }

    /**
     * Return mapping at deformation gradient @p F from the state
     * @p committed (a virgin state if nullptr); writes the updated state to
     * @p trial (if not nullptr), the first Piola-Kirchhoff stress @p P and
     * the consistent tangent @p A (A[i][J][k][L] = dP_iJ/dF_kL).
     */
    void
    evaluate(const Tensor<2, 3>  &F,
             const MaterialState *committed,
             MaterialState       *trial,
             Tensor<2, 3>        &P,
             Tensor<4, 3>        &A) const override;

    /// The return mapping of evaluate() without the consistent tangent:
    /// the stress @p P and the updated state @p trial only.
    void
    stress(const Tensor<2, 3>  &F,
           const MaterialState *committed,
           MaterialState       *trial,
           Tensor<2, 3>        &P) const override;

    /// Young's modulus (MPa).
    double
    youngs_modulus() const override
    {
      return parameters.E;
    }

    /// K + 4/3 mu (MPa).
    double
    p_wave_modulus() const override
    {
      return kappa + 4. / 3. * mu;
    }

    /// K (MPa).
    double
    bulk_modulus() const override
    {
      return kappa;
    }

    /// The mass density (t/mm^3).
    double
    density() const override
    {
      return parameters.density;
    }

    /// Hencky's K ln J; true.
    bool
    kirchhoff_pressure(const double log_J, double &p) const override
    {
      p = kappa * log_J;
      return true;
    }

    /// The deviator of the return mapping's Kirchhoff stress and the
    /// updated state (the same as stress()'s, without P); true.
    bool
    kirchhoff_deviator(const Tensor<2, 3>    &F,
                       const MaterialState   *committed,
                       MaterialState         *trial,
                       SymmetricTensor<2, 3> &tau_dev) const override;

    /**
     * kirchhoff_deviator() for @p n points side by side in SIMD lanes
     * (source/material/j2_plasticity_lanes.cc): the trial state, the series
     * of ln bbar, the radial return and the updated state of four points at
     * a time; a point whose trial state needs the spectral path (or fails)
     * takes kirchhoff_deviator() on its own. The same law to round-off.
     */
    bool
    kirchhoff_deviators(const unsigned int            n,
                        const Tensor<2, 3> *const    *F,
                        const MaterialState *const   *committed,
                        MaterialState *const         *trial,
                        SymmetricTensor<2, 3> *const *tau_dev) const override;

    /// The integral of sigma_y from 0 to the state's eps_p (MPa).
    double
    plastic_work(const MaterialState &state) const override;

    /// The state's eps_p.
    double
    equivalent_plastic_strain(const MaterialState &state) const override
    {
      return state.eps_p;
    }

    /// The parameters this law was constructed with.
    const J2Parameters &
    get_parameters() const
    {
      return parameters;
    }

    /// Yield stress sigma_y(eps_p) (MPa); eps_p is clamped to >= 0.
    double
    yield_stress(const double eps_p) const;

    /// Hardening modulus d sigma_y / d eps_p (MPa), evaluated at
    /// max(eps_p, 1e-12) so that it stays finite for the power law with
    /// n < 1.
    double
    hardening_modulus(const double eps_p) const;

  private:
    /// The trial state and the radial return at one point, shared by
    /// compute() and kirchhoff_deviator().
    struct TrialReturn
    {
      /// The state of the last converged step (a virgin one if none).
      const J2State *old = nullptr;
      /// G = F Cp^{-1}.
      Tensor<2, 3> G;
      /// Eigenvalues x_a of the trial be = G F^T, descending, and their
      /// eigenvectors Q[i][a] = (n_a)_i.
      double x[3], Q[3][3];
      /// Principal logarithmic strains, their trace and deviator.
      double eps[3], tr_eps = 0., e_dev[3];
      /// Trial Kirchhoff deviator (principal), its squared norm and von
      /// Mises value.
      double s_trial[3], s_norm2 = 0., q_trial = 0.;
      /// Whether the step yields, its plastic multiplier and the factor
      /// 1 - 3 mu dg / q_trial of the radial return (1 if elastic).
      bool   plastic = false;
      double dg = 0., factor = 1.;
    };

    /// Trial state, spectral decomposition and radial return at @p F.
    TrialReturn
    trial_return(const Tensor<2, 3> &F, const MaterialState *committed) const;

    /// The updated state: Cp^{-1} = F^{-1} be F^{-T} with the returned be,
    /// and eps_p (the last converged state if the step is elastic).
    void
    update_state(const Tensor<2, 3> &F,
                 const TrialReturn  &r,
                 MaterialState      &trial) const;

    /// The return mapping; the tangent into @p A unless it is nullptr.
    void
    compute(const Tensor<2, 3>  &F,
            const MaterialState *committed,
            MaterialState       *trial,
            Tensor<2, 3>        &P,
            Tensor<4, 3>        *A) const;

    /// kirchhoff_deviators()'s work (source/material/j2_plasticity_lanes.cc;
    /// not virtual, so that it can be compiled for more than one
    /// instruction set).
    void
    deviators_in_lanes(const unsigned int            n,
                       const Tensor<2, 3> *const    *F,
                       const MaterialState *const   *committed,
                       MaterialState *const         *trial,
                       SymmetricTensor<2, 3> *const *tau_dev) const;

    /// Plastic multiplier (increment of eps_p) of the radial return for a
    /// trial von Mises stress @p q_trial > sigma_y(@p eps_p_old).
    double
    plastic_increment(const double q_trial, const double eps_p_old) const;

    /// The material parameters.
    const J2Parameters parameters;
    /// Bulk modulus K = E / (3 (1 - 2 nu)) (MPa).
    const double kappa;
    /// Shear modulus mu = E / (2 (1 + nu)) (MPa).
    const double mu;
  };
} // namespace densify
