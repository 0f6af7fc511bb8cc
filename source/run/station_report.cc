// The report of a run at each station: the rows of statistics.csv and
// particles.csv, the graphics, the progress line and the warnings.
#include <deal.II/base/mpi.h>

#include <densify/postprocess/compact_envelope.h>
#include <densify/postprocess/compaction_curve.h>
#include <densify/postprocess/run_log.h>
#include <densify/run/checkpoint.h>
#include <densify/run/station_report.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>

namespace densify
{
  StationReport::StationReport(const Parameters   &parameters,
                               MultiBodySystem    &system,
                               ConditionalOStream &pcout,
                               TimerOutput        &timer)
    : prm(parameters)
    , system(system)
    , pcout(pcout)
    , timer(timer)
    , comm(system.comm)
    , this_rank(Utilities::MPI::this_mpi_process(system.comm))
    , has_density(parameters.tools.die_enabled &&
                  parameters.tools.lower_enabled &&
                  parameters.tools.upper_enabled)
  {}



  double
  StationReport::density(const double volume, const double gap) const
  {
    const double die_area =
      numbers::PI * std::pow(prm.tools.die_diameter / 2, 2);
    return has_density ? volume / (die_area * gap) :
                         std::numeric_limits<double>::quiet_NaN();
  }



  void
  StationReport::start()
  {
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    pcout << "Densify: " << system.particles.size() << " particle(s), "
          << system.triangulation.n_active_cells() << " tetrahedra, "
          << system.dof_handler.n_dofs() << " DoFs (P" << prm.mesh.degree
          << "), " << n_ranks << " MPI rank(s)" << std::endl;
    {
      // every distinct material law once, then the tools and the solver
      std::vector<std::string> laws;
      for (const auto &m : system.particle_material)
        if (std::find(laws.begin(), laws.end(), m->name()) == laws.end())
          laws.push_back(m->name());
      pcout << "Active effects: " << describe_effects(system.effects, laws, prm)
            << std::endl;
      if (!prm.fidelity_summary.empty())
        pcout << "Fidelity: " << prm.fidelity_summary << std::endl;
    }
    {
      double v0 = 0;
      for (const double v : system.particle_volumes())
        v0 += v;
      if (has_density)
        pcout << "Initial relative density " << std::fixed
              << std::setprecision(2)
              << 100 * density(v0, system.upper_initial - system.lower_initial)
              << " % (particle volume of the mesh " << std::setprecision(4)
              << v0 << " mm^3)" << std::defaultfloat << std::endl;
    }
    for (const ParticleMeasure &m : system.measure_particles())
      initial_volumes.push_back(m.volume);
  }



  void
  StationReport::open(const bool resume, const unsigned int first_step)
  {
    const std::string statistics_name =
      prm.output.directory + "/statistics.csv";
    const std::string particle_name = prm.output.directory + "/particles.csv";
    // what rank 0 cannot write ends the run on every rank
    std::string error;
    if (this_rank == 0)
      try
        {
          const bool append = resume &&
                              std::filesystem::exists(statistics_name) &&
                              std::filesystem::exists(particle_name);
          if (append)
            {
              Checkpoint::truncate_rows(statistics_name, first_step - 1);
              Checkpoint::truncate_rows(particle_name, first_step - 1);
            }
          statistics_writer =
            std::make_unique<StatisticsWriter>(statistics_name, append);
          particle_writer =
            std::make_unique<ParticleTableWriter>(particle_name, append);
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
    error = first_error(error, comm);
    if (!error.empty())
      throw std::runtime_error(error);
  }



  std::pair<std::vector<unsigned int>, std::vector<double>>
  StationReport::station_contacts(const Driver &driver) const
  {
    const ContactRecord *record = driver.station_record();
    if (record == nullptr)
      return {system.contact_partners(),
              system.particle_tool_forces(ToolKind::die_wall)};
    std::vector<double> die_force = record->die_force;
    Utilities::MPI::sum(die_force, comm, die_force);
    return {system.particle_contact ?
              system.particle_contact->partners_of(record->pairs) :
              std::vector<unsigned int>(system.particles.size(), 0),
            die_force};
  }



  void
  StationReport::record(StepStatistics       &s,
                        const ContactResults &results,
                        const Driver         &driver,
                        const double          upper_before,
                        const double          lower_before,
                        const Timer          &step_timer)
  {
    const double time   = s.time;
    const double before = prm.time.end_time * (s.step - 1) / prm.time.n_steps;
    const ToolContactResult &contact = results.tools;
    // where the step left the punches (a force-controlled punch is where
    // its force took it)
    const double upper         = system.upper_punch_position(time);
    const double lower         = system.lower_punch_position(time);
    s.punch_displacement       = system.upper_initial - upper;
    s.lower_punch_displacement = lower - system.lower_initial;
    s.die_displacement =
      interpolate(system.die_table, time) - interpolate(system.die_table, 0.);
    {
      // the lower punch's rise in the die (a die lowered past a held
      // compact ejects it too); a lower punch under force control presses:
      // its rise closes the gap as the upper punch's advance does
      const double rise = lower - lower_before -
                          (interpolate(system.die_table, time) -
                           interpolate(system.die_table, before));
      const bool pressing = system.lower_control.force_controlled(time);
      double     advance  = upper_before - upper + (pressing ? rise : 0.);
      // under force control the target's trend decides: a flat target
      // holds, whatever the punch's creep or elastic relaxation
      const PunchControl *controlled =
        system.punch_control.force_controlled(time) ? &system.punch_control :
        pressing                                    ? &system.lower_control :
                                                      nullptr;
      if (controlled != nullptr)
        {
          const double a     = controlled->target(before),
                       b     = controlled->target(time);
          const double still = 1e-9 * std::max({std::abs(a), std::abs(b), 1.});
          advance            = b - a > still ? 1. : b - a < -still ? -1. : 0.;
        }
      s.phase =
        static_cast<unsigned int>(press_phase(advance, pressing ? 0. : rise));
    }

    const auto upper_kind   = static_cast<unsigned int>(ToolKind::upper_punch);
    const auto lower_kind   = static_cast<unsigned int>(ToolKind::lower_punch);
    const auto die_kind     = static_cast<unsigned int>(ToolKind::die_wall);
    s.upper_punch_force     = contact.normal_force[upper_kind];
    s.lower_punch_force     = contact.normal_force[lower_kind];
    s.die_wall_force        = contact.axial_force[die_kind];
    s.die_wall_radial_force = contact.normal_force[die_kind];
    s.max_penetration =
      std::max(contact.max_penetration, results.particles.max_penetration);
    s.particle_contact_force = results.particles.normal_force;
    s.upper_punch_friction   = contact.friction_force[upper_kind].norm();
    s.lower_punch_friction   = contact.friction_force[lower_kind].norm();
    s.slipping_points        = contact.n_slip + results.particles.n_slip;
    system.update_ghosts();
    const auto [partners, die_force] = station_contacts(driver);
    for (const unsigned int n : partners)
      s.contact_pairs += n;
    s.contact_pairs /= 2;
    s.coordination_number = 2. * s.contact_pairs / system.particles.size();
    s.contact_area_fraction =
      2. * results.particles.contact_area /
      particle_surface_area(system.dof_handler, system.solution_ghosted);
    s.pole_force = system.pole_springs ? system.pole_springs->force() : 0.;
    std::vector<ParticleMeasure> measures;
    {
      TimerOutput::Scope t(timer, "Output: particle measures");
      measures = system.measure_particles(true);
    }
    for (const ParticleMeasure &m : measures)
      s.particle_volume += m.volume;
    // what rank 0 cannot write (e.g. a full disk) ends the run on every
    // rank; the rows written before stay complete
    std::string write_failure;
    if (this_rank == 0)
      write_failure = particle_writer->write(s.step,
                                             system.particles,
                                             measures,
                                             initial_volumes,
                                             partners,
                                             die_force);
    s.relative_density = density(s.particle_volume, upper - lower);
    {
      const DieStresses stress =
        die_stresses(s.upper_punch_force,
                     s.lower_punch_force,
                     s.die_wall_radial_force,
                     prm.tools.die_enabled ? prm.tools.die_diameter : 0.,
                     prm.tools.lower_enabled && prm.tools.upper_enabled ?
                       upper - lower :
                       0.);
      s.upper_punch_stress = stress.upper_punch;
      s.lower_punch_stress = stress.lower_punch;
      s.die_wall_pressure  = stress.die_wall;
      s.radial_axial_ratio = stress.radial_axial_ratio;
      const CompactEnvelope envelope =
        compact_envelope(system.dof_handler, system.solution_ghosted);
      s.compact_height   = envelope.top - envelope.bottom;
      s.compact_diameter = 2 * envelope.radius;
      s.envelope_density =
        s.particle_volume /
        (numbers::PI * envelope.radius * envelope.radius * s.compact_height);
    }
    s.plastic_work = system.continuum->plastic_work(*system.mapping);
    const SmallestCellVolume smallest =
      smallest_cell_volume(system.dof_handler,
                           *system.mapping,
                           system.solution_ghosted);
    s.min_cell_volume_ratio = smallest.ratio;

    if (prm.output.interval > 0 &&
        (s.step % prm.output.interval == 0 || s.step == prm.time.n_steps))
      write_graphics(s.step, time, measures);

    s.step_seconds = step_timer.wall_time();
    s.wall_seconds += s.step_seconds;
    step_statistics.push_back(s);
    if (statistics_writer && write_failure.empty())
      write_failure = statistics_writer->write(s);
    write_failure = first_error(write_failure, comm);
    if (!write_failure.empty())
      throw std::runtime_error(write_failure);
    if (system.effects.method == Method::explicit_dynamics)
      warn_penetration(s);
    warn_cell_volume(s.step, smallest);
  }



  void
  StationReport::progress(const StepStatistics &s,
                          const double          seconds_left) const
  {
    pcout << progress_line(s,
                           prm.time.n_steps,
                           system.pole_springs != nullptr,
                           has_density,
                           system.effects.method == Method::explicit_dynamics,
                           seconds_left)
          << std::endl;
  }



  void
  StationReport::summarise() const
  {
    if (!statistics_writer)
      return;
    const std::string statistics_name =
      prm.output.directory + "/statistics.csv";
    try
      {
        if (has_density)
          pcout << compaction_summary(read_loading_curve(
            statistics_name, system.upper_initial - prm.tools.lower_position));
        pcout << contact_summary(statistics_name)
              << springback_summary(statistics_name)
              << ejection_summary(statistics_name);
      }
    catch (const std::exception &)
      {
        // a statistics.csv of an older version: no summary
      }
  }



  void
  StationReport::write_graphics(const unsigned int                  step,
                                const double                        time,
                                const std::vector<ParticleMeasure> &measures)
  {
    TimerOutput::Scope t(timer, "Output: graphics");
    system.update_ghosts();
    graphics.write(step,
                   time,
                   system.dof_handler,
                   *system.mapping,
                   prm.mesh.degree,
                   system.solution_ghosted,
                   system.particle_material,
                   system.continuum->has_history() ?
                     &system.continuum->committed() :
                     nullptr,
                   system.continuum->states_per_cell(),
                   system.continuum->fbar(),
                   system.tool_contact.get(),
                   system.particle_contact.get(),
                   system.effects.any_friction(),
                   &measures,
                   prm.output.directory,
                   comm);
  }



  void
  StationReport::warn_cell_volume(const unsigned int        step,
                                  const SmallestCellVolume &smallest)
  {
    // once per run: the ratio stays low once a cell has collapsed
    if (cell_volume_warned || !(smallest.ratio < 0.2))
      return;
    cell_volume_warned = true;
    pcout << "  warning: a cell's volume fell to V/V0 = "
          << std::setprecision(3) << smallest.ratio << " (below 0.2) at step "
          << step << " in particle " << smallest.particle << " at ("
          << smallest.centre
          << ") mm (reference position; printed once, statistics.csv has "
             "min_cell_volume_ratio of every step): its forces are biased; "
             "raise Mesh/Cell volume barrier from "
          << prm.mesh.cell_volume_barrier << std::endl;
  }



  void
  StationReport::warn_penetration(const StepStatistics &s)
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
