// The explicit method's driver: lumped mass and its scaling, the forces of
// each explicit step, the energy account of the loads, and the stations'
// forces.
#include <deal.II/base/mpi.h>

#include <densify/drivers/explicit_driver.h>
#include <densify/utilities.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <type_traits>

namespace densify
{
  ExplicitDriver::ExplicitDriver(const Parameters   &parameters,
                                 MultiBodySystem    &system,
                                 ConditionalOStream &pcout,
                                 TimerOutput        &timer,
                                 std::ostream       *log)
    : prm(parameters)
    , system(system)
    , pcout(pcout)
    , timer(timer)
    , log(log)
    , comm(system.comm)
  {}



  std::vector<double>
  ExplicitDriver::prepare()
  {
    // the tangential springs' share of the stable step, where friction acts
    const double tangential_ratio =
      system.effects.any_friction() ?
        prm.contact.tangential_penalty_factor / prm.contact.penalty_factor :
        0.;
    lumped_mass = std::make_unique<LumpedMass>(system.dof_handler,
                                               system.particle_material,
                                               system.effects.mass_scaling,
                                               tangential_ratio,
                                               system.cell_volume_weights);
    lumped_mass->set_cell_volume_barrier(system.cell_volume_barrier);
    explicit_dynamics =
      std::make_unique<ExplicitDynamics>(prm.explicit_dynamics,
                                         prm.time.end_time,
                                         comm);
    // the mass (scaled for the target step), then the contact penalty that
    // fits the elements' stable step
    const bool   scaled   = (system.effects.mass_scaling != MassScaling::none);
    const double required = scaled ? prm.explicit_dynamics.loading_time /
                                       prm.explicit_dynamics.n_steps /
                                       prm.explicit_dynamics.safety :
                                     0.;
    TrilinosWrappers::MPI::Vector mass;
    system.update_ghosts();
    lumped_mass->update(system.solution_ghosted, required, mass);
    // the cell bound calibrated by the mesh's measured largest frequency,
    // with a margin for the power iteration (which approaches it from
    // below) and for the cells' later distortion
    lumped_mass->calibrate(largest_frequency2(mass), calibration_margin, true);
    lumped_mass->update(system.solution_ghosted, required, mass);
    calibrated_bound   = lumped_mass->bound_frequency2();
    calibration_target = lumped_mass->calibration_factor();
    // Explicit/Contact stiffness, per particle from its material
    std::vector<double>           stiffness;
    std::map<std::string, double> by_material;
    for (unsigned int p = 0; p < system.particles.size(); ++p)
      {
        stiffness.push_back(
          explicit_contact_stiffness(prm.explicit_dynamics.contact_stiffness,
                                     *system.particle_material[p]));
        by_material[system.particles[p].material] = stiffness.back();
      }
    if (Utilities::trim(prm.explicit_dynamics.contact_stiffness) == "auto")
      {
        pcout << "Explicit/Contact stiffness = auto:";
        for (const auto &[name, k] : by_material)
          pcout << " " << name << " " << std::setprecision(3) << k;
        pcout << std::endl;
      }
    explicit_penalty = lumped_mass->contact_penalties(stiffness);
    // a punch under force control is a rigid body whose mass keeps its
    // contact springs within the stable step (PunchControl::drive())
    punch_stiffness =
      *std::max_element(explicit_penalty.begin(), explicit_penalty.end()) *
      system.pressed_area();
    std::vector<double> diameters;
    for (const Particle &p : system.particles)
      diameters.push_back(p.diameter);
    explicit_dynamics->set_damping(2. * prm.explicit_dynamics.damping_ratio *
                                   lumped_mass->lowest_frequency(diameters));
    search_solution.reinit(system.locally_owned, comm);
    body_forces.reinit(system.locally_owned, comm);
    body_solution.reinit(system.locally_owned, comm);
    return explicit_penalty;
  }



  void
  ExplicitDriver::start()
  {
    const double dt = explicit_dynamics->start(
      *this, system.solution, system.effects.mass_scaling != MassScaling::none);
    const auto [low, high] =
      std::minmax_element(explicit_penalty.begin(), explicit_penalty.end());
    pcout << "Explicit dynamics: time step " << std::setprecision(4) << dt
          << " s (stable " << explicit_dynamics->stable_step() << " s), about "
          << static_cast<unsigned long long>(
               prm.explicit_dynamics.loading_time / dt + 0.5)
          << " steps; added mass " << std::setprecision(3)
          << 100. * lumped_mass->added_mass_fraction() << " %; contact penalty "
          << std::setprecision(4) << *low;
    if (*high > *low)
      pcout << " - " << *high;
    pcout << " MPa/mm" << std::endl;
  }



  ExplicitDriver::Saved
  ExplicitDriver::saved() const
  {
    Saved saved;
    saved.dynamics    = explicit_dynamics->state();
    saved.work        = explicit_work;
    saved.factors     = lumped_mass->scaling_factors();
    saved.calibration = lumped_mass->calibration_factor();
    saved.bound       = calibrated_bound;
    saved.updates     = mass_updates;
    saved.mode.assign(frequency_mode.begin(), frequency_mode.end());
    saved.n_explicit = prm.explicit_dynamics.n_steps;
    saved.target     = calibration_target;
    return saved;
  }



  void
  ExplicitDriver::restore(const Saved &saved, const double time)
  {
    if (saved.dynamics.velocity.size() != system.locally_owned.n_elements() ||
        saved.factors.size() != system.triangulation.n_active_cells())
      throw InputError("--resume: the checkpoint was written by an "
                       "implicit run; resume it with Solver/Method = "
                       "implicit");
    explicit_work      = saved.work;
    calibrated_bound   = saved.bound;
    mass_updates       = saved.updates;
    calibration_target = saved.target;
    // with another Explicit/Number of steps (the advice of a run that left
    // the quasi-static limits) the mass scaling starts anew for the new
    // step: the mass set up for it is kept, and the nodes keep their
    // velocities (a quasi-static motion follows the punch, whatever the
    // mass)
    const bool same_steps = saved.n_explicit == prm.explicit_dynamics.n_steps;
    explicit_dynamics->set_state(saved.dynamics, same_steps);
    // the factors were raised for the step of the station ending at the
    // checkpoint (Explicit/Step profile)
    if (same_steps)
      lumped_mass->set_scaling_factors(saved.factors,
                                       explicit_dynamics->target_step_at(time) /
                                         prm.explicit_dynamics.safety,
                                       saved.dynamics.mass);
    else
      pcout << "Explicit/Number of steps " << prm.explicit_dynamics.n_steps
            << " (the checkpoint's: " << saved.n_explicit
            << "): the mass scaling starts anew" << std::endl;
    lumped_mass->set_calibration_factor(saved.calibration);
    AssertDimension(saved.mode.size(), frequency_mode.locally_owned_size());
    std::copy(saved.mode.begin(), saved.mode.end(), frequency_mode.begin());
    search_solution = system.solution;
    body_solution   = system.solution;
  }



  void
  ExplicitDriver::write_checkpoint(
    boost::archive::binary_oarchive &archive) const
  {
    const Saved state = saved();
    archive    &state;
  }



  void
  ExplicitDriver::read_checkpoint(boost::archive::binary_iarchive &archive)
  {
    loaded = std::make_unique<Saved>();
    archive &*loaded;
  }



  void
  ExplicitDriver::resume()
  {
    Assert(loaded, ExcInternalError());
    restore(*loaded, system.current_time);
    loaded.reset();
  }



  double
  ExplicitDriver::largest_frequency2(const TrilinosWrappers::MPI::Vector &mass)
  {
    TimerOutput::Scope t(timer, "Explicit: largest frequency");
    // power iteration on M^-1 K with K the cells' elastic stiffness in their
    // current shape (LumpedMass::stiffness_product); a start vector that
    // depends on the vertices' positions only (not on the DoF numbering,
    // which depends on the number of ranks), so that any number of ranks
    // finds the same; a measurement during the run starts from the last
    // one's vector, which is close to the new mode: fewer iterations
    TrilinosWrappers::MPI::Vector x(system.locally_owned, comm), Kx(x);
    TrilinosWrappers::MPI::Vector x_ghosted(system.solution_ghosted);
    system.update_ghosts();
    const bool warm = frequency_mode.size() == x.size();
    if (warm)
      x = frequency_mode;
    else
      {
        for (const auto &cell : system.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int c = 0; c < 3; ++c)
                {
                  const types::global_dof_index i =
                    cell->vertex_dof_index(v, c);
                  const Point<3> &X = cell->vertex(v);
                  if (system.locally_owned.is_element(i))
                    x(i) =
                      std::sin(1. + 7. * X[0] + 9. * X[1] + 11. * X[2] + c);
                }
        x.compress(VectorOperation::insert);
      }
    double omega2 = 0.;
    for (unsigned int it = 0; it < (warm ? 15u : 40u); ++it)
      {
        x_ghosted = x;
        lumped_mass->stiffness_product(system.solution_ghosted, x_ghosted, Kx);
        // Rayleigh quotient x.Kx / x.Mx, then x <- M^-1 K x normalised
        double xMx = 0.;
        for (unsigned int k = 0; k < x.locally_owned_size(); ++k)
          xMx += x.begin()[k] * mass.begin()[k] * x.begin()[k];
        omega2 = (x * Kx) / Utilities::MPI::sum(xMx, comm);
        for (unsigned int k = 0; k < x.locally_owned_size(); ++k)
          x.begin()[k] =
            mass.begin()[k] > 0. ? Kx.begin()[k] / mass.begin()[k] : 0.;
        x /= std::max(x.linfty_norm(), 1e-300);
      }
    frequency_mode = x;
    return omega2;
  }



  double
  ExplicitDriver::update_mass(const double                   required_step,
                              TrilinosWrappers::MPI::Vector &mass)
  {
    TimerOutput::Scope t(timer, "Explicit: mass");
    system.update_ghosts();
    if (lumped_mass->calibration_factor() < calibration_target)
      lumped_mass->set_calibration_factor(
        std::min(calibration_target,
                 calibration_rise * lumped_mass->calibration_factor()));
    double stable =
      lumped_mass->update(system.solution_ghosted, required_step, mass);
    // the calibration measured anew once the cells' bound has moved by more
    // than a tenth since the last measurement (the cells flatten as the
    // powder densifies, and the ratio of the true largest frequency to the
    // bound changes with their shape), and at least every
    // recalibration_interval stations
    ++mass_updates;
    const double drift =
      std::abs(lumped_mass->bound_frequency2() / calibrated_bound - 1.);
    if (drift > 0.1 || mass_updates % recalibration_interval == 0)
      {
        const double before = lumped_mass->calibration_factor();
        double       omega2 = largest_frequency2(mass);
        lumped_mass->calibrate(omega2, calibration_margin, false);
        // a fall measured from the last mode may be the power iteration's
        // (it approaches the largest frequency from below, slowly where a
        // flattening cell's new mode lies far from the last one), not the
        // mesh's: it is measured again from the vertices' start vector and
        // the larger of the two kept
        const bool fell = lumped_mass->calibration_factor() < before;
        if (fell)
          {
            const TrilinosWrappers::MPI::Vector last_mode = frequency_mode;
            frequency_mode    = TrilinosWrappers::MPI::Vector();
            const double cold = largest_frequency2(mass);
            if (cold < omega2)
              frequency_mode = last_mode;
            omega2 = std::max(omega2, cold);
            lumped_mass->calibrate(omega2, calibration_margin, false);
          }
        calibration_target = lumped_mass->calibration_factor();
        // a rise within the margin: the mass before it gives a stable step
        // at the measured frequency, so the mass follows over stations, a
        // little at each
        if (calibration_target > calibration_rise * before &&
            calibration_target <= calibration_margin * before)
          lumped_mass->set_calibration_factor(calibration_rise * before);
        stable =
          lumped_mass->update(system.solution_ghosted, required_step, mass);
        calibrated_bound = lumped_mass->bound_frequency2();
        // in log.txt only: a line per measurement would crowd the progress
        if (log != nullptr)
          *log << "Explicit dynamics: stable step measured anew at t = "
               << system.load_time << ": calibration " << before << " -> "
               << calibration_target << " (applied "
               << lumped_mass->calibration_factor() << "), added mass "
               << 100. * lumped_mass->added_mass_fraction() << " %"
               << (fell ? " (a fall: measured again from the start vector)" :
                          "")
               << std::endl;
      }
    return stable;
  }



  void
  ExplicitDriver::forces(const TrilinosWrappers::MPI::Vector &u,
                         const double                         scene_time,
                         const double                         scene_increment,
                         const double                         dt,
                         TrilinosWrappers::MPI::Vector       &internal,
                         TrilinosWrappers::MPI::Vector       &external)
  {
    // a punch under force control moves as a rigid body pressed by its
    // target and its contact force of the last step, with a mass whose
    // frequency on the stiffest contact springs over the whole bore, h
    // sqrt(2 k / m), stays below the stable 2 (PunchControl::drive())
    if (scene_increment > 0.)
      for (PunchControl *control :
           {&system.punch_control, &system.lower_control})
        control->drive(scene_time,
                       scene_increment,
                       dt,
                       punch_stiffness * dt * dt,
                       explicit_dynamics->damping_coefficient());
    system.apply_loads(scene_time, scene_increment);
    if (&u != &system.solution)
      system.solution = u;
    system.update_ghosts();
    if (system.particle_contact)
      {
        // a new search once two points may have closed by more than its
        // margin since the last one (each moved at most max |u - u_search|)
        double moved = 0.;
        for (unsigned int i = 0; i < system.solution.locally_owned_size(); ++i)
          moved = std::max(moved,
                           std::abs(system.solution.begin()[i] -
                                    search_solution.begin()[i]));
        if (Utilities::MPI::max(moved, comm) * 2. * std::sqrt(3.) >
            system.search_margin)
          {
            TimerOutput::Scope ts(timer, "Contact: search");
            system.particle_contact->update_search(system.solution_ghosted,
                                                   system.search_margin);
            search_solution = system.solution;
          }
      }
    // the values read once into plain arrays for the element loops
    explicit_values.gather(system.solution_ghosted);
    explicit_committed.gather(system.committed_ghosted);
    AssemblyContext c  = system.context();
    c.values           = &explicit_values;
    c.committed_values = &explicit_committed;
    c.plain_forces     = &explicit_forces;
    // the pass at the station records its contact pairs and die forces for
    // the station's statistics
    if (scene_time == record_time)
      {
        record.pairs.clear();
        record.die_force.assign(system.particles.size(), 0.);
        c.record         = &record;
        station_recorded = true;
      }
    {
      TimerOutput::Scope ti(timer, "Explicit: internal forces");
      internal = 0.;
      system.continuum->assemble(c, internal, nullptr);
      // every explicit step is accepted
      system.continuum->commit(c);
    }

    TimerOutput::Scope tc(timer, "Explicit: contact and loads");
    external         = 0.;
    double body_work = 0.;
    if (system.body_force)
      {
        // trapezoidal work of the body force over the step
        const TrilinosWrappers::MPI::Vector old_forces = body_forces;
        body_forces                                    = 0.;
        system.body_force->assemble(c, body_forces, nullptr);
        for (unsigned int i = 0; i < system.solution.locally_owned_size(); ++i)
          {
            const double du =
              system.solution.begin()[i] - body_solution.begin()[i];
            body_work -=
              (old_forces.begin()[i] + body_forces.begin()[i]) / 2. * du;
          }
        external += body_forces;
        body_solution = system.solution;
      }
    // the contact terms accept each evaluation (with the integral action of
    // Explicit/Contact multiplier steps)
    // the terms with a plain force path add into one array, passed into
    // external before any other term adds to it, so that every entry sums
    // its contributions in the order of the terms
    bool open = false;
    for (ForceTerm *term : system.other_terms)
      {
        if (term->adds_plain_forces() && !open)
          explicit_forces.start(external);
        else if (!term->adds_plain_forces() && open)
          explicit_forces.finish(external);
        open = term->adds_plain_forces();
        term->assemble(c, external, nullptr);
      }
    if (open)
      explicit_forces.finish(external);
    external.compress(VectorOperation::add);
    const ContactResults contact = system.contact_results();
    system.punch_control.observe(
      contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    system.lower_control.observe(
      contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);

    // the account of the loads: work of the moving upper punch (its normal
    // force along its travel, its friction along its lateral motion)
    const unsigned int upper = static_cast<unsigned int>(ToolKind::upper_punch);
    const double       position = system.upper_punch_position(scene_time);
    const double       lateral  = interpolate(system.lateral_table, scene_time);
    if (scene_increment > 0.)
      {
        explicit_work.tools +=
          (explicit_work.upper_force + contact.tools.normal_force[upper]) / 2. *
            (explicit_work.upper_position - position) +
          (explicit_work.upper_friction[0] +
           contact.tools.friction_force[upper][0]) /
            2. * (lateral - explicit_work.lateral);
        explicit_work.body += Utilities::MPI::sum(body_work, comm);
        // the lower punch's rise (ejection) times its force at the end of
        // the step: over one explicit step the force changes little
        const unsigned int lower =
          static_cast<unsigned int>(ToolKind::lower_punch);
        explicit_work.tools +=
          contact.tools.normal_force[lower] *
          (system.lower_punch_position(scene_time) -
           system.lower_punch_position(scene_time - scene_increment));
        // the die's axial force on the particles along its axial motion
        explicit_work.tools +=
          contact.tools
            .axial_force[static_cast<unsigned int>(ToolKind::die_wall)] *
          (interpolate(system.die_table, scene_time) -
           interpolate(system.die_table, scene_time - scene_increment));
      }
    explicit_work.upper_force    = contact.tools.normal_force[upper];
    explicit_work.upper_friction = contact.tools.friction_force[upper];
    explicit_work.upper_position = position;
    explicit_work.lateral        = lateral;
    explicit_work.friction +=
      contact.tools.friction_work + contact.particles.friction_work;
    explicit_work.multipliers +=
      contact.tools.multiplier_work + contact.particles.multiplier_work;
    explicit_work.contact_energy =
      contact.tools.elastic_energy + contact.particles.elastic_energy;
    // friction measures the slip of the next step from here
    system.committed_ghosted = system.solution_ghosted;

    // time-weighted sums of the forces and of their first moments in scene
    // time, for the least-squares line over the interval
    for (const double tau : {0., scene_time})
      {
        const double    w   = (tau == 0. ? dt : dt * scene_time);
        ContactResults &sum = (tau == 0. ? interval_sum : interval_moment);
        for (unsigned int k = 0; k < n_tool_kinds; ++k)
          {
            sum.tools.normal_force[k] += w * contact.tools.normal_force[k];
            sum.tools.axial_force[k] += w * contact.tools.axial_force[k];
            sum.tools.friction_force[k] += w * contact.tools.friction_force[k];
          }
        sum.particles.normal_force += w * contact.particles.normal_force;
        sum.particles.friction_force += w * contact.particles.friction_force;
      }
    ContactResults &sum = interval_sum;
    sum.tools.max_penetration =
      std::max(sum.tools.max_penetration, contact.tools.max_penetration);
    sum.particles.max_penetration = std::max(sum.particles.max_penetration,
                                             contact.particles.max_penetration);
    sum.tools.n_active            = contact.tools.n_active;
    sum.tools.n_slip              = contact.tools.n_slip;
    sum.particles.n_active        = contact.particles.n_active;
    sum.particles.n_slip          = contact.particles.n_slip;
    sum.particles.contact_area    = contact.particles.contact_area;
    interval_weight[0] += dt;
    interval_weight[1] += dt * scene_time;
    interval_weight[2] += dt * scene_time * scene_time;
  }



  ContactResults
  ExplicitDriver::advance(const double time,
                          const unsigned int /*step*/,
                          StepStatistics &s)
  {
    interval_sum    = ContactResults();
    interval_moment = ContactResults();
    interval_weight = {{0., 0., 0.}};
    // half the force's gap to the target per station: the station's force
    // lags its move, and closing all of it overshoots
    system.plan_punches(time, system.current_time, 0.5);
    // the last step's forces are evaluated at the station: they record
    record_time      = time;
    station_recorded = false;
    explicit_account = explicit_dynamics->advance(*this, system.solution, time);
    record_time      = -1.;
    system.current_time  = time;
    system.current_upper = system.upper_punch_position(time);
    system.update_ghosts();

    // each force at the station from the least-squares line through its
    // values over the interval: it filters the vibrations like a mean, but
    // without the mean's lag of half an interval behind a rising force
    const auto [S0, S1, S2] = interval_weight;
    const double det        = S0 * S2 - S1 * S1;
    const bool   line       = det > 1e-12 * S0 * S2;
    const auto   at_station = [&](const auto &sum, const auto &moment) {
      if (!line)
        return std::decay_t<decltype(sum)>(sum / S0);
      const auto slope = (S0 * moment - S1 * sum) / det;
      return std::decay_t<decltype(sum)>((sum - S1 * slope) / S0 +
                                         time * slope);
    };
    ContactResults        fit = interval_sum;
    const ContactResults &m   = interval_moment;
    for (unsigned int k = 0; k < n_tool_kinds; ++k)
      {
        fit.tools.normal_force[k] =
          at_station(interval_sum.tools.normal_force[k],
                     m.tools.normal_force[k]);
        fit.tools.axial_force[k] =
          at_station(interval_sum.tools.axial_force[k], m.tools.axial_force[k]);
        fit.tools.friction_force[k] =
          at_station(interval_sum.tools.friction_force[k],
                     m.tools.friction_force[k]);
      }
    fit.particles.normal_force =
      at_station(interval_sum.particles.normal_force, m.particles.normal_force);
    // contact only presses: where contacts open within the interval (a
    // punch withdrawn), the line through a falling force and then zeros
    // runs below zero at the station
    for (double &f : fit.tools.normal_force)
      f = std::max(f, 0.);
    fit.particles.normal_force = std::max(fit.particles.normal_force, 0.);
    fit.particles.friction_force =
      at_station(interval_sum.particles.friction_force,
                 m.particles.friction_force);
    system.punch_control.accept(
      fit.tools.normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    system.lower_control.accept(
      fit.tools.normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);
    // the explicit columns of the station's statistics
    const ExplicitDynamics::Account &a = explicit_account;
    const ExplicitWork              &w = explicit_work;
    s.increments                       = a.interval_steps;
    s.explicit_steps                   = a.steps;
    s.time_step                        = a.step;
    s.kinetic_energy                   = a.kinetic;
    s.internal_work                    = a.internal;
    s.damping_work                     = a.damping;
    s.friction_work                    = w.friction;
    s.contact_energy                   = w.contact_energy;
    s.external_work                    = w.tools + w.body;
    s.multiplier_work                  = w.multipliers;
    s.added_mass                       = lumped_mass->added_mass_fraction();
    s.energy_balance                   = s.external_work + s.multiplier_work -
                       (s.kinetic_energy + s.internal_work + s.damping_work +
                        s.friction_work + s.contact_energy);
    return fit;
  }
} // namespace densify
