// Helper of the tangent tests: the central-difference check of an assembled
// tangent against its residual.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include "test_utilities.h"

#include <algorithm>
#include <random>
#include <utility>

namespace densify
{
  namespace testing
  {
    /**
     * The largest relative difference |K v - (R(u + h v) - R(u - h v)) / 2h|
     * / |K v| over three random directions v each for h = 1e-6 and 1e-7,
     * where @p assemble(solution, residual, matrix or nullptr) adds the
     * residual R (and the tangent K) at a ghosted solution; @p u_owned: the
     * state u, @p pattern: the tangent's sparsity. Writes the result of the
     * assembly at u to @p result.
     */
    template <typename Assemble, typename Result>
    double
    tangent_error(const dealii::DoFHandler<3>                     &dof_handler,
                  const dealii::TrilinosWrappers::SparsityPattern &pattern,
                  const dealii::TrilinosWrappers::MPI::Vector     &u_owned,
                  const Assemble                                  &assemble,
                  Result                                          &result)
    {
      using dealii::TrilinosWrappers::MPI::Vector;
      const dealii::IndexSet &owned = dof_handler.locally_owned_dofs();
      dealii::TrilinosWrappers::SparseMatrix matrix(pattern);
      Vector residual(owned, dof_handler.get_communicator()), plus(residual),
        minus(residual), direction(residual), Kv(residual);
      result = assemble(ghosted(dof_handler, u_owned), residual, &matrix);
      matrix.compress(dealii::VectorOperation::add);

      std::mt19937                           random(42);
      std::uniform_real_distribution<double> uniform(-1., 1.);
      double                                 worst = 0;
      for (const double h : {1e-6, 1e-7})
        for (unsigned int trial = 0; trial < 3; ++trial)
          {
            for (const auto i : owned)
              direction(i) = uniform(random);
            direction.compress(dealii::VectorOperation::insert);
            matrix.vmult(Kv, direction);
            for (const double sign : {1., -1.})
              {
                Vector moved = u_owned;
                moved.add(sign * h, direction);
                Vector &target = sign > 0 ? plus : minus;
                target         = 0;
                assemble(ghosted(dof_handler, moved), target, nullptr);
                target.compress(dealii::VectorOperation::add);
              }
            plus -= minus;
            plus /= 2 * h;
            plus -= Kv;
            worst = std::max(worst, plus.l2_norm() / Kv.l2_norm());
          }
      return worst;
    }

    /**
     * tangent_error() of a contact term whose assemble(mapping, solution,
     * residual, matrix or nullptr) adds its residual and tangent: the
     * largest relative difference and the term's result at @p u_owned.
     */
    template <typename Contact, typename Mapping>
    auto
    contact_tangent_error(
      const dealii::DoFHandler<3>                     &dof_handler,
      const dealii::TrilinosWrappers::SparsityPattern &pattern,
      const dealii::TrilinosWrappers::MPI::Vector     &u_owned,
      const Mapping                                   &mapping,
      Contact                                         &contact)
    {
      using dealii::TrilinosWrappers::MPI::Vector;
      decltype(contact.assemble(
        mapping, u_owned, std::declval<Vector &>(), nullptr)) result;
      const double worst = tangent_error(
        dof_handler,
        pattern,
        u_owned,
        [&](const Vector                           &solution,
            Vector                                 &residual,
            dealii::TrilinosWrappers::SparseMatrix *matrix) {
          return contact.assemble(mapping, solution, residual, matrix);
        },
        result);
      return std::make_pair(worst, result);
    }
  } // namespace testing
} // namespace densify
