// Frustum plane tests (Cookbook chapter 13) as lane templates: one shape per lane against
// the six planes of one frustum (broadcast to every lane). The scalar API of gyro/frustum.hpp
// is the float instantiation and the batch kernels (frustum_kernels.cpp) the SIMD one, so
// lane k gives exactly the bits the scalar call gives for shape k.
//
// For each plane (unit normal n into the frustum, distance d) and a shape with centre c
// and projected radius r on n (sphere: r; AABB: e . |n|; OBB: sum e_i |u_i . n|):
//   s = dot(n, c) - d, tol = kRel * ((|d| + max|c_i|) + r) + kAbs
//   outside this plane  <=>  (s + r) + tol < 0
//   inside this plane   <=>  (s - r) - tol > 0
// A shape is culled when it is outside one plane, inside the frustum when inside all six.
// tol bounds the rounding of the float planes (each coefficient rounded once from double)
// and of this evaluation (a few ulps of |n . c|, |d| and r), so only a shape certainly
// outside is culled and only one certainly inside is called inside. A NaN anywhere makes
// both comparisons false: such a shape is kept and never called inside.
#pragma once

#include "geometry/point_lanes.hpp"
#include "geometry/shapes_lanes.hpp"
#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

// Mirrored in gyro/frustum.hpp (static_assert in frustum.cpp).
inline constexpr float kFrustumRelTolerance = 4e-6f;
inline constexpr float kFrustumAbsTolerance = 1e-30f;

/// One frustum plane, with |n| and |d| kept beside it: they are the same for every shape,
/// and abs is exact, so computing them once changes no bit.
template <class L> struct FrustumPlaneL {
  V3<L> n, abs_n;
  L d, abs_d;
};

/// Six planes (left, right, bottom, top, near, far), normals into the frustum.
template <class L> struct FrustumL {
  FrustumPlaneL<L> p[6];
};

/// The frustum of planes given as (nx, ny, nz, d) rows, in every lane.
template <class L> inline FrustumL<L> splat_frustum(const float (&planes)[6][4]) {
  FrustumL<L> f;
  for (int k = 0; k < 6; ++k) {
    const V3<L> n{L(planes[k][0]), L(planes[k][1]), L(planes[k][2])};
    const L d(planes[k][3]);
    f.p[k] = {n, vabs(n), d, abs(d)};
  }
  return f;
}

// The shape's extent along a plane's unit normal.
template <class L> inline L projected_radius(const SphereL<L>& s, const FrustumPlaneL<L>&) { return s.r; }
template <class L> inline L projected_radius(const AabbL<L>& b, const FrustumPlaneL<L>& p) {
  return (b.e.x * p.abs_n.x + b.e.y * p.abs_n.y) + b.e.z * p.abs_n.z;
}
template <class L> inline L projected_radius(const ObbL<L>& b, const FrustumPlaneL<L>& p) {
  return (b.e.x * abs(dot(b.u[0], p.n)) + b.e.y * abs(dot(b.u[1], p.n))) + b.e.z * abs(dot(b.u[2], p.n));
}

/// Masks of one shape per lane: outside one plane (culled), inside all six.
template <class M> struct FrustumSide {
  M outside, inside;
};

/// The six plane tests for a sphere, AABB or OBB (anything with a centre c and a
/// projected_radius).
template <class L, class Shape> inline auto frustum_side(const FrustumL<L>& f, const Shape& s) {
  const L magnitude = max_abs3(s.c);
  auto outside = L(0.0f) != L(0.0f);  // all false
  auto inside = L(0.0f) == L(0.0f);   // all true
  for (int k = 0; k < 6; ++k) {
    const FrustumPlaneL<L>& p = f.p[k];
    const L dist = dot(p.n, s.c) - p.d;
    const L r = projected_radius(s, p);
    const L tol = L(kFrustumRelTolerance) * ((p.abs_d + magnitude) + r) + L(kFrustumAbsTolerance);
    outside = outside || ((dist + r) + tol < L(0.0f));
    inside = inside && ((dist - r) - tol > L(0.0f));
  }
  return FrustumSide<decltype(outside)>{outside, inside};
}

}  // namespace gyro::GYRO_ARCH_NS
