// Plain arrays of a Trilinos vector's values and of forces on the way into
// one, for the element loops of explicit dynamics.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_BlockMap.h>
#include <Epetra_Import.h>

#include <memory>
#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * The global index of each entry a Trilinos vector holds on this rank (its
   * map's local elements), looked up once per layout: the step loops of
   * explicit dynamics then read and write the vector's entries through a
   * plain array, where Epetra_BlockMap::GID() is a call per entry. It holds a
   * copy of the map, so a layout it has seen cannot be freed and another one
   * made at its address.
   */
  class LocalIndices
  {
  public:
    /// The global index of each local entry of @p map, in local order.
    const std::vector<types::global_dof_index> &
    operator()(const Epetra_BlockMap &map);

    /// How many layouts operator() has seen: a new value, a new layout.
    unsigned int
    n_layouts() const
    {
      return layouts;
    }

  private:
    std::unique_ptr<Epetra_BlockMap>     map;
    std::vector<types::global_dof_index> global;
    unsigned int                         layouts = 0;
  };



  /**
   * The values a (ghosted) Trilinos vector holds on this rank, read once
   * into a plain array indexed by global DoF index. Every rank holds the
   * whole mesh (parallel::shared::Triangulation), so the array has the
   * global size; entries the vector does not hold on this rank stay zero.
   * Reading an entry is an array access, where the Trilinos vector's
   * operator() or get_dof_values() looks the index up in its map.
   */
  class AllValues
  {
  public:
    /// Read every entry @p vector holds on this rank (owned and ghost).
    void
    gather(const TrilinosWrappers::MPI::Vector &vector);

    /// The value of global DoF @p i.
    double
    operator[](const types::global_dof_index i) const
    {
      return values[i];
    }

    /// The whole array, indexed by global DoF index.
    const double *
    data() const
    {
      return values.data();
    }

  private:
    std::vector<double> values;
    LocalIndices        indices;
  };



  /**
   * @p ghosted = @p owned for a vector with ghost entries: its owned entries
   * and its ghosts get the values of the vector without ghosts. deal.II's
   * assignment between vectors of different layouts makes a new
   * Epetra_Import at every call, whose set-up sorts and looks up every
   * ghost index; this class keeps its Epetra_Import while the two layouts
   * stay the same (it holds copies of both maps, so a layout it has seen
   * cannot be freed and another one made at its address).
   */
  class GhostImport
  {
  public:
    /// Copy the values of @p owned into @p ghosted (owned and ghost
    /// entries).
    void
    operator()(const TrilinosWrappers::MPI::Vector &owned,
               TrilinosWrappers::MPI::Vector       &ghosted);

  private:
    std::unique_ptr<Epetra_BlockMap> source, target;
    std::unique_ptr<Epetra_Import>   importer;
  };



  /**
   * Forces added entry by entry into a plain array indexed by global DoF
   * index, then into a Trilinos vector (without ghosts) at once. start()
   * copies the vector's locally owned entries, so that each owned entry
   * receives its additions in the same order and from the same start value
   * as by the vector's add(); finish() writes the owned entries back and
   * passes the nonzero entries owned elsewhere to the vector's add(), whose
   * compress() adds them on their owner as before: the sums are
   * bit-identical to adding each contribution to the vector.
   */
  class LocalForces
  {
  public:
    /// Start from the locally owned entries of @p vector (others zero).
    void
    start(const TrilinosWrappers::MPI::Vector &vector);

    /// Add @p value to global DoF @p i.
    void
    add(const types::global_dof_index i, const double value)
    {
      forces[i] += value;
    }

    /// Write the sums into @p vector: its owned entries are replaced, the
    /// others go to its add(); compress(VectorOperation::add) must follow.
    void
    finish(TrilinosWrappers::MPI::Vector &vector);

  private:
    std::vector<double> forces;
    /// Per global DoF index: owned by this rank?
    std::vector<bool> owned;
    LocalIndices      indices;
    /// The layout @p owned was made for (LocalIndices::n_layouts()).
    unsigned int owned_layout = 0;
    /// Work space for the entries owned elsewhere.
    std::vector<types::global_dof_index> other_indices;
    std::vector<double>                  other_values;
  };
} // namespace densify
