// Augmented-Lagrangian contact with Coulomb friction between particle
// surfaces and the rigid tools.
#pragma once

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/contact/contact_law.h>
#include <densify/contact/rigid_tools.h>

#include <array>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// What one evaluation of the tool contact produced (summed over ranks).
  struct ToolContactResult
  {
    /// Normal force on each tool (N, positive in compression), by ToolKind.
    std::array<double, n_tool_kinds> normal_force = {{0., 0., 0.}};
    /// Axial (z) force of each tool on the particles (N; normal and friction
    /// part), by ToolKind; for the die wall this is the wall friction that
    /// holds the compact (positive upwards).
    std::array<double, n_tool_kinds> axial_force = {{0., 0., 0.}};
    /// Friction force of each tool on the particles (N), by ToolKind.
    std::array<Tensor<1, 3>, n_tool_kinds> friction_force;
    /// Largest penetration over all quadrature points (mm, >= 0).
    double max_penetration = 0.;
    /// Number of quadrature points in contact.
    unsigned int n_active = 0;
    /// Number of them that slip (with friction).
    unsigned int n_slip = 0;
    /// Work the friction tractions dissipated in the increment since the
    /// last commit (mJ = N mm): -t . (slip + change of t/eps_t), the slip
    /// beyond the stick spring's; computed by commit() and
    /// assemble_and_commit() only.
    double friction_work = 0.;
    /// Elastic energy of the penalty springs now (mJ): 1/2 (p^2 / eps +
    /// |t|^2 / eps_t) over the contact points (the stored energy of pure
    /// penalty contact, without multipliers).
    double elastic_energy = 0.;
  };

  /**
   * Surface fields for output: lumped L2 projections onto a scalar P1 field,
   * each as (int phi_i f, int phi_i) pairs filled by project_fields().
   */
  struct SurfaceFieldSums
  {
    /// Contact pressure (MPa).
    TrilinosWrappers::MPI::Vector pressure;
    /// Accumulated slip (mm).
    TrilinosWrappers::MPI::Vector slip;
    /// 0 open, 1 stick, 2 slip.
    TrilinosWrappers::MPI::Vector status;
    /// The weights int phi_i over the surface.
    TrilinosWrappers::MPI::Vector weights;
  };

  /**
   * Contact of particle surfaces with rigid tools, enforced at the quadrature
   * points of the boundary faces (a segment-to-analytic-surface scheme): the
   * nominal pressure is p = max(0, lambda - eps g) with a multiplier lambda
   * per quadrature point and tool, updated by update_multipliers() (Uzawa),
   * and the tangential traction follows evaluate_contact_law() (Coulomb
   * return map or arctangent law) with its history committed by commit().
   * Its normal tangent eps n n^T (plus p/r times the tangential projector
   * for the concave die wall) and the symmetrised friction tangent are
   * symmetric positive semi-definite, so CG stays usable; the consistent
   * friction tangent (FrictionLaw::consistent) is exact, including how the
   * friction traction turns with the die wall's normal, and not symmetric. Only
   * enabled tools are stored and searched; a tool with mu = 0 runs no friction
   * code. Works on the locally owned cells of a parallel::shared triangulation.
   */
  class ToolContact
  {
  public:
    /**
     * Collect the boundary faces of the locally owned cells and set every
     * multiplier to zero. @p penalty_per_particle[material_id] is eps (MPa/mm);
     * @p friction[t] is the friction law of tools[t]. @p contact_quadrature
     * on the reference triangle gives the contact points of each face.
     */
    void
    setup(const DoFHandler<3>            &dof_handler,
          const std::vector<RigidTool>   &tools,
          const std::vector<FrictionLaw> &friction,
          const std::vector<double>      &penalty_per_particle,
          const Quadrature<2>            &contact_quadrature);

    /// Move a tool (its position), e.g. the upper punch at each step.
    void
    set_tool_position(const ToolKind kind, const double position);

    /// Move a tool tangentially (its rigid translation, mm; only the part
    /// along the tool surface matters, through friction).
    void
    set_tool_translation(const ToolKind kind, const Tensor<1, 3> &translation);

    /**
     * The displacement of the last accepted increment (with ghost entries),
     * from which friction measures slip; must outlive this object's use.
     */
    void
    set_committed_solution(const TrilinosWrappers::MPI::Vector &committed)
    {
      committed_solution = &committed;
    }

    /// Set the regularisation slip of the arctangent law (mm) for the next
    /// increment.
    void
    set_friction_regularisation(const double delta)
    {
      for (FrictionLaw &law : friction_laws)
        law.regularisation = delta;
    }

    /// Normal force (N) of the tool @p kind on each particle (by index) at
    /// @p solution, on every rank; > 0 where the particle touches the tool.
    std::vector<double>
    particle_forces(const Mapping<3>                    &mapping,
                    const TrilinosWrappers::MPI::Vector &solution,
                    const ToolKind                       kind) const;

    /// The enabled tools.
    const std::vector<RigidTool> &
    tools() const
    {
      return tool_list;
    }

    /// Is friction on at any tool?
    bool
    has_friction() const
    {
      return !committed_traction.empty();
    }

    /**
     * Add the contact contributions to the residual @p residual (R = f_int -
     * f_ext, so contact adds -(p n + t) . phi) and, if @p matrix is not null,
     * to the tangent. @p solution must have ghost entries. Quadrature points
     * not in contact but closer than @p tangent_margin (mm) get the penalty
     * stiffness in the tangent only (a predictor for contacts about to close;
     * the residual, hence the converged state, is unaffected). Returns forces,
     * summed over all ranks. Needs compress() on @p residual and @p matrix
     * afterwards.
     */
    ToolContactResult
    assemble(const Mapping<3>                    &mapping,
             const TrilinosWrappers::MPI::Vector &solution,
             TrilinosWrappers::MPI::Vector       &residual,
             TrilinosWrappers::SparseMatrix      *matrix,
             const double                         tangent_margin = 0.) const;

    /// Evaluate forces and penetration only (summed over ranks).
    ToolContactResult
    evaluate(const Mapping<3>                    &mapping,
             const TrilinosWrappers::MPI::Vector &solution) const;

    /**
     * assemble() without a tangent and commit() in one pass: add the contact
     * forces at @p solution to @p residual and accept @p solution as the
     * start of the next increment (explicit dynamics, where every step is
     * accepted). The result carries the friction work of the increment.
     */
    ToolContactResult
    assemble_and_commit(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution,
                        TrilinosWrappers::MPI::Vector       &residual);

    /// lambda <- max(0, lambda - eps g) at every quadrature point.
    void
    update_multipliers(const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution);

    /// Accept @p solution: its tangential tractions, slips and tool
    /// translations become the committed state of the next increment.
    void
    commit(const Mapping<3>                    &mapping,
           const TrilinosWrappers::MPI::Vector &solution);

    /**
     * Lumped L2 projection of pressure (sum over tools), accumulated slip and
     * stick/slip status onto the scalar field of @p post_dof_handler (same
     * triangulation): adds int phi_i f to the field sums and int phi_i to the
     * weights, on the surface.
     */
    void
    project_fields(const Mapping<3>                    &mapping,
                   const TrilinosWrappers::MPI::Vector &solution,
                   const DoFHandler<3>                 &post_dof_handler,
                   SurfaceFieldSums                    &sums) const;

    /// Everything a roll-back or a checkpoint must restore.
    struct State
    {
      /// Normal multipliers.
      std::vector<double> lambda;
      /// Committed tangential tractions.
      std::vector<Tensor<1, 3>> traction;
      /// Accumulated slip.
      std::vector<double> slip;
      /// Committed tool translations.
      std::vector<Tensor<1, 3>> translation;

      /// Write or read the state with a boost archive (checkpoints).
      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        archive &lambda &traction &slip &translation;
      }
    };

    /// The state (multipliers and friction history).
    State
    state() const
    {
      return {lambda, committed_traction, accumulated_slip, committed_shift};
    }

    /// Restore a state saved by state() (same setup).
    void
    set_state(const State &saved)
    {
      lambda             = saved.lambda;
      committed_traction = saved.traction;
      accumulated_slip   = saved.slip;
      committed_shift    = saved.translation;
    }

  private:
    /// What one pass over the contact points writes besides the forces.
    struct Outputs
    {
      TrilinosWrappers::MPI::Vector  *residual       = nullptr;
      TrilinosWrappers::SparseMatrix *matrix         = nullptr;
      double                          tangent_margin = 0.;
      std::vector<double>            *new_lambda     = nullptr;
      std::vector<Tensor<1, 3>>      *new_traction   = nullptr;
      std::vector<double>            *new_slip       = nullptr;
      const DoFHandler<3>            *post           = nullptr;
      SurfaceFieldSums               *sums           = nullptr;
      std::vector<double>            *particle_force = nullptr;
      ToolKind                        force_kind     = ToolKind::die_wall;
    };

    /// One pass over all contact quadrature points; the core of the class.
    ToolContactResult
    loop(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const Outputs                       &out) const;

    const DoFHandler<3>                 *dof_handler        = nullptr;
    const TrilinosWrappers::MPI::Vector *committed_solution = nullptr;
    std::vector<RigidTool>               tool_list;
    std::vector<FrictionLaw>             friction_laws;
    std::vector<Tensor<1, 3>>            shift, committed_shift;
    std::vector<double>                  penalty;
    Quadrature<2>                        face_quadrature;
    std::vector<std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
                              faces;
    std::vector<double>       lambda;
    std::vector<Tensor<1, 3>> committed_traction;
    std::vector<double>       accumulated_slip;
  };

  /**
   * Add @p cell_values (indexed by the post cell's DoFs) into the field sums
   * of @p sums: helper shared by the contact classes' projections.
   */
  void
  add_surface_field_values(const std::vector<types::global_dof_index> &dofs,
                           const Vector<double>                       &p,
                           const Vector<double>                       &slip,
                           const Vector<double>                       &status,
                           const Vector<double>                       &weights,
                           SurfaceFieldSums                           &sums);
} // namespace densify
