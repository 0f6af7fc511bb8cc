// F-bar with nodal averaging of the volume ratio for linear tetrahedra: the
// remedy of volumetric locking under isochoric plastic flow
// (doc/theory.md, section "Volumetric locking").
#pragma once

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/cell_volume_barrier.h>
#include <densify/material/material.h>
#include <densify/parameters.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  /**
   * Internal forces and tangent of linear tetrahedra with the volume ratio
   * averaged over vertex patches (Bonet & Burton 1998, "averaged nodal
   * volume" tetrahedron, written as an F-bar method).
   *
   * Each vertex a gets J_a = (current volume of its cell patch) / (reference
   * volume of the patch) = sum_f V_f J_f / sum_f V_f. A cell e is integrated
   * with one point per corner (weight V_e / 4, the four points of the P1
   * quadrature and their history slots), and at corner a the material sees
   * Fbar = (J_a / J_e)^(1/3) F_e (at small strain: Fbar = F_e +
   * (J_a - j_e)/3 I with j = 1 + div u). The internal forces are the exact
   * derivative of sum_e sum_a V_e/4 W(Fbar_ea), and the tangent is their
   * exact derivative: symmetric when dP/dF is (hyperelastic laws and the
   * consistent J2 tangent), so CG applies. It couples all DoFs of the cells
   * around each vertex (add_sparsity()).
   *
   * Stabilisation of the cell's own volume change: with a weight alpha per
   * material, the corner sees the blend
   * ln j_used = (1 - alpha) ln J_a + alpha ln J_e (at small strain
   * j_used = (1 - alpha) j_a + alpha j_e) instead of J_a, so that a cell
   * keeps the bulk stiffness alpha^2 kappa against a volume change of its
   * own that its patch does not share (the mode that lets single cells crush
   * under J2 flow; doc/theory.md, "Volumetric locking"). alpha = 0 is the
   * plain nodal-averaged F-bar, alpha = 1 the plain element. Forces and
   * tangent remain the exact derivatives of the blended energy. A cell whose
   * own volume ratio leaves the band of set_cell_volume_barrier() meets the
   * barrier's stiffness too (CellVolumeBarrier).
   *
   * Every rank holds the whole mesh (parallel::shared::Triangulation without
   * artificial cells) and a solution vector with all DoFs, so the vertex
   * averages are computed over all cells on every rank; the material is
   * evaluated on locally owned cells only.
   */
  class NodalAveraging
  {
  public:
    /**
     * Precompute shape gradients, volumes and vertex patches of a P1 vector
     * DoFHandler (FESystem(FE_SimplexP(1), 3)). @p cell_volume_weights: the
     * stabilisation weight alpha in [0, 1] of each material id (see the
     * class documentation); empty or missing entries: 0.
     */
    NodalAveraging(const DoFHandler<3>       &dof_handler,
                   const Mapping<3>          &mapping,
                   const std::vector<double> &cell_volume_weights = {});

    /// The stabilisation weight alpha of material id @p material.
    double
    cell_volume_weight(const unsigned int material) const
    {
      return material < weights.size() ? weights[material] : 0.;
    }

    /// Stop the cells' own volume ratio at the band of @p barrier
    /// (CellVolumeBarrier; off until this is called).
    void
    set_cell_volume_barrier(const CellVolumeBarrier &barrier)
    {
      volume_barrier = barrier;
    }

    /// Add the couplings of all DoFs of the cells around every vertex that
    /// touches a locally owned cell.
    void
    add_sparsity(TrilinosWrappers::SparsityPattern &sparsity);

    /**
     * Add the internal forces at @p solution (which must hold the values of
     * all DoFs) to @p residual and, if @p tangent is not nullptr, their
     * derivative to @p tangent (one kernel for both, kernel(), on plain
     * arrays of the solution and the forces). @p materials is indexed by the
     * cells' material id; @p committed and @p trial hold four states per cell
     * (index active_cell_index * 4 + vertex), or are nullptr. Returns an
     * empty string, or the message of the first material failure (e.g. an
     * inverted element); then the caller must not use the result.
     *
     * With @p shared_corners (residual only, finite strain, laws with
     * Material::kirchhoff_pressure()) the return mapping runs once per cell
     * at its first corner: the corners' Fbar differ by a volume factor only,
     * so they share the deviatoric stress and the updated state, and each
     * corner gets its own pressure. Exact when the four committed corner
     * states are equal, as this mode leaves them.
     */
    std::string
    assemble(const TrilinosWrappers::MPI::Vector                &solution,
             const std::vector<std::shared_ptr<const Material>> &materials,
             const std::vector<MaterialState>                   *committed,
             std::vector<MaterialState>                         *trial,
             TrilinosWrappers::MPI::Vector                      &residual,
             TrilinosWrappers::SparseMatrix                     *tangent,
             const bool shared_corners = false);

    /**
     * The internal forces alone, for explicit dynamics: add them at
     * @p solution (all DoFs' values) to @p residual. The same kernel as
     * assemble() (source/assembly/nodal_averaging_kernel.cc) without the
     * tangent's terms and with shared corners: for laws whose corners share
     * the Kirchhoff deviator (Material::kirchhoff_deviator()) one return
     * mapping a cell and the corner terms summed in closed form; the same
     * forces as assemble() with a tangent to round-off
     * (tests/nodal_averaging_consistency.cc). Returns an empty string or the
     * message of the first material failure, as assemble().
     *
     * @p trial may be @p committed (explicit steps, each accepted): the
     * states are then updated in place, and a cell whose corners share the
     * deviator writes its first corner only; fill_shared_corners() copies
     * it to the other three before the states are read.
     */
    std::string
    forces(const AllValues                                    &solution,
           const std::vector<std::shared_ptr<const Material>> &materials,
           const std::vector<MaterialState>                   *committed,
           std::vector<MaterialState>                         *trial,
           LocalForces                                        &residual);

    /**
     * Copy the first corner's state of each owned cell whose corners share
     * the deviator in the last forces() call to its other three corners
     * (after forces() updated @p states in place).
     */
    void
    fill_shared_corners(std::vector<MaterialState> &states) const;

    /**
     * The vertex averages j_a = sum_f V_f j_f / sum_f V_f of the volume
     * measure (det F at finite strain, 1 + div u at small strain) at
     * @p solution (which must hold the values of all DoFs), indexed by
     * global vertex index and complete at the vertices of locally owned
     * cells. At corner a of cell e the material sees
     * Fbar = (j_a / j_e)^(1/3) F_e (finite strain) or F_e + (j_a - j_e)/3 I.
     */
    std::vector<double>
    vertex_volume_measures(
      const AllValues                                    &solution,
      const std::vector<std::shared_ptr<const Material>> &materials) const;

    /// F = I + Grad u of the active cell with index @p e at @p solution
    /// (P1: constant in the cell).
    Tensor<2, 3>
    deformation_gradient(const unsigned int e, const AllValues &solution) const;

    /// The reference volume of the active cell with index @p e (mm^3).
    double
    reference_volume(const unsigned int e) const
    {
      return cells[e].volume;
    }

  private:
    /// Fixed data of one cell. Its 12 vector DoFs in the order
    /// i = 3 v + r (vertex v, component r), whatever the element's own
    /// order: every array of the kernels that runs over i uses it. The
    /// fields the force loops read come first (a cell is read three times
    /// a step).
    struct Cell
    {
      /// Reference gradients of the shape functions of the four vertices.
      std::array<Tensor<1, 3>, 4> grad;
      /// Global DoF indices.
      std::array<types::global_dof_index, 12> dofs;
      /// Global vertex indices.
      std::array<unsigned int, 4> vertex;
      /// Reference volume (mm^3).
      double volume = 0.;
      /// V / V_a of the patch of each vertex a, 0 where no locally owned
      /// cell touches the patch (the weights of the patch terms).
      std::array<double, 4> patch_share;
      /// Material id (index into the materials; the particle).
      unsigned int material = 0;
      /// Locally owned?
      bool owned = false;
      /// This cell's slot in each vertex patch.
      std::array<unsigned int, 4> slot;
      /// Centre in the reference configuration (mm), for messages.
      Point<3> centre;

      /// The reference gradient of shape function @p i.
      const Tensor<1, 3> &
      gradient(const unsigned int i) const
      {
        return grad[i / 3];
      }

      /// The nonzero component of shape function @p i.
      static unsigned int
      component(const unsigned int i)
      {
        return i % 3;
      }
    };

    /// The cells around one vertex and the union of their DoFs.
    struct Patch
    {
      std::vector<unsigned int>            cells;
      std::vector<types::global_dof_index> dofs;
      /// position[slot][i]: index in dofs of DoF i of cell cells[slot].
      std::vector<std::array<unsigned int, 12>> position;
      /// Reference volume of the patch (mm^3).
      double volume = 0.;
      /// Some cell of the patch is locally owned.
      bool touched = false;
      /// Offset of this patch's DoFs in the flat work arrays.
      unsigned int offset = 0;
    };

    /// The message of an inverted cell @p c with volume measure @p j.
    static std::string
    inverted(const Cell &c, const double j);

    /**
     * The element kernel of assemble() and forces(): the internal forces at
     * @p solution added to @p residual, and with @p with_tangent their
     * derivative added to @p tangent (not nullptr then). With
     * @p shared_corners (forces alone) the return mapping runs once a cell
     * where the law allows it (see assemble()). Returns an empty string or
     * the message of the first material failure.
     */
    template <bool with_tangent>
    std::string
    kernel(const AllValues                                    &solution,
           const std::vector<std::shared_ptr<const Material>> &materials,
           const std::vector<MaterialState>                   *committed,
           std::vector<MaterialState>                         *trial,
           LocalForces                                        &residual,
           TrilinosWrappers::SparseMatrix                     *tangent,
           const bool                                          shared_corners);

    /**
     * kernel()'s deviators of the cells whose corners share them (forces
     * alone): cell_tau_dev[e] of every owned cell of a law with
     * Material::kirchhoff_pressure() at cell_F[e], and their updated states
     * at their first corners, a material's cells side by side
     * (Material::kirchhoff_deviators()). Returns an empty string or the
     * message of the first material failure.
     */
    std::string
    shared_deviators(
      const std::vector<std::shared_ptr<const Material>> &materials,
      const std::vector<MaterialState>                   *committed,
      std::vector<MaterialState>                         *trial);

    std::vector<Cell>  cells;
    std::vector<Patch> patches;
    /// Stabilisation weight alpha per material id.
    std::vector<double> weights;
    /// The barrier against crushed cells (off by default).
    CellVolumeBarrier volume_barrier;
    /// Work arrays: per patch DoF, the vectors U and U' of the rank-one
    /// tangent terms; per vertex, the averaged volume measure, its
    /// logarithm and the scalars S (pressure) and beta.
    std::vector<double> U, U_prime;
    std::vector<double> j_bar, log_j_bar, S, beta;
    /// The kinematics per cell, in compact arrays: F, F^{-T} (finite
    /// strain), the volume measure j and d j / d u_i.
    std::vector<Tensor<2, 3>> cell_F, inverse_transpose;
    std::vector<double>       cell_j;
    /// Per material id: finite strain, and whether its cells' corners share
    /// the Kirchhoff deviator in this kernel call (forces alone).
    std::vector<char> finite_law, shared_law;
    /// The Kirchhoff deviator of each owned cell (shared_deviators()).
    std::vector<SymmetricTensor<2, 3>>  cell_tau_dev;
    std::vector<std::array<double, 12>> cell_dj;
    /// The cells whose kinematics this rank needs: those in the patch of a
    /// vertex of a locally owned cell (all cells on one rank).
    std::vector<unsigned int> needed_cells;
    /// The locally owned cells (the loops over them do not read the other
    /// cells' data).
    std::vector<unsigned int> owned_cells;
    /// assemble()'s plain arrays of the solution and of the forces.
    AllValues   solution_values;
    LocalForces residual_forces;
    /// Work space of add_block() and add_cell_block().
    std::vector<std::pair<int, unsigned int>> columns;
    std::vector<types::global_dof_index>      cell_dofs;

    /**
     * Where the entries of each block (the 12 x 12 matrix of an owned cell,
     * then the matrix of a touched patch) sit in the tangent's row storage:
     * per block row its local row (-1 if owned elsewhere), and per entry
     * its index in that row. Made at the first assembly after
     * add_sparsity() (a new pattern), so that adding a block is a scatter
     * rather than a search of each row (on the paper scene 40 million
     * additions per tangent, most of them from the patch blocks).
     */
    struct Placement
    {
      /// Per block: offsets into rows and entries (one past the last block
      /// at the end).
      std::vector<std::size_t>   row_start, entry_start;
      std::vector<int>           rows;
      std::vector<std::uint16_t> entries;
      /// Made for the current pattern?
      bool valid = false;
    } placement;

    /// Fill placement for the pattern of @p A; returns false (and leaves it
    /// invalid) if some row is too long for the 16-bit entry indices.
    bool
    place(const TrilinosWrappers::SparseMatrix &A);

    /// A += M on the rows and columns @p dofs of block @p block, through the
    /// placement; @p row is work space for rows owned elsewhere.
    void
    add_placed(TrilinosWrappers::SparseMatrix &A,
               const unsigned int              block,
               const types::global_dof_index  *dofs,
               const FullMatrix<double>       &M,
               std::vector<double>            &row) const;

    /// A += M on the rows and columns @p dofs, merged into the rows'
    /// sorted indices (for blocks without a placement).
    void
    add_block(TrilinosWrappers::SparseMatrix             &A,
              const std::vector<types::global_dof_index> &dofs,
              const FullMatrix<double>                   &M);

    /// A += M for the 12 x 12 block of cell @p e: through the placement if
    /// @p placed, else by add_block().
    void
    add_cell_block(TrilinosWrappers::SparseMatrix &A,
                   const bool                      placed,
                   const unsigned int              e,
                   const FullMatrix<double>       &M,
                   std::vector<double>            &row);

    /// A += u v^T + y z^T on the rows and columns @p dofs of block
    /// @p block, through the placement, without forming the matrix.
    void
    add_rank_two(TrilinosWrappers::SparseMatrix &A,
                 const unsigned int              block,
                 const types::global_dof_index  *dofs,
                 const double                   *u,
                 const double                   *v,
                 const double                   *y,
                 const double                   *z,
                 std::vector<double>            &row) const;

    /// A(i, j) += value(i, j) for the block @p block with rows and columns
    /// @p dofs: straight into the row storage through the placement, and
    /// through deal.II's add() (with @p row as work space) for rows owned
    /// elsewhere.
    template <typename Value>
    void
    add_through_placement(TrilinosWrappers::SparseMatrix &A,
                          const unsigned int              block,
                          const types::global_dof_index  *dofs,
                          const Value                    &value,
                          std::vector<double>            &row) const;
  };

  /**
   * The volume measure a cell corner hands the material: the blend of the
   * vertex average @p j_bar and the cell's own @p j_cell with weight
   * @p alpha, j_bar^(1 - alpha) j_cell^alpha at finite strain and
   * (1 - alpha) j_bar + alpha j_cell at small strain; exactly @p j_bar for
   * alpha = 0.
   */
  double
  blended_volume_measure(const double j_bar,
                         const double j_cell,
                         const double alpha,
                         const bool   finite_strain);

  /**
   * The factor sc of the finite-strain F-bar at a cell corner, Fbar = sc F:
   * sc = (j_used / j_cell)^(1/3) with j_used the blend
   * blended_volume_measure(@p j_bar, @p j_cell, @p alpha, true), which it
   * returns in @p j_used (computed as one power; exactly @p j_bar and
   * cbrt(j_bar / j_cell) for alpha = 0).
   */
  double
  fbar_scale(const double j_bar,
             const double j_cell,
             const double alpha,
             double      &j_used);

  /**
   * The modified deformation gradient of the nodal-averaged F-bar at a cell
   * corner: with the cell's deformation gradient @p F and the vertex average
   * @p j_bar of the volume measure (NodalAveraging::vertex_volume_measures()),
   * Fbar = (j_bar / det F)^(1/3) F at finite strain and
   * Fbar = F + (j_bar - (tr F - 2)) / 3 I at small strain. If @p scale is
   * not nullptr it receives the factor (j_bar / det F)^(1/3) at finite
   * strain and 1 at small strain.
   */
  Tensor<2, 3>
  fbar_deformation(const Tensor<2, 3> &F,
                   const double        j_bar,
                   const bool          finite_strain,
                   double             *scale = nullptr);
} // namespace densify
