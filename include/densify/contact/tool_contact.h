// Augmented-Lagrangian normal contact between particle surfaces and the rigid
// tools.
#pragma once

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

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
    /// Axial (z) force on each tool (N), by ToolKind.
    std::array<double, n_tool_kinds> axial_force = {{0., 0., 0.}};
    /// Largest penetration over all quadrature points (mm, >= 0).
    double max_penetration = 0.;
    /// Number of quadrature points in contact.
    unsigned int n_active = 0;
  };

  /**
   * Normal contact of particle surfaces with rigid tools, enforced at the
   * quadrature points of the boundary faces (a segment-to-analytic-surface
   * scheme): the nominal pressure is p = max(0, lambda - eps g) with a
   * multiplier lambda per quadrature point and tool, updated by
   * update_multipliers() (Uzawa). Its tangent eps n n^T (plus p/r times the
   * tangential projector for the concave die wall) is symmetric positive
   * semi-definite, so CG stays usable. Only enabled tools are stored and
   * searched. Works on the locally owned cells of a parallel::shared
   * triangulation.
   */
  class ToolContact
  {
  public:
    /**
     * Collect the boundary faces of the locally owned cells and set every
     * multiplier to zero. @p penalty_per_particle[material_id] is eps (MPa/mm).
     */
    void
    setup(const DoFHandler<3>          &dof_handler,
          const std::vector<RigidTool> &tools,
          const std::vector<double>    &penalty_per_particle,
          const unsigned int            quadrature_points_1d);

    /// Move a tool (its position), e.g. the upper punch at each step.
    void
    set_tool_position(const ToolKind kind, const double position);

    /// The enabled tools.
    const std::vector<RigidTool> &
    tools() const
    {
      return tool_list;
    }

    /**
     * Add the contact contributions to the residual @p residual (R = f_int -
     * f_ext, so contact adds -p n . phi) and, if @p matrix is not null, to the
     * tangent. @p solution must have ghost entries. Quadrature points not in
     * contact but closer than @p tangent_margin (mm) get the penalty stiffness
     * in the tangent only (a predictor for contacts about to close; the
     * residual, hence the converged state, is unaffected). Returns forces,
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

    /// lambda <- max(0, lambda - eps g) at every quadrature point.
    void
    update_multipliers(const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution);

    /**
     * Lumped L2 projection of the contact pressure (sum over tools) onto the
     * scalar field of @p post_dof_handler (same triangulation): adds
     * int phi_i p to @p weighted and int phi_i to @p weights on the surface.
     */
    void
    project_pressure(const Mapping<3>                    &mapping,
                     const TrilinosWrappers::MPI::Vector &solution,
                     const DoFHandler<3>                 &post_dof_handler,
                     TrilinosWrappers::MPI::Vector       &weighted,
                     TrilinosWrappers::MPI::Vector       &weights) const;

    /// The multipliers, for checkpoints, roll-back and tests.
    const std::vector<double> &
    multipliers() const
    {
      return lambda;
    }

    /// Restore multipliers saved by multipliers() (same setup).
    void
    set_multipliers(const std::vector<double> &saved)
    {
      lambda = saved;
    }

  private:
    /// One pass over all contact quadrature points; the core of the class.
    ToolContactResult
    loop(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         TrilinosWrappers::MPI::Vector       *residual,
         TrilinosWrappers::SparseMatrix      *matrix,
         const double                         tangent_margin,
         std::vector<double>                 *new_lambda,
         const DoFHandler<3>                 *post_dof_handler,
         TrilinosWrappers::MPI::Vector       *weighted,
         TrilinosWrappers::MPI::Vector       *weights) const;

    const DoFHandler<3>   *dof_handler = nullptr;
    std::vector<RigidTool> tool_list;
    std::vector<double>    penalty;
    Quadrature<2>          face_quadrature;
    std::vector<std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
                        faces;
    std::vector<double> lambda;
  };
} // namespace densify
