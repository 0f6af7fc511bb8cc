// The explicit method's driver: the lumped mass and its scaling, the
// central-difference integrator between stations, and the forces of the
// multi-body system at each explicit step.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_vector.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/lumped_mass.h>
#include <densify/drivers/driver.h>
#include <densify/drivers/explicit_dynamics.h>
#include <densify/multi_body_system.h>
#include <densify/parameters.h>

#include <array>
#include <memory>
#include <ostream>
#include <vector>

namespace densify
{
  /**
   * Explicit dynamics of a MultiBodySystem (Solver/Method = explicit,
   * doc/theory.md section 10): sets up the lumped mass, scaled so that the
   * stable step reaches the target step, and the contact penalty that fits
   * it; integrates from station to station with ExplicitDynamics, evaluating
   * the system's force terms at every explicit step (each step accepted);
   * keeps the energy account, and gives each station its forces from the
   * least-squares line through their values over the interval.
   */
  class ExplicitDriver : public Driver, public ExplicitSystem
  {
  public:
    /// Energy account of the explicit run kept by the driver (mJ): work of
    /// the moving tools and of the body force, friction work, the contact
    /// springs' elastic energy now, and the energy the multiplier updates
    /// put into them.
    struct ExplicitWork
    {
      double tools = 0., body = 0., friction = 0., contact_energy = 0.,
             multipliers = 0.;
      /// Upper punch force and position, friction and lateral position at
      /// the last evaluation (for the trapezoidal tool work).
      double       upper_force = 0., upper_position = 0., lateral = 0.;
      Tensor<1, 3> upper_friction;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &tools &body &friction &contact_energy &multipliers &upper_force
          &upper_position &lateral &upper_friction;
      }
    };

    /// The driver of @p system; log-only lines go to @p log (null: none).
    ExplicitDriver(const Parameters   &parameters,
                   MultiBodySystem    &system,
                   ConditionalOStream &pcout,
                   TimerOutput        &timer,
                   std::ostream       *log);

    /**
     * Set up the lumped mass (with the largest-frequency measurement that
     * calibrates it), the integrator and the contact penalty that fits its
     * stable step; returns the penalty per particle.
     */
    std::vector<double>
    prepare() override;

    /// Start at rest (or at the checkpoint's state, which restore() then
    /// sets) and print the time step, added mass and contact penalty.
    void
    start() override;

    /// Integrate to @p time, the end of a station; returns the contact
    /// forces at the station (the least-squares line over the interval)
    /// and fills the explicit columns of @p s.
    ContactResults
    advance(const double       time,
            const unsigned int step,
            StepStatistics    &s) override;

    /// The account of the last station.
    const ExplicitDynamics::Account &
    account() const
    {
      return explicit_account;
    }

    /// The energy account so far.
    const ExplicitWork &
    work() const
    {
      return explicit_work;
    }

    /// The mass added by mass scaling, as a fraction of the physical mass.
    double
    added_mass_fraction() const
    {
      return lumped_mass->added_mass_fraction();
    }

    /// The physical time at scene time @p scene_time (s).
    double
    physical_time(const double scene_time) const override
    {
      return explicit_dynamics->physical_time(scene_time);
    }

    /// The contact record of the pass at the last station, if that pass
    /// filled it (else null).
    const ContactRecord *
    station_record() const override
    {
      return station_recorded ? &record : nullptr;
    }

    /// What a checkpoint keeps of the driver.
    struct Saved
    {
      ExplicitDynamics::State dynamics;
      ExplicitWork            work;
      /// The mass-scaling factors and the calibration applied.
      std::vector<double> factors;
      double              calibration = 1.;
      /// The cell bound at the last measurement and the mass updates so far.
      double       bound   = 0.;
      unsigned int updates = 0;
      /// The power iteration's last vector (locally owned entries).
      std::vector<double> mode;
      /// The Explicit/Number of steps the mass scaling was set for.
      unsigned int n_explicit = 0;
      /// The calibration's target.
      double target = 0.;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &dynamics &work &factors &calibration &bound &updates &mode
          &n_explicit &target;
      }
    };

    /// The driver's state for a checkpoint.
    Saved
    saved() const;

    /// Continue from @p saved at the scene time @p time. Throws InputError
    /// if it does not fit this run (a checkpoint of an implicit run).
    void
    restore(const Saved &saved, const double time);

    /// Write saved().
    void
    write_checkpoint(boost::archive::binary_oarchive &archive) const override;

    /// Read what write_checkpoint() wrote.
    void
    read_checkpoint(boost::archive::binary_iarchive &archive) override;

    /// restore() what read_checkpoint() read at the system's time.
    void
    resume() override;

    // ExplicitSystem
    double
    update_mass(const double                   required_step,
                TrilinosWrappers::MPI::Vector &mass) override;
    void
    forces(const TrilinosWrappers::MPI::Vector &u,
           const double                         scene_time,
           const double                         scene_increment,
           const double                         dt,
           TrilinosWrappers::MPI::Vector       &internal,
           TrilinosWrappers::MPI::Vector       &external) override;
    double
    external_work() const override
    {
      return explicit_work.tools + explicit_work.body;
    }

  private:
    /// The state read by read_checkpoint(), until resume() takes it up.
    std::unique_ptr<Saved> loaded;

    /// The largest squared frequency of the elements (elastic, at the
    /// current state) with the lumped mass @p mass, by power iteration.
    double
    largest_frequency2(const TrilinosWrappers::MPI::Vector &mass);

    const Parameters   &prm;
    MultiBodySystem    &system;
    ConditionalOStream &pcout;
    TimerOutput        &timer;
    std::ostream       *log;
    MPI_Comm            comm;

    std::unique_ptr<LumpedMass> lumped_mass;
    /// Margin of the measured largest frequency over the power iteration's
    /// estimate (which approaches it from below).
    static constexpr double calibration_margin = 1.25;
    /// Stations between two measurements of the largest frequency at most.
    static constexpr unsigned int recalibration_interval = 10;
    /// Mass updates so far (one per station), and the raw cell bound at the
    /// last measurement of the largest frequency (1/s^2).
    unsigned int mass_updates     = 0;
    double       calibrated_bound = 0.;
    /// The calibration factor of the last measurement. A rise within
    /// calibration_margin (the mass before it still gives a stable step) is
    /// approached by at most calibration_rise a station, so that the mass of
    /// nodes that move with the compact grows over stations, not at once.
    double calibration_target = 0.;
    /// The largest growth of the applied calibration factor from one station
    /// to the next, about calibration_margin^(1 / recalibration_interval).
    static constexpr double calibration_rise = 1.0226;
    /// The power iteration's last vector, the start of the next one.
    TrilinosWrappers::MPI::Vector frequency_mode;
    /// The explicit run's contact penalty per particle (MPa/mm).
    std::vector<double> explicit_penalty;
    /// An upper bound of the contact stiffness a punch meets (N/mm): the
    /// stiffest particle's penalty over the die's bore, for the mass of a
    /// punch under force control (PunchControl::drive()).
    double                            punch_stiffness = 0.;
    std::unique_ptr<ExplicitDynamics> explicit_dynamics;
    ExplicitWork                      explicit_work;
    /// Time-weighted sums of the contact forces over the current interval
    /// between stations, of the forces times scene time, and of the
    /// weights times 1, t and t^2 (the least-squares line at the station).
    ContactResults        interval_sum, interval_moment;
    std::array<double, 3> interval_weight = {{0., 0., 0.}};
    /// Body force vector of the last evaluation and the displacement then
    /// (body work); the displacement at the last contact search.
    TrilinosWrappers::MPI::Vector body_forces, body_solution, search_solution;
    /// The explicit step's plain arrays: the solution's and the committed
    /// solution's values, and the forces on their way into a residual.
    AllValues   explicit_values, explicit_committed;
    LocalForces explicit_forces;
    /// The contact record of the explicit pass at the station (the scene
    /// time record_time; negative: no pass records), and whether the last
    /// station's pass filled it.
    ContactRecord record;
    double        record_time      = -1.;
    bool          station_recorded = false;
    /// The explicit run's last station account.
    ExplicitDynamics::Account explicit_account;
  };
} // namespace densify
