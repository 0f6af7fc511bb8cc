// Central-difference explicit dynamics over a system of forces: the
// integrator, its time map and its energy account. It knows no physics.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <densify/parameters.h>

#include <string>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * What the explicit integrator needs of the system it integrates. Vectors
   * hold the locally owned entries; forces are out-of-balance forces in the
   * sign of a residual (R = f_int - f_ext).
   */
  class ExplicitSystem
  {
  public:
    virtual ~ExplicitSystem() = default;

    /**
     * Recompute the lumped mass at the current state into @p mass, with
     * mass scaling (if any) so that the stable step reaches
     * @p required_step (0: no request); returns the stable step (s).
     */
    virtual double
    update_mass(const double                   required_step,
                TrilinosWrappers::MPI::Vector &mass) = 0;

    /**
     * The internal forces @p internal and the rest @p external (contact,
     * body force) at displacement @p u for the loads of scene time
     * @p scene_time, reached from the last call over the scene-time
     * increment @p scene_increment and the physical time step @p dt. Every
     * call is accepted: the system commits its history (plasticity,
     * friction) at @p u. Throws std::runtime_error if it cannot (e.g. an
     * inverted element).
     */
    virtual void
    forces(const TrilinosWrappers::MPI::Vector &u,
           const double                         scene_time,
           const double                         scene_increment,
           const double                         dt,
           TrilinosWrappers::MPI::Vector       &internal,
           TrilinosWrappers::MPI::Vector       &external) = 0;

    /// The work the loads (moving tools, body forces) did so far (mJ).
    virtual double
    external_work() const = 0;
  };

  /**
   * Explicit dynamics by central differences with a lumped mass
   * (doc/theory.md): with the half-step velocities v and mass-proportional
   * damping c,
   *   v_{n+1/2} = ((1 - c h/2) v_{n-1/2} - h M^-1 R(u_n)) / (1 + c h/2),
   *   u_{n+1}   = u_n + h_{n+1/2} v_{n+1/2},  h = (h_{n-1/2} + h_{n+1/2})/2.
   * The scene's load history (scene time 0 ... T_s) is mapped onto physical
   * time 0 ... Loading time: the scene-time rate rises from zero along a
   * smooth step (3x^2 - 2x^3) over the ramp and then falls linearly with
   * the scene time to End speed fraction of its value at the end (constant
   * at the default 1). With the uniform time sigma, d sigma = d tau / g(tau),
   * g(tau) = 1 - (1 - End speed fraction) tau / T_s, sigma follows the
   * ramp and the constant rate, and tau(sigma) is in closed form.
   * advance() runs from one station (a scene load step) to the next with
   * equal steps that end on it. The energy account: kinetic energy, the
   * work of the internal forces, of the other forces on the mesh and of the
   * damping (trapezoidal rule on each step), whose balance is the
   * integrator's own check.
   */
  class ExplicitDynamics
  {
  public:
    /// Energies and counts at a station (summed over ranks, mJ).
    struct Account
    {
      /// Kinetic energy 1/2 v.M.v at the station.
      double kinetic = 0.;
      /// Work of the internal forces (elastic energy plus plastic work).
      double internal = 0.;
      /// Work of the external forces (contact, body force) on the mesh.
      double external_on_mesh = 0.;
      /// Work dissipated by the damping.
      double damping = 0.;
      /// Explicit steps since the start and in the last interval.
      unsigned long long steps          = 0;
      unsigned int       interval_steps = 0;
      /// Time step of the last interval (s) and the stable step (s).
      double step = 0., stable_step = 0.;
      /// Physical time (s).
      double time = 0.;
    };

    /// What a checkpoint keeps (this rank's part).
    struct State
    {
      std::vector<double> velocity, internal, external, mass;
      double              time = 0., last_step = 0.;
      unsigned long long  steps = 0;
      double kinetic = 0., w_internal = 0., w_external = 0., w_damping = 0.;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &velocity &internal &external &mass &time &last_step &steps
          &kinetic &w_internal &w_external &w_damping;
      }
    };

    /**
     * @p prm the subsection Explicit, @p scene_end_time the end of the
     * scene's load history, @p damping the mass-proportional damping
     * coefficient c (1/s).
     */
    ExplicitDynamics(const ExplicitParameters &prm,
                     const double              scene_end_time,
                     const MPI_Comm            comm);

    /**
     * Start at rest at displacement @p u: the mass, the time step and the
     * forces at @p u (scene time 0). @p scaled: the mass scaling sets the
     * step (Loading time / Number of steps) rather than the stable step.
     * Returns the time step (s).
     */
    double
    start(ExplicitSystem                      &system,
          const TrilinosWrappers::MPI::Vector &u,
          const bool                           scaled);

    /// The stable step of the last mass update (s).
    double
    stable_step() const
    {
      return stable;
    }

    /// Set the mass-proportional damping coefficient (1/s).
    void
    set_damping(const double c)
    {
      damping = c;
    }

    /// The mass-proportional damping coefficient (1/s).
    double
    damping_coefficient() const
    {
      return damping;
    }

    /**
     * Integrate from the current state to scene time @p scene_time, updating
     * @p u. Renews the mass (and the step) at the start of the interval.
     * Throws std::runtime_error with a one-line message if the integration
     * goes unstable (energy far above the work put in, or a failure of the
     * system).
     */
    Account
    advance(ExplicitSystem                &system,
            TrilinosWrappers::MPI::Vector &u,
            const double                   scene_time);

    /// The target step (s) of the station ending at scene time
    /// @p scene_time: Loading time / Number of steps times Explicit/Step
    /// profile there.
    double
    target_step_at(const double scene_time) const;

    /// Scene time at physical time @p t.
    double
    scene_time(const double t) const;

    /// Physical time at scene time @p tau (the inverse of scene_time()).
    double
    physical_time(const double tau) const;

    /// The state for a checkpoint.
    State
    state() const;

    /// Restore a state from state() (after start()); without @p with_mass
    /// the mass set up by start() is kept (a run resumed with another
    /// target step).
    void
    set_state(const State &saved, const bool with_mass = true);

  private:
    /// What to change when the integration fails: Explicit/Number of steps
    /// where the mass scaling sets the step, else Explicit/Time step safety.
    std::string
    remedy() const;

    const ExplicitParameters prm;
    const double             scene_end;
    const MPI_Comm           comm;
    double                   damping     = 0.;
    bool                     scaled      = true;
    double                   target_step = 0., step = 0., stable = 0.;
    /// Explicit/Step profile: the target step's factor against scene time.
    std::vector<std::pair<double, double>> step_profile;
    double                                 time = 0., last_step = 0.;
    unsigned long long                     n_steps = 0;
    TrilinosWrappers::MPI::Vector mass, inverse_mass, velocity, r_internal,
      r_external, previous_u;
    /// Energy sums so far (this rank's part of the work; kinetic global).
    double kinetic = 0., w_internal = 0., w_external = 0., w_damping = 0.;

    /// The uniform time sigma at scene time @p tau (the integral of
    /// 1 / g, the inverse of the slowing-down speed).
    double
    uniform_time(const double tau) const;

    /// Scene time at uniform time @p sigma (the inverse of uniform_time()).
    double
    slowed_time(const double sigma) const;

    /// The ramp's end t_r (s) and the uniform-time rate k after it.
    std::pair<double, double>
    ramp() const;

    /// Renew the mass and the time step.
    void
    renew_mass(ExplicitSystem &system);
  };
} // namespace densify
