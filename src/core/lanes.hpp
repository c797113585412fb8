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
#include <type_traits>

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

// The SIMD lane is generic over the xsimd architecture so a level can also offer a lane of
// fixed width 4 (Quad below: one BVH node's four children, one leaf's four triangles). The
// operations are elementwise, so a 4-wide SSE lane inside the AVX2 kernels computes exactly
// what the AVX2 lane (or the float lane) computes for the same element.
template <class A> struct vmask_t {
  xsimd::batch_bool<float, A> m;
  friend vmask_t operator&&(vmask_t a, vmask_t b) { return {a.m & b.m}; }
  friend vmask_t operator||(vmask_t a, vmask_t b) { return {a.m | b.m}; }
  friend vmask_t operator!(vmask_t a) { return {~a.m}; }
};

template <class A> struct vfloat_t {
  using batch_f = xsimd::batch<float, A>;
  using mask = vmask_t<A>;
  batch_f v;
  vfloat_t() = default;
  vfloat_t(float s) : v(s) {}  // NOLINT: broadcast, implicit so `x + 1.0f` reads naturally
  explicit vfloat_t(batch_f b) : v(b) {}

  friend vfloat_t operator+(vfloat_t a, vfloat_t b) { return vfloat_t(a.v + b.v); }
  friend vfloat_t operator-(vfloat_t a, vfloat_t b) { return vfloat_t(a.v - b.v); }
  friend vfloat_t operator*(vfloat_t a, vfloat_t b) { return vfloat_t(a.v * b.v); }
  friend vfloat_t operator/(vfloat_t a, vfloat_t b) {
#if defined(GYRO_ARCH_NEON)
    return vfloat_t(batch_f(vdivq_f32(a.v, b.v)));  // xsimd's neon64 divide is an estimate
#else
    return vfloat_t(a.v / b.v);
#endif
  }
  // Negation flips the sign bit (xsimd's AVX-512 negate computes 0 - x, so -(+0) = +0).
  friend vfloat_t operator-(vfloat_t a) { return vfloat_t(xsimd::bitwise_xor(a.v, batch_f(-0.0f))); }
  vfloat_t& operator+=(vfloat_t b) { v = v + b.v; return *this; }
  vfloat_t& operator-=(vfloat_t b) { v = v - b.v; return *this; }
  vfloat_t& operator*=(vfloat_t b) { v = v * b.v; return *this; }
  vfloat_t& operator/=(vfloat_t b) { *this = *this / b; return *this; }

  friend mask operator<(vfloat_t a, vfloat_t b) { return {a.v < b.v}; }
  friend mask operator<=(vfloat_t a, vfloat_t b) { return {a.v <= b.v}; }
  friend mask operator>(vfloat_t a, vfloat_t b) { return {a.v > b.v}; }
  friend mask operator>=(vfloat_t a, vfloat_t b) { return {a.v >= b.v}; }
  friend mask operator==(vfloat_t a, vfloat_t b) { return {a.v == b.v}; }
  // Not xsimd's !=: on AVX/AVX-512 it is an ordered compare (false when a lane is NaN)
  // while SSE2, NEON and C++ give true. !(a == b) is C++'s semantics on every level.
  friend mask operator!=(vfloat_t a, vfloat_t b) { return {~(a.v == b.v)}; }
};

template <class A> inline vfloat_t<A> select(vmask_t<A> m, vfloat_t<A> a, vfloat_t<A> b) {
  return vfloat_t<A>(xsimd::select(m.m, a.v, b.v));
}
// x86's MINPS/MAXPS are exactly `a < b ? a : b` and `a > b ? a : b`: when either operand
// is NaN, or both are zeros of any sign, they return the second operand. One instruction
// instead of a compare and a blend, with the same bits (lanes_test checks every pair of
// special values). NEON's fmin/fmax return NaN instead, so NEON keeps the select.
template <class A> inline vfloat_t<A> min(vfloat_t<A> a, vfloat_t<A> b) {
#if defined(GYRO_ARCH_AVX512)
  if constexpr (std::is_same_v<A, xsimd::avx512f>) return vfloat_t<A>(xsimd::batch<float, A>(_mm512_min_ps(a.v, b.v)));
#endif
#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
  if constexpr (std::is_same_v<A, xsimd::avx2>) return vfloat_t<A>(xsimd::batch<float, A>(_mm256_min_ps(a.v, b.v)));
#endif
#if !defined(GYRO_ARCH_NEON)
  if constexpr (xsimd::batch<float, A>::size == 4) return vfloat_t<A>(xsimd::batch<float, A>(_mm_min_ps(a.v, b.v)));
#endif
  return select(a < b, a, b);
}
template <class A> inline vfloat_t<A> max(vfloat_t<A> a, vfloat_t<A> b) {
#if defined(GYRO_ARCH_AVX512)
  if constexpr (std::is_same_v<A, xsimd::avx512f>) return vfloat_t<A>(xsimd::batch<float, A>(_mm512_max_ps(a.v, b.v)));
#endif
#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
  if constexpr (std::is_same_v<A, xsimd::avx2>) return vfloat_t<A>(xsimd::batch<float, A>(_mm256_max_ps(a.v, b.v)));
#endif
#if !defined(GYRO_ARCH_NEON)
  if constexpr (xsimd::batch<float, A>::size == 4) return vfloat_t<A>(xsimd::batch<float, A>(_mm_max_ps(a.v, b.v)));
#endif
  return select(a > b, a, b);
}
template <class A> inline vfloat_t<A> sqrt(vfloat_t<A> a) {
#if defined(GYRO_ARCH_NEON)
  return vfloat_t<A>(xsimd::batch<float, A>(vsqrtq_f32(a.v)));  // xsimd's neon64 float sqrt is an estimate
#else
  return vfloat_t<A>(xsimd::sqrt(a.v));
#endif
}
// Explicit masks: xsimd 8.1's bitwise_andnot(x, y) computes ~x & y (Intel's operand
// order), not what its name suggests.
template <class A> inline xsimd::batch<float, A> sign_mask() {
  return xsimd::bitwise_cast<xsimd::batch<float, A>>(xsimd::batch<uint32_t, A>(0x80000000u));
}
template <class A> inline xsimd::batch<float, A> magnitude_mask() {
  return xsimd::bitwise_cast<xsimd::batch<float, A>>(xsimd::batch<uint32_t, A>(0x7fffffffu));
}
template <class A> inline vfloat_t<A> abs(vfloat_t<A> a) { return vfloat_t<A>(xsimd::bitwise_and(a.v, magnitude_mask<A>())); }
template <class A> inline vfloat_t<A> copysign(vfloat_t<A> magnitude, vfloat_t<A> sign) {
  return vfloat_t<A>(xsimd::bitwise_or(xsimd::bitwise_and(magnitude.v, magnitude_mask<A>()),
                                       xsimd::bitwise_and(sign.v, sign_mask<A>())));
}
template <class A> inline bool any(vmask_t<A> m) { return xsimd::any(m.m); }
template <class A> inline bool all(vmask_t<A> m) { return xsimd::all(m.m); }

template <class A> struct lane_traits<vfloat_t<A>> {
  using batch_f = xsimd::batch<float, A>;
  using batch_u = xsimd::batch<uint32_t, A>;
  static constexpr std::size_t width = batch_f::size;
  static vfloat_t<A> load(const float* p) { return vfloat_t<A>(batch_f::load_unaligned(p)); }
  static void store(float* p, vfloat_t<A> v) { v.v.store_unaligned(p); }
  static void store_bits(uint32_t* p, vfloat_t<A> v) { xsimd::bitwise_cast<batch_u>(v.v).store_unaligned(p); }
  static vfloat_t<A> from_bits(uint32_t bits) { return vfloat_t<A>(xsimd::bitwise_cast<batch_f>(batch_u(bits))); }
};

using vfloat = vfloat_t<Arch>;
using vmask = vmask_t<Arch>;
static_assert(lane_traits<vfloat>::width == GYRO_ARCH_WIDTH, "lane width does not match the level");

// Quad: a lane of exactly 4 floats at every SIMD level (the float loop at the scalar level).
// The widest 128-bit instruction set of the level: SSE4.1's blendvps makes a select one
// instruction instead of three (and, andnot, or) inside the AVX2 and AVX-512 kernels.
#if defined(GYRO_ARCH_NEON)
using Quad = vfloat_t<xsimd::neon64>;
#elif defined(GYRO_ARCH_SSE2)
using Quad = vfloat_t<xsimd::sse2>;
#else
using Quad = vfloat_t<xsimd::sse4_2>;
#endif
static_assert(lane_traits<Quad>::width == 4, "Quad must be 4 wide");

/// Bit k set when lane k of a Quad mask is true (one movemask on x86, no branches).
inline unsigned lane_bits(vmask_t<Quad::batch_f::arch_type> m) {
#if defined(GYRO_ARCH_NEON)
  const uint32x4_t weights = {1u, 2u, 4u, 8u};
  const uint32x4_t lanes = m.m;
  return vaddvq_u32(vandq_u32(lanes, weights));
#else
  const __m128 lanes = m.m;
  return unsigned(_mm_movemask_ps(lanes));
#endif
}

using Wide = vfloat;
#else
using Wide = float;

// Quad at the scalar level: four floats, each operation the float lane's, element by element.
struct QuadMask {
  bool m[4];
  friend QuadMask operator&&(QuadMask a, QuadMask b) { return {{a.m[0] && b.m[0], a.m[1] && b.m[1], a.m[2] && b.m[2], a.m[3] && b.m[3]}}; }
  friend QuadMask operator||(QuadMask a, QuadMask b) { return {{a.m[0] || b.m[0], a.m[1] || b.m[1], a.m[2] || b.m[2], a.m[3] || b.m[3]}}; }
  friend QuadMask operator!(QuadMask a) { return {{!a.m[0], !a.m[1], !a.m[2], !a.m[3]}}; }
};

struct Quad {
  float v[4];
  Quad() = default;
  Quad(float s) : v{s, s, s, s} {}  // NOLINT: broadcast, as vfloat
  template <class F> static Quad map(F f) { return Quad(f(0), f(1), f(2), f(3), 0); }
  template <class F> static QuadMask test(F f) { return {{f(0), f(1), f(2), f(3)}}; }
  friend Quad operator+(Quad a, Quad b) { return map([&](int k) { return a.v[k] + b.v[k]; }); }
  friend Quad operator-(Quad a, Quad b) { return map([&](int k) { return a.v[k] - b.v[k]; }); }
  friend Quad operator*(Quad a, Quad b) { return map([&](int k) { return a.v[k] * b.v[k]; }); }
  friend Quad operator/(Quad a, Quad b) { return map([&](int k) { return a.v[k] / b.v[k]; }); }
  friend Quad operator-(Quad a) { return map([&](int k) { return -a.v[k]; }); }
  Quad& operator+=(Quad b) { return *this = *this + b; }
  Quad& operator-=(Quad b) { return *this = *this - b; }
  Quad& operator*=(Quad b) { return *this = *this * b; }
  Quad& operator/=(Quad b) { return *this = *this / b; }
  friend QuadMask operator<(Quad a, Quad b) { return test([&](int k) { return a.v[k] < b.v[k]; }); }
  friend QuadMask operator<=(Quad a, Quad b) { return test([&](int k) { return a.v[k] <= b.v[k]; }); }
  friend QuadMask operator>(Quad a, Quad b) { return test([&](int k) { return a.v[k] > b.v[k]; }); }
  friend QuadMask operator>=(Quad a, Quad b) { return test([&](int k) { return a.v[k] >= b.v[k]; }); }
  friend QuadMask operator==(Quad a, Quad b) { return test([&](int k) { return a.v[k] == b.v[k]; }); }
  friend QuadMask operator!=(Quad a, Quad b) { return test([&](int k) { return a.v[k] != b.v[k]; }); }

 private:
  Quad(float a, float b, float c, float d, int) : v{a, b, c, d} {}
};

inline Quad select(QuadMask m, Quad a, Quad b) { return Quad::map([&](int k) { return m.m[k] ? a.v[k] : b.v[k]; }); }
inline Quad min(Quad a, Quad b) { return Quad::map([&](int k) { return min(a.v[k], b.v[k]); }); }
inline Quad max(Quad a, Quad b) { return Quad::map([&](int k) { return max(a.v[k], b.v[k]); }); }
inline Quad sqrt(Quad a) { return Quad::map([&](int k) { return sqrt(a.v[k]); }); }
inline Quad abs(Quad a) { return Quad::map([&](int k) { return abs(a.v[k]); }); }
inline Quad copysign(Quad a, Quad b) { return Quad::map([&](int k) { return copysign(a.v[k], b.v[k]); }); }
inline bool any(QuadMask m) { return (m.m[0] || m.m[1]) || (m.m[2] || m.m[3]); }
/// Bit k set when lane k is true.
inline unsigned lane_bits(QuadMask m) {
  return unsigned(m.m[0]) | unsigned(m.m[1]) << 1 | unsigned(m.m[2]) << 2 | unsigned(m.m[3]) << 3;
}
inline bool all(QuadMask m) { return (m.m[0] && m.m[1]) && (m.m[2] && m.m[3]); }

template <> struct lane_traits<Quad> {
  static constexpr std::size_t width = 4;
  static Quad load(const float* p) { return Quad::map([&](int k) { return p[k]; }); }
  static void store(float* p, Quad q) { for (int k = 0; k < 4; ++k) p[k] = q.v[k]; }
  static void store_bits(uint32_t* p, Quad q) { for (int k = 0; k < 4; ++k) p[k] = std::bit_cast<uint32_t>(q.v[k]); }
  static Quad from_bits(uint32_t bits) { return Quad(std::bit_cast<float>(bits)); }
};
inline void store(float* p, Quad v) { lane_traits<Quad>::store(p, v); }
#endif

// ---------------------------------------------------------------- Oct: exactly 8 lanes
// One AVX register at the AVX levels; two Quads, element by element, everywhere else (the
// BVH's eight-child nodes). Every operation is elementwise, so each level gives the bits of
// the float lane.
template <class Q> struct PairMask {
  using M = decltype(Q(0.0f) < Q(0.0f));
  M lo, hi;
  friend PairMask operator&&(PairMask a, PairMask b) { return {a.lo && b.lo, a.hi && b.hi}; }
  friend PairMask operator||(PairMask a, PairMask b) { return {a.lo || b.lo, a.hi || b.hi}; }
  friend PairMask operator!(PairMask a) { return {!a.lo, !a.hi}; }
};

template <class Q> struct Pair {
  using Mask = PairMask<Q>;
  Q lo, hi;
  Pair() = default;
  Pair(float s) : lo(s), hi(s) {}  // NOLINT: broadcast, as vfloat
  Pair(Q l, Q h) : lo(l), hi(h) {}
  friend Pair operator+(Pair a, Pair b) { return {a.lo + b.lo, a.hi + b.hi}; }
  friend Pair operator-(Pair a, Pair b) { return {a.lo - b.lo, a.hi - b.hi}; }
  friend Pair operator*(Pair a, Pair b) { return {a.lo * b.lo, a.hi * b.hi}; }
  friend Pair operator/(Pair a, Pair b) { return {a.lo / b.lo, a.hi / b.hi}; }
  friend Pair operator-(Pair a) { return {-a.lo, -a.hi}; }
  Pair& operator+=(Pair b) { return *this = *this + b; }
  Pair& operator-=(Pair b) { return *this = *this - b; }
  Pair& operator*=(Pair b) { return *this = *this * b; }
  Pair& operator/=(Pair b) { return *this = *this / b; }
  friend Mask operator<(Pair a, Pair b) { return {a.lo < b.lo, a.hi < b.hi}; }
  friend Mask operator<=(Pair a, Pair b) { return {a.lo <= b.lo, a.hi <= b.hi}; }
  friend Mask operator>(Pair a, Pair b) { return {a.lo > b.lo, a.hi > b.hi}; }
  friend Mask operator>=(Pair a, Pair b) { return {a.lo >= b.lo, a.hi >= b.hi}; }
  friend Mask operator==(Pair a, Pair b) { return {a.lo == b.lo, a.hi == b.hi}; }
  friend Mask operator!=(Pair a, Pair b) { return {a.lo != b.lo, a.hi != b.hi}; }
};

template <class Q> inline Pair<Q> select(PairMask<Q> m, Pair<Q> a, Pair<Q> b) {
  return {select(m.lo, a.lo, b.lo), select(m.hi, a.hi, b.hi)};
}
template <class Q> inline Pair<Q> min(Pair<Q> a, Pair<Q> b) { return {min(a.lo, b.lo), min(a.hi, b.hi)}; }
template <class Q> inline Pair<Q> max(Pair<Q> a, Pair<Q> b) { return {max(a.lo, b.lo), max(a.hi, b.hi)}; }
template <class Q> inline Pair<Q> sqrt(Pair<Q> a) { return {sqrt(a.lo), sqrt(a.hi)}; }
template <class Q> inline Pair<Q> abs(Pair<Q> a) { return {abs(a.lo), abs(a.hi)}; }
template <class Q> inline Pair<Q> copysign(Pair<Q> a, Pair<Q> b) { return {copysign(a.lo, b.lo), copysign(a.hi, b.hi)}; }
template <class Q> inline bool any(PairMask<Q> m) { return any(m.lo) || any(m.hi); }
template <class Q> inline bool all(PairMask<Q> m) { return all(m.lo) && all(m.hi); }
template <class Q> inline unsigned lane_bits(PairMask<Q> m) { return lane_bits(m.lo) | lane_bits(m.hi) << 4; }

template <class Q> struct lane_traits<Pair<Q>> {
  static constexpr std::size_t width = 8;
  static Pair<Q> load(const float* p) { return {lane_traits<Q>::load(p), lane_traits<Q>::load(p + 4)}; }
  static void store(float* p, Pair<Q> v) { lane_traits<Q>::store(p, v.lo), lane_traits<Q>::store(p + 4, v.hi); }
  static void store_bits(uint32_t* p, Pair<Q> v) {
    lane_traits<Q>::store_bits(p, v.lo), lane_traits<Q>::store_bits(p + 4, v.hi);
  }
  static Pair<Q> from_bits(uint32_t bits) { return {lane_traits<Q>::from_bits(bits), lane_traits<Q>::from_bits(bits)}; }
};
template <class Q> inline void store(float* p, Pair<Q> v) { lane_traits<Pair<Q>>::store(p, v); }

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
using Oct = vfloat_t<xsimd::avx2>;
/// Bit k set when lane k of an Oct mask is true.
inline unsigned lane_bits(vmask_t<xsimd::avx2> m) {
  const __m256 lanes = m.m;
  return unsigned(_mm256_movemask_ps(lanes));
}
#else
using Oct = Pair<Quad>;
#endif
static_assert(lane_traits<Oct>::width == 8, "Oct must be 8 wide");

// ---------------------------------------------------------------- uniform helpers
template <class L> inline constexpr std::size_t width_v = lane_traits<L>::width;
template <class L> inline L load(const float* p) { return lane_traits<L>::load(p); }
inline void store(float* p, float v) { lane_traits<float>::store(p, v); }
#if !defined(GYRO_ARCH_SCALAR)
template <class A> inline void store(float* p, vfloat_t<A> v) { lane_traits<vfloat_t<A>>::store(p, v); }
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
