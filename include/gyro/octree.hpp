// The Cookbook's octree (chapter 12): boxes with ids in a tree whose nodes split into eight
// octants, each item stored in every leaf whose cell it overlaps. gyro's Scene uses it as one
// of its two acceleration structures (gyro/scene.hpp); it also serves on its own.
//
// Conventions:
//  - Built in one call from a set of (id, AABB) items; the tree is a function of that set
//    alone (items are taken in ascending id order), not of the order they were given in.
//  - The root cell is the union of the items' boxes (corners c - e and c + e, rounded as
//    gyro's own AABB tests round them). A node whose subtree holds more than leaf_capacity
//    items and that is shallower than max_depth splits at its cell's centre into eight
//    children (child k takes the upper half on axis a when bit a of k is set); an item goes
//    to every child cell its box overlaps, touching included. A split that would leave
//    every child with all of the node's items is not made (it would only copy them).
//  - Every node also keeps its content bounds: the union of the boxes of the items stored
//    at or below it (which may reach beyond its cell). Queries prune with these, so an
//    item is never missed, and they are tighter than the cells.
//  - Queries return the ids whose box passes gyro's own test (overlaps(AABB, AABB),
//    overlaps(Sphere, AABB), intersects(Frustum, AABB)), each id once, ascending: the
//    same ids as testing every item by brute force.
//  - Bad input changes nothing and returns a Status with a detail in gyro::last_error():
//    null arrays with a non-zero count (null_argument), NaN or infinite values
//    (non_finite), negative half extents, duplicate ids or a bad OctreeDef
//    (invalid_argument), counts of 2^31 or more (invalid_count). A failed query leaves
//    `out` empty.
//  - const queries may run concurrently; build() may not run alongside them.
#pragma once

#include "gyro/frustum.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro {

/// The deepest max_depth an OctreeDef may ask for (the root has depth 0): 8^16 cells is
/// far beyond any useful tree, and 16 halvings keep a cell many ulps wide.
inline constexpr int32_t kOctreeMaxDepth = 16;

/// How an octree subdivides.
struct OctreeDef {
  /// Depth of the deepest nodes, in [0, kOctreeMaxDepth] (the Cookbook's default).
  int32_t max_depth = 5;
  /// A node splits when its subtree holds more than this many items; in [1, 2^20]. 16 was
  /// the best of 8 and 16 on the scene benchmark (tests/spatial/scene_test.cpp, SceneBench).
  int32_t leaf_capacity = 16;
};

/// A node of the tree (read-only view, for traversals written elsewhere and for tests).
struct OctreeNode {
  float lo[3];         ///< content bounds: union of the boxes stored at or below (+inf, -inf when none)
  float hi[3];         ///< content bounds, maximum corner
  float cell_lo[3];    ///< the node's cell (its share of the parent's cell), minimum corner
  float cell_hi[3];    ///< the node's cell, maximum corner
  uint32_t first_child = 0;  ///< kOctreeLeaf for a leaf; otherwise children are nodes [first_child, first_child + 8)
  uint32_t first_item = 0;   ///< leaf: its items are items()[first_item, first_item + item_count)
  uint32_t item_count = 0;
  uint32_t depth = 0;        ///< root: 0
};

/// OctreeNode::first_child of a leaf.
inline constexpr uint32_t kOctreeLeaf = 0xFFFFFFFFu;

/// The shape of a built octree.
struct OctreeStats {
  std::size_t items = 0;       ///< distinct items
  std::size_t nodes = 0;       ///< all nodes, leaves included
  std::size_t leaves = 0;
  std::size_t references = 0;  ///< item entries over all leaves (>= items: an item may sit in many leaves)
  std::size_t max_depth = 0;   ///< of the deepest leaf
  std::size_t bytes = 0;       ///< nodes, item lists and boxes
};

/// An octree over boxes with uint32 ids.
class Octree {
 public:
  // An empty tree until build(): nodes() is empty and every query returns nothing.
  /// Replaces the tree with one over boxes[i] named ids[i], i in [0, count). Fails (changing
  /// nothing) on a bad def, null arrays, non-finite values, negative half extents or
  /// duplicate ids.
  Status build(const AABB* boxes, const uint32_t* ids, std::size_t count, const OctreeDef& def = {});
  /// Removes every item (keeps the def).
  void clear();

  /// The def of the last successful build.
  const OctreeDef& def() const { return def_; }
  /// Number of items.
  std::size_t size() const { return ids_.size(); }
  /// True when there are no items.
  bool empty() const { return ids_.empty(); }
  /// Counts and sizes of the current tree.
  OctreeStats stats() const;

  /// Nodes: after a build nodes()[0] is the root (an empty leaf when there are no items);
  /// before the first build there are none.
  const std::vector<OctreeNode>& nodes() const { return nodes_; }
  /// The leaves' item lists, concatenated: positions into ids() and boxes() (ascending id order).
  const std::vector<uint32_t>& items() const { return refs_; }
  /// The item ids, ascending.
  const std::vector<uint32_t>& ids() const { return ids_; }
  /// The item boxes, in ids() order.
  const std::vector<AABB>& boxes() const { return boxes_; }

  /// Ids of the items whose box overlaps the region (overlaps(AABB, AABB)), ascending.
  Status query(const AABB& region, std::vector<uint32_t>& out) const;
  /// Ids of the items whose box overlaps the sphere (overlaps(Sphere, AABB)), ascending.
  Status query(const Sphere& sphere, std::vector<uint32_t>& out) const;
  /// Ids of the items whose box intersects the frustum (intersects(Frustum, AABB): kept
  /// unless entirely outside one plane), ascending.
  Status query(const Frustum& frustum, std::vector<uint32_t>& out) const;

 private:
  template <class NodeTest, class ItemTest>
  void collect(NodeTest&& node_test, ItemTest&& item_test, std::vector<uint32_t>& out) const;

  OctreeDef def_;
  std::vector<OctreeNode> nodes_;
  std::vector<uint32_t> refs_;
  std::vector<uint32_t> ids_;
  std::vector<AABB> boxes_;
};

namespace detail {
/// Conservative node test shared by the octree and the scene: false only when the box
/// [lo, hi] lies outside one of the frustum's planes by far more than intersects()'s
/// tolerance (1e-4 of the magnitudes involved), so a node whose content bounds contain a
/// shape that intersects() keeps is never culled.
bool frustum_may_touch(const Frustum& frustum, const float lo[3], const float hi[3]);
/// Status::ok for a frustum whose planes are all finite, else non_finite (named "what").
Status check_frustum(const Frustum& frustum, const char* what);
}  // namespace detail

}  // namespace gyro
