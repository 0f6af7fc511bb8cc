// Narrow phase of the particle-particle contact search: a bounding-volume
// tree over the surface facets of one particle.
#include <densify/contact/broad_search.h>
#include <densify/contact/facet_tree.h>

#include <algorithm>
#include <numeric>

namespace densify
{
  void
  FacetTree::build(const std::vector<BoundingBox<3>> &boxes)
  {
    nodes.clear();
    order.resize(boxes.size());
    std::iota(order.begin(), order.end(), 0u);
    leaf_boxes = boxes;
    if (!boxes.empty())
      build_node(boxes, 0, boxes.size());
  }



  unsigned int
  FacetTree::build_node(const std::vector<BoundingBox<3>> &boxes,
                        const unsigned int                 begin,
                        const unsigned int                 end)
  {
    const unsigned int index = nodes.size();
    nodes.emplace_back();
    BoundingBox<3> box = boxes[order[begin]];
    for (unsigned int i = begin + 1; i < end; ++i)
      box.merge_with(boxes[order[i]]);
    nodes[index].box = box;
    if (end - begin <= leaf_size)
      {
        nodes[index].begin = begin;
        nodes[index].end   = end;
        return index;
      }
    // split at the median centre along the longest axis
    unsigned int axis = 0;
    for (unsigned int d = 1; d < 3; ++d)
      if (box.side_length(d) > box.side_length(axis))
        axis = d;
    const unsigned int middle = (begin + end) / 2;
    std::nth_element(order.begin() + begin,
                     order.begin() + middle,
                     order.begin() + end,
                     [&](const unsigned a, const unsigned b) {
                       return boxes[a].center()[axis] < boxes[b].center()[axis];
                     });
    const unsigned int left  = build_node(boxes, begin, middle);
    const unsigned int right = build_node(boxes, middle, end);
    nodes[index].left        = left;
    nodes[index].right       = right;
    return index;
  }



  void
  FacetTree::query(const BoundingBox<3>  &box,
                   const double           margin,
                   std::vector<unsigned> &hits) const
  {
    if (nodes.empty())
      return;
    std::vector<unsigned int> stack = {0};
    while (!stack.empty())
      {
        const Node &node = nodes[stack.back()];
        stack.pop_back();
        if (!boxes_overlap(node.box, box, margin))
          continue;
        if (node.left == 0)
          {
            for (unsigned int i = node.begin; i < node.end; ++i)
              if (boxes_overlap(leaf_boxes[order[i]], box, margin))
                hits.push_back(order[i]);
          }
        else
          {
            stack.push_back(node.left);
            stack.push_back(node.right);
          }
      }
  }
} // namespace densify
