// One row of statistics per load step, and the statistics.csv writer.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace densify
{
  /// What happened in one load step (forces in N, positive in compression).
  struct StepStatistics
  {
    /// Load step number, 1 ... N.
    unsigned int step = 0;
    /// Time at the end of the step (s).
    double time = 0.;
    /// Downward displacement of the upper punch (mm).
    double punch_displacement = 0.;
    /// Normal force on the upper punch (N).
    double upper_punch_force = 0.;
    /// Normal force on the lower punch (N).
    double lower_punch_force = 0.;
    /// Axial force the die wall takes (N); upper = lower + die wall.
    double die_wall_force = 0.;
    /// Particle volume / (die area x punch gap); NaN without die or punches.
    double relative_density = 0.;
    /// Newton iterations of the step, over all multiplier updates.
    unsigned int newton_iterations = 0;
    /// CG iterations of the step.
    unsigned int linear_iterations = 0;
    /// Wall time since the start of the run (s).
    double wall_seconds = 0.;
    /// Sum of the normal (radial) contact forces on the die wall (N).
    double die_wall_radial_force = 0.;
    /// l1 norm of the force the stabilisation put into the last Newton
    /// correction (N); it is not part of the converged equilibrium.
    double stabilisation_force = 0.;
    /// Largest penetration into a tool at the end of the step (mm).
    double max_penetration = 0.;
    /// Multiplier updates in this step.
    unsigned int augmentations = 0;
    /// Total particle volume (mm^3).
    double particle_volume = 0.;
    /// Wall time of this step (s).
    double step_seconds = 0.;
    /// Increments the step took (1 without cut-back).
    unsigned int increments = 0;
    /// Increments rolled back and retried with half the size.
    unsigned int cutbacks = 0;
    /// Total normal force between particles (N, each contact once).
    double particle_contact_force = 0.;
    /// Number of particle pairs in contact.
    unsigned int contact_pairs = 0;
    /// Number of contact quadrature points that slip (tools and particles).
    unsigned int slipping_points = 0;
    /// Friction (tangential) force of the upper and of the lower punch on
    /// the particles (N, magnitude).
    double upper_punch_friction = 0., lower_punch_friction = 0.;
    /// l2 norm of the horizontal forces of the pole springs (N; 0 unless
    /// Contact/Hold poles on axis).
    double pole_force = 0.;
    /// Plastic work of the particles so far (mJ).
    double plastic_work = 0.;
    /// Explicit dynamics (0 for implicit runs): explicit steps since the
    /// start, the last time step (s), the added mass over the physical mass.
    unsigned long long explicit_steps = 0;
    double             time_step = 0., added_mass = 0.;
    /// Explicit dynamics' energy account (mJ; 0 for implicit runs): kinetic
    /// energy, work of the internal forces (elastic energy + plastic work),
    /// friction and damping work, elastic energy of the contact springs,
    /// work of the moving tools and body forces, the energy the contact
    /// multipliers' updates put into the springs, and the balance
    /// external + multiplier - (kinetic + internal + friction + damping +
    /// contact).
    double kinetic_energy = 0., internal_work = 0., friction_work = 0.,
           damping_work = 0., contact_energy = 0., external_work = 0.,
           energy_balance = 0., multiplier_work = 0.;
    /// Increments retried with the pseudo-transient continuation
    /// (Solver/Pseudo-transient continuation = fallback).
    unsigned int continuations = 0;
    /// Consistency solves that did not converge (the progress line only).
    unsigned int failed_checks = 0;
    /// Newton iterations of the solves that did not converge (their
    /// increments retried with the continuation or cut back; not in
    /// newton_iterations).
    unsigned int failed_newton_iterations = 0;
    /// The smallest own volume ratio V/V0 of any cell at the end of the
    /// step (smallest_cell_volume()).
    double min_cell_volume_ratio = 1.;
    /// Mean axial stress of the upper and of the lower punch (MPa: force
    /// over the die's bore area; NaN without die).
    double upper_punch_stress = 0., lower_punch_stress = 0.;
    /// Mean radial pressure on the die wall between the punches (MPa: the
    /// radial force over pi x diameter x punch gap; NaN without die or a
    /// pair of punches), and its ratio to upper_punch_stress.
    double die_wall_pressure = 0., radial_axial_ratio = 0.;
    /// Height and diameter (mm) of the compact's envelope, the bounding
    /// cylinder about the die axis of the deformed particles
    /// (compact_envelope()), and the particle volume over its volume.
    double compact_height = 0., compact_diameter = 0., envelope_density = 0.;
    /// The press cycle's phase over the step, as a number (PressPhase).
    unsigned int phase = 0;
    /// The lower punch's rise from its start (mm; the ejection's travel).
    double lower_punch_displacement = 0.;
    /// The die's upward displacement from its start (mm).
    double die_displacement = 0.;
    /// Mean coordination number: twice the particle pairs in contact over
    /// the number of particles (the tools not counted).
    double coordination_number = 0.;
    /// The share of the particles' current surface in contact with another
    /// particle (flat facets; the tools not counted).
    double contact_area_fraction = 0.;
  };

  /// The phase of a press cycle in a step; its number is the statistics.csv
  /// column `phase`. Under force control the target's trend stands for the
  /// punch's motion (the Simulator passes it to press_phase()).
  enum class PressPhase : unsigned int
  {
    /// The upper punch advances (with or without the lower one rising).
    load = 0,
    /// Neither punch moves.
    hold = 1,
    /// The upper punch withdraws while the lower punch stays.
    unload = 2,
    /// The lower punch rises while the upper punch does not advance: the
    /// compact is pushed out of the die.
    eject = 3
  };

  /**
   * The phase of a step in which the upper punch advanced (moved down) by
   * @p upper_advance and the lower punch rose by @p lower_rise (mm).
   */
  PressPhase
  press_phase(const double upper_advance, const double lower_rise);

  /// The phase's name: "load", "hold", "unload" or "eject".
  std::string
  phase_name(const PressPhase phase);

  /**
   * Writes statistics.csv: a header line, then one row per step, flushed
   * at once so that the file is valid whenever a run stops.
   */
  class StatisticsWriter
  {
  public:
    /// Open (truncate) @p filename and write the header; with @p append,
    /// append rows to the existing file (a resumed run).
    StatisticsWriter(const std::string &filename, const bool append = false);

    /// Append one row. Returns "" or, if it cannot be written (e.g. a full
    /// disk), the error naming the file and the cause, with the file cut back
    /// to its complete rows.
    std::string
    write(const StepStatistics &s);

    /// The header line (column names, comma-separated).
    static std::string
    header();

  private:
    std::string   filename;
    std::ofstream out;
  };
} // namespace densify
