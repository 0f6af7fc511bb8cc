// Augmented-Lagrangian contact with Coulomb friction between particle
// surfaces and the rigid tools.
#pragma once

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/contact/contact_base.h>
#include <densify/contact/contact_law.h>
#include <densify/contact/face_tables.h>
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
    /// Elastic energy of the contact springs now (mJ): 1/2 (p^2 / eps +
    /// |t|^2 / eps_t) over the contact points, the potential of
    /// p = max(0, lambda - eps g) at fixed multipliers.
    double elastic_energy = 0.;
    /// Energy the multiplier update of assemble_and_commit() added to the
    /// springs (mJ): sum of p / eps times the change of lambda.
    double multiplier_work = 0.;
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
  class ToolContact : public ContactBase<ToolContactResult>
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

    /// Set the height of the top edge of the tools of @p kind (the die
    /// wall's; mm, infinity: none).
    void
    set_tool_top(const ToolKind kind, const double top);

    /// Set the regularisation slip of the arctangent law (mm) for the next
    /// increment.
    void
    set_friction_regularisation(const double delta)
    {
      for (FrictionLaw &law : friction_laws)
        law.regularisation = delta;
    }

    /// Set FrictionLaw::slip_secant of every tool's law (the tangent of the
    /// next assemblies).
    void
    set_slip_secant(const bool on)
    {
      for (FrictionLaw &law : friction_laws)
        law.slip_secant = on;
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

    std::string
    name() const override
    {
      return "tool contact";
    }

    /// Multipliers, friction history and the committed tool translations.
    using State = ContactState;

    State
    state() const override
    {
      return {lambda, committed_traction, accumulated_slip, committed_shift};
    }

    void
    set_state(const State &saved) override
    {
      ContactBase<ToolContactResult>::set_state(saved);
      committed_shift = saved.translation;
    }

    /// With @p on false the explicit pass evaluates every slave point of
    /// every face on its own (the reference vertex_pass() is tested
    /// against; on by default).
    void
    set_vertex_evaluation(const bool on)
    {
      vertex_evaluation = on;
    }

  protected:
    ToolContactResult
    pass(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const ContactOutputs                &out) const override;

    bool
    friction_on() const override
    {
      return has_friction();
    }

    void
    commit_motion() override
    {
      committed_shift = shift;
    }

  private:
    /// What one pass over the contact points writes besides the forces.
    struct Outputs : ContactOutputs
    {
      const DoFHandler<3> *post = nullptr;
      SurfaceFieldSums    *sums = nullptr;
    };

    /// One pass over all contact quadrature points; the core of the class.
    ToolContactResult
    loop(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const Outputs                       &out) const;

    /**
     * The contact law of tool @p t at the point with state index @p idx:
     * gap @p g (mm), normal @p n, penalty @p eps (MPa/mm), and the point's
     * displacement since the last accepted increment @p motion (mm), which
     * gives the slip relative to the tool @p delta (mm; zero without
     * friction).
     */
    ContactResponse
    respond(const unsigned int  idx,
            const unsigned int  t,
            const double        g,
            const double        eps,
            const Tensor<1, 3> &n,
            const Tensor<1, 3> &motion,
            Tensor<1, 3>       &delta) const;

    /**
     * Account for the response @p r of tool @p t at a slave point (or at
     * the slave points [@p copy_first, @p copy_last) that sit at one vertex,
     * all with the same state) with gap @p g, normal @p n, relative slip
     * @p delta, penalty @p eps and weight @p JxW of particle @p material:
     * the new multipliers and friction history of @p out, the work and the
     * sums of @p result. Returns whether the point carries a pressure.
     */
    bool
    record(const ContactResponse &r,
           const double           g,
           const Tensor<1, 3>    &n,
           const Tensor<1, 3>    &delta,
           const unsigned int     t,
           const double           eps,
           const double           JxW,
           const unsigned int     material,
           const unsigned int    *copy_first,
           const unsigned int    *copy_last,
           const Outputs         &out,
           ToolContactResult     &result) const;

    /**
     * The explicit pass (plain arrays, no tangent) for linear elements
     * whose contact points are the facet corners: each surface vertex is
     * evaluated once for the slave points of all its faces (about six,
     * which see the same displacement and carry the same history) with their
     * summed weight, and its gap to a tool decides alone whether it is in
     * contact. The same forces as the pass over the faces' points, but for
     * the order of the additions. Returns false (and does nothing) where
     * the contact points are not all corners.
     */
    bool
    vertex_pass(const Outputs &out, ToolContactResult &result) const;

    /// The surface vertices of the faces for vertex_pass(), made with the
    /// face tables: reference position, DoFs, particle, the slave points at
    /// it (CSR) and their summed JxW.
    struct Vertices
    {
      bool                                                checked = false;
      std::vector<Point<3>>                               position;
      std::vector<std::array<types::global_dof_index, 3>> dofs;
      std::vector<unsigned int>                           material;
      std::vector<unsigned int>                           copy_start, copies;
      std::vector<double>                                 weight;
    };
    mutable Vertices vertices;
    /// Whether the explicit pass may evaluate per vertex.
    bool vertex_evaluation = true;

    const DoFHandler<3>      *dof_handler = nullptr;
    std::vector<RigidTool>    tool_list;
    std::vector<FrictionLaw>  friction_laws;
    std::vector<Tensor<1, 3>> shift, committed_shift;
    std::vector<double>       penalty;
    Quadrature<2>             face_quadrature;
    std::vector<std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
      faces;
    /// The faces' quadrature data and, per face, its vertices and their
    /// DoFs (3 x 3 per face), for the explicit pass on plain arrays; made
    /// at its first use (the mapping comes with the pass).
    mutable FaceTables                           tables;
    mutable std::vector<Point<3>>                face_vertices;
    mutable std::vector<types::global_dof_index> face_vertex_dofs;
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
