// Deterministic sin, cos, tan, asin, acos, atan, atan2 as templates over the lane type.
//
// Only + - * /, sqrt, compare and select are used, with every constant a float and every
// expression's order fixed (the build forbids contraction), so the float instantiation and
// every SIMD level give identical bits on every compiler and CPU. Branches are selects: a
// lane computes every path and keeps one. Quadrants are found with the round-to-nearest
// "magic number" add (exact for |k| < 2^22) and compared as small exact floats, so no
// integer lanes and no subnormal bit tricks are needed (an FTZ/DAZ host could not change
// them). Minimax coefficients are the well-known single-precision sets of the Cephes
// library (S. L. Moshier); range reductions are Cody-Waite. Measured errors are in
// include/gyro/math_trig.hpp and tests/math/trig_test.cpp.
#pragma once

#include "core/lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace trig {

// pi/2 in four parts: the first three have 12 significant bits, so k * part is exact for
// |k| < 2^12 (|x| < 6434), and the sum carries pi/2 to about 2^-68. With three parts
// (8 + 11 + 24 bits) the error near multiples of pi/2 reached 20 ulp at |x| ~ 4000.
inline constexpr float kPio2_1 = 0x1.922p+0f;
inline constexpr float kPio2_2 = -0x1.2aep-18f;
inline constexpr float kPio2_3 = -0x1.deap-31f;
inline constexpr float kPio2_4 = 0x1.184698p-44f;
inline constexpr float kTwoOverPi = 0.636619772367581343f;
inline constexpr float kRoundMagic = 12582912.0f;  // 1.5 * 2^23
// hi + lo splits: hi is the float nearest the constant, lo the float nearest the rest.
inline constexpr float kPiHi = 3.14159274101257324f;
inline constexpr float kPiLo = -8.74227800037248e-8f;
inline constexpr float kPio2Hi = 1.57079637050628662f;
inline constexpr float kPio2Lo = -4.37113900018624e-8f;
inline constexpr float kPio4Hi = 0.785398185253143311f;
inline constexpr float kPio4Lo = -2.18556950009312e-8f;
inline constexpr float kTan3Pio8 = 2.414213562373095f;
inline constexpr float kTanPio8 = 0.4142135623730950f;

/// Nearest integer (ties to even), exact for |x| < 2^22; larger |x| gives a deterministic
/// but meaningless value.
template <class L> inline L round_nearest(L x) { return (x + L(kRoundMagic)) - L(kRoundMagic); }

/// k mod 4 for an integer-valued k, as an exact float in {0, 1, 2, 3}.
template <class L> inline L mod4(L k) {
  // floor(k/4) = nearest(k/4 - 3/8) because k/4 has a fraction in {0, 1/4, 1/2, 3/4}.
  const L m = round_nearest(k * L(0.25f) - L(0.375f));
  return k - m * L(4.0f);
}

/// r = x - k*pi/2 with k = nearest(x * 2/pi); returns k.
template <class L> inline L reduce_pio2(L x, L& r) {
  const L k = round_nearest(x * L(kTwoOverPi));
  L t = x - k * L(kPio2_1);
  t = t - k * L(kPio2_2);
  t = t - k * L(kPio2_3);
  r = t - k * L(kPio2_4);
  return k;
}

/// sin on [-pi/4, pi/4].
template <class L> inline L sin_poly(L r) {
  const L z = r * r;
  L p = L(-1.9515295891e-4f) * z + L(8.3321608736e-3f);
  p = p * z + L(-1.6666654611e-1f);
  return p * z * r + r;
}

/// cos on [-pi/4, pi/4].
template <class L> inline L cos_poly(L r) {
  const L z = r * r;
  L p = L(2.443315711809948e-5f) * z + L(-1.388731625493765e-3f);
  p = p * z + L(4.166664568298827e-2f);
  return p * z * z - L(0.5f) * z + L(1.0f);
}

/// tan on [-pi/4, pi/4].
template <class L> inline L tan_poly(L r) {
  const L z = r * r;
  L p = L(9.38540185543e-3f) * z + L(3.11992232697e-3f);
  p = p * z + L(2.44301354525e-2f);
  p = p * z + L(5.34112807005e-2f);
  p = p * z + L(1.33387994085e-1f);
  p = p * z + L(3.33331568548e-1f);
  return p * z * r + r;
}

/// atan on [0, tan(pi/8)].
template <class L> inline L atan_poly(L x) {
  const L z = x * x;
  L p = L(8.05374449538e-2f) * z + L(-1.38776856032e-1f);
  p = p * z + L(1.99777106478e-1f);
  p = p * z + L(-3.33329491539e-1f);
  return p * z * x;  // atan(x) - x
}

/// atan on [0, +inf]: reduces to [0, tan(pi/8)].
template <class L> inline L atan_nonneg(L a) {
  const auto big = a > L(kTan3Pio8);
  const auto mid = (a > L(kTanPio8)) && !big;
  // Each path is computed in every lane; the unused ones may divide by zero, harmlessly.
  const L x = select(big, L(-1.0f) / a, select(mid, (a - L(1.0f)) / (a + L(1.0f)), a));
  const L hi = select(big, L(kPio2Hi), select(mid, L(kPio4Hi), L(0.0f)));
  const L lo = select(big, L(kPio2Lo), select(mid, L(kPio4Lo), L(0.0f)));
  return hi + ((atan_poly(x) + lo) + x);
}

/// asin(s) - s on the reduced argument, with z = s*s.
template <class L> inline L asin_poly(L s, L z) {
  L p = L(4.2163199048e-2f) * z + L(2.4181311049e-2f);
  p = p * z + L(4.5470025998e-2f);
  p = p * z + L(7.4953002686e-2f);
  p = p * z + L(1.6666752422e-1f);
  return p * z * s;
}

}  // namespace trig

template <class L> inline void sincos(L x, L& s, L& c) {
  L r;
  const L q = trig::mod4(trig::reduce_pio2(x, r));
  const L sp = trig::sin_poly(r);
  const L cp = trig::cos_poly(r);
  const auto swap = (q == L(1.0f)) || (q == L(3.0f));
  const L s0 = select(swap, cp, sp);
  const L c0 = select(swap, sp, cp);
  // The polynomial turns -0 into +0; sin is odd, so keep the sign of a zero argument.
  s = select(x == L(0.0f), x, select(q >= L(2.0f), -s0, s0));
  c = select((q == L(1.0f)) || (q == L(2.0f)), -c0, c0);
}

template <class L> inline L sin(L x) {
  L s, c;
  sincos(x, s, c);
  return s;
}

template <class L> inline L cos(L x) {
  L s, c;
  sincos(x, s, c);
  return c;
}

template <class L> inline L tan(L x) {
  L r;
  const L q = trig::mod4(trig::reduce_pio2(x, r));
  const L t = trig::tan_poly(r);
  const auto odd = (q == L(1.0f)) || (q == L(3.0f));
  return select(x == L(0.0f), x, select(odd, L(-1.0f) / t, t));
}

template <class L> inline L atan(L x) { return copysign(trig::atan_nonneg(abs(x)), x); }

template <class L> inline L atan2(L y, L x) {
  const L ax = abs(x), ay = abs(y);
  const L mn = min(ax, ay), mx = max(ax, ay);
  const auto both_zero = mx == L(0.0f);
  const auto both_inf = mn == L(__builtin_inff());
  // t is in [0, 1]; the two cases where mn/mx is 0/0 or inf/inf are set directly.
  const L t = mn / mx;
  L a = select(both_zero, L(0.0f), select(both_inf, L(trig::kPio4Hi), trig::atan_nonneg(t)));
  a = select(ay > ax, (L(trig::kPio2Hi) - a) + L(trig::kPio2Lo), a);
  const auto x_negative = copysign(L(1.0f), x) < L(0.0f);  // -0 counts as negative
  a = select(x_negative, (L(trig::kPiHi) - a) + L(trig::kPiLo), a);
  a = copysign(a, y);
  const auto nan_in = (x != x) || (y != y);
  return select(nan_in, x + y, a);
}

template <class L> inline L asin(L x) {
  const L a = abs(x);
  const auto big = a > L(0.5f);
  const L z = select(big, L(0.5f) * (L(1.0f) - a), a * a);
  const L s = select(big, sqrt(z), a);
  const L p = trig::asin_poly(s, z) + s;
  // pi/2 - 2p, with pi/2 in two parts.
  const L r = select(big, (L(trig::kPio2Hi) - (p + p)) + L(trig::kPio2Lo), p);
  return copysign(r, x);  // |x| > 1 gives NaN through sqrt of a negative
}

template <class L> inline L acos(L x) {
  const auto lo_side = x < L(-0.5f);
  const auto hi_side = x > L(0.5f);
  const auto outer = lo_side || hi_side;
  // Outer: acos(x) = 2 asin(sqrt((1 - |x|)/2)), mirrored for x < -1/2. Inner: pi/2 - asin(x).
  const L a = abs(x);
  const L z = select(outer, L(0.5f) * (L(1.0f) - a), x * x);
  const L s = select(outer, sqrt(z), x);
  const L p = trig::asin_poly(s, z) + s;
  const L two_p = p + p;
  const L inner = (L(trig::kPio2Hi) - p) + L(trig::kPio2Lo);
  const L neg = (L(trig::kPiHi) - two_p) + L(trig::kPiLo);
  return select(hi_side, two_p, select(lo_side, neg, inner));
}

}  // namespace gyro::GYRO_ARCH_NS
