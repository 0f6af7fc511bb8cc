// The quasi-static compaction driver: mesh, DoFs, Newton per load step,
// contact, output.
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
    /// The points where contact is evaluated on a reference surface triangle
    /// (Contact/Contact points): the corners with weights area/3 (node to
    /// surface) or the Gauss points of degree + 1.
    Quadrature<2>
    contact_quadrature(const Parameters &prm)
    {
      const std::string &choice = prm.contact.contact_points;
      if (choice == "vertices" || (choice == "auto" && prm.mesh.degree == 1))
        return Quadrature<2>(std::vector<Point<2>>{Point<2>(0, 0),
                                                   Point<2>(1, 0),
                                                   Point<2>(0, 1)},
                             std::vector<double>(3, 1. / 6.));
      return QGaussSimplex<2>(prm.mesh.degree + 1);
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
  {
    method =
      (parameters.solver.method == "explicit" ? Method::explicit_dynamics :
                                                Method::implicit);
  }



  Simulator::~Simulator()
  {
    timer.reset();
  }



  void
  Simulator::setup_particles()
  {
    Scene scene      = build_scene(prm);
    particles        = std::move(scene.particles);
    upper_initial    = scene.upper_initial;
    punch_table      = std::move(scene.punch_table);
    lateral_table    = std::move(scene.lateral_table);
    body_force       = scene.body_force;
    body_force_table = std::move(scene.body_force_table);
    tool_friction    = scene.tool_friction;
    for (const Particle &p : particles)
      particle_material.push_back(create_material(p.material, prm.material));
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
    has_particle_contact = particles.size() > 1;
    ghosted_dofs =
      (has_particle_contact || prm.contact.hold_poles == "vertical") ?
        complete_index_set(dof_handler.n_dofs()) :
        locally_relevant;

    solution.reinit(locally_owned, comm);
    increment.reinit(locally_owned, comm);
    residual.reinit(locally_owned, comm);
    last_increment.reinit(locally_owned, comm);
    solution_ghosted.reinit(locally_owned, ghosted_dofs, comm);
    committed_ghosted.reinit(locally_owned, ghosted_dofs, comm);

    // enabled tools and per-particle penalties
    std::vector<RigidTool> tools;
    if (prm.tools.lower_enabled)
      tools.push_back({ToolKind::lower_punch, prm.tools.lower_position});
    if (prm.tools.upper_enabled)
      tools.push_back({ToolKind::upper_punch, upper_initial});
    if (prm.tools.die_enabled)
      tools.push_back({ToolKind::die_wall, prm.tools.die_diameter / 2});
    std::vector<double> penalty;
    for (const auto &m : particle_material)
      penalty.push_back(prm.contact.penalty_factor * m->youngs_modulus() /
                        h_min);
    FrictionLaw friction;
    friction.mu = prm.contact.friction_coefficient;
    friction.model =
      (prm.contact.friction_model == "arctangent" ? FrictionModel::arctangent :
                                                    FrictionModel::coulomb);
    // 'auto' choices: the consistent (nonsymmetric) friction tangent with
    // GMRES where friction acts, CG otherwise (doc/theory.md section 8)
    bool any_friction = has_particle_contact && friction.mu > 0;
    for (const RigidTool &tool : tools)
      any_friction |= tool_friction[static_cast<unsigned>(tool.kind)] > 0;
    const std::string &tangent_choice = prm.contact.friction_tangent;
    friction.consistent =
      any_friction &&
      (tangent_choice == "consistent" ||
       (tangent_choice == "auto" && prm.solver.linear_solver != "cg-amg"));
    linear_solver_type = prm.solver.linear_solver;
    if (linear_solver_type == "auto")
      linear_solver_type =
        (friction.consistent ||
         (has_particle_contact && prm.contact.geometric_tangent == "true")) ?
          "gmres-amg" :
          "cg-amg";
    geometric_tangent = has_particle_contact &&
                        (prm.contact.geometric_tangent == "true" ||
                         (prm.contact.geometric_tangent == "auto" &&
                          linear_solver_type != "cg-amg" && friction.mu <= 0));
    friction.tangential_ratio =
      prm.contact.tangential_penalty_factor / prm.contact.penalty_factor;
    std::vector<FrictionLaw> tool_laws;
    for (const RigidTool &tool : tools)
      {
        tool_laws.push_back(friction);
        tool_laws.back().mu = tool_friction[static_cast<unsigned>(tool.kind)];
      }
    if (use_nodal_averaging(prm) && !nodal_averaging)
      nodal_averaging = std::make_unique<NodalAveraging>(dof_handler, *mapping);
    if (method == Method::explicit_dynamics)
      {
        if (prm.contact.hold_poles != "false")
          throw InputError("Contact/Hold poles on axis holds free rigid-body "
                           "modes for the implicit method; set it to false "
                           "with Solver/Method = explicit");
        // the penalty that fits the stable step of the lumped mass
        penalty = setup_explicit(any_friction ? friction.tangential_ratio : 0.);
      }
    const Quadrature<2> contact_points = contact_quadrature(prm);
    tool_contact.setup(dof_handler, tools, tool_laws, penalty, contact_points);
    tool_contact.set_committed_solution(committed_ghosted);
    if (has_particle_contact)
      {
        // candidates within an element of the smallest size: more than a
        // Newton iteration can move (the step limiter allows h/2)
        search_margin = 0.25 * h_min;
        particle_contact.setup(dof_handler, penalty, friction, contact_points);
        particle_contact.set_geometric_tangent(geometric_tangent);
        particle_contact.set_committed_solution(committed_ghosted);
        update_ghosts();
        particle_contact.update_search(solution_ghosted, search_margin);
      }
    // explicit dynamics has no tangent and no linear solver
    if (method == Method::implicit)
      setup_matrix();

    // quadrature-point history only where a material needs it
    has_history = false;
    for (const auto &m : particle_material)
      has_history = has_history || m->needs_history();
    if (has_history)
      {
        // one state per quadrature point, or per cell corner with the
        // nodal-averaged F-bar (NodalAveraging's layout)
        history_per_cell = use_nodal_averaging(prm) ?
                             4 :
                             QGaussSimplex<3>(prm.mesh.degree + 1).size();
        committed_history.assign(triangulation.n_active_cells() *
                                   history_per_cell,
                                 MaterialState());
        trial_history = committed_history;
      }
    current_upper  = upper_initial;
    next_increment = prm.time.end_time / prm.time.n_steps;

    if (method == Method::explicit_dynamics)
      return;
    linear_solver =
      std::make_unique<LinearSolver>(linear_solver_type,
                                     prm.solver.linear_tolerance,
                                     prm.solver.max_linear_iterations,
                                     prm.solver.reuse_amg,
                                     prm.solver.reproducible,
                                     timer);
    linear_solver->setup_null_space(dof_handler, *mapping, locally_owned);
  }



  void
  Simulator::setup_matrix()
  {
    TimerOutput::Scope                t(timer, "Setup: matrix");
    TrilinosWrappers::SparsityPattern sp(locally_owned, comm);
    DoFTools::make_sparsity_pattern(
      dof_handler, sp, AffineConstraints<double>(), false, this_rank);
    if (use_nodal_averaging(prm))
      {
        // couples all DoFs of the cells around each vertex
        if (!nodal_averaging)
          nodal_averaging =
            std::make_unique<NodalAveraging>(dof_handler, *mapping);
        nodal_averaging->add_sparsity(sp);
      }
    if (has_particle_contact)
      particle_contact.add_couplings(sp);
    setup_pole_springs();
    add_pole_couplings(sp);
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
    stabilisation.reinit(sp);
    setup_stabilisation();
  }



  void
  Simulator::setup_stabilisation()
  {
    // beta E / D^2 times the mass matrix of each particle (tangent only)
    const QGaussSimplex<3>               quadrature(prm.mesh.degree + 1);
    FEValues<3>                          fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_JxW_values);
    const FEValuesExtractors::Vector     u(0);
    const unsigned int                   n = fe->n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int p     = cell->material_id();
          const double       alpha = prm.solver.stabilisation *
                               particle_material[p]->youngs_modulus() /
                               (particles[p].diameter * particles[p].diameter);
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) += alpha * fe_values[u].value(i, q) *
                                     fe_values[u].value(j, q) *
                                     fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          stabilisation.add(dofs, cell_matrix);
        }
    stabilisation.compress(VectorOperation::add);
  }



  void
  Simulator::update_ghosts()
  {
    solution_ghosted = solution;
  }



  double
  Simulator::upper_punch_position(const double t) const
  {
    return upper_initial - interpolate(punch_table, t);
  }



  void
  Simulator::assemble_internal(TrilinosWrappers::MPI::Vector &forces,
                               const bool                     with_matrix)
  {
    const QGaussSimplex<3>               quadrature(prm.mesh.degree + 1);
    FEValues<3>                          fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_gradients | update_JxW_values);
    const unsigned int                   n   = fe->n_dofs_per_cell();
    const unsigned int                   n_q = quadrature.size();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_residual(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<Tensor<2, 3>>            grad_u(n_q);
    std::vector<Tensor<1, 3>>            grad_phi(n);
    std::vector<Tensor<2, 3>>            A_grad(n);
    std::vector<unsigned int>            component(n);
    for (unsigned int i = 0; i < n; ++i)
      component[i] = fe->system_to_component_index(i).first;
    const FEValuesExtractors::Vector u(0);
    Tensor<2, 3>                     P;
    Tensor<4, 3>                     A;

    std::string material_failure;
    // with the locking remedy, its own assembly replaces the cell loop
    if (nodal_averaging)
      material_failure =
        nodal_averaging->assemble(solution_ghosted,
                                  particle_material,
                                  has_history ? &committed_history : nullptr,
                                  has_history ? &trial_history : nullptr,
                                  forces,
                                  with_matrix ? &tangent : nullptr,
                                  method == Method::explicit_dynamics);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!nodal_averaging && cell->is_locally_owned() &&
          material_failure.empty())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(solution_ghosted, grad_u);
          const Material &material = *particle_material[cell->material_id()];
          cell_matrix              = 0;
          cell_residual            = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
              const unsigned int k = cell->active_cell_index() * n_q + q;
              try
                {
                  const MaterialState *old =
                    has_history ? &committed_history[k] : nullptr;
                  MaterialState *now =
                    has_history ? &trial_history[k] : nullptr;
                  // a residual alone needs no tangent
                  if (with_matrix)
                    material.evaluate(F, old, now, P, A);
                  else
                    material.stress(F, old, now, P);
                }
              catch (const std::exception &e)
                {
                  // e.g. an inverted element; reported on every rank below
                  material_failure = e.what();
                  break;
                }
              const double JxW = fe_values.JxW(q);
              // each shape function of the FESystem has one nonzero
              // component c_i: grad phi_i = e_{c_i} (x) g_i
              for (unsigned int i = 0; i < n; ++i)
                {
                  grad_phi[i] = fe_values.shape_grad(i, q);
                  cell_residual(i) += (P[component[i]] * grad_phi[i]) * JxW;
                }
              if (!with_matrix)
                continue;
              // A_grad[j][k][J] = A[k][J][c_j][L] g_j[L]
              for (unsigned int j = 0; j < n; ++j)
                for (unsigned int k = 0; k < 3; ++k)
                  for (unsigned int J = 0; J < 3; ++J)
                    A_grad[j][k][J] = A[k][J][component[j]] * grad_phi[j];
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) +=
                    (A_grad[j][component[i]] * grad_phi[i]) * JxW;
            }
          cell->get_dof_indices(dofs);
          forces.add(dofs, cell_residual);
          if (with_matrix)
            tangent.add(dofs, cell_matrix);
        }
    forces.compress(VectorOperation::add);
    if (Utilities::MPI::max(material_failure.empty() ? 0 : 1, comm) > 0)
      {
        if (with_matrix)
          tangent.compress(VectorOperation::add);
        throw std::runtime_error("material: " +
                                 (material_failure.empty() ?
                                    std::string("failed on another rank") :
                                    material_failure));
      }
  }



  Simulator::AssemblyResult
  Simulator::assemble(const bool   with_matrix,
                      const double tangent_margin,
                      const bool   search)
  {
    TimerOutput::Scope t(timer,
                         with_matrix ? "Assembly: tangent+residual" :
                                       "Assembly: residual");
    update_ghosts();
    if ((with_matrix || search) && has_particle_contact)
      {
        // refresh the particle contact search; new couplings need a new
        // matrix pattern (without a tangent the next assembly with one
        // repeats the search and finds them)
        TimerOutput::Scope ts(timer, "Contact: search");
        if (!particle_contact.update_search(solution_ghosted, search_margin) &&
            with_matrix)
          setup_matrix();
      }
    residual = 0;
    if (with_matrix)
      tangent = 0;
    assemble_internal(residual, with_matrix);

    if (body_force.norm() > 0)
      add_body_force(residual);

    AssemblyResult result;
    const double   internal_norm = residual.l2_norm();
    {
      TimerOutput::Scope tc(timer, "Assembly: tool contact");
      result.contact = tool_contact.assemble(*mapping,
                                             solution_ghosted,
                                             residual,
                                             with_matrix ? &tangent : nullptr,
                                             tangent_margin);
    }
    if (has_particle_contact)
      {
        TimerOutput::Scope tc(timer, "Assembly: particle contact");
        result.particle_contact =
          particle_contact.assemble(*mapping,
                                    solution_ghosted,
                                    residual,
                                    with_matrix ? &tangent : nullptr,
                                    tangent_margin);
      }
    last_pole_force = add_pole_springs(with_matrix);
    residual.compress(VectorOperation::add);
    if (with_matrix)
      {
        tangent.compress(VectorOperation::add);
        if (prm.solver.stabilisation > 0)
          tangent.add(1., stabilisation);
      }
    result.residual_norm = residual.l2_norm();
    double contact_total = 0;
    for (const double f : result.contact.normal_force)
      contact_total += f;
    contact_total += result.particle_contact.normal_force;
    result.reference_norm = std::max(internal_norm, contact_total);
    return result;
  }



  void
  Simulator::add_body_force(TrilinosWrappers::MPI::Vector &forces)
  {
    const QGaussSimplex<3>           quadrature(prm.mesh.degree + 1);
    FEValues<3>                      fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    const Tensor<1, 3>               b =
      interpolate(body_force_table, load_time) * body_force;
    Vector<double>                       cell_residual(fe->n_dofs_per_cell());
    std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_residual = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < dofs.size(); ++i)
              cell_residual(i) -=
                (b * fe_values[u].value(i, q)) * fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          forces.add(dofs, cell_residual);
        }
    forces.compress(VectorOperation::add);
  }



  std::pair<unsigned int, unsigned int>
  Simulator::solve_newton(const unsigned int step, const double margin)
  {
    // absolute floor: a force far below anything the scene can carry
    double E_max = 0, D_max = 0;
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        E_max = std::max(E_max, particle_material[p]->youngs_modulus());
        D_max = std::max(D_max, particles[p].diameter);
      }
    const double floor = 1e-12 * E_max * D_max * D_max;
    const double tol   = prm.solver.newton_tolerance;

    unsigned int linear_iterations = 0;
    // each Newton solve starts from the closest master facets; within it a
    // slave point keeps its facet while it stays near (hysteresis)
    if (has_particle_contact)
      particle_contact.reset_projections();
    AssemblyResult current = assemble(true, margin);
    if (has_particle_contact &&
        particle_contact.update_projections(*mapping, solution_ghosted))
      current = assemble(true, margin);
    double line_search_step = 1.;
    // the first trial of a line search is assembled with the tangent, which
    // serves the next Newton iteration if the trial is kept; it is wasted if
    // the line search goes on or contact points then change their master
    // facet. So after a Newton iteration whose first trial was not kept, the
    // next first trial is assembled without it (the late steps of the paper
    // scene keep fewer than half of their first trials)
    bool first_trial_kept = true;
    // inexact Newton (Solver/Adaptive linear tolerance): the forcing term
    // eta of Eisenstat and Walker (1996), choice 2 with gamma = 0.9 (their
    // safeguard acts only above 0.1, beyond eta_max here)
    constexpr double eta_max = 1e-2;
    double           eta     = eta_max;
    residual_history.clear();
    // Output/Verbose: the material points yielding in this increment at the
    // current iterate, and how many of them changed since the last iterate
    std::vector<char> was_plastic;
    const auto        plastic_points = [&]() {
      unsigned long n = 0, changed = 0;
      was_plastic.resize(trial_history.size(), 0);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (unsigned int k = 0; k < history_per_cell; ++k)
            {
              const std::size_t i =
                cell->active_cell_index() * history_per_cell + k;
              const char plastic =
                trial_history[i].eps_p > committed_history[i].eps_p;
              n += plastic;
              changed += (plastic != was_plastic[i]);
              was_plastic[i] = plastic;
            }
      return std::make_pair(Utilities::MPI::sum(n, comm),
                            Utilities::MPI::sum(changed, comm));
    };
    for (unsigned int it = 0; it <= prm.solver.max_newton_iterations; ++it)
      {
        residual_history.push_back(current.residual_norm);
        const double target = std::max(tol * current.reference_norm, floor);
        if (prm.output.verbose)
          {
            pcout << "    newton " << it << ": |R| = " << std::scientific
                  << std::setprecision(3) << current.residual_norm
                  << " (target " << target << "), contact points "
                  << current.contact.n_active +
                       current.particle_contact.n_active
                  << " (slip "
                  << current.contact.n_slip + current.particle_contact.n_slip
                  << ")";
            if (has_history)
              {
                const auto [n, changed] = plastic_points();
                pcout << ", yielding points " << n << " (changed " << changed
                      << ")";
              }
            pcout << ", line search " << std::defaultfloat << line_search_step
                  << std::endl;
          }
        if (current.residual_norm <= target)
          return {it, linear_iterations};
        if (it == prm.solver.max_newton_iterations)
          break;

        if (prm.solver.adaptive_linear_tolerance && it > 0)
          {
            const double ratio =
              current.residual_norm / residual_history[it - 1];
            eta = 0.9 * ratio * ratio;
            // no more accuracy than the Newton target can use
            eta = std::max(eta, 0.1 * target / current.residual_norm);
            eta = std::min(eta, eta_max);
          }
        double phi0;
        {
          residual *= -1.;
          increment                     = 0;
          const unsigned int factorized = linear_solver->n_factorizations();
          linear_iterations +=
            linear_solver->solve(tangent,
                                 increment,
                                 residual,
                                 prm.solver.adaptive_linear_tolerance ?
                                   std::max(eta, prm.solver.linear_tolerance) :
                                   0.);
          if (prm.output.verbose &&
              linear_solver->n_factorizations() != factorized)
            pcout << "      factorization: "
                  << linear_solver->factorization_statistics() << std::endl;
          // R.du, with residual = -R here
          phi0 = -(residual * increment);
        }
        if (prm.solver.stabilisation > 0)
          {
            TrilinosWrappers::MPI::Vector f_s(locally_owned, comm);
            stabilisation.vmult(f_s, increment);
            last_stabilisation_force = f_s.l1_norm();
          }

        // step limiter: no node moves by more than half the smallest element
        // size in one Newton iteration (nearly free rigid-body modes would
        // otherwise take huge, at finite strain distorting, steps)
        const double max_step = increment.linfty_norm();
        const double limit    = 0.5 * h_min;
        // line search (Solver/Line search): "residual" backtracks until |R|
        // falls; "energy" looks for the step where phi(s) = R(u + s du).du,
        // the derivative of the incremental energy along du, has fallen to
        // half of |phi(0)| (regula falsi with the Illinois modification in a
        // bracket of phi's sign change). phi(0) = -du.K.du < 0 unless du is no
        // descent direction; then the residual search is used.
        const double   r0     = current.residual_norm;
        const double   s_max  = (max_step > limit ? limit / max_step : 1.);
        const bool     energy = prm.solver.line_search == "energy" && phi0 < 0;
        double         s = s_max, s_applied = 0;
        double         lo = 0, phi_lo = phi0, hi = s_max;
        double         phi_hi = std::numeric_limits<double>::infinity();
        int            kept   = 0; // Illinois: the bracket end moved last
        AssemblyResult trial;
        bool           have_matrix = true;
        unsigned int   n_trials    = 0;
        for (unsigned int ls = 0;; ++ls)
          {
            solution.add(s - s_applied, increment);
            s_applied   = s;
            have_matrix = (ls == 0 && first_trial_kept);
            n_trials    = ls + 1;
            bool failed = false;
            try
              {
                // the first trial refreshes the contact search, with or
                // without the tangent, so that its residual is the same
                trial = assemble(have_matrix, 0., ls == 0);
              }
            catch (const std::runtime_error &)
              {
                // e.g. an element inverted by the full step: try a shorter
                // one (the failure is collective, so all ranks agree)
                if (ls == 8)
                  throw;
                trial.residual_norm = std::numeric_limits<double>::infinity();
                failed              = true;
              }
            const double phi = (energy && !failed) ? residual * increment : 0.;
            // a NaN in the residual: a failed trial (thrown below if the
            // last)
            failed = failed || !std::isfinite(phi);
            if (prm.output.verbose)
              {
                pcout << "        trial step " << s
                      << ": |R| = " << trial.residual_norm;
                if (energy)
                  pcout << ", R.du/|R0.du| = " << phi / std::abs(phi0);
                pcout << ", penetration (tools, particles) "
                      << trial.contact.max_penetration << ", "
                      << trial.particle_contact.max_penetration << " mm"
                      << std::endl;
              }
            if (!energy)
              {
                if (trial.residual_norm < (1. - 1e-4 * s) * r0 || ls == 8)
                  break;
                // back to u, then the shorter step (the same round-off as
                // before the energy search existed)
                solution.add(-s, increment);
                s_applied = 0;
                s *= 0.5;
                continue;
              }
            if (ls == 8 || (!failed && (std::abs(phi) <= 0.5 * std::abs(phi0) ||
                                        (phi < 0 && s == s_max))))
              break;
            if (failed || phi > 0)
              {
                hi     = s;
                phi_hi = failed ? std::numeric_limits<double>::infinity() : phi;
                if (kept == 1)
                  phi_lo *= 0.5;
                kept = 1;
              }
            else
              {
                lo     = s;
                phi_lo = phi;
                if (kept == -1)
                  phi_hi *= 0.5;
                kept = -1;
              }
            s = std::isfinite(phi_hi) ?
                  lo + (hi - lo) * phi_lo / (phi_lo - phi_hi) :
                  0.5 * (lo + hi);
            s = std::min(std::max(s, lo + 0.01 * (hi - lo)),
                         hi - 0.01 * (hi - lo));
          }
        s = s_applied;
        if (!std::isfinite(trial.residual_norm))
          throw std::runtime_error(
            "step " + std::to_string(step) +
            ": the residual became NaN or infinite; try more steps "
            "(Time stepping/Number of steps) or a smaller Contact/Penalty "
            "factor");
        if (prm.output.verbose)
          pcout << "      line search: max|du| " << std::setprecision(3)
                << max_step << " mm, step " << s << ", "
                << trial.contact.n_active << " contact points" << std::endl;
        const unsigned int n_reassigned =
          has_particle_contact ?
            particle_contact.update_projections(*mapping, solution_ghosted) :
            0;
        const bool reassigned = n_reassigned > 0;
        if (prm.output.verbose && reassigned)
          pcout << "      " << n_reassigned
                << " contact points changed their master facet" << std::endl;
        current = (have_matrix && !reassigned) ? trial : assemble(true);
        first_trial_kept = n_trials == 1 && !reassigned;
        line_search_step = s;
      }
    std::ostringstream msg;
    msg << "step " << step << ": Newton did not converge in "
        << prm.solver.max_newton_iterations << " iterations (residual "
        << std::scientific << std::setprecision(2) << current.residual_norm
        << " N, target " << std::max(tol * current.reference_norm, floor)
        << " N); try more steps (Time stepping/Number of steps) or raise "
           "Solver/Maximum Newton iterations";
    throw std::runtime_error(msg.str());
  }



  std::vector<ParticleMeasure>
  Simulator::measure_particles() const
  {
    TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                          locally_relevant,
                                          comm);
    ghosted = solution;
    return densify::measure_particles(dof_handler,
                                      *mapping,
                                      prm.mesh.degree,
                                      ghosted,
                                      particles,
                                      particle_material,
                                      comm);
  }



  std::vector<double>
  Simulator::particle_volumes() const
  {
    std::vector<double> volume;
    for (const ParticleMeasure &m : measure_particles())
      volume.push_back(m.volume);
    return volume;
  }



  std::vector<Tensor<1, 3>>
  Simulator::particle_mean_displacements() const
  {
    std::vector<Tensor<1, 3>> mean;
    for (const ParticleMeasure &m : measure_particles())
      mean.push_back(m.mean_displacement);
    return mean;
  }



  Simulator::ContactResults
  Simulator::solve_increment(const double       time,
                             const unsigned int step,
                             StepStatistics    &s)
  {
    const double upper = upper_punch_position(time);
    set_loads(time, time - current_time);
    const double punch_increment = std::abs(upper - current_upper);
    // predictor: extrapolate the last increment in proportion to the punch
    // travel
    const TrilinosWrappers::MPI::Vector start = solution;
    if (last_punch_increment > 0)
      solution.add(punch_increment / last_punch_increment, last_increment);

    ContactResults contact;
    for (unsigned int aug = 0;; ++aug)
      {
        // predictor margin: contacts within this increment's punch travel
        const auto [newton, linear] =
          solve_newton(step, aug == 0 ? punch_increment : 0.);
        s.newton_iterations += newton;
        s.linear_iterations += linear;
        {
          TimerOutput::Scope t(timer, "Contact: multipliers");
          contact.tools = tool_contact.evaluate(*mapping, solution_ghosted);
          if (has_particle_contact)
            contact.particles =
              particle_contact.evaluate(*mapping, solution_ghosted);
          const double penetration =
            std::max(contact.tools.max_penetration,
                     contact.particles.max_penetration);
          if (penetration <= prm.contact.gap_tolerance ||
              aug == prm.contact.max_augmentations)
            break;
          tool_contact.update_multipliers(*mapping, solution_ghosted);
          if (has_particle_contact)
            particle_contact.update_multipliers(*mapping, solution_ghosted);
        }
        ++s.augmentations;
      }
    const double penetration = std::max(contact.tools.max_penetration,
                                        contact.particles.max_penetration);
    if (penetration > prm.contact.gap_tolerance)
      pcout << "  warning: penetration " << penetration
            << " mm above Contact/Gap tolerance after "
            << prm.contact.max_augmentations
            << " augmentations; raise Contact/Maximum augmentations or "
               "Contact/Penalty factor"
            << std::endl;

    // the converged increment, for the next predictor
    last_increment = solution;
    last_increment -= start;
    last_punch_increment = punch_increment;
    current_upper        = upper;
    return contact;
  }



  Simulator::ContactResults
  Simulator::advance_to(const double       time,
                        const unsigned int step,
                        StepStatistics    &s)
  {
    const double   step_length       = prm.time.end_time / prm.time.n_steps;
    double         dt                = next_increment;
    unsigned int   cutbacks_in_a_row = 0;
    ContactResults contact;
    while (current_time < time - 1e-12 * step_length)
      {
        // the increment that reaches the end of the step ends exactly there:
        // a round-off remainder would make one more, tiny increment, and the
        // next step would start from it (measured: 42 increments and 349
        // Newton iterations for step 248 of the 43-sphere layer)
        const bool   last  = dt >= (time - current_time) * (1. - 1e-9);
        const double t_end = last ? time : current_time + dt;
        // what a failed increment must restore
        const TrilinosWrappers::MPI::Vector saved_solution  = solution;
        const TrilinosWrappers::MPI::Vector saved_increment = last_increment;
        const ToolContact::State            saved_tools = tool_contact.state();
        const ParticleContact::State saved_particles = particle_contact.state();
        const double                 saved_punch     = last_punch_increment;
        const double                 saved_upper     = current_upper;
        const unsigned int           newton_before   = s.newton_iterations;
        try
          {
            contact = solve_increment(t_end, step, s);
          }
        catch (const std::runtime_error &e)
          {
            dt             = t_end - current_time;
            solution       = saved_solution;
            last_increment = saved_increment;
            tool_contact.set_state(saved_tools);
            particle_contact.set_state(saved_particles);
            last_punch_increment = saved_punch;
            current_upper        = saved_upper;
            update_ghosts();
            // at most max_cutbacks halvings in a row, and never below
            // step_length / 2^max_cutbacks (a load that can only creep on in
            // ever smaller increments, e.g. beyond the friction limit, stops)
            const double smallest =
              step_length *
              std::ldexp(1., -static_cast<int>(prm.time.max_cutbacks));
            if (cutbacks_in_a_row == prm.time.max_cutbacks ||
                dt / 2 < smallest * (1 - 1e-9))
              throw ConvergenceError(
                std::string(e.what()) +
                (prm.time.max_cutbacks > 0 ?
                   " (also after " + std::to_string(s.cutbacks) +
                     " cut-backs, the increment down to " +
                     std::to_string(dt / step_length) +
                     " of a step; raise Time stepping/Maximum cut-backs)" :
                   " (no cut-back tried: Time stepping/Maximum cut-backs = "
                   "0)"));
            dt /= 2;
            ++cutbacks_in_a_row;
            ++s.cutbacks;
            pcout << "  step " << step << ": increment cut back to "
                  << std::setprecision(3) << dt / step_length << " of a step ("
                  << one_line(e.what()) << ")" << std::endl;
            continue;
          }
        // accepted: commit the history of the material and of friction
        if (has_history)
          committed_history = trial_history;
        update_ghosts();
        tool_contact.commit(*mapping, solution_ghosted);
        if (has_particle_contact)
          particle_contact.commit(*mapping, solution_ghosted);
        committed_ghosted = solution;
        current_time      = t_end;
        ++s.increments;
        cutbacks_in_a_row = 0;
        // easy increments let the increment grow again, up to a full step
        if (s.newton_iterations - newton_before <= 10)
          dt = std::min(2 * dt, step_length);
      }
    next_increment = dt;
    return contact;
  }



  void
  Simulator::write_graphics(const unsigned int step, const double time)
  {
    TimerOutput::Scope t(timer, "Output: graphics");
    update_ghosts();
    const bool friction =
      tool_contact.has_friction() ||
      (has_particle_contact && prm.contact.friction_coefficient > 0);
    graphics.write(step,
                   time,
                   dof_handler,
                   *mapping,
                   prm.mesh.degree,
                   solution_ghosted,
                   particle_material,
                   has_history ? &committed_history : nullptr,
                   history_per_cell,
                   nodal_averaging.get(),
                   tool_contact,
                   has_particle_contact ? &particle_contact : nullptr,
                   friction,
                   prm.output.directory,
                   comm);
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
      pcout << "Active effects: ";
      for (unsigned int i = 0; i < laws.size(); ++i)
        pcout << (i > 0 ? ", " : "") << laws[i];
      auto friction_text = [&](const double mu) {
        std::ostringstream text;
        if (mu > 0)
          text << "friction " << mu << " "
               << (prm.contact.friction_model == "arctangent" ? "arctangent" :
                                                                "Coulomb");
        else
          text << "frictionless";
        return text.str();
      };
      for (const RigidTool &tool : tool_contact.tools())
        pcout << ", " << tool_name(tool.kind) << " contact ("
              << friction_text(tool_friction[static_cast<unsigned>(tool.kind)])
              << ")";
      if (has_particle_contact)
        pcout << ", particle-particle contact ("
              << friction_text(prm.contact.friction_coefficient) << ")";
      if (has_history)
        pcout << ", plastic history";
      if (nodal_averaging)
        pcout << ", nodal-averaged F-bar (P1 locking remedy)";
      if (method == Method::explicit_dynamics)
        pcout << "; explicit dynamics (lumped mass, "
              << prm.explicit_dynamics.mass_scaling << " mass scaling)";
      else
        {
          pcout << "; linear solver " << linear_solver_type;
          if (geometric_tangent)
            pcout << ", geometric contact tangent";
        }
      pcout << std::endl;
      if (!prm.fidelity_summary.empty())
        pcout << "Fidelity: " << prm.fidelity_summary << std::endl;
    }

    const double die_area =
      numbers::PI * std::pow(prm.tools.die_diameter / 2, 2);
    const bool has_density = prm.tools.die_enabled && prm.tools.lower_enabled &&
                             prm.tools.upper_enabled;
    auto density = [&](const double volume, const double upper) {
      return has_density ?
               volume / (die_area * (upper - prm.tools.lower_position)) :
               std::numeric_limits<double>::quiet_NaN();
    };
    {
      double v0 = 0;
      for (const double v : particle_volumes())
        v0 += v;
      if (has_density)
        pcout << "Initial relative density " << std::fixed
              << std::setprecision(2) << 100 * density(v0, upper_initial)
              << " % (particle volume of the mesh " << std::setprecision(4)
              << v0 << " mm^3)" << std::defaultfloat << std::endl;
    }

    for (const ParticleMeasure &m : measure_particles())
      initial_volumes.push_back(m.volume);
    // a resumed run continues after the checkpoint's step, appending to the
    // files' rows up to that step
    if (method == Method::explicit_dynamics)
      {
        // at rest at the start (or at the checkpoint's state, which
        // read_checkpoint() then restores)
        const double dt = explicit_dynamics->start(
          *this, solution, prm.explicit_dynamics.mass_scaling != "none");
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

    const unsigned int n_steps = prm.time.n_steps;
    for (unsigned int step = first_step; step <= n_steps; ++step)
      {
        Timer          step_timer;
        const double   time  = prm.time.end_time * step / n_steps;
        const double   upper = upper_punch_position(time);
        StepStatistics s;
        s.step                   = step;
        s.time                   = time;
        s.punch_displacement     = upper_initial - upper;
        last_stabilisation_force = 0;
        ContactResults results;
        try
          {
            results = method == Method::explicit_dynamics ?
                        advance_explicit(time, step, s) :
                        advance_to(time, step, s);
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
        const std::vector<unsigned int> partners =
          has_particle_contact ?
            particle_contact.contact_partners(*mapping, solution_ghosted) :
            std::vector<unsigned int>(particles.size(), 0);
        for (const unsigned int n : partners)
          s.contact_pairs += n;
        s.contact_pairs /= 2;
        const std::vector<double> die_force =
          tool_contact.particle_forces(*mapping,
                                       solution_ghosted,
                                       ToolKind::die_wall);
        s.pole_force                                = last_pole_force;
        const std::vector<ParticleMeasure> measures = measure_particles();
        for (const ParticleMeasure &m : measures)
          s.particle_volume += m.volume;
        // what rank 0 cannot write (e.g. a full disk) ends the run on every
        // rank; the rows written before stay complete
        std::string write_failure;
        if (this_rank == 0)
          write_failure = particle_writer->write(
            step, particles, measures, initial_volumes, partners, die_force);
        s.relative_density = density(s.particle_volume, upper);
        s.plastic_work     = plastic_work();
        if (method == Method::explicit_dynamics)
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
          write_graphics(step, time);

        s.step_seconds = step_timer.wall_time();
        s.wall_seconds = wall_before + wall.wall_time();
        step_statistics.push_back(s);
        if (statistics_writer && write_failure.empty())
          write_failure = statistics_writer->write(s);
        write_failure = first_error(write_failure, comm);
        if (!write_failure.empty())
          throw std::runtime_error(write_failure);

        const double left = (s.wall_seconds - wall_before) /
                            (step + 1 - first_step) * (n_steps - step);
        pcout << "step " << step << "/" << n_steps
              << "  t=" << std::setprecision(4) << time << " s  punch "
              << s.punch_displacement << " mm  F_upper " << std::setprecision(5)
              << s.upper_punch_force << " N  F_lower " << s.lower_punch_force
              << " N  F_die " << s.die_wall_radial_force << " N  F_stab "
              << std::setprecision(2) << s.stabilisation_force << " N";
        if (prm.contact.hold_poles != "false")
          pcout << "  F_pole " << std::setprecision(2) << s.pole_force << " N";
        if (has_density)
          pcout << "  density " << std::setprecision(4)
                << 100 * s.relative_density << " %";
        if (method == Method::explicit_dynamics)
          pcout << "  explicit " << s.increments << " steps (dt "
                << std::setprecision(3) << s.time_step << " s)  KE/IE "
                << std::setprecision(2)
                << 100. * s.kinetic_energy / std::max(s.internal_work, 1e-300)
                << " %";
        else
          {
            pcout << "  newton " << s.newton_iterations << " (cg "
                  << s.linear_iterations << ", aug " << s.augmentations;
            if (s.cutbacks > 0)
              pcout << ", " << s.cutbacks << " cut-back(s), " << s.increments
                    << " increments";
            pcout << ")";
          }
        pcout << "  " << format_seconds(s.wall_seconds) << ", ~"
              << format_seconds(left) << " left" << std::endl;

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
        if (stop || (prm.output.checkpoint_interval > 0 && step < n_steps &&
                     step % prm.output.checkpoint_interval == 0))
          write_checkpoint(step, s.wall_seconds);
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
    pcout << "Finished " << n_steps << " steps in "
          << format_seconds(wall_before + wall.wall_time()) << "; results in "
          << prm.output.directory << "/" << std::endl;
    timer.print_summary();
    return true;
  }
} // namespace densify
