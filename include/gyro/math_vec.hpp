// vec2, vec3, vec4 and the vector operations of Cookbook chapter 1.
//
// Conventions:
//  - Plain aggregates of floats: vec3{1, 2, 3}; vec3{} is the zero vector. No padding, so an
//    array of vec3 is an array of 3n floats (the C ABI's `float x, y, z`).
//  - == is exact IEEE equality per component (so -0 == +0 and NaN != NaN). The book's ==
//    compares with a tolerance; gyro keeps that as nearly_equal, because a tolerant == is
//    not transitive and silently changes what containers and tests mean.
//  - Angles are radians; all trigonometry is gyro's own (gyro/math_trig.hpp).
//  - Every operation is a fixed sequence of + - * / and sqrt, evaluated left to right
//    (dot(a, b) is ((ax*bx + ay*by) + az*bz) + aw*bw), so results are bit-identical across
//    compilers and CPUs. Division divides (v / s is x/s, y/s, ...); no reciprocal is taken.
#pragma once

#include "gyro/math_scalar.hpp"
#include "gyro/math_trig.hpp"

#include <cmath>
#include <type_traits>

namespace gyro {

/// A 2D vector or point.
struct vec2 {
  float x = 0.0f, y = 0.0f;  ///< components; zero unless initialised
  /// Component i, for i in {0, 1}.
  constexpr float& operator[](int i) { return i == 0 ? x : y; }
  /// Component i, for i in {0, 1}.
  constexpr float operator[](int i) const { return i == 0 ? x : y; }
  /// Exact per-component equality.
  constexpr bool operator==(const vec2&) const = default;
};

/// A 3D vector or point.
struct vec3 {
  float x = 0.0f, y = 0.0f, z = 0.0f;  ///< components; zero unless initialised
  /// Component i, for i in {0, 1, 2}.
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  /// Component i, for i in {0, 1, 2}.
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  /// Exact per-component equality.
  constexpr bool operator==(const vec3&) const = default;
};

/// A 4D vector: a homogeneous point (w = 1) or direction (w = 0), or a row of a mat4.
struct vec4 {
  float x = 0.0f, y = 0.0f, z = 0.0f, w = 0.0f;  ///< components; zero unless initialised
  /// Component i, for i in {0, 1, 2, 3}.
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
  /// Component i, for i in {0, 1, 2, 3}.
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
  /// Exact per-component equality.
  constexpr bool operator==(const vec4&) const = default;
};

static_assert(sizeof(vec2) == 8 && sizeof(vec3) == 12 && sizeof(vec4) == 16);
static_assert(std::is_standard_layout_v<vec3> && std::is_trivially_copyable_v<vec3>);
static_assert(std::is_aggregate_v<vec2> && std::is_aggregate_v<vec3> && std::is_aggregate_v<vec4>);

namespace detail {

/// The number of components of V (0 for anything that is not a gyro vector).
template <class V>
inline constexpr int kDims = 0;
template <>
inline constexpr int kDims<vec2> = 2;
template <>
inline constexpr int kDims<vec3> = 3;
template <>
inline constexpr int kDims<vec4> = 4;

/// vec2, vec3 or vec4: the generic operations below are written once for all three.
template <class V>
concept Vector = kDims<V> >
0;

/// {f(a.x, b.x), f(a.y, b.y), ...}
template <Vector V, class F>
constexpr V zip(const V& a, const V& b, F f) {
  if constexpr (kDims<V> == 2)
    return {f(a.x, b.x), f(a.y, b.y)};
  else if constexpr (kDims<V> == 3)
    return {f(a.x, b.x), f(a.y, b.y), f(a.z, b.z)};
  else
    return {f(a.x, b.x), f(a.y, b.y), f(a.z, b.z), f(a.w, b.w)};
}

/// {f(a.x), f(a.y), ...}
template <Vector V, class F>
constexpr V map(const V& a, F f) {
  if constexpr (kDims<V> == 2)
    return {f(a.x), f(a.y)};
  else if constexpr (kDims<V> == 3)
    return {f(a.x), f(a.y), f(a.z)};
  else
    return {f(a.x), f(a.y), f(a.z), f(a.w)};
}

}  // namespace detail

// The operators that take a float beside the vector carry their constraint in a default
// template argument, not the template head: clang forms the function type (say
// operator*(const T&, float)) before checking a template-head constraint, and for
// `int * enum` or `enum * size_t` (T = int, size_t) that type is a hard error.

/// Component-wise sum.
template <detail::Vector V>
constexpr V operator+(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return p + q; });
}
/// Component-wise difference.
template <detail::Vector V>
constexpr V operator-(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return p - q; });
}
/// Component-wise (Hadamard) product.
template <detail::Vector V>
constexpr V operator*(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return p * q; });
}
/// Component-wise quotient.
template <detail::Vector V>
constexpr V operator/(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return p / q; });
}
/// Every component times s.
template <class V, std::enable_if_t<detail::Vector<V>, int> = 0>
constexpr V operator*(const V& a, float s) {
  return detail::map(a, [s](float p) { return p * s; });
}
/// Every component times s.
template <class V, std::enable_if_t<detail::Vector<V>, int> = 0>
constexpr V operator*(float s, const V& a) {
  return detail::map(a, [s](float p) { return s * p; });
}
/// Every component divided by s (a true division per component, not a reciprocal product).
template <class V, std::enable_if_t<detail::Vector<V>, int> = 0>
constexpr V operator/(const V& a, float s) {
  return detail::map(a, [s](float p) { return p / s; });
}
/// Negation (exact: flips the sign bits).
template <detail::Vector V>
constexpr V operator-(const V& a) {
  return detail::map(a, [](float p) { return -p; });
}
/// a = a + b.
template <detail::Vector V>
constexpr V& operator+=(V& a, const V& b) {
  return a = a + b;
}
/// a = a - b.
template <detail::Vector V>
constexpr V& operator-=(V& a, const V& b) {
  return a = a - b;
}
/// a = a * b, component-wise.
template <detail::Vector V>
constexpr V& operator*=(V& a, const V& b) {
  return a = a * b;
}
/// a = a / b, component-wise.
template <detail::Vector V>
constexpr V& operator/=(V& a, const V& b) {
  return a = a / b;
}
/// a = a * s.
template <detail::Vector V>
constexpr V& operator*=(V& a, float s) {
  return a = a * s;
}
/// a = a / s.
template <detail::Vector V>
constexpr V& operator/=(V& a, float s) {
  return a = a / s;
}

/// Dot product, summed in component order x, y, z, w.
template <detail::Vector V>
constexpr float dot(const V& a, const V& b) {
  if constexpr (detail::kDims<V> == 2)
    return a.x * b.x + a.y * b.y;
  else if constexpr (detail::kDims<V> == 3)
    return a.x * b.x + a.y * b.y + a.z * b.z;
  else
    return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

/// Cross product a x b (right-hand rule in a right-handed frame: x cross y = z).
constexpr vec3 cross(const vec3& a, const vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// The 2D cross product: z of the 3D cross of (a, 0) and (b, 0); positive when b is
/// counter-clockwise from a.
constexpr float cross(const vec2& a, const vec2& b) { return a.x * b.y - a.y * b.x; }

/// Squared length, dot(v, v).
template <detail::Vector V>
constexpr float length_squared(const V& v) {
  return dot(v, v);
}
/// Length, sqrt(dot(v, v)). Like the book, the square can overflow (|v| above about 1.8e19
/// gives inf) or underflow (below about 1e-19 the result loses precision); normalized()
/// rescales and has neither problem.
template <detail::Vector V>
inline float length(const V& v) {
  return std::sqrt(dot(v, v));
}
/// Squared distance between two points.
template <detail::Vector V>
constexpr float distance_squared(const V& a, const V& b) {
  return length_squared(a - b);
}
/// Distance between two points.
template <detail::Vector V>
inline float distance(const V& a, const V& b) {
  return length(a - b);
}

/// v divided by its length. The zero vector (either sign of zero) gives the zero vector,
/// because callers pass degenerate directions far more often than they can check for
/// them; a NaN or infinite component gives NaN components. Vectors whose squared length is
/// outside [2^-100, 2^100] are first scaled by 2^100 or 2^-100 (exact), so tiny and huge
/// vectors normalize to unit length as accurately as ordinary ones.
template <detail::Vector V>
inline V normalized(const V& v) {
  float sq = length_squared(v);
  V s = v;
  if (sq < 0x1p-100f) {
    if (v == V{}) return V{};
    s = v * 0x1p+100f;
    sq = length_squared(s);
  } else if (sq > 0x1p+100f) {
    s = v * 0x1p-100f;
    sq = length_squared(s);
  }
  return s / std::sqrt(sq);
}
/// v = normalized(v) (the zero vector stays zero).
template <detail::Vector V>
inline void normalize(V& v) {
  v = normalized(v);
}

/// The angle between a and b in [0, pi]: acos of the dot of the normalized vectors, clamped
/// to [-1, 1] because rounding can push it just outside. 0 if either vector is zero; NaN
/// if either has a NaN. Near 0 and pi acos is ill-conditioned: a cosine one rounding away
/// from 1 is already 3.5e-4 rad, so parallel vectors can give up to about 7e-4; for angles
/// in [0.1, pi - 0.1] the error measured below 2e-6 rad (tests/math/vec_test.cpp).
template <detail::Vector V>
inline float angle(const V& a, const V& b) {
  const V na = normalized(a), nb = normalized(b);
  if (na == V{} || nb == V{}) return 0.0f;
  return gyro::acos(clamp(dot(na, nb), -1.0f, 1.0f));
}

/// The component of v along dir: dir * (dot(v, dir) / dot(dir, dir)); dir need not be unit
/// length. A zero dir gives the zero vector.
template <detail::Vector V>
constexpr V project(const V& v, const V& dir) {
  const float dd = dot(dir, dir);
  if (dd == 0.0f) return V{};
  return dir * (dot(v, dir) / dd);
}
/// The component of v orthogonal to dir: v - project(v, dir). A zero dir gives v.
template <detail::Vector V>
constexpr V perpendicular(const V& v, const V& dir) {
  return v - project(v, dir);
}
/// v reflected about the plane with unit normal n: v - n * (2 dot(v, n)). n must have unit
/// length (as in the book and GLSL); the result is then as long as v.
template <detail::Vector V>
constexpr V reflect(const V& v, const V& n) {
  return v - n * (dot(v, n) * 2.0f);
}

/// a + (b - a) * t per component (exactly a at t = 0).
template <detail::Vector V>
constexpr V lerp(const V& a, const V& b, float t) {
  return a + (b - a) * t;
}
/// Component-wise gyro::min (NaN rule: the second operand's component wins).
template <detail::Vector V>
constexpr V min(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return gyro::min(p, q); });
}
/// Component-wise gyro::max (NaN rule: the second operand's component wins).
template <detail::Vector V>
constexpr V max(const V& a, const V& b) {
  return detail::zip(a, b, [](float p, float q) { return gyro::max(p, q); });
}
/// Component-wise absolute value.
template <detail::Vector V>
inline V abs(const V& v) {
  return detail::map(v, [](float p) { return std::abs(p); });
}
/// True if every component is finite (no NaN, no infinity).
template <detail::Vector V>
inline bool is_finite(const V& v) {
  for (int i = 0; i < detail::kDims<V>; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
/// Every component nearly_equal(a, b, eps): the book's tolerant vector ==.
template <detail::Vector V>
inline bool nearly_equal(const V& a, const V& b, float eps = kEpsilon) {
  for (int i = 0; i < detail::kDims<V>; ++i)
    if (!nearly_equal(a[i], b[i], eps)) return false;
  return true;
}
/// Every component nearly_equal(a, b, abs_tol, rel_tol).
template <detail::Vector V>
inline bool nearly_equal(const V& a, const V& b, float abs_tol, float rel_tol) {
  for (int i = 0; i < detail::kDims<V>; ++i)
    if (!nearly_equal(a[i], b[i], abs_tol, rel_tol)) return false;
  return true;
}

}  // namespace gyro
