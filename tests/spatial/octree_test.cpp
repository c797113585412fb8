// The octree against its definition and against brute force: every item sits in exactly
// the leaves whose cell its box overlaps, content bounds are the unions of what lies below,
// the tree does not depend on the input order, and AABB / sphere / frustum queries return
// exactly the ids that gyro's own tests accept when looping over every item.
#include "gyro/camera.hpp"
#include "gyro/frustum.hpp"
#include "gyro/octree.hpp"
#include "gyro/overlap.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

namespace gyro {
namespace {

using testing::SplitMix64;

float uni(SplitMix64& rng, double lo, double hi) { return float(lo + (hi - lo) * rng.u()); }

// Boxes of mixed sizes in a 100-unit cube: many small, some large, some flat or points.
std::vector<AABB> random_boxes(std::size_t n, SplitMix64& rng) {
  std::vector<AABB> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const vec3 c{uni(rng, -50, 50), uni(rng, -50, 50), uni(rng, -50, 50)};
    const float s = i % 40 == 0 ? 20.0f : 2.0f;
    vec3 e{uni(rng, 0, s), uni(rng, 0, s), uni(rng, 0, s)};
    if (i % 17 == 0) e.y = 0.0f;
    if (i % 29 == 0) e = {0.0f, 0.0f, 0.0f};
    out[i] = {c, e};
  }
  return out;
}

std::vector<uint32_t> random_ids(std::size_t n, SplitMix64& rng) {
  std::vector<uint32_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = uint32_t(3 * i + 7);
  for (std::size_t i = n; i > 1; --i) std::swap(ids[i - 1], ids[rng.next() % i]);
  return ids;
}

bool closed_overlap(const AABB& b, const float lo[3], const float hi[3]) {
  const vec3 blo = aabb_min(b), bhi = aabb_max(b);
  const float l[3] = {blo.x, blo.y, blo.z}, h[3] = {bhi.x, bhi.y, bhi.z};
  for (int a = 0; a < 3; ++a)
    if (!(l[a] <= hi[a] && lo[a] <= h[a])) return false;
  return true;
}

Frustum random_frustum(SplitMix64& rng) {
  Camera cam = perspective_camera(uni(rng, 0.4, 1.6), uni(rng, 0.5, 2.0), uni(rng, 0.1, 2.0), uni(rng, 30, 150));
  const vec3 eye{uni(rng, -70, 70), uni(rng, -70, 70), uni(rng, -70, 70)};
  const vec3 target{uni(rng, -30, 30), uni(rng, -30, 30), uni(rng, -30, 30)};
  set_look_at(cam, eye, target, {0.0f, 1.0f, 0.0f});
  return frustum(cam);
}

template <class Test> std::vector<uint32_t> brute(const std::vector<AABB>& boxes, const std::vector<uint32_t>& ids, Test&& test) {
  std::vector<uint32_t> out;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (test(boxes[i])) out.push_back(ids[i]);
  std::sort(out.begin(), out.end());
  return out;
}

void expect_invariants(const Octree& tree, const OctreeDef& def) {
  const auto& nodes = tree.nodes();
  const auto& items = tree.items();
  const auto& boxes = tree.boxes();
  ASSERT_FALSE(nodes.empty());
  ASSERT_TRUE(std::is_sorted(tree.ids().begin(), tree.ids().end()));
  std::size_t leaves = 0, refs = 0;
  // Content bounds of every node, recomputed bottom-up (children always follow parents).
  std::vector<std::array<float, 6>> content(nodes.size());
  for (std::size_t k = nodes.size(); k-- > 0;) {
    const OctreeNode& n = nodes[k];
    auto& c = content[k];
    for (int a = 0; a < 3; ++a) c[a] = __builtin_inff(), c[3 + a] = -__builtin_inff();
    if (n.first_child == kOctreeLeaf) {
      ++leaves;
      refs += n.item_count;
      if (n.item_count > uint32_t(def.leaf_capacity) && n.depth < uint32_t(def.max_depth)) {
        // Kept whole only when no octant would have fewer items.
        for (int j = 0; j < 8; ++j) {
          float lo[3], hi[3];
          for (int a = 0; a < 3; ++a) {
            const float mid = n.cell_lo[a] * 0.5f + n.cell_hi[a] * 0.5f;
            lo[a] = (j >> a) & 1 ? mid : n.cell_lo[a];
            hi[a] = (j >> a) & 1 ? n.cell_hi[a] : mid;
          }
          uint32_t in = 0;
          for (uint32_t r = n.first_item; r < n.first_item + n.item_count; ++r) in += closed_overlap(boxes[items[r]], lo, hi);
          EXPECT_EQ(in, n.item_count) << "leaf " << k << " could have split";
        }
      }
      // Exactly the items whose box overlaps the cell (touching included), ascending.
      std::vector<uint32_t> expect;
      for (uint32_t i = 0; i < boxes.size(); ++i)
        if (closed_overlap(boxes[i], n.cell_lo, n.cell_hi)) expect.push_back(i);
      const std::vector<uint32_t> got(items.begin() + n.first_item, items.begin() + n.first_item + n.item_count);
      // The root leaf of a non-empty tree holds everything; other leaves exactly their cell's items.
      EXPECT_EQ(got, expect) << "leaf " << k;
      for (uint32_t i : got) {
        const vec3 lo = aabb_min(boxes[i]), hi = aabb_max(boxes[i]);
        const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
        for (int a = 0; a < 3; ++a) c[a] = std::min(c[a], l[a]), c[3 + a] = std::max(c[3 + a], h[a]);
      }
    } else {
      EXPECT_LT(n.depth, uint32_t(def.max_depth));
      for (uint32_t j = 0; j < 8; ++j) {
        const OctreeNode& ch = nodes[n.first_child + j];
        EXPECT_EQ(ch.depth, n.depth + 1);
        for (int a = 0; a < 3; ++a) {
          const float mid = n.cell_lo[a] * 0.5f + n.cell_hi[a] * 0.5f;
          const bool upper = (j >> a) & 1;
          EXPECT_EQ(ch.cell_lo[a], upper ? mid : n.cell_lo[a]);
          EXPECT_EQ(ch.cell_hi[a], upper ? n.cell_hi[a] : mid);
          c[a] = std::min(c[a], content[n.first_child + j][a]);
          c[3 + a] = std::max(c[3 + a], content[n.first_child + j][3 + a]);
        }
      }
    }
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(std::bit_cast<uint32_t>(n.lo[a]), std::bit_cast<uint32_t>(c[a])) << "node " << k;
      EXPECT_EQ(std::bit_cast<uint32_t>(n.hi[a]), std::bit_cast<uint32_t>(c[3 + a])) << "node " << k;
    }
  }
  const OctreeStats s = tree.stats();
  EXPECT_EQ(s.nodes, nodes.size());
  EXPECT_EQ(s.leaves, leaves);
  EXPECT_EQ(s.references, refs);
  EXPECT_EQ(s.items, boxes.size());
  EXPECT_LE(s.max_depth, std::size_t(def.max_depth));
}

TEST(Octree, LeavesHoldExactlyTheItemsOverlappingTheirCells) {
  SplitMix64 rng(11);
  const auto boxes = random_boxes(700, rng);
  const auto ids = random_ids(boxes.size(), rng);
  for (const OctreeDef def : {OctreeDef{}, OctreeDef{3, 1}, OctreeDef{0, 8}, OctreeDef{8, 4}}) {
    Octree tree;
    ASSERT_EQ(tree.build(boxes.data(), ids.data(), boxes.size(), def), Status::ok);
    expect_invariants(tree, def);
    if (def.max_depth > 0) {
      EXPECT_GT(tree.stats().leaves, 8u);
    }
    EXPECT_GE(tree.stats().references, boxes.size());
  }
}

TEST(Octree, TreeDependsOnTheSetNotTheOrder) {
  SplitMix64 rng(12);
  auto boxes = random_boxes(300, rng);
  auto ids = random_ids(boxes.size(), rng);
  Octree a, b;
  ASSERT_EQ(a.build(boxes.data(), ids.data(), boxes.size()), Status::ok);
  for (std::size_t i = boxes.size(); i > 1; --i) {
    const std::size_t j = rng.next() % i;
    std::swap(boxes[i - 1], boxes[j]), std::swap(ids[i - 1], ids[j]);
  }
  ASSERT_EQ(b.build(boxes.data(), ids.data(), boxes.size()), Status::ok);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  EXPECT_EQ(std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size() * sizeof(OctreeNode)), 0);
  EXPECT_EQ(a.items(), b.items());
  EXPECT_EQ(a.ids(), b.ids());
}

TEST(Octree, QueriesEqualBruteForce) {
  SplitMix64 rng(13);
  const auto boxes = random_boxes(800, rng);
  const auto ids = random_ids(boxes.size(), rng);
  for (const OctreeDef def : {OctreeDef{}, OctreeDef{4, 2}}) {
    Octree tree;
    ASSERT_EQ(tree.build(boxes.data(), ids.data(), boxes.size(), def), Status::ok);
    std::vector<uint32_t> got;
    std::size_t nonempty = 0;
    for (int q = 0; q < 150; ++q) {
      const vec3 c{uni(rng, -60, 60), uni(rng, -60, 60), uni(rng, -60, 60)};
      const AABB region{c, {uni(rng, 0, 12), uni(rng, 0, 12), uni(rng, 0, 12)}};
      ASSERT_EQ(tree.query(region, got), Status::ok);
      EXPECT_EQ(got, brute(boxes, ids, [&](const AABB& b) { return overlaps(b, region); }));
      nonempty += !got.empty();
      const Sphere sphere{c, uni(rng, 0, 15)};
      ASSERT_EQ(tree.query(sphere, got), Status::ok);
      EXPECT_EQ(got, brute(boxes, ids, [&](const AABB& b) { return overlaps(sphere, b); }));
      const Frustum f = random_frustum(rng);
      ASSERT_EQ(tree.query(f, got), Status::ok);
      EXPECT_EQ(got, brute(boxes, ids, [&](const AABB& b) { return intersects(f, b); }));
      nonempty += !got.empty();
    }
    EXPECT_GT(nonempty, 150u);  // the queries find things
  }
  // Queries exactly touching an item's face, and a point query on its corner.
  Octree tree;
  const AABB one{{1.0f, 2.0f, 3.0f}, {0.5f, 0.25f, 1.0f}};
  const uint32_t id = 42;
  ASSERT_EQ(tree.build(&one, &id, 1), Status::ok);
  std::vector<uint32_t> got;
  ASSERT_EQ(tree.query(AABB{{2.0f, 2.0f, 3.0f}, {0.5f, 0.0f, 0.0f}}, got), Status::ok);
  EXPECT_EQ(got, std::vector<uint32_t>{42});
  ASSERT_EQ(tree.query(Sphere{{1.5f, 2.25f, 4.0f}, 0.0f}, got), Status::ok);
  EXPECT_EQ(got, std::vector<uint32_t>{42});
  ASSERT_EQ(tree.query(Sphere{{1.5f, 2.25f, 4.5f}, 0.25f}, got), Status::ok);
  EXPECT_TRUE(got.empty());
}

TEST(Octree, CoincidentAndHugeBoxesStaySmall) {
  // 500 copies of one box: no split makes progress, so the root stays a leaf.
  std::vector<AABB> same(500, AABB{{1.0f, 1.0f, 1.0f}, {0.5f, 0.5f, 0.5f}});
  std::vector<uint32_t> ids(same.size());
  for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  Octree tree;
  ASSERT_EQ(tree.build(same.data(), ids.data(), same.size(), OctreeDef{kOctreeMaxDepth, 1}), Status::ok);
  EXPECT_EQ(tree.stats().nodes, 1u);
  EXPECT_EQ(tree.stats().references, 500u);
  // All at one point: the cell has no extent; still one node.
  std::vector<AABB> points(64, AABB{{3.0f, -2.0f, 7.0f}, {0.0f, 0.0f, 0.0f}});
  ASSERT_EQ(tree.build(points.data(), ids.data(), points.size(), OctreeDef{kOctreeMaxDepth, 1}), Status::ok);
  EXPECT_EQ(tree.stats().nodes, 1u);
  std::vector<uint32_t> got;
  ASSERT_EQ(tree.query(Sphere{{3.0f, -2.0f, 7.0f}, 0.0f}, got), Status::ok);
  EXPECT_EQ(got.size(), 64u);
  // Boxes near float's range.
  const AABB far[2] = {{{3e38f, 0.0f, 0.0f}, {1e37f, 1.0f, 1.0f}}, {{-3e38f, 0.0f, 0.0f}, {1e37f, 1.0f, 1.0f}}};
  ASSERT_EQ(tree.build(far, ids.data(), 2, OctreeDef{4, 1}), Status::ok);
  expect_invariants(tree, OctreeDef{4, 1});
  ASSERT_EQ(tree.query(AABB{{3e38f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}}, got), Status::ok);
  EXPECT_EQ(got, std::vector<uint32_t>{0});
}

TEST(Octree, EmptyTree) {
  Octree tree;
  std::vector<uint32_t> got{1, 2};
  EXPECT_EQ(tree.query(AABB{}, got), Status::ok);
  EXPECT_TRUE(got.empty());
  ASSERT_EQ(tree.build(nullptr, nullptr, 0), Status::ok);
  EXPECT_EQ(tree.stats().nodes, 1u);
  EXPECT_EQ(tree.query(Sphere{{0, 0, 0}, 1e30f}, got), Status::ok);
  EXPECT_TRUE(got.empty());
}

TEST(Octree, BadInputChangesNothing) {
  SplitMix64 rng(14);
  auto boxes = random_boxes(50, rng);
  auto ids = random_ids(boxes.size(), rng);
  Octree tree;
  ASSERT_EQ(tree.build(boxes.data(), ids.data(), boxes.size()), Status::ok);
  const std::size_t nodes = tree.nodes().size();
  const auto before = tree.items();

  auto bad = boxes;
  bad[7].center.y = std::nanf("");
  EXPECT_EQ(tree.build(bad.data(), ids.data(), bad.size()), Status::non_finite);
  EXPECT_NE(std::string(last_error()).find("boxes[7]"), std::string::npos);
  bad = boxes;
  bad[3].half_extents.z = -1.0f;
  EXPECT_EQ(tree.build(bad.data(), ids.data(), bad.size()), Status::invalid_argument);
  bad = boxes;
  bad[3].center.x = 3e38f, bad[3].half_extents.x = 3e38f;  // corner overflows
  EXPECT_EQ(tree.build(bad.data(), ids.data(), bad.size()), Status::non_finite);
  auto dup = ids;
  dup[10] = dup[20];
  EXPECT_EQ(tree.build(boxes.data(), dup.data(), boxes.size()), Status::invalid_argument);
  EXPECT_EQ(tree.build(nullptr, ids.data(), boxes.size()), Status::null_argument);
  EXPECT_EQ(tree.build(boxes.data(), nullptr, boxes.size()), Status::null_argument);
  EXPECT_EQ(tree.build(boxes.data(), ids.data(), std::size_t(1) << 31), Status::invalid_count);
  EXPECT_EQ(tree.build(boxes.data(), ids.data(), boxes.size(), OctreeDef{kOctreeMaxDepth + 1, 8}), Status::invalid_argument);
  EXPECT_EQ(tree.build(boxes.data(), ids.data(), boxes.size(), OctreeDef{-1, 8}), Status::invalid_argument);
  EXPECT_EQ(tree.build(boxes.data(), ids.data(), boxes.size(), OctreeDef{4, 0}), Status::invalid_argument);
  EXPECT_EQ(tree.nodes().size(), nodes);
  EXPECT_EQ(tree.items(), before);

  std::vector<uint32_t> got{5};
  EXPECT_EQ(tree.query(Sphere{{0.0f, std::nanf(""), 0.0f}, 1.0f}, got), Status::non_finite);
  EXPECT_TRUE(got.empty());
  got = {5};
  EXPECT_EQ(tree.query(Sphere{{0.0f, 0.0f, 0.0f}, -1.0f}, got), Status::invalid_argument);
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(tree.query(AABB{{0.0f, 0.0f, 0.0f}, {1.0f, -1.0f, 1.0f}}, got), Status::invalid_argument);
  EXPECT_EQ(tree.query(AABB{{__builtin_inff(), 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}}, got), Status::non_finite);
  Frustum f = random_frustum(rng);
  f.planes[2].distance = std::nanf("");
  got = {5};
  EXPECT_EQ(tree.query(f, got), Status::non_finite);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace gyro
