// The 3D primitives with lane components, and how to load them: element i of a SoA view
// (SIMD: elements i..i+width-1), a broadcast of element k, or a scalar public struct.
// Every geometric test is a template over these, so the scalar API (L = float) and the
// batch kernels (L = vfloat) run the same expressions.
#pragma once

#include "gyro/shape_arrays.hpp"
#include "math/vec3_lanes.hpp"

#include <cstddef>

namespace gyro::GYRO_ARCH_NS {

template <class L> struct SphereL {
  V3<L> c;
  L r;
};
template <class L> struct AabbL {
  V3<L> c, e;  // centre, half extents
};
template <class L> struct ObbL {
  V3<L> c, e;
  V3<L> u[3];  // unit axes (rows of the orientation)
};
template <class L> struct PlaneL {
  V3<L> n;
  L d;
};
template <class L> struct TriangleL {
  V3<L> a, b, c;
};
template <class L> struct RayL {
  V3<L> o, d;
};
template <class L> struct SegmentL {
  V3<L> a, b;
};

// ---- validity, fused into the batch kernels: x - x is +0 for a finite x and NaN for an
// infinite or NaN one, so one sum per shape tells whether every input is finite (2 ops per
// float instead of a separate pass over memory). Sizes must also be >= 0.
template <class L> inline L nonfinite_sum(const V3<L>& v) { return ((v.x - v.x) + (v.y - v.y)) + (v.z - v.z); }
template <class L> inline auto finite_and_nonneg(L sum, L smallest_size) { return (sum == sum) && (smallest_size >= L(0.0f)); }
template <class L> inline L min3(const V3<L>& v) { return min(min(v.x, v.y), v.z); }

template <class L> inline auto valid(const SphereL<L>& s) { return finite_and_nonneg(nonfinite_sum(s.c) + (s.r - s.r), s.r); }
template <class L> inline auto valid(const AabbL<L>& b) { return finite_and_nonneg(nonfinite_sum(b.c) + nonfinite_sum(b.e), min3(b.e)); }
template <class L> inline auto valid(const ObbL<L>& b) {
  const L sum = ((nonfinite_sum(b.c) + nonfinite_sum(b.e)) + (nonfinite_sum(b.u[0]) + nonfinite_sum(b.u[1]))) + nonfinite_sum(b.u[2]);
  return finite_and_nonneg(sum, min3(b.e));
}
template <class L> inline auto valid(const PlaneL<L>& p) { return finite_and_nonneg(nonfinite_sum(p.n) + (p.d - p.d), L(0.0f)); }
template <class L> inline auto valid(const TriangleL<L>& t) {
  return finite_and_nonneg((nonfinite_sum(t.a) + nonfinite_sum(t.b)) + nonfinite_sum(t.c), L(0.0f));
}

// ---- from SoA views: lanes i..i+width-1
template <class L> inline SphereL<L> load_sphere(const SpheresView& v, std::size_t i) {
  return {load3<L>(v.cx, v.cy, v.cz, i), load<L>(v.r + i)};
}
template <class L> inline AabbL<L> load_aabb(const AabbsView& v, std::size_t i) {
  return {load3<L>(v.cx, v.cy, v.cz, i), load3<L>(v.ex, v.ey, v.ez, i)};
}
template <class L> inline ObbL<L> load_obb(const ObbsView& v, std::size_t i) {
  return {load3<L>(v.cx, v.cy, v.cz, i),
          load3<L>(v.ex, v.ey, v.ez, i),
          {load3<L>(v.u0x, v.u0y, v.u0z, i), load3<L>(v.u1x, v.u1y, v.u1z, i), load3<L>(v.u2x, v.u2y, v.u2z, i)}};
}
template <class L> inline PlaneL<L> load_plane(const PlanesView& v, std::size_t i) {
  return {load3<L>(v.nx, v.ny, v.nz, i), load<L>(v.d + i)};
}
template <class L> inline TriangleL<L> load_triangle(const TrianglesView& v, std::size_t i) {
  return {load3<L>(v.ax, v.ay, v.az, i), load3<L>(v.bx, v.by, v.bz, i), load3<L>(v.cx, v.cy, v.cz, i)};
}

// ---- broadcast of element k to every lane
template <class L> inline V3<L> splat3(const float* x, const float* y, const float* z, std::size_t k) {
  return {L(x[k]), L(y[k]), L(z[k])};
}
template <class L> inline SphereL<L> splat_sphere(const SpheresView& v, std::size_t k) {
  return {splat3<L>(v.cx, v.cy, v.cz, k), L(v.r[k])};
}
template <class L> inline AabbL<L> splat_aabb(const AabbsView& v, std::size_t k) {
  return {splat3<L>(v.cx, v.cy, v.cz, k), splat3<L>(v.ex, v.ey, v.ez, k)};
}
template <class L> inline ObbL<L> splat_obb(const ObbsView& v, std::size_t k) {
  return {splat3<L>(v.cx, v.cy, v.cz, k),
          splat3<L>(v.ex, v.ey, v.ez, k),
          {splat3<L>(v.u0x, v.u0y, v.u0z, k), splat3<L>(v.u1x, v.u1y, v.u1z, k), splat3<L>(v.u2x, v.u2y, v.u2z, k)}};
}
template <class L> inline PlaneL<L> splat_plane(const PlanesView& v, std::size_t k) {
  return {splat3<L>(v.nx, v.ny, v.nz, k), L(v.d[k])};
}
template <class L> inline TriangleL<L> splat_triangle(const TrianglesView& v, std::size_t k) {
  return {splat3<L>(v.ax, v.ay, v.az, k), splat3<L>(v.bx, v.by, v.bz, k), splat3<L>(v.cx, v.cy, v.cz, k)};
}

}  // namespace gyro::GYRO_ARCH_NS
