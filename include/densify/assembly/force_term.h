// The interface of everything that adds to the residual (and to the tangent)
// of the multi-body system.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/fe/mapping.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace boost
{
  namespace archive
  {
    class binary_oarchive;
    class binary_iarchive;
  } // namespace archive
} // namespace boost

namespace densify
{
  using namespace dealii;

  class AllValues;
  class LocalForces;

  /**
   * What the contact terms also record in one explicit pass, for the
   * station's statistics: the pairs of particles in contact and each
   * particle's normal force from the die wall, on this rank's contact
   * points (the caller sums over the ranks).
   */
  struct ContactRecord
  {
    /// Pairs of particles in contact, the smaller index first.
    std::set<std::pair<unsigned int, unsigned int>> pairs;
    /// Normal force (N) of the die wall on each particle (by index).
    std::vector<double> die_force;
  };

  /// Where and how a force term is evaluated.
  struct AssemblyContext
  {
    /// The mapping of the cells.
    const Mapping<3> *mapping = nullptr;
    /// The displacement (mm), with the ghost entries the terms need.
    const TrilinosWrappers::MPI::Vector *solution = nullptr;
    /// Contact points not in contact but closer than this (mm) get the
    /// penalty stiffness in the tangent only (a predictor for contacts
    /// about to close; the residual is unaffected).
    double tangent_margin = 0.;
    /// True for explicit dynamics: no tangent is ever asked for, and every
    /// evaluation is an accepted state.
    bool explicit_dynamics = false;
    /// Explicit dynamics: the values of @p solution and of the committed
    /// solution as plain arrays (AllValues), or null.
    const AllValues *values           = nullptr;
    const AllValues *committed_values = nullptr;
    /// Explicit dynamics: where a term that adds_plain_forces() adds its
    /// forces instead of the residual vector, or null.
    LocalForces *plain_forces = nullptr;
    /// Explicit dynamics: where the contact terms record what
    /// ContactRecord holds in this pass, or null.
    ContactRecord *record = nullptr;
  };

  /**
   * A force term of the system: the continuum, the body force, the
   * stabilisation, the pole springs, the tool contact or the particle
   * contact. The system builds a term only for an effect that is on, asks
   * each for the couplings of its tangent once the cells' pattern is made,
   * and sums their contributions into the residual R = f_int - f_ext (and
   * the tangent dR/du). A term owns its state (history, multipliers,
   * friction) and accepts it with commit() at the end of an increment.
   */
  class ForceTerm
  {
  public:
    virtual ~ForceTerm() = default;

    /// Name of the term, for the timer and the log.
    virtual std::string
    name() const = 0;

    /// Add the couplings of this term's tangent beyond those of the cells.
    virtual void
    add_couplings(TrilinosWrappers::SparsityPattern & /*pattern*/)
    {}

    /**
     * Add the term's forces at @p context's solution to @p residual and, if
     * @p tangent is not null, their derivative to @p tangent. Terms of the
     * bulk (continuum, body force) compress @p residual themselves; the
     * others leave it to the caller.
     */
    virtual void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) = 0;

    /**
     * True if the term, given AssemblyContext::plain_forces and the plain
     * values, reads the solution from AssemblyContext::values and adds its
     * forces to AssemblyContext::plain_forces instead of @p residual (the
     * explicit force path of the contacts); the caller then passes the plain
     * forces into the residual (LocalForces::finish()).
     */
    virtual bool
    adds_plain_forces() const
    {
      return false;
    }

    /// Add a fixed matrix to the compressed tangent (terms whose tangent
    /// does not depend on the state; the others do nothing).
    virtual void
    finish_tangent(TrilinosWrappers::SparseMatrix & /*tangent*/) const
    {}

    /// Accept the state at @p context's solution as the start of the next
    /// increment.
    virtual void
    commit(const AssemblyContext & /*context*/)
    {}

    /// Keep the committed state, for a roll-back of a failed increment.
    virtual void
    save()
    {}

    /// Go back to the state kept by save().
    virtual void
    restore()
    {}

    /// Write the committed state this rank holds into a checkpoint.
    virtual void
    write_checkpoint(boost::archive::binary_oarchive & /*archive*/) const
    {}

    /// Read what write_checkpoint() wrote (same scene and ranks); throws
    /// if it does not fit.
    virtual void
    read_checkpoint(boost::archive::binary_iarchive & /*archive*/)
    {}
  };
} // namespace densify
