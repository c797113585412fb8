// The BVH's structural invariants: every triangle in exactly one leaf lane, every child box
// containing everything below it, padding lanes and empty slots that no ray can enter, and
// the depth bound the traversal stack relies on.
#include "gyro/runtime.hpp"
#include "spatial/bvh.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace gyro {
namespace {

using testing::SplitMix64;

MeshData random_mesh(std::size_t n, uint64_t seed, bool clustered) {
  SplitMix64 rng(seed);
  MeshData m;
  for (std::size_t t = 0; t < n; ++t) {
    // Clustered: many triangles with the same centroid, which binning cannot split.
    const vec3 c = clustered && t % 3 ? vec3{1.0f, 2.0f, 3.0f} : vec3{float(50 * rng.u()), float(rng.u()), float(50 * rng.u())};
    for (int k = 0; k < 3; ++k) m.add_vertex(c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)});
    m.add_triangle(uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2));
  }
  return m;
}

struct Box {
  float lo[3], hi[3];
};

// Walks the tree; checks containment and counts triangle occurrences. Returns the depth.
std::size_t check(const detail::Bvh8& bvh, const MeshData& m, uint32_t code, const Box& parent, std::vector<int>& seen) {
  if (code & detail::kLeafBit) {
    const detail::BvhLeaf4& leaf = bvh.leaves[code & ~detail::kLeafBit];
    for (int k = 0; k < 4; ++k) {
      if (leaf.triangle[k] == detail::kNoTriangle) {
        EXPECT_TRUE(std::isnan(leaf.corner[0][k])) << "padding lane must be NaN";
        continue;
      }
      ++seen[leaf.triangle[k]];
      const Triangle t = m.triangle(leaf.triangle[k]);
      const vec3 p[3] = {t.a, t.b, t.c};
      for (int c = 0; c < 3; ++c) {
        const float xyz[3] = {p[c].x, p[c].y, p[c].z};
        EXPECT_EQ(leaf.corner[3 * c][k], xyz[0]);
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(parent.lo[a] <= xyz[a] && xyz[a] <= parent.hi[a]);
      }
    }
    return 0;
  }
  const detail::BvhNode8& node = bvh.nodes[code];
  std::size_t depth = 0;
  int used = 0;
  for (int k = 0; k < 8; ++k) {
    if (node.child[k] == detail::kEmptyChild) {
      for (int a = 0; a < 3; ++a) EXPECT_TRUE(node.bounds[2 * a][k] == INFINITY && node.bounds[2 * a + 1][k] == -INFINITY);
      continue;
    }
    ++used;
    Box b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = node.bounds[2 * a][k], b.hi[a] = node.bounds[2 * a + 1][k];
      EXPECT_TRUE(parent.lo[a] <= b.lo[a] && b.hi[a] <= parent.hi[a]);
    }
    depth = std::max(depth, check(bvh, m, node.child[k], b, seen));
  }
  EXPECT_GE(used, 1);
  return depth + 1;
}

void check_mesh(const MeshData& m) {
  const detail::Bvh8 bvh = detail::build_bvh8(m);
  std::vector<int> seen(m.triangle_count(), 0);
  const Box all{{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, INFINITY}};
  const std::size_t depth = check(bvh, m, 0, all, seen);
  for (std::size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << "triangle " << t;
  EXPECT_EQ(depth, bvh.stats.max_depth);
  EXPECT_LE(depth, detail::kBvhMaxDepth);
  // Most leaves should be full: the SAH counts blocks of four.
  EXPECT_LE(bvh.leaves.size(), m.triangle_count() / 2 + 1);
  // Deterministic to the byte.
  const detail::Bvh8 again = detail::build_bvh8(m);
  ASSERT_EQ(again.nodes.size(), bvh.nodes.size());
  EXPECT_EQ(std::memcmp(again.nodes.data(), bvh.nodes.data(), bvh.nodes.size() * sizeof(detail::BvhNode8)), 0);
  ASSERT_EQ(again.leaves.size(), bvh.leaves.size());
  // Leaves hold NaN padding (never equal to itself), so compare their bytes.
  EXPECT_EQ(std::memcmp(again.leaves.data(), bvh.leaves.data(), bvh.leaves.size() * sizeof(detail::BvhLeaf4)), 0);
}

TEST(Bvh, EveryTriangleOnceAndBoxesNested) {
  for (std::size_t n : {1u, 3u, 4u, 5u, 16u, 17u, 1000u, 20000u}) check_mesh(random_mesh(n, 100 + n, false));
}

TEST(Bvh, CoincidentCentroidsStillSplitAndStayShallow) {
  const MeshData m = random_mesh(30000, 7, true);
  check_mesh(m);
  EXPECT_LE(detail::build_bvh8(m).stats.max_depth, 40u);
}

// Centroids that differ by a subnormal amount on one axis: kBins / extent overflows to
// infinity there, which once turned into an int bin index far outside the bins (a crash
// the C ABI fuzzer found). That axis now counts as flat; the others still split.
TEST(Bvh, SubnormalCentroidSpreadStillBuilds) {
  SplitMix64 rng(11);
  MeshData m;
  for (uint32_t t = 0; t < 300; ++t) {
    const float x = t % 2 ? 4e-39f : 0.0f;
    for (int k = 0; k < 3; ++k) m.add_vertex({x, float(20 * rng.u()), float(20 * rng.u())});
    m.add_triangle(3 * t, 3 * t + 1, 3 * t + 2);
  }
  check_mesh(m);
  EXPECT_LE(detail::build_bvh8(m).stats.max_depth, 12u);
}

uint64_t fnv(const void* p, std::size_t n, uint64_t h) {
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<const unsigned char*>(p)[i]) * 1099511628211ull;
  return h;
}

// The tree: every node's bounds and children, then the leaves. The nodes' child orders came
// later (derived from the bounds, checked below): they are hashed as the zero bytes their
// field held before, so the pins below still are those of the tree before them.
template <class B> uint64_t tree_hash(const B& b) {
  const uint32_t zeros[8] = {};
  static_assert(sizeof(zeros) == sizeof(b.nodes[0].order));
  uint64_t h = 1469598103934665603ull;
  for (const auto& n : b.nodes) h = fnv(zeros, sizeof(zeros), fnv(n.child, sizeof(n.child), fnv(n.bounds, sizeof(n.bounds), h)));
  return fnv(b.leaves.data(), b.leaves.size() * sizeof(b.leaves[0]), h);
}

template <class B> uint64_t bytes_hash(const B& b) {
  const uint64_t h = fnv(b.nodes.data(), b.nodes.size() * sizeof(b.nodes[0]), 1469598103934665603ull);
  return fnv(b.leaves.data(), b.leaves.size() * sizeof(b.leaves[0]), h);
}

// BvhNode8::order for every octant: a permutation of the slots, the used ones first, front
// to back along the octant's diagonal by their centres (ties in slot order). Returns the
// number of nodes that break it.
template <class B> std::size_t bad_orders(const B& b) {
  std::size_t bad = 0;
  for (const auto& n : b.nodes) {
    bool ok = true;
    for (int o = 0; o < 8; ++o) {
      unsigned seen = 0;
      double last_key = -INFINITY;
      int last_slot = -1;
      bool empties = false;
      for (int j = 0; j < 8; ++j) {
        const int s = int(n.order[o] >> (4 * j) & 15u);
        ok = ok && s < 8 && !(seen >> s & 1u);
        seen |= 1u << (s & 7);
        if (n.child[s & 7] == detail::kEmptyChild) {
          empties = true;
          continue;
        }
        ok = ok && !empties;
        double key = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double c = double(n.bounds[2 * a][s & 7]) + double(n.bounds[2 * a + 1][s & 7]);
          key += o >> a & 1 ? -c : c;
        }
        ok = ok && (key > last_key || (key == last_key && s > last_slot));
        last_key = key, last_slot = s;
      }
    }
    bad += !ok;
  }
  return bad;
}

// 50k boxes of up to 1 m in a 100 m cube.
std::vector<detail::BvhBox> random_boxes() {
  std::vector<detail::BvhBox> boxes(50000);
  SplitMix64 rng(8);
  for (auto& b : boxes)
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = float(100 * rng.u());
      b.hi[a] = b.lo[a] + float(rng.u());
    }
  return boxes;
}

// The slots a tree's nodes use, on average; and the nodes that could take in one of their
// child nodes whole (its slots in place of its own), which a collapse of least cost never
// leaves: the merge drops that child's area from the cost and changes nothing else.
template <class Tree> double mean_fill(const Tree& t, std::size_t& mergeable) {
  const auto used = [&](const detail::BvhNode8& n) {
    int u = 0;
    for (uint32_t c : n.child) u += c != detail::kEmptyChild;
    return u;
  };
  std::size_t total = 0;
  mergeable = 0;
  for (const detail::BvhNode8& n : t.nodes) {
    total += std::size_t(used(n));
    for (int k = 0; k < 8; ++k) {
      const uint32_t c = n.child[k];
      if (c == detail::kEmptyChild || (c & detail::kLeafBit)) continue;
      const detail::BvhNode8& kid = t.nodes[c];
      bool flat = false;  // a child box of no area costs nothing to keep
      for (int a = 0; a < 3; ++a) flat = flat || n.bounds[2 * a][k] == n.bounds[2 * a + 1][k];
      mergeable += !flat && used(n) - 1 + used(kid) <= 8;
    }
  }
  return double(total) / double(t.nodes.size());
}

// The collapse into wide nodes is planned for the least SAH cost (bvh_build.cpp): it fills
// the nodes that the greedy collapse (open the largest child until eight) left half empty
// near the leaves. The trees of SameBytesAtEveryThreadCount below: the mesh's mean fill
// 4.78 -> 6.36 slots (4,692 -> 3,309 nodes), SAH cost 31.21 -> 29.27; the 50k boxes' (one
// to a leaf) 3.62 -> 4.13 (19,098 -> 15,956 nodes), 31.86 -> 31.64. R2's 522k triangles:
// 4.48 -> 6.13 (38,513 -> 26,142 nodes), 15.32 -> 14.82. Fewer bins for small nodes
// (bins_for) then moved the SAH costs: the mesh 29.27 -> 29.50, the boxes 31.644 -> 31.643,
// R2 14.820 -> 14.813.
TEST(Bvh, CollapseFillsTheNodes) {
  const MeshData mesh = random_mesh(70000, 5, false);
  const std::vector<detail::BvhBox> boxes = random_boxes();
  const detail::Bvh8 a = detail::build_bvh8(mesh);
  const detail::BoxBvh8 c = detail::build_box_bvh8(boxes.data(), boxes.size());
  std::size_t mergeable_a = 0, mergeable_c = 0;
  EXPECT_GT(mean_fill(a, mergeable_a), 6.0);
  EXPECT_GT(mean_fill(c, mergeable_c), 4.0);
  EXPECT_EQ(mergeable_a, 0u);
  EXPECT_EQ(mergeable_c, 0u);
  EXPECT_LT(a.stats.sah_cost, 29.6);
  EXPECT_LT(c.stats.sah_cost, 31.7);
}

// The build runs its top level by level in parallel chunks, its subtrees as parallel tasks
// and its layout as parallel runs: the bytes must not depend on the thread count. 70k
// triangles take every path (the top above 4k primitives, the layout's subtrees below wide
// depth 4); the hashes pin the tree itself too (those of the least-cost collapse); the
// whole bytes (with the child orders) must match across thread counts, and
// the orders must be what BvhNode8 says.
// The whole bytes of SameBytesAtEveryThreadCount's three trees.
constexpr uint64_t kWholeBytes[3] = {18196415548053710919ull, 3277331604974551807ull, 1123117721935374864ull};

TEST(Bvh, SameBytesAtEveryThreadCount) {
  const MeshData mesh = random_mesh(70000, 5, false), clustered = random_mesh(40000, 6, true);
  const std::vector<detail::BvhBox> boxes = random_boxes();
  const uint32_t saved = thread_count();
  uint64_t whole[3] = {};
  for (uint32_t threads : {1u, 2u, 3u, 8u}) {
    set_thread_count(threads);
    const detail::Bvh8 a = detail::build_bvh8(mesh), b = detail::build_bvh8(clustered);
    const detail::BoxBvh8 c = detail::build_box_bvh8(boxes.data(), boxes.size());
    EXPECT_EQ(tree_hash(a), 9813848147624824449ull) << threads << " threads";
    EXPECT_EQ(tree_hash(b), 15166388934927890453ull) << threads << " threads";
    EXPECT_EQ(tree_hash(c), 15192136064466148556ull) << threads << " threads";
    const uint64_t h[3] = {bytes_hash(a), bytes_hash(b), bytes_hash(c)};
    for (int k = 0; k < 3; ++k) {
      if (threads == 1u) whole[k] = h[k];
      EXPECT_EQ(h[k], whole[k]) << "tree " << k << ", " << threads << " threads";
    }
    EXPECT_EQ(bad_orders(a) + bad_orders(b) + bad_orders(c), 0u) << threads << " threads";
    EXPECT_GT(a.stats.max_depth, 4u);  // deep enough for the layout's subtree runs
    EXPECT_GT(c.stats.max_depth, 4u);
  }
  // Every byte is written (the nodes and leaf blocks are not zeroed before the fill): the
  // whole bytes are pinned too.
  EXPECT_EQ(whole[0], kWholeBytes[0]);
  EXPECT_EQ(whole[1], kWholeBytes[1]);
  EXPECT_EQ(whole[2], kWholeBytes[2]);
  set_thread_count(saved);
}

// The build writes its nodes' octant orders at the SIMD level (bvh_orders.hpp): every level
// gives the same bytes.
TEST(Bvh, SameBytesAtEverySimdLevel) {
  const MeshData mesh = random_mesh(70000, 5, false), clustered = random_mesh(40000, 6, true);
  const std::vector<detail::BvhBox> boxes = random_boxes();
  for (uint32_t v = 1; v <= 5; ++v) {
    if (!simd_level_available(SimdLevel(v))) continue;
    ASSERT_EQ(set_simd_level(SimdLevel(v)), Status::ok);
    const detail::Bvh8 a = detail::build_bvh8(mesh), b = detail::build_bvh8(clustered);
    const detail::BoxBvh8 c = detail::build_box_bvh8(boxes.data(), boxes.size());
    EXPECT_EQ(bytes_hash(a), kWholeBytes[0]) << simd_level_name(SimdLevel(v));
    EXPECT_EQ(bytes_hash(b), kWholeBytes[1]) << simd_level_name(SimdLevel(v));
    EXPECT_EQ(bytes_hash(c), kWholeBytes[2]) << simd_level_name(SimdLevel(v));
  }
  set_simd_level(SimdLevel::automatic);
}

}  // namespace
}  // namespace gyro
