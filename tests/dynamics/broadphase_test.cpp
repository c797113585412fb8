// Broadphase: the pair list against an O(n^2) brute force on random scenes (mixed sizes,
// flags, filters, zero-size boxes, exactly touching boxes, a huge ground box), and the
// contract's invariances (repeat, slot permutation, all static).
#include "dynamics/broadphase.hpp"
#include "gyro/runtime.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace gyro::detail {
namespace {

using testing::SplitMix64;

struct Scene {
  std::vector<float> lo[3], hi[3];
  std::vector<uint32_t> cat, mask, key;
  std::vector<uint8_t> flags;

  std::size_t size() const { return key.size(); }
  void add(const float l[3], const float h[3], uint8_t f, uint32_t c, uint32_t m, uint32_t k) {
    for (int a = 0; a < 3; ++a) lo[a].push_back(l[a]), hi[a].push_back(h[a]);
    flags.push_back(f), cat.push_back(c), mask.push_back(m), key.push_back(k);
  }
  BroadphaseInput input() const {
    BroadphaseInput in;
    in.count = size();
    in.min_x = lo[0].data(), in.min_y = lo[1].data(), in.min_z = lo[2].data();
    in.max_x = hi[0].data(), in.max_y = hi[1].data(), in.max_z = hi[2].data();
    in.category = cat.data(), in.mask = mask.data(), in.flags = flags.data(), in.key = key.data();
    return in;
  }
};

constexpr uint8_t kStatic = 0, kAwake = kBroadDynamic | kBroadActive, kAsleep = kBroadDynamic, kKinematic = kBroadActive;

/// A random scene of n boxes in a cube of side `side`: mostly unit-ish boxes, some tiny,
/// some zero-size, some large, a quarter snapped to an integer grid so faces touch exactly,
/// one huge static ground box; random flags and filters; unique, shuffled, gappy keys.
Scene random_scene(std::size_t n, uint64_t seed, float side) {
  SplitMix64 rng(seed);
  Scene s;
  std::vector<uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = static_cast<uint32_t>(3 * i + 7);
  for (std::size_t i = n; i > 1; --i) std::swap(keys[i - 1], keys[rng.next() % i]);
  for (std::size_t i = 0; i < n; ++i) {
    float l[3], h[3];
    const uint64_t kind = rng.next() % 100;
    if (i == n / 2) {  // the ground: spans everything in x and z
      l[0] = -2 * side, l[1] = -1.0f, l[2] = -2 * side, h[0] = 2 * side, h[1] = 0.0f, h[2] = 2 * side;
      s.add(l, h, kStatic, 1, 0xFFFFFFFFu, keys[i]);
      continue;
    }
    if (kind < 25) {  // snapped to the grid: unit cells, touching neighbours exactly
      for (int a = 0; a < 3; ++a) l[a] = float(int(rng.u() * side)), h[a] = l[a] + 1.0f;
    } else {
      float ext = kind < 30 ? 0.0f : kind < 40 ? float(rng.u() * 0.05) : kind < 97 ? float(0.2 + rng.u()) : float(rng.u() * side * 0.5);
      for (int a = 0; a < 3; ++a) {
        l[a] = float(rng.u() * side);
        const float e = kind < 60 ? ext : float(ext * (0.5 + rng.u()));
        h[a] = l[a] + e;
      }
    }
    const uint64_t fk = rng.next() % 10;
    const uint8_t f = fk < 5 ? kAwake : fk < 7 ? kStatic : fk < 9 ? kAsleep : kKinematic;
    const uint32_t c = 1u << (rng.next() % 4);
    const uint32_t m = rng.next() % 8 == 0 ? static_cast<uint32_t>(rng.next()) & 0xFu : 0xFFFFFFFFu;
    s.add(l, h, f, c, m, keys[i]);
  }
  return s;
}

/// The contract, literally: every pair of slots, sorted by keys.
std::vector<std::pair<uint32_t, uint32_t>> brute_force(const Scene& s) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  const std::size_t n = s.size();
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = i + 1; j < n; ++j) {
      bool overlap = true;
      for (int a = 0; a < 3; ++a) overlap = overlap && s.lo[a][i] <= s.hi[a][j] && s.lo[a][j] <= s.hi[a][i];
      if (!overlap) continue;
      if (!(s.cat[i] & s.mask[j]) || !(s.cat[j] & s.mask[i])) continue;
      if (!((s.flags[i] | s.flags[j]) & kBroadDynamic)) continue;
      if (!((s.flags[i] | s.flags[j]) & kBroadActive)) continue;
      out.push_back(s.key[i] < s.key[j] ? std::pair{s.key[i], s.key[j]} : std::pair{s.key[j], s.key[i]});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The same contract by a plain sweep along x over all boxes (no lists, no cells): an
/// independent reference for scenes too large for the O(n^2) loop.
std::vector<std::pair<uint32_t, uint32_t>> plain_sweep(const Scene& s) {
  std::vector<uint32_t> order(s.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return s.lo[0][a] < s.lo[0][b] || (s.lo[0][a] == s.lo[0][b] && a < b); });
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (std::size_t x = 0; x < order.size(); ++x) {
    const uint32_t i = order[x];
    for (std::size_t y = x + 1; y < order.size() && s.lo[0][order[y]] <= s.hi[0][i]; ++y) {
      const uint32_t j = order[y];
      if (!(s.lo[1][i] <= s.hi[1][j] && s.lo[1][j] <= s.hi[1][i] && s.lo[2][i] <= s.hi[2][j] && s.lo[2][j] <= s.hi[2][i])) continue;
      if (!(s.cat[i] & s.mask[j]) || !(s.cat[j] & s.mask[i])) continue;
      if (!((s.flags[i] | s.flags[j]) & kBroadDynamic) || !((s.flags[i] | s.flags[j]) & kBroadActive)) continue;
      out.push_back(s.key[i] < s.key[j] ? std::pair{s.key[i], s.key[j]} : std::pair{s.key[j], s.key[i]});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::pair<uint32_t, uint32_t>> key_pairs(const Scene& s, const std::vector<BroadPair>& pairs) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const BroadPair& p : pairs) out.emplace_back(s.key[p.a], s.key[p.b]);
  return out;
}

void expect_matches_brute_force(const Scene& s) {
  Broadphase bp;
  std::vector<BroadPair> pairs;
  bp.find_pairs(s.input(), pairs);
  const auto want = brute_force(s);
  const auto got = key_pairs(s, pairs);
  // Slots must name the keys in order (key[a] < key[b]), and the list must equal the reference.
  for (const BroadPair& p : pairs) ASSERT_LT(s.key[p.a], s.key[p.b]);
  ASSERT_EQ(got.size(), want.size());
  EXPECT_TRUE(got == want);
  EXPECT_GT(want.size(), s.size() / 4) << "the scene should produce a fair number of pairs";
}

TEST(Broadphase, MatchesBruteForce1k) {
  for (uint64_t seed : {1u, 2u, 3u}) expect_matches_brute_force(random_scene(1000, seed, 12.0f));
  // Denser and sparser scenes.
  expect_matches_brute_force(random_scene(1000, 4, 6.0f));
  expect_matches_brute_force(random_scene(1000, 5, 30.0f));
}

TEST(Broadphase, MatchesBruteForce5k) {
  expect_matches_brute_force(random_scene(5000, 11, 24.0f));
  expect_matches_brute_force(random_scene(5000, 12, 40.0f));
}

TEST(Broadphase, MatchesBruteForceOnFlatPileAndTallTower) {
  // A wide flat pile (many bodies per row of x: the bands matter) and a tall tower (the
  // sweep axis must follow the spread), both on a ground box, keys increasing with slots.
  for (int shape = 0; shape < 2; ++shape) {
    Scene s;
    SplitMix64 rng(77 + shape);
    const float g_lo[3] = {-100, -1, -100}, g_hi[3] = {100, 0, 100};
    s.add(g_lo, g_hi, kStatic, 1, 0xFFFFFFFFu, 0);
    for (uint32_t i = 1; i < 3000; ++i) {
      const float x = shape == 0 ? float(rng.u() * 60) : float(rng.u() * 3);
      const float y = shape == 0 ? float(rng.u() * 2) : float(rng.u() * 300);
      const float z = shape == 0 ? float(rng.u() * 60) : float(rng.u() * 3);
      const float l[3] = {x, y, z}, h[3] = {x + 1, y + 1, z + 1};
      s.add(l, h, i % 7 == 0 ? kAsleep : kAwake, 1, 0xFFFFFFFFu, i);
    }
    expect_matches_brute_force(s);
  }
}

TEST(Broadphase, LargeSceneMatchesPlainSweepAtEveryThreadCount) {
  // 60k boxes: enough for the sweep to run in parallel chunks of cells.
  const Scene s = random_scene(60000, 51, 60.0f);
  const auto want = plain_sweep(s);
  std::vector<BroadPair> first;
  for (uint32_t threads : {1u, 2u, 3u}) {
    ASSERT_EQ(set_thread_count(threads), Status::ok);
    Broadphase bp;
    std::vector<BroadPair> pairs;
    bp.find_pairs(s.input(), pairs);
    EXPECT_TRUE(key_pairs(s, pairs) == want) << threads << " threads";
    if (first.empty()) first = pairs;
    ASSERT_EQ(pairs.size(), first.size());
    EXPECT_EQ(0, std::memcmp(pairs.data(), first.data(), first.size() * sizeof(BroadPair)));
  }
  ASSERT_EQ(set_thread_count(0), Status::ok);
  EXPECT_GT(want.size(), 30000u);
}

TEST(Broadphase, ClosedOverlapAndPairRules) {
  Scene s;
  const float a_lo[3] = {0, 0, 0}, a_hi[3] = {1, 1, 1};
  const float b_lo[3] = {1, 0, 0}, b_hi[3] = {2, 1, 1};        // touches a on the x = 1 face
  const float c_lo[3] = {2, 1, 1}, c_hi[3] = {2, 1, 1};        // a point: touches b's corner
  const float d_lo[3] = {1.0f + 1e-6f, 0, 0}, d_hi[3] = {3, 1, 1};  // just misses a
  s.add(a_lo, a_hi, kAwake, 1, 0xFFFFFFFFu, 10);
  s.add(b_lo, b_hi, kStatic, 1, 0xFFFFFFFFu, 5);
  s.add(c_lo, c_hi, kAsleep, 1, 0xFFFFFFFFu, 7);
  s.add(d_lo, d_hi, kKinematic, 1, 0xFFFFFFFFu, 1);
  Broadphase bp;
  std::vector<BroadPair> pairs;
  bp.find_pairs(s.input(), pairs);
  // a-b (touching, dynamic+static, a active); c-d (sleeping dynamic + kinematic).
  // b-c: static + sleeping: nobody active. b-d: no dynamic. a-d: apart by 1e-6.
  const std::vector<std::pair<uint32_t, uint32_t>> want = {{1, 7}, {5, 10}};
  EXPECT_EQ(key_pairs(s, pairs), want);
  EXPECT_EQ(key_pairs(s, pairs), brute_force(s));
  // The filter: a's mask excludes b's category.
  s.mask[0] = 2;
  bp.find_pairs(s.input(), pairs);
  EXPECT_EQ(key_pairs(s, pairs), (std::vector<std::pair<uint32_t, uint32_t>>{{1, 7}}));
}

TEST(Broadphase, EmptySingleAndAllStatic) {
  Broadphase bp;
  std::vector<BroadPair> pairs{{1, 2}};
  Scene empty;
  bp.find_pairs(empty.input(), pairs);
  EXPECT_TRUE(pairs.empty());
  Scene s = random_scene(1000, 21, 10.0f);
  std::fill(s.flags.begin(), s.flags.end(), kStatic);
  bp.find_pairs(s.input(), pairs);
  EXPECT_TRUE(pairs.empty());
  // All asleep: nobody active.
  std::fill(s.flags.begin(), s.flags.end(), kAsleep);
  bp.find_pairs(s.input(), pairs);
  EXPECT_TRUE(pairs.empty());
  // Only kinematic and static: no dynamic body.
  for (std::size_t i = 0; i < s.size(); ++i) s.flags[i] = i % 2 ? kKinematic : kStatic;
  bp.find_pairs(s.input(), pairs);
  EXPECT_TRUE(pairs.empty());
}

TEST(Broadphase, AllAtOnePointAndZeroSize) {
  // Every box the same point: no spread on any axis, every pair overlaps.
  Scene s;
  for (uint32_t i = 0; i < 300; ++i) {
    const float p[3] = {1.5f, -2.0f, 0.25f};
    s.add(p, p, i % 3 ? kAwake : kStatic, 1, 0xFFFFFFFFu, 1000 - i);
  }
  Broadphase bp;
  std::vector<BroadPair> pairs;
  bp.find_pairs(s.input(), pairs);
  EXPECT_EQ(key_pairs(s, pairs), brute_force(s));
  EXPECT_EQ(pairs.size(), 300u * 299u / 2u - 100u * 99u / 2u);
}

TEST(Broadphase, RepeatedCallsAreIdentical) {
  const Scene s = random_scene(3000, 31, 20.0f);
  Broadphase bp;
  std::vector<BroadPair> first, again;
  bp.find_pairs(s.input(), first);
  for (int k = 0; k < 3; ++k) {
    bp.find_pairs(s.input(), again);
    ASSERT_EQ(again.size(), first.size());
    EXPECT_EQ(0, std::memcmp(again.data(), first.data(), first.size() * sizeof(BroadPair)));
  }
  // A fresh object after another scene gives the same answer too (no state leaks between calls).
  Broadphase other;
  other.find_pairs(random_scene(500, 32, 5.0f).input(), again);
  other.find_pairs(s.input(), again);
  ASSERT_EQ(again.size(), first.size());
  EXPECT_EQ(0, std::memcmp(again.data(), first.data(), first.size() * sizeof(BroadPair)));
}

TEST(Broadphase, SlotPermutationGivesSameKeyPairs) {
  const Scene s = random_scene(2000, 41, 16.0f);
  SplitMix64 rng(42);
  std::vector<uint32_t> perm(s.size());
  for (uint32_t i = 0; i < perm.size(); ++i) perm[i] = i;
  for (std::size_t i = perm.size(); i > 1; --i) std::swap(perm[i - 1], perm[rng.next() % i]);
  Scene t;
  for (uint32_t i : perm) {
    const float l[3] = {s.lo[0][i], s.lo[1][i], s.lo[2][i]}, h[3] = {s.hi[0][i], s.hi[1][i], s.hi[2][i]};
    t.add(l, h, s.flags[i], s.cat[i], s.mask[i], s.key[i]);
  }
  Broadphase bp;
  std::vector<BroadPair> ps, pt;
  bp.find_pairs(s.input(), ps);
  bp.find_pairs(t.input(), pt);
  EXPECT_EQ(key_pairs(s, ps), key_pairs(t, pt));
  EXPECT_FALSE(ps.empty());
}

}  // namespace
}  // namespace gyro::detail
