// scene_raycast at this translation unit's SIMD level: rays through the models' 8-wide BVH
// (or the octree's node form, octree_bvh.hpp), with a node's eight child boxes tested in one
// 8-wide lane (Oct) and each leaf's one model by the scalar raycast's own expressions
// (ray_sphere_t, ray_obb_t, or the scene's exact test for a mesh), so their bits.
//
// Closest hit, rays from many origins: eight rays take turns, one visit each, and a node's
// entered children are pushed in the node's stored order for the ray's octant, without a
// branch (bvh_order.hpp). Each is needed for the other: alone, the branch-free push's chain
// of dependent instructions sat on the walk's critical path (R1 3.4 against the sorted
// walk's 3.8 Mrays/s), and turns with the sorted push paid its mispredicted branches plus
// the turns' bookkeeping (3.0); together, R1 went from 3.8 to 5.2 Mrays/s (AVX-512, one
// thread), and to about 6 with a visit popping its own entry and the turns unrolled. Only
// in a large tree (SceneRaycastArgs::prefetch) does a visit pop the next entry and prefetch
// its lines, as the mesh kernel (bvh_kernels.cpp) does. Any hit walks the same way (R1's
// rays: 3.7 Mrays/s sorted and alone, 6.3 ordered in turns); its answer is the first hit in
// the stored order, whatever the rays beside it.
//
// Exactness (scene.cpp's header): boxes are widened by the ray's pad, a box whose exit
// precedes its entry by up to 2^-18 of the exit still counts as entered, a NaN slab product
// (0 * inf) constrains nothing (`t > tn ? t : tn` keeps tn), subtrees entered beyond the
// best t by 2^-16 of it are skipped, and ties go to the lowest id index. Every operation is
// elementwise and the visiting order depends on float values only, so every level gives the
// brute-force loop's bits, and a ray's answer does not depend on the rays beside it.
// The single walk mirrors bvh_kernels.cpp's instead of sharing helpers with it: factored
// out, the mesh kernel ran 7 to 11% more instructions (callgrind, R2); even the child
// ordering alone (one inline function for both, same results) cost R1 8.6% (27.9 M ->
// 30.3 M instructions on 20k rays, AVX2), so enter_node()'s ordering block is written
// twice. Measured again after the register cursor (walk_alone): a shared template taking
// values in and out (so no aliasing through references) still ran 24.8 M -> 26.3 M
// instructions and was slower in 5 of 6 alternating R1 runs (median -6%). Rays from one
// origin (closest hit) walk in packets of eight through the walk both kernels share
// (packet_walk.hpp; sharing it cost the LIDAR packets 2% more instructions).
// Any hit: the walk stops at the first hit, the nodes taken in their stored order (a leaf
// is one model), so the model it names is the same at every level, thread
// count and prefetch mode (another tree, the octree's, may name another; gyro/scene.hpp
// promises no more than that).
#include "geometry/ray_lanes.hpp"
#include "spatial/bvh_order.hpp"
#include "spatial/packet_walk.hpp"
#include "spatial/scene_rays.hpp"

#include <bit>
#include <utility>

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::BvhNode8;
using detail::kLeafBit;
using detail::SceneLeaf;

constexpr float kInf = __builtin_inff();
constexpr float kSlabSlack = 0x1p-18f;
// A box counts as entered where tn <= tf * kSlabScale: the same verdict as tn <= tf +
// |tf| * kSlabSlack in one multiply instead of three operations. For tf >= 0 both round the
// same exact value tf * (1 + slack) once (tf * slack, a power of two, is exact above the
// subnormals, and 1 + slack is a float); for tf < 0 both sides are negative and tn >= tmin
// >= 0, so neither enters.
constexpr float kSlabScale = 1.0f + kSlabSlack;
constexpr float kBestSlack = 0x1p-16f;
constexpr uint32_t kNone = 0xFFFFFFFFu;
constexpr std::size_t kStackSize = 7 * detail::kBvhMaxDepth + 8 + order::kOverhang;

constexpr int kInFlight = 8;

struct Entry {
  uint32_t code;
  float near;
};

struct Walk {
  Oct o_near[3], o_far[3], inv[3], tmin8;  // the origin moved by the pad: o_near[k] - bound is the widened slab
  RayL<float> ray1;
  RayDd<float> dd1;
  float tmin1, tmax1;
  std::ptrdiff_t near_at[3], far_at[3];  // the slab rows' offsets in BvhNode8::bounds, in bytes (bounds_row)
  unsigned oct;
  float tmax, best_t, limit;
  uint32_t best_key, best_item;
  uint32_t mask;  // the ray's layers
  std::size_t ray;
  Entry next;
  int sp;
  uint32_t stack_code[kStackSize];  // two columns, so an ordered push stores each from one register (bvh_order.hpp)
  float stack_near[kStackSize];
};

inline void push(Walk& w, int& sp, const Entry& e) { w.stack_code[sp] = e.code, w.stack_near[sp] = e.near, ++sp; }

// Only in a tree beyond the cache: in one the cache holds the prefetches are only
// instructions (a tenth of the walk's, R1 on 10^4 spheres).
template <bool Fetch> inline void prefetch(const SceneRaycastArgs& a, uint32_t code) {
  if constexpr (Fetch) detail::prefetch_visit(a.nodes, a.leaves, code);
}

// The pad with the sign of a negative direction (neg = 1): o - pad is o + (-pad) to the bit,
// so the near and far origins need no branch (as ternaries they compiled to one,
// mispredicted 1.5 times per random ray).
inline float signed_pad(float pad, int neg) {
  return std::bit_cast<float>(std::bit_cast<uint32_t>(pad) ^ (uint32_t(neg) << 31));
}

// The limit: the best t plus its slack, never beyond tmax (any hit: tmax).
inline float limit_of(const Walk& w, bool any_hit) {
  if (any_hit || !(w.best_t < kInf)) return w.tmax;
  const float l = w.best_t + w.best_t * kBestSlack;
  return l < w.tmax ? l : w.tmax;
}

// OnStack: the root goes onto the stack (step() without Fetch pops every visit's entry);
// else it is w.next (step() with Fetch, and walk_alone()).
template <bool OnStack, bool Fetch> inline void start(const SceneRaycastArgs& a, Walk& w, std::size_t i) {
  const float o[3] = {a.ox[i], a.oy[i], a.oz[i]}, d[3] = {a.dx[i], a.dy[i], a.dz[i]};
  const float pad = a.pad[i];
  w.oct = 0;
  for (int k = 0; k < 3; ++k) {
    const float inv = 1.0f / d[k];
    const int neg = int(std::bit_cast<uint32_t>(inv) >> 31);
    // The near plane of a slab is the box's low side widened down (high side widened up
    // when the direction is negative): the origin moves the other way, once per ray, so a
    // plane costs a subtraction and a product (scene.cpp's header: a rounding of the origin
    // is far inside the pads).
    const float sp = signed_pad(pad, neg);
    w.near_at[k] = detail::bounds_offset(k, neg), w.far_at[k] = detail::bounds_offset(k, 1 - neg);
    w.oct |= unsigned(neg) << k;
    w.o_near[k] = Oct(o[k] + sp), w.o_far[k] = Oct(o[k] - sp);
    w.inv[k] = Oct(inv);
  }
  const float tmin = a.tmin ? a.tmin[i] : 0.0f;
  w.tmax = a.tmax ? a.tmax[i] : kInf;
  w.tmin8 = Oct(tmin), w.tmin1 = tmin, w.tmax1 = w.tmax;
  w.ray1 = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
  w.dd1 = ray_dd(w.ray1.d);
  w.best_t = a.best_t[i], w.best_key = a.best_key[i], w.best_item = kNone;
  w.ray = i;
  w.mask = a.mask ? a.mask[i] : 0xFFFFFFFFu;
  w.next = {0, tmin};
  w.stack_code[0] = 0, w.stack_near[0] = tmin;
  w.sp = OnStack ? 1 : 0;
  prefetch<Fetch>(a, 0);
}

// Takes (t, key) if it beats the best: the smaller t, then the smaller id index.
inline bool take(Walk& w, float t, uint32_t key, uint32_t item) {
  if (t < w.best_t || (t == w.best_t && t < kInf && key < w.best_key)) {
    w.best_t = t, w.best_key = key, w.best_item = item;
    return true;
  }
  return false;
}

// Pops the next entry entered within the limit; false when the walk is over.
template <bool Fetch> inline bool next_entry(const SceneRaycastArgs& a, Walk& w) {
  while (w.sp > 0) {
    --w.sp;
    const Entry p{w.stack_code[w.sp], w.stack_near[w.sp]};
    if (p.near > w.limit) continue;
    w.next = p;
    prefetch<Fetch>(a, p.code);
    return true;
  }
  return false;
}

// A leaf's model for one ray: its best and limit updated. True when an any-hit walk has
// found its hit (the walk is over). One model, tested by the scalar raycast's expressions
// (lanes.hpp: a lane computes what a float does, so the bits are the same).
template <bool AnyHit> inline bool visit_leaf(const SceneRaycastArgs& a, Walk& w, const SceneLeaf& leaf) {
  if ((leaf.layers & w.mask) == 0) return false;  // a layer the ray does not see
  float t;
  if (leaf.box_block == detail::kExactLeaf) {
    t = a.exact(a.ctx, w.ray, leaf.item, w.best_t, w.best_key, limit_of(w, AnyHit));
  } else if (leaf.box_block != detail::kNoItem) {
    const float* v = a.boxes[leaf.box_block].obb;
    const auto v3 = [&](int r) { return V3<float>{v[r], v[r + 1], v[r + 2]}; };
    const ObbL<float> b{v3(0), v3(3), {v3(6), v3(9), v3(12)}};
    t = ray_obb_t(w.ray1, b, w.tmin1, w.tmax1);
  } else {
    // Most spheres a ray's walk reaches it does not hit: nothing more to do there.
    const SphereL<float> s{{leaf.sphere[0], leaf.sphere[1], leaf.sphere[2]}, leaf.sphere[3]};
    t = ray_sphere_t(w.ray1, w.dd1, s, w.tmin1, w.tmax1);
  }
  if (!(t < kInf)) return false;
  take(w, t, leaf.key, leaf.item);
  if constexpr (AnyHit) return true;
  w.limit = limit_of(w, AnyHit);
  return false;
}

// Tests a node's child boxes: each one's entry in tn, lane k true where slot k is entered
// within the limit.
inline auto entered(const Walk& w, const BvhNode8& node, Oct& tn) {
  tn = w.tmin8;
  Oct tf = Oct(w.limit);
  for (int k = 0; k < 3; ++k) {  // x, y, z, each slab value first, as RayWalk::enter (scene.cpp)
    const Oct t0 = (load<Oct>(detail::bounds_row(node, w.near_at[k])) - w.o_near[k]) * w.inv[k];
    const Oct t1 = (load<Oct>(detail::bounds_row(node, w.far_at[k])) - w.o_far[k]) * w.inv[k];
    tn = max(t0, tn);  // t0 > tn ? t0 : tn (lanes.hpp), one instruction on x86
    tf = min(t1, tf);
  }
  // An empty slot's (+inf, -inf) box gives tn = +inf for any valid ray, so it never passes.
  return (tn <= tf * Oct(kSlabScale)) && (tn < Oct(kInf));
}

// The sorted walk's visit (walk_alone): pushes the entered children but the nearest onto the
// stack at sp and makes that one `next`; true when it lies within the limit.
inline bool enter_node(Walk& w, const BvhNode8& node, Entry& next, int& sp) {
  Oct tn;
  const unsigned mask = lane_bits(entered(w, node, tn));
  if (mask == 0) return false;
  float nears[8];
  store(nears, tn);
  const int k0 = __builtin_ctz(mask);
  next = {node.child[k0], nears[k0]};
  const unsigned rest = mask & (mask - 1);
  if (rest != 0 && (rest & (rest - 1)) == 0) {
    // Two (the commonest several): the nearer next, the other pushed; a tie keeps the slot
    // order, as the sort below would.
    const int k1 = __builtin_ctz(rest);
    const Entry e0{node.child[k0], nears[k0]}, e1{node.child[k1], nears[k1]};
    const bool swap = nears[k1] < nears[k0];
    push(w, sp, swap ? e0 : e1);
    next = swap ? e1 : e0;
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
    for (int j = n - 1; j > 0; --j) push(w, sp, hit[j]);
    next = hit[0];
  }
  return next.near <= w.limit;
}

// One visit of a ray taking turns; false when its walk is over (its stack is empty, or an
// any-hit walk found its hit). Children are pushed in the node's stored order
// (bvh_order.hpp), for the closest hit and any hit alike. With Fetch, a visit ends by
// popping the next entry and prefetching its lines (w.next); without, a visit pops its own.
// Both visit the same entries in the same order, so an any-hit walk reports the same hit.
template <bool AnyHit, bool Fetch> inline bool step(const SceneRaycastArgs& a, Walk& w) {
  // Visits `code` with the stack at depth sp; false when an any-hit walk found its hit.
  const auto visit = [&](uint32_t code, int& sp) {
    if (code & kLeafBit) return !visit_leaf<AnyHit>(a, w, a.leaves[code & ~kLeafBit]);
    const BvhNode8& node = a.nodes[code];
    Oct tn;
    sp = order::push(node, w.oct, tn, entered(w, node, tn), w.stack_code, w.stack_near, sp);
    return true;
  };
  if constexpr (Fetch) {
    return visit(w.next.code, w.sp) && next_entry<Fetch>(a, w);
  } else {
    int sp = w.sp;
    do {
      if (sp == 0) return false;
      --sp;
    } while (w.stack_near[sp] > w.limit);
    const bool going = visit(w.stack_code[sp], sp);
    w.sp = sp;
    return going;
  }
}

// One ray at a time, children sorted by entry distance (closest hit only: the packets'
// fallback, rays from one origin whose direction signs differ). Alone, the sorted walk's
// branches are predicted ahead, where the ordered push's chain of dependent instructions
// would sit on the walk's critical path. The cursor (the next entry, the stack depth) stays
// in locals, in registers; as Walk's fields it went through memory, and the store-to-load
// forwarding sat on every visit's chain of dependent instructions.
inline void walk_alone(const SceneRaycastArgs& a, Walk& w) {
  Entry e = w.next;
  int sp = 0;
  for (;;) {
    if (e.code & kLeafBit) {
      visit_leaf<false>(a, w, a.leaves[e.code & ~kLeafBit]);
    } else if (enter_node(w, a.nodes[e.code], e, sp)) {
      continue;
    }
    do {  // next_entry()'s pops
      if (sp == 0) return;
      --sp;
      e = {w.stack_code[sp], w.stack_near[sp]};
    } while (e.near > w.limit);
  }
}

// Rays from one origin (a camera, a lidar) walk nearly the same nodes one after another: for
// the closest hit they walk as packets.
inline bool one_origin(const SceneRaycastArgs& a, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin + 1; i < end; ++i)
    if (a.ox[i] != a.ox[begin] || a.oy[i] != a.oy[begin] || a.oz[i] != a.oz[begin]) return false;
  return true;
}

template <bool AnyHit, bool Fetch> void run(const SceneRaycastArgs& a, std::size_t begin, std::size_t end) {
  Walk walks[kInFlight];
  int live[kInFlight], n = 0;
  std::size_t next = begin;
  const auto refill = [&](Walk& w) {
    for (; next < end; ++next) {
      if (!a.walk[next]) continue;
      start<!Fetch, Fetch>(a, w, next);
      w.limit = limit_of(w, AnyHit);
      ++next;
      return true;
    }
    return false;
  };
  const auto finish = [&](const Walk& w) {
    a.best_t[w.ray] = w.best_t;
    a.best_key[w.ray] = w.best_key;
    if (w.best_item != kNone) a.best_item[w.ray] = w.best_item;
  };
  for (int k = 0; k < kInFlight; ++k)
    if (refill(walks[k])) live[n++] = k;
  // While every walk is live (all but the range's last rays), a round gives each its turn,
  // unrolled: the loop over the live walks mispredicted its exit once a round (R1: 1.9
  // mispredicted branches per ray; unrolled, 5.7 -> 6.2 Mrays/s, AVX-512, one thread).
  if (n == kInFlight) {
    bool all = true, dead[kInFlight] = {};
    const auto turn = [&](int k) {
      if (step<AnyHit, Fetch>(a, walks[k])) return;
      finish(walks[k]);
      if (!refill(walks[k])) all = false, dead[k] = true;
    };
    while (all) [&]<int... K>(std::integer_sequence<int, K...>) { (turn(K), ...); }(std::make_integer_sequence<int, kInFlight>{});
    n = 0;
    for (int k = 0; k < kInFlight; ++k)
      if (!dead[k]) live[n++] = k;
  }
  while (n > 0) {
    for (int j = 0; j < n;) {
      Walk& w = walks[live[j]];
      if (step<AnyHit, Fetch>(a, w)) {
        ++j;
        continue;
      }
      finish(w);
      if (refill(w)) ++j;
      else live[j] = live[--n];
    }
  }
}

// ---- packets: rays from one origin walk the tree together (packet_walk.hpp) ----
//
// Closest hit only (an any-hit answer depends on the visiting order); a leaf's models are
// tested ray by ray by visit_leaf, as in the single walk; a group whose origins or direction
// signs differ walks ray by ray.

constexpr int kPacket = packet::kRays;

struct Packet {
  float o_near[3], o_far[3];
  int near_row[3], far_row[3];
  Oct inv[3], tmin;
  float limit[kPacket];
  packet::Entry stack[kStackSize];
};

// The packet of the rays started in W[0 .. n); false when their origins or the signs of
// their directions differ.
inline bool start_packet(const SceneRaycastArgs& a, const Walk* W, int n, Packet& P) {
  alignas(32) float inv[3][kPacket], tmin[kPacket];
  const std::size_t i0 = W[0].ray;
  unsigned neg_all = 7, neg_any = 0;
  for (int r = 0; r < kPacket; ++r) {
    const std::size_t i = W[r < n ? r : 0].ray;  // lanes past n repeat ray 0 (never entered: mask)
    if (a.ox[i] != a.ox[i0] || a.oy[i] != a.oy[i0] || a.oz[i] != a.oz[i0]) return false;
    unsigned neg = 0;
    const float d[3] = {a.dx[i], a.dy[i], a.dz[i]};
    for (int k = 0; k < 3; ++k) {
      inv[k][r] = 1.0f / d[k];
      neg |= (std::bit_cast<uint32_t>(inv[k][r]) >> 31) << k;
    }
    neg_all &= neg, neg_any |= neg;
    tmin[r] = a.tmin ? a.tmin[i] : 0.0f;
    P.limit[r] = W[r < n ? r : 0].limit;
  }
  if (neg_all != neg_any) return false;
  const float o[3] = {a.ox[i0], a.oy[i0], a.oz[i0]};
  const float pad = a.pad[i0];
  for (int k = 0; k < 3; ++k) {
    const int neg = int(neg_all >> k & 1u);
    P.near_row[k] = 2 * k + neg, P.far_row[k] = 2 * k + 1 - neg;
    const float sp = signed_pad(pad, neg);
    P.o_near[k] = o[k] + sp, P.o_far[k] = o[k] - sp;
    P.inv[k] = load<Oct>(inv[k]);
  }
  P.tmin = load<Oct>(tmin);
  return true;
}

// The packet's walk from the root (packet_walk.hpp); the rays' answers in W.
inline void walk_packet(const SceneRaycastArgs& a, Walk* W, unsigned rays, Packet& P) {
  // bound - (o moved by the pad) is the same for every ray of the packet: once, in a float
  // (the lane expression's bits), then times each ray's 1/d.
  const auto enter = [&](const BvhNode8& node, int c, const Oct& limit, Oct& tn) {
    tn = P.tmin;
    Oct tf = limit;
    for (int k = 0; k < 3; ++k) {  // the single walk's order: x, y, z, each slab value first
      const Oct t0 = Oct(node.bounds[P.near_row[k]][c] - P.o_near[k]) * P.inv[k];
      const Oct t1 = Oct(node.bounds[P.far_row[k]][c] - P.o_far[k]) * P.inv[k];
      tn = max(t0, tn);  // t0 > tn ? t0 : tn (lanes.hpp), one instruction on x86
      tf = min(t1, tf);
    }
    return lane_bits((tn <= tf * Oct(kSlabScale)) && (tn < Oct(kInf)));
  };
  const auto visit = [&](uint32_t code, unsigned mask) {
    const SceneLeaf& leaf = a.leaves[code & ~kLeafBit];
    for (unsigned m = mask; m != 0; m &= m - 1) {
      const int r = __builtin_ctz(m);
      visit_leaf<false>(a, W[r], leaf);
      P.limit[r] = W[r].limit;
    }
  };
  packet::walk(a.nodes, P.stack, P.limit, rays, enter, visit);
}

// Rays [begin, end), all from one origin, closest hit: groups of eight rays to walk, in ray
// order, as packets (a group whose direction signs differ walks ray by ray).
void run_packets(const SceneRaycastArgs& a, std::size_t begin, std::size_t end) {
  Packet P;
  Walk W[kPacket];
  std::size_t next = begin;
  for (;;) {
    int n = 0;
    for (; n < kPacket && next < end; ++next) {
      if (!a.walk[next]) continue;
      start<false, false>(a, W[n], next);
      W[n].limit = limit_of(W[n], false);
      ++n;
    }
    if (n == 0) return;
    if (start_packet(a, W, n, P)) {
      walk_packet(a, W, (1u << n) - 1u, P);
    } else {
      for (int r = 0; r < n; ++r) walk_alone(a, W[r]);
    }
    for (int r = 0; r < n; ++r) {
      a.best_t[W[r].ray] = W[r].best_t;
      a.best_key[W[r].ray] = W[r].best_key;
      if (W[r].best_item != kNone) a.best_item[W[r].ray] = W[r].best_item;
    }
  }
}

}  // namespace

GYRO_FLATTEN void scene_raycast(const SceneRaycastArgs& a, std::size_t begin, std::size_t end) {
  const bool origin = one_origin(a, begin, end);
  if (!a.any_hit && origin) run_packets(a, begin, end);
  else if (a.any_hit) a.prefetch ? run<true, true>(a, begin, end) : run<true, false>(a, begin, end);
  else a.prefetch ? run<false, true>(a, begin, end) : run<false, false>(a, begin, end);
}

}  // namespace gyro::GYRO_ARCH_NS
