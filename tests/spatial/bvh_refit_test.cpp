// The octant orders and the partial refit against their definitions: the orders as eight
// independent insertion sorts (the rule bvh.hpp states), and a refit of the marked nodes as
// every node recomputed from its items, compared to the byte. Both the build and the refit
// take their shortcuts (one sort per pair of opposite octants; slots whose child did not move,
// nodes whose slots did not change) on the claim that they give these bytes.
#include "gyro/runtime.hpp"
#include "spatial/bvh.hpp"
#include "spatial/bvh_orders.hpp"
#include "spatial/bvh_refit.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

namespace gyro {
namespace {

using detail::BvhNode8;
using testing::SplitMix64;

// BvhNode8::order by its definition: per octant, slots by the key ((0 + s_x c_x) + s_y c_y)
// + s_z c_z (c = lo + hi in binary64, s_a = -1 where octant bit a is set), empty slots as
// +inf, stable in slot order.
void reference_orders(BvhNode8& n) {
  for (int o = 0; o < 8; ++o) {
    double key[8];
    int slot[8];
    for (int k = 0; k < 8; ++k) {
      key[k] = __builtin_inf();
      if (n.child[k] != detail::kEmptyChild) {
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

// Slot k's bounds of `kind` (see random_node).
void random_slot(SplitMix64& rng, int kind, BvhNode8& n, int k) {
  for (int a = 0; a < 3; ++a) {
    float lo, hi;
    if (kind == 0) lo = float(int(rng.next() % 3) - 1), hi = lo + float(rng.next() % 3);
    else if (kind == 1) lo = float(rng.u() - 0.5) * 1e-3f, hi = lo + float(rng.u()) * 1e30f;
    else if (kind == 2) lo = float(rng.u() * 1e6), hi = lo + float(rng.u());
    else lo = -0.0f, hi = rng.next() % 2 ? 0.0f : float(rng.u());
    n.bounds[2 * a][k] = lo, n.bounds[2 * a + 1][k] = hi;
  }
}

// A node with about a quarter of its slots empty. Few distinct values (kinds 0 and 3) make
// ties in some octants and not in their opposite's; wide ranges (1, 2) make sums that round.
BvhNode8 random_node(SplitMix64& rng, int kind) {
  BvhNode8 n = detail::empty_node8();
  for (int k = 0; k < 8; ++k) {
    if (rng.next() % 4 == 0) continue;  // empty
    random_slot(rng, kind, n, k);
    n.child[k] = uint32_t(k);
  }
  return n;
}

// f(it, kind, node) for 60000 random nodes of every kind in turn, their orders set by the
// code under test.
template <class F> void each_sorted_node(uint64_t seed, F&& f) {
  SplitMix64 rng(seed);
  for (int it = 0; it < 60000; ++it) {
    const int kind = it % 4;
    BvhNode8 n = random_node(rng, kind);
    detail::set_child_orders(n);
    f(it, kind, n, rng);
  }
}

// n's orders recomputed by their definition.
BvhNode8 with_reference_orders(BvhNode8 n) {
  reference_orders(n);
  return n;
}

TEST(BvhOrders, EqualEightIndependentSorts) {
  std::size_t checked = 0, with_ties = 0;
  each_sorted_node(41, [&](int it, int kind, const BvhNode8& n, SplitMix64&) {
    const BvhNode8 ref = with_reference_orders(n);
    for (int o = 0; o < 8; ++o) ASSERT_EQ(n.order[o], ref.order[o]) << "node " << it << " octant " << o;
    ++checked;
    with_ties += kind == 0 || kind == 3;
  });
  EXPECT_EQ(checked, 60000u);
  EXPECT_GT(with_ties, 20000u);
}

// Changes n as a refit or a corrupted node might (`how` in 0..4): one used slot moved anywhere
// (same kind of values), every bound nudged by an ulp or two, two nibbles of one order swapped,
// a nibble set to a value no slot has, or the first nibble of an octant and of its opposite
// set to the same other slot (with one used slot, an empty one: no pair of keys to compare).
void disturb(SplitMix64& rng, int kind, BvhNode8& n, int how) {
  if (how == 0) {
    const int start = int(rng.next() % 8);
    for (int j = 0; j < 8; ++j)  // a node may have no used slot
      if (const int k = (start + j) % 8; n.child[k] != detail::kEmptyChild) {
        random_slot(rng, kind, n, k);
        break;
      }
  } else if (how == 1) {
    for (auto& row : n.bounds)
      for (float& v : row)
        if (v == v && v != __builtin_inff() && v != -__builtin_inff())
          for (int s = int(rng.next() % 3); s > 0; --s) v = std::nextafter(v, rng.next() % 2 ? 1e38f : -1e38f);
  } else if (how == 2) {
    const int o = int(rng.next() % 8), i = int(rng.next() % 8), j = int(rng.next() % 8);
    const uint32_t a = n.order[o] >> (4 * i) & 15u, b = n.order[o] >> (4 * j) & 15u;
    n.order[o] &= ~((15u << (4 * i)) | (15u << (4 * j)));
    n.order[o] |= b << (4 * i) | a << (4 * j);
  } else if (how == 3) {
    n.order[rng.next() % 8] |= 8u << (4 * (rng.next() % 8));
  } else {
    const int o = int(rng.next() % 4);
    const uint32_t other = ((n.order[o] & 7u) + 1u + uint32_t(rng.next() % 7)) % 8u;
    n.order[o] = (n.order[o] & ~15u) | other, n.order[7 - o] = (n.order[7 - o] & ~15u) | other;
  }
}

// Nodes with one used slot, the rest empty: the case where a check has no pair of keys and
// must still find the slot its first nibble names.
BvhNode8 one_slot_node(SplitMix64& rng, int kind) {
  BvhNode8 n = detail::empty_node8();
  const int k = int(rng.next() % 8);
  random_slot(rng, kind, n, k);
  n.child[k] = uint32_t(k);
  detail::set_child_orders(n);
  return n;
}

bool same_orders(const BvhNode8& a, const BvhNode8& b) {
  for (int o = 0; o < 8; ++o)
    if (a.order[o] != b.order[o]) return false;
  return true;
}

// A refit keeps a node's orders when child_orders_hold() says they are what the sort would
// give: it must say so exactly then. Nodes whose orders were set, then disturbed (the order
// kept or not).
TEST(BvhOrders, HoldExactlyWhenTheSortWouldGiveThem) {
  std::size_t kept = 0, changed = 0;
  each_sorted_node(47, [&](int it, int kind, BvhNode8 n, SplitMix64& rng) {
    ASSERT_TRUE(detail::child_orders_hold(n)) << "node " << it;
    const int how = int(rng.next() % 5);
    disturb(rng, kind, n, how);
    const bool same = same_orders(n, with_reference_orders(n));
    ASSERT_EQ(detail::child_orders_hold(n), same) << "node " << it << " change " << how;
    (same ? kept : changed) += 1;
    BvhNode8 one = one_slot_node(rng, kind);
    ASSERT_TRUE(detail::child_orders_hold(one)) << "node " << it;
    disturb(rng, kind, one, 4);
    ASSERT_FALSE(detail::child_orders_hold(one)) << "node " << it;
  });
  EXPECT_GT(kept, 10000u);
  EXPECT_GT(changed, 10000u);
}

// The refit's refresh of changed nodes' orders (bvh_orders.hpp) leaves exactly the sort's
// orders, and nothing else changed, at every SIMD level the machine has: whether its fast
// check clears a node or sends it to the sort, for nodes disturbed as above.
TEST(BvhOrders, RefreshLeavesTheSortsOrdersAtEveryLevel) {
  int levels = 0;
  for (SimdLevel level : {SimdLevel::scalar, SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    ++levels;
    std::size_t kept = 0, changed = 0;
    each_sorted_node(59, [&](int it, int kind, BvhNode8 n, SplitMix64& rng) {
      BvhNode8 nodes[2] = {n, one_slot_node(rng, kind)};
      disturb(rng, kind, nodes[0], int(rng.next() % 5));
      disturb(rng, kind, nodes[1], int(rng.next() % 5));
      for (const BvhNode8& node : nodes) (same_orders(node, with_reference_orders(node)) ? kept : changed) += 1;
      const uint32_t which[2] = {1, 0};
      BvhNode8 refreshed[2] = {nodes[0], nodes[1]};
      detail::bvh_orders_refresh_for(level)(refreshed, which, 2);
      for (int k = 0; k < 2; ++k) {
        BvhNode8 want = with_reference_orders(nodes[k]);
        ASSERT_EQ(std::memcmp(&refreshed[k], &want, sizeof(BvhNode8)), 0)
            << simd_level_name(level) << " node " << it << " slot node " << k;
      }
    });
    EXPECT_GT(kept, 20000u) << simd_level_name(level);
    EXPECT_GT(changed, 20000u) << simd_level_name(level);
  }
  EXPECT_GE(levels, 2);
}

struct Item {
  float lo[3], hi[3];
};

Item random_item(SplitMix64& rng) {
  Item b;
  for (int a = 0; a < 3; ++a) {
    const float c = float(rng.u() * 100.0), h = float(0.1 + rng.u());
    b.lo[a] = c - h, b.hi[a] = c + h;
  }
  return b;
}

// The union of a node's slots.
detail::BoxUnion union_of(const BvhNode8& n) {
  detail::BoxUnion u;
  for (int j = 0; j < 8; ++j) {
    if (n.child[j] == detail::kEmptyChild) continue;
    const float l[3] = {n.bounds[0][j], n.bounds[2][j], n.bounds[4][j]};
    const float h[3] = {n.bounds[1][j], n.bounds[3][j], n.bounds[5][j]};
    u.grow(l, h);
  }
  return u;
}

// Every node of `bvh` recomputed from the items, children before parents: slots, orders,
// bounds and the expected ray cost, as a refit of the whole tree defines them.
void recompute_all(detail::BoxBvh8& bvh, const std::vector<Item>& items) {
  std::vector<double> node_area(bvh.nodes.size()), leaf_area(bvh.leaves.size());
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode8& n = bvh.nodes[i];
    detail::BoxUnion own;
    for (int k = 0; k < 8; ++k) {
      const uint32_t code = n.child[k];
      if (code == detail::kEmptyChild) continue;
      detail::BoxUnion slot;
      if (code & detail::kLeafBit) {
        for (uint32_t item : bvh.leaves[code & ~detail::kLeafBit].item)
          if (item != detail::kNoItem) slot.grow(items[item].lo, items[item].hi);
        leaf_area[code & ~detail::kLeafBit] = slot.half_area();
      } else {
        slot = union_of(bvh.nodes[code]);
      }
      for (int a = 0; a < 3; ++a) n.bounds[2 * a][k] = slot.lo[a], n.bounds[2 * a + 1][k] = slot.hi[a];
      own.grow(slot.lo, slot.hi);
    }
    reference_orders(n);
    node_area[i] = own.half_area();
  }
  bvh.stats.sah_cost = detail::sah_cost(node_area.data(), node_area.size(), leaf_area.data(), leaf_area.size());
}

// A tree built over n random items, and its links.
detail::BoxBvh8 linked_tree(SplitMix64& rng, std::size_t n, std::vector<Item>& items, detail::BvhRefit& links) {
  items.resize(n);
  for (Item& b : items) b = random_item(rng);
  std::vector<detail::BvhBox> boxes(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) boxes[i].lo[a] = items[i].lo[a], boxes[i].hi[a] = items[i].hi[a];
  detail::BoxBvh8 bvh = detail::build_box_bvh8(boxes.data(), n);
  links.link(bvh, n);
  return bvh;
}

TEST(BvhRefit, MarkedNodesEqualEveryNodeRecomputed) {
  SplitMix64 rng(43);
  const std::size_t n = 3000;
  std::vector<Item> items;
  detail::BvhRefit links;
  detail::BoxBvh8 bvh = linked_tree(rng, n, items, links);
  EXPECT_GT(links.task_count(), 2u);  // the tree is split for the parallel refit
  links.set_parallel_nodes(256);       // in parallel from 256 marked nodes (every round of 2^8 moves and more)
  std::size_t unchanged_rounds = 0;
  const uint32_t saved = thread_count();
  uint64_t all_order = 0;
  for (int round = 0; round < 40; ++round) {
    // Round sizes from none to all; some moves keep the box (a leaf that does not change),
    // some shrink it inside itself (a leaf that changes under a parent that may not).
    const std::size_t moves = round % 8 == 0 ? 0 : round % 8 == 1 ? n : std::size_t(1) << (round % 8);
    const bool all = moves == n;
    for (std::size_t m = 0; m < moves; ++m) {
      const std::size_t i = all ? m : rng.next() % n;
      const uint64_t how = rng.next() % 3;
      if (how == 1) items[i] = random_item(rng);
      if (how == 2)
        for (int a = 0; a < 3; ++a) {
          const float c = 0.5f * (items[i].lo[a] + items[i].hi[a]);
          items[i].lo[a] = 0.5f * (items[i].lo[a] + c), items[i].hi[a] = 0.5f * (items[i].hi[a] + c);
        }
      if (!all) links.mark_item(uint32_t(i));
    }
    if (all) links.mark_all();
    const std::vector<BvhNode8> before(bvh.nodes.begin(), bvh.nodes.end());
    detail::BoxBvh8 ref;
    ref.nodes.assign(bvh.nodes.begin(), bvh.nodes.end());
    ref.leaves.assign(bvh.leaves.begin(), bvh.leaves.end());
    recompute_all(ref, items);
    // The subtrees run as parallel tasks when many nodes are marked: the bytes may not
    // depend on the thread count, nor the leaves asked for again (each marked leaf whose
    // item is odd, in one order at every count).
    set_thread_count(1u + uint32_t(round % 3));
    std::vector<uint8_t> asked(bvh.leaves.size(), 0);
    ASSERT_TRUE(links.refit(bvh, [&](uint32_t leaf, uint32_t item, float lo[3], float hi[3]) {
      for (int a = 0; a < 3; ++a) lo[a] = items[item].lo[a], hi[a] = items[item].hi[a];
      asked[leaf] = 1;  // each leaf by one thread
      return item % 2 == 1;
    }));
    set_thread_count(saved);
    std::vector<uint32_t> want_revisit;
    for (std::size_t l = 0; l < asked.size(); ++l)
      if (asked[l] && bvh.leaves[l].item[0] % 2 == 1) want_revisit.push_back(uint32_t(l));
    std::vector<uint32_t> got = links.revisit();
    uint64_t order = 0xcbf29ce484222325ull;  // FNV-1a over the list
    for (const uint32_t l : got) order = (order ^ l) * 0x100000001b3ull;
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want_revisit) << round;
    if (all) {
      if (all_order == 0) all_order = order;
      EXPECT_EQ(order, all_order) << "the all-moved rounds' revisit order, round " << round;
    }
    links.clear_marks();
    ASSERT_EQ(bvh.nodes.size(), ref.nodes.size());
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
      ASSERT_EQ(std::memcmp(&bvh.nodes[i], &ref.nodes[i], sizeof(BvhNode8)), 0) << "round " << round << " node " << i;
    EXPECT_EQ(std::bit_cast<uint64_t>(bvh.stats.sah_cost), std::bit_cast<uint64_t>(ref.stats.sah_cost)) << round;
    const detail::BoxUnion root = union_of(ref.nodes[0]);
    const AABB want = aabb_from_min_max({root.lo[0], root.lo[1], root.lo[2]}, {root.hi[0], root.hi[1], root.hi[2]});
    EXPECT_EQ(std::memcmp(&bvh.bounds, &want, sizeof(AABB)), 0) << round;
    unchanged_rounds += std::memcmp(before.data(), bvh.nodes.data(), before.size() * sizeof(BvhNode8)) == 0;
  }
  // Rounds with no move leave every byte; the others change some.
  EXPECT_GE(unchanged_rounds, 5u);
  EXPECT_LT(unchanged_rounds, 40u);
}

}  // namespace
// Items taken out (detach) and put in (attach: a free slot on the least-growth path, or a
// new node shared with a leaf, numbered after every other), then refit: the bytes of every
// node recomputed from the items, at 1 to 3 threads; every live item in exactly one leaf
// reachable from the root, within kBvhMaxDepth. Clusters of items in one spot fill a node of
// leaves and make new nodes under new nodes (which the refit must take children first); a
// node whose last child leaves is taken out of its parent.
TEST(BvhRefit, AttachAndDetachEqualEveryNodeRecomputed) {
  SplitMix64 rng(47);
  std::size_t n = 400;
  std::vector<Item> items;
  detail::BvhRefit links;
  detail::BoxBvh8 bvh = linked_tree(rng, n, items, links);
  links.set_parallel_nodes(64);
  const std::size_t nodes0 = bvh.nodes.size();
  std::vector<uint8_t> live(n, 1);
  const uint32_t saved = thread_count();
  for (int round = 0; round < 30; ++round) {
    const std::size_t outs = rng.next() % 40, ins = rng.next() % 40;
    for (std::size_t k = 0; k < outs; ++k) {
      const uint32_t i = uint32_t(rng.next() % n);
      EXPECT_EQ(links.detach(bvh, i), live[i] != 0) << round;
      live[i] = 0;
    }
    // Round 3 empties a whole subtree: every item under the root's first node child.
    if (round == 3) {
      std::vector<uint32_t> open;
      for (uint32_t code : bvh.nodes[0].child)
        if (code != detail::kEmptyChild && !(code & detail::kLeafBit)) {
          open.push_back(code);
          break;
        }
      while (!open.empty()) {
        const BvhNode8& node = bvh.nodes[open.back()];
        open.pop_back();
        for (uint32_t code : node.child) {
          if (code == detail::kEmptyChild) continue;
          if (!(code & detail::kLeafBit)) {
            open.push_back(code);
            continue;
          }
          const uint32_t item = bvh.leaves[code & ~detail::kLeafBit].item[0];
          if (item == detail::kNoItem) continue;
          EXPECT_TRUE(links.detach(bvh, item));
          live[item] = 0;
        }
      }
    }
    const float spot = float(rng.u() * 100.0);
    for (std::size_t k = 0; k < ins; ++k) {
      Item b = random_item(rng);
      if (round % 2 == 1)  // a cluster: boxes within 10^-3 of one point
        for (int a = 0; a < 3; ++a) b.lo[a] = spot + float(rng.u()) * 1e-3f, b.hi[a] = b.lo[a] + 1e-3f;
      items.push_back(b);
      live.push_back(1);
      ASSERT_NE(links.attach(bvh, uint32_t(n), b.lo, b.hi), detail::kNoItem) << round;
      EXPECT_EQ(links.attach(bvh, uint32_t(n), b.lo, b.hi), detail::kNoItem);  // already in
      ++n;
    }
    // Some items moved as well.
    for (int k = 0; k < 20; ++k) {
      const uint32_t i = uint32_t(rng.next() % n);
      if (!live[i]) continue;
      items[i] = random_item(rng);
      links.mark_item(i);
    }
    detail::BoxBvh8 ref;
    ref.nodes.assign(bvh.nodes.begin(), bvh.nodes.end());
    ref.leaves.assign(bvh.leaves.begin(), bvh.leaves.end());
    recompute_all(ref, items);
    set_thread_count(1u + uint32_t(round % 3));
    ASSERT_TRUE(links.refit(bvh, [&](uint32_t, uint32_t item, float lo[3], float hi[3]) {
      for (int a = 0; a < 3; ++a) lo[a] = items[item].lo[a], hi[a] = items[item].hi[a];
      return false;
    }));
    set_thread_count(saved);
    links.clear_marks();
    ASSERT_EQ(bvh.nodes.size(), ref.nodes.size());
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
      ASSERT_EQ(std::memcmp(&bvh.nodes[i], &ref.nodes[i], sizeof(BvhNode8)), 0) << "round " << round << " node " << i;
    EXPECT_EQ(std::bit_cast<uint64_t>(bvh.stats.sah_cost), std::bit_cast<uint64_t>(ref.stats.sah_cost)) << round;
    // Each live item once, from the root, within the walks' depth; no dead one.
    std::vector<int> seen(n, 0);
    std::vector<std::pair<uint32_t, std::size_t>> open{{0u, std::size_t(1)}};
    std::size_t deepest = 0;
    while (!open.empty()) {
      const auto [i, depth] = open.back();
      open.pop_back();
      deepest = std::max(deepest, depth);
      for (uint32_t code : bvh.nodes[i].child) {
        if (code == detail::kEmptyChild) continue;
        if (code & detail::kLeafBit) {
          for (uint32_t item : bvh.leaves[code & ~detail::kLeafBit].item)
            if (item != detail::kNoItem) ++seen[item];
        } else {
          open.push_back({code, depth + 1});
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], int(live[i])) << "item " << i << " round " << round;
    EXPECT_LE(deepest, detail::kBvhMaxDepth);
  }
  EXPECT_GT(bvh.nodes.size(), nodes0 + 10);  // the clusters made nodes
}

}  // namespace gyro
