// V3<L>: a 3-vector whose components are lanes (float, or a SIMD batch of floats).
//
// Geometry is written once against V3<L>: instantiated with float it is the scalar API,
// instantiated with vfloat it runs one primitive pair per lane. Every expression has a
// fixed evaluation order (dot = (x*x' + y*y') + z*z'), so both give the same bits.
#pragma once

#include "core/lanes.hpp"

#include <cstddef>

namespace gyro::GYRO_ARCH_NS {

template <class L> struct V3 {
  L x, y, z;

  V3() = default;
  V3(L x_, L y_, L z_) : x(x_), y(y_), z(z_) {}
  /// Broadcast of a scalar vector to every lane.
  template <class F> static V3 splat(F fx, F fy, F fz) { return {L(fx), L(fy), L(fz)}; }

  friend V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
  friend V3 operator*(const V3& a, L s) { return {a.x * s, a.y * s, a.z * s}; }
  friend V3 operator*(L s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
};

template <class L> inline L dot(const V3<L>& a, const V3<L>& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
template <class L> inline L length_sq(const V3<L>& a) { return dot(a, a); }
template <class L> inline V3<L> cross(const V3<L>& a, const V3<L>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class L> inline V3<L> vmin(const V3<L>& a, const V3<L>& b) { return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)}; }
template <class L> inline V3<L> vmax(const V3<L>& a, const V3<L>& b) { return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)}; }
template <class L> inline V3<L> vabs(const V3<L>& a) { return {abs(a.x), abs(a.y), abs(a.z)}; }
template <class M, class L> inline V3<L> vselect(M m, const V3<L>& a, const V3<L>& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

/// Loads element i of three SoA columns.
template <class L> inline V3<L> load3(const float* x, const float* y, const float* z, std::size_t i) {
  return {load<L>(x + i), load<L>(y + i), load<L>(z + i)};
}
template <class L> inline void store3(float* x, float* y, float* z, std::size_t i, const V3<L>& v) {
  store(x + i, v.x), store(y + i, v.y), store(z + i, v.z);
}

}  // namespace gyro::GYRO_ARCH_NS
