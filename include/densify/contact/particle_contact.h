// Augmented-Lagrangian contact with Coulomb friction between the surfaces of
// deformable particles: two-pass quadrature-point-to-facet, with a broad
// (particles) and a narrow (facets) search.
#pragma once

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/contact/broad_search.h>
#include <densify/contact/contact_law.h>
#include <densify/contact/face_tables.h>
#include <densify/contact/facet_tree.h>
#include <densify/contact/tool_contact.h>

#include <array>
#include <set>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// What one evaluation of the particle contact produced (on all ranks).
  struct ParticleContactResult
  {
    /// Total normal force between particles (N; each contact once).
    double normal_force = 0.;
    /// Total friction force magnitude between particles (N; each contact
    /// once).
    double friction_force = 0.;
    /// Largest penetration (mm, >= 0).
    double max_penetration = 0.;
    /// Number of slave quadrature points in contact, and of those slipping.
    unsigned int n_active = 0, n_slip = 0;
    /// Current area in contact (mm^2; each contact once): the slave facets
    /// of which a point carries a pressure, each whole, at its current area
    /// (flat facets).
    double contact_area = 0.;
    /// Number of candidate particle pairs of the broad phase.
    unsigned int n_candidate_pairs = 0;
    /// Friction work of the increment, as ToolContactResult::friction_work.
    double friction_work = 0.;
    /// Elastic energy of the springs, as ToolContactResult::elastic_energy.
    double elastic_energy = 0.;
    /// As ToolContactResult::multiplier_work.
    double multiplier_work = 0.;
  };

  /**
   * Contact between the surfaces of different particles. Every boundary
   * quadrature point of a particle (the slave) is projected onto the closest
   * surface facet of the other particles (the master: the flat triangle
   * through the facet's current vertices); the gap is g = (x_s - x_m) . n_m
   * with n_m the facet's outward normal and x_m the master point given by the
   * master cell's shape functions. The pressure p = max(0, lambda - eps g)
   * (Uzawa multiplier lambda per slave point) and the friction traction act
   * on the slave point and, opposite, on the master point, so action equals
   * reaction. Both surfaces of a contact act as slave in turn (two passes,
   * each with weight 1/2), which treats the bodies alike and avoids the
   * penetration of master nodes into slave facets that one pass allows. The
   * tangent eps n n^T plus the friction stiffness couples the slave and
   * master cells. By default it neglects the change of the normal and of the
   * projection point (symmetric positive semi-definite);
   * set_geometric_tangent() adds both (the consistent tangent of a
   * frictionless contact; not symmetric).
   *
   * Search in two stages: the broad phase (BroadSearch, a hashed cell grid
   * over the particles' current bounding boxes) finds candidate particle
   * pairs, the narrow phase (a FacetTree per particle) candidate master
   * facets of every slave face; update_search() refreshes both in the
   * current configuration. The matrix couplings that the candidates need
   * are reported by add_couplings().
   *
   * The solution vectors must hold every DoF (fully ghosted): masters may
   * lie anywhere.
   */
  class ParticleContact : public ContactBase<ParticleContactResult>
  {
  public:
    /**
     * Collect the surface facets of all particles and the slave faces of the
     * locally owned cells. @p penalty_per_particle[material_id] is eps; a
     * pair of particles uses the smaller one. @p contact_quadrature on the
     * reference triangle gives the slave points of each facet.
     */
    void
    setup(const DoFHandler<3>       &dof_handler,
          const std::vector<double> &penalty_per_particle,
          const FrictionLaw         &friction,
          const Quadrature<2>       &contact_quadrature);

    /// Set the regularisation slip of the arctangent law (mm).
    void
    set_friction_regularisation(const double delta)
    {
      friction.regularisation = delta;
    }

    /// Set FrictionLaw::slip_secant (the tangent of the next assemblies).
    void
    set_slip_secant(const bool on)
    {
      friction.slip_secant = on;
    }

    /**
     * Add to the tangent the terms from the motion of the master facet: the
     * rotation of its normal, along which the pressure acts, and the sliding
     * of the projection point over it, which moves the reaction to other
     * master shape functions, and for P2 the curvature of the master facet
     * (doc/theory.md section 9). With them the tangent of frictionless
     * contact is exact (not symmetric); the dependence of the friction
     * traction on the normal is still left out.
     */
    void
    set_geometric_tangent(const bool on)
    {
      geometric_tangent = on;
    }

    /// Is there any particle-particle contact candidate at all?
    bool
    has_candidates() const
    {
      return !candidates.empty();
    }

    /**
     * Refresh the broad and narrow search in the configuration of
     * @p solution: candidate master facets of each slave face within
     * @p margin (mm). Returns whether the matrix couplings the candidates
     * need are all in the pattern made by the last add_couplings() (the same
     * answer on every rank).
     */
    bool
    update_search(const TrilinosWrappers::MPI::Vector &solution,
                  const double                         margin);

    /// Add the slave-master cell couplings of the facets within
    /// pattern_margin_factor times the search margin at the last
    /// update_search() (and of every earlier call) to @p pattern.
    void
    add_couplings(TrilinosWrappers::SparsityPattern &pattern) override;

    /**
     * Forget the master facets assigned to the slave points: the next
     * evaluation projects each point onto the closest candidate facet.
     * Called at the start of every Newton solve.
     */
    void
    reset_projections()
    {
      std::fill(assigned.begin(),
                assigned.end(),
                numbers::invalid_unsigned_int);
    }

    /**
     * Assign a master facet to every slave point at @p solution, with
     * hysteresis: a point keeps its facet while its projection stays within
     * the facet enlarged about its centroid by #projection_band of its size
     * beyond each edge, and no other candidate facet is closer by more than
     * that band times the facet's size; otherwise it takes the closest
     * candidate facet of the same particle (a point keeps its particle from
     * the first call after reset_projections() on). Evaluations between two
     * calls use the assigned facets, enlarged once the point has projected
     * into its facet, so the residual stays continuous while a point slides
     * across a facet edge instead of jumping with the facet normal; a point
     * assigned a facet beside which it lies (its closest point on an edge or
     * corner) measures its gap to the facet itself, as the assignment did,
     * not to the facet's plane, until it projects into the facet. Returns
     * how many points in contact changed their facet (the sum over all
     * ranks, on every rank).
     */
    unsigned int
    update_projections(const Mapping<3>                    &mapping,
                       const TrilinosWrappers::MPI::Vector &solution);

    /// Number of distinct contact partners of each particle at @p solution
    /// (on every rank).
    std::vector<unsigned int>
    contact_partners(const Mapping<3>                    &mapping,
                     const TrilinosWrappers::MPI::Vector &solution) const;

    /// Number of distinct contact partners of each particle from the pairs
    /// in contact that a pass recorded on each rank (ContactOutputs::pairs;
    /// @p pairs: this rank's), on every rank.
    std::vector<unsigned int>
    partners_of(
      const std::set<std::pair<unsigned int, unsigned int>> &pairs) const;

    /// As ToolContact::project_fields().
    void
    project_fields(const Mapping<3>                    &mapping,
                   const TrilinosWrappers::MPI::Vector &solution,
                   const DoFHandler<3>                 &post_dof_handler,
                   SurfaceFieldSums                    &sums) const;

    std::string
    name() const override
    {
      return "particle contact";
    }

    /// With @p on false the explicit pass searches every candidate facet at
    /// every evaluation, as a pass that assigns facets does (the reference
    /// the near lists are tested against; on by default).
    void
    set_near_lists(const bool on)
    {
      near.enabled = on;
      near.valid   = false;
    }

    /// With @p on false the explicit pass evaluates every slave point on its
    /// own, also where several slave points sit at one surface vertex (the
    /// reference the evaluation per vertex is tested against; on by
    /// default; NearLists).
    void
    set_vertex_evaluation(const bool on)
    {
      near.by_vertex = on;
      near.valid     = false;
    }

    /// How many times the explicit pass has built its near lists (the
    /// closest facet of a slave point is searched among all candidates only
    /// then; NearLists).
    unsigned int
    near_list_builds() const
    {
      return near.builds;
    }

    /// Multipliers and friction history, for roll-back and checkpoints.
    using State = ContactState;

  protected:
    ParticleContactResult
    pass(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const ContactOutputs                &out) const override;

    bool
    friction_on() const override
    {
      return friction.mu > 0.;
    }

  private:
    /// A surface facet: a boundary face of some particle's cell.
    struct Facet
    {
      DoFHandler<3>::active_cell_iterator cell;
      unsigned int                        face     = 0;
      unsigned int                        particle = 0;
      /// The cell's local vertex numbers of the face's vertices, then the
      /// opposite vertex.
      std::array<unsigned int, 4> local_vertex = {{0, 0, 0, 0}};
      /// Their global vertex indices.
      std::array<unsigned int, 4> vertex = {{0, 0, 0, 0}};
      /// Reference positions of the face's vertices.
      std::array<Point<3>, 3> position;
    };

    /// The contact partner of one slave quadrature point.
    struct Projection
    {
      /// Facet index (numbers::invalid_unsigned_int: none).
      unsigned int facet = numbers::invalid_unsigned_int;
      /// Barycentric coordinates on the facet's vertices.
      std::array<double, 3> bary = {{0., 0., 0.}};
      /// Outward unit normal of the facet.
      Tensor<1, 3> normal;
    };

    /// What one pass writes besides the result.
    struct Outputs : ContactOutputs
    {
      const DoFHandler<3>       *post           = nullptr;
      SurfaceFieldSums          *sums           = nullptr;
      std::vector<unsigned int> *new_assignment = nullptr;
      std::vector<char>         *new_in_band    = nullptr;
      unsigned int              *n_changed      = nullptr;
    };

    /// One pass over the slave points; the core of the class.
    ParticleContactResult
    loop(const Mapping<3>                    &mapping,
         const TrilinosWrappers::MPI::Vector &solution,
         const Outputs                       &out) const;

    /// Current positions of all vertices of the triangulation.
    std::vector<Point<3>>
    current_vertices(const TrilinosWrappers::MPI::Vector &solution) const;

    /// current_vertices() from the plain array @p values, written into a
    /// buffer the class keeps (the explicit steps' passes: no array of all
    /// vertices allocated and cleared a step; only the surface vertices'
    /// entries are meaningful).
    const std::vector<Point<3>> &
    current_vertices(const AllValues &values) const;

    /// A vertex of the surface facets: its index, reference position and
    /// DoFs.
    struct SurfaceVertex
    {
      unsigned int                           index = 0;
      Point<3>                               position;
      std::array<types::global_dof_index, 3> dofs;
    };

    /// Closest point to @p x of the facet @p m in the current configuration
    /// @p vertices, enlarged about its centroid so that the barycentric
    /// coordinates reach down to -@p band (0: the facet itself). Without
    /// @p with_normal the projection's normal is left zero.
    Projection
    project(const Point<3>              &x,
            const unsigned int           m,
            const std::vector<Point<3>> &vertices,
            const double                 band,
            double                      &distance_squared,
            const bool                   with_normal = true) const;

    /// The outward unit normal of facet @p m in the configuration
    /// @p vertices.
    Tensor<1, 3>
    outward_normal(const unsigned int           m,
                   const std::vector<Point<3>> &vertices) const;

    /**
     * The master facet of the point @p x among the candidate facets
     * [@p first, @p last), with its normal; @p distance_squared is its
     * squared distance. Each master particle offers its closest facet; the
     * closest of these is taken, unless @p x lies behind the closest facet of
     * some particle (inside it): then the particle it lies deepest in. Where
     * three particles meet, a point can be inside one particle and yet
     * closer to the surface of another, outside which it lies; the closest
     * facet alone would hide that penetration (doc/theory.md section 9).
     * With a valid @p particle, only that particle's facets are offered
     * (all of them if it has none among the candidates): within a Newton
     * solve a point keeps the particle its first iterate chose, so the
     * residual does not jump between particles from one iterate to the next.
     */
    Projection
    choose_facet(
      const Point<3>              &x,
      const unsigned int          *first,
      const unsigned int          *last,
      const std::vector<Point<3>> &vertices,
      double                      &distance_squared,
      const unsigned int particle = numbers::invalid_unsigned_int) const;

    /// How far beyond its edges a slave point keeps its master facet, in
    /// barycentric coordinates (update_projections()).
    static constexpr double projection_band = 0.1;

    const DoFHandler<3> *dof_handler = nullptr;
    std::vector<double>  penalty;
    FrictionLaw          friction;
    Quadrature<2>        face_quadrature;
    unsigned int         n_particles       = 0;
    bool                 geometric_tangent = false;

    /// All surface facets, by particle (facets_of[p] ranges over facets).
    std::vector<Facet>        facets;
    std::vector<unsigned int> first_facet;
    /// The DoF indices of each facet's cell (n_dofs_per_cell per facet).
    std::vector<types::global_dof_index> facet_dofs;
    /// The vertices of all facets, each once.
    std::vector<SurfaceVertex> surface_vertices;
    /// The slave faces' quadrature data for the explicit pass on plain
    /// arrays; made at its first use (the mapping comes with the pass).
    mutable FaceTables tables;
    /// current_vertices()'s buffer of the explicit passes.
    mutable std::vector<Point<3>> vertex_buffer;
    /// The slave faces (boundary faces of locally owned cells): facet index.
    std::vector<unsigned int> slave_faces;
    /// Candidate master facets of each slave face (CSR).
    std::vector<unsigned int> candidate_start, candidates;
    /// Cell couplings (active cell indices) of the candidates, and those of
    /// the pattern made last.
    /// (Sorted vectors without repeats: as sets they cost a heap node per
    /// entry at every search.)
    std::vector<std::pair<unsigned, unsigned>> couplings, pattern_couplings;
    /// Cell couplings within pattern_margin_factor times the search margin.
    std::vector<std::pair<unsigned, unsigned>> wide_couplings;
    /// How much wider than the search margin the pattern couplings reach.
    static constexpr double pattern_margin_factor = 1.5;

    BroadSearch            broad_search;
    std::vector<FacetTree> trees;

    /// Per slave quadrature point (slave face * n_q + q).
    /// The master facet assigned to each slave point
    /// (numbers::invalid_unsigned_int: the closest candidate).
    std::vector<unsigned int> assigned;

    /// Per slave point, whether its gap to the assigned facet is measured to
    /// the facet enlarged by #projection_band (the point has projected into
    /// the facet since the facet was assigned to it) or to the facet itself
    /// (it was assigned a facet beside which it lies, its closest point on an
    /// edge or corner, and has not projected into it since): the evaluations
    /// between two assignments measure the gap as the assignment did.
    std::vector<char> assigned_in_band;

    /**
     * Near lists of the explicit pass (Verlet lists): per slave point the
     * candidate facets whose distance was within #reach of the closest
     * one's at the last rebuild (CSR by slave point, in the candidates'
     * order), and the surface vertices' positions then. A point-triangle
     * distance moves by at most the point's displacement plus the largest
     * of the triangle's vertices', so while no surface vertex has moved by
     * more than a quarter of the reach, no facet outside a point's list can
     * be closer than the list's closest: the pass finds the same facet as a
     * search over all candidates, to the last bit.
     */
    struct NearLists
    {
      /// Per slave point, its range in facets (size: points + 1).
      std::vector<unsigned int> start;
      /// The listed facets.
      std::vector<unsigned int> facets;
      /// Positions of surface_vertices at the rebuild.
      std::vector<Point<3>> reference;
      /// The lists' reach (mm): the search margin of update_search().
      double reach = 0.;
      /// False until built, and after each new candidate search.
      bool valid = false;
      /// Builds so far.
      unsigned int builds = 0;
      /// False: every candidate searched at every evaluation.
      bool enabled = true;

      /**
       * Slave points at the surface vertices (P1 with the facet corners as
       * contact points): a vertex is a slave point of each of its about six
       * facets, and all those copies see the same displacement, the same
       * candidates near it and the same history, so they give the same
       * traction. The explicit pass then evaluates each vertex once, at its
       * first slave point (its representative), with the copies' summed
       * weight, searching the union of their candidate facets, and writes
       * the multiplier and friction history to every copy; the forces are
       * those of the evaluation per point up to the order of the additions.
       */
      bool by_vertex = true;
      /// Whether every slave point is a facet corner (checked at the first
      /// build); the evaluation per vertex needs it.
      bool at_corners = false, corners_checked = false;
      /// Per slave point, the global index of its vertex.
      std::vector<unsigned int> point_vertex;
      /// Per slave point, the slave points it is evaluated for (CSR, size:
      /// points + 1; itself among them): empty for a copy whose vertex is
      /// evaluated at another point and for a point without candidates.
      std::vector<unsigned int> copy_start, copies;
      /// Per representative slave point, the summed JxW of its copies.
      std::vector<double> weight;
    };
    mutable NearLists near;

    /// Rebuild #near at the current vertex positions @p x_now (the slave
    /// points' displacements from @p values) unless it still holds.
    void
    update_near_lists(const std::vector<Point<3>> &x_now,
                      const AllValues             &values) const;
  };
} // namespace densify
