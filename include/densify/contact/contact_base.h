// The life cycle shared by the tool contact and the particle contact:
// augmented-Lagrangian multipliers, friction history, commit, roll-back,
// and their use as a force term.
#pragma once

#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/force_term.h>
#include <densify/contact/rigid_tools.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace densify
{
  /// Everything a roll-back or a checkpoint of a contact must restore.
  struct ContactState
  {
    /// Normal multipliers.
    std::vector<double> lambda;
    /// Committed tangential tractions.
    std::vector<Tensor<1, 3>> traction;
    /// Accumulated slip.
    std::vector<double> slip;
    /// Committed tool translations (tool contact only).
    std::vector<Tensor<1, 3>> translation;

    /// Write or read the state with a boost archive (checkpoints).
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &lambda &traction &slip &translation;
    }
  };

  /// What one pass over the contact points writes besides its result; the
  /// part every contact has.
  struct ContactOutputs
  {
    TrilinosWrappers::MPI::Vector  *residual       = nullptr;
    TrilinosWrappers::SparseMatrix *matrix         = nullptr;
    double                          tangent_margin = 0.;
    /// Where a pass writes each contact point's new multiplier and
    /// traction, or null. Both arrive zeroed; a point that is open may be
    /// left unwritten.
    std::vector<double>       *new_lambda   = nullptr;
    std::vector<Tensor<1, 3>> *new_traction = nullptr;
    std::vector<double>       *new_slip     = nullptr;
    /// Explicit dynamics: the solution and the committed solution as plain
    /// arrays, read instead of the vectors, and where the forces go instead
    /// of @p residual (all three or none).
    const AllValues *values           = nullptr;
    const AllValues *committed_values = nullptr;
    LocalForces     *plain_residual   = nullptr;
    /// Where the particle contact adds each pair of particles in contact
    /// (the smaller index first), or null.
    std::set<std::pair<unsigned int, unsigned int>> *pairs = nullptr;
    /// Where the tool contact adds each particle's normal force (N) from the
    /// tools of kind @p force_kind, or null.
    std::vector<double> *particle_force = nullptr;
    ToolKind             force_kind     = ToolKind::die_wall;
  };

  /**
   * The augmented-Lagrangian contact life cycle over one pass of a derived
   * class over its contact points (pass()): the pressure p = max(0, lambda -
   * eps g) with a multiplier lambda per contact point, updated by
   * update_multipliers() (Uzawa); the tangential traction from the friction
   * law with its history (traction and accumulated slip) accepted by
   * commit(); assemble_and_commit() for explicit dynamics. @p Result is the
   * derived class's result of a pass, which carries friction_work and
   * multiplier_work.
   */
  template <class Result>
  class ContactBase : public ForceTerm
  {
  public:
    /**
     * The displacement of the last accepted increment (with ghost entries),
     * from which friction measures slip; must outlive this object's use.
     */
    void
    set_committed_solution(const TrilinosWrappers::MPI::Vector &committed)
    {
      committed_solution = &committed;
    }

    /**
     * Add the contact forces at @p solution to @p residual (R = f_int -
     * f_ext, so contact adds -(p n + t) . phi) and, if @p matrix is not null,
     * their tangent. Points not in contact but closer than @p tangent_margin
     * (mm) get the penalty stiffness in the tangent only. Returns the forces,
     * summed over all ranks. Needs compress() on @p residual and @p matrix
     * afterwards.
     */
    Result
    assemble(const Mapping<3>                    &mapping,
             const TrilinosWrappers::MPI::Vector &solution,
             TrilinosWrappers::MPI::Vector       &residual,
             TrilinosWrappers::SparseMatrix      *matrix,
             const double                         tangent_margin = 0.) const
    {
      ContactOutputs out;
      out.residual       = &residual;
      out.matrix         = matrix;
      out.tangent_margin = tangent_margin;
      return pass(mapping, solution, out);
    }

    /// Forces and penetration only (summed over ranks).
    Result
    evaluate(const Mapping<3>                    &mapping,
             const TrilinosWrappers::MPI::Vector &solution) const
    {
      return pass(mapping, solution, ContactOutputs());
    }

    /// lambda <- max(0, lambda - eps g) at every contact point.
    void
    update_multipliers(const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution)
    {
      std::vector<double> new_lambda(lambda.size());
      ContactOutputs      out;
      out.new_lambda = &new_lambda;
      pass(mapping, solution, out);
      lambda.swap(new_lambda);
    }

    /// Accept @p solution: its tangential tractions and slips become the
    /// committed state of the next increment.
    void
    commit(const Mapping<3>                    &mapping,
           const TrilinosWrappers::MPI::Vector &solution)
    {
      if (friction_on())
        {
          std::vector<Tensor<1, 3>> new_traction(committed_traction.size());
          std::vector<double>       new_slip = accumulated_slip;
          ContactOutputs            out;
          out.new_traction = &new_traction;
          out.new_slip     = &new_slip;
          pass(mapping, solution, out);
          committed_traction.swap(new_traction);
          accumulated_slip.swap(new_slip);
        }
      commit_motion();
    }

    /**
     * assemble() without a tangent and commit() in one pass: add the contact
     * forces at @p solution to @p residual and accept @p solution as the
     * start of the next increment (explicit dynamics, where every step is
     * accepted). The result carries the friction work of the increment.
     * With @p relaxation r > 0 each multiplier then moves towards its
     * pressure, lambda += r (p - lambda): an integral action that removes
     * the penetration of lasting contacts over about 1/r calls, so that the
     * penalty does not bias the slowly loaded (quasi-static) answer. With
     * @p plain (its values, committed_values and plain_residual) the pass
     * reads the plain arrays and adds the forces to plain_residual instead.
     */
    Result
    assemble_and_commit(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution,
                        TrilinosWrappers::MPI::Vector       &residual,
                        const double                         relaxation = 0.,
                        const ContactOutputs                *plain = nullptr)
    {
      ContactOutputs out;
      out.residual = &residual;
      if (plain != nullptr)
        {
          out.values           = plain->values;
          out.committed_values = plain->committed_values;
          out.plain_residual   = plain->plain_residual;
          out.pairs            = plain->pairs;
          out.particle_force   = plain->particle_force;
          out.force_kind       = plain->force_kind;
        }
      std::vector<double> pressure(lambda.size());
      if (relaxation > 0.)
        out.new_lambda = &pressure;
      std::vector<Tensor<1, 3>> new_traction(committed_traction.size());
      std::vector<double>       new_slip = accumulated_slip;
      const bool                friction = friction_on();
      if (friction)
        {
          out.new_traction = &new_traction;
          out.new_slip     = &new_slip;
        }
      Result result = pass(mapping, solution, out);
      result.multiplier_work *= relaxation;
      // the multipliers relax towards the pressures (an integral action on
      // the penetration)
      if (relaxation > 0.)
        for (unsigned int k = 0; k < lambda.size(); ++k)
          lambda[k] += relaxation * (pressure[k] - lambda[k]);
      if (friction)
        {
          committed_traction.swap(new_traction);
          accumulated_slip.swap(new_slip);
        }
      commit_motion();
      return result;
    }

    /// The state (multipliers and friction history).
    virtual ContactState
    state() const
    {
      return {lambda, committed_traction, accumulated_slip, {}};
    }

    /// Restore a state saved by state() (same setup).
    virtual void
    set_state(const ContactState &saved)
    {
      lambda             = saved.lambda;
      committed_traction = saved.traction;
      accumulated_slip   = saved.slip;
    }

    /// The integral action of explicit dynamics (assemble_and_commit()).
    void
    set_relaxation(const double r)
    {
      relaxation = r;
    }

    /// The result of the last assemble() as a force term.
    const Result &
    last_result() const
    {
      return last;
    }

    // ForceTerm: in explicit dynamics every evaluation is accepted at once
    void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) override
    {
      ContactOutputs plain;
      plain.values           = context.values;
      plain.committed_values = context.committed_values;
      plain.plain_residual   = context.plain_forces;
      if (context.record != nullptr)
        {
          plain.pairs          = &context.record->pairs;
          plain.particle_force = &context.record->die_force;
          plain.force_kind     = ToolKind::die_wall;
        }
      const bool use_plain = context.values != nullptr &&
                             context.committed_values != nullptr &&
                             context.plain_forces != nullptr;
      last = context.explicit_dynamics ?
               assemble_and_commit(*context.mapping,
                                   *context.solution,
                                   residual,
                                   relaxation,
                                   use_plain ? &plain : nullptr) :
               assemble(*context.mapping,
                        *context.solution,
                        residual,
                        tangent,
                        context.tangent_margin);
    }

    /// The explicit pass reads and writes plain arrays when given them.
    bool
    adds_plain_forces() const override
    {
      return true;
    }

    void
    commit(const AssemblyContext &context) override
    {
      if (!context.explicit_dynamics)
        commit(*context.mapping, *context.solution);
    }

    void
    save() override
    {
      saved = state();
    }

    void
    restore() override
    {
      set_state(saved);
    }

    void
    write_checkpoint(boost::archive::binary_oarchive &archive) const override
    {
      const ContactState now = state();
      archive << now;
    }

    void
    read_checkpoint(boost::archive::binary_iarchive &archive) override
    {
      ContactState loaded;
      archive >> loaded;
      if (loaded.lambda.size() != lambda.size())
        throw std::runtime_error("the checkpoint's " + name() +
                                 " has another number of contact points");
      set_state(loaded);
    }

  protected:
    /// One pass over the contact points with the outputs @p out; the core
    /// of the derived class.
    virtual Result
    pass(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const ContactOutputs                &out) const = 0;

    /// Does friction act at any of this contact's points?
    virtual bool
    friction_on() const = 0;

    /// Accept the motion of the contact partners (the tools' translations).
    virtual void
    commit_motion()
    {}

    const TrilinosWrappers::MPI::Vector *committed_solution = nullptr;
    std::vector<double>                  lambda;
    std::vector<Tensor<1, 3>>            committed_traction;
    std::vector<double>                  accumulated_slip;

  private:
    double       relaxation = 0.;
    Result       last;
    ContactState saved;
  };
} // namespace densify
