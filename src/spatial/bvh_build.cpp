// BVH construction: a binary tree by binned SAH (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007) over the triangles' bounding-box centroids, then
// collapsed into 8-wide nodes by repeatedly opening the child with the largest surface area
// (the usual BVH2-to-BVHn collapse), with triangles (or a scene's items) packed into 4-wide
// leaf blocks.
//
// Determinism: every decision is a function of float values and indices only (ties go to
// the lower axis, the lower bin, the earlier child); partitions are stable and the median
// fallback sorts by (centroid, index). The same mesh always gives the same bytes.
//
// Parallel (core/parallel's fixed chunks, so any thread count gives the same bytes): the
// binary tree's top is built on the calling thread, its nodes' boxes and bins gathered in
// chunks in parallel (per-chunk bins merged: min, max and counts, exact in any order); the
// subtrees below kTaskPrims primitives are built in parallel, each into its own node list
// over its own range of the primitive order, and linked in afterwards. A subtree's shape is
// a function of its range alone, and the wide tree is emitted from the binary tree's shape,
// not from where its nodes were stored.
//
// The SAH cost counts 4-wide leaf blocks, not triangles (a block of 1 to 4 triangles costs
// one lane test), so a node of at most 4 triangles is always a leaf.
//
// One builder serves two outputs: a mesh's BVH (leaves hold the triangles' corners) and a
// BVH over arbitrary boxes (leaves hold item indices; the scene's top level). Only the
// primitive boxes and the leaf writer differ, so both get the same tree for the same boxes.
#include "spatial/bvh.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <array>

namespace gyro::detail {
namespace {

constexpr int kBins = 32;
constexpr uint32_t kLeafSize = 4;
// Subtrees of at most kTaskPrims primitives are built as parallel tasks (R2's 522k
// triangles make 182); nodes of at least two chunks gather their boxes and bins in parallel
// chunks of kChunkPrims (16384 measured no different on R2).
constexpr uint32_t kTaskPrims = 4096;
constexpr uint32_t kChunkPrims = 4096;
constexpr float kInf = __builtin_inff();

// x, y, z and a fourth lane that no decision reads: one vector operation grows all three
// axes (the scalar min and max were a third of R2's build; GCC's and Clang's vector
// extensions, so every target gets its own 4-wide instructions, or four floats).
using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));

inline F4 f4(const float p[3]) { return F4{p[0], p[1], p[2], 0.0f}; }

struct Box {
  F4 lo = {kInf, kInf, kInf, kInf};
  F4 hi = {-kInf, -kInf, -kInf, -kInf};
  // std::min(lo, b.lo) and std::max(hi, b.hi) lane by lane (the same selects, so the same
  // bits, signed zeros included).
  void grow(const Box& b) {
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

struct BinaryNode {
  Box box;
  uint32_t left = 0, right = 0;  // interior
  uint32_t first = 0, count = 0;  // leaf when count > 0
};

// A node's bins along the three axes.
struct Bins {
  Box box[3][kBins];
  uint32_t count[3][kBins] = {};
  void merge(const Bins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < kBins; ++b) box[a][b].grow(o.box[a][b]), count[a][b] += o.count[a][b];
  }
};

// A subtree left for the parallel phase: its range, its depth, and the node standing for it.
struct Task {
  uint32_t first, count, node;
  std::size_t depth;
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
// (lo + hi in binary64, exact for floats, so the order is a function of the bounds alone).
inline void set_orders(BvhNode8& n) {
  for (int o = 0; o < 8; ++o) {
    double key[8];
    int slot[8];
    for (int k = 0; k < 8; ++k) {
      key[k] = kInf;
      if (n.child[k] != kEmptyChild) {
        key[k] = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double c = double(n.bounds[2 * a][k]) + double(n.bounds[2 * a + 1][k]);
          key[k] += o >> a & 1 ? -c : c;
        }
      }
      int j = k;
      while (j > 0 && key[slot[j - 1]] > key[k]) slot[j] = slot[j - 1], --j;
      slot[j] = k;
    }
    uint32_t packed = 0;
    for (int j = 0; j < 8; ++j) packed |= uint32_t(slot[j]) << (4 * j);
    n.order[o] = packed;
  }
}

double blocks(uint32_t n) { return double((n + kLeafSize - 1) / kLeafSize); }

class Builder {
 public:
  // prim[i] is primitive i's box; the leaf writer receives primitive indices.
  explicit Builder(std::vector<Box> prims) : prim_(std::move(prims)) {
    const std::size_t n = prim_.size();
    centroid_.resize(n);
    order_.resize(n);
    scratch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Box& b = prim_[i];
      centroid_[i] = (b.lo + b.hi) * 0.5f;
      order_[i] = uint32_t(i);
    }
  }

  // Out is Bvh8 or BoxBvh8; leaf(block, items, count) fills a leaf block with binary leaf
  // items[0, count).
  template <class Out, class Leaf> Out run(Leaf&& leaf) {
    std::vector<Task> tasks;
    const uint32_t root = build(nodes_, 0, uint32_t(order_.size()), 0, &tasks);
    build_tasks(tasks);
    Out out;
    out.nodes.reserve(nodes_.size() / 2 + 1);
    out.leaves.reserve(order_.size() / 2 + 1);
    const Box& rb = nodes_[root].box;
    out.bounds = aabb_from_min_max({rb.lo[0], rb.lo[1], rb.lo[2]}, {rb.hi[0], rb.hi[1], rb.hi[2]});
    root_area_ = std::max(rb.half_area(), 1e-300);
    // The root is always a wide node, even over a single leaf, so traversal has one shape.
    std::size_t depth = 0;
    if (nodes_[root].count > 0) {
      out.nodes.push_back(empty_node<typename decltype(out.nodes)::value_type>());
      set_child(out.nodes[0], 0, nodes_[root].box, emit_leaf(out, nodes_[root]));
      sah_ += 1.0;
      depth = 1;
    } else {
      emit(out, root, 1, depth);
    }
    // The emission fixed every node's and leaf block's place; what each holds is a function
    // of its own inputs, filled in parallel (they were a sixth of R2's build, on one thread).
    parallel_for(out.leaves.size(), 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) leaf(out.leaves[k], order_.data() + leaf_range_[k][0], leaf_range_[k][1]);
    });
    parallel_for(out.nodes.size(), 1024, [&](std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) set_orders(out.nodes[k]);
    });
    out.stats.nodes = out.nodes.size();
    out.stats.leaves = out.leaves.size();
    out.stats.max_depth = depth;
    out.stats.bytes = out.nodes.size() * sizeof(out.nodes[0]) + out.leaves.size() * sizeof(out.leaves[0]);
    out.stats.sah_cost = sah_;
    return out;
  }

 private:
  std::vector<Box> prim_;
  std::vector<F4> centroid_;
  std::vector<uint32_t> order_;
  std::vector<std::array<uint32_t, 2>> leaf_range_;  // leaf block k: its first item in order_, its count
  std::vector<uint32_t> scratch_;  // sah_split's right side, before it is copied back
  std::vector<BinaryNode> nodes_;
  double root_area_ = 1.0;
  double sah_ = 0.0;

  // Runs f(begin, end) over [first, first + count) in chunks of kChunkPrims, in parallel
  // where there are several, each with its own accumulator (acc[k] for chunk k).
  template <class Acc, class F> void chunked(uint32_t first, uint32_t count, std::vector<Acc>& acc, F&& f) {
    const std::size_t chunks = (std::size_t(count) + kChunkPrims - 1) / kChunkPrims;
    acc.assign(chunks, Acc{});
    const auto body = [&](std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) {
        const uint32_t lo = first + uint32_t(k) * kChunkPrims;
        f(acc[k], lo, std::min(first + count, lo + kChunkPrims));
      }
    };
    if (chunks > 1) parallel_for(chunks, 1, body);
    else body(0, chunks);
  }

  void node_boxes(uint32_t first, uint32_t end, Box& box, Box& cbox) const {
    for (uint32_t i = first; i < end; ++i) {
      box.grow(prim_[order_[i]]);
      cbox.grow(centroid_[order_[i]]);
    }
  }

  // Builds the subtree over order_[first, first + count) into `nodes`; returns its root.
  // With `defer`, subtrees of at most kTaskPrims primitives are not built but listed there,
  // each standing as a node of its box with no children yet.
  uint32_t build(std::vector<BinaryNode>& nodes, uint32_t first, uint32_t count, std::size_t depth,
                 std::vector<Task>* defer) {
    Box box, cbox;
    if (count >= 2 * kChunkPrims) {
      std::vector<std::array<Box, 2>> parts;
      chunked(first, count, parts, [&](std::array<Box, 2>& acc, uint32_t b, uint32_t e) { node_boxes(b, e, acc[0], acc[1]); });
      for (const auto& part : parts) box.grow(part[0]), cbox.grow(part[1]);
    } else {
      node_boxes(first, first + count, box, cbox);
    }
    const uint32_t index = uint32_t(nodes.size());
    nodes.push_back({box, 0, 0, 0, 0});
    if (count <= kLeafSize) {
      nodes[index].first = first, nodes[index].count = count;
      return index;
    }
    if (defer && count <= kTaskPrims) {
      defer->push_back({first, count, index, depth});
      return index;
    }
    uint32_t left_count = 0;
    // Past this depth only median splits, which end within log2(count) <= 31 more levels.
    if (depth + 33 < kBvhMaxDepth) left_count = sah_split(first, count, cbox);
    if (left_count == 0 || left_count == count) left_count = median_split(first, count, cbox);
    const uint32_t l = build(nodes, first, left_count, depth + 1, defer);
    const uint32_t r = build(nodes, first + left_count, count - left_count, depth + 1, defer);
    nodes[index].left = l, nodes[index].right = r;
    return index;
  }

  // Builds the deferred subtrees in parallel, then appends each one's nodes (its root in
  // place of the node standing for it, its other indices moved past the nodes before it).
  void build_tasks(const std::vector<Task>& tasks) {
    std::vector<std::vector<BinaryNode>> sub(tasks.size());
    parallel_for(tasks.size(), 1, [&](std::size_t b, std::size_t e) {
      for (std::size_t t = b; t < e; ++t) build(sub[t], tasks[t].first, tasks[t].count, tasks[t].depth, nullptr);
    });
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      const uint32_t base = uint32_t(nodes_.size()) - 1;  // local index 1 lands at nodes_.size()
      const auto moved = [&](BinaryNode n) {
        if (n.count == 0) n.left += base, n.right += base;
        return n;
      };
      nodes_[tasks[t].node] = moved(sub[t][0]);
      for (std::size_t k = 1; k < sub[t].size(); ++k) nodes_.push_back(moved(sub[t][k]));
    }
  }

  // Clamped as a float before the conversion: a float past INT_MAX (or NaN) has no int.
  int bin_of(float c, float lo, float scale) const {
    const float f = (c - lo) * scale;
    if (!(f >= 0.0f)) return 0;
    return f < float(kBins) ? int(f) : kBins - 1;
  }

  // Binned SAH: the best plane between bins on any axis; returns the left count (0 if none).
  // One pass bins every primitive on all three axes (its box and centroid are read once), and
  // the partition is stable through a scratch buffer, with no allocation.
  uint32_t sah_split(uint32_t first, uint32_t count, const Box& cbox) {
    float lo[3], scale[3];
    for (int axis = 0; axis < 3; ++axis) {
      const float ext = cbox.hi[axis] - cbox.lo[axis];
      lo[axis] = cbox.lo[axis];
      scale[axis] = ext > 0.0f ? float(kBins) / ext : 0.0f;  // 0: a flat axis, all in bin 0
      // A subnormal extent overflows the scale: as good as flat, left to the median split.
      if (!(scale[axis] < kInf)) scale[axis] = 0.0f;
    }
    // bin_of() on the three axes at once: the same operations and the same clamps.
    const F4 lo4 = f4(lo), scale4 = f4(scale);
    const auto bin_one = [&](Bins& bins, uint32_t p) {
      F4 f = (centroid_[p] - lo4) * scale4;
      f = f >= 0.0f ? f : F4{};  // NaN too
      f = f < float(kBins) ? f : F4{} + float(kBins - 1);
      const I4 b = __builtin_convertvector(f, I4);
      for (int axis = 0; axis < 3; ++axis) {
        bins.box[axis][b[axis]].grow(prim_[p]);
        ++bins.count[axis][b[axis]];
      }
    };
    const auto bin = [&](Bins& bins, uint32_t b0, uint32_t e0) {
      for (uint32_t i = b0; i < e0; ++i) bin_one(bins, order_[i]);
    };
    Bins bins;
    if (count >= 2 * kChunkPrims) {
      std::vector<Bins> parts;
      chunked(first, count, parts, bin);
      for (const Bins& part : parts) bins.merge(part);
    } else {
      bin(bins, first, first + count);
    }
    const auto& bin_box = bins.box;
    const auto& bin_count = bins.count;
    double best_cost = kInf;
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (scale[axis] == 0.0f) continue;
      // Right-to-left sweep: the cost of everything right of each plane. An empty bin
      // changes neither the box nor the count, so its plane costs what the plane before it
      // costs, to the bit: it is not evaluated (most bins of the many small nodes are empty;
      // the sweeps were a third of the build).
      double right_cost[kBins];
      Box acc;
      uint32_t n = 0;
      double last = 0.0;  // an empty right side: area 0 times 0 blocks
      for (int b = kBins - 1; b > 0; --b) {
        if (bin_count[axis][b] != 0) {
          acc.grow(bin_box[axis][b]);
          n += bin_count[axis][b];
          last = acc.half_area() * blocks(n);
        }
        right_cost[b] = last;
      }
      acc = Box();
      n = 0;
      // A plane after an empty bin repeats the plane before it, which the strict < below
      // already preferred (or skipped, with the same n).
      for (int b = 0; b < kBins - 1; ++b) {
        if (bin_count[axis][b] == 0) continue;
        acc.grow(bin_box[axis][b]);
        n += bin_count[axis][b];
        if (n == count) break;
        const double cost = acc.half_area() * blocks(n) + right_cost[b + 1];
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
      }
    }
    if (best_axis < 0) return 0;
    uint32_t* const range = order_.data() + first;
    uint32_t* const spill = scratch_.data() + first;  // this range's own: subtrees run in parallel
    uint32_t left = 0, right = 0;
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t p = range[i];
      if (bin_of(centroid_[p][best_axis], lo[best_axis], scale[best_axis]) <= best_bin) range[left++] = p;
      else spill[right++] = p;
    }
    std::copy(spill, spill + right, range + left);
    return left;
  }

  // Half by count along the widest centroid axis, ordered by (centroid, index).
  uint32_t median_split(uint32_t first, uint32_t count, const Box& cbox) {
    int axis = 0;
    float ext = -1.0f;
    for (int a = 0; a < 3; ++a) {
      const float e = cbox.hi[a] - cbox.lo[a];
      if (e > ext) ext = e, axis = a;
    }
    std::sort(order_.begin() + first, order_.begin() + first + count, [&](uint32_t p, uint32_t q) {
      const float cp = centroid_[p][axis], cq = centroid_[q][axis];
      return cp < cq || (cp == cq && p < q);
    });
    return count / 2;
  }

  template <class Node> static void set_child(Node& n, int k, const Box& b, uint32_t code) {
    for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = b.lo[a], n.bounds[2 * a + 1][k] = b.hi[a];
    n.child[k] = code;
  }

  // Places binary leaf b's block (filled later, in run()); returns its code.
  template <class Out> uint32_t emit_leaf(Out& out, const BinaryNode& b) {
    sah_ += b.box.half_area() / root_area_;
    out.leaves.emplace_back();
    leaf_range_.push_back({b.first, b.count});
    return kLeafBit | uint32_t(out.leaves.size() - 1);
  }

  // Emits the wide node for binary interior node b; returns its index.
  template <class Out> uint32_t emit(Out& out, uint32_t b, std::size_t depth, std::size_t& max_depth) {
    using Node = typename decltype(out.nodes)::value_type;
    constexpr int kWidth = width_of<Node>;
    max_depth = std::max(max_depth, depth);
    uint32_t kids[kWidth] = {nodes_[b].left, nodes_[b].right};
    // Each kid's area, or -1 for a leaf (never opened).
    const auto area_of = [&](uint32_t kid) { return nodes_[kid].count == 0 ? nodes_[kid].box.half_area() : -1.0; };
    double areas[kWidth] = {area_of(kids[0]), area_of(kids[1])};
    int n = 2;
    while (n < kWidth) {
      int open = -1;
      double area = -1.0;
      for (int k = 0; k < n; ++k)
        if (areas[k] > area) area = areas[k], open = k;
      if (open < 0) break;
      const BinaryNode& c = nodes_[kids[open]];
      for (int k = n; k > open + 1; --k) kids[k] = kids[k - 1], areas[k] = areas[k - 1];
      kids[open + 1] = c.right, areas[open + 1] = area_of(c.right);
      kids[open] = c.left, areas[open] = area_of(c.left);
      ++n;
    }
    const uint32_t index = uint32_t(out.nodes.size());
    out.nodes.push_back(empty_node<Node>());
    sah_ += nodes_[b].box.half_area() / root_area_;
    for (int k = 0; k < n; ++k) {
      const BinaryNode& c = nodes_[kids[k]];
      const uint32_t code = c.count > 0 ? emit_leaf(out, c) : emit(out, kids[k], depth + 1, max_depth);
      set_child(out.nodes[index], k, c.box, code);
    }
    return index;
  }
};

// Packs up to four triangles (their corners, in leaf order) into a block; unused lanes get
// NaN corners, which no ray hits.
struct MeshLeaf {
  const MeshData& mesh;
  void operator()(BvhLeaf4& leaf, const uint32_t* tris, uint32_t count) const {
    const float nan = __builtin_nanf("");
    for (int k = 0; k < 4; ++k) {
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
  }
};

void box_leaf(BvhItems4& leaf, const uint32_t* items, uint32_t count) {
  for (uint32_t k = 0; k < 4; ++k) leaf.item[k] = k < count ? items[k] : kNoItem;
}

}  // namespace

Bvh8 build_bvh8(const MeshData& mesh) {
  const std::size_t n = mesh.triangle_count();
  std::vector<Box> prims(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * i + k];
      prims[i].grow(F4{mesh.x[v], mesh.y[v], mesh.z[v], 0.0f});
    }
  return Builder(std::move(prims)).run<Bvh8>(MeshLeaf{mesh});
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
  std::vector<Box> prims(count);
  for (std::size_t i = 0; i < count; ++i) {
    prims[i].grow(f4(boxes[i].lo));
    prims[i].grow(f4(boxes[i].hi));
  }
  return Builder(std::move(prims)).run<BoxBvh8>(box_leaf);
}

}  // namespace gyro::detail
