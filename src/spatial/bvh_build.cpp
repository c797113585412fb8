// BVH construction: a binary tree by binned SAH (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007) over the triangles' bounding-box centroids, then
// collapsed into 8-wide nodes by the collapse of least SAH cost (Collapse below), with
// triangles packed into 4-wide leaf blocks (a scene's items: kBoxBvhLeafItems to a block).
//
// Determinism: every decision is a function of float values and indices only (ties go to
// the lower axis, the lower bin, the earlier child); partitions are stable and the median
// fallback sorts by (centroid, index). The same mesh always gives the same bytes.
//
// Parallel (core/parallel's fixed chunks, so any thread count gives the same bytes), in four
// phases, each a function of the inputs alone:
// - the binary tree's top, level by level: each level's boxes, bins and stable partitions
//   run over fixed chunks of all its ranges at once, down to ranges of kTaskPrims;
// - those ranges' subtrees, built depth first as parallel tasks, each into its own node list
//   over its own range of the primitive order, linked in afterwards, and their collapse
//   planned bottom up (then the top's);
// - the wide tree's layout: its top placed depth first, its subtrees below kSplitDepth each
//   placed into a layout of their own in parallel, and the runs spliced into the order one
//   depth-first emission gives (the wide tree follows the binary tree's shape, not where its
//   nodes were stored);
// - every node and leaf block written whole, in parallel.
//
// The SAH cost counts leaf blocks, not primitives: a mesh's 4-wide blocks (a block of 1 to
// 4 triangles costs one lane test, so a node of at most 4 triangles is always a leaf), a box
// BVH's blocks of kBoxBvhLeafItems (bvh.hpp).
//
// One builder serves two outputs: a mesh's BVH (leaves hold the triangles' corners) and a
// BVH over arbitrary boxes (leaves hold item indices; the scene's top level). Only the
// primitive boxes and the leaf writer differ, so both get the same tree for the same boxes.
#include "spatial/bvh.hpp"
#include "spatial/bvh_orders.hpp"

#include "core/default_init.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <array>

namespace gyro::detail {
namespace {

constexpr int kBins = 32;
constexpr uint32_t kMeshLeafTriangles = 4;  // BvhLeaf4's lanes
// Subtrees of at most kTaskPrims primitives are built as parallel tasks (R2's 522k
// triangles make 182); the top's levels work in chunks of kChunkPrims. R1's 10^4 spheres
// make only 4, yet smaller tasks for small builds did not pay: at 512 two threads built
// them in 4.45 ms against 4.75, and at n / 16 (625) or 1024 the build took 14.4 ms against
// 5.7 on one thread for the same instructions (callgrind: 43.0 against 43.8 M a build), the
// time going to memory, not work (on this VM a fresh page costs about 10 us to fault in).
constexpr uint32_t kTaskPrims = 4096;
constexpr uint32_t kChunkPrims = 4096;
constexpr float kInf = __builtin_inff();

// x, y, z and a fourth lane that no decision reads: one vector operation grows all three
// axes (the scalar min and max were a third of R2's build; GCC's and Clang's vector
// extensions, so every target gets its own 4-wide instructions, or four floats).
using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));

inline F4 f4(const float p[3]) { return F4{p[0], p[1], p[2], 0.0f}; }

// A box as the builder's large arrays store it (primitives, binary nodes): trivially
// constructible, so they resize without writing and their parallel fills first-touch them.
struct Bounds {
  F4 lo, hi;
  // std::min(lo, b.lo) and std::max(hi, b.hi) lane by lane (the same selects, so the same
  // bits, signed zeros included).
  void grow(const Bounds& b) {
    lo = b.lo < lo ? b.lo : lo;
    hi = hi < b.hi ? b.hi : hi;
  }
  void grow(const F4& p) {
    lo = p < lo ? p : lo;
    hi = hi < p ? p : hi;
  }
  // Half the surface area, in double so large scenes keep their precision.
  double half_area() const {
    if (!(lo[0] <= hi[0])) return 0.0;
    const double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// A box that starts empty, (+inf, -inf): every accumulator.
struct Box : Bounds {
  Box() : Bounds{F4{} + kInf, F4{} - kInf} {}
  Box(const Bounds& b) : Bounds(b) {}
};

// A box's centroid (its corners' mean, lane by lane).
inline F4 centroid(const Bounds& b) { return (b.lo + b.hi) * 0.5f; }

struct BinaryNode {
  Bounds box;
  uint32_t left, right;   // interior
  uint32_t first, count;  // leaf when count > 0
};

// A node's bins along the three axes: the first `used` of kBins (Grid::bins), the only ones
// cleared, binned and swept.
struct Bins {
  Bounds box[3][kBins];
  uint32_t count[3][kBins];
  int used;
  explicit Bins(int n = kBins) : used(n) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < n; ++b) box[a][b] = Box(), count[a][b] = 0;
  }
  void merge(const Bins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < used; ++b) box[a][b].grow(o.box[a][b]), count[a][b] += o.count[a][b];
  }
};

// A subtree left for the parallel phase: its range, its depth, the node standing for it, and
// that node's boxes (already gathered, the subtree's root does not gather them again).
struct Task {
  uint32_t first, count, node;
  std::size_t depth;
  Box box, cbox;
};

template <class Node> constexpr int width_of = int(sizeof(Node::child) / sizeof(uint32_t));

// A node whose slots are all empty: bounds (+inf, -inf), which no slab test enters.
template <class Node> Node empty_node() {
  Node n;
  for (int k = 0; k < width_of<Node>; ++k) {
    for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = kInf, n.bounds[2 * a + 1][k] = -kInf;
    n.child[k] = kEmptyChild;
  }
  for (uint32_t& o : n.order) o = 0x76543210u;
  return n;
}

// BvhNode8::order: for each octant, the slots sorted by their centres along its diagonal
// (lo + hi in binary64, exact for floats, so the order is a function of the bounds alone):
// slot k's key for octant o is ((0 + s_x c_x) + s_y c_y) + s_z c_z, with s_a = -1 where bit
// a of o is set, +inf for an empty slot; ties go to the lower slot.
//
// A refit writes the orders of every node it changes, and eight insertion sorts that each
// recomputed every key were half of a scene's refit (R1M, a tenth moved: 1.8 M of 3.1 M
// instructions a frame). So the centres are summed once, and the keys are compared only for
// the four octants with a positive z: octant 7 - o has every sign flipped, and round to
// nearest is symmetric (fl(-a - b) = -fl(a + b)), so its keys are exactly the negated ones,
// and one comparison of two keys places both slots in both octants. A slot's place is a
// count (no branch on the keys: on the scene refit's unpredictable orders this ran 4% faster
// than two insertion sorts per pair, tests/spatial/bvh_refit_test.cpp holds both to the
// definition above); the empty slots come last, in slot order.
//
// OrderKeys holds what both the sort (set_orders) and its check (orders_hold) read, so the
// two cannot disagree on a key's bits.
struct OrderKeys {
  // key[o][k]: slot k's key for octant o < 4, ((0 + s_x c_x) + s_y c_y) + c_z. Every slot
  // without a branch (the loops vectorise): an empty slot's bounds (+inf, -inf) sum to a NaN
  // centre, so its keys are NaN.
  double key[4][8];
  int used[8], m = 0;    // the used slots in slot order, and how many
  uint32_t empties = 0;  // the empty slots' nibbles, last in every order, in slot order
  explicit OrderKeys(const BvhNode8& n) {
    double c[3][8];
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 8; ++k) c[a][k] = double(n.bounds[2 * a][k]) + double(n.bounds[2 * a + 1][k]);
    for (int k = 0; k < 8; ++k) {
      key[0][k] = ((0.0 + c[0][k]) + c[1][k]) + c[2][k];
      key[1][k] = ((0.0 - c[0][k]) + c[1][k]) + c[2][k];
      key[2][k] = ((0.0 + c[0][k]) - c[1][k]) + c[2][k];
      key[3][k] = ((0.0 - c[0][k]) - c[1][k]) + c[2][k];
    }
    for (int k = 0, e = 0; k < 8; ++k) {
      if (n.child[k] == kEmptyChild) empties |= uint32_t(k) << (4 * e++);
      else used[m++] = k;
    }
    if (m < 8) empties <<= 4 * m;  // with none empty, a shift by 32 would be undefined
  }
};

inline void set_orders(BvhNode8& n) {
  const OrderKeys keys(n);
  const int m = keys.m;
  const int* used = keys.used;
  const uint32_t empties = keys.empties;
  // Octant O (bit 2 clear) and 7 - O. A slot's place in O: the keys below its own plus the
  // equal ones of lower slots; in 7 - O: the keys above its own plus, again, the equal ones
  // of lower slots.
  const auto octant = [&]<int O>() {
    double key[8];
    for (int i = 0; i < m; ++i) key[i] = keys.key[O][used[i]];
    int below[8] = {}, equal_before[8] = {}, equal_after[8] = {};
    for (int j = 0; j < m; ++j)
      for (int i = j + 1; i < m; ++i) {
        const int lt = key[j] < key[i], gt = key[j] > key[i], eq = 1 - lt - gt;
        below[i] += lt, below[j] += gt, equal_before[i] += eq, equal_after[j] += eq;
      }
    uint32_t front = empties, back = empties;
    for (int i = 0; i < m; ++i) {
      const int above = m - 1 - below[i] - equal_before[i] - equal_after[i];
      front |= uint32_t(used[i]) << (4 * (below[i] + equal_before[i]));
      back |= uint32_t(used[i]) << (4 * (above + equal_before[i]));
    }
    n.order[O] = front, n.order[7 - O] = back;
  };
  octant.template operator()<0>();
  octant.template operator()<1>();
  octant.template operator()<2>();
  octant.template operator()<3>();
}

// Whether n.order is what set_orders would write, checked rather than recomputed: a refit
// moves boxes a little and seldom changes an order (R1M, a tenth moved: 4% of the nodes it
// changes). The order by (key, slot) is total, so the used slots in strictly ascending
// order, then the empty slots in slot order, is the one sequence the sort can give.
inline bool orders_hold(const BvhNode8& n) {
  // An order naming an empty slot finds its NaN key, which fails the comparisons below.
  const OrderKeys keys(n);
  const auto& key = keys.key;
  const int m = keys.m;
  const uint32_t empties = keys.empties;
  const uint32_t tail = m < 8 ? ~0u << (4 * m) : 0u;
  if (m == 0) {
    for (const uint32_t order : n.order)
      if (order != empties) return false;
    return true;
  }
  // Whether `order` ascends in keys k (descends with `down`), ties in slot order; `ties`
  // tells whether two keys were equal.
  const auto ascending = [&](uint32_t order, const double* k, bool down, bool& ties) {
    if ((order & tail) != empties || (order & 0x88888888u) != 0) return false;  // no slot past 7
    uint32_t r = order & 15u;
    double a = k[r];
    ties = false;
    for (int j = 1; j < m; ++j) {
      const uint32_t s = order >> (4 * j) & 15u;
      const double b = k[s];
      if (!((down ? b < a : a < b) || (a == b && r < s))) return false;
      ties = ties || a == b;
      r = s, a = b;
    }
    return a == a;  // one used slot: its nibble still names it
  };
  // Octant 7 - o's keys are octant o's negated (set_orders' comment). Without ties its order
  // is o's reversed (the used nibbles; the empty ones stay last), which a nibble reversal
  // checks without a key.
  const uint32_t want = (1u << (m - 1)) - 1u;  // the adjacent pairs among the used slots
  for (int o = 0; o < 4; ++o) {
    bool ties = false;
    const uint32_t front = n.order[o], back = n.order[7 - o];
    // The common case first, without a branch per slot: the keys in the stored order,
    // strictly ascending (an empty slot's NaN key fails). Anything else, ties included,
    // takes the exact walk.
    double g[8];
    for (int j = 0; j < 8; ++j) g[j] = key[o][front >> (4 * j) & 7u];
    uint32_t rising = 0;
    for (int j = 0; j < 7; ++j) rising |= uint32_t(g[j] < g[j + 1]) << j;
    // The first key ordered: with one used slot there is no pair to compare, and its nibble
    // must still name it.
    const bool strict = g[0] == g[0] && (rising & want) == want && (front & tail) == empties && (front & 0x88888888u) == 0;
    if (!strict && !ascending(front, key[o], false, ties)) return false;
    if (!ties) {
      uint32_t rev = __builtin_bswap32(front);
      rev = (rev & 0x0F0F0F0Fu) << 4 | (rev >> 4 & 0x0F0F0F0Fu);  // nibble j at 7 - j
      rev >>= 4 * (8 - m);                                        // the used ones at 0 .. m - 1
      if (back != (rev | empties)) return false;
    } else if (!ascending(back, key[o], true, ties)) {
      return false;
    }
  }
  return true;
}

// The leaf blocks of up to 2^shift primitives that n primitives fill (a shift, not a
// division: best_plane asks for every bin it sweeps).
double blocks(uint32_t n, uint32_t shift) { return double((n + (1u << shift) - 1) >> shift); }

// How many bins a node of `count` primitives is binned into: 8 + count / 4, at most kBins
// (from 96 primitives up). Small nodes have few distinct centroids to separate, and clearing
// and sweeping 32 bins on each axis for each of them was a third of R2's build (best_plane
// 314 M and the bins' clearing 80 M of 1,685 M instructions); Embree and Wald (2007) shrink
// the bins the same way. Measured (one thread, instructions of a whole R2 run, SAH costs):
//   bins           R2 instr.  R2 SAH   70k random triangles  50k random boxes
//   32             1,746 M    14.820   29.27                 31.644
//   16 + n/8       1,655 M    14.816   29.40                 31.657
//   8 + n/4        1,617 M    14.813   29.50                 31.643
//   4 + n/8        1,544 M    14.797   29.90                 31.781
// 8 + n/4 keeps the boxes' tree and R2's as good and the random triangle soup within 1%.
constexpr int bins_for(uint32_t count) { return int(std::min<uint32_t>(uint32_t(kBins), 8u + count / 4u)); }

// Where a node's centroids fall into bins along each axis (scale 0: a flat axis, all in bin 0).
struct Grid {
  float lo[3], scale[3];
  int bins;  // bins_for(the node's count)
  Grid(const Box& cbox, uint32_t count) : bins(bins_for(count)) {
    for (int axis = 0; axis < 3; ++axis) {
      const float ext = cbox.hi[axis] - cbox.lo[axis];
      lo[axis] = cbox.lo[axis];
      scale[axis] = ext > 0.0f ? float(bins) / ext : 0.0f;
      // A subnormal extent overflows the scale: as good as flat, left to the median split.
      if (!(scale[axis] < kInf)) scale[axis] = 0.0f;
    }
  }
  // Whether centroid c falls in a bin above `bin` < bins - 1 along axis (a plane's test),
  // from the binning's f = (c - lo) * scale without its clamps and conversion: the bin is
  // f's integer part clamped to [0, bins) (bin_range; bin 0 for a NaN or negative f), which
  // exceeds `bin` exactly when f >= bin + 1 (that is below bins).
  bool beyond(const F4& c, int axis, int bin) const { return (c[axis] - lo[axis]) * scale[axis] >= float(bin + 1); }
};

// A split: primitives whose centroid falls in bins [0, bin] along axis go left (axis -1: none).
struct Plane {
  int axis = -1, bin = 0;
};

// Binned SAH: the best plane between bins on any axis.
Plane best_plane(const Bins& bins, uint32_t count, const Grid& grid, uint32_t leaf_shift) {
  const auto& bin_box = bins.box;
  const auto& bin_count = bins.count;
  double best_cost = kInf;
  Plane best;
  for (int axis = 0; axis < 3; ++axis) {
    if (grid.scale[axis] == 0.0f) continue;
    // Only the non-empty bins, in order: an empty bin changes neither a side's box nor its
    // count, so its plane costs what the plane before it costs, to the bit, which the strict
    // < below already preferred (or skipped). Most bins of the many small nodes are empty:
    // sweeping all 32 was a third of the build's instructions.
    int used[kBins];
    int m = 0;
    for (int b = 0; b < grid.bins; ++b) used[m] = b, m += bin_count[axis][b] != 0;
    // Right to left: right_cost[i] is the cost of bins used[i..m) (the same grows in the
    // same order as a sweep over every bin).
    double right_cost[kBins];
    Box acc;
    uint32_t n = 0;
    for (int i = m - 1; i > 0; --i) {
      acc.grow(bin_box[axis][used[i]]);
      n += bin_count[axis][used[i]];
      right_cost[i] = acc.half_area() * blocks(n, leaf_shift);
    }
    acc = Box();
    n = 0;
    for (int i = 0; i < m; ++i) {
      const int b = used[i];
      acc.grow(bin_box[axis][b]);
      n += bin_count[axis][b];
      if (n == count) break;
      const double cost = acc.half_area() * blocks(n, leaf_shift) + right_cost[i + 1];
      if (cost < best_cost) best_cost = cost, best = {axis, b};
    }
  }
  return best;
}

class Builder {
 public:
  // prim[i] is primitive i's box; a leaf block holds up to leaf_size of them, and the leaf
  // writer receives their indices.
  Builder(DefaultInitVector<Bounds> prims, uint32_t leaf_size)
      : box_{std::move(prims), {}}, leaf_size_(leaf_size), leaf_shift_(uint32_t(__builtin_ctz(leaf_size))) {
    const std::size_t n = box_[0].size();
    index_[0].resize(n);
    index_[1].resize(n);
    box_[1].resize(n);
    parallel_for(n, kChunkPrims, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) index_[0][i] = uint32_t(i);
    });
  }

  // Out is Bvh8 or BoxBvh8; leaf(block, items, count) writes every byte of a leaf block
  // holding binary leaf items[0, count).
  template <class Out, class Leaf> Out run(Leaf&& leaf) {
    using Node = typename decltype(Out::nodes)::value_type;
    static_assert(width_of<Node> == kWidth);
    std::vector<Task> tasks;
    build_top(tasks);
    const std::size_t top_nodes = nodes_.size();
    build_tasks(tasks);
    for (std::size_t i = top_nodes; i-- > 0;) plan(uint32_t(i));  // the tasks' roots again: the same plan
    constexpr uint32_t root = 0;
    Out out;
    const Bounds& rb = nodes_[root].box;
    out.bounds = aabb_from_min_max({rb.lo[0], rb.lo[1], rb.lo[2]}, {rb.hi[0], rb.hi[1], rb.hi[2]});
    // The root is always a wide node, even over a single leaf, so traversal has one shape.
    // Below kSplitDepth the layout is placed in parallel, one subtree per layout.
    Layout top;
    std::vector<Layout> sub;
    if (nodes_[root].count > 0) {
      top.wide.push_back({root, 1, {root}, {kLeafBit}});
      top.leaf.push_back(root);
      top.max_depth = 1;
    } else {
      std::vector<uint32_t> deferred;
      place(top, root, 1, &deferred);
      sub.resize(deferred.size());
      parallel_for(sub.size(), 1, [&](std::size_t b, std::size_t e) {
        for (std::size_t d = b; d < e; ++d) place(sub[d], deferred[d], kSplitDepth, nullptr);
      });
    }
    // The numbering one depth-first emission gives: the top's order with each subtree's
    // layout spliced in where its root stands.
    std::vector<uint32_t> top_index(top.wide.size()), top_leaf(top.leaf.size());
    uint32_t node_count = 0, leaf_count = 0;
    assemble(top, sub, 0, node_count, leaf_count, top_index, top_leaf);
    // What each node and leaf block holds is a function of its own inputs, written whole in
    // parallel (with the pages' first touches: the serial emission that wrote them was most
    // of the build's serial time on two threads).
    out.nodes.resize(node_count);
    out.leaves.resize(leaf_count);
    std::vector<double> node_area(node_count), leaf_area(leaf_count);  // for the SAH cost
    bvh_orders_set_fn* const set_orders_at_level = GYRO_DISPATCH(bvh_orders_set);  // the bytes of set_orders()
    const auto write_node = [&](const Wide& w, uint32_t at, const uint32_t* codes) {
      Node node = empty_node<Node>();
      for (uint32_t j = 0; j < w.n; ++j) set_child(node, int(j), nodes_[w.kid[j]].box, codes[j]);
      set_orders_at_level(node);
      out.nodes[at] = node;
      node_area[at] = nodes_[w.self].box.half_area();
    };
    const auto write_leaf = [&](uint32_t binary, uint32_t at) {
      const BinaryNode& b = nodes_[binary];
      leaf(out.leaves[at], index_[0].data() + b.first, b.count);
      leaf_area[at] = b.box.half_area();
    };
    parallel_for(sub.size() + 1, 1, [&](std::size_t b, std::size_t e) {
      for (std::size_t d = b; d < e; ++d) {
        if (d == sub.size()) {
          for (std::size_t k = 0; k < top.wide.size(); ++k) write_node(top.wide[k], top_index[k], top.wide[k].code);
          for (std::size_t k = 0; k < top.leaf.size(); ++k) write_leaf(top.leaf[k], top_leaf[k]);
          continue;
        }
        const Layout& l = sub[d];
        for (std::size_t k = 0; k < l.wide.size(); ++k) {
          uint32_t codes[kWidth];
          for (uint32_t j = 0; j < l.wide[k].n; ++j) {
            const uint32_t c = l.wide[k].code[j];
            codes[j] = c & kLeafBit ? kLeafBit | (l.leaf_base + (c & ~kLeafBit)) : l.node_base + c;
          }
          write_node(l.wide[k], l.node_base + uint32_t(k), codes);
        }
        for (std::size_t k = 0; k < l.leaf.size(); ++k) write_leaf(l.leaf[k], l.leaf_base + uint32_t(k));
      }
    });
    std::size_t depth = top.max_depth;
    for (const Layout& l : sub) depth = std::max(depth, l.max_depth);
    out.stats.nodes = out.nodes.size();
    out.stats.leaves = out.leaves.size();
    out.stats.max_depth = depth;
    out.stats.bytes = out.nodes.size() * sizeof(out.nodes[0]) + out.leaves.size() * sizeof(out.leaves[0]);
    out.stats.sah_cost = sah_cost(node_area.data(), node_area.size(), leaf_area.data(), leaf_area.size());
    return out;
  }

 private:
  static constexpr int kWidth = 8;
  static constexpr uint32_t kNoParent = 0xFFFFFFFFu;

  // Wide nodes at this depth root layouts of their own, placed in parallel (up to 8^3 of them).
  static constexpr std::size_t kSplitDepth = 4;
  // In the top layout, a child that roots a subtree layout (its index in the list).
  static constexpr uint32_t kSubBit = 0x40000000u;

  // A wide node as a layout placed it: the binary node it stands for, its binary kids and
  // their codes (numbered within its layout until the assembly).
  struct Wide {
    uint32_t self, n;
    uint32_t kid[kWidth];
    uint32_t code[kWidth];
  };
  // A depth-first run of wide nodes and leaf blocks (the binary leaf of each).
  struct Layout {
    std::vector<Wide> wide;
    std::vector<uint32_t> leaf;
    std::size_t max_depth = 0;
    uint32_t node_base = 0, leaf_base = 0;  // its first node and leaf block in the output
  };

  // The primitives' indices and boxes in two buffers that the partitions alternate between:
  // a range at depth d lies in buffer d & 1, each split (by SAH or by the median) writes
  // both sides into the other buffer, each where it ends up, and a leaf at an odd depth
  // copies its few indices back into buffer 0, where the leaf writer reads them. The boxes
  // move with their indices, so binning and partitions stream them from memory instead of
  // gathering them by index (with the centroids, the gathers were R2's build's cache
  // misses). One buffer with a scratch copy back after each partition (the right side of a
  // task's, everything at the top) cost R2's build 114 M more data reads and 106 M more
  // writes (callgrind: 384 and 307 M against 270 and 201 M).
  DefaultInitVector<uint32_t> index_[2];
  DefaultInitVector<Bounds> box_[2];
  uint32_t leaf_size_;   // the most primitives a leaf block holds: a power of two,
  uint32_t leaf_shift_;  // 2^leaf_shift_
  uint32_t* index_at(std::size_t depth) { return index_[depth & 1].data(); }
  Bounds* box_at(std::size_t depth) { return box_[depth & 1].data(); }
  const Bounds* box_at(std::size_t depth) const { return box_[depth & 1].data(); }
  // A leaf's indices where the leaf writer reads them.
  void settle_leaf(uint32_t first, uint32_t count, std::size_t depth) {
    if (depth & 1) std::copy(index_[1].data() + first, index_[1].data() + first + count, index_[0].data() + first);
  }
  // How many of bins go left of plane (bins [0, plane.bin] on its axis): the partition's
  // own count, as its test (Grid::beyond) reads the binning's f.
  static uint32_t left_of(const Bins& bins, const Plane& plane) {
    uint32_t n = 0;
    for (int b = 0; b <= plane.bin; ++b) n += bins.count[plane.axis][b];
    return n;
  }
  DefaultInitVector<BinaryNode> nodes_;

  // The collapse into wide nodes, planned per binary node by dynamic programming over its
  // subtree (Ylitie, Karras and Laine, "Efficient incoherent ray traversal on GPUs through
  // compressed wide BVHs", HPG 2017; without their leaf merging: the leaf blocks are the
  // binary leaves). A subtree shown to its wide parent as at most j kids costs the least of
  // itself as one kid (a leaf block: its area; a wide node: its area plus its kids', the
  // left child's share of kWidth slots chosen) and, for j >= 2, its children's subtrees as
  // k and j - k kids: the cost model of sah_cost(), every node and leaf block tested with
  // the probability of its area. Opening the largest child until eight (the usual greedy
  // collapse) filled R2's lowest nodes with about four blocks: 38,513 nodes and SAH cost
  // 15.32 against 26,142 and 14.82 here, and R2's rays ran 11-13% faster.
  //
  // Children are numbered after their parents (build_top() level by level, a task depth
  // first), so a plan made in falling index order finds its children's made. Ties keep the
  // node whole, then the smallest left share: a function of the boxes alone.
  struct Collapse {
    float cost[kWidth];     // cost[j - 1]: the subtree as at most j kids
    uint8_t split[kWidth];  // split[j - 1]: the left child's share of those j, or 0: the node as one kid
    uint8_t wide;           // the node as a wide node: the left child's share of its kWidth slots
  };
  DefaultInitVector<Collapse> collapse_;

  void plan(uint32_t i) {
    const BinaryNode& b = nodes_[i];
    Collapse& c = collapse_[i];
    const float area = float(b.box.half_area());
    if (b.count > 0) {
      for (int j = 0; j < kWidth; ++j) c.cost[j] = area, c.split[j] = 0;
      c.wide = 0;
      return;
    }
    const Collapse& l = collapse_[b.left];
    const Collapse& r = collapse_[b.right];
    // as[j - 1]: the children's subtrees as j kids, the best share of the left's.
    float as[kWidth];
    uint8_t share[kWidth];
    for (int j = 2; j <= kWidth; ++j) {
      float best = kInf;
      int pick = 1;
      for (int k = 1; k < j; ++k) {
        const float cost = l.cost[k - 1] + r.cost[j - k - 1];
        if (cost < best) best = cost, pick = k;
      }
      as[j - 1] = best, share[j - 1] = uint8_t(pick);
    }
    const float whole = area + as[kWidth - 1];
    c.wide = share[kWidth - 1];
    c.cost[0] = whole, c.split[0] = 0;
    for (int j = 2; j <= kWidth; ++j) {
      const bool open = as[j - 1] < whole;
      c.cost[j - 1] = open ? as[j - 1] : whole, c.split[j - 1] = open ? share[j - 1] : 0;
    }
  }

  void node_boxes(uint32_t first, uint32_t end, std::size_t depth, Box& box, Box& cbox) const {
    const Bounds* const boxes = box_at(depth);
    for (uint32_t i = first; i < end; ++i) {
      box.grow(boxes[i]);
      cbox.grow(centroid(boxes[i]));
    }
  }

  // A primitive's bins along all three axes from one vector expression: f = (c - lo) *
  // scale lane by lane, clamped to [0, bins) (NaN to 0) before its conversion (a float past
  // INT_MAX has no int). Grid::beyond() reads the same f.
  static I4 bins_of(const Bounds& r, const Grid& grid, const F4& lo4, const F4& scale4) {
    F4 f = (centroid(r) - lo4) * scale4;
    f = f >= 0.0f ? f : F4{};  // NaN too
    f = f < float(grid.bins) ? f : F4{} + float(grid.bins - 1);
    return __builtin_convertvector(f, I4);
  }
  void bin_range(Bins& bins, const Grid& grid, uint32_t first, uint32_t end, std::size_t depth) const {
    const F4 lo4 = f4(grid.lo), scale4 = f4(grid.scale);
    const Bounds* const boxes = box_at(depth);
    for (uint32_t i = first; i < end; ++i) {
      const Bounds& r = boxes[i];
      const I4 b = bins_of(r, grid, lo4, scale4);
      for (int axis = 0; axis < 3; ++axis) {
        bins.box[axis][b[axis]].grow(r);
        ++bins.count[axis][b[axis]];
      }
    }
  }

  // The binary tree's top, level by level down to ranges of kTaskPrims, which are listed
  // in `tasks` (each standing as a node of its box with no children yet). A level's bins
  // and partitions each run as one parallel loop over fixed chunks of all its ranges: a
  // recursion left one thread partitioning the root's primitives, then its halves', while
  // the others waited (the top was a fifth of R2's build on two threads and did not scale).
  // Each range gets the decisions a recursion would give it (bins and boxes merged exactly,
  // the partition stable), and the wide tree is emitted from the binary tree's shape, not
  // from where its nodes are stored: the same bytes.
  void build_top(std::vector<Task>& tasks) {
    struct Open {
      uint32_t first, count, parent;
      int side;
      std::size_t depth;
      bool known;  // box and cbox gathered by the parent's partition
      Box box, cbox;
    };
    struct Piece {
      uint32_t range, begin, end;
    };
    // A piece's partition: both sides' boxes and centroid boxes.
    struct Split {
      Box box[2], cbox[2];
    };
    std::vector<Open> level(1), next;
    level[0].first = 0, level[0].count = uint32_t(index_[0].size()), level[0].parent = kNoParent;
    level[0].side = 0, level[0].depth = 0, level[0].known = false;
    while (!level.empty()) {
      std::vector<Piece> pieces;
      for (uint32_t r = 0; r < level.size(); ++r)
        for (uint32_t b = level[r].first, e = b + level[r].count; b < e; b += std::min(kChunkPrims, e - b))
          pieces.push_back({r, b, b + std::min(kChunkPrims, e - b)});
      const auto each_piece = [&](auto&& f) {
        parallel_for(pieces.size(), 1, [&](std::size_t b, std::size_t e) {
          for (std::size_t k = b; k < e; ++k) f(k, pieces[k]);
        });
      };
      std::vector<Split> part(pieces.size());
      each_piece([&](std::size_t k, const Piece& p) {
        if (!level[p.range].known) node_boxes(p.begin, p.end, level[p.range].depth, part[k].box[0], part[k].cbox[0]);
      });
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        Open& o = level[pieces[k].range];
        if (!o.known) o.box.grow(part[k].box[0]), o.cbox.grow(part[k].cbox[0]);
      }
      // Which ranges split here, by SAH (1) or by the median (2).
      std::vector<uint8_t> split(level.size(), 0);
      std::vector<uint32_t> node(level.size());
      std::vector<Grid> grid;
      grid.reserve(level.size());
      for (uint32_t r = 0; r < level.size(); ++r) {
        const Open& o = level[r];
        grid.emplace_back(o.cbox, o.count);
        node[r] = uint32_t(nodes_.size());
        nodes_.push_back({o.box, 0, 0, 0, 0});
        if (o.parent != kNoParent) (o.side ? nodes_[o.parent].right : nodes_[o.parent].left) = node[r];
        if (o.count <= leaf_size_) nodes_[node[r]].first = o.first, nodes_[node[r]].count = o.count, settle_leaf(o.first, o.count, o.depth);
        else if (o.count <= kTaskPrims) tasks.push_back({o.first, o.count, node[r], o.depth, o.box, o.cbox});
        // Past this depth only median splits, which end within log2(count) <= 31 more levels.
        else split[r] = o.depth + 33 < kBvhMaxDepth ? 1 : 2;
      }
      // (Ranges here hold over kTaskPrims primitives: all kBins bins.)
      static_assert(bins_for(kTaskPrims) == kBins);
      std::vector<Bins> bins(pieces.size());
      each_piece([&](std::size_t k, const Piece& p) {
        if (split[p.range] == 1) bin_range(bins[k], grid[p.range], p.begin, p.end, level[p.range].depth);
      });
      std::vector<Bins> merged(level.size());
      for (std::size_t k = 0; k < pieces.size(); ++k)
        if (split[pieces[k].range] == 1) merged[pieces[k].range].merge(bins[k]);
      std::vector<Plane> plane(level.size());
      for (uint32_t r = 0; r < level.size(); ++r)
        if (split[r] == 1) plane[r] = best_plane(merged[r], level[r].count, grid[r], leaf_shift_);
      // Each piece's left count from its bins, and from those every piece's places: the
      // stable partition then writes both sides straight into the other buffer, in parallel,
      // gathering both sides' boxes for the next level.
      std::vector<uint32_t> left_total(level.size(), 0), left_at(pieces.size()), right_at(pieces.size());
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        const uint32_t r = pieces[k].range;
        if (plane[r].axis < 0) continue;
        left_at[k] = left_total[r];
        right_at[k] = pieces[k].begin - level[r].first - left_total[r];
        left_total[r] += left_of(bins[k], plane[r]);
      }
      // A plane with everything on one side partitions nothing: the median split follows.
      for (uint32_t r = 0; r < level.size(); ++r)
        if (plane[r].axis >= 0 && (left_total[r] == 0 || left_total[r] == level[r].count)) plane[r].axis = -1;
      for (Split& sp : part) sp = Split{};
      each_piece([&](std::size_t k, const Piece& p) {
        const Plane& pl = plane[p.range];
        if (pl.axis < 0) return;
        const Open& o = level[p.range];
        Box sides[2][2];
        partition(o.depth, p.begin, p.end, grid[p.range], pl, o.first + left_at[k],
                  o.first + left_total[p.range] + right_at[k], sides);
        Split& sp = part[k];
        for (int side = 0; side < 2; ++side) sp.box[side] = sides[side][0], sp.cbox[side] = sides[side][1];
      });
      next.clear();
      for (uint32_t r = 0; r < level.size(); ++r) {
        if (!split[r]) continue;
        const Open& o = level[r];
        const bool known = plane[r].axis >= 0;
        const uint32_t left = known ? left_total[r] : median_split(o.first, o.count, o.depth, o.cbox);
        next.push_back({o.first, left, node[r], 0, o.depth + 1, known, {}, {}});
        next.push_back({o.first + left, o.count - left, node[r], 1, o.depth + 1, known, {}, {}});
      }
      // The children's boxes, merged from their parent's pieces.
      for (std::size_t k = 0, c = 0; k < pieces.size(); ++k) {
        const uint32_t r = pieces[k].range;
        if (!split[r]) continue;
        while (next[c].parent != node[r]) c += 2;
        if (!next[c].known) continue;
        for (int side = 0; side < 2; ++side)
          next[c + side].box.grow(part[k].box[side]), next[c + side].cbox.grow(part[k].cbox[side]);
      }
      level.swap(next);
    }
  }

  // Builds the subtree over the primitives [first, first + count) of buffer depth & 1 into
  // `nodes`; returns its root.
  // `known` holds the range's box and centroid box when they are already gathered (by the
  // parent's partition, which visits each side's primitives in the order they end up in, so
  // the boxes have the bits a gathering pass would give them, signed zeros included).
  uint32_t build(std::vector<BinaryNode>& nodes, uint32_t first, uint32_t count, std::size_t depth,
                 const Box* known = nullptr) {
    Box box, cbox;
    if (known) box = known[0], cbox = known[1];
    else node_boxes(first, first + count, depth, box, cbox);
    const uint32_t index = uint32_t(nodes.size());
    nodes.push_back({box, 0, 0, 0, 0});
    if (count <= leaf_size_) {
      nodes[index].first = first, nodes[index].count = count;
      settle_leaf(first, count, depth);
      return index;
    }
    uint32_t left_count = 0;
    Box sides[2][2];  // [side]{box, cbox}
    // Past this depth only median splits, which end within log2(count) <= 31 more levels.
    if (depth + 33 < kBvhMaxDepth) left_count = sah_split(first, count, depth, cbox, sides);
    const bool split = left_count != 0;
    if (!split) left_count = median_split(first, count, depth, cbox);
    const uint32_t l = build(nodes, first, left_count, depth + 1, split ? sides[0] : nullptr);
    const uint32_t r = build(nodes, first + left_count, count - left_count, depth + 1, split ? sides[1] : nullptr);
    nodes[index].left = l, nodes[index].right = r;
    return index;
  }

  // Builds the listed subtrees in parallel, then puts each one's nodes in place (its root in
  // place of the node standing for it, its other indices moved past the nodes before it).
  void build_tasks(const std::vector<Task>& tasks) {
    std::vector<std::vector<BinaryNode>> sub(tasks.size());
    parallel_for(tasks.size(), 1, [&](std::size_t b, std::size_t e) {
      for (std::size_t t = b; t < e; ++t) {
        const Box known[2] = {tasks[t].box, tasks[t].cbox};
        build(sub[t], tasks[t].first, tasks[t].count, tasks[t].depth, known);
      }
    });
    std::vector<uint32_t> base(tasks.size());
    std::size_t total = nodes_.size();
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      base[t] = uint32_t(total) - 1;  // local index 1 lands at base + 1
      total += sub[t].size() - 1;
    }
    nodes_.resize(total);
    collapse_.resize(total);
    parallel_for(tasks.size(), 1, [&](std::size_t b, std::size_t e) {
      for (std::size_t t = b; t < e; ++t) {
        const auto moved = [&](BinaryNode n) {
          if (n.count == 0) n.left += base[t], n.right += base[t];
          return n;
        };
        nodes_[tasks[t].node] = moved(sub[t][0]);
        for (std::size_t k = 1; k < sub[t].size(); ++k) nodes_[base[t] + k] = moved(sub[t][k]);
        for (std::size_t k = sub[t].size(); k-- > 1;) plan(uint32_t(base[t] + k));
        plan(tasks[t].node);
      }
    });
  }

  // sah_split() of two primitives without bins (a box BVH, one item to a leaf, has one such
  // node for about every three items, and clearing and sweeping bins for them was 9% of a
  // scene's build's instructions). What the bins would decide: on every axis where the two fall in
  // different bins (the binning's own expression), those bins are the only used ones and the
  // plane between them costs area(a) + area(b) (the sum commutes, so the same bits), so the
  // strict < of best_plane keeps the first such axis; the stable partition puts the one in
  // the lower bin left. No such axis: no plane, as best_plane finds none.
  uint32_t split_pair(uint32_t first, std::size_t depth, const Grid& grid, Box (&sides)[2][2]) {
    const uint32_t* const from = index_at(depth) + first;
    const Bounds* const from_box = box_at(depth) + first;
    const F4 lo4 = f4(grid.lo), scale4 = f4(grid.scale);
    const I4 b0 = bins_of(from_box[0], grid, lo4, scale4), b1 = bins_of(from_box[1], grid, lo4, scale4);
    int axis = 0;
    while (axis < 3 && (grid.scale[axis] == 0.0f || b0[axis] == b1[axis])) ++axis;
    if (axis == 3) return 0;
    const int l = b1[axis] < b0[axis] ? 1 : 0;  // the first of the two, unless the second's bin is lower
    uint32_t* const to = index_at(depth + 1) + first;
    Bounds* const to_box = box_at(depth + 1) + first;
    to[0] = from[l], to_box[0] = from_box[l];
    to[1] = from[1 - l], to_box[1] = from_box[1 - l];
    for (int side = 0; side < 2; ++side) {
      Box box, cbox;
      box.grow(to_box[side]), cbox.grow(centroid(to_box[side]));
      sides[side][0] = box, sides[side][1] = cbox;
    }
    return 1;
  }

  // Binned SAH for a task's node at `depth`: the best plane, and the stable partition into
  // the other buffer (each side where its count from the bins puts it), gathering both
  // sides' boxes and centroid boxes into `sides` (in place of a pass over each child's
  // range: R2's build 1718 -> 1685 M instructions); returns the left count, or 0 (no plane,
  // nothing partitioned).
  uint32_t sah_split(uint32_t first, uint32_t count, std::size_t depth, const Box& cbox, Box (&sides)[2][2]) {
    const Grid grid(cbox, count);
    if (count == 2) return split_pair(first, depth, grid, sides);
    Bins bins(grid.bins);
    bin_range(bins, grid, first, first + count, depth);
    const Plane plane = best_plane(bins, count, grid, leaf_shift_);
    if (plane.axis < 0) return 0;
    const uint32_t left = left_of(bins, plane);
    if (left == 0 || left == count) return 0;
    partition(depth, first, first + count, grid, plane, first, first + left, sides);  // this range's own places
    return left;
  }

  // The stable partition by `plane` of [begin, end) of buffer depth & 1 into the other
  // buffer, its left side from to_left on and its right side from to_right on (the places
  // its count from the bins gives each), with each side's box and centroid box grown in the
  // order its primitives land (a gathering pass's bits). Ranges running in parallel write
  // their own places.
  void partition(std::size_t depth, uint32_t begin, uint32_t end, const Grid& grid, const Plane& plane,
                 uint32_t to_left, uint32_t to_right, Box (&sides)[2][2]) {
    const uint32_t* const from = index_at(depth);
    const Bounds* const from_box = box_at(depth);
    uint32_t* const to = index_at(depth + 1);
    Bounds* const to_box = box_at(depth + 1);
    uint32_t l = to_left, r = to_right;
    Box lbox, lcbox, rbox, rcbox;  // locals, not sides[]: they stay in registers
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t p = from[i];
      const Bounds q = from_box[i];
      const F4 c = centroid(q);
      if (grid.beyond(c, plane.axis, plane.bin)) {
        to[r] = p, to_box[r++] = q;
        rbox.grow(q), rcbox.grow(c);
      } else {
        to[l] = p, to_box[l++] = q;
        lbox.grow(q), lcbox.grow(c);
      }
    }
    sides[0][0] = lbox, sides[0][1] = lcbox, sides[1][0] = rbox, sides[1][1] = rcbox;
  }

  // Half by count along the widest centroid axis, ordered by (centroid, index), into the
  // other buffer (which first holds the sort's positions).
  uint32_t median_split(uint32_t first, uint32_t count, std::size_t depth, const Box& cbox) {
    int axis = 0;
    float ext = -1.0f;
    for (int a = 0; a < 3; ++a) {
      const float e = cbox.hi[a] - cbox.lo[a];
      if (e > ext) ext = e, axis = a;
    }
    uint32_t* const at = index_at(depth + 1) + first;  // at[k]: the position in the range of the k-th
    for (uint32_t k = 0; k < count; ++k) at[k] = k;
    const uint32_t* const index = index_at(depth) + first;
    const Bounds* const box = box_at(depth) + first;
    std::sort(at, at + count, [&](uint32_t a, uint32_t b) {
      const float ca = centroid(box[a])[axis], cb = centroid(box[b])[axis];
      return ca < cb || (ca == cb && index[a] < index[b]);
    });
    Bounds* const sorted = box_at(depth + 1) + first;
    for (uint32_t k = 0; k < count; ++k) sorted[k] = box[at[k]];
    for (uint32_t k = 0; k < count; ++k) at[k] = index[at[k]];
    return count / 2;
  }

  template <class Node> static void set_child(Node& n, int k, const Bounds& b, uint32_t code) {
    for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = b.lo[a], n.bounds[2 * a + 1][k] = b.hi[a];
    n.child[k] = code;
  }

  // Places the wide node for binary interior node b at `depth` in layout l, depth first (its
  // kids, as its plan opens them, and their codes); returns its index there. With `defer`,
  // a kid that would be placed at kSplitDepth is listed there instead, as kSubBit | its place
  // in the list.
  uint32_t place(Layout& l, uint32_t b, std::size_t depth, std::vector<uint32_t>* defer) const {
    l.max_depth = std::max(l.max_depth, depth);
    uint32_t kids[kWidth];
    int n = 0;
    // Binary node m's subtree as at most j kids, in the binary tree's left-to-right order.
    const auto open = [&](const auto& self, uint32_t m, int j) -> void {
      const int k = collapse_[m].split[j - 1];
      if (k == 0) {
        kids[n++] = m;
        return;
      }
      self(self, nodes_[m].left, k);
      self(self, nodes_[m].right, j - k);
    };
    open(open, nodes_[b].left, collapse_[b].wide);
    open(open, nodes_[b].right, kWidth - collapse_[b].wide);
    const uint32_t index = uint32_t(l.wide.size());
    l.wide.push_back({b, uint32_t(n), {}, {}});
    std::copy(kids, kids + n, l.wide[index].kid);
    for (int k = 0; k < n; ++k) {
      uint32_t code;
      if (nodes_[kids[k]].count > 0) {
        code = kLeafBit | uint32_t(l.leaf.size());
        l.leaf.push_back(kids[k]);
      } else if (defer && depth + 1 == kSplitDepth) {
        code = kSubBit | uint32_t(defer->size());
        defer->push_back(kids[k]);
      } else {
        code = place(l, kids[k], depth + 1, defer);
      }
      l.wide[index].code[k] = code;
    }
    return index;
  }

  // Numbers top node k and, depth first, everything below it: its leaf blocks in turn, the
  // top nodes below it, and each subtree layout as one run. The top's codes become final.
  static void assemble(Layout& top, std::vector<Layout>& sub, uint32_t k, uint32_t& nodes, uint32_t& leaves,
                       std::vector<uint32_t>& top_index, std::vector<uint32_t>& top_leaf) {
    top_index[k] = nodes++;
    for (uint32_t j = 0; j < top.wide[k].n; ++j) {
      uint32_t& code = top.wide[k].code[j];
      if (code & kLeafBit) {
        top_leaf[code & ~kLeafBit] = leaves;
        code = kLeafBit | leaves++;
      } else if (code & kSubBit) {
        Layout& l = sub[code & ~kSubBit];
        l.node_base = nodes, l.leaf_base = leaves;
        nodes += uint32_t(l.wide.size()), leaves += uint32_t(l.leaf.size());
        code = l.node_base;
      } else {
        assemble(top, sub, code, nodes, leaves, top_index, top_leaf);
        code = top_index[code];
      }
    }
  }
};

// Packs up to four triangles (their corners, in leaf order) into a block; unused lanes get
// NaN corners, which no ray hits.
struct MeshLeaf {
  const MeshData& mesh;
  void operator()(BvhLeaf4& leaf, const uint32_t* tris, uint32_t count) const {
    const float nan = __builtin_nanf("");
    for (int k = 0; k < int(kMeshLeafTriangles); ++k) {
      if (uint32_t(k) < count) {
        const uint32_t t = tris[k];
        for (int c = 0; c < 3; ++c) {
          const uint32_t v = mesh.indices[3 * std::size_t(t) + c];
          leaf.corner[3 * c][k] = mesh.x[v], leaf.corner[3 * c + 1][k] = mesh.y[v], leaf.corner[3 * c + 2][k] = mesh.z[v];
        }
        leaf.triangle[k] = t;
      } else {
        for (auto& row : leaf.corner) row[k] = nan;
        leaf.triangle[k] = kNoTriangle;
      }
    }
    for (uint32_t& u : leaf.unused) u = 0;
  }
};

void box_leaf(BvhItems& leaf, const uint32_t* items, uint32_t count) {
  for (uint32_t k = 0; k < kBoxBvhLeafItems; ++k) leaf.item[k] = k < count ? items[k] : kNoItem;
}

}  // namespace

BvhNode8 empty_node8() { return empty_node<BvhNode8>(); }

// Eight running sums, each over every eighth area, then one division: a refit pays this
// for the whole tree every frame, and one sum of quotients was a chain of dependent
// additions (R1M with 10^4 single-model leaves: most of a frame that moved a thousandth).
double sah_cost(const double* node_area, std::size_t nodes, const double* leaf_area, std::size_t leaves) {
  if (nodes == 0) return 0.0;
  const double root = std::max(node_area[0], 1e-300);
  double lane[8] = {};
  const auto add = [&lane](const double* a, std::size_t n) {
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8)
      for (int k = 0; k < 8; ++k) lane[k] += a[i + std::size_t(k)];
    for (int k = 0; i < n; ++i, ++k) lane[k] += a[i];
  };
  add(node_area + 1, nodes - 1);
  add(leaf_area, leaves);
  const double sum = ((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]));
  return 1.0 + sum / root;  // the root is always tested (1, also for a flat root)
}
void set_child_orders(BvhNode8& node) { set_orders(node); }
bool child_orders_hold(const BvhNode8& node) { return orders_hold(node); }

Bvh8 build_bvh8(const MeshData& mesh) {
  const std::size_t n = mesh.triangle_count();
  DefaultInitVector<Bounds> prims(n);
  parallel_for(n, kChunkPrims, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Box box;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.indices[3 * i + k];
        box.grow(F4{mesh.x[v], mesh.y[v], mesh.z[v], 0.0f});
      }
      prims[i] = box;
    }
  });
  return Builder(std::move(prims), kMeshLeafTriangles).run<Bvh8>(MeshLeaf{mesh});
}

BoxBvh8 build_box_bvh8(const BvhBox* boxes, std::size_t count) {
  if (count == 0) {
    BoxBvh8 out;
    out.nodes.push_back(empty_node<BvhNode8>());
    out.bounds = AABB{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    out.stats.nodes = 1;
    out.stats.bytes = sizeof(BvhNode8);
    return out;
  }
  DefaultInitVector<Bounds> prims(count);
  parallel_for(count, kChunkPrims, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Box box;
      box.grow(f4(boxes[i].lo)), box.grow(f4(boxes[i].hi));
      prims[i] = box;
    }
  });
  return Builder(std::move(prims), kBoxBvhLeafItems).run<BoxBvh8>(box_leaf);
}

}  // namespace gyro::detail
