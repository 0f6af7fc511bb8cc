// The constitutive-law interface of Densify: stress and tangent from the
// deformation gradient.
#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <limits>
#include <memory>
#include <string>

namespace densify
{
  using namespace dealii;

  struct J2State;

  /**
   * State kept at one quadrature point between load steps. Only materials
   * whose needs_history() returns true get one; an elastic scene allocates
   * none. The one law with history is J2Plasticity, so the state is its
   * J2State (include/densify/material/j2_plasticity.h, which code that
   * stores or copies states includes). Code outside the law reads a state
   * through the law: plastic_work(), equivalent_plastic_strain().
   */
  using MaterialState = J2State;

  /**
   * A constitutive law in total-Lagrangian form: given the deformation
   * gradient F at a quadrature point (and the committed history, if any),
   * return the first Piola-Kirchhoff stress P (MPa) and the tangent
   * A = dP/dF (MPa). Implementations are stateless apart from their
   * parameters, so one object serves every quadrature point of a particle.
   */
  class Material
  {
  public:
    virtual ~Material() = default;

    /// Name shown in the log, e.g. "linear elastic (Sn)".
    virtual std::string
    name() const = 0;

    /// True if the law needs a MaterialState per quadrature point.
    virtual bool
    needs_history() const
    {
      return false;
    }

    /// True if the law is linear in F (then one Newton iteration suffices
    /// when nothing else is nonlinear).
    virtual bool
    is_linear() const
    {
      return false;
    }

    /**
     * Evaluate P(F) and A = dP/dF. @p committed is the state at the end of
     * the last converged step and @p trial receives the updated state; both
     * are nullptr when needs_history() is false.
     */
    virtual void
    evaluate(const Tensor<2, 3>  &F,
             const MaterialState *committed,
             MaterialState       *trial,
             Tensor<2, 3>        &P,
             Tensor<4, 3>        &A) const = 0;

    /**
     * Evaluate P(F) and the updated state alone, for a residual without its
     * tangent. The default calls evaluate(); laws whose tangent costs much
     * more than their stress override it.
     */
    virtual void
    stress(const Tensor<2, 3>  &F,
           const MaterialState *committed,
           MaterialState       *trial,
           Tensor<2, 3>        &P) const
    {
      Tensor<4, 3> A;
      evaluate(F, committed, trial, P, A);
    }

    /// True if the law uses finite-strain kinematics (then the current
    /// volume is det F dV; for small strain it is (1 + tr grad u) dV).
    virtual bool
    finite_strain() const
    {
      return true;
    }

    /// Young's modulus (MPa), used to scale penalties and stabilisation.
    virtual double
    youngs_modulus() const = 0;

    /// Initial yield stress (MPa); infinite for laws that do not yield.
    virtual double
    initial_yield_stress() const
    {
      return std::numeric_limits<double>::infinity();
    }

    /// P-wave modulus lambda + 2 mu of the elastic response (MPa): with the
    /// density it gives the dilatational wave speed, hence the stable time
    /// step of explicit dynamics.
    virtual double
    p_wave_modulus() const = 0;

    /// Bulk modulus K of the elastic response (MPa).
    virtual double
    bulk_modulus() const = 0;

    /// Mass density (t/mm^3); 0 if none was given.
    virtual double
    density() const = 0;

    /**
     * For laws whose Kirchhoff stress splits into a pressure of J alone and
     * a deviator of the isochoric part of F and the history, with isochoric
     * plastic flow (then corners of a cell that differ only in their volume
     * ratio share the deviator and the updated state): set @p p to the
     * Kirchhoff pressure at the volume ratio J with ln J = @p log_J (MPa)
     * and return true (the logarithm, which the F-bar kernels have at hand,
     * spares an exponential and a logarithm a corner). Other laws return
     * false.
     */
    virtual bool
    kirchhoff_pressure(const double /*log_J*/, double & /*p*/) const
    {
      return false;
    }

    /**
     * For laws with kirchhoff_pressure(): the deviator @p tau_dev of the
     * Kirchhoff stress at @p F (MPa), which the isochoric part of F and the
     * history decide, and the updated state @p trial, without the first
     * Piola-Kirchhoff stress or the tangent (the explicit force kernel,
     * NodalAveraging::forces()); returns true. Other laws return false.
     * @p trial may be @p committed (the explicit kernel updates its states
     * in place): a law reads the committed state before it writes.
     */
    virtual bool
    kirchhoff_deviator(const Tensor<2, 3> & /*F*/,
                       const MaterialState * /*committed*/,
                       MaterialState * /*trial*/,
                       SymmetricTensor<2, 3> & /*tau_dev*/) const
    {
      return false;
    }

    /**
     * kirchhoff_deviator() for the @p n points *F[k], committed[k] (nullptr
     * entries or a nullptr array: the virgin state), trial[k] (or a nullptr
     * array: no update), *tau_dev[k] at once, so that a law can evaluate
     * several points side by side in SIMD lanes. The default calls
     * kirchhoff_deviator() point by point; returns what it returns.
     */
    virtual bool
    kirchhoff_deviators(const unsigned int            n,
                        const Tensor<2, 3> *const    *F,
                        const MaterialState *const   *committed,
                        MaterialState *const         *trial,
                        SymmetricTensor<2, 3> *const *tau_dev) const
    {
      for (unsigned int k = 0; k < n; ++k)
        if (!kirchhoff_deviator(*F[k],
                                committed ? committed[k] : nullptr,
                                trial ? trial[k] : nullptr,
                                *tau_dev[k]))
          return false;
      return true;
    }

    /// Plastic work per unit reference volume dissipated to reach the state
    /// @p state (MPa = mJ/mm^3); 0 for laws without plasticity.
    virtual double
    plastic_work(const MaterialState & /*state*/) const
    {
      return 0.;
    }

    /// Accumulated equivalent plastic strain of the state @p state
    /// (dimensionless); 0 for laws without plasticity.
    virtual double
    equivalent_plastic_strain(const MaterialState & /*state*/) const
    {
      return 0.;
    }
  };

  /**
   * Small-strain isotropic linear elasticity: P = lambda tr(eps) I + 2 mu eps
   * with eps = sym(F - I). Valid for small displacements and rotations.
   */
  class LinearElastic : public Material
  {
  public:
    /// @p E Young's modulus (MPa), @p nu Poisson's ratio, @p label shown in the
    /// log, @p density the mass density (t/mm^3).
    LinearElastic(const double       E,
                  const double       nu,
                  const std::string &label,
                  const double       density = 0.);

    std::string
    name() const override;

    bool
    is_linear() const override
    {
      return true;
    }

    bool
    finite_strain() const override
    {
      return false;
    }

    void
    evaluate(const Tensor<2, 3>  &F,
             const MaterialState *committed,
             MaterialState       *trial,
             Tensor<2, 3>        &P,
             Tensor<4, 3>        &A) const override;

    double
    youngs_modulus() const override
    {
      return E;
    }

    double
    p_wave_modulus() const override
    {
      return lambda + 2. * mu;
    }

    double
    bulk_modulus() const override
    {
      return lambda + 2. / 3. * mu;
    }

    double
    density() const override
    {
      return rho;
    }

  private:
    const double      E, nu, lambda, mu, rho;
    const std::string label;
    Tensor<4, 3>      C;
  };
} // namespace densify
