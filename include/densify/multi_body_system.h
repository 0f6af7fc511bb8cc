// The multi-body system: all particles in one triangulation and one
// DoFHandler, the displacement, the force terms of the scene's effects, their
// assembly, and the tools' loads.
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>

#include <deal.II/distributed/shared_tria.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/body_force.h>
#include <densify/assembly/continuum.h>
#include <densify/assembly/pole_springs.h>
#include <densify/assembly/stabilisation.h>
#include <densify/contact/particle_contact.h>
#include <densify/contact/punch_control.h>
#include <densify/contact/tool_contact.h>
#include <densify/effects.h>
#include <densify/geometry/particles.h>
#include <densify/material/material.h>
#include <densify/parameters.h>
#include <densify/postprocess/particle_measures.h>
#include <densify/scene.h>

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  /// Contact forces of the tools and between particles.
  struct ContactResults
  {
    ToolContactResult     tools;
    ParticleContactResult particles;
  };

  /**
   * The system both solution methods advance: the particles and their
   * materials, the multi-body mesh (parallel::shared::Triangulation with a
   * METIS partition, every rank holding the whole mesh and assembling its own
   * cells), the DoFs with no DoF shared between particles, the displacement,
   * the force terms that the scene's effects call for (each built only if its
   * effect is on), and the tools' positions and loads over time. It does
   * not advance itself: the ImplicitDriver and the ExplicitDriver read and
   * write its state. Effects::method decides only which terms it builds
   * (no pole springs or stabilisation under explicit dynamics), the
   * contact multipliers' relaxation and the punches' dynamic force control.
   */
  class MultiBodySystem
  {
  public:
    /// An empty system; the setup functions build it in their order.
    MultiBodySystem(const Parameters   &parameters,
                    const MPI_Comm      comm,
                    ConditionalOStream &pcout,
                    TimerOutput        &timer);

    /// The particles, their materials and the tools' histories of @p scene
    /// with its effects @p scene_effects.
    void
    setup_particles(Scene scene, const Effects &scene_effects);

    /// Mesh every particle into the one triangulation.
    void
    setup_mesh();

    /// The finite element, the DoFs and the displacement vectors.
    void
    setup_dofs();

    /// The contact penalty of each particle for the implicit method: its
    /// Young's modulus over the smallest element size times
    /// Contact/Penalty factor (MPa/mm).
    std::vector<double>
    contact_penalty() const;

    /// Build the force terms the effects call for, with the contact penalty
    /// @p penalty of each particle, in the order they add to the residual.
    void
    setup_force_terms(const std::vector<double> &penalty);

    /// Builds a force term over the system it is given, once the system's
    /// own terms are built (add_force_term()).
    using ForceTermFactory =
      std::function<std::unique_ptr<ForceTerm>(const MultiBodySystem &)>;

    /**
     * Add the force term that @p factory builds to every later
     * setup_force_terms(), after the contact terms, under both methods: a
     * term defined outside Densify's sources (a test, a program that links
     * Densify) joins the residual, the tangent, the commit, the roll-back
     * and the checkpoint as the system's own terms do.
     */
    void
    add_force_term(ForceTermFactory factory)
    {
      added_term_factories.push_back(std::move(factory));
    }

    /// Every force term that is on: the bulk terms, then the others.
    std::vector<ForceTerm *>
    force_terms() const
    {
      std::vector<ForceTerm *> all = bulk_terms;
      all.insert(all.end(), other_terms.begin(), other_terms.end());
      return all;
    }

    /// The context of an assembly at solution_ghosted.
    AssemblyContext
    context(const double tangent_margin = 0.) const;

    /**
     * Add every force term at solution_ghosted to @p forces (and to
     * @p matrix unless null), compressed; returns the reference norm of the
     * relative Newton criterion: the larger of the bulk forces' norm and the
     * total contact force (N).
     */
    double
    assemble_terms(TrilinosWrappers::MPI::Vector  &forces,
                   TrilinosWrappers::SparseMatrix *matrix,
                   const double                    tangent_margin);

    /// The contact results of the last assembly.
    ContactResults
    contact_results() const;

    /// Copy solution into the ghosted vector.
    void
    update_ghosts();

    /// Write this rank's part of the state at a station into a checkpoint:
    /// the time, the upper punch, the owned entries of the solution, the
    /// punches' controls and each force term's state.
    void
    write_checkpoint(boost::archive::binary_oarchive &archive) const;

    /// Read what write_checkpoint() wrote and take it up (take_up_solution()).
    void
    read_checkpoint(boost::archive::binary_iarchive &archive);

    /// The locally owned entries of solution, in the order of locally_owned.
    std::vector<double>
    owned_solution() const;

    /// Set solution to @p values (in the order of owned_solution()) as the
    /// accepted state: the committed solution, the ghosts and the particle
    /// contact search of that configuration.
    void
    take_up_solution(const std::vector<double> &values);

    /// Position of the upper punch face at time @p t (mm).
    double
    upper_punch_position(const double t) const;

    /// Position of the lower punch face at time @p t (mm).
    double
    lower_punch_position(const double t) const;

    /// Plan both punches' moves from @p before to @p time (PunchControl::
    /// plan() with @p gain): a force-controlled punch gives back the other,
    /// displacement-controlled punch's travel over the move.
    void
    plan_punches(const double time, const double before, const double gain);

    /// Set the tools, body force and friction scale for time @p time,
    /// reached by an increment of @p increment (both methods; the upper
    /// punch where punch_control has it); returns the larger punch travel
    /// over the increment (mm).
    double
    apply_loads(const double time, const double increment);

    /// Measure every particle (one pass over the cells; on every rank),
    /// @p with_stress its mean stresses too (a second pass, which evaluates
    /// the material).
    std::vector<ParticleMeasure>
    measure_particles(const bool with_stress = false) const;

    /// Current volume of each particle (mm^3), on every rank.
    std::vector<double>
    particle_volumes() const;

    /// Rigid translation of each particle: its mean displacement (mm).
    std::vector<Tensor<1, 3>>
    particle_mean_displacements() const;

    /// Normal force (N) of the tool @p kind on each particle now.
    std::vector<double>
    particle_tool_forces(const ToolKind kind) const;

    /// Number of particles each particle touches now.
    std::vector<unsigned int>
    contact_partners() const;

    /// The area a punch presses (mm^2): the die's bore, or without a die
    /// the particles' cross-sections.
    double
    pressed_area() const;

    const Parameters   &prm;
    MPI_Comm            comm;
    ConditionalOStream &pcout;
    TimerOutput        &timer;

    /// The effects of the scene, resolved once.
    Effects                                      effects;
    std::vector<Particle>                        particles;
    std::vector<std::shared_ptr<const Material>> particle_material;
    /// Per particle: the F-bar's weight of the cell's own volume change
    /// (Mesh/Cell volume stabilisation, NodalAveraging).
    std::vector<double> cell_volume_weights;
    /// The barrier against crushed cells (Mesh/Cell volume barrier), per
    /// particle the material's bulk modulus; off without nodal averaging.
    CellVolumeBarrier cell_volume_barrier;

    /// Height of the upper punch face at t = 0 (mm).
    double upper_initial = 0.;
    /// Where the upper punch is: its displacement and force histories.
    PunchControl punch_control;
    /// Where the lower punch is (its rise): its histories likewise.
    PunchControl lower_control;
    /// Height of the lower punch face at t = 0 (mm).
    double lower_initial = 0.;
    /// The smallest element size of the mesh (mm).
    double h_min = 0.;

    parallel::shared::Triangulation<3> triangulation;
    std::unique_ptr<FESystem<3>>       fe;
    std::unique_ptr<MappingFE<3>>      mapping;
    DoFHandler<3>                      dof_handler;
    IndexSet                           locally_owned, locally_relevant;
    /// The ghost entries of solution_ghosted: every DoF when particles can
    /// touch (masters may lie anywhere), else the locally relevant ones.
    IndexSet ghosted_dofs;

    TrilinosWrappers::MPI::Vector solution, solution_ghosted;
    /// solution_ghosted = solution with the communication plan kept.
    GhostImport ghost_import;
    /// The solution of the last accepted increment, with ghost entries
    /// (friction measures slip from it).
    TrilinosWrappers::MPI::Vector committed_ghosted;

    /// Time and upper punch position of the last accepted increment.
    double current_time = 0., current_upper = 0.;
    /// The time of the load being solved for (s).
    double load_time = 0.;
    /// The axial (z) translation of the whole compact that the planned
    /// move imposes (mm): the travel of the punch that moves by its history
    /// while the other follows it by force control (plan_punches()); 0
    /// otherwise.
    double rigid_shift = 0.;

    /// The force terms, each built only if its effect is on (else null).
    std::unique_ptr<Continuum>       continuum;
    std::unique_ptr<BodyForce>       body_force;
    std::unique_ptr<ToolContact>     tool_contact;
    std::unique_ptr<ParticleContact> particle_contact;
    std::unique_ptr<PoleSprings>     pole_springs;
    std::unique_ptr<Stabilisation>   stabilisation;
    /// The terms of add_force_term(): their factories and the terms built.
    std::vector<ForceTermFactory>           added_term_factories;
    std::vector<std::unique_ptr<ForceTerm>> added_terms;
    /// The force terms that are on, in the order they add to the residual:
    /// the bulk (continuum, body force), then the others.
    std::vector<ForceTerm *> bulk_terms, other_terms;
    /// Search margin of the particle contact (mm).
    double search_margin = 0.;
    /// The scene's body force and its factor against time, and the
    /// sideways upper punch displacement against time.
    Tensor<1, 3>                           scene_body_force;
    std::vector<std::pair<double, double>> body_force_table;
    std::vector<std::pair<double, double>> lateral_table;
    /// The die's top edge at t = 0 (infinity: none), and its upward
    /// displacement against time.
    double die_top = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, double>> die_table;

  private:
    /// A punch's largest speed under force control (mm/s): its Maximum
    /// speed @p max_speed if positive, or from its displacement history
    /// @p table.
    double
    force_control_speed(const std::vector<std::pair<double, double>> &table,
                        const double max_speed) const;
  };
} // namespace densify
