// Overlap tests of Cookbook chapter 9 as lane templates, for every pair of spheres, AABBs,
// OBBs and planes, taking the pair in the canonical order sphere < aabb < obb < plane.
//
// Each returns a mask (bool for float, vmask for SIMD lanes), true where the shapes overlap
// or touch. No branch on lane values, so lane k gives exactly the bits of the float
// instantiation; the batch kernels and the scalar API (gyro/overlap.hpp) run these.
//
// Exactness where it is cheap: the sphere-box tests measure the distance in the box's
// frame, where a centre inside the box gives exactly 0, and AABBs are compared through the
// rounded bounds contains() uses. So a sphere whose centre a solid contains overlaps it, an
// AABB whose centre another AABB contains overlaps it, and sphere-sphere, AABB-AABB and
// plane-plane give the same bits in both argument orders (all checked in the tests).
#pragma once

#include "geometry/obb_obb_lanes.hpp"
#include "geometry/point_lanes.hpp"
#include "geometry/shapes_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

// Planes whose unit normals make an angle with sine at most this are parallel (they meet
// only if they coincide). Float unit normals carry about 1e-7 of rounding, so their cross
// product cannot resolve smaller angles. Mirrored in gyro/overlap.hpp.
inline constexpr float kPlaneParallelSine = 1e-6f;

/// |ca - cb|^2 <= (ra + rb)^2.
template <class L> inline auto overlaps(const SphereL<L>& a, const SphereL<L>& b) {
  const L r = a.r + b.r;
  return length_sq(b.c - a.c) <= r * r;
}

/// The squared distance from the centre to the solid box (0 inside) against r^2.
template <class L> inline auto overlaps(const SphereL<L>& s, const AabbL<L>& b) { return distance_sq(b, s.c) <= s.r * s.r; }

template <class L> inline auto overlaps(const SphereL<L>& s, const ObbL<L>& b) { return distance_sq(b, s.c) <= s.r * s.r; }

/// |dot(n, c) - d| <= r.
template <class L> inline auto overlaps(const SphereL<L>& s, const PlaneL<L>& p) { return abs(signed_distance(p, s.c)) <= s.r; }

/// The intervals [lo, hi] (contains()'s rounded bounds) overlap on every axis.
template <class L> inline auto overlaps(const AabbL<L>& a, const AabbL<L>& b) {
  const V3<L> alo = box_lo(a), ahi = box_hi(a), blo = box_lo(b), bhi = box_hi(b);
  return ((alo.x <= bhi.x && blo.x <= ahi.x) && (alo.y <= bhi.y && blo.y <= ahi.y)) && (alo.z <= bhi.z && blo.z <= ahi.z);
}

/// The AABB as an OBB with the world axes.
template <class L> inline ObbL<L> obb_of(const AabbL<L>& b) {
  const L one(1.0f), zero(0.0f);
  return {b.c, b.e, {V3<L>(one, zero, zero), V3<L>(zero, one, zero), V3<L>(zero, zero, one)}};
}

/// Separating axes (obb_obb_overlap, with the AABB as the first box in both argument orders,
/// so the answer does not depend on the order).
template <class L> inline auto overlaps(const AabbL<L>& a, const ObbL<L>& b) { return obb_obb_overlap(obb_of(a), b); }

/// The box's projection radius onto n, e . |n|, against the centre's distance to the plane.
template <class L> inline auto overlaps(const AabbL<L>& b, const PlaneL<L>& p) {
  const L radius = (b.e.x * abs(p.n.x) + b.e.y * abs(p.n.y)) + b.e.z * abs(p.n.z);
  return abs(signed_distance(p, b.c)) <= radius;
}

/// 15 separating axes (obb_obb_lanes.hpp): a pair closer than about 1e-6 * size to touching
/// may be reported as overlapping, and may depend on the argument order.
template <class L> inline auto overlaps(const ObbL<L>& a, const ObbL<L>& b) { return obb_obb_overlap(a, b); }

/// The box's projection radius onto n, sum e_i |u_i . n|, against the centre's distance.
template <class L> inline auto overlaps(const ObbL<L>& b, const PlaneL<L>& p) {
  const L radius = (b.e.x * abs(dot(b.u[0], p.n)) + b.e.y * abs(dot(b.u[1], p.n))) + b.e.z * abs(dot(b.u[2], p.n));
  return abs(signed_distance(p, b.c)) <= radius;
}

/// Two planes meet unless they are parallel (sine of their angle <= kPlaneParallelSine) and
/// distinct. Parallel planes coincide when d1 and +-d2 (the sign of n1 . n2) agree within the
/// surface tolerance of max(|d1|, |d2|) (point_lanes.hpp).
template <class L> inline auto overlaps(const PlaneL<L>& a, const PlaneL<L>& b) {
  const L sin_sq = length_sq(cross(a.n, b.n));
  const auto parallel = sin_sq <= L(kPlaneParallelSine * kPlaneParallelSine);
  const L gap = select(dot(a.n, b.n) >= L(0.0f), a.d - b.d, a.d + b.d);
  const auto coincident = gap * gap <= surface_tolerance_sq(max(abs(a.d), abs(b.d)));
  return !parallel || coincident;
}

}  // namespace gyro::GYRO_ARCH_NS
