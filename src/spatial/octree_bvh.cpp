// The octree's 8-wide form (octree_bvh.hpp): one depth-first pass, parents before children.
#include "spatial/octree_bvh.hpp"

#include <algorithm>

namespace gyro::detail {
namespace {

class Flattener {
 public:
  Flattener(const Octree& octree, const BvhBox* boxes, BoxBvh8& out) : tree_(octree), boxes_(boxes), out_(out) {}

  // The root: a node even when the octree's root is a leaf (the kernel starts at nodes[0]).
  void run() {
    const std::vector<OctreeNode>& nodes = tree_.nodes();
    if (nodes.empty() || !(nodes[0].lo[0] <= nodes[0].hi[0])) {
      out_.nodes.push_back(empty_node8());
      out_.stats.max_depth = 1;
      return;
    }
    const OctreeNode& root = nodes[0];
    if (root.first_child == kOctreeLeaf) holder(&tree_.items()[root.first_item], root.item_count, 1);
    else inner(root, 1);
  }

 private:
  const Octree& tree_;
  const BvhBox* boxes_;
  BoxBvh8& out_;

  uint32_t add_node(std::size_t depth) {
    out_.nodes.push_back(empty_node8());
    out_.stats.max_depth = std::max(out_.stats.max_depth, depth);
    return uint32_t(out_.nodes.size() - 1);
  }

  void set_slot(uint32_t node, int k, uint32_t code, const float lo[3], const float hi[3]) {
    BvhNode8& n = out_.nodes[node];  // after the child's own nodes were added (no dangling)
    for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = lo[a], n.bounds[2 * a + 1][k] = hi[a];
    n.child[k] = code;
  }

  BoxUnion items_bounds(const uint32_t* items, uint32_t count) const {
    BoxUnion b;
    for (uint32_t i = 0; i < count; ++i) b.grow(boxes_[items[i]].lo, boxes_[items[i]].hi);
    return b;
  }

  uint32_t block(const uint32_t* items, uint32_t count) {
    BvhItems leaf;
    for (uint32_t k = 0; k < kBoxBvhLeafItems; ++k) leaf.item[k] = k < count ? items[k] : kNoItem;
    out_.leaves.push_back(leaf);
    return kLeafBit | uint32_t(out_.leaves.size() - 1);
  }

  // A leaf's items (more than a block holds, or the root's) under a node: up to eight
  // blocks, each in its slot, or eight even groups of blocks, each under a node of its own.
  uint32_t holder(const uint32_t* items, uint32_t count, std::size_t depth) {
    constexpr uint32_t K = kBoxBvhLeafItems;
    const uint32_t me = add_node(depth);
    const uint32_t blocks = (count + K - 1) / K;
    for (uint32_t g = 0; g < 8; ++g) {
      const uint32_t b0 = uint32_t(uint64_t(blocks) * g / 8), b1 = uint32_t(uint64_t(blocks) * (g + 1) / 8);
      if (b0 == b1) continue;
      const uint32_t first = K * b0, n = std::min(count, K * b1) - first;
      const uint32_t code = b1 - b0 == 1 ? block(items + first, n) : holder(items + first, n, depth + 1);
      const BoxUnion b = items_bounds(items + first, n);
      set_slot(me, int(g), code, b.lo, b.hi);
    }
    set_child_orders(out_.nodes[me]);
    return me;
  }

  uint32_t inner(const OctreeNode& n, std::size_t depth) {
    const uint32_t me = add_node(depth);
    for (int k = 0; k < 8; ++k) {
      const OctreeNode& c = tree_.nodes()[n.first_child + uint32_t(k)];
      if (!(c.lo[0] <= c.hi[0])) continue;  // holds nothing
      uint32_t code;
      if (c.first_child != kOctreeLeaf) code = inner(c, depth + 1);
      else if (c.item_count <= kBoxBvhLeafItems) code = block(&tree_.items()[c.first_item], c.item_count);
      else code = holder(&tree_.items()[c.first_item], c.item_count, depth + 1);
      set_slot(me, k, code, c.lo, c.hi);
    }
    set_child_orders(out_.nodes[me]);
    return me;
  }
};

}  // namespace

BoxBvh8 octree_bvh8(const Octree& octree, const BvhBox* boxes) {
  BoxBvh8 out;
  Flattener(octree, boxes, out).run();
  const std::vector<OctreeNode>& nodes = octree.nodes();
  if (!nodes.empty() && nodes[0].lo[0] <= nodes[0].hi[0]) {
    const OctreeNode& r = nodes[0];
    out.bounds = aabb_from_min_max({r.lo[0], r.lo[1], r.lo[2]}, {r.hi[0], r.hi[1], r.hi[2]});
  }
  out.stats.nodes = out.nodes.size();
  out.stats.leaves = out.leaves.size();
  out.stats.bytes = out.nodes.size() * sizeof(BvhNode8) + out.leaves.size() * sizeof(BvhItems);
  return out;
}

}  // namespace gyro::detail
