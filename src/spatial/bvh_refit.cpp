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

void BvhRefit::clear_marks() {
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
          marked_leaves_.capacity()) * sizeof(uint32_t) +
         (node_area_.capacity() + leaf_area_.capacity()) * sizeof(double) + node_mark_.capacity() + leaf_mark_.capacity() +
         node_box_.capacity() * sizeof(BoxUnion) + node_changed_.capacity() +
         (revisit_.capacity() + task_root_.capacity() + task_end_.capacity() + top_.capacity()) * sizeof(uint32_t) +
         parts_bytes();
}

std::size_t BvhRefit::parts_bytes() const {
  std::size_t bytes = parts_.capacity() * sizeof(Part);
  for (const Part& part : parts_) bytes += (part.changed.capacity() + part.revisit.capacity()) * sizeof(uint32_t);
  return bytes;
}

double BvhRefit::sah_cost() const {
  return detail::sah_cost(node_area_.data(), node_area_.size(), leaf_area_.data(), leaf_area_.size());
}

}  // namespace gyro::detail
