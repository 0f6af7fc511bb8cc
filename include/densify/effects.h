// The effects a scene calls for, resolved once from the parameters and the
// scene: every 'auto' rule and every cross-check of the options in one place.
#pragma once

#include <densify/assembly/lumped_mass.h>
#include <densify/contact/contact_law.h>
#include <densify/contact/rigid_tools.h>
#include <densify/material/factory.h>
#include <densify/parameters.h>
#include <densify/scene.h>
#include <densify/solvers/linear_solver.h>
#include <densify/solvers/newton_solver.h>

#include <array>
#include <string>
#include <vector>

namespace densify
{
  /// How the load steps are solved (Solver/Method).
  enum class Method
  {
    /// Quasi-static Newton per load step.
    implicit,
    /// Mass-scaled explicit dynamics between the load steps.
    explicit_dynamics
  };

  /// The remedy of volumetric locking (Mesh/Volumetric locking remedy).
  enum class LockingRemedy
  {
    none,
    /// F-bar with the volume change averaged over each vertex's patch.
    nodal_averaging
  };

  /// How the free rigid-body modes are held (Contact/Hold poles on axis).
  enum class PoleHolding
  {
    /// No springs.
    none,
    /// The poles of every particle held on the vertical axis through them.
    axis,
    /// Springs between the two poles of each particle.
    vertical
  };

  /// Where contact is evaluated on a surface triangle (Contact/Contact
  /// points).
  enum class ContactPoints
  {
    /// The corners (node to surface).
    vertices,
    /// The Gauss points of degree + 1.
    gauss
  };

  /**
   * The effects of one run, each resolved once (the 'auto' rules applied and
   * the options cross-checked): the system builds a force term, a history or
   * a solver part only for the effects that are on.
   */
  struct Effects
  {
    /// Solver/Method.
    Method method = Method::implicit;
    /// The material law of every particle, and its kinematics.
    MaterialModel law           = parse_material_model("elastic");
    bool          finite_strain = false;
    /// The locking remedy.
    LockingRemedy locking = LockingRemedy::none;
    /// The enabled tools, by ToolKind.
    std::array<bool, n_tool_kinds> tools = {{false, false, false}};
    /// Friction coefficient of each tool (by ToolKind) and between particles.
    std::array<double, n_tool_kinds> tool_friction     = {{0., 0., 0.}};
    double                           particle_friction = 0.;
    /// The slip rule of every contact pair (Contact/Friction model).
    std::shared_ptr<const SlipRule> slip_rule = densify::slip_rule("Coulomb");
    /// The consistent friction tangent where friction acts.
    bool consistent_friction_tangent = false;
    /// With it, its nonsymmetric coupling of the slip traction with the
    /// pressure (false: Contact/Friction tangent = symmetric-secant-start).
    bool friction_pressure_coupling = true;
    /// With it, the secant along the slip in the first iterations of each
    /// Newton solve (Contact/Friction tangent = secant-start, or auto).
    bool friction_secant_start = false;
    /// Contact between particles (more than one particle).
    bool particle_contact = false;
    /// The particle contact tangent with the motion of the master facets.
    bool geometric_tangent = false;
    /// Where contact is evaluated.
    ContactPoints contact_points = ContactPoints::gauss;
    /// A body force acts.
    bool body_force = false;
    /// The stabilisation of the tangent (Solver/Stabilisation > 0).
    bool stabilisation = false;
    /// The pole springs.
    PoleHolding poles = PoleHolding::none;
    /// The linear solver (implicit method).
    LinearSolverType linear_solver = LinearSolverType::cg_amg;
    /// The line search (implicit method).
    LineSearch line_search = LineSearch::residual;
    /// The pseudo-transient continuation (implicit method).
    Continuation continuation = Continuation::off;
    /// The mass scaling (explicit method).
    MassScaling mass_scaling = MassScaling::selective;

    /// Does friction act at any contact pair?
    bool
    any_friction() const;

    /// Is @p kind enabled?
    bool
    has_tool(const ToolKind kind) const
    {
      return tools[static_cast<unsigned int>(kind)];
    }

    /// Friction coefficient of the tool @p kind.
    double
    friction_of(const ToolKind kind) const
    {
      return tool_friction[static_cast<unsigned int>(kind)];
    }
  };

  /**
   * Resolve the effects of the scene @p scene with the parameters @p prm:
   * every 'auto' rule, the friction coefficient of every contact pair, and
   * every cross-check between options. Throws std::runtime_error with a
   * one-line message naming the parameter and the fix on options that do not
   * fit together.
   */
  Effects
  resolve_effects(const Parameters &prm, const Scene &scene);

  /**
   * The "Active effects" line of the log (without the label): the material
   * laws @p law_names, the tools and their friction, particle contact, the
   * history, the locking remedy and the solution method.
   */
  std::string
  describe_effects(const Effects                  &effects,
                   const std::vector<std::string> &law_names,
                   const Parameters               &prm);

  /// Solver/Linear solver as named in the parameter file.
  std::string
  linear_solver_name(const LinearSolverType type);
} // namespace densify
