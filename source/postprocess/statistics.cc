// The statistics.csv writer.
#include <densify/postprocess/statistics.h>
#include <densify/utilities.h>

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace densify
{



  StatisticsWriter::StatisticsWriter(const std::string &filename,
                                     const bool         append)
    : filename(filename)
  {
    if (append)
      extend_csv_columns(filename, header());
    out.open(filename, append ? std::ios::app : std::ios::trunc);
    if (!out)
      throw std::runtime_error("Output/Directory: " + write_error(filename));
    if (!append)
      {
        const std::string error =
          append_or_roll_back(out, filename, header() + "\n");
        if (!error.empty())
          throw std::runtime_error(error);
      }
  }



  std::string
  StatisticsWriter::header()
  {
    return "step,time,punch_displacement,upper_punch_force,lower_punch_force,"
           "die_wall_force,relative_density,newton_iterations,"
           "linear_iterations,wall_seconds,die_wall_radial_force,"
           "stabilisation_force,max_penetration,augmentations,"
           "particle_volume,step_seconds,increments,cutbacks,"
           "particle_contact_force,contact_pairs,slipping_points,"
           "upper_punch_friction,lower_punch_friction,pole_force,plastic_work,"
           "explicit_steps,time_step,added_mass,kinetic_energy,internal_work,"
           "friction_work,damping_work,contact_energy,external_work,"
           "energy_balance,multiplier_work,continuations,min_cell_volume_ratio,"
           "upper_punch_stress,lower_punch_stress,die_wall_pressure,"
           "radial_axial_ratio,compact_height,compact_diameter,"
           "envelope_density,phase,lower_punch_displacement,"
           "coordination_number,contact_area_fraction,die_displacement,"
           "failed_newton_iterations";
  }



  PressPhase
  press_phase(const double upper_advance, const double lower_rise)
  {
    // travel below a nanometre is the round-off of a step's end time
    // against a breakpoint of the tables, not motion
    constexpr double still = 1e-6;
    if (upper_advance > still)
      return PressPhase::load;
    if (lower_rise > still)
      return PressPhase::eject;
    return upper_advance < -still ? PressPhase::unload : PressPhase::hold;
  }



  std::string
  phase_name(const PressPhase phase)
  {
    switch (phase)
      {
        case PressPhase::load:
          return "load";
        case PressPhase::hold:
          return "hold";
        case PressPhase::unload:
          return "unload";
        default:
          return "eject";
      }
  }



  std::string
  StatisticsWriter::write(const StepStatistics &s)
  {
    std::ostringstream row;
    row << s.step << ',' << std::setprecision(10) << s.time << ','
        << s.punch_displacement << ',' << s.upper_punch_force << ','
        << s.lower_punch_force << ',' << s.die_wall_force << ','
        << s.relative_density << ',' << s.newton_iterations << ','
        << s.linear_iterations << ',' << std::setprecision(4) << s.wall_seconds
        << ',' << std::setprecision(10) << s.die_wall_radial_force << ','
        << std::setprecision(4) << s.stabilisation_force << ','
        << s.max_penetration << ',' << s.augmentations << ','
        << std::setprecision(10) << s.particle_volume << ','
        << std::setprecision(4) << s.step_seconds << ',' << s.increments << ','
        << s.cutbacks << ',' << std::setprecision(10)
        << s.particle_contact_force << ',' << s.contact_pairs << ','
        << s.slipping_points << ',' << s.upper_punch_friction << ','
        << s.lower_punch_friction << ',' << s.pole_force << ','
        << s.plastic_work << ',' << s.explicit_steps << ',' << s.time_step
        << ',' << s.added_mass << ',' << s.kinetic_energy << ','
        << s.internal_work << ',' << s.friction_work << ',' << s.damping_work
        << ',' << s.contact_energy << ',' << s.external_work << ','
        << s.energy_balance << ',' << s.multiplier_work << ','
        << s.continuations << ',' << std::setprecision(6)
        << s.min_cell_volume_ratio << ',' << std::setprecision(10)
        << s.upper_punch_stress << ',' << s.lower_punch_stress << ','
        << s.die_wall_pressure << ',' << s.radial_axial_ratio << ','
        << s.compact_height << ',' << s.compact_diameter << ','
        << s.envelope_density << ',' << s.phase << ','
        << s.lower_punch_displacement << ',' << s.coordination_number << ','
        << s.contact_area_fraction << ',' << s.die_displacement << ','
        << s.failed_newton_iterations << '\n';
    return append_or_roll_back(out, filename, row.str());
  }
} // namespace densify
