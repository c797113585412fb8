// Point tests of Cookbook chapter 8 as lane templates: containment, closest points and
// signed distances for spheres, AABBs, OBBs, planes, segments and rays.
//
// One template per test over the lane type L (float: the scalar API; vfloat: one point per
// lane in the batch kernels). No branch on lane values: every case is computed and the
// answer picked with select, so lane k gives exactly the bits the float instantiation gives.
//
// Solids (sphere, AABB, OBB) are closed and filled: a point inside is its own closest point
// and its distance is 0. Surfaces (plane, segment, ray) have no interior, so contains() on
// them accepts points within a tolerance (kSurfaceAbsTolerance, kSurfaceRelTolerance).
#pragma once

#include "geometry/shapes_lanes.hpp"
#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

// A point is on a surface when its distance to it is at most
// max(kSurfaceAbsTolerance, kSurfaceRelTolerance * m), m the largest coordinate magnitude
// among the point and the surface's defining values: float rounds each of them by up to
// 2^-24 relative, so a point computed on the surface (o + t d, p - n dist, ...) lands up
// to a few ulp of m off it; 1e-6 is about 17 of those. Mirrored in gyro/point_tests.hpp.
inline constexpr float kSurfaceAbsTolerance = 1e-6f;
inline constexpr float kSurfaceRelTolerance = 1e-6f;

template <class L> inline L max_abs3(const V3<L>& v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }

// The tolerance as a squared distance, so a test needs no square root.
template <class L> inline L surface_tolerance_sq(L magnitude) {
  const L tol = max(L(kSurfaceRelTolerance) * magnitude, L(kSurfaceAbsTolerance));
  return tol * tol;
}

// v limited to [lo, hi] per component; a NaN component stays NaN (v is the second operand
// of both selects, as in gyro::clamp).
template <class L> inline V3<L> clamp3(const V3<L>& v, const V3<L>& lo, const V3<L>& hi) { return vmin(hi, vmax(lo, v)); }

// ---------------------------------------------------------------- sphere
/// Closed ball: |p - c|^2 <= r^2.
template <class L> inline auto contains(const SphereL<L>& s, const V3<L>& p) { return length_sq(p - s.c) <= s.r * s.r; }

/// p itself when inside; else the surface point towards p. The division is guarded, so the
/// centre of a radius-0 sphere gives the centre, not NaN.
template <class L> inline V3<L> closest_point(const SphereL<L>& s, const V3<L>& p) {
  const V3<L> d = p - s.c;
  const L len_sq = length_sq(d);
  const auto inside = len_sq <= s.r * s.r;
  const L k = s.r / sqrt(select(inside, L(1.0f), len_sq));
  return vselect(inside, p, s.c + d * k);
}

/// |p - c| - r: negative inside.
template <class L> inline L signed_distance(const SphereL<L>& s, const V3<L>& p) { return sqrt(length_sq(p - s.c)) - s.r; }

// ---------------------------------------------------------------- AABB
// The box's corners, each rounded once. contains, closest_point and the AABB overlaps all
// use these same bounds, so e.g. a point the box contains is its own closest point exactly.
template <class L> inline V3<L> box_lo(const AabbL<L>& b) { return b.c - b.e; }
template <class L> inline V3<L> box_hi(const AabbL<L>& b) { return b.c + b.e; }

/// lo <= p <= hi on every axis.
template <class L> inline auto contains(const AabbL<L>& b, const V3<L>& p) {
  const V3<L> lo = box_lo(b), hi = box_hi(b);
  return ((lo.x <= p.x && p.x <= hi.x) && (lo.y <= p.y && p.y <= hi.y)) && (lo.z <= p.z && p.z <= hi.z);
}

/// p clamped to the box (p itself when inside).
template <class L> inline V3<L> closest_point(const AabbL<L>& b, const V3<L>& p) { return clamp3(p, box_lo(b), box_hi(b)); }

/// Squared distance from p to the solid box; exactly 0 when contains(b, p).
template <class L> inline L distance_sq(const AabbL<L>& b, const V3<L>& p) { return length_sq(p - closest_point(b, p)); }

// ---------------------------------------------------------------- OBB
/// p - c in the box's frame: the coordinates along its unit axes.
template <class L> inline V3<L> obb_local(const ObbL<L>& b, const V3<L>& p) {
  const V3<L> d = p - b.c;
  return {dot(d, b.u[0]), dot(d, b.u[1]), dot(d, b.u[2])};
}

template <class L> inline auto obb_local_inside(const ObbL<L>& b, const V3<L>& l) {
  return (abs(l.x) <= b.e.x && abs(l.y) <= b.e.y) && abs(l.z) <= b.e.z;
}

/// |p - c along each axis| <= half extent.
template <class L> inline auto contains(const ObbL<L>& b, const V3<L>& p) { return obb_local_inside(b, obb_local(b, p)); }

/// p itself when inside (so it is exact, not p rebuilt from its local coordinates); else
/// the local coordinates clamped to the box and mapped back to world space.
template <class L> inline V3<L> closest_point(const ObbL<L>& b, const V3<L>& p) {
  const V3<L> l = obb_local(b, p);
  const V3<L> q = clamp3(l, -b.e, b.e);
  const V3<L> world = b.c + ((b.u[0] * q.x + b.u[1] * q.y) + b.u[2] * q.z);
  return vselect(obb_local_inside(b, l), p, world);
}

/// Squared distance from p to the solid box, measured in its frame (the axes are
/// orthonormal): exactly 0 when contains(b, p).
template <class L> inline L distance_sq(const ObbL<L>& b, const V3<L>& p) {
  const V3<L> l = obb_local(b, p);
  return length_sq(l - clamp3(l, -b.e, b.e));
}

// ---------------------------------------------------------------- plane
/// dot(n, p) - d: positive on the side n points to, in units of |n| (distance for unit n).
template <class L> inline L signed_distance(const PlaneL<L>& pl, const V3<L>& p) { return dot(pl.n, p) - pl.d; }

/// p moved along n onto the plane. A point far from the plane lands off it by about 2^-24
/// of its distance (p - n dist cancels), so the residual is measured again on the result
/// and removed: the answer then lies on the plane to within a few ulp of its own magnitude,
/// which is what contains() tolerates.
template <class L> inline V3<L> closest_point(const PlaneL<L>& pl, const V3<L>& p) {
  const V3<L> q = p - pl.n * signed_distance(pl, p);
  return q - pl.n * signed_distance(pl, q);
}

/// |dot(n, p) - d| within the surface tolerance of max(|d|, |p_i|).
template <class L> inline auto contains(const PlaneL<L>& pl, const V3<L>& p) {
  const L dist = signed_distance(pl, p);
  return dist * dist <= surface_tolerance_sq(max(max_abs3(p), abs(pl.d)));
}

// ---------------------------------------------------------------- segment
/// The point of segment ab nearest to p; a at t <= 0, b exactly at t >= 1. A zero-length
/// segment (a == b) gives a.
template <class L> inline V3<L> closest_point(const SegmentL<L>& s, const V3<L>& p) {
  const V3<L> ab = s.b - s.a;
  const L len_sq = length_sq(ab);
  const auto degenerate = !(len_sq > L(0.0f));
  const L t = select(degenerate, L(0.0f), dot(p - s.a, ab) / select(degenerate, L(1.0f), len_sq));
  const L tc = min(L(1.0f), max(L(0.0f), t));
  return vselect(tc >= L(1.0f), s.b, s.a + ab * tc);
}

/// The distance from p to the segment within the surface tolerance of the largest
/// coordinate of p, a and b.
template <class L> inline auto contains(const SegmentL<L>& s, const V3<L>& p) {
  const L m = max(max_abs3(p), max(max_abs3(s.a), max_abs3(s.b)));
  return length_sq(p - closest_point(s, p)) <= surface_tolerance_sq(m);
}

// ---------------------------------------------------------------- ray
/// The point of the ray o + t d (t >= 0) nearest to p; o when p is behind it or d is zero.
template <class L> inline V3<L> closest_point(const RayL<L>& r, const V3<L>& p) {
  const L len_sq = length_sq(r.d);
  const auto degenerate = !(len_sq > L(0.0f));
  const L t = select(degenerate, L(0.0f), dot(p - r.o, r.d) / select(degenerate, L(1.0f), len_sq));
  return r.o + r.d * max(L(0.0f), t);
}

/// The distance from p to the ray within the surface tolerance of the largest coordinate
/// of p and o.
template <class L> inline auto contains(const RayL<L>& r, const V3<L>& p) {
  const L m = max(max_abs3(p), max_abs3(r.o));
  return length_sq(p - closest_point(r, p)) <= surface_tolerance_sq(m);
}

}  // namespace gyro::GYRO_ARCH_NS
