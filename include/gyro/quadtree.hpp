// A 2D quadtree of axis-aligned rectangles with user ids (Cookbook chapter 6's quadtree,
// with removal, moving items, circle queries and deterministic results).
//
// Conventions:
//  - An item is a Rectangle2D and a uint32 id, unique in the tree. It is stored in the
//    deepest node whose bounds contain it entirely; an item that straddles a split line
//    stays in the parent, and one that is not inside the root's bounds stays in the root,
//    so every item is found by every query whatever its position.
//  - The shape of the tree is a function of the set of items and the QuadtreeDef alone:
//    a node has children exactly when it holds more than split_threshold items in its
//    subtree and is shallower than max_depth (an insert splits, a remove merges back).
//    So two trees that hold the same items have the same nodes, whatever the order of the
//    inserts, removes and updates that led there.
//  - Queries return the ids of the items whose rectangle overlaps the region (touching
//    included), sorted ascending: the same ids as testing every item with
//    gyro::overlaps(item, region) (gyro/geometry2d.hpp), bit for bit, in the same order
//    for any insertion history.
//  - Bad input changes nothing and returns a Status (gyro/status.hpp) with a detail in
//    gyro::last_error(): a NaN or infinite coordinate is non_finite; a negative size or
//    radius, a duplicate id or a bad QuadtreeDef is invalid_argument; an id that is not
//    in the tree is stale_id. A failed query leaves `out` empty.
//  - Not thread-safe for writes; const queries may run concurrently.
#pragma once

#include "gyro/geometry2d.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace gyro {

/// The parameters of a quadtree.
struct QuadtreeDef {
  /// The root's region: finite, size >= 0. Items outside it are still stored (in the root).
  Rectangle2D bounds{{0.0f, 0.0f}, {1024.0f, 1024.0f}};
  /// Depth of the deepest nodes (the root has depth 0), in [0, kQuadtreeMaxDepth].
  int32_t max_depth = 8;
  /// A node splits when more than this many items lie in its subtree; in [1, 2^20].
  int32_t split_threshold = 8;
};

/// The largest max_depth a QuadtreeDef may ask for: beyond about 20 halvings a float
/// node is a few ulps wide and a deeper split separates nothing.
inline constexpr int32_t kQuadtreeMaxDepth = 20;

/// A quadtree of rectangles with ids.
class Quadtree {
 public:
  /// An empty tree with the default QuadtreeDef.
  Quadtree();
  /// An empty tree with `def`; an invalid def leaves the default one (check with
  /// configure() when the def comes from outside).
  explicit Quadtree(const QuadtreeDef& def);

  /// Replaces the parameters and rebuilds the tree with the items it holds. An invalid def
  /// (non-finite or negative bounds, max_depth or split_threshold out of range) returns
  /// non_finite or invalid_argument and changes nothing.
  Status configure(const QuadtreeDef& def);
  /// The current parameters.
  const QuadtreeDef& def() const { return def_; }

  /// Adds an item. Fails (changing nothing) on non-finite bounds, a negative size or an
  /// id already in the tree.
  Status insert(uint32_t id, const Rectangle2D& bounds);
  /// Removes an item; stale_id if the id is not in the tree.
  Status remove(uint32_t id);
  /// Moves an item to new bounds; stale_id if the id is not in the tree, non_finite or
  /// invalid_argument for bad bounds (the item then keeps its old bounds).
  Status update(uint32_t id, const Rectangle2D& bounds);
  /// Removes every item (keeps the def).
  void clear();

  /// True if the id is in the tree.
  bool has(uint32_t id) const { return where_.count(id) != 0; }
  /// The item's bounds as inserted; stale_id if the id is not in the tree.
  Status bounds_of(uint32_t id, Rectangle2D* out) const;
  /// The number of items.
  std::size_t size() const { return where_.size(); }

  /// Ids of the items overlapping `region`, ascending, into out (replacing its contents).
  Status query(const Rectangle2D& region, std::vector<uint32_t>& out) const;
  /// Ids of the items overlapping the solid circle, ascending, into out.
  Status query(const Circle& region, std::vector<uint32_t>& out) const;

  /// The number of nodes (1 for an unsplit tree): with node_depth_histogram, a witness of
  /// the tree's shape for tests.
  std::size_t node_count() const { return nodes_.size() - 4 * free_blocks_.size(); }
  /// histogram[d] = the number of nodes at depth d.
  std::vector<std::size_t> node_depth_histogram() const;

 private:
  struct Entry {
    uint32_t id;
    Rectangle2D rect;  // as inserted
    vec2 hi;           // rect.origin + rect.size, rounded once as overlaps() rounds it
  };
  struct Node {
    vec2 lo, hi;            // the node's region
    int32_t children = -1;  // first of four consecutive nodes, or -1 for a leaf
    int32_t parent = -1;
    int32_t depth = 0;
    uint32_t count = 0;     // items in this node and below
    std::vector<Entry> entries;
  };

  void reset_nodes();
  void place(int32_t node, const Entry& e);
  void split(int32_t node);
  void collapse(int32_t node);
  void gather(int32_t node, std::vector<Entry>& out);
  int32_t child_fitting(int32_t node, const Entry& e) const;
  void erase(uint32_t id);
  template <class Prune, class Test>
  void collect(Prune prune, Test test, std::vector<uint32_t>& out) const;

  QuadtreeDef def_;
  std::vector<Node> nodes_;
  std::vector<int32_t> free_blocks_;  // first index of each unused block of four nodes
  std::map<uint32_t, int32_t> where_;  // id -> node holding it
};

}  // namespace gyro
