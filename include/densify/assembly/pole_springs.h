// The pole springs (Contact/Hold poles on axis): horizontal springs on the
// top and bottom pole vertex of every particle against the free rigid-body
// modes that frictionless contact leaves to faceted spheres.
#pragma once

#include <deal.II/dofs/dof_handler.h>

#include <densify/assembly/force_term.h>
#include <densify/geometry/particles.h>

#include <vector>

namespace densify
{
  /**
   * Springs holding the pole vertices of each particle on the vertical line
   * through its centre (axis: towards zero horizontal displacement; in a
   * vertical stack one more spring per particle against the spin about the
   * axis), or keeping the line through the two poles vertical (between the
   * poles' horizontal DoFs). Each spring is added by one rank.
   */
  class PoleSprings : public ForceTerm
  {
  public:
    /**
     * Find the pole vertices of @p particles; @p vertical: springs between
     * the poles instead of towards the axis; @p spin: the spin spring of a
     * vertical stack; @p stiffness of each particle (N/mm). Throws
     * std::runtime_error if a pole is not a mesh vertex.
     */
    PoleSprings(const DoFHandler<3>         &dof_handler,
                const std::vector<Particle> &particles,
                const std::vector<double>   &stiffness,
                const bool                   vertical,
                const bool                   spin);

    std::string
    name() const override
    {
      return "pole springs";
    }

    void
    add_couplings(TrilinosWrappers::SparsityPattern &pattern) override;

    void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) override;

    /// l2 norm of the spring forces at the last assembly (N), on every rank.
    double
    force() const
    {
      return last_force;
    }

  private:
    /// A spring of stiffness k (N/mm) on DoF i, towards zero or towards DoF
    /// j.
    struct Spring
    {
      types::global_dof_index i = 0;
      types::global_dof_index j = numbers::invalid_dof_index;
      double                  k = 0.;
    };
    std::vector<Spring> springs;
    MPI_Comm            comm;
    double              last_force = 0.;
  };
} // namespace densify
