#include "spatial/bvh_refit.hpp"

#include <algorithm>

namespace gyro::detail {

BoxUnion BvhRefit::slots_of(const BvhNode8& node) {
  BoxUnion u;
  for (int j = 0; j < 8; ++j) {
    if (node.child[j] == kEmptyChild) continue;
    const float l[3] = {node.bounds[0][j], node.bounds[2][j], node.bounds[4][j]};
    const float h[3] = {node.bounds[1][j], node.bounds[3][j], node.bounds[5][j]};
    u.grow(l, h);
  }
  return u;
}

void BvhRefit::link(const BoxBvh8& bvh, std::size_t items) {
  const std::size_t nodes = bvh.nodes.size(), leaves = bvh.leaves.size();
  item_leaf_.assign(items, kNoItem);
  leaf_parent_.assign(leaves, kNoItem);
  node_parent_.assign(nodes, kNoItem);
  node_area_.assign(nodes, 0.0);
  leaf_area_.assign(leaves, 0.0);
  node_mark_.assign(nodes, 0);
  node_box_.assign(nodes, BoxUnion{});
  node_changed_.assign(nodes, 0);
  leaf_mark_.assign(leaves, 0);
  node_forced_.assign(nodes, 0);
  forced_nodes_.clear();
  free_leaves_.clear();
  marked_nodes_.clear();
  marked_leaves_.clear();
  for (std::size_t l = 0; l < leaves; ++l)
    for (uint32_t item : bvh.leaves[l].item)
      if (item != kNoItem && item < items) item_leaf_[item] = uint32_t(l);
  // The areas as refit() computes them, from the same stored bounds (so the same bits).
  for (std::size_t i = 0; i < nodes; ++i) {
    const BvhNode8& n = bvh.nodes[i];
    node_area_[i] = slots_of(n).half_area();
    for (int k = 0; k < 8; ++k) {
      const uint32_t code = n.child[k];
      if (code == kEmptyChild) continue;
      if (code & kLeafBit) {
        const uint32_t l = code & ~kLeafBit;
        if (l >= leaves) continue;
        leaf_parent_[l] = uint32_t(i);
        BoxUnion slot;
        const float lo[3] = {n.bounds[0][k], n.bounds[2][k], n.bounds[4][k]};
        const float hi[3] = {n.bounds[1][k], n.bounds[3][k], n.bounds[5][k]};
        slot.grow(lo, hi);
        leaf_area_[l] = slot.half_area();
      } else if (code < nodes) {
        node_parent_[code] = uint32_t(i);
      }
    }
  }
  linked_nodes_ = nodes;
  extra_ = Part{};
  plan_tasks(bvh);
}

void BvhRefit::plan_tasks(const BoxBvh8& bvh) {
  const std::size_t nodes = bvh.nodes.size();
  task_root_.clear();
  task_end_.clear();
  top_.clear();
  // Each subtree's size and the end of its index range, children first (their indices are
  // above their parent's); the tasks need every subtree to fill its range (the build's
  // depth-first numbering), else every node is left to the top, in the order of one pass.
  std::vector<uint32_t> size(nodes, 1), end(nodes);
  bool contiguous = true;
  for (std::size_t i = nodes; i-- > 0 && contiguous;) {
    end[i] = uint32_t(i + 1);
    for (const uint32_t code : bvh.nodes[i].child) {
      if (code == kEmptyChild || (code & kLeafBit)) continue;
      if (code <= i || code >= nodes) {
        contiguous = false;
        break;
      }
      size[i] += size[code], end[i] = std::max(end[i], end[code]);
    }
    contiguous = contiguous && end[i] - i == size[i];
  }
  if (!contiguous) {
    for (std::size_t i = 0; i < nodes; ++i) top_.push_back(uint32_t(i));
  } else if (nodes > 0) {
    std::vector<uint32_t> open{0};
    while (!open.empty()) {
      const uint32_t i = open.back();
      open.pop_back();
      if (size[i] <= kTaskNodes) {
        task_root_.push_back(i);
        continue;
      }
      top_.push_back(i);
      for (const uint32_t code : bvh.nodes[i].child)
        if (code != kEmptyChild && !(code & kLeafBit)) open.push_back(code);
    }
    std::sort(task_root_.begin(), task_root_.end());
    std::sort(top_.begin(), top_.end());
    for (const uint32_t root : task_root_) task_end_.push_back(end[root]);
  }
  parts_.assign(task_root_.size() + 1, Part{});
  for (std::size_t t = 0; t < task_root_.size(); ++t) parts_[t].changed.resize(task_end_[t] - task_root_[t]);
  parts_.back().changed.resize(top_.size());
}

void BvhRefit::mark_item(uint32_t item) {
  if (item >= item_leaf_.size() || item_leaf_[item] == kNoItem) return;
  const uint32_t l = item_leaf_[item];
  if (leaf_mark_[l]) return;  // its ancestors too
  leaf_mark_[l] = 1, marked_leaves_.push_back(l);
  for (uint32_t n = leaf_parent_[l]; n != kNoItem && !node_mark_[n]; n = node_parent_[n])
    node_mark_[n] = 1, marked_nodes_.push_back(n);
}

void BvhRefit::mark_all() {
  std::fill(node_mark_.begin(), node_mark_.end(), uint8_t(1));
  std::fill(leaf_mark_.begin(), leaf_mark_.end(), uint8_t(1));
  marked_nodes_.clear();
  marked_leaves_.clear();
  all_marked_ = true;
}

bool BvhRefit::detach(BoxBvh8& bvh, uint32_t item) {
  const uint32_t l = leaf_of(item);
  if (l == kNoItem) return false;
  // The slot holding `code` in node i emptied; a node left with no child is taken out of its
  // parent the same way (a used slot over an empty box would sort among the used ones with
  // a NaN key). The nodes are marked, not the block, which attach() may reuse at once.
  uint32_t code = kLeafBit | l;
  for (uint32_t i = leaf_parent_[l]; i != kNoItem; code = i, i = node_parent_[i]) {
    BvhNode8& n = bvh.nodes[i];
    bool used = false;
    for (int k = 0; k < 8; ++k) {
      if (n.child[k] == code) {
        n.child[k] = kEmptyChild;
        for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = __builtin_inff(), n.bounds[2 * a + 1][k] = -__builtin_inff();
      }
      used = used || n.child[k] != kEmptyChild;
    }
    if (!node_forced_[i]) node_forced_[i] = 1, forced_nodes_.push_back(i);
    for (uint32_t m = i; m != kNoItem && !node_mark_[m]; m = node_parent_[m]) node_mark_[m] = 1, marked_nodes_.push_back(m);
    if (used || i == 0) break;
  }
  for (uint32_t& it : bvh.leaves[l].item) it = kNoItem;
  item_leaf_[item] = kNoItem;
  leaf_parent_[l] = kNoItem;
  leaf_area_[l] = 0.0;  // out of the expected cost
  free_leaves_.push_back(l);
  return true;
}

uint32_t BvhRefit::attach(BoxBvh8& bvh, uint32_t item, const float lo[3], const float hi[3]) {
  if (bvh.nodes.size() != node_mark_.size() || bvh.leaves.size() != leaf_mark_.size() || leaf_of(item) != kNoItem)
    return kNoItem;
  BoxUnion box;
  box.grow(lo, hi);
  // Down from the root by the least growth of area (in double, from the stored bounds: a
  // function of the boxes alone) to the first node with an empty slot: every node below the
  // one that takes the block would grow too, so the first is the least expected cost (the
  // build's), the block's own area being the same anywhere. At a node of leaves alone with
  // no empty slot, the leaf whose union with the box is least shares a new node with it.
  uint32_t i = 0, at = kNoItem, pair_slot = 8;
  std::size_t depth = 1;  // the root's, as BvhStats::max_depth counts
  for (;;) {
    const BvhNode8& n = bvh.nodes[i];
    double best = __builtin_inf(), best_pair = __builtin_inf();
    uint32_t next = kNoItem;
    int pair = 8;
    bool room = false;
    for (int k = 0; k < 8; ++k) {
      const uint32_t code = n.child[k];
      if (code == kEmptyChild) {
        room = true;
        continue;
      }
      BoxUnion slot;
      const float l[3] = {n.bounds[0][k], n.bounds[2][k], n.bounds[4][k]};
      const float h[3] = {n.bounds[1][k], n.bounds[3][k], n.bounds[5][k]};
      slot.grow(l, h);
      const double before = slot.half_area();
      slot.grow(box.lo, box.hi);
      const double after = slot.half_area();
      if (code & kLeafBit) {
        if (after < best_pair) best_pair = after, pair = k;
      } else if (after - before < best && code < bvh.nodes.size()) {
        best = after - before, next = code;
      }
    }
    if (room) {
      at = i;
      break;
    }
    if (next == kNoItem) {
      // A new node below this one, past the depth the walks' stacks allow: the caller rebuilds.
      if (pair == 8 || depth + 1 > kBvhMaxDepth) return kNoItem;
      at = i, pair_slot = uint32_t(pair);
      break;
    }
    i = next, ++depth;
  }
  uint32_t l;
  if (!free_leaves_.empty()) {
    l = free_leaves_.back();
    free_leaves_.pop_back();
  } else {
    l = uint32_t(bvh.leaves.size());
    BvhItems empty;
    for (uint32_t& it : empty.item) it = kNoItem;
    bvh.leaves.push_back(empty);
    leaf_parent_.push_back(kNoItem);
    leaf_area_.push_back(0.0);
    leaf_mark_.push_back(0);
  }
  if (pair_slot < 8) {
    // The node's leaf in slot pair_slot moves into a new node (numbered after every other, so
    // after its parent: refit() refits such nodes first) with the new block beside it; the
    // slot keeps the leaf's box until the refit unites them.
    const uint32_t fresh = uint32_t(bvh.nodes.size());
    BvhNode8 node = empty_node8();
    BvhNode8& parent = bvh.nodes[at];
    const uint32_t moved = parent.child[pair_slot];
    node.child[0] = moved;
    for (int r = 0; r < 6; ++r) node.bounds[r][0] = parent.bounds[r][pair_slot];
    parent.child[pair_slot] = fresh;
    leaf_parent_[moved & ~kLeafBit] = fresh;
    bvh.nodes.push_back(node);
    node_parent_.push_back(at);
    BoxUnion moved_box;
    const float ml[3] = {node.bounds[0][0], node.bounds[2][0], node.bounds[4][0]};
    const float mh[3] = {node.bounds[1][0], node.bounds[3][0], node.bounds[5][0]};
    moved_box.grow(ml, mh);
    node_area_.push_back(moved_box.half_area());
    node_box_.push_back(moved_box);
    node_mark_.push_back(0);
    node_changed_.push_back(0);
    node_forced_.push_back(0);
    extra_.changed.resize(bvh.nodes.size() - linked_nodes_);
    bvh.stats.nodes = bvh.nodes.size();
    bvh.stats.max_depth = std::max(bvh.stats.max_depth, depth + 1);
    at = fresh;
  }
  BvhNode8& n = bvh.nodes[at];
  int k = 0;
  while (n.child[k] != kEmptyChild) ++k;  // the first empty slot (its bounds +inf, -inf)
  n.child[k] = kLeafBit | l;
  bvh.leaves[l].item[0] = item;
  if (item >= item_leaf_.size()) item_leaf_.resize(std::size_t(item) + 1, kNoItem);
  item_leaf_[item] = l;
  leaf_parent_[l] = at;
  mark_item(item);
  return l;
}

void BvhRefit::clear_marks() {
  for (uint32_t i : forced_nodes_) node_forced_[i] = 0;
  forced_nodes_.clear();
  if (all_marked_) {
    std::fill(node_mark_.begin(), node_mark_.end(), uint8_t(0));
    std::fill(leaf_mark_.begin(), leaf_mark_.end(), uint8_t(0));
  } else {
    for (uint32_t n : marked_nodes_) node_mark_[n] = 0;
    for (uint32_t l : marked_leaves_) leaf_mark_[l] = 0;
  }
  marked_nodes_.clear();
  marked_leaves_.clear();
  all_marked_ = false;
}

std::size_t BvhRefit::bytes() const {
  return (item_leaf_.capacity() + leaf_parent_.capacity() + node_parent_.capacity() + marked_nodes_.capacity() +
          marked_leaves_.capacity() + forced_nodes_.capacity() + free_leaves_.capacity()) * sizeof(uint32_t) +
         (node_area_.capacity() + leaf_area_.capacity()) * sizeof(double) + node_mark_.capacity() + leaf_mark_.capacity() +
         node_forced_.capacity() +
         node_box_.capacity() * sizeof(BoxUnion) + node_changed_.capacity() +
         (revisit_.capacity() + task_root_.capacity() + task_end_.capacity() + top_.capacity()) * sizeof(uint32_t) +
         parts_bytes();
}

std::size_t BvhRefit::parts_bytes() const {
  std::size_t bytes = parts_.capacity() * sizeof(Part) + (extra_.changed.capacity() + extra_.revisit.capacity()) * sizeof(uint32_t);
  for (const Part& part : parts_) bytes += (part.changed.capacity() + part.revisit.capacity()) * sizeof(uint32_t);
  return bytes;
}

double BvhRefit::sah_cost() const {
  return detail::sah_cost(node_area_.data(), node_area_.size(), leaf_area_.data(), leaf_area_.size());
}

}  // namespace gyro::detail
