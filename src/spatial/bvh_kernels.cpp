// bvh_raycast at this translation unit's SIMD level: each ray walks the 8-wide BVH on its
// own, testing a node's eight child boxes in one 8-wide lane (Oct: one AVX register, or two
// Quads) and a leaf's four triangles in one 4-wide lane (Quad); sixteen rays take turns, one
// visit each, so that each one's next node arrives from memory while the others work. A
// node's entered children are pushed in the node's stored order for the ray's octant,
// without a branch (bvh_order.hpp; R2 3.1 -> 3.9 Mrays/s, AVX2, one thread); an any-hit
// answer is the first hit in that order. Rays from one origin (closest hit) walk in packets
// of eight instead (packet_walk.hpp: a child box against eight rays per lane).
//
// Exactness: the answer is the brute-force one, the smallest (t, triangle index) over every
// triangle the watertight test of ray_triangle_lanes.hpp hits in [tmin, tmax]. The order in
// which nodes are visited only changes speed, because
//  - ties are broken by the triangle index, not by the visiting order;
//  - a subtree is skipped only when its box is entered beyond the best t found so far by a
//    relative margin (kBestSlack, 2^-16), far more than the few ulps by which a triangle's
//    rounded t can precede its exact entry into the box;
//  - the slab test accepts a box whose computed exit precedes its entry by up to 2^-20 of
//    the exit distance (Ize, "Robust BVH ray traversal", JCGT 2013, asks for 2 gamma_3):
//    rays grazing a face still enter;
//  - a slab product that is NaN (an origin exactly on a slab plane of an axis the ray is
//    parallel to: 0 * inf) is ignored by the ordered max/min (`a > b ? a : b` keeps b).
// Every lane operation is elementwise and the visiting order is a function of float values
// only, so each level (the scalar one runs Quad as four floats) gives the same bits; a ray's
// walk does not depend on which rays share its turns.
#include "geometry/ray_triangle_lanes.hpp"
#include "spatial/bvh_batch.hpp"
#include "spatial/bvh_order.hpp"
#include "spatial/packet_walk.hpp"

#include <bit>

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::Bvh8;
using detail::BvhLeaf4;
using detail::BvhNode8;
using detail::kLeafBit;
using detail::kNoTriangle;

constexpr float kInf = __builtin_inff();
constexpr float kSlabSlack = 0x1p-20f;
// A box counts as entered where tn <= tf * kSlabScale: the same verdict as tn <= tf +
// |tf| * kSlabSlack in one multiply instead of three operations. For tf >= 0 both round the
// same exact value tf * (1 + slack) once (tf * slack, a power of two, is exact above the
// subnormals, and 1 + slack is a float); for tf < 0 both sides are negative and tn >= tmin
// >= 0, so neither enters.
constexpr float kSlabScale = 1.0f + kSlabSlack;
constexpr float kBestSlack = 0x1p-16f;

struct Entry {
  uint32_t code;
  float near;
};

// The watertight test's frame of one ray with its axis permutation resolved once: a leaf's
// corner rows are loaded in (kx, ky, kz) order, the values permute() would select lane by
// lane, so the test gives ray_triangle_t's bits without a select per corner.
struct LeafRay {
  int row[3];  // kx, ky, kz
  Quad o[3];   // the origin's kx, ky, kz coordinates
  Quad sx, sy, sz;
};

inline LeafRay leaf_ray(const float o[3], const float d[3]) {
  const WatertightRay<float> w = watertight_ray(RayL<float>{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}});
  const int kz = w.z_is_x ? 0 : w.z_is_y ? 1 : 2, x0 = (kz + 1) % 3, y0 = (kz + 2) % 3;
  const int kx = w.swap ? y0 : x0, ky = w.swap ? x0 : y0;
  return {{kx, ky, kz}, {Quad(o[kx]), Quad(o[ky]), Quad(o[kz])}, Quad(w.sx), Quad(w.sy), Quad(w.sz)};
}

// ray_triangle_t's double path (ray_triangle_lanes.hpp: hits whose edge functions cancelled)
// for the lanes in `flag`, from ray i as given: the same inputs, so the same bits. Out of
// line and cold, and reading the ray from the arguments: any state it added to the walk cost
// the common path 5 to 8% more instructions (R2, callgrind). Its lane loop is written here
// rather than through refine_lanes(): with that call the compiler laid out the hot walk
// differently, 319.9 M -> 330.3 M instructions on R2 for a function that runs once in 10^5
// leaf tests.
[[gnu::noinline, gnu::cold]] Quad refined_t(const BvhRaycastArgs& a, std::size_t i, const BvhLeaf4& leaf,
                                            detail_rt::mask_of<Quad> flag, Quad t) {
  const float o[3] = {a.ox[i], a.oy[i], a.oz[i]}, d[3] = {a.dx[i], a.dy[i], a.dz[i]};
  float f[4], ts[4];
  store(f, select(flag, Quad(1.0f), Quad(0.0f)));
  store(ts, t);
  for (int k = 0; k < 4; ++k) {
    if (f[k] == 0.0f) continue;
    float c[3][3];
    for (int q = 0; q < 9; ++q) c[q / 3][q % 3] = leaf.corner[q][k];
    const detail_rt::RefinedHit h = detail_rt::refine_hit(c[0], c[1], c[2], o, d);
    if (h.ok) ts[k] = h.t;
  }
  return load<Quad>(ts);
}

// Only t of ray_triangle_t (the same expressions, so the same bits): the traversal needs no
// barycentrics, and the caller recomputes them for the one triangle that wins.
// Ray i of a (for the double path of ray_triangle_lanes.hpp) in its frame r.
inline Quad leaf_t(const BvhRaycastArgs& a, std::size_t i, const LeafRay& r, const BvhLeaf4& leaf, Quad tmin, Quad tmax) {
  const auto corner = [&](int c) {
    const auto row = [&](int k) { return load<Quad>(leaf.corner[3 * c + r.row[k]]) - r.o[k]; };
    return V3<Quad>(row(0), row(1), row(2));
  };
  const auto k = detail_rt::permuted_terms(r.sx, r.sy, r.sz, corner(0), corner(1), corner(2));
  if (!any(k.inside)) return Quad(kInf);  // most leaves a ray enters it does not hit
  Quad t = k.T / k.det;
  const auto cancelled = k.cancelled();
  if (any(cancelled)) t = refined_t(a, i, leaf, cancelled, t);
  return select(k.inside && (t >= tmin) && (t <= tmax), t + Quad(0.0f), Quad(kInf));
}

// Asks for every line of a node or leaf block: a visit needs all of them. Only where rays
// take turns: rays from one origin find their nodes in the cache, and there the prefetches
// are only instructions.
template <bool Turns> inline void prefetch(const Bvh8& bvh, uint32_t code) {
  if constexpr (Turns) detail::prefetch_visit(bvh.nodes.data(), bvh.leaves.data(), code);
}

// One ray's walk, advanced one visit at a time so that several rays can take turns: a visit
// ends by prefetching the next node or leaf, and the other rays' visits hide the wait for it
// (the BVH is far larger than the L2 cache, so most visits would otherwise stall on memory).
struct Walk {
  Oct o[3], inv[3], tmin8;
  Quad tmin4, tmax4;
  LeafRay leaf;
  std::ptrdiff_t near_at[3], far_at[3];  // the slab rows' offsets in BvhNode8::bounds, in bytes (bounds_row)
  unsigned oct;
  float best_t, limit;
  uint32_t best_id;
  std::size_t ray;
  Entry next;  // what the next visit tests, its lines already asked for
  int sp;
  uint32_t stack_code[detail::kBvhStackSize + order::kOverhang];  // two columns: bvh_order.hpp
  float stack_near[detail::kBvhStackSize + order::kOverhang];
};

inline void push(Walk& w, const Entry& e) { w.stack_code[w.sp] = e.code, w.stack_near[w.sp] = e.near, ++w.sp; }

template <bool Turns>
inline void start(const Bvh8& bvh, Walk& w, std::size_t ray, const float o[3], const float d[3], float tmin, float tmax) {
  const float inv[3] = {1.0f / d[0], 1.0f / d[1], 1.0f / d[2]};
  w.oct = order::octant(inv);
  for (int a = 0; a < 3; ++a) {
    const int neg = int(std::bit_cast<uint32_t>(inv[a]) >> 31);
    w.near_at[a] = detail::bounds_offset(a, neg), w.far_at[a] = detail::bounds_offset(a, 1 - neg);
    w.o[a] = Oct(o[a]), w.inv[a] = Oct(inv[a]);
  }
  w.tmin8 = Oct(tmin), w.tmin4 = Quad(tmin), w.tmax4 = Quad(tmax);
  w.leaf = leaf_ray(o, d);
  w.best_t = kInf, w.limit = tmax, w.best_id = kNoTriangle;
  w.ray = ray;
  w.next = {0, tmin};
  w.sp = 0;
  prefetch<Turns>(bvh, 0);
}

// Visits w.next and picks the one after it; false when the walk is over. Rays taking turns
// (closest and any hit) push a node's children in its stored order (bvh_order.hpp): without
// branches, and the other rays' visits hide the push's latency. A ray walking alone (the
// closest-hit packets' fallback) sorts them by entry distance instead: there the branches
// are predicted ahead, and the push's chain of dependent instructions would sit on the
// walk's critical path.
template <bool AnyHit, bool Turns> inline bool step(const BvhRaycastArgs& a, Walk& w) {
  const Bvh8& bvh = *a.bvh;
  const Entry e = w.next;
  if (e.code & kLeafBit) {
    const BvhLeaf4& leaf = bvh.leaves[e.code & ~kLeafBit];
    const Quad t = leaf_t(a, w.ray, w.leaf, leaf, w.tmin4, w.tmax4);
    if (any(t < Quad(kInf))) {  // most leaves a ray enters it does not hit
      float ts[4];
      store(ts, t);
      for (int k = 0; k < 4; ++k) {
        if (ts[k] < w.best_t || (ts[k] == w.best_t && leaf.triangle[k] < w.best_id))
          w.best_t = ts[k], w.best_id = leaf.triangle[k];
      }
      if constexpr (AnyHit) return false;
      w.limit = w.best_t + w.best_t * kBestSlack;
    }
  } else {
    const BvhNode8& node = bvh.nodes[e.code];
    const auto slab = [&](std::ptrdiff_t at, int axis) { return (load<Oct>(detail::bounds_row(node, at)) - w.o[axis]) * w.inv[axis]; };
    const std::ptrdiff_t* nr = w.near_at;
    const std::ptrdiff_t* fr = w.far_at;
    const Oct tn = max(slab(nr[0], 0), max(slab(nr[1], 1), max(slab(nr[2], 2), w.tmin8)));
    const Oct tf = min(slab(fr[0], 0), min(slab(fr[1], 1), min(slab(fr[2], 2), Oct(w.limit))));
    const auto in = tn <= tf * Oct(kSlabScale);
    const unsigned mask = Turns ? 0u : lane_bits(in);
    if constexpr (Turns) {
      w.sp = order::push(node, w.oct, tn, in, w.stack_code, w.stack_near, w.sp);
    } else if (mask != 0) {
      float nears[8];
      store(nears, tn);
      const int k0 = __builtin_ctz(mask);
      w.next = {node.child[k0], nears[k0]};
      // The same ordering as scene_kernels.cpp's enter_node(), kept apart on purpose (its header).
      const unsigned rest = mask & (mask - 1);
      if (rest != 0 && (rest & (rest - 1)) == 0) {
        // Two (the commonest several): the nearer next, the other pushed; a tie keeps the
        // slot order, as the sort below would.
        const int k1 = __builtin_ctz(rest);
        const Entry e0{node.child[k0], nears[k0]}, e1{node.child[k1], nears[k1]};
        const bool swap = nears[k1] < nears[k0];
        push(w, swap ? e0 : e1);
        w.next = swap ? e1 : e0;
      } else if (rest != 0) {
        // Several: the nearest next, the others pushed farthest first (ties keep the slot
        // order, so the order is a function of the values only).
        Entry hit[8];
        int n = 0;
        for (unsigned m = mask; m != 0; m &= m - 1) {
          const int k = __builtin_ctz(m);
          int j = n++;
          while (j > 0 && hit[j - 1].near > nears[k]) hit[j] = hit[j - 1], --j;
          hit[j] = {node.child[k], nears[k]};
        }
        for (int j = n - 1; j > 0; --j) push(w, hit[j]);
        w.next = hit[0];
      }
      if (w.next.near <= w.limit) {
        prefetch<Turns>(bvh, w.next.code);
        return true;
      }
    }
  }
  while (w.sp > 0) {
    --w.sp;
    const Entry p{w.stack_code[w.sp], w.stack_near[w.sp]};
    if (p.near > w.limit) continue;
    w.next = p;
    prefetch<Turns>(bvh, p.code);
    return true;
  }
  return false;
}

inline bool finite(float v) { return (std::bit_cast<uint32_t>(v) & 0x7f800000u) != 0x7f800000u; }

// A ray the query cannot answer: a NaN or infinite coordinate, a zero direction, tmin not
// finite or negative, tmax NaN or negative (+infinity is fine), or tmin > tmax.
inline bool valid_ray(const float o[3], const float d[3], float tmin, float tmax) {
  const bool coords = finite(o[0]) && finite(o[1]) && finite(o[2]) && finite(d[0]) && finite(d[1]) && finite(d[2]);
  const bool dir = d[0] != 0.0f || d[1] != 0.0f || d[2] != 0.0f;
  return coords && dir && finite(tmin) && tmin >= 0.0f && tmax >= tmin;
}

// Rays in flight at once: enough visits between a prefetch and its use to cover a miss to
// the last-level cache. With the branch-free push, 16 beat 8 on R2 (one thread, alternating:
// 3.5-3.8 -> 4.3-4.5 Mrays/s; 12 and 24 in between or level with 16).
constexpr int kInFlight = 16;

// Rays from one origin (a camera, a lidar) walk nearly the same nodes one after another, which
// the cache then already holds: for the closest hit they walk as packets.
inline bool one_origin(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin + 1; i < end; ++i)
    if (a.ox[i] != a.ox[begin] || a.oy[i] != a.oy[begin] || a.oz[i] != a.oz[begin]) return false;
  return true;
}

// ---- packets: rays from one origin walk the tree together (packet_walk.hpp) ----
//
// Closest hit only: an any-hit answer depends on the order of the visits, and a ray's answer
// must not depend on the rays beside it. The rays of a packet must share their origin and
// the sign of each direction component (they share near and far planes); a group that does
// not walks ray by ray.

constexpr int kPacket = packet::kRays;

struct Packet {
  float o[3];  // the rays' common origin
  Oct inv[3], tmin;
  int near_row[3], far_row[3];
  float limit[kPacket], best_t[kPacket];
  uint32_t best_id[kPacket];
  LeafRay leaf[kPacket];
  Quad tmin4[kPacket], tmax4[kPacket];
  packet::Entry stack[detail::kBvhStackSize];
};

// Sets up the packet of rays idx[0 .. n) (valid rays); false when their direction signs or
// origins differ (then they walk one by one).
inline bool start_packet(const BvhRaycastArgs& a, const std::size_t* idx, int n, Packet& P) {
  alignas(32) float lanes[3][2][kPacket];  // [axis][o, inv][ray]
  alignas(32) float tmin[kPacket];
  unsigned neg_all = 0, neg_any = 0;
  bool same_origin = true;
  for (int r = 0; r < kPacket; ++r) {
    const std::size_t i = idx[r < n ? r : 0];  // the lanes past n repeat ray 0 (never entered: mask)
    const float o[3] = {a.ox[i], a.oy[i], a.oz[i]}, d[3] = {a.dx[i], a.dy[i], a.dz[i]};
    same_origin = same_origin && o[0] == a.ox[idx[0]] && o[1] == a.oy[idx[0]] && o[2] == a.oz[idx[0]];
    unsigned neg = 0;
    for (int k = 0; k < 3; ++k) {
      const float inv = 1.0f / d[k];
      neg |= (std::bit_cast<uint32_t>(inv) >> 31) << k;
      lanes[k][0][r] = o[k], lanes[k][1][r] = inv;
    }
    neg_all = r == 0 ? neg : neg_all & neg, neg_any |= neg;
    const float t0 = a.tmin ? a.tmin[i] : 0.0f, t1 = a.tmax ? a.tmax[i] : kInf;
    tmin[r] = t0;
    P.limit[r] = t1, P.best_t[r] = kInf, P.best_id[r] = kNoTriangle;
    P.leaf[r] = leaf_ray(o, d);
    P.tmin4[r] = Quad(t0), P.tmax4[r] = Quad(t1);
  }
  if (neg_all != neg_any || !same_origin) return false;
  for (int k = 0; k < 3; ++k) {
    const int neg = int(neg_all >> k & 1u);
    P.near_row[k] = 2 * k + neg, P.far_row[k] = 2 * k + 1 - neg;
    P.o[k] = lanes[k][0][0], P.inv[k] = load<Oct>(lanes[k][1]);
  }
  P.tmin = load<Oct>(tmin);
  return true;
}

// The packet's walk from the root (packet_walk.hpp); the rays' answers in P.best_t, P.best_id.
inline void walk_packet(const BvhRaycastArgs& a, const std::size_t* idx, Packet& P, unsigned rays) {
  const Bvh8& bvh = *a.bvh;
  // bound - o is the same for every ray of the packet: once, in a float (the lane
  // expression's bits), then times each ray's 1/d.
  const auto enter = [&](const BvhNode8& node, int c, const Oct& limit, Oct& tn) {
    const auto slab = [&](int row, int axis) { return Oct(node.bounds[row][c] - P.o[axis]) * P.inv[axis]; };
    const int* nr = P.near_row;
    const int* fr = P.far_row;
    tn = max(slab(nr[0], 0), max(slab(nr[1], 1), max(slab(nr[2], 2), P.tmin)));
    const Oct tf = min(slab(fr[0], 0), min(slab(fr[1], 1), min(slab(fr[2], 2), limit)));
    return lane_bits(tn <= tf * Oct(kSlabScale));
  };
  const auto visit = [&](uint32_t code, unsigned mask) {
    const BvhLeaf4& leaf = bvh.leaves[code & ~kLeafBit];
    for (unsigned m = mask; m != 0; m &= m - 1) {
      const int r = __builtin_ctz(m);
      const Quad t = leaf_t(a, idx[r], P.leaf[r], leaf, P.tmin4[r], P.tmax4[r]);
      if (!any(t < Quad(kInf))) continue;
      float ts[4];
      store(ts, t);
      for (int k = 0; k < 4; ++k)
        if (ts[k] < P.best_t[r] || (ts[k] == P.best_t[r] && leaf.triangle[k] < P.best_id[r]))
          P.best_t[r] = ts[k], P.best_id[r] = leaf.triangle[k];
      P.limit[r] = P.best_t[r] + P.best_t[r] * kBestSlack;
    }
  };
  packet::walk(bvh.nodes.data(), P.stack, P.limit, rays, enter, visit);
}

// Rays [begin, end) taking turns, kInFlight at a time.
template <bool AnyHit> void run(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  Walk walks[kInFlight];
  std::size_t next = begin;
  // Starts the next valid ray on w (invalid ones are answered at once); false when none is left.
  const auto refill = [&](Walk& w) {
    for (; next < end; ++next) {
      const std::size_t i = next;
      const float o[3] = {a.ox[i], a.oy[i], a.oz[i]};
      const float d[3] = {a.dx[i], a.dy[i], a.dz[i]};
      const float tmin = a.tmin ? a.tmin[i] : 0.0f;
      const float tmax = a.tmax ? a.tmax[i] : kInf;
      if (valid_ray(o, d, tmin, tmax)) {
        start<true>(*a.bvh, w, i, o, d, tmin, tmax);
        ++next;
        return true;
      }
      a.t_out[i] = kInf;
      a.index_out[i] = detail::kInvalidRay;
    }
    return false;
  };
  const auto finish = [&](const Walk& w) {
    a.t_out[w.ray] = w.best_t;
    a.index_out[w.ray] = w.best_id;
  };
  int live[kInFlight], n = 0;
  for (int k = 0; k < kInFlight; ++k)
    if (refill(walks[k])) live[n++] = k;
  // While every walk is live (all but the range's last rays), a round gives each its turn.
  // The loop is not unrolled, so the visit's code is there once: with the rounds unrolled
  // eight walks at a time (a copy of the visit each), the kernel was 80 kB of code, more
  // than the core's instruction cache, and R2 ran about 10% slower on 3% more instructions
  // (its stated reason, the loop's exit mispredicted once a round, costs less). A flag per
  // walk, to run the range's last rays in this loop too, cost 2% more instructions and
  // measured slower.
  if (n == kInFlight) {
    bool all = true, dead[kInFlight] = {};
    while (all) {
#pragma GCC unroll 1
      for (Walk* w = walks; w != walks + kInFlight; ++w) {
        if (step<AnyHit, true>(a, *w)) continue;
        finish(*w);
        if (!refill(*w)) all = false, dead[w - walks] = true;
      }
    }
    n = 0;
    for (int k = 0; k < kInFlight; ++k)
      if (!dead[k]) live[n++] = k;
  }
  while (n > 0) {
    for (int j = 0; j < n;) {
      Walk& w = walks[live[j]];
      if (step<AnyHit, true>(a, w)) {
        ++j;
        continue;
      }
      finish(w);
      if (refill(w)) ++j;
      else live[j] = live[--n];
    }
  }
}

// Rays [begin, end), all from one origin, closest hit: groups of eight valid rays in ray
// order walk as packets (a group whose direction signs differ walks ray by ray).
void run_packets(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  Packet P;
  Walk w;
  std::size_t idx[kPacket];
  std::size_t next = begin;
  for (;;) {
    int n = 0;
    for (; n < kPacket && next < end; ++next) {
      const std::size_t i = next;
      const float o[3] = {a.ox[i], a.oy[i], a.oz[i]}, d[3] = {a.dx[i], a.dy[i], a.dz[i]};
      if (valid_ray(o, d, a.tmin ? a.tmin[i] : 0.0f, a.tmax ? a.tmax[i] : kInf)) {
        idx[n++] = i;
        continue;
      }
      a.t_out[i] = kInf;
      a.index_out[i] = detail::kInvalidRay;
    }
    if (n == 0) return;
    if (start_packet(a, idx, n, P)) {
      walk_packet(a, idx, P, (1u << n) - 1u);
      for (int r = 0; r < n; ++r) a.t_out[idx[r]] = P.best_t[r], a.index_out[idx[r]] = P.best_id[r];
      continue;
    }
    for (int r = 0; r < n; ++r) {
      const std::size_t i = idx[r];
      const float o[3] = {a.ox[i], a.oy[i], a.oz[i]}, d[3] = {a.dx[i], a.dy[i], a.dz[i]};
      start<false>(*a.bvh, w, i, o, d, a.tmin ? a.tmin[i] : 0.0f, a.tmax ? a.tmax[i] : kInf);
      while (step<false, false>(a, w)) {
      }
      a.t_out[i] = w.best_t;
      a.index_out[i] = w.best_id;
    }
  }
}

}  // namespace

GYRO_FLATTEN void bvh_raycast(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  // Any hit takes turns even from one origin: its answer (the first hit in the stored
  // order) must not depend on the rays beside it.
  if (!a.any_hit && one_origin(a, begin, end)) run_packets(a, begin, end);
  else a.any_hit ? run<true>(a, begin, end) : run<false>(a, begin, end);
}

}  // namespace gyro::GYRO_ARCH_NS
