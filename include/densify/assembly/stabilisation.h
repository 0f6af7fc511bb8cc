// The stabilisation term: a small mass-like matrix added to the Newton
// tangent only, against the free rigid-body modes of particles that nothing
// holds yet.
#pragma once

#include <deal.II/dofs/dof_handler.h>

#include <densify/assembly/force_term.h>

#include <vector>

namespace densify
{
  /**
   * beta E_p / D_p^2 times the mass matrix (unit density) of each particle p,
   * added to the tangent and never to the residual: it changes the Newton
   * path, not the converged answer. force() reports the size of the force it
   * stands for in one correction.
   */
  class Stabilisation : public ForceTerm
  {
  public:
    /// @p alpha the factor beta E_p / D_p^2 of each particle (MPa/mm^2).
    Stabilisation(const DoFHandler<3>       &dof_handler,
                  const std::vector<double> &alpha,
                  const unsigned int         degree);

    std::string
    name() const override
    {
      return "stabilisation";
    }

    /// Assemble the matrix on @p pattern (the tangent's pattern).
    void
    reinit(const TrilinosWrappers::SparsityPattern &pattern,
           const Mapping<3>                        &mapping);

    /// Nothing: the matrix is added by finish_tangent().
    void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) override;

    void
    finish_tangent(TrilinosWrappers::SparseMatrix &tangent) const override;

    /// l1 norm of the matrix times the Newton correction @p du (N).
    double
    force(const TrilinosWrappers::MPI::Vector &du) const;

  private:
    const DoFHandler<3>           &dof_handler;
    const std::vector<double>      alpha;
    const unsigned int             degree;
    TrilinosWrappers::SparseMatrix matrix;
  };
} // namespace densify
