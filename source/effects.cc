// The effects a scene calls for: every option value read, every 'auto' rule
// applied and every cross-check made here, once.
#include <deal.II/base/utilities.h>

#include <densify/effects.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// The friction coefficient of a tool: 'default' (Contact/Friction
    /// coefficient) or a number >= 0.
    double
    tool_friction(const std::string &tool,
                  const std::string &text,
                  const double       default_mu)
    {
      if (text == "default")
        return default_mu;
      double mu = -1;
      try
        {
          mu = Utilities::string_to_double(text);
        }
      catch (...)
        {}
      if (!(mu >= 0))
        throw std::runtime_error("Tools/" + tool + "/Friction coefficient: '" +
                                 text +
                                 "' is neither a number >= 0 nor 'default'");
      return mu;
    }
  } // namespace



  bool
  Effects::any_friction() const
  {
    bool friction = particle_contact && particle_friction > 0;
    for (unsigned int t = 0; t < n_tool_kinds; ++t)
      friction = friction || (tools[t] && tool_friction[t] > 0);
    return friction;
  }



  Effects
  resolve_effects(const Parameters &prm, const Scene &scene)
  {
    Effects e;
    e.method = (prm.solver.method == "explicit" ? Method::explicit_dynamics :
                                                  Method::implicit);
    e.law    = parse_material_model(prm.material.model);
    e.finite_strain = prm.material.finite_strain;

    // the locking remedy: nodal averaging for linear tetrahedra under
    // plastic flow
    const std::string &remedy = prm.mesh.locking_remedy;
    if (remedy == "nodal averaging" && prm.mesh.degree != 1)
      throw std::runtime_error(
        "Mesh/Volumetric locking remedy = nodal averaging needs "
        "Mesh/Polynomial degree = 1 (quadratic tetrahedra do not lock: use "
        "none or auto)");
    e.locking = (remedy == "nodal averaging" ||
                 (remedy == "auto" && prm.mesh.degree == 1 && e.law.plastic)) ?
                  LockingRemedy::nodal_averaging :
                  LockingRemedy::none;

    // tools and the friction coefficient of every contact pair
    e.tools[static_cast<unsigned int>(ToolKind::lower_punch)] =
      prm.tools.lower_enabled;
    e.tools[static_cast<unsigned int>(ToolKind::upper_punch)] =
      prm.tools.upper_enabled;
    e.tools[static_cast<unsigned int>(ToolKind::die_wall)] =
      prm.tools.die_enabled;
    const double mu = prm.contact.friction_coefficient;
    e.tool_friction[static_cast<unsigned int>(ToolKind::lower_punch)] =
      tool_friction("Lower punch", prm.tools.lower_friction, mu);
    e.tool_friction[static_cast<unsigned int>(ToolKind::upper_punch)] =
      tool_friction("Upper punch", prm.tools.upper_friction, mu);
    e.tool_friction[static_cast<unsigned int>(ToolKind::die_wall)] =
      tool_friction("Die wall", prm.tools.die_friction, mu);
    e.particle_contact  = scene.particles.size() > 1;
    e.particle_friction = mu;
    e.slip_rule         = slip_rule(prm.contact.friction_model);

    // contact points: the corners for P1, the Gauss points for P2
    const std::string &points = prm.contact.contact_points;
    if (points == "vertices" && prm.mesh.degree != 1)
      throw std::runtime_error(
        "Contact/Contact points = vertices is for P1 elements (the edge "
        "midpoints of P2 would not be held): set it to auto or Gauss points, "
        "or Mesh/Polynomial degree = 1");
    e.contact_points =
      (points == "vertices" || (points == "auto" && prm.mesh.degree == 1)) ?
        ContactPoints::vertices :
        ContactPoints::gauss;

    // the tangents and the linear solver: the consistent (nonsymmetric)
    // friction tangent with GMRES where friction acts, CG otherwise
    // (doc/theory.md section 8)
    const std::string &solver  = prm.solver.linear_solver;
    const bool         cg      = solver == "cg-amg";
    const std::string &tangent = prm.contact.friction_tangent;
    if ((tangent == "consistent" || tangent == "secant-start") && cg)
      throw std::runtime_error(
        "Contact/Friction tangent = " + tangent +
        " gives a nonsymmetric tangent that CG cannot solve: set "
        "Solver/Linear solver = gmres-amg (or direct)");
    const std::string &geometric = prm.contact.geometric_tangent;
    if (geometric == "true" && cg)
      throw std::runtime_error(
        "Contact/Geometric tangent = true gives a nonsymmetric tangent that "
        "CG cannot solve: set Solver/Linear solver = gmres-amg, gmres-lu or "
        "direct, or Contact/Geometric tangent = auto");
    e.consistent_friction_tangent =
      e.any_friction() &&
      (tangent == "consistent" || tangent == "secant-start" ||
       tangent == "symmetric-secant-start" || tangent == "auto");
    e.friction_pressure_coupling =
      tangent != "symmetric-secant-start" && !(tangent == "auto" && cg);
    e.friction_secant_start =
      e.consistent_friction_tangent && tangent != "consistent";
    if (solver == "auto")
      e.linear_solver =
        ((e.consistent_friction_tangent && e.friction_pressure_coupling) ||
         (e.particle_contact && geometric == "true")) ?
          LinearSolverType::gmres_amg :
          LinearSolverType::cg_amg;
    else
      e.linear_solver = solver == "cg-amg"    ? LinearSolverType::cg_amg :
                        solver == "gmres-amg" ? LinearSolverType::gmres_amg :
                        solver == "gmres-lu"  ? LinearSolverType::gmres_lu :
                                                LinearSolverType::direct;
    e.geometric_tangent =
      e.particle_contact &&
      (geometric == "true" ||
       (geometric == "auto" && e.linear_solver != LinearSolverType::cg_amg &&
        e.particle_friction <= 0));
    e.line_search   = (prm.solver.line_search == "energy" ? LineSearch::energy :
                                                            LineSearch::residual);
    e.stabilisation = prm.solver.stabilisation > 0;
    e.continuation =
      e.method == Method::explicit_dynamics ? Continuation::off :
      prm.solver.continuation == "always"   ? Continuation::always :
      prm.solver.continuation == "fallback" ? Continuation::fallback :
                                              Continuation::off;

    // loads
    e.body_force = scene.body_force.norm() > 0;

    // the pole springs: for frictionless implicit scenes
    const std::string &poles = prm.contact.hold_poles;
    e.poles                  = poles == "true"     ? PoleHolding::axis :
                               poles == "vertical" ? PoleHolding::vertical :
                                                     PoleHolding::none;
    if (e.poles != PoleHolding::none)
      {
        // the springs join the vertices at centre +- radius e_z of a sphere
        for (unsigned int i = 0; i < scene.particles.size(); ++i)
          if (scene.particles[i].shape != ParticleShape::sphere)
            throw std::runtime_error(
              "Contact/Hold poles on axis is for spheres (particle " +
              std::to_string(i) +
              " is an ellipsoid or a surface particle): set it to false");
        for (unsigned int t = 0; t < n_tool_kinds; ++t)
          if (e.tool_friction[t] > 0)
            throw std::runtime_error(
              "Contact/Hold poles on axis is for frictionless scenes: set "
              "Contact/Friction coefficient = 0 (and no tool Friction "
              "coefficient above 0), or switch it off");
        // axis: one particle, or a stack on one vertical line
        // (axisymmetric); vertical: any layout
        if (e.poles == PoleHolding::axis)
          for (const Particle &p : scene.particles)
            if (std::hypot(p.centre[0] - scene.particles[0].centre[0],
                           p.centre[1] - scene.particles[0].centre[1]) >
                1e-9 * scene.particles[0].diameter)
              throw std::runtime_error(
                "Contact/Hold poles on axis = true is for one particle or a "
                "stack of particles on one vertical line: use 'vertical' "
                "(the particles may move sideways) or false in this scene");
        if (e.method == Method::explicit_dynamics)
          throw std::runtime_error(
            "Contact/Hold poles on axis holds free rigid-body modes for the "
            "implicit method; set it to false with Solver/Method = explicit");
      }

    const std::string &scaling = prm.explicit_dynamics.mass_scaling;
    e.mass_scaling             = scaling == "none"    ? MassScaling::none :
                                 scaling == "uniform" ? MassScaling::uniform :
                                                        MassScaling::selective;
    return e;
  }



  std::string
  linear_solver_name(const LinearSolverType type)
  {
    switch (type)
      {
        case LinearSolverType::cg_amg:
          return "cg-amg";
        case LinearSolverType::gmres_amg:
          return "gmres-amg";
        case LinearSolverType::gmres_lu:
          return "gmres-lu";
        case LinearSolverType::direct:
          return "direct";
      }
    return "unknown";
  }



  std::string
  describe_effects(const Effects                  &e,
                   const std::vector<std::string> &law_names,
                   const Parameters               &prm)
  {
    std::ostringstream out;
    for (unsigned int i = 0; i < law_names.size(); ++i)
      out << (i > 0 ? ", " : "") << law_names[i];
    const auto friction_text = [&](const double mu) {
      std::ostringstream text;
      if (mu > 0)
        text << "friction " << mu << " " << e.slip_rule->name();
      else
        text << "frictionless";
      return text.str();
    };
    // in the order of the contact's tool list
    for (const ToolKind kind :
         {ToolKind::lower_punch, ToolKind::upper_punch, ToolKind::die_wall})
      if (e.has_tool(kind))
        out << ", " << tool_name(kind) << " contact ("
            << friction_text(e.friction_of(kind)) << ")";
    if (e.particle_contact)
      out << ", particle-particle contact ("
          << friction_text(e.particle_friction) << ")";
    if (e.law.plastic)
      out << ", plastic history";
    if (e.locking == LockingRemedy::nodal_averaging)
      out << ", nodal-averaged F-bar (P1 locking remedy)";
    if (e.method == Method::explicit_dynamics)
      out << "; explicit dynamics (lumped mass, "
          << prm.explicit_dynamics.mass_scaling << " mass scaling)";
    else
      {
        out << "; linear solver " << linear_solver_name(e.linear_solver);
        if (e.geometric_tangent)
          out << ", geometric contact tangent";
        if (e.continuation == Continuation::always)
          out << ", pseudo-transient continuation";
      }
    return out.str();
  }
} // namespace densify
