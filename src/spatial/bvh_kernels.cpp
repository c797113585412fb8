// bvh_raycast at this translation unit's SIMD level: each ray walks the 8-wide BVH alone,
// testing a node's eight child boxes in one 8-wide lane (Oct: one AVX register, or two
// Quads) and a leaf's four triangles in one 4-wide lane (Quad).
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
// only, so each level (the scalar one runs Quad as four floats) gives the same bits.
#include "geometry/ray_triangle_lanes.hpp"
#include "spatial/bvh_batch.hpp"

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
constexpr float kBestSlack = 0x1p-16f;

struct Entry {
  uint32_t code;
  float near;
};

// Only t of ray_triangle_t (the same expressions, so the same bits): the traversal needs no
// barycentrics, and the caller recomputes them for the one triangle that wins.
inline Quad leaf_t(const WatertightRay<Quad>& r, const TriangleL<Quad>& tri, Quad tmin, Quad tmax) {
  const auto k = detail_rt::ray_triangle_terms(r, tri);
  const Quad t = k.T / k.det;
  return select(k.inside && (t >= tmin) && (t <= tmax), t + Quad(0.0f), Quad(kInf));
}

// Asks for every line of a child that was pushed: by the time it is popped its lines are on
// their way.
inline void prefetch(const Bvh8& bvh, uint32_t code) {
  const char* p = code & kLeafBit ? reinterpret_cast<const char*>(&bvh.leaves[code & ~kLeafBit])
                                  : reinterpret_cast<const char*>(&bvh.nodes[code]);
  const std::size_t size = code & kLeafBit ? sizeof(BvhLeaf4) : sizeof(BvhNode8);
  for (std::size_t line = 0; line < size; line += 64) __builtin_prefetch(p + line);
}

template <bool AnyHit>
inline void trace(const Bvh8& bvh, const float o[3], const float d[3], float tmin, float tmax, float& out_t,
                  uint32_t& out_id) {
  const float inv[3] = {1.0f / d[0], 1.0f / d[1], 1.0f / d[2]};
  int near_row[3], far_row[3];
  for (int a = 0; a < 3; ++a) {
    const int neg = int(std::bit_cast<uint32_t>(inv[a]) >> 31);
    near_row[a] = 2 * a + neg, far_row[a] = 2 * a + 1 - neg;
  }
  const Oct qo[3] = {Oct(o[0]), Oct(o[1]), Oct(o[2])};
  const Oct qi[3] = {Oct(inv[0]), Oct(inv[1]), Oct(inv[2])};
  const Oct otmin(tmin);
  const Quad qtmin(tmin), qtmax(tmax);
  const WatertightRay<Quad> wr =
      watertight_ray(RayL<Quad>{V3<Quad>(Quad(o[0]), Quad(o[1]), Quad(o[2])), V3<Quad>(Quad(d[0]), Quad(d[1]), Quad(d[2]))});

  float best_t = kInf, limit = tmax;
  uint32_t best_id = kNoTriangle;
  Entry stack[detail::kBvhStackSize];
  int sp = 0;
  stack[sp++] = {0, tmin};
  Entry e;
  while (sp > 0) {
    e = stack[--sp];
  visit:
    if (e.near > limit) continue;
    if (e.code & kLeafBit) {
      const BvhLeaf4& leaf = bvh.leaves[e.code & ~kLeafBit];
      const auto row = [&](int k) { return load<Quad>(leaf.corner[k]); };
      const TriangleL<Quad> tri{{row(0), row(1), row(2)}, {row(3), row(4), row(5)}, {row(6), row(7), row(8)}};
      const Quad t = leaf_t(wr, tri, qtmin, qtmax);
      if (!any(t < Quad(kInf))) continue;  // most leaves a ray enters it does not hit
      float ts[4];
      store(ts, t);
      for (int k = 0; k < 4; ++k) {
        if (ts[k] < best_t || (ts[k] == best_t && leaf.triangle[k] < best_id)) best_t = ts[k], best_id = leaf.triangle[k];
      }
      if constexpr (AnyHit) break;
      limit = best_t + best_t * kBestSlack;
      continue;
    }
    const BvhNode8& node = bvh.nodes[e.code];
    const auto slab = [&](int row, int axis) { return (load<Oct>(node.bounds[row]) - qo[axis]) * qi[axis]; };
    const Oct olimit(limit);
    const Oct tn = max(slab(near_row[0], 0), max(slab(near_row[1], 1), max(slab(near_row[2], 2), otmin)));
    const Oct tf = min(slab(far_row[0], 0), min(slab(far_row[1], 1), min(slab(far_row[2], 2), olimit)));
    const auto entered = tn <= tf + abs(tf) * Oct(kSlabSlack);
    const unsigned mask = lane_bits(entered);
    if (mask == 0) continue;
    float nears[8];
    store(nears, tn);
    if ((mask & (mask - 1)) == 0) {  // one child entered, the common case: descend at once
      const int k = __builtin_ctz(mask);
      e = {node.child[k], nears[k]};
      goto visit;
    }
    const unsigned rest = mask & (mask - 1);
    if ((rest & (rest - 1)) == 0) {  // two: the nearer next (ties: the lower slot), the other pushed
      const int k0 = __builtin_ctz(mask), k1 = __builtin_ctz(rest);
      const bool swap = nears[k1] < nears[k0];
      const int kn = swap ? k1 : k0, kf = swap ? k0 : k1;
      const uint32_t c = node.child[kf];
      prefetch(bvh, c);
      stack[sp++] = {c, nears[kf]};
      e = {node.child[kn], nears[kn]};
      goto visit;
    }
    // Several: visit the nearest next and push the others farthest first (ties keep the
    // slot order, so the order is a function of the values only).
    Entry hit[8];
    int n = 0;
    for (unsigned m = mask; m != 0; m &= m - 1) {
      const int k = __builtin_ctz(m);
      int j = n++;
      while (j > 0 && hit[j - 1].near > nears[k]) hit[j] = hit[j - 1], --j;
      hit[j] = {node.child[k], nears[k]};
    }
    for (int j = n - 1; j > 0; --j) {
      prefetch(bvh, hit[j].code);
      stack[sp++] = hit[j];
    }
    e = hit[0];
    goto visit;
  }
  out_t = best_t;
  out_id = best_id;
}

inline bool finite(float v) { return (std::bit_cast<uint32_t>(v) & 0x7f800000u) != 0x7f800000u; }

// A ray the query cannot answer: a NaN or infinite coordinate, a zero direction, tmin not
// finite or negative, tmax NaN or negative (+infinity is fine), or tmin > tmax.
inline bool valid_ray(const float o[3], const float d[3], float tmin, float tmax) {
  const bool coords = finite(o[0]) && finite(o[1]) && finite(o[2]) && finite(d[0]) && finite(d[1]) && finite(d[2]);
  const bool dir = d[0] != 0.0f || d[1] != 0.0f || d[2] != 0.0f;
  return coords && dir && finite(tmin) && tmin >= 0.0f && tmax >= tmin;
}

template <bool AnyHit> void run(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const float o[3] = {a.ox[i], a.oy[i], a.oz[i]};
    const float d[3] = {a.dx[i], a.dy[i], a.dz[i]};
    const float tmin = a.tmin ? a.tmin[i] : 0.0f;
    const float tmax = a.tmax ? a.tmax[i] : kInf;
    if (!valid_ray(o, d, tmin, tmax)) {
      a.t_out[i] = kInf;
      a.index_out[i] = detail::kInvalidRay;
      continue;
    }
    trace<AnyHit>(*a.bvh, o, d, tmin, tmax, a.t_out[i], a.index_out[i]);
  }
}

}  // namespace

GYRO_FLATTEN void bvh_raycast(const BvhRaycastArgs& a, std::size_t begin, std::size_t end) {
  a.any_hit ? run<true>(a, begin, end) : run<false>(a, begin, end);
}

}  // namespace gyro::GYRO_ARCH_NS
