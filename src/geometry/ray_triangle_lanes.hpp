// Watertight ray-triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013), double-sided, written once over a lane type.
//
// The ray is turned into the +z axis of a sheared frame: kz is the axis of largest |d|, kx
// and ky the next two in cyclic order, swapped when d[kz] < 0 so the winding is kept; the
// shear (Sx, Sy, Sz) = (d[kx], d[ky], 1) / d[kz] maps the ray onto the z axis. Corners are
// taken relative to the origin and sheared into 2D; U, V, W are the 2D edge functions of
// the edges bc, ca, ab (the barycentric weights of a, b, c times det = U + V + W).
//
// Why it is watertight: the edge function of an edge P -> Q is Qx Py - Qy Px, which depends
// only on the two sheared corners, and the same edge walked the other way, Q -> P, computes
// exactly -(Qx Py - Qy Px): the same two products subtracted the other way round, and
// round-to-nearest is symmetric. A sheared corner depends only on the corner and the ray.
// So two triangles sharing an edge see the ray on opposite sides of it, or both exactly on
// it; since 0 counts as inside (a hit is U, V, W all >= 0 or all <= 0), a ray through a
// shared edge or vertex hits at least one of the triangles around it. The paper re-evaluates
// edge functions that round to 0 in double precision to know exactly which side they are on;
// lanes are float only, so a ray within rounding of an edge may hit both triangles sharing
// it (never neither). A triangle whose sheared image has zero area (det = 0) is not hit.
//
// The per-lane axis permutation is done with selects: each lane may have its own kz.
// Degenerate triangles (collinear corners) have det = 0 up to rounding: a ray is reported to
// hit one only when it passes within rounding of its segment, and t is then between the
// corners' depths along the ray's dominant axis (U, V, W all have one sign, so t is a convex
// combination of those depths), not necessarily where the ray meets the segment. Such hits
// are kept rather than rejected: the sliver a degenerate triangle covers in float is what
// closes the mesh around it.
//
// Accuracy: on a thin triangle, or for a ray that grazes one, U, V and W cancel, and T / det
// in float can put the hit anywhere between the corners' depths. A lane that hits with
// edge functions cancelled by more than 6 bits has t and the weights computed again in
// double, lane by lane (refine_hit, below): the inside test stays the float one, so the test
// stays watertight, and the double path runs the same operations at every level and on
// every platform, so the bits stay the same everywhere.
#pragma once

#include "geometry/shapes_lanes.hpp"
#include "geometry/triangle_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

namespace detail_rt {
template <class L> using mask_of = decltype(L(0.0f) < L(0.0f));
}

/// A ray in the watertight test's sheared frame: compute once per ray, test many triangles.
template <class L> struct WatertightRay {
  V3<L> o, d;  // d: the direction as given (for the refined hits below)
  detail_rt::mask_of<L> z_is_x, z_is_y;  // kz = x, y, else z
  detail_rt::mask_of<L> swap;            // d[kz] < 0: kx and ky swapped to keep the winding
  L sx, sy, sz;                          // d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz]
};

namespace detail_rt {

// (v[kx], v[ky], v[kz]) for each lane's own permutation.
template <class L> inline V3<L> permute(const WatertightRay<L>& r, const V3<L>& v) {
  const L z = select(r.z_is_x, v.x, select(r.z_is_y, v.y, v.z));
  const L x0 = select(r.z_is_x, v.y, select(r.z_is_y, v.z, v.x));
  const L y0 = select(r.z_is_x, v.z, select(r.z_is_y, v.x, v.y));
  return {select(r.swap, y0, x0), select(r.swap, x0, y0), z};
}

/// The raw quantities of the test, for callers that need more than t (and for tests).
template <class L> struct RayTriangleTerms {
  L U, V, W;  // edge functions of bc, ca, ab: the weights of a, b, c times det
  L det;      // U + V + W
  L T;        // t * det
  L prod[6];  // the products whose differences are U, V and W
  mask_of<L> inside;  // U, V, W all >= 0 or all <= 0, and det != 0

  /// Lanes whose edge functions cancelled by more than kRefineBelow allows (below); only
  /// asked where some lane is inside, so the common miss pays nothing for it.
  mask_of<L> cancelled() const;
};

/// A hit whose edge functions cancelled by more than 6 bits (|det| below 2^-6 of the sum of
/// the magnitudes of their products) has
/// t and weights computed again in double (refine_hit): in float, T / det weights the
/// corners' depths with weights that carry the cancelled bits' rounding, so on a sliver (a
/// thin triangle) the point could land anywhere between its corners' depths (measured on
/// random slivers 1e-3 as wide as long: 1.6e-3 of the scene's size off the triangle's
/// plane, against 1.2e-7 for ordinary triangles). The inside test stays the float one, so
/// the test stays watertight. About 1 in 100 hits on ordinary triangles (grazing rays) take
/// the double path; it changes their t by an ulp or so.
inline constexpr float kRefineBelow = 0x1p-6f;

struct RefinedHit {
  float t, u, v, w;  // the weights of a, b, c
  bool ok;           // false: keep the float answer (below)
};

/// The test's t and weights in double from the float inputs (corners, origin, direction),
/// with the float test's axis permutation: the same operations at every level and on every
/// platform (double arithmetic, no contraction), so the same bits.
inline RefinedHit refine_hit(const float a[3], const float b[3], const float c[3], const float o[3],
                             const float d[3]) {
  const float ax = d[0] < 0.0f ? -d[0] : d[0], ay = d[1] < 0.0f ? -d[1] : d[1], az = d[2] < 0.0f ? -d[2] : d[2];
  const int kz = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
  if (d[kz] < 0.0f) {  // swapped to keep the winding, as watertight_ray
    const int t = kx;
    kx = ky, ky = t;
  }
  const int k[3] = {kx, ky, kz};
  double A[3], B[3], C[3];
  for (int i = 0; i < 3; ++i)
    A[i] = double(a[k[i]]) - double(o[k[i]]), B[i] = double(b[k[i]]) - double(o[k[i]]),
    C[i] = double(c[k[i]]) - double(o[k[i]]);
  const double dz = double(d[kz]);
  const double sx = double(d[kx]) / dz, sy = double(d[ky]) / dz, sz = 1.0 / dz;
  const double Ax = A[0] - sx * A[2], Ay = A[1] - sy * A[2];
  const double Bx = B[0] - sx * B[2], By = B[1] - sy * B[2];
  const double Cx = C[0] - sx * C[2], Cy = C[1] - sy * C[2];
  const double U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
  // Weights of mixed signs: a degenerate triangle, or a ray within rounding of an edge, which
  // the float test counted inside; the float answer stays (a convex combination of the
  // corners' depths: clamping the double weights instead put hits on slivers further off,
  // and the plane's crossing would leave a degenerate triangle's depth range).
  const bool one_sign = (U >= 0.0 && V >= 0.0 && W >= 0.0) || (U <= 0.0 && V <= 0.0 && W <= 0.0);
  const double det = (U + V) + W;
  if (!one_sign || !(det != 0.0)) return {0.0f, 0.0f, 0.0f, 0.0f, false};
  const double T = (U * (sz * A[2]) + V * (sz * B[2])) + W * (sz * C[2]);
  const RefinedHit h{float(T / det), float(U / det), float(V / det), float(W / det), true};
  const float sum = ((h.t - h.t) + (h.u - h.u)) + ((h.v - h.v) + (h.w - h.w));
  return sum == 0.0f ? h : RefinedHit{0.0f, 0.0f, 0.0f, 0.0f, false};
}

template <class L> inline mask_of<L> RayTriangleTerms<L>::cancelled() const {
  const L mag = ((abs(prod[0]) + abs(prod[1])) + (abs(prod[2]) + abs(prod[3]))) + (abs(prod[4]) + abs(prod[5]));
  return inside && (abs(det) < mag * L(kRefineBelow));
}

/// refine_hit for the lanes in `flag`, lane by lane (scalar): t, u, v, w replaced where it
/// succeeds. a, b, c, o and d are each lane's own inputs.
template <class L>
inline void refine_lanes(mask_of<L> flag, const V3<L>& a, const V3<L>& b, const V3<L>& c, const V3<L>& o,
                         const V3<L>& d, L& t, L& u, L& v, L& w) {
  constexpr std::size_t n = width_v<L>;
  float f[n], in[15][n], out[4][n];
  store(f, select(flag, L(1.0f), L(0.0f)));
  const V3<L>* vs[5] = {&a, &b, &c, &o, &d};
  for (int q = 0; q < 5; ++q) store(in[3 * q], vs[q]->x), store(in[3 * q + 1], vs[q]->y), store(in[3 * q + 2], vs[q]->z);
  store(out[0], t), store(out[1], u), store(out[2], v), store(out[3], w);
  for (std::size_t k = 0; k < n; ++k) {
    if (f[k] == 0.0f) continue;
    float p[5][3];
    for (int q = 0; q < 5; ++q)
      for (int j = 0; j < 3; ++j) p[q][j] = in[3 * q + j][k];
    const RefinedHit h = refine_hit(p[0], p[1], p[2], p[3], p[4]);
    if (h.ok) out[0][k] = h.t, out[1][k] = h.u, out[2][k] = h.v, out[3][k] = h.w;
  }
  t = load<L>(out[0]), u = load<L>(out[1]), v = load<L>(out[2]), w = load<L>(out[3]);
}

/// The test from the corners relative to the origin, already permuted to (kx, ky, kz): for
/// callers that permute once per ray instead of per lane (one ray against many triangles).
template <class L>
inline RayTriangleTerms<L> permuted_terms(const L& sx, const L& sy, const L& sz, const V3<L>& A, const V3<L>& B,
                                          const V3<L>& C) {
  const L ax = A.x - sx * A.z, ay = A.y - sy * A.z;
  const L bx = B.x - sx * B.z, by = B.y - sy * B.z;
  const L cx = C.x - sx * C.z, cy = C.y - sy * C.z;
  const L cb = cx * by, cyb = cy * bx, ac = ax * cy, ayc = ay * cx, ba = bx * ay, bya = by * ax;
  const L U = cb - cyb;
  const L V = ac - ayc;
  const L W = ba - bya;
  const L det = (U + V) + W;
  const L T = (U * (sz * A.z) + V * (sz * B.z)) + W * (sz * C.z);
  const L zero(0.0f);
  const auto inside = (((U >= zero) && (V >= zero) && (W >= zero)) || ((U <= zero) && (V <= zero) && (W <= zero))) &&
                      (det != zero);
  return {U, V, W, det, T, {cb, cyb, ac, ayc, ba, bya}, inside};
}

template <class L> inline RayTriangleTerms<L> ray_triangle_terms(const WatertightRay<L>& r, const TriangleL<L>& tri) {
  return permuted_terms(r.sx, r.sy, r.sz, permute(r, tri.a - r.o), permute(r, tri.b - r.o), permute(r, tri.c - r.o));
}

}  // namespace detail_rt

/// The sheared frame of a ray (axis of largest |d| as z; ties go to x, then y). A zero or
/// NaN direction makes the shear NaN, and such a ray hits nothing.
template <class L> inline WatertightRay<L> watertight_ray(const RayL<L>& ray) {
  const V3<L>& d = ray.d;
  const L ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  const auto z_is_x = (ax >= ay) && (ax >= az);
  const auto z_is_y = !z_is_x && (ay >= az);
  const L dz = select(z_is_x, d.x, select(z_is_y, d.y, d.z));
  const L dx0 = select(z_is_x, d.y, select(z_is_y, d.z, d.x));
  const L dy0 = select(z_is_x, d.z, select(z_is_y, d.x, d.y));
  const auto swap = dz < L(0.0f);
  const L dx = select(swap, dy0, dx0), dy = select(swap, dx0, dy0);
  return {ray.o, ray.d, z_is_x, z_is_y, swap, dx / dz, dy / dz, L(1.0f) / dz};
}

/// Ray (prepared by watertight_ray) against a triangle, double-sided: the t of the hit
/// (in units of |d|) if there is one with t in [tmin, tmax], else +infinity. On a hit u, v,
/// w are the barycentric weights of a, b, c at the hit (u + v + w = 1 up to rounding);
/// otherwise they are unspecified. A hit at t = -0 is returned as +0.
template <class L>
inline L ray_triangle_t(const WatertightRay<L>& r, const TriangleL<L>& tri, L tmin, L tmax, L& u, L& v, L& w) {
  const auto k = detail_rt::ray_triangle_terms(r, tri);
  L t = k.T / k.det;
  u = k.U / k.det;
  v = k.V / k.det;
  w = k.W / k.det;
  if (any(k.inside)) {
    const auto cancelled = k.cancelled();
    if (any(cancelled)) detail_rt::refine_lanes(cancelled, tri.a, tri.b, tri.c, r.o, r.d, t, u, v, w);
  }
  return select(k.inside && (t >= tmin) && (t <= tmax), t + L(0.0f), L(__builtin_inff()));
}

/// As above, without w.
template <class L> inline L ray_triangle_t(const WatertightRay<L>& r, const TriangleL<L>& tri, L tmin, L tmax, L& u, L& v) {
  L w;
  return ray_triangle_t(r, tri, tmin, tmax, u, v, w);
}

/// Ray against a triangle: t of the hit in [tmin, tmax] or +infinity; u, v the barycentric
/// weights of corners a and b at the hit (c's is 1 - u - v); unspecified on a miss.
template <class L> inline L ray_triangle_t(const RayL<L>& ray, const TriangleL<L>& tri, L tmin, L tmax, L& u, L& v) {
  return ray_triangle_t(watertight_ray(ray), tri, tmin, tmax, u, v);
}

namespace detail_rt {
// v / |v| without underflow or overflow (v is first divided by its largest component), or
// the zero vector when v is zero, infinite or NaN.
template <class L> inline V3<L> unit_or_zero(const V3<L>& v) {
  const L m = max(max(abs(v.x), abs(v.y)), abs(v.z));
  const auto usable = (m > L(0.0f)) && (m <= L(3.40282347e38f));
  const L ms = select(usable, m, L(1.0f));
  const V3<L> s(v.x / ms, v.y / ms, v.z / ms);
  const L len = sqrt(dot(s, s));
  const L zero(0.0f);
  return vselect(usable, V3<L>(s.x / len, s.y / len, s.z / len), V3<L>(zero, zero, zero));
}
}  // namespace detail_rt

/// The triangle's unit geometric normal ((b - a) x (c - a), computed with the accurate
/// cross product of triangle_lanes.hpp and normalised), flipped to face the side the ray
/// comes from: dot(normal, ray_dir) <= 0. A triangle with no normal (coincident or exactly
/// collinear corners, which a ray can still touch within rounding) gets -ray_dir / |ray_dir|,
/// the only direction that faces every origin; with a zero ray_dir as well, the zero vector.
template <class L> inline V3<L> triangle_normal_facing(const TriangleL<L>& tri, const V3<L>& ray_dir) {
  const V3<L> n = detail_rt::unit_or_zero(detail_tri::accurate_cross(tri.b - tri.a, tri.c - tri.a));
  const L zero(0.0f);
  const auto none = (n.x == zero) && (n.y == zero) && (n.z == zero);
  const V3<L> facing = vselect(dot(n, ray_dir) > zero, -n, n);
  return vselect(none, detail_rt::unit_or_zero(-ray_dir), facing);
}

}  // namespace gyro::GYRO_ARCH_NS
