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
    update_ghosts();
    if ((with_matrix || search) && particle_contact)
      {
        // refresh the particle contact search; new couplings need a new
        // matrix pattern (without a tangent the next assembly with one
        // repeats the search and finds them)
        TimerOutput::Scope ts(timer, "Contact: search");
        if (!particle_contact->update_search(solution_ghosted, search_margin) &&
            with_matrix)
          setup_matrix();
      }
    residual = 0;
    if (with_matrix)
      tangent = 0;
    Evaluation result;
    result.reference_norm =
      assemble_terms(residual, with_matrix, tangent_margin);
    result.residual_norm         = residual.l2_norm();
    const ContactResults contact = contact_results();
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
    if (stabilisation)
      last_stabilisation_force = stabilisation->force(du);
    return iterations;
  }



  void
  Simulator::add_pseudo_mass(const double factor)
  {
    Assert(stabilisation, ExcInternalError());
    stabilisation->add_scaled(tangent, factor);
  }



  void
  Simulator::begin_solve()
  {
    // each Newton solve starts from the closest master facets, assigned
    // before its first assembly; within it a slave point keeps its facet
    // while it stays near (hysteresis)
    if (particle_contact)
      {
        update_ghosts();
        particle_contact->reset_projections();
        particle_contact->update_projections(*mapping, solution_ghosted);
      }
  }



  void
  Simulator::set_secant_tangent(const bool on)
  {
    if (tool_contact)
      tool_contact->set_slip_secant(on);
    if (particle_contact)
      particle_contact->set_slip_secant(on);
  }



  unsigned int
  Simulator::after_update()
  {
    update_ghosts();
    return particle_contact ?
             particle_contact->update_projections(*mapping, solution_ghosted) :
             0;
  }



  std::string
  Simulator::iteration_details()
  {
    if (!continuum->has_history())
      return "";
    // the material points yielding in this increment at the current
    // iterate, and how many of them changed since the last iterate
    const std::vector<MaterialState> &now      = continuum->trial();
    const std::vector<MaterialState> &old      = continuum->committed();
    const unsigned int                per_cell = continuum->states_per_cell();
    unsigned long                     n = 0, changed = 0;
    was_plastic.resize(now.size(), 0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int k = 0; k < per_cell; ++k)
          {
            const std::size_t i      = cell->active_cell_index() * per_cell + k;
            const Material &material = *particle_material[cell->material_id()];
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
    plan_punches(time, time - increment, 1.);
    return apply_loads(time, increment);
  }



  void
  Simulator::plan_punches(const double time,
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



  bool
  Simulator::rigid_predictor(TrilinosWrappers::MPI::Vector &increment)
  {
    if (rigid_shift == 0.)
      return false;
    ComponentMask axial(3, false);
    axial.set(2, true);
    for (const types::global_dof_index i :
         DoFTools::extract_dofs(dof_handler, axial))
      increment[i] = rigid_shift;
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
    const bool upper_reached = punch_control.correct(
      force[static_cast<unsigned int>(ToolKind::upper_punch)], scale);
    const bool lower_reached = lower_control.correct(
      force[static_cast<unsigned int>(ToolKind::lower_punch)], lower_scale);
    if (upper_reached && lower_reached)
      return true;
    if (upper_reached)
      scale = lower_scale;
    // the same increment, from the committed time
    apply_loads(load_time, load_time - current_time);
    return false;
  }



  double
  Simulator::apply_loads(const double time, const double increment)
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



  double
  Simulator::evaluate_constraints()
  {
    TimerOutput::Scope t(timer, "Contact: multipliers");
    ContactResults     contact;
    if (tool_contact)
      contact.tools = tool_contact->evaluate(*mapping, solution_ghosted);
    if (particle_contact)
      contact.particles =
        particle_contact->evaluate(*mapping, solution_ghosted);
    last_contact = contact;
    return std::max(contact.tools.max_penetration,
                    contact.particles.max_penetration);
  }



  void
  Simulator::update_multipliers()
  {
    TimerOutput::Scope t(timer, "Contact: multipliers");
    if (tool_contact)
      tool_contact->update_multipliers(*mapping, solution_ghosted);
    if (particle_contact)
      particle_contact->update_multipliers(*mapping, solution_ghosted);
  }



  void
  Simulator::save_state()
  {
    for (ForceTerm *term : other_terms)
      term->save();
  }



  void
  Simulator::restore_state()
  {
    for (ForceTerm *term : other_terms)
      term->restore();
    update_ghosts();
  }



  void
  Simulator::commit()
  {
    // the history of the material and of friction
    update_ghosts();
    const AssemblyContext c = context();
    for (ForceTerm *term : bulk_terms)
      term->commit(c);
    for (ForceTerm *term : other_terms)
      term->commit(c);
    committed_ghosted = solution;
    punch_control.accept(
      last_contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::upper_punch)]);
    lower_control.accept(
      last_contact.tools
        .normal_force[static_cast<unsigned int>(ToolKind::lower_punch)]);
    current_upper = upper_punch_position(load_time);
  }
} // namespace densify
