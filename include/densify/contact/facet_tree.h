// Narrow phase of the particle-particle contact search: a bounding-volume
// tree over the surface facets of one particle.
#pragma once

#include <deal.II/base/bounding_box.h>

#include <vector>

namespace densify
{
  using namespace dealii;

  /**
   * A binary tree of axis-aligned bounding boxes over a set of boxes (the
   * facets of one particle surface in the current configuration): each node
   * splits its boxes at the median of their centres along the longest axis
   * of its box, down to leaves of at most leaf_size boxes. Building costs
   * O(n log n), a query O(log n + k) for k hits.
   */
  class FacetTree
  {
  public:
    /// Build the tree over @p boxes (their indices are what query() returns).
    void
    build(const std::vector<BoundingBox<3>> &boxes);

    /**
     * Append to @p hits the indices of all boxes whose gap to @p box is at
     * most @p margin in every direction (the same test as boxes_overlap()).
     */
    void
    query(const BoundingBox<3>  &box,
          const double           margin,
          std::vector<unsigned> &hits) const;

    /// Number of boxes in the tree.
    unsigned int
    size() const
    {
      return order.size();
    }

    /// Largest number of boxes in a leaf.
    static constexpr unsigned int leaf_size = 4;

  private:
    /// A node: its box and either two children or a range of order[].
    struct Node
    {
      BoundingBox<3> box;
      /// Children (0 for a leaf: the root is never a child).
      unsigned int left = 0, right = 0;
      /// Range [begin, end) of order[] for a leaf.
      unsigned int begin = 0, end = 0;
    };

    /// Build the node over order[begin, end); returns its index.
    unsigned int
    build_node(const std::vector<BoundingBox<3>> &boxes,
               const unsigned int                 begin,
               const unsigned int                 end);

    std::vector<Node>           nodes;
    std::vector<unsigned>       order;
    std::vector<BoundingBox<3>> leaf_boxes;
  };
} // namespace densify
