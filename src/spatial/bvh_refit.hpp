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

  /// The leaf block holding `item` (kNoItem: none, or not linked).
  uint32_t leaf_of(uint32_t item) const { return item < item_leaf_.size() ? item_leaf_[item] : kNoItem; }
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
  /// box may run on several threads at once, for different leaves; it returns true to have
  /// its leaf listed in revisit() (what the caller writes afterwards, on its own thread).
  ///
  /// A slot whose child is not marked already holds that child's box, and a node none of
  /// whose slots changed keeps its box, area and orders (a function of the slots alone): the
  /// bytes of recomputing everything, without the work. Most of a node's slots are unmarked
  /// when few models moved, and the orders were half of a refit's work. The changed nodes'
  /// orders are refreshed after their boxes, at the SIMD level (bvh_orders.hpp): checked, and
  /// sorted again only where they no longer sort; the bytes are the sort's either way.
  ///
  /// The subtrees of link()'s tasks (contiguous ranges of nodes) are refit in parallel when
  /// many nodes are marked, then the nodes above them on the calling thread: every node is
  /// computed from its own slots and its children's new boxes alone, so neither the split
  /// nor the thread count can change a byte.
  template <class BoxOf> bool refit(BoxBvh8& bvh, BoxOf&& box) {
    if (bvh.nodes.size() != node_mark_.size() || bvh.leaves.size() != leaf_mark_.size()) return false;
    bvh_slots_store_fn* const store = GYRO_DISPATCH(bvh_slots_store);
    // The orders of a part's changed nodes (bvh_orders.hpp), which no box depends on, each
    // node's from its own bounds: refreshed by the thread that just wrote those bounds, while
    // they are in its cache.
    bvh_orders_refresh_fn* const refresh = GYRO_DISPATCH(bvh_orders_refresh);
    for (Part& part : parts_) part.changed_count = 0, part.revisit.clear(), part.ok = true;
    // The nodes attach() added, numbered after every linked one, each after its parent, and
    // with no linked node below them: first, children before parents.
    extra_.changed_count = 0, extra_.revisit.clear(), extra_.ok = true;
    for (std::size_t i = bvh.nodes.size(); i-- > linked_nodes_;)
      if (node_mark_[i]) refit_node(bvh, uint32_t(i), box, store, extra_);
    refresh(bvh.nodes.data(), extra_.changed.data(), extra_.changed_count);
    const auto run_task = [&](std::size_t t) {
      const uint32_t root = task_root_[t];
      if (!node_mark_[root]) return;  // nor any node below it
      Part& part = parts_[t];
      for (uint32_t i = task_end_[t]; i-- > root;)
        if (node_mark_[i]) refit_node(bvh, i, box, store, part);
      refresh(bvh.nodes.data(), part.changed.data(), part.changed_count);
    };
    const std::size_t marked = all_marked_ ? bvh.nodes.size() : marked_nodes_.size();
    if (marked >= parallel_nodes_) {
      parallel_for(task_root_.size(), 1, [&](std::size_t b, std::size_t e) {
        for (std::size_t t = b; t < e; ++t) run_task(t);
      });
    } else {
      for (std::size_t t = 0; t < task_root_.size(); ++t) run_task(t);
    }
    Part& top = parts_.back();
    for (std::size_t k = top_.size(); k-- > 0;)
      if (node_mark_[top_[k]]) refit_node(bvh, top_[k], box, store, top);
    refresh(bvh.nodes.data(), top.changed.data(), top.changed_count);
    // The parts in a fixed order (the tasks', then the top's): the same list at any thread count.
    if (!extra_.ok) return false;
    revisit_.assign(extra_.revisit.begin(), extra_.revisit.end());
    for (const Part& part : parts_) {
      if (!part.ok) return false;
      revisit_.insert(revisit_.end(), part.revisit.begin(), part.revisit.end());
    }
    bvh.stats.sah_cost = sah_cost();
    return true;
  }

  /// How many marked nodes make refit() run its tasks in parallel (kParallelNodes unless
  /// set; the bytes are the same either way, which the tests check from 256).
  void set_parallel_nodes(std::size_t marked) { parallel_nodes_ = marked; }

  /// The subtrees refit() may run in parallel (none when the numbering is not depth first).
  std::size_t task_count() const { return task_root_.size(); }

  /// The leaves whose box() returned true in the last refit(), in an order fixed by the tree.
  const std::vector<uint32_t>& revisit() const { return revisit_; }

  /// Takes `item` out of the tree: its leaf block's slot in its node becomes empty (bounds
  /// +inf, -inf), the block holds no item and is kept for attach(), and the node and those
  /// above it are marked, the node as changed whatever its other slots do, so the next
  /// refit() unites what is left and sorts the node's orders again. False (nothing changed)
  /// when the item has no leaf block. Only for a one-item leaf block (the scene's).
  bool detach(BoxBvh8& bvh, uint32_t item);
  /// Puts a new item (one with no leaf block) into the tree with box [lo, hi]: from the root
  /// down through the node child whose box grows least (ties: the lower slot) to the first
  /// node with an empty slot, or at a full node of leaves, into a new node (appended to
  /// bvh.nodes) shared with the leaf whose union with the box is least; in a leaf block that
  /// detach() freed (the last one) or a new one at the end of bvh.leaves. Marks the block and
  /// the nodes above it for the next refit(), which writes their boxes and orders. Returns
  /// the leaf block, or kNoItem (nothing changed) when the new node would pass kBvhMaxDepth:
  /// the caller then rebuilds. The same boxes in the same order give the same tree.
  uint32_t attach(BoxBvh8& bvh, uint32_t item, const float lo[3], const float hi[3]);

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
  std::vector<uint8_t> node_forced_;     // by node: detach() emptied one of its slots
  std::vector<uint32_t> forced_nodes_;   // what clear_marks() resets
  std::vector<uint32_t> free_leaves_;    // blocks detach() emptied, reused last first
  std::vector<uint32_t> marked_nodes_, marked_leaves_;  // what clear_marks() resets
  std::vector<uint32_t> revisit_;
  // Subtrees of at most kTaskNodes nodes, each as large as it can be, that refit() runs as
  // parallel tasks (R1's 10^4 spheres: 64 tasks of about 47 nodes, 9 nodes above them);
  // task t holds nodes [task_root_[t], task_end_[t]); top_ holds the rest, ascending.
  static constexpr uint32_t kTaskNodes = 128;
  // Marked nodes from which the tasks run in parallel. When the refit gathered each moved
  // model's placement itself, two threads lost (R1M's 10^4 spheres, every node: 0.13 ms on
  // one thread, 0.26-0.32 on two, the placements' lines moving between the cores) and the
  // threshold was 16,384. With the boxes staged by leaf first (scene.cpp), two threads win
  // from a few hundred marked nodes (a 2-core AVX-512 VM, median prepare() a frame, 2
  // threads, 16,384 against 512: 10^4 spheres all moved 0.47-0.50 -> 0.36-0.37 ms, a tenth
  // moved 0.187 -> 0.153, a hundredth 0.034 either way (128: 0.036); 3 * 10^4 spheres all
  // moved 1.66 -> 0.94, 10^5 4.2 -> 3.6; one thread unchanged).
  static constexpr std::size_t kParallelNodes = 512;
  std::size_t parallel_nodes_ = kParallelNodes;
  std::vector<uint32_t> task_root_, task_end_, top_;
  // What each task (and, last, the top) changed and was asked to revisit; and whether its
  // numbering held.
  struct alignas(64) Part {  // a cache line each: tasks on different threads write their own
    // changed holds a place for each of the part's nodes (link() sizes it), each refit at most
    // once: a store, not a push_back's call (24 instructions a changed node).
    std::vector<uint32_t> changed, revisit;
    std::size_t changed_count = 0;
    bool ok = true;
  };
  std::vector<Part> parts_;
  Part extra_;                     // the nodes attach() added (from linked_nodes_ on)
  std::size_t linked_nodes_ = 0;   // the nodes link() saw
  bool all_marked_ = false;

  // Node i's slots from its marked children (refit()'s body for one node).
  template <class BoxOf>
  void refit_node(BoxBvh8& bvh, uint32_t i, BoxOf& box, bvh_slots_store_fn* store, Part& part) {
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
        bool again = false;
        if constexpr (kBoxBvhLeafItems == 1) {
          // One item: its finite box is its union with the empty one.
          const uint32_t item = bvh.leaves[l].item[0];
          if (item != kNoItem) again = box(l, item, slot.lo, slot.hi);
        } else {
          float lo[3], hi[3];
          for (uint32_t item : bvh.leaves[l].item)
            if (item != kNoItem) again |= box(l, item, lo, hi), slot.grow(lo, hi);
        }
        if (again) part.revisit.push_back(l);
        leaf_area_[l] = slot.half_area();
      } else {
        if (code <= i || code >= bvh.nodes.size()) {
          part.ok = false;
          return;
        }
        if (!node_mark_[code] || !node_changed_[code]) continue;
        slot = node_box_[code];
      }
      for (int a = 0; a < 3; ++a) rows[2 * a][k] = slot.lo[a], rows[2 * a + 1][k] = slot.hi[a];
    }
    BoxUnion own;
    // The bits compared, as the build's; a slot detach() emptied is already in the bounds.
    const bool changed = store(n, rows, own.lo, own.hi) || node_forced_[i];
    node_changed_[i] = changed;
    if (!changed) return;
    part.changed[part.changed_count++] = i;
    node_box_[i] = own;
    node_area_[i] = own.half_area();
    if (i == 0) bvh.bounds = aabb_from_min_max({own.lo[0], own.lo[1], own.lo[2]}, {own.hi[0], own.hi[1], own.hi[2]});
  }

  void plan_tasks(const BoxBvh8& bvh);
  std::size_t parts_bytes() const;
  static BoxUnion slots_of(const BvhNode8& node);
  static bool same_bits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
  double sah_cost() const;
};

}  // namespace gyro::detail
