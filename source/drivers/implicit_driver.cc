// The implicit method's driver: the multi-body system as the problem of the
// LoadStepper and the NewtonSolver (residual and tangent of the force
// terms, linear solves, loads, contact augmentation, commit and roll-back of
// an increment).
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/component_mask.h>

#include <densify/drivers/implicit_driver.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace densify
{
  ImplicitDriver::ImplicitDriver(const Parameters   &parameters,
                                 MultiBodySystem    &system,
                                 ConditionalOStream &pcout,
                                 TimerOutput        &timer)
    : prm(parameters)
    , system(system)
    , pcout(pcout)
    , timer(timer)
  {}



  void
  ImplicitDriver::setup()
  {
    residual.reinit(system.locally_owned, system.comm);
    setup_matrix();

    NewtonControl newton_control;
    newton_control.tolerance      = prm.solver.newton_tolerance;
    newton_control.max_iterations = prm.solver.max_newton_iterations;
    newton_control.line_search    = system.effects.line_search;
    newton_control.adaptive_linear_tolerance =
      prm.solver.adaptive_linear_tolerance;
    newton_control.linear_tolerance = prm.solver.linear_tolerance;
    // no node moves by more than half the smallest element size in one
    // Newton iteration
    newton_control.step_limit         = 0.5 * system.h_min;
    newton_control.secant_start       = system.effects.friction_secant_start;
    newton_control.verbose            = prm.output.verbose;
    newton_control.continuation       = system.effects.continuation;
    newton_control.continuation_start = prm.solver.pseudo_mass;
    // absolute floor: a force far below anything the scene can carry
    double E_max = 0, D_max = 0;
    for (unsigned int p = 0; p < system.particles.size(); ++p)
      {
        E_max = std::max(E_max, system.particle_material[p]->youngs_modulus());
        D_max = std::max(D_max, system.particles[p].diameter);
      }
    newton_control.floor = 1e-12 * E_max * D_max * D_max;
    newton = std::make_unique<NewtonSolver>(newton_control, pcout);

    LoadStepperControl stepper_control;
    stepper_control.step_length       = prm.time.end_time / prm.time.n_steps;
    stepper_control.max_cutbacks      = prm.time.max_cutbacks;
    stepper_control.gap_tolerance     = prm.contact.gap_tolerance;
    stepper_control.max_augmentations = prm.contact.max_augmentations;
    stepper = std::make_unique<LoadStepper>(stepper_control, *newton, pcout);
    stepper->setup(system.solution);

    linear_solver =
      std::make_unique<LinearSolver>(system.effects.linear_solver,
                                     prm.solver.linear_tolerance,
                                     prm.solver.max_linear_iterations,
                                     prm.solver.reuse_amg,
                                     prm.solver.reproducible,
                                     timer);
    linear_solver->setup_null_space(system.dof_handler,
                                    *system.mapping,
                                    system.locally_owned);
  }



  void
  ImplicitDriver::setup_matrix()
  {
    TimerOutput::Scope                t(timer, "Setup: matrix");
    TrilinosWrappers::SparsityPattern sp(system.locally_owned, system.comm);
    DoFTools::make_sparsity_pattern(system.dof_handler,
                                    sp,
                                    AffineConstraints<double>(),
                                    false,
                                    Utilities::MPI::this_mpi_process(
                                      system.comm));
    for (ForceTerm *term : system.bulk_terms)
      term->add_couplings(sp);
    for (ForceTerm *term : system.other_terms)
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
    if (system.stabilisation)
      system.stabilisation->reinit(sp, *system.mapping);
  }



  ContactResults
  ImplicitDriver::advance(const double       time,
                          const unsigned int step,
                          StepStatistics    &s)
  {
    last_stabilisation_force = 0.;
    StepCounts counts;
    stepper->advance_to(*this, system.current_time, time, step, counts);
    s.newton_iterations        = counts.newton_iterations;
    s.linear_iterations        = counts.linear_iterations;
    s.augmentations            = counts.augmentations;
    s.cutbacks                 = counts.cutbacks;
    s.continuations            = counts.continuations;
    s.failed_checks            = counts.failed_checks;
    s.failed_newton_iterations = counts.failed_newton_iterations;
    s.increments               = counts.increments;
    s.stabilisation_force      = last_stabilisation_force;
    return last_contact;
  }



  ImplicitDriver::Saved
  ImplicitDriver::saved() const
  {
    Saved saved;
    saved.increment.reserve(system.locally_owned.n_elements());
    for (const types::global_dof_index i : system.locally_owned)
      saved.increment.push_back(stepper->last_increment[i]);
    saved.next_increment = stepper->next_increment;
    saved.last_travel    = stepper->last_travel;
    return saved;
  }



  void
  ImplicitDriver::restore(const Saved &saved)
  {
    AssertDimension(saved.increment.size(), system.locally_owned.n_elements());
    unsigned int k = 0;
    for (const types::global_dof_index i : system.locally_owned)
      stepper->last_increment[i] = saved.increment[k++];
    stepper->last_increment.compress(VectorOperation::insert);
    stepper->next_increment = saved.next_increment;
    stepper->last_travel    = saved.last_travel;
  }



  void
  ImplicitDriver::write_checkpoint(
    boost::archive::binary_oarchive &archive) const
  {
    const Saved state = saved();
    archive    &state;
  }



  void
  ImplicitDriver::read_checkpoint(boost::archive::binary_iarchive &archive)
  {
    loaded = std::make_unique<Saved>();
    archive &*loaded;
  }



  void
  ImplicitDriver::resume()
  {
    Assert(loaded, ExcInternalError());
    restore(*loaded);
    loaded.reset();
    if (system.particle_contact)
      setup_matrix();
  }



  NonlinearProblem::Evaluation
  ImplicitDriver::assemble(const bool   with_matrix,
                           const double tangent_margin,
                           const bool   search)
  {
    TimerOutput::Scope t(timer,
                         with_matrix ? "Assembly: tangent+residual" :
                                       "Assembly: residual");
    system.update_ghosts();
    if ((with_matrix || search) && system.particle_contact)
      {
        // refresh the particle contact search; new couplings need a new
        // matrix pattern (without a tangent the next assembly with one
        // repeats the search and finds them)
        TimerOutput::Scope ts(timer, "Contact: search");
        if (!system.particle_contact->update_search(system.solution_ghosted,
                                                    system.search_margin) &&
            with_matrix)
          setup_matrix();
      }
    residual = 0;
    if (with_matrix)
      tangent = 0;
    Evaluation result;
    result.reference_norm =
      system.assemble_terms(residual,
                            with_matrix ? &tangent : nullptr,
                            tangent_margin);
    result.residual_norm         = residual.l2_norm();
    const ContactResults contact = system.contact_results();
    std::ostringstream   text;
    text << "contact points "
         << contact.tools.n_active + contact.particles.n_active << " (slip "
         << contact.tools.n_slip + contact.particles.n_slip
         << "), penetration (tools, particles) "
         << contact.tools.max_penetration << ", "
         << contact.particles.max_penetration << " mm";
    result.description = text.str();
    return result;
  }



  unsigned int
  ImplicitDriver::solve_linear(const TrilinosWrappers::MPI::Vector &rhs,
                               TrilinosWrappers::MPI::Vector       &du,
                               const double relative_tolerance)
  {
    const unsigned int factorized = linear_solver->n_factorizations();
    const unsigned int iterations =
      linear_solver->solve(tangent, du, rhs, relative_tolerance);
    if (prm.output.verbose && linear_solver->n_factorizations() != factorized)
      pcout << "      factorization: "
            << linear_solver->factorization_statistics() << std::endl;
    if (system.stabilisation)
      last_stabilisation_force = system.stabilisation->force(du);
    return iterations;
  }



  void
  ImplicitDriver::add_pseudo_mass(const double factor)
  {
    Assert(system.stabilisation, ExcInternalError());
    system.stabilisation->add_scaled(tangent, factor);
  }



  void
  ImplicitDriver::begin_solve()
  {
    // each Newton solve starts from the closest master facets, assigned
    // before its first assembly; within it a slave point keeps its facet
    // while it stays near (hysteresis)
    if (system.particle_contact)
      {
        system.update_ghosts();
        system.particle_contact->reset_projections();
        system.particle_contact->update_projections(*system.mapping,
                                                    system.solution_ghosted);
      }
  }



  void
  ImplicitDriver::set_secant_tangent(const bool on)
  {
    if (system.tool_contact)
      system.tool_contact->set_slip_secant(on);
    if (system.particle_contact)
      system.particle_contact->set_slip_secant(on);
  }



  unsigned int
  ImplicitDriver::after_update()
  {
    system.update_ghosts();
    return system.particle_contact ?
             system.particle_contact->update_projections(
               *system.mapping, system.solution_ghosted) :
             0;
  }



  std::string
  ImplicitDriver::iteration_details()
  {
    if (!system.continuum->has_history())
      return "";
    // the material points yielding in this increment at the current
    // iterate, and how many of them changed since the last iterate
    const std::vector<MaterialState> &now = system.continuum->trial();
    const std::vector<MaterialState> &old = system.continuum->committed();
    const unsigned int per_cell           = system.continuum->states_per_cell();
    unsigned long      n = 0, changed = 0;
    was_plastic.resize(now.size(), 0);
    for (const auto &cell : system.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int k = 0; k < per_cell; ++k)
          {
            const std::size_t i = cell->active_cell_index() * per_cell + k;
            const Material   &material =
              *system.particle_material[cell->material_id()];
            const char plastic = material.equivalent_plastic_strain(now[i]) >
                                 material.equivalent_plastic_strain(old[i]);
            n += plastic;
            changed += (plastic != was_plastic[i]);
            was_plastic[i] = plastic;
          }
    return ", yielding points " +
           std::to_string(Utilities::MPI::sum(n, system.comm)) + " (changed " +
           std::to_string(Utilities::MPI::sum(changed, system.comm)) + ")";
  }



  double
  ImplicitDriver::set_loads(const double time, const double increment)
  {
    system.plan_punches(time, time - increment, 1.);
    return system.apply_loads(time, increment);
  }



  bool
  ImplicitDriver::rigid_predictor(TrilinosWrappers::MPI::Vector &increment)
  {
    if (system.rigid_shift == 0.)
      return false;
    ComponentMask axial(3, false);
    axial.set(2, true);
    for (const types::global_dof_index i :
         DoFTools::extract_dofs(system.dof_handler, axial))
      increment[i] = system.rigid_shift;
    increment.compress(VectorOperation::insert);
    return true;
  }



  bool
  ImplicitDriver::loads_reached(double &scale)
  {
    const auto &force = last_contact.tools.normal_force;
    // each punch's correction from its own force (a punch whose move stands
    // keeps it; the solve's start scales with the force-controlled one's)
    double     lower_scale   = 1.;
    const bool upper_reached = system.punch_control.correct(
      force[static_cast<unsigned int>(ToolKind::upper_punch)], scale);
    const bool lower_reached = system.lower_control.correct(
      force[static_cast<unsigned int>(ToolKind::lower_punch)], lower_scale);
    if (upper_reached && lower_reached)
      return true;
    if (upper_reached)
      scale = lower_scale;
    // the same increment, from the committed time
    system.apply_loads(system.load_time,
                       system.load_time - system.current_time);
    return false;
  }



  double
  ImplicitDriver::evaluate_constraints()
  {
    TimerOutput::Scope t(timer, "Contact: multipliers");
    ContactResults     contact;
    if (system.tool_contact)
      contact.tools =
        system.tool_contact->evaluate(*system.mapping, system.solution_ghosted);
    if (system.particle_contact)
      contact.particles =
        system.particle_contact->evaluate(*system.mapping,
                                          system.solution_ghosted);
    last_contact = contact;
    return std::max(contact.tools.max_penetration,
                    contact.particles.max_penetration);
  }



  void
  ImplicitDriver::update_multipliers()
  {
    TimerOutput::Scope t(timer, "Contact: multipliers");
    if (system.tool_contact)
      system.tool_contact->update_multipliers(*system.mapping,
                                              system.solution_ghosted);
    if (system.particle_contact)
      system.particle_contact->update_multipliers(*system.mapping,
                                                  system.solution_ghosted);
  }



  void
  ImplicitDriver::save_state()
  {
    for (ForceTerm *term : system.other_terms)
      term->save();
  }



  void
  ImplicitDriver::restore_state()
  {
    for (ForceTerm *term : system.other_terms)
      term->restore();
    system.update_ghosts();
  }



  void
  ImplicitDriver::commit()
  {
    // the history of the material and of friction
    system.update_ghosts();
    const AssemblyContext c = system.context();
    for (ForceTerm *term : system.bulk_terms)
      term->commit(c);
    for (ForceTerm *term : system.other_terms)
      term->commit(c);
    system.committed_ghosted = system.solution;
    system.punch_control.accept(
      last_contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    system.lower_control.accept(
      last_contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);
    system.current_upper = system.upper_punch_position(system.load_time);
  }
} // namespace densify
