// B1: the broadphase on pile-like scenes. n random boxes (edges 0.5 to 1.5 m) in a flat
// volume 8 m high whose square footprint is sized for about 4 overlapping neighbours per box
// (2 pairs per box), 90% awake dynamic and 10% asleep, plus one static ground box under
// everything whose top (y = 0.25) overlaps the lowest boxes, for n = 1k, 10k, 100k, slots in
// random spatial order (a rain of boxes, the worst order for memory). Time per find_pairs
// call (median of reps, warm: no allocation) per thread count, pairs found, and the error:
// pairs differing from an exact reference (brute force O(n^2) at 1k and 10k, a uniform grid
// at 100k; both compare the same floats exactly, so any difference is a bug).
#include "core/state_hash.hpp"
#include "dynamics/broadphase.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gyro::bench {
namespace {

using detail::BroadPair;
using detail::BroadphaseInput;

struct B1Scene {
  std::vector<float> lo[3], hi[3];
  std::vector<uint32_t> cat, mask, key;
  std::vector<uint8_t> flags;
  BroadphaseInput input() const {
    BroadphaseInput in;
    in.count = key.size();
    in.min_x = lo[0].data(), in.min_y = lo[1].data(), in.min_z = lo[2].data();
    in.max_x = hi[0].data(), in.max_y = hi[1].data(), in.max_z = hi[2].data();
    in.category = cat.data(), in.mask = mask.data(), in.flags = flags.data(), in.key = key.data();
    return in;
  }
};

B1Scene make_scene(std::size_t n, uint64_t seed) {
  testing::SplitMix64 rng(seed);
  B1Scene s;
  // Two random boxes with edges e, f overlap when their centres are within (e+f)/2 on each
  // axis: E[(e+f)^3] = 8.5 for edges uniform in [0.5, 1.5], so 4 neighbours need a volume
  // of n * 8.5 / 4 (height 8 m; the footprint is square).
  const double height = 8.0, side = std::sqrt(double(n) * 8.5 / 4.0 / height);
  auto push = [&](const float l[3], const float h[3], uint8_t f) {
    for (int a = 0; a < 3; ++a) s.lo[a].push_back(l[a]), s.hi[a].push_back(h[a]);
    s.cat.push_back(1), s.mask.push_back(0xFFFFFFFFu), s.flags.push_back(f);
    s.key.push_back(static_cast<uint32_t>(s.key.size()));
  };
  const float g_lo[3] = {float(-side), -1.0f, float(-side)}, g_hi[3] = {float(2 * side), 0.25f, float(2 * side)};
  push(g_lo, g_hi, 0);  // the ground: static, touching the lowest boxes
  for (std::size_t i = 1; i < n; ++i) {
    float l[3], h[3];
    for (int a = 0; a < 3; ++a) {
      const double e = 0.5 + rng.u();
      const double c = (a == 1 ? 0.5 * e + rng.u() * (height - e) : rng.u() * side);
      l[a] = float(c - 0.5 * e), h[a] = float(c + 0.5 * e);
    }
    l[1] = std::max(l[1], 0.0f);  // the lowest boxes rest on the ground (touching: closed overlap)
    push(l, h, rng.next() % 10 == 0 ? detail::kBroadDynamic : detail::kBroadDynamic | detail::kBroadActive);
  }
  return s;
}

bool pair_wanted(const B1Scene& s, uint32_t i, uint32_t j) {
  for (int a = 0; a < 3; ++a)
    if (!(double(s.lo[a][i]) <= double(s.hi[a][j]) && double(s.lo[a][j]) <= double(s.hi[a][i]))) return false;
  if (!(s.cat[i] & s.mask[j]) || !(s.cat[j] & s.mask[i])) return false;
  return ((s.flags[i] | s.flags[j]) & detail::kBroadDynamic) && ((s.flags[i] | s.flags[j]) & detail::kBroadActive);
}

using KeyPairs = std::vector<std::pair<uint32_t, uint32_t>>;

KeyPairs brute_force(const B1Scene& s) {
  KeyPairs out;
  const uint32_t n = static_cast<uint32_t>(s.key.size());
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j)
      if (pair_wanted(s, i, j)) out.emplace_back(std::min(s.key[i], s.key[j]), std::max(s.key[i], s.key[j]));
  std::sort(out.begin(), out.end());
  return out;
}

/// Uniform grid in binary64 with cells as large as the largest small box: each small box is
/// listed in every cell it touches, a pair is tested in every shared cell and duplicates are
/// removed at the end; boxes larger than a cell are tested against every box.
KeyPairs grid_reference(const B1Scene& s) {
  const uint32_t n = static_cast<uint32_t>(s.key.size());
  double cell = 0;
  for (uint32_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      if (s.hi[a][i] - s.lo[a][i] < 4.0f) cell = std::max(cell, double(s.hi[a][i]) - double(s.lo[a][i]));
  cell = std::max(cell, 1e-3);
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  std::vector<uint32_t> large;
  for (uint32_t i = 0; i < n; ++i) {
    bool big = false;
    int64_t c0[3], c1[3];
    for (int a = 0; a < 3; ++a) {
      big |= double(s.hi[a][i]) - double(s.lo[a][i]) > cell;
      c0[a] = int64_t(std::floor(double(s.lo[a][i]) / cell)), c1[a] = int64_t(std::floor(double(s.hi[a][i]) / cell));
    }
    if (big) {
      large.push_back(i);
      continue;
    }
    for (int64_t x = c0[0]; x <= c1[0]; ++x)
      for (int64_t y = c0[1]; y <= c1[1]; ++y)
        for (int64_t z = c0[2]; z <= c1[2]; ++z)
          entries.emplace_back((uint64_t(x & 0x1FFFFF) << 42) | (uint64_t(y & 0x1FFFFF) << 21) | uint64_t(z & 0x1FFFFF), i);
  }
  std::sort(entries.begin(), entries.end());
  KeyPairs out;
  auto add = [&](uint32_t i, uint32_t j) {
    if (pair_wanted(s, i, j)) out.emplace_back(std::min(s.key[i], s.key[j]), std::max(s.key[i], s.key[j]));
  };
  for (std::size_t b = 0; b < entries.size();) {
    std::size_t e = b;
    while (e < entries.size() && entries[e].first == entries[b].first) ++e;
    for (std::size_t i = b; i < e; ++i)
      for (std::size_t j = i + 1; j < e; ++j) add(entries[i].second, entries[j].second);
    b = e;
  }
  for (std::size_t k = 0; k < large.size(); ++k)
    for (uint32_t j = 0; j < n; ++j)
      if (j != large[k] && !(std::find(large.begin(), large.begin() + k, j) != large.begin() + k)) add(large[k], j);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Pairs in one list and not the other (both sorted).
std::size_t differing(const KeyPairs& a, const KeyPairs& b) {
  std::size_t i = 0, j = 0, d = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i] < b[j])) ++i, ++d;
    else if (i == a.size() || b[j] < a[i]) ++j, ++d;
    else ++i, ++j;
  }
  return d;
}

}  // namespace

void run_b1(const Options& o) {
  std::printf("# B1: find_pairs is scalar C++ with SSE2 compares (no per-level kernels); the sweep runs in\n"
              "# fixed chunks of cells on gyro's threads, so every thread count gives the same pairs\n");
  for (std::size_t n : {std::size_t{1000}, std::size_t{10000}, std::size_t{100000}}) {
    const B1Scene s = make_scene(n, 0xB1 + n);
    const BroadphaseInput in = s.input();
    const bool brute = n <= 10000;
    const auto t0 = std::chrono::steady_clock::now();
    const KeyPairs want = brute ? brute_force(s) : grid_reference(s);
    const double ref_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      detail::Broadphase bp;
      std::vector<BroadPair> pairs;
      const double ms = median_ms(o.reps, [&] { bp.find_pairs(in, pairs); });

      KeyPairs got;
      got.reserve(pairs.size());
      uint64_t checksum = 0xcbf29ce484222325ull;
      std::size_t ground_pairs = 0;
      for (const BroadPair& p : pairs) {
        got.emplace_back(s.key[p.a], s.key[p.b]);
        ground_pairs += s.key[p.a] == 0;
        const uint64_t w = (uint64_t{s.key[p.a]} << 32) | s.key[p.b];
        checksum = detail::fnv1a64(&w, sizeof w, checksum);
      }
      JsonLine line;
      line.str("workload", "B1").str("library", "gyro").str("method", "celled_sap").str("simd", "sse2")
          .integer("threads", threads).integer("bodies", int64_t(n)).num("time_ms", ms, 5)
          .num("throughput", double(n) / ms / 1e3, 5).str("unit", "Mbodies/s").integer("pairs", int64_t(pairs.size()))
          .integer("ground_pairs", int64_t(ground_pairs)).num("pairs_per_body", double(pairs.size()) / double(n), 4)
          .hex("checksum", checksum).num("error", double(differing(got, want)))
          .str("error_metric", brute ? "pairs differing from brute force O(n^2)"
                                     : "pairs differing from a binary64 uniform-grid reference")
          .num("reference_ms", ref_ms, 5).integer("reps", o.reps);
      line.print();
    }
  }
  set_thread_count(0);
}

}  // namespace gyro::bench
