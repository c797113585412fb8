// Refitting a BVH over boxes (BoxBvh8) to its items' new boxes over the same topology,
// touching only what changed: the leaves holding a moved item and the nodes above them. A
// frame that moves a few of a scene's models then costs what moved times the depth, not the
// whole tree (Box2D's, Jolt's and Bullet's trees update their moved proxies the same way).
//
// Exactness: a slot's box is the union of what it holds, and min and max are exact and do
// not depend on the order of their operands (the boxes have no signed zeros: lo = c - h - pad
// and hi = c + h + pad are never -0), so refitting only the marked nodes gives the same bytes
// as recomputing every node, and as the build gave for a subtree that did not move. The
// expected ray cost comes from every node's and leaf block's area through the build's
// formula (detail::sah_cost, a fixed order of sums), so it too is the full refit's, to the bit.
#pragma once

#include "core/parallel.hpp"
#include "spatial/bvh.hpp"
#include "spatial/bvh_orders.hpp"
#include "spatial/bvh_slots.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

namespace gyro::detail {

class BvhRefit {
 public:
  /// Reads the links of a freshly built tree over `items` items (item -> leaf block, leaf
  /// block and node -> parent node) and each node's and leaf block's area; marks nothing.
  void link(const BoxBvh8& bvh, std::size_t items);

  /// Marks the leaf block holding `item` and every node above it.
  void mark_item(uint32_t item);
  /// Marks every node and leaf block (a refit of the whole tree).
  void mark_all();
  /// Recomputes the marked nodes' slot boxes, children before parents (the build numbers
  /// nodes depth first, so a child's index is above its parent's), each marked leaf slot
  /// from box(leaf, item, lo, hi) (called once for each item of each marked leaf block) and
  /// each marked node slot from that child's new box, then the octant orders of the nodes
  /// whose slots changed, the tree's bounds and its expected ray cost (the build's formula).
  /// False when the numbering is not the build's: the caller then rebuilds, which overwrites
  /// whatever this wrote. The marks stay until clear_marks().
  ///
  /// A slot whose child is not marked already holds that child's box, and a node none of
  /// whose slots changed keeps its box, area and orders (a function of the slots alone): the
  /// bytes of recomputing everything, without the work. Most of a node's slots are unmarked
  /// when few models moved, and the orders were half of a refit's work. The changed nodes'
  /// orders are refreshed after their boxes, at the SIMD level (bvh_orders.hpp): checked, and
  /// sorted again only where they no longer sort; the bytes are the sort's either way.
  template <class BoxOf> bool refit(BoxBvh8& bvh, BoxOf&& box) {
    order_nodes_.clear();
    bvh_slots_store_fn* const store = GYRO_DISPATCH(bvh_slots_store);
    for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
      if (!node_mark_[i]) continue;
      BvhNode8& n = bvh.nodes[i];
      // The slots gathered in a copy of the rows, then compared, stored and united in SIMD
      // lanes (bvh_slots.hpp).
      float rows[6][8];
      std::memcpy(rows, n.bounds, sizeof rows);
      for (int k = 0; k < 8; ++k) {
        const uint32_t code = n.child[k];
        if (code == kEmptyChild) continue;
        BoxUnion slot;
        if (code & kLeafBit) {
          const uint32_t l = code & ~kLeafBit;
          if (!leaf_mark_[l]) continue;
          if constexpr (kBoxBvhLeafItems == 1) {
            // One item: its finite box is its union with the empty one.
            const uint32_t item = bvh.leaves[l].item[0];
            if (item != kNoItem) box(l, item, slot.lo, slot.hi);
          } else {
            float lo[3], hi[3];
            for (uint32_t item : bvh.leaves[l].item)
              if (item != kNoItem) box(l, item, lo, hi), slot.grow(lo, hi);
          }
          leaf_area_[l] = slot.half_area();
        } else {
          if (code <= i) return false;
          if (!node_mark_[code] || !node_changed_[code]) continue;
          slot = node_box_[code];
        }
        for (int a = 0; a < 3; ++a) rows[2 * a][k] = slot.lo[a], rows[2 * a + 1][k] = slot.hi[a];
      }
      BoxUnion own;
      const bool changed = store(n, rows, own.lo, own.hi);  // the bits compared, as the build's
      node_changed_[i] = changed;
      if (!changed) continue;
      order_nodes_.push_back(uint32_t(i));
      node_box_[i] = own;
      node_area_[i] = own.half_area();
      if (i == 0) bvh.bounds = aabb_from_min_max({own.lo[0], own.lo[1], own.lo[2]}, {own.hi[0], own.hi[1], own.hi[2]});
    }
    // The orders of the changed nodes (bvh_orders.hpp), which no box depends on: each node's
    // from its own bounds, so fixed chunks on any threads give the same bytes.
    bvh_orders_refresh_fn* const refresh = GYRO_DISPATCH(bvh_orders_refresh);
    parallel_for(order_nodes_.size(), kOrderChunk, [&](std::size_t b, std::size_t e) {
      refresh(bvh.nodes.data(), order_nodes_.data() + b, e - b);
    });
    order_nodes_.clear();
    bvh.stats.sah_cost = sah_cost();
    return true;
  }

  void clear_marks();
  /// Heap bytes held (the links, areas and marks).
  std::size_t bytes() const;

 private:
  std::vector<uint32_t> item_leaf_, leaf_parent_, node_parent_;
  std::vector<double> node_area_, leaf_area_;
  // Written by refit() for each marked node, read by its parent in the same pass: the
  // node's new box, and whether any of its slots changed.
  std::vector<BoxUnion> node_box_;
  std::vector<uint8_t> node_changed_;
  std::vector<uint8_t> node_mark_, leaf_mark_;
  std::vector<uint32_t> marked_nodes_, marked_leaves_;  // what clear_marks() resets
  // Nodes per parallel chunk of the order refresh: a frame that moves every one of 10^4
  // models changes all of its 3,030 nodes; fewer than two chunks run on the calling thread.
  static constexpr std::size_t kOrderChunk = 1024;
  std::vector<uint32_t> order_nodes_;                   // the nodes refit() changed, for their orders
  bool all_marked_ = false;

  static BoxUnion slots_of(const BvhNode8& node);
  static bool same_bits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
  double sah_cost() const;
};

}  // namespace gyro::detail
