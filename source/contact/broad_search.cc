// Broad-phase contact search: candidate pairs of overlapping bounding boxes
// on a hashed uniform cell grid, and the brute-force reference.
#include <densify/contact/broad_search.h>
#include <densify/geometry/particle_shape.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace densify
{
  namespace
  {
    /// The hash slot of a cell for a table of mask + 1 slots (a power of 2).
    std::uint32_t
    slot_of(const std::array<std::int64_t, 3> &key, const std::uint64_t mask)
    {
      std::uint64_t x = static_cast<std::uint64_t>(key[0]);
      x = x * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(key[1]);
      x = x * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(key[2]);
      // splitmix64 finaliser, so that lattice-like keys spread evenly.
      x ^= x >> 30;
      x *= 0xBF58476D1CE4E5B9ULL;
      x ^= x >> 27;
      x *= 0x94D049BB133111EBULL;
      x ^= x >> 31;
      return static_cast<std::uint32_t>(x & mask);
    }



    /// Throw if @p margin or a box is unusable.
    void
    check_input(const std::vector<BoundingBox<3>> &boxes, const double margin)
    {
      if (!std::isfinite(margin) || margin < 0.)
        throw std::runtime_error("Broad contact search: the margin must be "
                                 "finite and >= 0, got " +
                                 std::to_string(margin));
      if (boxes.size() >= std::numeric_limits<std::uint32_t>::max() / 2)
        throw std::runtime_error("Broad contact search: too many boxes");
      for (unsigned int i = 0; i < boxes.size(); ++i)
        {
          const auto &corners = boxes[i].get_boundary_points();
          for (unsigned int d = 0; d < 3; ++d)
            if (!std::isfinite(corners.first[d]) ||
                !std::isfinite(corners.second[d]) ||
                corners.first[d] > corners.second[d])
              throw std::runtime_error(
                "Broad contact search: box " + std::to_string(i) +
                " has a non-finite corner or its lower corner above its "
                "upper corner in direction " +
                std::to_string(d));
        }
    }
  } // namespace



  bool
  boxes_overlap(const BoundingBox<3> &a,
                const BoundingBox<3> &b,
                const double          margin)
  {
    const auto &pa = a.get_boundary_points();
    const auto &pb = b.get_boundary_points();
    for (unsigned int d = 0; d < 3; ++d)
      if (pa.first[d] > pb.second[d] + margin ||
          pb.first[d] > pa.second[d] + margin)
        return false;
    return true;
  }



  std::vector<BoundingBox<3>>
  bounding_boxes(const std::vector<Particle> &particles)
  {
    std::vector<BoundingBox<3>> boxes;
    boxes.reserve(particles.size());
    for (const Particle &p : particles)
      {
        // a sphere's radius, another shape's extent along each axis
        Point<3> lower, upper;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const Tensor<1, 3> e = Point<3>::unit_vector(d);
            lower[d]             = p.centre[d] - support(p, -e);
            upper[d]             = p.centre[d] + support(p, e);
          }
        boxes.emplace_back(std::make_pair(lower, upper));
      }
    return boxes;
  }



  const std::vector<CandidatePair> &
  BroadSearch::update(const std::vector<BoundingBox<3>> &boxes,
                      const double                       margin)
  {
    check_input(boxes, margin);
    candidate_pairs.clear();
    const std::uint32_t n = boxes.size();
    h                     = 0.;
    if (n < 2)
      return candidate_pairs;
    if (n < brute_force_below)
      {
        // Few boxes: testing all pairs is cheaper than building the grid.
        for (std::uint32_t i = 0; i < n; ++i)
          for (std::uint32_t j = i + 1; j < n; ++j)
            if (boxes_overlap(boxes[i], boxes[j], margin))
              candidate_pairs.emplace_back(i, j);
        return candidate_pairs;
      }

    // Cell size: the largest extent plus the margin, so that the lower
    // corners of two candidate boxes differ by at most h in each direction.
    double   max_extent = 0., max_abs = 0.;
    Point<3> lowest = boxes[0].get_boundary_points().first;
    double   domain = 0.;
    {
      Point<3> highest = boxes[0].get_boundary_points().second;
      for (const BoundingBox<3> &box : boxes)
        {
          const auto &corners = box.get_boundary_points();
          for (unsigned int d = 0; d < 3; ++d)
            {
              max_extent =
                std::max(max_extent, corners.second[d] - corners.first[d]);
              lowest[d]  = std::min(lowest[d], corners.first[d]);
              highest[d] = std::max(highest[d], corners.second[d]);
              max_abs    = std::max({max_abs,
                                     std::abs(corners.first[d]),
                                     std::abs(corners.second[d])});
            }
        }
      for (unsigned int d = 0; d < 3; ++d)
        domain = std::max(domain, highest[d] - lowest[d]);
    }
    h = max_extent + margin;
    if (!(h > 0.))
      // Only points and margin 0: only coincident points pair up, so any
      // cell size works; spread the points over about n cells.
      h = (domain > 0. ? domain / std::cbrt(static_cast<double>(n)) : 1.);
    // Guard against round-off in the corner differences (a candidate pair
    // must never end up two cells apart).
    h = h * (1. + 1e-9) + 1e-12 * max_abs;

    // Cell of each box (its lower corner), clamped against overflow; the
    // clamp keeps neighbouring cells neighbours.
    box_cell.resize(n);
    for (std::uint32_t i = 0; i < n; ++i)
      {
        const Point<3> &lower = boxes[i].get_boundary_points().first;
        for (unsigned int d = 0; d < 3; ++d)
          box_cell[i][d] = static_cast<std::int64_t>(
            std::min(std::floor((lower[d] - lowest[d]) / h), 1e15));
      }

    // Hash table of about 2n slots, filled by a counting sort (stable, so
    // each slot lists its boxes in increasing index order).
    std::uint64_t n_slots = 1;
    while (n_slots < 2 * static_cast<std::uint64_t>(n))
      n_slots *= 2;
    const std::uint64_t mask = n_slots - 1;
    box_slot.resize(n);
    slot_start.assign(n_slots + 1, 0);
    for (std::uint32_t i = 0; i < n; ++i)
      {
        box_slot[i] = slot_of(box_cell[i], mask);
        ++slot_start[box_slot[i] + 1];
      }
    for (std::uint64_t s = 0; s < n_slots; ++s)
      slot_start[s + 1] += slot_start[s];
    // Now slot_start[s + 1] is the end of slot s: fill backwards, which
    // leaves slot_start[s + 1] at the start of slot s, then shift.
    sorted_boxes.resize(n);
    for (std::uint32_t i = n; i-- > 0;)
      sorted_boxes[--slot_start[box_slot[i] + 1]] = i;
    for (std::uint64_t s = 0; s < n_slots; ++s)
      slot_start[s] = slot_start[s + 1];
    slot_start[n_slots] = n;

    // Compare each box with the later boxes of the 27 surrounding cells.
    for (std::uint32_t i = 0; i < n; ++i)
      {
        partners.clear();
        const CellKey &key = box_cell[i];
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
              {
                const CellKey neighbour = {
                  {key[0] + dx, key[1] + dy, key[2] + dz}};
                const std::uint32_t slot = slot_of(neighbour, mask);
                for (std::uint32_t k = slot_start[slot];
                     k < slot_start[slot + 1];
                     ++k)
                  {
                    const std::uint32_t j = sorted_boxes[k];
                    if (j > i && box_cell[j] == neighbour &&
                        boxes_overlap(boxes[i], boxes[j], margin))
                      partners.push_back(j);
                  }
              }
        std::sort(partners.begin(), partners.end());
        for (const std::uint32_t j : partners)
          candidate_pairs.emplace_back(i, j);
      }
    return candidate_pairs;
  }



  const std::vector<CandidatePair> &
  BroadSearch::pairs() const
  {
    return candidate_pairs;
  }



  double
  BroadSearch::cell_size() const
  {
    return h;
  }



  std::vector<CandidatePair>
  find_candidate_pairs(const std::vector<BoundingBox<3>> &boxes,
                       const double                       margin)
  {
    BroadSearch search;
    return search.update(boxes, margin);
  }



  std::vector<CandidatePair>
  find_candidate_pairs_brute_force(const std::vector<BoundingBox<3>> &boxes,
                                   const double                       margin)
  {
    std::vector<CandidatePair> result;
    const unsigned int         n = boxes.size();
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 1; j < n; ++j)
        if (boxes_overlap(boxes[i], boxes[j], margin))
          result.emplace_back(i, j);
    return result;
  }
} // namespace densify
