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
#pragma once

#include "geometry/shapes_lanes.hpp"
#include "geometry/triangle_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

namespace detail_rt {
template <class L> using mask_of = decltype(L(0.0f) < L(0.0f));
}

/// A ray in the watertight test's sheared frame: compute once per ray, test many triangles.
template <class L> struct WatertightRay {
  V3<L> o;
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
  mask_of<L> inside;  // U, V, W all >= 0 or all <= 0, and det != 0
};

/// The test from the corners relative to the origin, already permuted to (kx, ky, kz): for
/// callers that permute once per ray instead of per lane (one ray against many triangles).
template <class L>
inline RayTriangleTerms<L> permuted_terms(const L& sx, const L& sy, const L& sz, const V3<L>& A, const V3<L>& B,
                                          const V3<L>& C) {
  const L ax = A.x - sx * A.z, ay = A.y - sy * A.z;
  const L bx = B.x - sx * B.z, by = B.y - sy * B.z;
  const L cx = C.x - sx * C.z, cy = C.y - sy * C.z;
  const L U = cx * by - cy * bx;
  const L V = ax * cy - ay * cx;
  const L W = bx * ay - by * ax;
  const L det = (U + V) + W;
  const L T = (U * (sz * A.z) + V * (sz * B.z)) + W * (sz * C.z);
  const L zero(0.0f);
  const auto inside = (((U >= zero) && (V >= zero) && (W >= zero)) || ((U <= zero) && (V <= zero) && (W <= zero))) &&
                      (det != zero);
  return {U, V, W, det, T, inside};
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
  return {ray.o, z_is_x, z_is_y, swap, dx / dz, dy / dz, L(1.0f) / dz};
}

/// Ray (prepared by watertight_ray) against a triangle, double-sided: the t of the hit
/// (in units of |d|) if there is one with t in [tmin, tmax], else +infinity. On a hit u, v,
/// w are the barycentric weights of a, b, c at the hit (u + v + w = 1 up to rounding);
/// otherwise they are unspecified. A hit at t = -0 is returned as +0.
template <class L>
inline L ray_triangle_t(const WatertightRay<L>& r, const TriangleL<L>& tri, L tmin, L tmax, L& u, L& v, L& w) {
  const auto k = detail_rt::ray_triangle_terms(r, tri);
  const L t = k.T / k.det;
  u = k.U / k.det;
  v = k.V / k.det;
  w = k.W / k.det;
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
