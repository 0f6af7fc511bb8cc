#ifndef densify_material_symmetric_eigen_h
#define densify_material_symmetric_eigen_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <utility>

namespace densify
{
  using namespace dealii;

  /**
   * Eigenvalues, in descending order, and orthonormal eigenvectors of a
   * symmetric 3x3 tensor, as dealii::eigenvectors() returns them, in closed
   * form: the eigenvalues of the deviator (scaled to entries of order one)
   * from the trigonometric solution of its characteristic cubic; the
   * eigenvector of the eigenvalue farthest from the other two (its gap is
   * at least 0.87 times the deviator's norm, so it is well conditioned) from
   * cross products of the rows of A - lambda I; the other two from one Jacobi
   * rotation in the plane orthogonal to it, which stays accurate when their
   * eigenvalues are close or equal. Each eigenpair satisfies A v = lambda v
   * to round-off of the norm of A (tests/material_symmetric_eigen.cc). Not
   * yet used by J2Plasticity, whose Newton paths it would move by round-off
   * (doc/performance.md, "What limits it").
   */
  std::array<std::pair<double, Tensor<1, 3>>, 3>
  symmetric_eigenvectors(const SymmetricTensor<2, 3> &A);
} // namespace densify

#endif
