// The Simulator: mesh, DoFs, the force terms of the scene's effects, and the
// run's load steps with their statistics and output.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/contact/broad_search.h>
#include <densify/geometry/multi_body_mesh.h>
#include <densify/material/factory.h>
#include <densify/postprocess/compact_envelope.h>
#include <densify/postprocess/compaction_curve.h>
#include <densify/postprocess/quasi_static_guard.h>
#include <densify/postprocess/run_log.h>
#include <densify/scene.h>
#include <densify/simulator.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

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



  Simulator::Simulator(const Parameters &parameters,
                       const MPI_Comm    comm,
                       const bool        console,
                       const RunControl &control)
    : prm(parameters)
    , control(control)
    , comm(comm)
    , this_rank(Utilities::MPI::this_mpi_process(comm))
    , log_file(open_log(parameters.output.directory, comm, control.resume))
    , tee(std::make_unique<TeeStream>(console ? &std::cout : nullptr,
                                      this_rank == 0 ? &log_file : nullptr))
    , pcout(*tee, this_rank == 0)
    , timer(comm, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(comm,
                    Triangulation<3>::none,
                    false,
                    parallel::shared::Triangulation<3>::partition_metis)
    , dof_handler(triangulation)
  {}



  Simulator::~Simulator()
  {
    timer.reset();
  }



  double
  Simulator::force_control_speed(
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
  Simulator::setup_particles()
  {
    Scene scene = given_scene ? std::move(*given_scene) : build_scene(prm);
    given_scene.reset();
    effects       = resolve_effects(prm, scene);
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
  Simulator::setup_mesh()
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
  Simulator::setup_system()
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
    residual.reinit(locally_owned, comm);
    solution_ghosted.reinit(locally_owned, ghosted_dofs, comm);
    committed_ghosted.reinit(locally_owned, ghosted_dofs, comm);

    // the contact penalty of each particle: E / h times the factor, or for
    // explicit dynamics the one that fits the stable step of the lumped mass
    std::vector<double> penalty;
    for (const auto &m : particle_material)
      penalty.push_back(prm.contact.penalty_factor * m->youngs_modulus() /
                        h_min);
    const double tangential_ratio =
      prm.contact.tangential_penalty_factor / prm.contact.penalty_factor;
    if (effects.method == Method::explicit_dynamics)
      penalty = setup_explicit(effects.any_friction() ? tangential_ratio : 0.);
    setup_force_terms(penalty);
    // explicit dynamics has no tangent and no linear solver
    current_upper = upper_initial;
    if (effects.method == Method::explicit_dynamics)
      return;
    setup_matrix();

    NewtonControl newton_control;
    newton_control.tolerance      = prm.solver.newton_tolerance;
    newton_control.max_iterations = prm.solver.max_newton_iterations;
    newton_control.line_search    = effects.line_search;
    newton_control.adaptive_linear_tolerance =
      prm.solver.adaptive_linear_tolerance;
    newton_control.linear_tolerance = prm.solver.linear_tolerance;
    // no node moves by more than half the smallest element size in one
    // Newton iteration
    newton_control.step_limit         = 0.5 * h_min;
    newton_control.secant_start       = effects.friction_secant_start;
    newton_control.verbose            = prm.output.verbose;
    newton_control.continuation       = effects.continuation;
    newton_control.continuation_start = prm.solver.pseudo_mass;
    // absolute floor: a force far below anything the scene can carry
    double E_max = 0, D_max = 0;
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        E_max = std::max(E_max, particle_material[p]->youngs_modulus());
        D_max = std::max(D_max, particles[p].diameter);
      }
    newton_control.floor = 1e-12 * E_max * D_max * D_max;
    newton = std::make_unique<NewtonSolver>(newton_control, pcout);

    LoadStepperControl stepper_control;
    stepper_control.step_length       = prm.time.end_time / prm.time.n_steps;
    stepper_control.max_cutbacks      = prm.time.max_cutbacks;
    stepper_control.gap_tolerance     = prm.contact.gap_tolerance;
    stepper_control.max_augmentations = prm.contact.max_augmentations;
    stepper = std::make_unique<LoadStepper>(stepper_control, *newton, pcout);
    stepper->setup(solution);

    linear_solver =
      std::make_unique<LinearSolver>(effects.linear_solver,
                                     prm.solver.linear_tolerance,
                                     prm.solver.max_linear_iterations,
                                     prm.solver.reuse_amg,
                                     prm.solver.reproducible,
                                     timer);
    linear_solver->setup_null_space(dof_handler, *mapping, locally_owned);
  }



  void
  Simulator::setup_force_terms(const std::vector<double> &penalty)
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
    friction.model             = effects.friction_model;
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
  Simulator::setup_matrix()
  {
    TimerOutput::Scope                t(timer, "Setup: matrix");
    TrilinosWrappers::SparsityPattern sp(locally_owned, comm);
    DoFTools::make_sparsity_pattern(
      dof_handler, sp, AffineConstraints<double>(), false, this_rank);
    for (ForceTerm *term : bulk_terms)
      term->add_couplings(sp);
    for (ForceTerm *term : other_terms)
      term->add_couplings(sp);
    sp.compress();
    // the preconditioner (or factorization) refers to the old matrix: free
    // it before the matrix goes
    if (linear_solver)
      linear_solver->rebuild_preconditioner();
    tangent.reinit(sp);
    // the size of the tangent decides what the linear solvers cost; the
    // pattern is made again when contact candidates move out of it
    if (n_matrix_setups++ == 0 || prm.output.verbose)
      pcout << "Tangent matrix: " << tangent.n_nonzero_elements()
            << " entries, "
            << tangent.n_nonzero_elements() /
                 std::max<types::global_dof_index>(1, tangent.m())
            << " per row" << std::endl;
    if (stabilisation)
      stabilisation->reinit(sp, *mapping);
  }



  void
  Simulator::update_ghosts()
  {
    ghost_import(solution, solution_ghosted);
  }



  double
  Simulator::upper_punch_position(const double t) const
  {
    return upper_initial - punch_control.travel(t);
  }



  double
  Simulator::lower_punch_position(const double t) const
  {
    return prm.tools.lower_position + lower_control.travel(t);
  }



  AssemblyContext
  Simulator::context(const double tangent_margin) const
  {
    AssemblyContext c;
    c.mapping           = mapping.get();
    c.solution          = &solution_ghosted;
    c.tangent_margin    = tangent_margin;
    c.explicit_dynamics = effects.method == Method::explicit_dynamics;
    return c;
  }



  double
  Simulator::assemble_terms(TrilinosWrappers::MPI::Vector &forces,
                            const bool                     with_matrix,
                            const double                   tangent_margin)
  {
    TrilinosWrappers::SparseMatrix *matrix = with_matrix ? &tangent : nullptr;
    const AssemblyContext           c      = context(tangent_margin);
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
    if (with_matrix)
      {
        tangent.compress(VectorOperation::add);
        for (ForceTerm *term : other_terms)
          term->finish_tangent(tangent);
      }
    const ContactResults contact       = contact_results();
    double               contact_total = contact.particles.normal_force;
    for (const double f : contact.tools.normal_force)
      contact_total += f;
    return std::max(bulk_norm, contact_total);
  }



  std::pair<std::vector<unsigned int>, std::vector<double>>
  Simulator::station_contacts() const
  {
    if (!station_recorded)
      return {contact_partners(), particle_tool_forces(ToolKind::die_wall)};
    std::vector<double> die_force = station_record.die_force;
    Utilities::MPI::sum(die_force, comm, die_force);
    return {particle_contact ?
              particle_contact->partners_of(station_record.pairs) :
              std::vector<unsigned int>(particles.size(), 0),
            die_force};
  }



  Simulator::ContactResults
  Simulator::contact_results() const
  {
    ContactResults r;
    if (tool_contact)
      r.tools = tool_contact->last_result();
    if (particle_contact)
      r.particles = particle_contact->last_result();
    return r;
  }



  void
  Simulator::setup()
  {
    if (dof_handler.has_active_dofs())
      return;
    TimerOutput::Scope t(timer, "Setup");
    setup_particles();
    setup_mesh();
    setup_system();
  }



  bool
  Simulator::run()
  {
    Timer wall;
    setup();

    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    pcout << "Densify: " << particles.size() << " particle(s), "
          << triangulation.n_active_cells() << " tetrahedra, " << n_dofs()
          << " DoFs (P" << prm.mesh.degree << "), " << n_ranks << " MPI rank(s)"
          << std::endl;
    {
      // every distinct material law once, then the tools and the solver
      std::vector<std::string> laws;
      for (const auto &m : particle_material)
        if (std::find(laws.begin(), laws.end(), m->name()) == laws.end())
          laws.push_back(m->name());
      pcout << "Active effects: " << describe_effects(effects, laws, prm)
            << std::endl;
      if (!prm.fidelity_summary.empty())
        pcout << "Fidelity: " << prm.fidelity_summary << std::endl;
    }

    const double die_area =
      numbers::PI * std::pow(prm.tools.die_diameter / 2, 2);
    const bool has_density = prm.tools.die_enabled && prm.tools.lower_enabled &&
                             prm.tools.upper_enabled;
    auto density = [&](const double volume, const double gap) {
      return has_density ? volume / (die_area * gap) :
                           std::numeric_limits<double>::quiet_NaN();
    };
    {
      double v0 = 0;
      for (const double v : particle_volumes())
        v0 += v;
      if (has_density)
        pcout << "Initial relative density " << std::fixed
              << std::setprecision(2)
              << 100 * density(v0, upper_initial - lower_initial)
              << " % (particle volume of the mesh " << std::setprecision(4)
              << v0 << " mm^3)" << std::defaultfloat << std::endl;
    }

    for (const ParticleMeasure &m : measure_particles())
      initial_volumes.push_back(m.volume);
    // a resumed run continues after the checkpoint's step, appending to the
    // files' rows up to that step
    if (effects.method == Method::explicit_dynamics)
      {
        // at rest at the start (or at the checkpoint's state, which
        // read_checkpoint() then restores)
        const double dt =
          explicit_dynamics->start(*this,
                                   solution,
                                   effects.mass_scaling != MassScaling::none);
        const auto [low, high] =
          std::minmax_element(explicit_penalty.begin(), explicit_penalty.end());
        pcout << "Explicit dynamics: time step " << std::setprecision(4) << dt
              << " s (stable " << explicit_dynamics->stable_step()
              << " s), about "
              << static_cast<unsigned long long>(
                   prm.explicit_dynamics.loading_time / dt + 0.5)
              << " steps; added mass " << std::setprecision(3)
              << 100. * lumped_mass->added_mass_fraction()
              << " %; contact penalty " << std::setprecision(4) << *low;
        if (*high > *low)
          pcout << " - " << *high;
        pcout << " MPa/mm" << std::endl;
      }
    const unsigned int first_step = control.resume ? read_checkpoint() + 1 : 1;
    const std::string  statistics_name =
      prm.output.directory + "/statistics.csv";
    const std::string particle_name = prm.output.directory + "/particles.csv";
    // what rank 0 cannot write ends the run on every rank
    std::string open_error;
    if (this_rank == 0)
      try
        {
          const bool append = control.resume &&
                              std::filesystem::exists(statistics_name) &&
                              std::filesystem::exists(particle_name);
          if (append)
            {
              truncate_rows(statistics_name, first_step - 1);
              truncate_rows(particle_name, first_step - 1);
            }
          statistics_writer =
            std::make_unique<StatisticsWriter>(statistics_name, append);
          particle_writer =
            std::make_unique<ParticleTableWriter>(particle_name, append);
        }
      catch (const std::exception &e)
        {
          open_error = e.what();
        }
    open_error = first_error(open_error, comm);
    if (!open_error.empty())
      throw std::runtime_error(open_error);

    // the quasi-static guard of explicit runs whose mass scaling sets the
    // step (Explicit/Maximum kinetic energy ratio, Maximum force imbalance)
    QuasiStaticGuard guard(quasi_static_limits());
    guard_snapshot      = CheckpointSnapshot();
    guard_snapshot_wall = guard_snapshot_cost = 0.;

    const unsigned int n_steps = prm.time.n_steps;
    for (unsigned int step = first_step; step <= n_steps; ++step)
      {
        Timer          step_timer;
        const double   time         = prm.time.end_time * step / n_steps;
        const double   before       = prm.time.end_time * (step - 1) / n_steps;
        const double   upper_before = upper_punch_position(before);
        const double   lower_before = lower_punch_position(before);
        StepStatistics s;
        s.step                   = step;
        s.time                   = time;
        last_stabilisation_force = 0;
        ContactResults results;
        try
          {
            if (effects.method == Method::explicit_dynamics)
              results = advance_explicit(time, step, s);
            else
              {
                StepCounts counts;
                stepper->advance_to(*this, current_time, time, step, counts);
                s.newton_iterations        = counts.newton_iterations;
                s.linear_iterations        = counts.linear_iterations;
                s.augmentations            = counts.augmentations;
                s.cutbacks                 = counts.cutbacks;
                s.continuations            = counts.continuations;
                s.failed_checks            = counts.failed_checks;
                s.failed_newton_iterations = counts.failed_newton_iterations;
                s.increments               = counts.increments;
                results                    = last_contact;
              }
          }
        catch (const ConvergenceError &e)
          {
            // every rank failed alike, back at the last converged increment:
            // keep it for a resumption with other solver settings
            if (step == first_step && current_time == 0)
              throw;
            try
              {
                write_checkpoint(step - 1, wall_before + wall.wall_time());
              }
            catch (const std::exception &c)
              {
                throw ConvergenceError(std::string(e.what()) + "; " + c.what());
              }
            throw ConvergenceError(
              std::string(e.what()) + "; the last converged state (time " +
              Utilities::to_string(current_time) + " s) is in " +
              prm.output.directory +
              "/checkpoint/: continue with --resume and other Solver or "
              "Time stepping/Maximum cut-backs settings");
          }
        const ToolContactResult &contact = results.tools;
        // where the step left the punches (a force-controlled punch is
        // where its force took it)
        const double upper         = upper_punch_position(time);
        const double lower         = lower_punch_position(time);
        s.punch_displacement       = upper_initial - upper;
        s.lower_punch_displacement = lower - lower_initial;
        s.die_displacement =
          interpolate(die_table, time) - interpolate(die_table, 0.);
        {
          // the lower punch's rise in the die (a die lowered past a held
          // compact ejects it too); a lower punch under force control
          // presses: its rise closes the gap as the upper punch's advance
          // does
          const double rise =
            lower - lower_before -
            (interpolate(die_table, time) - interpolate(die_table, before));
          const bool pressing = lower_control.force_controlled(time);
          double     advance  = upper_before - upper + (pressing ? rise : 0.);
          // under force control the target's trend decides: a flat target
          // holds, whatever the punch's creep or elastic relaxation
          const PunchControl *controlled =
            punch_control.force_controlled(time) ? &punch_control :
            pressing                             ? &lower_control :
                                                   nullptr;
          if (controlled != nullptr)
            {
              const double a = controlled->target(before),
                           b = controlled->target(time);
              const double still =
                1e-9 * std::max({std::abs(a), std::abs(b), 1.});
              advance = b - a > still ? 1. : b - a < -still ? -1. : 0.;
            }
          s.phase = static_cast<unsigned int>(
            press_phase(advance, pressing ? 0. : rise));
        }

        const auto upper_kind =
          static_cast<unsigned int>(ToolKind::upper_punch);
        const auto lower_kind =
          static_cast<unsigned int>(ToolKind::lower_punch);
        const auto die_kind     = static_cast<unsigned int>(ToolKind::die_wall);
        s.upper_punch_force     = contact.normal_force[upper_kind];
        s.lower_punch_force     = contact.normal_force[lower_kind];
        s.die_wall_force        = contact.axial_force[die_kind];
        s.die_wall_radial_force = contact.normal_force[die_kind];
        s.stabilisation_force   = last_stabilisation_force;
        s.max_penetration =
          std::max(contact.max_penetration, results.particles.max_penetration);
        s.particle_contact_force = results.particles.normal_force;
        s.upper_punch_friction   = contact.friction_force[upper_kind].norm();
        s.lower_punch_friction   = contact.friction_force[lower_kind].norm();
        s.slipping_points        = contact.n_slip + results.particles.n_slip;
        update_ghosts();
        const auto [partners, die_force] = station_contacts();
        for (const unsigned int n : partners)
          s.contact_pairs += n;
        s.contact_pairs /= 2;
        s.coordination_number = 2. * s.contact_pairs / particles.size();
        s.contact_area_fraction =
          2. * results.particles.contact_area /
          particle_surface_area(dof_handler, solution_ghosted);
        s.pole_force = pole_springs ? pole_springs->force() : 0.;
        std::vector<ParticleMeasure> measures;
        {
          TimerOutput::Scope t(timer, "Output: particle measures");
          measures = measure_particles(true);
        }
        for (const ParticleMeasure &m : measures)
          s.particle_volume += m.volume;
        // what rank 0 cannot write (e.g. a full disk) ends the run on every
        // rank; the rows written before stay complete
        std::string write_failure;
        if (this_rank == 0)
          write_failure = particle_writer->write(
            step, particles, measures, initial_volumes, partners, die_force);
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
            compact_envelope(dof_handler, solution_ghosted);
          s.compact_height   = envelope.top - envelope.bottom;
          s.compact_diameter = 2 * envelope.radius;
          s.envelope_density =
            s.particle_volume / (numbers::PI * envelope.radius *
                                 envelope.radius * s.compact_height);
        }
        s.plastic_work = continuum->plastic_work(*mapping);
        const SmallestCellVolume smallest =
          smallest_cell_volume(dof_handler, *mapping, solution_ghosted);
        s.min_cell_volume_ratio = smallest.ratio;
        if (effects.method == Method::explicit_dynamics)
          {
            const ExplicitDynamics::Account &a = explicit_account;
            s.explicit_steps                   = a.steps;
            s.time_step                        = a.step;
            s.kinetic_energy                   = a.kinetic;
            s.internal_work                    = a.internal;
            s.damping_work                     = a.damping;
            s.friction_work                    = explicit_work.friction;
            s.contact_energy                   = explicit_work.contact_energy;
            s.external_work   = explicit_work.tools + explicit_work.body;
            s.multiplier_work = explicit_work.multipliers;
            s.added_mass      = lumped_mass->added_mass_fraction();
            s.energy_balance =
              s.external_work + s.multiplier_work -
              (s.kinetic_energy + s.internal_work + s.damping_work +
               s.friction_work + s.contact_energy);
          }

        if (prm.output.interval > 0 &&
            (step % prm.output.interval == 0 || step == n_steps))
          write_graphics(step, time, measures);

        s.step_seconds = step_timer.wall_time();
        s.wall_seconds = wall_before + wall.wall_time();
        step_statistics.push_back(s);
        if (statistics_writer && write_failure.empty())
          write_failure = statistics_writer->write(s);
        write_failure = first_error(write_failure, comm);
        if (!write_failure.empty())
          throw std::runtime_error(write_failure);
        if (effects.method == Method::explicit_dynamics)
          warn_penetration(s);
        warn_cell_volume(s.step, smallest);
        // the station's rows are written, so that they show why it stops
        if (guard.active())
          check_quasi_static(s, guard);

        // the share of the work done since the start of this process: the
        // stations, or for explicit runs the physical time, whose steps
        // are equal while a station's are not (Explicit/End speed fraction)
        const auto work = [&](const unsigned int k) {
          const double tau = prm.time.end_time * k / n_steps;
          return explicit_dynamics ? explicit_dynamics->physical_time(tau) :
                                     tau;
        };
        const double done = work(step) - work(first_step - 1);
        const double left =
          (s.wall_seconds - wall_before) / done * (work(n_steps) - work(step));
        pcout << progress_line(s,
                               n_steps,
                               pole_springs != nullptr,
                               has_density,
                               effects.method == Method::explicit_dynamics,
                               left)
              << std::endl;

        // stop on request (every rank must agree) or write the periodic
        // checkpoint
        const bool signalled =
          Utilities::MPI::max(control.stop_request != nullptr &&
                                  *control.stop_request != 0 ?
                                1 :
                                0,
                              comm) > 0;
        const bool stop =
          step < n_steps && (signalled || step == control.stop_after);
        // the snapshot for the guard's checkpoint at most every 50 times
        // its own cost in run time (every station of the light layer, every
        // few of the paper scene), so that it costs at most 2 %. Each rank
        // reads its own clock, so the ranks agree on it: taking a snapshot
        // is collective (its timer section synchronises the ranks), and a
        // rank that took one alone would wait there forever
        if (guard.judging() && step < n_steps &&
            Utilities::MPI::max(s.wall_seconds - guard_snapshot_wall >=
                                    50. * guard_snapshot_cost ?
                                  1 :
                                  0,
                                comm) > 0)
          {
            Timer snapshot;
            guard_snapshot      = checkpoint_snapshot(step, s.wall_seconds);
            guard_snapshot_cost = snapshot.wall_time();
            guard_snapshot_wall = s.wall_seconds;
          }
        // the last step's too where it is a multiple of the interval: a
        // finished run can be pressed further
        if (stop || (prm.output.checkpoint_interval > 0 &&
                     step % prm.output.checkpoint_interval == 0))
          {
            if (guard_snapshot.step == step)
              store_checkpoint(guard_snapshot);
            else
              write_checkpoint(step, s.wall_seconds);
          }
        if (stop)
          {
            pcout << "Stopped after step " << step << "/" << n_steps
                  << (signalled ? " on a signal" : " (--stop-after)")
                  << "; checkpoint in " << prm.output.directory
                  << "/checkpoint/; continue with --resume" << std::endl;
            timer.print_summary();
            return false;
          }
      }
    // the field's constants of the whole loading curve and the springback
    // (the rows of earlier runs of a resumed one included)
    if (statistics_writer)
      try
        {
          if (has_density)
            pcout << compaction_summary(
              read_loading_curve(statistics_name,
                                 upper_initial - prm.tools.lower_position));
          pcout << contact_summary(statistics_name)
                << springback_summary(statistics_name)
                << ejection_summary(statistics_name);
        }
      catch (const std::exception &)
        {
          // a statistics.csv of an older version: no summary
        }
    pcout << "Finished " << n_steps << " steps in "
          << format_seconds(wall_before + wall.wall_time()) << "; results in "
          << prm.output.directory << "/" << std::endl;
    timer.print_summary();
    return true;
  }
} // namespace densify
