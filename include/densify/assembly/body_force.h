// The body force term: a uniform force per volume on every particle,
// scaled by a factor against time.
#pragma once

#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <densify/assembly/force_term.h>

#include <utility>
#include <vector>

namespace densify
{
  /**
   * The body force b(t) = f(t) b_0 (N/mm^3) on every locally owned cell:
   * adds -int b . phi dV to the residual (reference volume; no tangent).
   */
  class BodyForce : public ForceTerm
  {
  public:
    /// @p force b_0, @p table the factor f against time (s).
    BodyForce(const DoFHandler<3>                          &dof_handler,
              const Tensor<1, 3>                           &force,
              const std::vector<std::pair<double, double>> &table,
              const unsigned int                            degree);

    std::string
    name() const override
    {
      return "body force";
    }

    /// Set the time of the load (s).
    void
    set_time(const double t)
    {
      time = t;
    }

    /// Compresses @p residual.
    void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) override;

  private:
    const DoFHandler<3>                   &dof_handler;
    const Tensor<1, 3>                     force;
    std::vector<std::pair<double, double>> table;
    const unsigned int                     degree;
    double                                 time = 0.;
  };
} // namespace densify
