// The continuum force term: the internal forces of the particles' material
// law on every cell (plain elements or the nodal-averaged F-bar), and the
// quadrature-point history the law keeps.
#pragma once

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <densify/assembly/force_term.h>
#include <densify/material/j2_plasticity.h>
#include <densify/material/material.h>

#include <memory>
#include <vector>

namespace densify
{
  class NodalAveraging;

  /**
   * Internal forces int P : grad phi of every locally owned cell and their
   * tangent, with the material law of the cell's particle (material id). With
   * a NodalAveraging object, its F-bar assembly replaces the plain cell loop
   * (the P1 locking remedy). The history (one state per quadrature point, or
   * per cell corner with the F-bar) exists only if some law needs one: the
   * trial states of the last assembly become the committed ones by commit().
   */
  class Continuum : public ForceTerm
  {
  public:
    /**
     * @p materials by particle (material id); @p nodal_averaging the F-bar
     * of the locking remedy, or null for plain elements; @p degree the
     * polynomial degree (the quadrature is of degree + 1).
     */
    Continuum(const DoFHandler<3>                                &dof_handler,
              const std::vector<std::shared_ptr<const Material>> &materials,
              std::unique_ptr<NodalAveraging> nodal_averaging,
              const unsigned int              degree);

    /// Out of line: NodalAveraging is complete only there.
    ~Continuum() override;

    std::string
    name() const override
    {
      return "continuum";
    }

    /// The F-bar couples all DoFs of the cells around each vertex.
    void
    add_couplings(TrilinosWrappers::SparsityPattern &pattern) override;

    /// Throws std::runtime_error on a material failure (e.g. an inverted
    /// cell), on every rank; compresses @p residual.
    void
    assemble(const AssemblyContext          &context,
             TrilinosWrappers::MPI::Vector  &residual,
             TrilinosWrappers::SparseMatrix *tangent) override;

    /// The trial history becomes the committed one (explicit dynamics: the
    /// two are swapped, the trial states are all written anew at the next
    /// assembly; nothing to do where the explicit force path updated the
    /// committed states in place).
    void
    commit(const AssemblyContext &context) override;

    /// Does some law keep a history?
    bool
    has_history() const
    {
      return history;
    }

    /// States per cell: per quadrature point, or per corner with the F-bar.
    unsigned int
    states_per_cell() const
    {
      return per_cell;
    }

    /// The committed history (index: active cell index * states_per_cell()
    /// + k); empty without history.
    const std::vector<MaterialState> &
    committed() const
    {
      fill_corners();
      return committed_history;
    }

    /// The history of the last assembly (not yet committed).
    const std::vector<MaterialState> &
    trial() const
    {
      return trial_history;
    }

    /// The history of the locally owned cells.
    void
    write_checkpoint(boost::archive::binary_oarchive &archive) const override;

    void
    read_checkpoint(boost::archive::binary_iarchive &archive) override;

    /// The F-bar of the locking remedy, or null.
    const NodalAveraging *
    fbar() const
    {
      return nodal_averaging.get();
    }

    /// The material law of each particle.
    const std::vector<std::shared_ptr<const Material>> &
    laws() const
    {
      return materials;
    }

    /// Plastic work of the committed history (mJ), on every rank.
    double
    plastic_work(const Mapping<3> &mapping) const;

  private:
    const DoFHandler<3>                               &dof_handler;
    const std::vector<std::shared_ptr<const Material>> materials;
    std::unique_ptr<NodalAveraging>                    nodal_averaging;
    const unsigned int                                 degree;
    bool                                               history  = false;
    unsigned int                                       per_cell = 0;
    /// The committed states; an explicit step of the F-bar's force path
    /// updates them in place (each step is accepted), and a cell whose
    /// corners share the deviator at its first corner only, so the other
    /// corners are filled before anything reads them (fill_corners()).
    mutable std::vector<MaterialState> committed_history;
    std::vector<MaterialState>         trial_history;
    /// Did the last assembly update the committed states in place?
    bool in_place = false;
    /// Do corners of the committed states wait for fill_corners()?
    mutable bool corners_pending = false;

    /// Copy the first corner's state to the others where an in-place
    /// update left them behind (NodalAveraging::fill_shared_corners()).
    void
    fill_corners() const;
  };
} // namespace densify
