// All run-time parameters of Densify, one struct per .prm subsection.
#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// Subsection "Particles": where the particles are and what they are made of.
  struct ParticleParameters
  {
    /// "list" (Centres or the particle file), "hexagonal layer", "random
    /// layer" or "deposited" (generated in the die on the lower punch).
    std::string packing = "list";
    /// Particles of the random layer and of the deposited bed.
    unsigned int n_particles = 43;
    /// Seed of the random layer and of the deposited bed.
    unsigned int packing_seed = 1;
    /// Diameters of the deposited bed: "equal", "uniform" or "log-normal".
    std::string size_distribution = "equal";
    /// Standard deviation of ln d of the log-normal distribution.
    double diameter_spread = 0.2;
    /// Pour the deposited bed up to this height above the lower punch (mm;
    /// 0: Number of particles).
    double fill_height = 0.;
    /// Where the die axis sits in the hexagonal layer: "particle centred",
    /// "hole centred", "edge centred" or "most particles".
    std::string hexagonal_placement = "particle centred";
    /// Centres "x,y,z; x,y,z; ..." (mm); ignored if a particle file is given.
    std::string centres = "0,0,1.25";
    /// Diameters (mm): one value for all particles or one per particle.
    std::string diameters = "2.5";
    /// Materials: one name for all particles or one per particle.
    std::string materials = "Sn";
    /// CSV file x,y,z,diameter[,material]; relative to the working directory.
    std::string particle_file = "";
    /// Mixture "name:fraction, ..." drawn over the particles (overrides the
    /// materials when not empty).
    std::string material_fractions = "";
    /// Seed of that draw.
    unsigned int material_seed = 1;
    /// Body force "bx,by,bz" on every particle (N/mm^3), e.g. gravity.
    std::string body_force = "0,0,0";
    /// Factor on the body force against time "t:f, ..." (s:-).
    std::string body_force_history = "0:1";
  };

  /// Subsection "Mesh": how each particle is meshed and discretised.
  struct MeshParameters
  {
    /// Target element size (mm).
    double element_size = 0.3;
    /// Refinement directions "x,y,z; ..." from each particle's centre.
    std::string refinement_directions = "";
    /// Element size at the refinement points (mm).
    double refined_element_size = 0.1;
    /// Growth rate of the element size away from refinement points (-).
    double growth = 0.5;
    /// Polynomial degree of the displacement (1 or 2).
    unsigned int degree = 1;
    /// "auto", "nodal averaging" (P1 only) or "none".
    std::string locking_remedy = "auto";
    /// Weight alpha of the cell's own volume change in the nodal-averaged
    /// F-bar (0: none, 1: plain elements).
    double cell_volume_stabilisation = 0.03;
    /// Smallest own volume ratio V/V0 of a cell that meets no barrier (and
    /// 1 / it the largest); 0: no barrier.
    double cell_volume_barrier = 0.5;
    /// Largest estimated number of tetrahedra a run may mesh.
    unsigned int max_elements = 4000000;
  };

  /// Subsection "Material": the constitutive model and the material "custom".
  struct MaterialParameters
  {
    /// "elastic" or "J2 plasticity".
    std::string model = "elastic";
    /// Finite-strain kinematics (false: small strain, elastic only).
    bool finite_strain = false;
    /// "none", "linear" or "power law".
    std::string hardening = "none";
    /// Initial yield stress of "custom" (MPa).
    double yield_stress = 31.;
    /// Linear hardening modulus H (MPa).
    double hardening_modulus = 0.;
    /// Power-law coefficient K (MPa).
    double hardening_coefficient = 0.;
    /// Power-law exponent n (-).
    double hardening_exponent = 1.;
    /// Young's modulus of "custom" (MPa).
    double youngs_modulus = 43120.;
    /// Poisson's ratio of "custom" (-).
    double poissons_ratio = 0.3;
    /// Mass density of the material 'custom' (t/mm^3; 7.29e-9 is tin).
    double density = 7.29e-9;
  };

  /// Subsection "Tools": the rigid upper punch, lower punch and die wall.
  struct ToolParameters
  {
    /// Lower punch present?
    bool lower_enabled = true;
    /// Lower punch face height (mm).
    double lower_position = 0.;
    /// Upward displacement history of the lower punch "t:d, ..." (s:mm),
    /// piecewise linear: ejection.
    std::string lower_displacement = "0:0";
    /// Target force history of the lower punch "t:F, ..." (s:N; upward);
    /// within its times the punch is force-controlled. Empty: displacement
    /// control.
    std::string lower_force;
    /// The same as a mean axial stress over the die's bore (s:MPa).
    std::string lower_pressure;
    /// Relative tolerance of the lower punch's force control.
    double lower_force_tolerance = 1e-3;
    /// Largest lower punch speed under force control (mm/s; 0: from its
    /// displacement history).
    double lower_max_speed = 0.;
    /// Upper punch present?
    bool upper_enabled = true;
    /// Upper punch face height at t = 0 (mm), or "auto": top of the highest
    /// particle.
    std::string upper_initial_position = "auto";
    /// Downward displacement history "t:d, t:d, ..." (s:mm), piecewise linear.
    std::string upper_displacement = "0:0, 1:0.1";
    /// Target force history of the upper punch "t:F, ..." (s:N); within its
    /// times the punch is force-controlled. Empty: displacement control.
    std::string upper_force;
    /// The same as a mean axial stress over the die's bore "t:p, ..."
    /// (s:MPa).
    std::string upper_pressure;
    /// Relative tolerance of the force control.
    double force_tolerance = 1e-3;
    /// Largest punch speed under force control (mm/s; 0: from the
    /// displacement history).
    double max_speed = 0.;
    /// Die wall present?
    bool die_enabled = false;
    /// Inner die diameter (mm).
    double die_diameter = 20.;
    /// Height of the die's top edge (mm), or "none": a die without end.
    std::string die_top = "none";
    /// Upward (z) displacement history of the die "t:d, ..." (s:mm).
    std::string die_displacement = "0:0";
    /// Sideways (x) displacement history of the upper punch "t:d, ..."
    /// (s:mm).
    std::string upper_lateral_displacement = "0:0";
    /// Friction coefficient of each tool: a number, or "default" for
    /// Contact/Friction coefficient.
    std::string lower_friction = "default", upper_friction = "default",
                die_friction = "default";
  };

  /// Subsection "Contact": augmented-Lagrangian normal contact.
  struct ContactParameters
  {
    /// Penalty = factor * E / h (MPa/mm), h the smallest element size.
    double penalty_factor = 100.;
    /// Largest penetration accepted at the end of a step (mm).
    double gap_tolerance = 1e-4;
    /// Maximum multiplier updates per step.
    unsigned int max_augmentations = 20;
    /// Coulomb friction coefficient between particles (and of the tools by
    /// default).
    double friction_coefficient = 0.2;
    /// "Coulomb" (stick/slip return map) or "arctangent" (the paper's).
    std::string friction_model = "Coulomb";
    /// Sliding velocity below which the arctangent law is nearly stuck
    /// (mm/s).
    double slip_velocity = 0.01;
    /// Tangential (stick) penalty = factor * E / h (MPa/mm).
    double tangential_penalty_factor = 1.;
    /// "auto" (consistent unless the linear solver is cg-amg), "symmetric"
    /// (CG) or "consistent" (needs GMRES or a direct solver).
    std::string friction_tangent = "auto";
    /// Particle contact tangent with the rotation of the master normal and
    /// the sliding of the projection point: "auto" (frictionless particle
    /// contact where the linear solver is not cg-amg), "true" (needs GMRES or
    /// a direct solver) or "false".
    std::string geometric_tangent = "auto";
    /// Where contact is evaluated on particle surfaces: "auto" (vertices for
    /// P1, Gauss points for P2), "vertices" or "Gauss points".
    std::string contact_points = "auto";
    /// Horizontal springs on the top and bottom pole vertices of every
    /// particle (frictionless scenes; doc/theory.md): "false" (none), "true"
    /// (on the vertical line through the initial centre) or "vertical" (the
    /// axis through the two poles stays vertical; the particle may move).
    std::string hold_poles = "false";
  };

  /// Subsection "Time stepping": load steps.
  struct TimeParameters
  {
    /// End time (s).
    double end_time = 1.;
    /// Number of load steps.
    unsigned int n_steps = 10;
    /// Maximum halvings of the increment within one load step.
    unsigned int max_cutbacks = 8;
  };

  /// Subsection "Solver": Newton, linear solver and stabilisation.
  struct SolverParameters
  {
    /// "implicit" (quasi-static Newton per load step) or "explicit"
    /// (central differences with a lumped mass, subsection Explicit).
    std::string method = "implicit";
    /// "auto" (gmres-amg where friction acts with the consistent tangent,
    /// cg-amg otherwise), "cg-amg", "gmres-amg" or "direct" (MUMPS).
    std::string linear_solver = "auto";
    /// Relative tolerance of the linear solver.
    double linear_tolerance = 1e-8;
    /// Inexact Newton: the linear tolerance of each Newton iteration follows
    /// the residual's convergence (Eisenstat-Walker), between Linear
    /// tolerance and 1e-2.
    bool adaptive_linear_tolerance = false;
    /// Maximum CG iterations.
    unsigned int max_linear_iterations = 2000;
    /// Keep the AMG hierarchy across Newton iterations while it works.
    bool reuse_amg = true;
    /// Relative residual tolerance of Newton.
    double newton_tolerance = 1e-9;
    /// Maximum Newton iterations per augmentation.
    unsigned int max_newton_iterations = 30;
    /// Line search along the Newton direction du: "residual" (backtrack
    /// until |R| falls) or "energy" (the step where R.du, the derivative of
    /// the incremental energy along du, has fallen to half its size).
    std::string line_search = "energy";
    /// Stabilisation factor beta: tangent += beta E / D^2 M (tangent only).
    double stabilisation = 1e-6;
    /// Pseudo-transient continuation: "off", "fallback" (retry a failed
    /// increment with it) or "always".
    std::string continuation = "fallback";
    /// Factor of the pseudo mass (E / D^2 times the mass matrix) in the
    /// first iteration of the continuation.
    double pseudo_mass = 1.;
    /// The direct solvers factorize on rank 0 alone, so that runs on several
    /// ranks repeat exactly.
    bool reproducible = true;
  };

  /// Subsection "Explicit": the explicit integrator (Solver/Method =
  /// explicit).
  struct ExplicitParameters
  {
    /// Physical duration of the whole load history (s).
    double loading_time = 1.;
    /// Explicit steps over the whole load history, when mass scaling sets
    /// the time step (Mass scaling = uniform or selective).
    unsigned int n_steps = 20000;
    /// "selective" (only elements whose stable step is below the target),
    /// "uniform" (every element by one factor) or "none" (physical density;
    /// the stable step sets the number of steps).
    std::string mass_scaling = "selective";
    /// Time step as a fraction of the computed stable step (and the bound
    /// the mass scaling keeps).
    double safety = 0.9;
    /// Fraction of the loading time over which the punch velocity rises
    /// smoothly from zero.
    double ramp_fraction = 0.05;
    /// Punch speed at the end of the load history as a fraction of its
    /// speed after the ramp; it falls linearly with scene time in between.
    double end_speed_fraction = 1.;
    /// The target step's factor against the scene time, "t:factor, ...",
    /// piecewise linear (factors in (0, 1]).
    std::string step_profile = "0:1";
    /// Mass-proportional damping as a fraction of the critical damping of
    /// a particle's lowest compression mode.
    double damping_ratio = 0.;
    /// Contact springs' squared frequency against the elements' largest one
    /// (sets the contact penalty; the stable step accounts for it): a number
    /// for every particle, or "auto" for one per material from its initial
    /// yield stress over Young's modulus (explicit_contact_stiffness()).
    std::string contact_stiffness = "1";
    /// The contact multipliers follow the pressures over about this many
    /// steps (0: pure penalty).
    unsigned int multiplier_steps = 0;
    /// Largest kinetic energy of a quasi-static run (mass scaling on) at a
    /// station, as a fraction of the internal work (0: not checked).
    double max_kinetic_ratio = 0.25;
    /// Largest difference between the upper punch force and the lower
    /// punch's plus the die wall's, each a mean over the last ten stations,
    /// as a fraction of the upper punch force (0: not checked).
    double max_force_imbalance = 0.5;
    /// Largest miss of a force-controlled punch's target at a station, as a
    /// fraction of the larger of the target and the largest force so far
    /// (0: not checked).
    double max_force_control_error = 0.1;
  };

  /// Subsection "Output": where and what to write.
  struct OutputParameters
  {
    /// Output directory; relative to the working directory.
    std::string directory = "output";
    /// Write graphics every this many steps (0: never).
    unsigned int interval = 1;
    /// Print the Newton iterations of every step.
    bool verbose = false;
    /// Write a checkpoint every this many steps (0: only when stopped).
    unsigned int checkpoint_interval = 25;
  };

  /// Subsection "Scene": settings that stand for several entries.
  struct SceneParameters
  {
    /// "as set" (nothing changed), "draft", "standard" or "reference": the
    /// accuracy levers of that level for every lever entry the parameter
    /// file and --set leave unset (resolve_fidelity(), doc/accuracy.md).
    std::string fidelity = "as set";
  };

  /// Every parameter of a run.
  struct Parameters
  {
    /// Subsection "Scene".
    SceneParameters scene;
    /// Subsection "Particles".
    ParticleParameters particles;
    /// Subsection "Mesh".
    MeshParameters mesh;
    /// Subsection "Material".
    MaterialParameters material;
    /// Subsection "Tools".
    ToolParameters tools;
    /// Subsection "Contact".
    ContactParameters contact;
    /// Subsection "Time stepping".
    TimeParameters time;
    /// Subsection "Solver".
    SolverParameters solver;
    /// Subsection "Explicit".
    ExplicitParameters explicit_dynamics;
    /// Subsection "Output".
    OutputParameters output;

    /**
     * Every entry that shapes the scene (all but subsections Output and
     * Solver, which say how to write and how to solve it; Solver/Method is
     * kept, since the two methods' states differ), one
     * "Subsection/Name = value" per line, as read_parameters() leaves them.
     * A checkpoint stores it and --resume refuses a different one. Empty
     * unless set (then nothing is checked).
     */
    std::string fingerprint;

    /// What Scene/Fidelity set, for the banner (resolve_fidelity()); empty
    /// for "as set".
    std::string fidelity_summary;

    /// Declare every entry (bound to the members above) in @p prm.
    void
    declare(ParameterHandler &prm);

  private:
    /// Declare the subsections Solver and Explicit (part of declare()).
    void
    declare_solution_method(ParameterHandler &prm);
  };

  /// The Parameters::fingerprint of the entries in @p prm.
  std::string
  parameter_fingerprint(const ParameterHandler &prm);

  /**
   * Read @p filename into @p prm (declared by Parameters::declare), apply
   * the overrides "Sub/Sub/Name=value" in order, then Scene/Fidelity to the
   * entries neither set (resolve_fidelity()); its banner text goes to
   * @p fidelity_summary where given. Throws std::runtime_error with a
   * one-line message naming the file, line or entry on any problem.
   */
  void
  read_parameters(ParameterHandler               &prm,
                  const std::string              &filename,
                  const std::vector<std::string> &overrides,
                  std::string                    *fidelity_summary = nullptr);

  /**
   * Checks of single entries beyond their patterns (an empty output
   * directory, material constants no solid has). Throws std::runtime_error
   * with a one-line message naming the entry.
   */
  void
  check_parameters(const Parameters &parameters);

  /// Parse "x,y,z; x,y,z" into points; @p what names the entry for errors.
  std::vector<Point<3>>
  parse_points(const std::string &text, const std::string &what);

  /// Parse "t:v, t:v" into a sorted table; @p what names the entry for errors.
  std::vector<std::pair<double, double>>
  parse_table(const std::string &text, const std::string &what);

  /// Piecewise-linear interpolation in @p table (constant beyond its ends).
  double
  interpolate(const std::vector<std::pair<double, double>> &table,
              const double                                  t);
} // namespace densify
