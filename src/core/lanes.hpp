// Lanes: the one vocabulary every kernel is written in.
//
// A kernel is a template over a lane type L: `float` (one element, the scalar reference)
// or `vfloat` (an xsimd batch of this translation unit's level). Both support exactly the
// operations that are correctly rounded and bit-identical on every level and compiler:
// + - * /, sqrt, comparisons, select, min/max (NaN rule: `a < b ? a : b`, the second operand
// wins when either is NaN), abs, negate, copysign, bit patterns. There is deliberately
// no FMA, no rcp/rsqrt estimate, no xsimd math function and no horizontal reduction: a
// kernel written with these cannot break the determinism contract. Lane k of a vfloat
// computes exactly what the float instantiation computes for element k.
//
// Masks: `bool` for float, `vmask` for vfloat; combine them with && || ! (for vmask these
// do not short-circuit, which is harmless because lane expressions have no side effects).
#pragma once

#include "core/arch.hpp"

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if !defined(GYRO_ARCH_SCALAR)
#include <xsimd/xsimd.hpp>
#endif
#if defined(GYRO_ARCH_NEON)
#include <arm_neon.h>
#endif

namespace gyro::GYRO_ARCH_NS {

// ---------------------------------------------------------------- scalar lane: float
inline float select(bool m, float a, float b) { return m ? a : b; }
inline float min(float a, float b) { return a < b ? a : b; }
inline float max(float a, float b) { return a > b ? a : b; }
inline float sqrt(float a) { return std::sqrt(a); }  // IEEE: correctly rounded
inline float abs(float a) { return std::bit_cast<float>(std::bit_cast<uint32_t>(a) & 0x7fffffffu); }
inline float copysign(float magnitude, float sign) {
  return std::bit_cast<float>((std::bit_cast<uint32_t>(magnitude) & 0x7fffffffu) |
                              (std::bit_cast<uint32_t>(sign) & 0x80000000u));
}
inline bool any(bool m) { return m; }
inline bool all(bool m) { return m; }

template <class L> struct lane_traits;

template <> struct lane_traits<float> {
  static constexpr std::size_t width = 1;
  static float load(const float* p) { return *p; }
  static void store(float* p, float v) { *p = v; }
  static void store_bits(uint32_t* p, float v) { *p = std::bit_cast<uint32_t>(v); }
  static float from_bits(uint32_t bits) { return std::bit_cast<float>(bits); }
};

// ---------------------------------------------------------------- SIMD lane: vfloat
#if !defined(GYRO_ARCH_SCALAR)

#if defined(GYRO_ARCH_SSE2)
using Arch = xsimd::sse2;
#elif defined(GYRO_ARCH_AVX2)
using Arch = xsimd::avx2;
#elif defined(GYRO_ARCH_AVX512)
using Arch = xsimd::avx512f;
#elif defined(GYRO_ARCH_NEON)
using Arch = xsimd::neon64;
#endif

using batch_f = xsimd::batch<float, Arch>;
using batch_u = xsimd::batch<uint32_t, Arch>;
using batch_b = xsimd::batch_bool<float, Arch>;
static_assert(batch_f::size == GYRO_ARCH_WIDTH, "lane width does not match the level");

struct vmask {
  batch_b m;
  friend vmask operator&&(vmask a, vmask b) { return {a.m & b.m}; }
  friend vmask operator||(vmask a, vmask b) { return {a.m | b.m}; }
  friend vmask operator!(vmask a) { return {~a.m}; }
};

struct vfloat {
  batch_f v;
  vfloat() = default;
  vfloat(float s) : v(s) {}  // NOLINT: broadcast, implicit so `x + 1.0f` reads naturally
  explicit vfloat(batch_f b) : v(b) {}

  friend vfloat operator+(vfloat a, vfloat b) { return vfloat(a.v + b.v); }
  friend vfloat operator-(vfloat a, vfloat b) { return vfloat(a.v - b.v); }
  friend vfloat operator*(vfloat a, vfloat b) { return vfloat(a.v * b.v); }
  friend vfloat operator/(vfloat a, vfloat b) {
#if defined(GYRO_ARCH_NEON)
    return vfloat(batch_f(vdivq_f32(a.v, b.v)));  // xsimd's neon64 divide is an estimate
#else
    return vfloat(a.v / b.v);
#endif
  }
  // Negation flips the sign bit (xsimd's AVX-512 negate computes 0 - x, so -(+0) = +0).
  friend vfloat operator-(vfloat a) { return vfloat(xsimd::bitwise_xor(a.v, batch_f(-0.0f))); }
  vfloat& operator+=(vfloat b) { v = v + b.v; return *this; }
  vfloat& operator-=(vfloat b) { v = v - b.v; return *this; }
  vfloat& operator*=(vfloat b) { v = v * b.v; return *this; }
  vfloat& operator/=(vfloat b) { *this = *this / b; return *this; }

  friend vmask operator<(vfloat a, vfloat b) { return {a.v < b.v}; }
  friend vmask operator<=(vfloat a, vfloat b) { return {a.v <= b.v}; }
  friend vmask operator>(vfloat a, vfloat b) { return {a.v > b.v}; }
  friend vmask operator>=(vfloat a, vfloat b) { return {a.v >= b.v}; }
  friend vmask operator==(vfloat a, vfloat b) { return {a.v == b.v}; }
  // Not xsimd's !=: on AVX/AVX-512 it is an ordered compare (false when a lane is NaN)
  // while SSE2, NEON and C++ give true. !(a == b) is C++'s semantics on every level.
  friend vmask operator!=(vfloat a, vfloat b) { return {~(a.v == b.v)}; }
};

inline vfloat select(vmask m, vfloat a, vfloat b) { return vfloat(xsimd::select(m.m, a.v, b.v)); }
inline vfloat min(vfloat a, vfloat b) { return select(a < b, a, b); }
inline vfloat max(vfloat a, vfloat b) { return select(a > b, a, b); }
inline vfloat sqrt(vfloat a) {
#if defined(GYRO_ARCH_NEON)
  return vfloat(batch_f(vsqrtq_f32(a.v)));  // xsimd's neon64 float sqrt is an estimate
#else
  return vfloat(xsimd::sqrt(a.v));
#endif
}
// Explicit masks: xsimd 8.1's bitwise_andnot(x, y) computes ~x & y (Intel's operand
// order), not what its name suggests.
inline batch_f sign_mask() { return xsimd::bitwise_cast<batch_f>(batch_u(0x80000000u)); }
inline batch_f magnitude_mask() { return xsimd::bitwise_cast<batch_f>(batch_u(0x7fffffffu)); }
inline vfloat abs(vfloat a) { return vfloat(xsimd::bitwise_and(a.v, magnitude_mask())); }
inline vfloat copysign(vfloat magnitude, vfloat sign) {
  return vfloat(xsimd::bitwise_or(xsimd::bitwise_and(magnitude.v, magnitude_mask()), xsimd::bitwise_and(sign.v, sign_mask())));
}
inline bool any(vmask m) { return xsimd::any(m.m); }
inline bool all(vmask m) { return xsimd::all(m.m); }

template <> struct lane_traits<vfloat> {
  static constexpr std::size_t width = batch_f::size;
  static vfloat load(const float* p) { return vfloat(batch_f::load_unaligned(p)); }
  static void store(float* p, vfloat v) { v.v.store_unaligned(p); }
  static void store_bits(uint32_t* p, vfloat v) { xsimd::bitwise_cast<batch_u>(v.v).store_unaligned(p); }
  static vfloat from_bits(uint32_t bits) { return vfloat(xsimd::bitwise_cast<batch_f>(batch_u(bits))); }
};

using Wide = vfloat;
#else
using Wide = float;
#endif

// ---------------------------------------------------------------- uniform helpers
template <class L> inline constexpr std::size_t width_v = lane_traits<L>::width;
template <class L> inline L load(const float* p) { return lane_traits<L>::load(p); }
inline void store(float* p, float v) { lane_traits<float>::store(p, v); }
#if !defined(GYRO_ARCH_SCALAR)
inline void store(float* p, vfloat v) { lane_traits<vfloat>::store(p, v); }
#endif
template <class L> inline void store_bits(uint32_t* p, L v) { lane_traits<L>::store_bits(p, v); }
// A lane whose every element holds the given bit pattern: used to carry integers (indices,
// flags) through select, which moves bits without arithmetic.
template <class L> inline L from_bits(uint32_t bits) { return lane_traits<L>::from_bits(bits); }

// Runs body(L{}, i) over [begin, end): full Wide batches first, then the float tail. The
// lambda takes the lane type by a tag: [&](auto tag, std::size_t i) { using L = decltype(tag); }.
template <class Body> inline void for_lanes(std::size_t begin, std::size_t end, Body&& body) {
  std::size_t i = begin;
  if constexpr (width_v<Wide> > 1) {
    for (; i + width_v<Wide> <= end; i += width_v<Wide>) body(Wide{}, i);
  }
  for (; i < end; ++i) body(float{}, i);
}

}  // namespace gyro::GYRO_ARCH_NS
