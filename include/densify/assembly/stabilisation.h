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
    /// @p alpha the factor E_p / D_p^2 of each particle (MPa/mm^2), @p beta
    /// the factor of the matrix in every tangent (0: only the
    /// pseudo-transient continuation uses it).
    Stabilisation(const DoFHandler<3>       &dof_handler,
                  const std::vector<double> &alpha,
                  const double               beta,
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

    /// l1 norm of beta times the matrix times the Newton correction @p du
    /// (N).
    double
    force(const TrilinosWrappers::MPI::Vector &du) const;

    /// Add @p factor times the matrix (E_p / D_p^2 times the mass matrix)
    /// to @p tangent: the pseudo mass of the pseudo-transient continuation.
    void
    add_scaled(TrilinosWrappers::SparseMatrix &tangent,
               const double                    factor) const;

  private:
    /// Add @p factor times E_p / D_p^2 times the mass matrix to @p target.
    void
    add_mass(TrilinosWrappers::SparseMatrix &target, const double factor) const;

    const DoFHandler<3>      &dof_handler;
    const std::vector<double> alpha;
    const double              beta;
    const unsigned int        degree;
    /// The mapping of the last reinit().
    const Mapping<3> *mapping = nullptr;
    /// beta E_p / D_p^2 times the mass matrix; made only if beta > 0.
    TrilinosWrappers::SparseMatrix matrix;
  };
} // namespace densify
