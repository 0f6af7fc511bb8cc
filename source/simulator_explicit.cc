// The Simulator as the system of the explicit integrator: lumped mass,
// forces without a tangent, and the energy account of the loads.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <densify/postprocess/quasi_static_guard.h>
#include <densify/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <type_traits>

namespace densify
{
  namespace
  {
    /// The area a punch presses (mm^2): the die's bore, or without a die
    /// the particles' cross-sections.
    double
    pressed_area(const std::vector<Particle> &particles,
                 const bool                   die,
                 const double                 die_diameter)
    {
      if (die)
        return numbers::PI * std::pow(die_diameter / 2., 2);
      double area = 0.;
      for (const Particle &p : particles)
        area += numbers::PI * std::pow(p.diameter / 2., 2);
      return area;
    }
  } // namespace



  std::vector<double>
  Simulator::setup_explicit(const double tangential_ratio)
  {
    lumped_mass = std::make_unique<LumpedMass>(dof_handler,
                                               particle_material,
                                               effects.mass_scaling,
                                               tangential_ratio,
                                               cell_volume_weights);
    lumped_mass->set_cell_volume_barrier(cell_volume_barrier);
    explicit_dynamics =
      std::make_unique<ExplicitDynamics>(prm.explicit_dynamics,
                                         prm.time.end_time,
                                         comm);
    // the mass (scaled for the target step), then the contact penalty that
    // fits the elements' stable step
    const bool   scaled   = (effects.mass_scaling != MassScaling::none);
    const double required = scaled ? prm.explicit_dynamics.loading_time /
                                       prm.explicit_dynamics.n_steps /
                                       prm.explicit_dynamics.safety :
                                     0.;
    TrilinosWrappers::MPI::Vector mass;
    update_ghosts();
    lumped_mass->update(solution_ghosted, required, mass);
    // the cell bound calibrated by the mesh's measured largest frequency,
    // with a margin for the power iteration (which approaches it from
    // below) and for the cells' later distortion
    lumped_mass->calibrate(largest_frequency2(mass), calibration_margin, true);
    lumped_mass->update(solution_ghosted, required, mass);
    calibrated_bound   = lumped_mass->bound_frequency2();
    calibration_target = lumped_mass->calibration_factor();
    // Explicit/Contact stiffness, per particle from its material
    std::vector<double>           stiffness;
    std::map<std::string, double> by_material;
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        stiffness.push_back(
          explicit_contact_stiffness(prm.explicit_dynamics.contact_stiffness,
                                     *particle_material[p]));
        by_material[particles[p].material] = stiffness.back();
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
      pressed_area(particles,
                   effects.has_tool(ToolKind::die_wall),
                   prm.tools.die_diameter);
    std::vector<double> diameters;
    for (const Particle &p : particles)
      diameters.push_back(p.diameter);
    explicit_dynamics->set_damping(2. * prm.explicit_dynamics.damping_ratio *
                                   lumped_mass->lowest_frequency(diameters));
    search_solution.reinit(locally_owned, comm);
    body_forces.reinit(locally_owned, comm);
    body_solution.reinit(locally_owned, comm);
    return explicit_penalty;
  }



  double
  Simulator::largest_frequency2(const TrilinosWrappers::MPI::Vector &mass)
  {
    TimerOutput::Scope t(timer, "Explicit: largest frequency");
    // power iteration on M^-1 K with K the cells' elastic stiffness in their
    // current shape (LumpedMass::stiffness_product); a start vector that
    // depends on the vertices' positions only (not on the DoF numbering,
    // which depends on the number of ranks), so that any number of ranks
    // finds the same; a measurement during the run starts from the last
    // one's vector, which is close to the new mode: fewer iterations
    TrilinosWrappers::MPI::Vector x(locally_owned, comm), Kx(x);
    TrilinosWrappers::MPI::Vector x_ghosted(solution_ghosted);
    update_ghosts();
    const bool warm = frequency_mode.size() == x.size();
    if (warm)
      x = frequency_mode;
    else
      {
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int c = 0; c < 3; ++c)
                {
                  const types::global_dof_index i =
                    cell->vertex_dof_index(v, c);
                  const Point<3> &X = cell->vertex(v);
                  if (locally_owned.is_element(i))
                    x(i) =
                      std::sin(1. + 7. * X[0] + 9. * X[1] + 11. * X[2] + c);
                }
        x.compress(VectorOperation::insert);
      }
    double omega2 = 0.;
    for (unsigned int it = 0; it < (warm ? 15u : 40u); ++it)
      {
        x_ghosted = x;
        lumped_mass->stiffness_product(solution_ghosted, x_ghosted, Kx);
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
  Simulator::update_mass(const double                   required_step,
                         TrilinosWrappers::MPI::Vector &mass)
  {
    TimerOutput::Scope t(timer, "Explicit: mass");
    update_ghosts();
    if (lumped_mass->calibration_factor() < calibration_target)
      lumped_mass->set_calibration_factor(
        std::min(calibration_target,
                 calibration_rise * lumped_mass->calibration_factor()));
    double stable = lumped_mass->update(solution_ghosted, required_step, mass);
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
        stable = lumped_mass->update(solution_ghosted, required_step, mass);
        calibrated_bound = lumped_mass->bound_frequency2();
        // in log.txt only: a line per measurement would crowd the progress
        if (this_rank == 0)
          log_file << "Explicit dynamics: stable step measured anew at t = "
                   << load_time << ": calibration " << before << " -> "
                   << calibration_target << " (applied "
                   << lumped_mass->calibration_factor() << "), added mass "
                   << 100. * lumped_mass->added_mass_fraction() << " %"
                   << (fell ?
                         " (a fall: measured again from the start vector)" :
                         "")
                   << std::endl;
      }
    return stable;
  }



  void
  Simulator::forces(const TrilinosWrappers::MPI::Vector &u,
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
      for (PunchControl *control : {&punch_control, &lower_control})
        control->drive(scene_time,
                       scene_increment,
                       dt,
                       punch_stiffness * dt * dt,
                       explicit_dynamics->damping_coefficient());
    apply_loads(scene_time, scene_increment);
    if (&u != &solution)
      solution = u;
    update_ghosts();
    if (particle_contact)
      {
        // a new search once two points may have closed by more than its
        // margin since the last one (each moved at most max |u - u_search|)
        double moved = 0.;
        for (unsigned int i = 0; i < solution.locally_owned_size(); ++i)
          moved = std::max(moved,
                           std::abs(solution.begin()[i] -
                                    search_solution.begin()[i]));
        if (Utilities::MPI::max(moved, comm) * 2. * std::sqrt(3.) >
            search_margin)
          {
            TimerOutput::Scope ts(timer, "Contact: search");
            particle_contact->update_search(solution_ghosted, search_margin);
            search_solution = solution;
          }
      }
    // the values read once into plain arrays for the element loops
    explicit_values.gather(solution_ghosted);
    explicit_committed.gather(committed_ghosted);
    AssemblyContext c  = context();
    c.values           = &explicit_values;
    c.committed_values = &explicit_committed;
    c.plain_forces     = &explicit_forces;
    // the pass at the station records its contact pairs and die forces for
    // the station's statistics
    if (scene_time == record_time)
      {
        station_record.pairs.clear();
        station_record.die_force.assign(particles.size(), 0.);
        c.record         = &station_record;
        station_recorded = true;
      }
    {
      TimerOutput::Scope ti(timer, "Explicit: internal forces");
      internal = 0.;
      continuum->assemble(c, internal, nullptr);
      // every explicit step is accepted
      continuum->commit(c);
    }

    TimerOutput::Scope tc(timer, "Explicit: contact and loads");
    external         = 0.;
    double body_work = 0.;
    if (body_force)
      {
        // trapezoidal work of the body force over the step
        const TrilinosWrappers::MPI::Vector old_forces = body_forces;
        body_forces                                    = 0.;
        body_force->assemble(c, body_forces, nullptr);
        for (unsigned int i = 0; i < solution.locally_owned_size(); ++i)
          {
            const double du = solution.begin()[i] - body_solution.begin()[i];
            body_work -=
              (old_forces.begin()[i] + body_forces.begin()[i]) / 2. * du;
          }
        external += body_forces;
        body_solution = solution;
      }
    // the contact terms accept each evaluation (with the integral action of
    // Explicit/Contact multiplier steps)
    // the terms with a plain force path add into one array, passed into
    // external before any other term adds to it, so that every entry sums
    // its contributions in the order of the terms
    bool open = false;
    for (ForceTerm *term : other_terms)
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
    const ContactResults contact = contact_results();
    punch_control.observe(
      contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    lower_control.observe(
      contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);

    // the account of the loads: work of the moving upper punch (its normal
    // force along its travel, its friction along its lateral motion)
    const unsigned int upper = static_cast<unsigned int>(ToolKind::upper_punch);
    const double       position = upper_punch_position(scene_time);
    const double       lateral  = interpolate(lateral_table, scene_time);
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
          (lower_punch_position(scene_time) -
           lower_punch_position(scene_time - scene_increment));
        // the die's axial force on the particles along its axial motion
        explicit_work.tools +=
          contact.tools
            .axial_force[static_cast<unsigned int>(ToolKind::die_wall)] *
          (interpolate(die_table, scene_time) -
           interpolate(die_table, scene_time - scene_increment));
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
    committed_ghosted = solution_ghosted;

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



  Simulator::ContactResults
  Simulator::advance_explicit(const double       time,
                              const unsigned int step,
                              StepStatistics    &s)
  {
    (void)step;
    interval_sum    = ContactResults();
    interval_moment = ContactResults();
    interval_weight = {{0., 0., 0.}};
    // half the force's gap to the target per station: the station's force
    // lags its move, and closing all of it overshoots
    plan_punches(time, current_time, 0.5);
    // the last step's forces are evaluated at the station: they record
    record_time      = time;
    station_recorded = false;
    explicit_account = explicit_dynamics->advance(*this, solution, time);
    record_time      = -1.;
    current_time     = time;
    current_upper    = upper_punch_position(time);
    update_ghosts();
    s.increments = explicit_account.interval_steps;

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
    punch_control.accept(
      fit.tools.normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    lower_control.accept(
      fit.tools.normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);
    return fit;
  }



  QuasiStaticLimits
  Simulator::quasi_static_limits() const
  {
    QuasiStaticLimits limits;
    // high-speed compaction (no mass scaling) has inertia by intent
    if (effects.method != Method::explicit_dynamics ||
        effects.mass_scaling == MassScaling::none)
      return limits;
    limits.kinetic_ratio       = prm.explicit_dynamics.max_kinetic_ratio;
    limits.force_imbalance     = prm.explicit_dynamics.max_force_imbalance;
    limits.force_control_error = prm.explicit_dynamics.max_force_control_error;
    // the guard judges from the force that gives the compact a mean axial
    // stress of a tenth of the weakest particle's initial yield stress (for
    // laws that do not yield, the stress of an elastic strain of 1e-3) over
    // the die's bore (without a die, over the particles' cross-sections):
    // below it a loose bed rearranges, and mass scaling makes that inertial
    // (the inertial number grows as the square root of the scaled density
    // over the pressure)
    double stress = std::numeric_limits<double>::infinity();
    for (const auto &material : particle_material)
      stress = std::min({stress,
                         material->initial_yield_stress(),
                         1e-3 * material->youngs_modulus()});
    limits.load_floor = 0.1 * stress *
                        pressed_area(particles,
                                     effects.has_tool(ToolKind::die_wall),
                                     prm.tools.die_diameter);
    return limits;
  }



  void
  Simulator::check_quasi_static(const StepStatistics &s,
                                QuasiStaticGuard     &guard)
  {
    std::string breach = guard.add(s);
    std::string advice = "raise Explicit/Number of steps (now " +
                         std::to_string(prm.explicit_dynamics.n_steps) + ")";
    // a loose bed that settles dynamically in the first stations: a slower
    // start gives them more explicit steps at the same total (the paper
    // scene at 10,000 steps stops at step 9 with the default ramp and runs
    // within the limits with 0.2, doc/performance.md)
    if (s.time <= 0.2 * prm.time.end_time &&
        prm.explicit_dynamics.ramp_fraction < 0.2)
      {
        std::ostringstream ramp;
        ramp << " or Explicit/Ramp fraction (now "
             << prm.explicit_dynamics.ramp_fraction
             << "; 0.2 starts the punch slower while a loose bed settles)";
        advice += ramp.str();
      }
    // a punch under force control that misses its target
    const double limit = prm.explicit_dynamics.max_force_control_error;
    for (const auto &[control, punch] :
         {std::make_pair(&punch_control, "upper"),
          std::make_pair(&lower_control, "lower")})
      if (breach.empty() && limit > 0. && control->miss() > limit)
        {
          std::ostringstream text;
          text << "the " << punch << " punch's force missed its target by "
               << std::setprecision(3) << 100. * control->miss()
               << " % of the larger of the target and the largest force so "
                  "far, above Explicit/Maximum force control error = "
               << 100. * limit << " %";
          breach = text.str();
          advice += ", or let the target change slowly (the punch presses "
                    "the compact with the target as a load, and a compact "
                    "that has too little time per station to follow it "
                    "lags or rings), or use Solver/Method = implicit";
        }
    if (breach.empty())
      return;
    std::ostringstream text;
    text << "the explicit run is no longer quasi-static at step " << s.step
         << " (punch " << s.punch_displacement << " mm): " << breach << "; "
         << advice;
    if (guard_snapshot.bytes.empty())
      text << "; no earlier station of this run was judged within the "
              "limits, so "
              "no checkpoint is written";
    else
      {
        store_checkpoint(guard_snapshot);
        text << "; the last station within them that was kept (step "
             << guard_snapshot.step << ") is in " << prm.output.directory
             << "/checkpoint/: continue from it with --resume and more steps";
      }
    throw std::runtime_error(text.str());
  }



  void
  Simulator::warn_penetration(const StepStatistics &s)
  {
    // once per run: an explicit run's penalty leaves the same penetration
    // station after station
    if (penetration_warned || !(s.max_penetration > prm.contact.gap_tolerance))
      return;
    penetration_warned = true;
    pcout << "  warning: penetration " << std::setprecision(3)
          << s.max_penetration
          << " mm above Contact/Gap tolerance = " << prm.contact.gap_tolerance
          << " mm at step " << s.step
          << " (printed once; statistics.csv has max_penetration of every "
             "step): ";
    // the multipliers remove a lasting penetration over about their number
    // of steps, not a passing one
    if (prm.explicit_dynamics.multiplier_steps == 0)
      pcout << "raise Explicit/Contact multiplier steps from 0 (e.g. 200) or "
               "Explicit/Contact stiffness";
    else
      pcout << "raise Explicit/Contact stiffness (Explicit/Contact multiplier "
               "steps = "
            << prm.explicit_dynamics.multiplier_steps
            << " removes a lasting penetration over about as many explicit "
               "steps)";
    pcout << std::endl;
  }
} // namespace densify
