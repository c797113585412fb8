// Scalar helpers of Cookbook chapter 1: constants, degree/radian conversion, min/max/clamp
// with a defined NaN rule, lerp, and tolerant float comparison.
//
// Determinism: everything here is + - * / and comparisons on float, so the same inputs give
// the same bits on every compiler and CPU (the build forbids contraction into FMA).
// min and max are written as selects, `a < b ? a : b`, which is also what SSE's minps and
// NEON's bit-select compute; std::min/std::fmin differ in which operand a NaN or a signed
// zero returns, so gyro never uses them on state.
#pragma once

#include <cmath>

namespace gyro {

/// pi rounded to float.
inline constexpr float kPi = 3.14159265358979323846f;
/// 2 pi rounded to float.
inline constexpr float kTwoPi = 6.28318530717958647692f;
/// pi / 2 rounded to float.
inline constexpr float kHalfPi = 1.57079632679489661923f;
/// 1 / pi rounded to float.
inline constexpr float kInvPi = 0.318309886183790671538f;
/// Multiply degrees by this to get radians (pi / 180 rounded to float).
inline constexpr float kDegToRad = 0.0174532925199432957692f;
/// Multiply radians by this to get degrees (180 / pi rounded to float).
inline constexpr float kRadToDeg = 57.2957795130823208768f;
/// The gap between 1 and the next float (FLT_EPSILON), the book's comparison tolerance.
inline constexpr float kEpsilon = 1.1920928955078125e-7f;

/// Degrees to radians. gyro's own functions all take radians; the book's take degrees.
constexpr float deg_to_rad(float degrees) { return degrees * kDegToRad; }
/// Radians to degrees.
constexpr float rad_to_deg(float radians) { return radians * kRadToDeg; }

/// The smaller of a and b. If either is NaN the second operand is returned, and
/// min(-0, +0) is +0 (the second operand), exactly like SSE minps.
constexpr float min(float a, float b) { return a < b ? a : b; }
/// The larger of a and b. If either is NaN the second operand is returned (like maxps).
constexpr float max(float a, float b) { return a > b ? a : b; }
/// x limited to [lo, hi] (lo <= hi). A NaN x stays NaN, so bad input is not hidden: the
/// order min(hi, max(lo, x)) makes x the second operand of both selects.
constexpr float clamp(float x, float lo, float hi) { return min(hi, max(lo, x)); }

/// a + (b - a) * t: exactly a at t = 0 and wherever a == b; b at t = 1 up to one rounding.
constexpr float lerp(float a, float b, float t) { return a + (b - a) * t; }

/// The book's CMP: |a - b| <= eps * max(1, |a|, |b|). The tolerance is absolute (eps) for
/// magnitudes up to 1 and relative (eps per unit of magnitude) above. Equal values,
/// infinities included, compare equal; an infinity is not near any other value, and NaN
/// compares unequal to everything.
inline bool nearly_equal(float a, float b, float eps = kEpsilon) {
  if (a == b) return true;
  if (!std::isfinite(a) || !std::isfinite(b)) return false;  // else inf - x <= eps * inf
  const float scale = max(1.0f, max(std::abs(a), std::abs(b)));
  return std::abs(a - b) <= eps * scale;
}

/// |a - b| <= max(abs_tol, rel_tol * max(|a|, |b|)): separate tolerances for values near
/// zero (where a relative test would demand exact equality) and for large values (where an
/// absolute one would be finer than a float's spacing). Equal values compare equal; an
/// infinity is not near any other value; NaN compares unequal to everything.
inline bool nearly_equal(float a, float b, float abs_tol, float rel_tol) {
  if (a == b) return true;
  if (!std::isfinite(a) || !std::isfinite(b)) return false;
  const float magnitude = max(std::abs(a), std::abs(b));
  return std::abs(a - b) <= max(abs_tol, rel_tol * magnitude);
}

}  // namespace gyro
