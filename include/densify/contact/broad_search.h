// Broad phase of the particle-particle contact search: candidate pairs of
// overlapping bounding boxes found with a uniform cell grid.
#pragma once

#include <deal.II/base/bounding_box.h>

#include <densify/geometry/particles.h>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// A pair (i, j) of box indices with i < j.
  using CandidatePair = std::pair<unsigned int, unsigned int>;

  /**
   * Are the boxes @p a and @p b candidates for contact, i.e. is their gap at
   * most @p margin in each coordinate direction? Equivalently: do the boxes
   * overlap after enlarging each of them by margin/2 on every side? Boxes
   * that touch (gap exactly @p margin, e.g. 0) count as overlapping. The
   * comparison is done exactly, in floating point, on the box coordinates:
   * spheres at a centre distance of exactly one diameter are found with
   * margin 0 only where the coordinates are exact (e.g. dyadic diameters), so
   * callers should use a small positive margin in practice.
   */
  bool
  boxes_overlap(const BoundingBox<3> &a,
                const BoundingBox<3> &b,
                const double          margin);

  /**
   * The axis-aligned bounding box of each particle: centre -/+ its extent
   * along each axis (a sphere's radius; an ellipsoid's or a surface's
   * support() in that direction). For deformed particles the caller builds
   * the boxes from the current vertex positions instead.
   */
  std::vector<BoundingBox<3>>
  bounding_boxes(const std::vector<Particle> &particles);

  /**
   * Broad-phase contact search on a uniform cell grid (the usual DEM linked
   * cell method), keeping its work arrays between calls so that the search
   * can be refreshed cheaply every time the particles move.
   *
   * The cell size is h = (largest box extent in any direction + margin),
   * slightly enlarged against round-off, so that two candidate boxes have
   * their lower corners in the same or in neighbouring cells. Each box is
   * binned by its lower corner; the non-empty cells are stored in a hash
   * table (so the grid costs O(N) memory however far apart the boxes are)
   * and filled by a counting sort, and each box is then compared with the
   * boxes of the 27 surrounding cells. The expected cost is O(N + P) for N
   * boxes and P candidate pairs as long as the box sizes are similar.
   *
   * A spread of box sizes costs time: the cell size follows the largest box,
   * so many small boxes share a cell and are compared with each other (in
   * the extreme, one huge box puts all boxes into a few cells and the search
   * degenerates to the O(N^2) brute force). The result is still exact.
   */
  class BroadSearch
  {
  public:
    /**
     * Find all pairs (i, j), i < j, of @p boxes with boxes_overlap(boxes[i],
     * boxes[j], margin), sorted lexicographically, each pair once. The result
     * is identical to find_candidate_pairs_brute_force(). Throws
     * std::runtime_error if @p margin is negative or not finite, or if a box
     * has a non-finite coordinate or a lower corner above its upper corner.
     * The returned reference is valid until the next call. Below
     * brute_force_below boxes all pairs are tested directly (faster there).
     */
    const std::vector<CandidatePair> &
    update(const std::vector<BoundingBox<3>> &boxes, const double margin);

    /// The pairs found by the last call of update().
    const std::vector<CandidatePair> &
    pairs() const;

    /// The cell size (mm) used by the last call of update() (0 before, and
    /// if the grid was not used).
    double
    cell_size() const;

    /// Below this number of boxes update() tests all pairs (the brute force
    /// is as fast or faster for a few dozen boxes, see
    /// benchmarks/README_search.md).
    static constexpr unsigned int brute_force_below = 64;

  private:
    /// Integer cell coordinates.
    using CellKey = std::array<std::int64_t, 3>;

    /// Cell of each box (of its lower corner).
    std::vector<CellKey> box_cell;
    /// Hash slot of each box.
    std::vector<std::uint32_t> box_slot;
    /// Start of each hash slot's boxes in sorted_boxes (size n_slots + 1).
    std::vector<std::uint32_t> slot_start;
    /// Box indices ordered by hash slot.
    std::vector<std::uint32_t> sorted_boxes;
    /// Candidates j > i of the current box i, before sorting.
    std::vector<std::uint32_t> partners;
    /// The result.
    std::vector<CandidatePair> candidate_pairs;
    /// Cell size used by the last search.
    double h = 0.;
  };

  /**
   * Find all pairs (i, j), i < j, of @p boxes whose gap is at most @p margin
   * in every direction (see boxes_overlap(); touching boxes count), sorted
   * lexicographically, each pair once. Uses a BroadSearch (a uniform cell
   * grid, expected O(N + P)); keep a BroadSearch object instead to reuse its
   * memory when searching repeatedly. A spread of box sizes costs time, see
   * BroadSearch. Zero or one box gives no pairs.
   */
  std::vector<CandidatePair>
  find_candidate_pairs(const std::vector<BoundingBox<3>> &boxes,
                       const double                       margin);

  /**
   * The same pairs as find_candidate_pairs(), by testing all N (N - 1) / 2
   * pairs: O(N^2), for testing and benchmarks. Does not check its input.
   */
  std::vector<CandidatePair>
  find_candidate_pairs_brute_force(const std::vector<BoundingBox<3>> &boxes,
                                   const double                       margin);
} // namespace densify
