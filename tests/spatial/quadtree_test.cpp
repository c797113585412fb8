// The 2D quadtree (gyro/quadtree.hpp) against brute force: random insert / remove /
// update / query sequences under several depths and thresholds, with items on the split
// lines, outside the root, of zero size and larger than the root; every query must give
// exactly the ids that testing every item with gyro::overlaps gives, in ascending order.
// Then the history independence of the tree's shape and answers, and bad input.
#include "gyro/quadtree.hpp"

#include "core/error.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <vector>

namespace gyro {
namespace {

using gyro::testing::SplitMix64;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

class Gen {
 public:
  Gen(uint64_t seed, const Rectangle2D& root) : rng_(seed), root_(root) {}
  double u() { return rng_.u(); }
  int pick(int n) { return int(rng_.next() % uint64_t(n)); }

  /// A coordinate along axis a: random over the root widened by a fifth on each side, or
  /// on a split line of the root's subdivision (depth up to 6) so items touch and
  /// straddle the node boundaries exactly.
  float coord(int a) {
    const double lo = root_.origin[a], size = root_.size[a];
    if (pick(3) == 0) {
      const int d = pick(7);
      const double k = double(pick((1 << d) + 1));
      return float(lo + size * (k / double(1 << d)));
    }
    return float(lo - 0.2 * size + 1.4 * size * u());
  }
  float extent(int a) {
    const double size = root_.size[a];
    switch (pick(8)) {
      case 0: return 0.0f;
      case 1: return float(size * 1e-6 * u());
      case 2: return float(size * 0.8 * u());
      case 3: return float(size * 1.5 * u());
      default: return float(size * 0.05 * u());
    }
  }
  Rectangle2D rect() {
    Rectangle2D r{{coord(0), coord(1)}, {extent(0), extent(1)}};
    if (pick(4) == 0) {  // end exactly on a split line
      const float hx = coord(0);
      if (hx >= r.origin.x) r.size.x = hx - r.origin.x;
    }
    return r;
  }
  Circle circle() { return {{coord(0), coord(1)}, pick(6) == 0 ? 0.0f : float(root_.size.x * 0.2 * u())}; }

 private:
  SplitMix64 rng_;
  Rectangle2D root_;
};

/// The answer every query must give: ids in ascending order, each tested with overlaps().
template <class Region>
std::vector<uint32_t> brute(const std::map<uint32_t, Rectangle2D>& items, const Region& region) {
  std::vector<uint32_t> ids;
  for (const auto& [id, r] : items)
    if (overlaps(r, region)) ids.push_back(id);
  return ids;
}

/// A tree with the same def and items, inserted in a shuffled order.
Quadtree rebuilt(const QuadtreeDef& def, const std::map<uint32_t, Rectangle2D>& items, SplitMix64& rng) {
  std::vector<std::pair<uint32_t, Rectangle2D>> v(items.begin(), items.end());
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng.next() % i]);
  Quadtree t(def);
  for (const auto& [id, r] : v) EXPECT_EQ(t.insert(id, r), Status::ok);
  return t;
}

struct Config {
  Rectangle2D bounds;
  int32_t depth, threshold;
};

TEST(QuadtreeReference, RandomOperationsMatchBruteForce) {
  const Config configs[] = {
      {{{-100, -50}, {300, 200}}, 8, 4},  {{{0, 0}, {1, 1}}, 12, 1},          {{{1e4f, -2e4f}, {1e3f, 1e3f}}, 6, 8},
      {{{-1e-3f, -1e-3f}, {2e-3f, 2e-3f}}, 20, 2}, {{{0, 0}, {64, 64}}, 0, 1}, {{{0, 0}, {0, 0}}, 4, 2},
  };
  long total_ops = 0, queries = 0, mismatches = 0, failed_statuses = 0, shape_mismatches = 0, hits = 0;
  uint64_t seed = 1;
  for (const Config& c : configs) {
    QuadtreeDef def;
    def.bounds = c.bounds;
    def.max_depth = c.depth;
    def.split_threshold = c.threshold;
    Quadtree tree;
    ASSERT_EQ(tree.configure(def), Status::ok);
    const Rectangle2D gen_root = c.bounds.size.x > 0 ? c.bounds : Rectangle2D{c.bounds.origin, {1, 1}};
    Gen g(seed++, gen_root);
    SplitMix64 shuffle(seed * 7);
    std::map<uint32_t, Rectangle2D> model;
    uint32_t next_id = 1;
    std::vector<uint32_t> out;
    for (int op = 0; op < 4000; ++op, ++total_ops) {
      const int kind = g.pick(model.size() < 20 ? 3 : 10);
      const auto some_id = [&]() -> uint32_t {
        if (model.empty() || g.pick(10) == 0) return next_id + 1000;  // unknown
        auto it = model.begin();
        std::advance(it, g.pick(int(model.size())));
        return it->first;
      };
      if (kind <= 2) {  // insert (a tenth of them reuse an id: must fail)
        const uint32_t id = g.pick(10) == 0 && !model.empty() ? some_id() : next_id++ * 7919u % 100003u;
        const Rectangle2D r = g.rect();
        const Status s = tree.insert(id, r);
        const Status want = model.count(id) ? Status::invalid_argument : Status::ok;
        failed_statuses += s != want;
        if (want == Status::ok) model[id] = r;
      } else if (kind <= 4) {  // remove
        const uint32_t id = some_id();
        const Status want = model.count(id) ? Status::ok : Status::stale_id;
        failed_statuses += tree.remove(id) != want;
        model.erase(id);
      } else if (kind <= 6) {  // update (move)
        const uint32_t id = some_id();
        const Rectangle2D r = g.rect();
        const Status want = model.count(id) ? Status::ok : Status::stale_id;
        failed_statuses += tree.update(id, r) != want;
        if (want == Status::ok) model[id] = r;
      } else if (kind <= 8) {  // rectangle query
        Rectangle2D region = g.rect();
        failed_statuses += tree.query(region, out) != Status::ok;
        mismatches += out != brute(model, region);
        hits += long(out.size());
        ++queries;
      } else {  // circle query
        const Circle region = g.circle();
        failed_statuses += tree.query(region, out) != Status::ok;
        mismatches += out != brute(model, region);
        hits += long(out.size());
        ++queries;
      }
      failed_statuses += tree.size() != model.size();
      if (op % 500 == 499) {
        // The shape is a function of the items: a tree built from scratch in another
        // order has the same nodes.
        const Quadtree fresh = rebuilt(def, model, shuffle);
        shape_mismatches += fresh.node_count() != tree.node_count();
        shape_mismatches += fresh.node_depth_histogram() != tree.node_depth_histogram();
        for (const auto& [id, r] : model) {
          Rectangle2D b;
          failed_statuses += tree.bounds_of(id, &b) != Status::ok || std::memcmp(&b, &r, sizeof b) != 0;
        }
      }
    }
    const std::vector<std::size_t> h = tree.node_depth_histogram();
    EXPECT_LE(h.size(), std::size_t(c.depth) + 1);
    std::printf("  depth %2d, threshold %d: %zu items at the end in %zu nodes over %zu levels\n", c.depth, c.threshold,
                tree.size(), tree.node_count(), h.size());
  }
  std::printf("  %ld operations, %ld queries (%ld ids returned): %ld differ from brute force, %ld wrong statuses, "
              "%ld shape differences from a rebuilt tree\n",
              total_ops, queries, hits, mismatches, failed_statuses, shape_mismatches);
  EXPECT_GE(total_ops, 10000);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(failed_statuses, 0);
  EXPECT_EQ(shape_mismatches, 0);
  EXPECT_GT(hits, queries);  // the queries do find things
}

// Two histories that end with the same items give the same tree and the same answers.
TEST(QuadtreeProperties, ShapeAndResultsDoNotDependOnHistory) {
  const Rectangle2D root{{0, 0}, {256, 256}};
  QuadtreeDef def;
  def.bounds = root;
  def.max_depth = 7;
  def.split_threshold = 3;
  Gen g(99, root);
  std::vector<std::pair<uint32_t, Rectangle2D>> items;
  for (uint32_t i = 0; i < 600; ++i) items.push_back({i * 13u + 5u, g.rect()});

  Quadtree a(def);
  for (const auto& [id, r] : items) ASSERT_EQ(a.insert(id, r), Status::ok);

  // b: reverse order, with decoys inserted and removed, and every item first inserted
  // elsewhere, then moved into place; c: a different def first, then reconfigured.
  Quadtree b(def);
  for (uint32_t i = 0; i < 300; ++i) ASSERT_EQ(b.insert(100000 + i, g.rect()), Status::ok);
  for (auto it = items.rbegin(); it != items.rend(); ++it) ASSERT_EQ(b.insert(it->first, g.rect()), Status::ok);
  for (uint32_t i = 0; i < 300; ++i) ASSERT_EQ(b.remove(100000 + i), Status::ok);
  for (std::size_t k = 0; k < items.size(); ++k) {
    const auto& [id, r] = items[(k * 389) % items.size()];
    ASSERT_EQ(b.update(id, r), Status::ok);
  }
  QuadtreeDef other = def;
  other.max_depth = 2;
  other.split_threshold = 50;
  Quadtree c(other);
  for (const auto& [id, r] : items) ASSERT_EQ(c.insert(id, r), Status::ok);
  ASSERT_EQ(c.configure(def), Status::ok);

  EXPECT_EQ(a.size(), items.size());
  EXPECT_EQ(b.size(), items.size());
  EXPECT_EQ(a.node_count(), b.node_count());
  EXPECT_EQ(a.node_count(), c.node_count());
  EXPECT_EQ(a.node_depth_histogram(), b.node_depth_histogram());
  EXPECT_EQ(a.node_depth_histogram(), c.node_depth_histogram());
  EXPECT_GT(a.node_count(), 1u);
  std::vector<uint32_t> ra, rb, rc;
  long differ = 0, found = 0;
  for (int q = 0; q < 2000; ++q) {
    if (q % 2) {
      const Circle region = g.circle();
      a.query(region, ra), b.query(region, rb), c.query(region, rc);
    } else {
      const Rectangle2D region = g.rect();
      a.query(region, ra), b.query(region, rb), c.query(region, rc);
    }
    differ += ra != rb || ra != rc || !std::is_sorted(ra.begin(), ra.end());
    found += long(ra.size());
  }
  std::printf("  2000 queries on three histories of the same %zu items (%zu nodes): %ld differ, %ld ids found\n",
              items.size(), a.node_count(), differ, found);
  EXPECT_EQ(differ, 0);
  EXPECT_GT(found, 2000);
}

TEST(Quadtree, SplitsAtTheThresholdAndMergesBack) {
  QuadtreeDef def;
  def.bounds = {{0, 0}, {16, 16}};
  def.max_depth = 3;
  def.split_threshold = 2;
  Quadtree t(def);
  ASSERT_EQ(t.insert(1, {{1, 1}, {0.5f, 0.5f}}), Status::ok);
  ASSERT_EQ(t.insert(2, {{1.5f, 1}, {0.5f, 0.5f}}), Status::ok);
  EXPECT_EQ(t.node_count(), 1u);
  ASSERT_EQ(t.insert(3, {{1, 1.5f}, {0.5f, 0.5f}}), Status::ok);  // 3 > 2: splits to max depth
  EXPECT_EQ(t.node_count(), 1u + 4u + 4u + 4u);
  EXPECT_EQ(t.node_depth_histogram(), (std::vector<std::size_t>{1, 4, 4, 4}));
  ASSERT_EQ(t.insert(4, {{7, 7}, {2, 2}}), Status::ok);       // straddles the root's center
  ASSERT_EQ(t.insert(5, {{-50, -50}, {1, 1}}), Status::ok);   // outside the root
  std::vector<uint32_t> out;
  ASSERT_EQ(t.query(Rectangle2D{{-100, -100}, {200, 200}}, out), Status::ok);
  EXPECT_EQ(out, (std::vector<uint32_t>{1, 2, 3, 4, 5}));
  ASSERT_EQ(t.query(Circle{{-49.5f, -49.5f}, 0}, out), Status::ok);
  EXPECT_EQ(out, (std::vector<uint32_t>{5}));
  ASSERT_EQ(t.query(Rectangle2D{{1.5f, 1.5f}, {0, 0}}, out), Status::ok);  // a corner of 1, 2 and 3
  EXPECT_EQ(out, (std::vector<uint32_t>{1, 2, 3}));
  ASSERT_EQ(t.query(Rectangle2D{{2, 1.5f}, {0, 0}}, out), Status::ok);  // a corner of 2 only
  EXPECT_EQ(out, (std::vector<uint32_t>{2}));
  ASSERT_EQ(t.remove(5), Status::ok);
  ASSERT_EQ(t.remove(4), Status::ok);
  EXPECT_GT(t.node_count(), 1u);
  ASSERT_EQ(t.remove(2), Status::ok);  // 2 items left: everything merges back
  EXPECT_EQ(t.node_count(), 1u);
  ASSERT_EQ(t.query(Rectangle2D{{0, 0}, {16, 16}}, out), Status::ok);
  EXPECT_EQ(out, (std::vector<uint32_t>{1, 3}));
  t.clear();
  EXPECT_EQ(t.size(), 0u);
  EXPECT_EQ(t.node_count(), 1u);
  EXPECT_EQ(t.def().max_depth, 3);
}

// Many identical items at max depth 20: the tree stays bounded and answers.
TEST(Quadtree, PilesOfIdenticalItemsStopAtMaxDepth) {
  QuadtreeDef def;
  def.bounds = {{0, 0}, {1, 1}};
  def.max_depth = kQuadtreeMaxDepth;
  def.split_threshold = 1;
  Quadtree t(def);
  for (uint32_t i = 0; i < 200; ++i) ASSERT_EQ(t.insert(i, {{0.3f, 0.3f}, {0, 0}}), Status::ok);
  EXPECT_EQ(t.node_depth_histogram().size(), std::size_t(kQuadtreeMaxDepth) + 1);
  EXPECT_EQ(t.node_count(), 1u + 4u * std::size_t(kQuadtreeMaxDepth));
  std::vector<uint32_t> out;
  ASSERT_EQ(t.query(Circle{{0.3f, 0.3f}, 0}, out), Status::ok);
  EXPECT_EQ(out.size(), 200u);
  for (uint32_t i = 0; i < 199; ++i) ASSERT_EQ(t.remove(i), Status::ok);
  EXPECT_EQ(t.node_count(), 1u);
}

TEST(Quadtree, BadInputChangesNothing) {
  QuadtreeDef def;
  def.bounds = {{0, 0}, {10, 10}};
  def.max_depth = 4;
  def.split_threshold = 1;
  Quadtree t(def);
  ASSERT_EQ(t.insert(1, {{1, 1}, {1, 1}}), Status::ok);
  ASSERT_EQ(t.insert(2, {{6, 6}, {1, 1}}), Status::ok);
  const std::size_t nodes = t.node_count();
  detail::clear_error();
  EXPECT_EQ(t.insert(3, {{kNaN, 0}, {1, 1}}), Status::non_finite);
  EXPECT_NE(std::strlen(last_error()), 0u);
  EXPECT_EQ(t.insert(3, {{0, 0}, {kInf, 1}}), Status::non_finite);
  EXPECT_EQ(t.insert(3, {{3e38f, 0}, {3e38f, 1}}), Status::non_finite);  // the far corner overflows
  EXPECT_EQ(t.insert(3, {{0, 0}, {-1, 1}}), Status::invalid_argument);
  EXPECT_EQ(t.insert(1, {{0, 0}, {1, 1}}), Status::invalid_argument);  // duplicate id
  EXPECT_EQ(t.remove(3), Status::stale_id);
  EXPECT_EQ(t.update(3, {{0, 0}, {1, 1}}), Status::stale_id);
  EXPECT_EQ(t.update(1, {{0, kNaN}, {1, 1}}), Status::non_finite);
  Rectangle2D b;
  ASSERT_EQ(t.bounds_of(1, &b), Status::ok);
  EXPECT_EQ(b.origin, (vec2{1, 1}));  // kept its old bounds
  EXPECT_EQ(t.bounds_of(3, &b), Status::stale_id);
  EXPECT_EQ(t.bounds_of(1, nullptr), Status::null_argument);
  EXPECT_EQ(t.size(), 2u);
  EXPECT_EQ(t.node_count(), nodes);
  std::vector<uint32_t> out{42};
  EXPECT_EQ(t.query(Rectangle2D{{kNaN, 0}, {1, 1}}, out), Status::non_finite);
  EXPECT_TRUE(out.empty());
  out = {42};
  EXPECT_EQ(t.query(Circle{{0, 0}, -1}, out), Status::invalid_argument);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(t.query(Circle{{0, kInf}, 1}, out), Status::non_finite);
  QuadtreeDef bad = def;
  bad.max_depth = kQuadtreeMaxDepth + 1;
  EXPECT_EQ(t.configure(bad), Status::invalid_argument);
  bad = def;
  bad.split_threshold = 0;
  EXPECT_EQ(t.configure(bad), Status::invalid_argument);
  bad = def;
  bad.bounds.size.y = kNaN;
  EXPECT_EQ(t.configure(bad), Status::non_finite);
  EXPECT_EQ(t.def().max_depth, 4);
  EXPECT_EQ(t.node_count(), nodes);
  const Quadtree from_bad(bad);  // an invalid def in the constructor falls back to the default
  EXPECT_EQ(from_bad.def().max_depth, QuadtreeDef{}.max_depth);
  ASSERT_EQ(t.query(Rectangle2D{{0, 0}, {10, 10}}, out), Status::ok);
  EXPECT_EQ(out, (std::vector<uint32_t>{1, 2}));
}

}  // namespace
}  // namespace gyro
