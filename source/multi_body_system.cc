// The multi-body system: the particles, their mesh and DoFs, the force terms
// of the scene's effects and their assembly, the tools' loads, and the
// particles' measures.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/geometry/multi_body_mesh.h>
#include <densify/material/factory.h>
#include <densify/multi_body_system.h>
#include <densify/postprocess/material_points.h>
#include <densify/postprocess/run_log.h>
#include <densify/utilities.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <cmath>

namespace densify
{
  namespace
  {
    /// The points where contact is evaluated on a reference surface triangle:
    /// the corners with weights area/3 (node to surface) or the Gauss points
    /// of degree + 1.
    Quadrature<2>
    contact_quadrature(const ContactPoints points, const unsigned int degree)
    {
      if (points == ContactPoints::vertices)
        return Quadrature<2>(std::vector<Point<2>>{Point<2>(0, 0),
                                                   Point<2>(1, 0),
                                                   Point<2>(0, 1)},
                             std::vector<double>(3, 1. / 6.));
      return QGaussSimplex<2>(degree + 1);
    }
  } // namespace



  MultiBodySystem::MultiBodySystem(const Parameters   &parameters,
                                   const MPI_Comm      comm,
                                   ConditionalOStream &pcout,
                                   TimerOutput        &timer)
    : prm(parameters)
    , comm(comm)
    , pcout(pcout)
    , timer(timer)
    , triangulation(comm,
                    Triangulation<3>::none,
                    false,
                    parallel::shared::Triangulation<3>::partition_metis)
    , dof_handler(triangulation)
  {}



  double
  MultiBodySystem::force_control_speed(
    const std::vector<std::pair<double, double>> &table,
    const double                                  max_speed) const
  {
    if (max_speed > 0.)
      return max_speed;
    // the steepest segment of the displacement history
    double speed = 0.;
    for (unsigned int i = 1; i < table.size(); ++i)
      speed = std::max(speed,
                       std::abs(table[i].second - table[i - 1].second) /
                         (table[i].first - table[i - 1].first));
    return speed > 0. ?
             speed :
             (upper_initial - prm.tools.lower_position) / prm.time.end_time;
  }



  void
  MultiBodySystem::setup_particles(Scene scene, const Effects &scene_effects)
  {
    effects       = scene_effects;
    particles     = std::move(scene.particles);
    upper_initial = scene.upper_initial;
    // before the first contact, a force-controlled punch moves by a
    // hundredth of the gap between the punches
    const double trial = 0.01 * (upper_initial - prm.tools.lower_position);
    punch_control =
      PunchControl(scene.punch_table,
                   scene.force_table,
                   prm.tools.force_tolerance,
                   trial,
                   force_control_speed(scene.punch_table, prm.tools.max_speed));
    lower_initial =
      prm.tools.lower_position + interpolate(scene.lower_table, 0.);
    lower_control =
      PunchControl(scene.lower_table,
                   scene.lower_force_table,
                   prm.tools.lower_force_tolerance,
                   trial,
                   force_control_speed(scene.lower_table,
                                       prm.tools.lower_max_speed));
    // the explicit method follows force windows dynamically
    punch_control.set_dynamic(effects.method == Method::explicit_dynamics);
    lower_control.set_dynamic(effects.method == Method::explicit_dynamics);
    lateral_table    = std::move(scene.lateral_table);
    die_top          = scene.die_top;
    die_table        = std::move(scene.die_table);
    scene_body_force = scene.body_force;
    body_force_table = std::move(scene.body_force_table);
    for (const Particle &p : particles)
      {
        particle_material.push_back(create_material(p.material, prm.material));
        cell_volume_weights.push_back(prm.mesh.cell_volume_stabilisation);
      }
    if (effects.locking == LockingRemedy::nodal_averaging &&
        prm.mesh.cell_volume_barrier > 0.)
      {
        cell_volume_barrier.log_limit = std::log(prm.mesh.cell_volume_barrier);
        for (const auto &material : particle_material)
          cell_volume_barrier.stiffness.push_back(
            material->finite_strain() ? material->bulk_modulus() : 0.);
      }
  }



  void
  MultiBodySystem::setup_mesh()
  {
    SphereMeshSpec spec;
    spec.element_size = prm.mesh.element_size;
    for (const Point<3> &d : parse_points(prm.mesh.refinement_directions,
                                          "Mesh/Refinement directions"))
      {
        if (d.norm() == 0)
          throw std::runtime_error(
            "Mesh/Refinement directions: a direction must not be zero");
        spec.refinement_directions.push_back(d);
      }
    spec.refined_element_size = prm.mesh.refined_element_size;
    spec.growth               = prm.mesh.growth;
    // a progress line where meshing and the setup take a while
    const MeshEstimate estimate = estimate_mesh(prm, particles);
    const bool         large    = estimate.elements > 5e5;
    Timer              meshing;
    if (large)
      pcout << "Meshing " << particles.size() << " particle(s) ("
            << estimate.distinct_diameters << " diameter(s), about "
            << format_count(estimate.elements) << " tetrahedra)..."
            << std::endl;
    build_multi_body_triangulation(particles, spec, triangulation);
    if (large)
      pcout << "  mesh of " << triangulation.n_active_cells()
            << " tetrahedra in " << format_seconds(meshing.wall_time())
            << "; setting up the system..." << std::endl;
    h_min = spec.element_size;
    if (!spec.refinement_directions.empty())
      h_min = std::min(h_min, spec.refined_element_size);
  }



  void
  MultiBodySystem::setup_dofs()
  {
    fe      = std::make_unique<FESystem<3>>(FE_SimplexP<3>(prm.mesh.degree), 3);
    mapping = std::make_unique<MappingFE<3>>(FE_SimplexP<3>(1));
    dof_handler.distribute_dofs(*fe);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

    // masters of particle contact, and the partner of a vertical pole
    // spring, may lie on any rank's cells (spin springs exist only with
    // particle contact)
    ghosted_dofs =
      (effects.particle_contact || effects.poles == PoleHolding::vertical) ?
        complete_index_set(dof_handler.n_dofs()) :
        locally_relevant;

    solution.reinit(locally_owned, comm);
    solution_ghosted.reinit(locally_owned, ghosted_dofs, comm);
    committed_ghosted.reinit(locally_owned, ghosted_dofs, comm);
    current_upper = upper_initial;
  }



  std::vector<double>
  MultiBodySystem::contact_penalty() const
  {
    std::vector<double> penalty;
    for (const auto &m : particle_material)
      penalty.push_back(prm.contact.penalty_factor * m->youngs_modulus() /
                        h_min);
    return penalty;
  }



  void
  MultiBodySystem::setup_force_terms(const std::vector<double> &penalty)
  {
    // the continuum, with the F-bar of the locking remedy
    std::unique_ptr<NodalAveraging> nodal_averaging;
    if (effects.locking == LockingRemedy::nodal_averaging)
      {
        nodal_averaging = std::make_unique<NodalAveraging>(dof_handler,
                                                           *mapping,
                                                           cell_volume_weights);
        nodal_averaging->set_cell_volume_barrier(cell_volume_barrier);
      }
    continuum  = std::make_unique<Continuum>(dof_handler,
                                            particle_material,
                                            std::move(nodal_averaging),
                                            prm.mesh.degree);
    bulk_terms = {continuum.get()};
    if (effects.body_force)
      {
        body_force = std::make_unique<BodyForce>(dof_handler,
                                                 scene_body_force,
                                                 body_force_table,
                                                 prm.mesh.degree);
        bulk_terms.push_back(body_force.get());
      }

    // the friction law of every contact pair
    FrictionLaw friction;
    friction.slip              = effects.slip_rule;
    friction.consistent        = effects.consistent_friction_tangent;
    friction.pressure_coupling = effects.friction_pressure_coupling;
    friction.tangential_ratio =
      prm.contact.tangential_penalty_factor / prm.contact.penalty_factor;
    const Quadrature<2> contact_points =
      contact_quadrature(effects.contact_points, prm.mesh.degree);
    std::vector<RigidTool>   tools;
    std::vector<FrictionLaw> tool_laws;
    if (effects.has_tool(ToolKind::lower_punch))
      tools.push_back({ToolKind::lower_punch, lower_initial});
    if (effects.has_tool(ToolKind::upper_punch))
      tools.push_back({ToolKind::upper_punch, upper_initial});
    if (effects.has_tool(ToolKind::die_wall))
      {
        tools.push_back({ToolKind::die_wall, prm.tools.die_diameter / 2});
        tools.back().top = die_top;
      }
    for (const RigidTool &tool : tools)
      {
        tool_laws.push_back(friction);
        tool_laws.back().mu = effects.friction_of(tool.kind);
      }
    other_terms.clear();
    if (!tools.empty())
      {
        tool_contact = std::make_unique<ToolContact>();
        tool_contact->setup(
          dof_handler, tools, tool_laws, penalty, contact_points);
        tool_contact->set_committed_solution(committed_ghosted);
        other_terms.push_back(tool_contact.get());
      }
    if (effects.particle_contact)
      {
        // candidates within an element of the smallest size: more than a
        // Newton iteration can move (the step limiter allows h/2)
        search_margin    = 0.25 * h_min;
        friction.mu      = effects.particle_friction;
        particle_contact = std::make_unique<ParticleContact>();
        particle_contact->setup(dof_handler, penalty, friction, contact_points);
        particle_contact->set_geometric_tangent(effects.geometric_tangent);
        particle_contact->set_committed_solution(committed_ghosted);
        update_ghosts();
        particle_contact->update_search(solution_ghosted, search_margin);
        other_terms.push_back(particle_contact.get());
      }
    added_terms.clear();
    for (const ForceTermFactory &make : added_term_factories)
      {
        added_terms.push_back(make(*this));
        other_terms.push_back(added_terms.back().get());
      }
    if (effects.method == Method::explicit_dynamics)
      {
        // the integral action on the penetration (Explicit/Contact
        // multiplier steps)
        const unsigned int n_relax    = prm.explicit_dynamics.multiplier_steps;
        const double       relaxation = n_relax > 0 ? 1. / n_relax : 0.;
        if (tool_contact)
          tool_contact->set_relaxation(relaxation);
        if (particle_contact)
          particle_contact->set_relaxation(relaxation);
        return;
      }
    if (effects.poles != PoleHolding::none)
      {
        // the stiffness of a penalty contact on an element face: penalty *
        // h^2
        std::vector<double> stiffness;
        for (const auto &m : particle_material)
          stiffness.push_back(prm.contact.penalty_factor * m->youngs_modulus() *
                              h_min);
        pole_springs =
          std::make_unique<PoleSprings>(dof_handler,
                                        particles,
                                        stiffness,
                                        effects.poles == PoleHolding::vertical,
                                        effects.poles == PoleHolding::axis &&
                                          effects.particle_contact);
        other_terms.push_back(pole_springs.get());
      }
    if (effects.stabilisation || effects.continuation != Continuation::off)
      {
        // E / D^2 times the mass matrix of each particle: the stabilisation
        // (times beta) and the pseudo mass of the continuation
        std::vector<double> alpha;
        for (unsigned int p = 0; p < particles.size(); ++p)
          alpha.push_back(particle_material[p]->youngs_modulus() /
                          (particles[p].diameter * particles[p].diameter));
        stabilisation =
          std::make_unique<Stabilisation>(dof_handler,
                                          alpha,
                                          effects.stabilisation ?
                                            prm.solver.stabilisation :
                                            0.,
                                          prm.mesh.degree);
        other_terms.push_back(stabilisation.get());
      }
  }



  void
  MultiBodySystem::update_ghosts()
  {
    ghost_import(solution, solution_ghosted);
  }



  void
  MultiBodySystem::write_checkpoint(
    boost::archive::binary_oarchive &archive) const
  {
    const std::vector<double> values = owned_solution();
    archive &current_time &current_upper &values &punch_control &lower_control;
    for (const ForceTerm *term : force_terms())
      term->write_checkpoint(archive);
  }



  void
  MultiBodySystem::read_checkpoint(boost::archive::binary_iarchive &archive)
  {
    std::vector<double>                                          values;
    archive &current_time &current_upper &values &punch_control &lower_control;
    for (ForceTerm *term : force_terms())
      term->read_checkpoint(archive);
    take_up_solution(values);
  }



  std::vector<double>
  MultiBodySystem::owned_solution() const
  {
    std::vector<double> values;
    values.reserve(locally_owned.n_elements());
    for (const types::global_dof_index i : locally_owned)
      values.push_back(solution[i]);
    return values;
  }



  void
  MultiBodySystem::take_up_solution(const std::vector<double> &values)
  {
    AssertDimension(values.size(), locally_owned.n_elements());
    unsigned int k = 0;
    for (const types::global_dof_index i : locally_owned)
      solution[i] = values[k++];
    solution.compress(VectorOperation::insert);
    committed_ghosted = solution;
    update_ghosts();
    // the search of the loaded configuration
    if (particle_contact)
      particle_contact->update_search(solution_ghosted, search_margin);
  }



  double
  MultiBodySystem::upper_punch_position(const double t) const
  {
    return upper_initial - punch_control.travel(t);
  }



  double
  MultiBodySystem::lower_punch_position(const double t) const
  {
    return prm.tools.lower_position + lower_control.travel(t);
  }



  AssemblyContext
  MultiBodySystem::context(const double tangent_margin) const
  {
    AssemblyContext c;
    c.mapping           = mapping.get();
    c.solution          = &solution_ghosted;
    c.tangent_margin    = tangent_margin;
    c.explicit_dynamics = effects.method == Method::explicit_dynamics;
    return c;
  }



  double
  MultiBodySystem::assemble_terms(TrilinosWrappers::MPI::Vector  &forces,
                                  TrilinosWrappers::SparseMatrix *matrix,
                                  const double tangent_margin)
  {
    const AssemblyContext c = context(tangent_margin);
    // the bulk terms compress the forces themselves
    for (ForceTerm *term : bulk_terms)
      term->assemble(c, forces, matrix);
    const double bulk_norm = forces.l2_norm();
    for (ForceTerm *term : other_terms)
      {
        TimerOutput::Scope tc(timer, "Assembly: " + term->name());
        term->assemble(c, forces, matrix);
      }
    forces.compress(VectorOperation::add);
    if (matrix != nullptr)
      {
        matrix->compress(VectorOperation::add);
        for (ForceTerm *term : other_terms)
          term->finish_tangent(*matrix);
      }
    const ContactResults contact       = contact_results();
    double               contact_total = contact.particles.normal_force;
    for (const double f : contact.tools.normal_force)
      contact_total += f;
    return std::max(bulk_norm, contact_total);
  }



  ContactResults
  MultiBodySystem::contact_results() const
  {
    ContactResults r;
    if (tool_contact)
      r.tools = tool_contact->last_result();
    if (particle_contact)
      r.particles = particle_contact->last_result();
    return r;
  }



  void
  MultiBodySystem::plan_punches(const double time,
                                const double before,
                                const double gain)
  {
    // the punch that follows a force plans after the one that moves by its
    // history (with both under force control, neither knows the other's)
    const bool upper_follows = punch_control.force_controlled(time) &&
                               !lower_control.force_controlled(time);
    PunchControl &first  = upper_follows ? lower_control : punch_control;
    PunchControl &second = upper_follows ? punch_control : lower_control;
    first.plan(time, gain);
    const double other = first.travel(time) - first.travel(before);
    const bool   follows =
      second.force_controlled(time) && !first.force_controlled(time);
    second.plan(time, gain, follows ? other : 0.);
    // the lower punch's rise lifts the compact, the upper punch's advance
    // lowers it
    rigid_shift = !follows ? 0. : upper_follows ? other : -other;
    // a compact that nothing presses from above rides on a rising lower
    // punch (the ejection with the upper punch withdrawn): the die wall's
    // friction then slips rather than the lower punch indenting the compact
    const double rise =
      lower_control.travel(time) - lower_control.travel(before);
    const double upper_advance =
      punch_control.travel(time) - punch_control.travel(before);
    if (!follows && rise > 0. && upper_advance <= 0. &&
        punch_control.accepted_force() == 0.)
      rigid_shift = rise;
  }



  double
  MultiBodySystem::apply_loads(const double time, const double increment)
  {
    const double upper = upper_punch_position(time);
    if (upper <= lower_punch_position(time))
      {
        const bool lower = !punch_control.force_controlled(time);
        throw ConvergenceError(
          std::string(lower ? "Tools/Lower punch" : "Tools/Upper punch") +
          "/Force history: the target force of " +
          std::to_string((lower ? lower_control : punch_control).target(time)) +
          " N at t = " + std::to_string(time) +
          " s is not reached before the punches meet; give a smaller force");
      }
    load_time = time;
    if (body_force)
      body_force->set_time(time);
    if (tool_contact)
      {
        tool_contact->set_tool_position(ToolKind::upper_punch, upper);
        tool_contact->set_tool_position(ToolKind::lower_punch,
                                        lower_punch_position(time));
        tool_contact->set_tool_translation(
          ToolKind::upper_punch,
          Tensor<1, 3>({interpolate(lateral_table, time), 0., 0.}));
        // the die moves along its axis: its top edge with it, and its wall
        // drags through friction
        const double die_shift = interpolate(die_table, time);
        tool_contact->set_tool_translation(ToolKind::die_wall,
                                           Tensor<1, 3>({0., 0., die_shift}));
        tool_contact->set_tool_top(ToolKind::die_wall, die_top + die_shift);
      }
    // the arctangent law's slip scale: the threshold velocity times the
    // increment's duration
    const double regularisation = prm.contact.slip_velocity * increment;
    if (tool_contact)
      tool_contact->set_friction_regularisation(regularisation);
    if (particle_contact)
      particle_contact->set_friction_regularisation(regularisation);
    // the larger of the punches' travels over the increment
    return std::max(std::abs(upper - current_upper),
                    std::abs(lower_punch_position(time) -
                             lower_punch_position(time - increment)));
  }



  std::vector<ParticleMeasure>
  MultiBodySystem::measure_particles(const bool with_stress) const
  {
    TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                          locally_relevant,
                                          comm);
    ghosted = solution;
    std::vector<ParticleMeasure> measures =
      densify::measure_particles(dof_handler,
                                 *mapping,
                                 prm.mesh.degree,
                                 ghosted,
                                 particles,
                                 particle_material,
                                 comm);
    if (with_stress)
      {
        MaterialPoints points(dof_handler,
                              *mapping,
                              prm.mesh.degree,
                              ghosted,
                              particle_material,
                              continuum->has_history() ?
                                &continuum->committed() :
                                nullptr,
                              continuum->states_per_cell(),
                              continuum->fbar());
        measure_particle_stresses(dof_handler, points, measures, comm);
      }
    return measures;
  }



  std::vector<double>
  MultiBodySystem::particle_volumes() const
  {
    std::vector<double> volume;
    for (const ParticleMeasure &m : measure_particles())
      volume.push_back(m.volume);
    return volume;
  }



  std::vector<Tensor<1, 3>>
  MultiBodySystem::particle_mean_displacements() const
  {
    std::vector<Tensor<1, 3>> mean;
    for (const ParticleMeasure &m : measure_particles())
      mean.push_back(m.mean_displacement);
    return mean;
  }



  std::vector<double>
  MultiBodySystem::particle_tool_forces(const ToolKind kind) const
  {
    return tool_contact ?
             tool_contact->particle_forces(*mapping, solution_ghosted, kind) :
             std::vector<double>(particles.size(), 0.);
  }



  std::vector<unsigned int>
  MultiBodySystem::contact_partners() const
  {
    return particle_contact ?
             particle_contact->contact_partners(*mapping, solution_ghosted) :
             std::vector<unsigned int>(particles.size(), 0);
  }



  double
  MultiBodySystem::pressed_area() const
  {
    if (effects.has_tool(ToolKind::die_wall))
      return numbers::PI * std::pow(prm.tools.die_diameter / 2., 2);
    double area = 0.;
    for (const Particle &p : particles)
      area += numbers::PI * std::pow(p.diameter / 2., 2);
    return area;
  }
} // namespace densify
