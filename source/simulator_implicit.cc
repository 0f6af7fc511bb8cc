// The Simulator as the problem of the implicit method: the residual and
// tangent of the force terms for the NewtonSolver, the loads, the contact
// augmentation and the commit and roll-back of an increment for the
// LoadStepper.
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/component_mask.h>

#include <densify/simulator.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace densify
{
  NonlinearProblem::Evaluation
  Simulator::assemble(const bool   with_matrix,
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
  Simulator::solve_linear(const TrilinosWrappers::MPI::Vector &rhs,
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
  Simulator::add_pseudo_mass(const double factor)
  {
    Assert(system.stabilisation, ExcInternalError());
    system.stabilisation->add_scaled(tangent, factor);
  }



  void
  Simulator::begin_solve()
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
  Simulator::set_secant_tangent(const bool on)
  {
    if (system.tool_contact)
      system.tool_contact->set_slip_secant(on);
    if (system.particle_contact)
      system.particle_contact->set_slip_secant(on);
  }



  unsigned int
  Simulator::after_update()
  {
    system.update_ghosts();
    return system.particle_contact ?
             system.particle_contact->update_projections(
               *system.mapping, system.solution_ghosted) :
             0;
  }



  std::string
  Simulator::iteration_details()
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
    return ", yielding points " + std::to_string(Utilities::MPI::sum(n, comm)) +
           " (changed " + std::to_string(Utilities::MPI::sum(changed, comm)) +
           ")";
  }



  double
  Simulator::set_loads(const double time, const double increment)
  {
    system.plan_punches(time, time - increment, 1.);
    return system.apply_loads(time, increment);
  }



  bool
  Simulator::rigid_predictor(TrilinosWrappers::MPI::Vector &increment)
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
  Simulator::loads_reached(double &scale)
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
  Simulator::evaluate_constraints()
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
  Simulator::update_multipliers()
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
  Simulator::save_state()
  {
    for (ForceTerm *term : system.other_terms)
      term->save();
  }



  void
  Simulator::restore_state()
  {
    for (ForceTerm *term : system.other_terms)
      term->restore();
    system.update_ghosts();
  }



  void
  Simulator::commit()
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
