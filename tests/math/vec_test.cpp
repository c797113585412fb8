// Scalars and vectors (include/gyro/math_scalar.hpp, math_vec.hpp): exact results on small
// integers, the comparison functions' absolute and relative behaviour, the NaN rules, and
// seeded random properties against double precision. Each property prints its largest
// error; the bounds are about twice the measured maxima (GCC 12, x86-64).
#include "gyro/math.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr float kNan = __builtin_nanf("");
constexpr float kInf = __builtin_inff();

// Not inlined: with it inlined, GCC 12 -O3 (its SLP vectoriser) gave mat_test's double
// references values other than the rounded floats the code under test received (an
// adjugate product that is exactly zero came out as 2e-6; clang, and GCC with
// -fno-tree-slp-vectorize, were right). A call hands over the rounded float, once.
[[gnu::noinline]] float uniform(SplitMix64& rng, double lo, double hi) {
  return static_cast<float>(lo + (hi - lo) * rng.u());
}
vec3 random_vec3(SplitMix64& rng, double r) { return {uniform(rng, -r, r), uniform(rng, -r, r), uniform(rng, -r, r)}; }
/// A random direction times a magnitude 10^e, e uniform in [lo_exp, hi_exp].
vec3 random_scaled_vec3(SplitMix64& rng, double lo_exp, double hi_exp) {
  const double m = std::pow(10.0, lo_exp + (hi_exp - lo_exp) * rng.u());
  return {uniform(rng, -m, m), uniform(rng, -m, m), uniform(rng, -m, m)};
}

struct D3 {
  double x, y, z;
};
D3 d(const vec3& v) { return {v.x, v.y, v.z}; }
double ddot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 dcross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dlen(D3 a) { return std::sqrt(ddot(a, a)); }

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

/// The largest error of one property over every sample: printed, then checked against its
/// bound when the property's scope ends, so the printed maximum is the true one even when
/// the check fails. A NaN error is kept as the worst.
struct MaxError {
  const char* what;
  double bound;
  double max = 0.0;
  long worst = -1;
  void add(double e, long sample) {
    if (std::isnan(max)) return;
    if (!(e <= max)) max = e, worst = sample;
  }
  ~MaxError() {
    std::printf("  %-60s max %.3g (bound %.2g)\n", what, max, bound);
    EXPECT_LE(max, bound) << what << ": worst at sample " << worst;
  }
};

TEST(VecScalar, ConstantsAreTheNearestFloats) {
  EXPECT_EQ(kPi, static_cast<float>(M_PI));
  EXPECT_EQ(kTwoPi, static_cast<float>(2 * M_PI));
  EXPECT_EQ(kHalfPi, static_cast<float>(M_PI / 2));
  EXPECT_EQ(kInvPi, static_cast<float>(1 / M_PI));
  EXPECT_EQ(kDegToRad, static_cast<float>(M_PI / 180));
  EXPECT_EQ(kRadToDeg, static_cast<float>(180 / M_PI));
  EXPECT_EQ(kEpsilon, FLT_EPSILON);
}

TEST(VecScalar, DegreeRadianConversion) {
  EXPECT_EQ(deg_to_rad(180.0f), kPi);
  EXPECT_EQ(deg_to_rad(90.0f), kHalfPi);
  EXPECT_EQ(rad_to_deg(kPi), 180.0f);
  EXPECT_EQ(deg_to_rad(0.0f), 0.0f);
  // A round trip costs at most two roundings: within 2 ulp over [-720, 720].
  MaxError err{"rad_to_deg(deg_to_rad(x)) - x, ulp", 2.0};
  for (int i = -72000; i <= 72000; ++i) {
    const float x = static_cast<float>(i) * 0.01f;
    if (x == 0.0f) continue;
    const double e = std::fabs(double(rad_to_deg(deg_to_rad(x))) - x) / std::ldexp(1.0, std::ilogb(x) - 23);
    err.add(e, i);
  }
}

TEST(VecScalar, MinMaxClampFollowTheSecondOperandNanRule) {
  EXPECT_EQ(gyro::min(1.0f, 2.0f), 1.0f);
  EXPECT_EQ(gyro::min(2.0f, 1.0f), 1.0f);
  EXPECT_EQ(gyro::max(1.0f, 2.0f), 2.0f);
  EXPECT_EQ(gyro::max(2.0f, 1.0f), 2.0f);
  // NaN: the second operand wins, whichever it is.
  EXPECT_EQ(gyro::min(kNan, 1.0f), 1.0f);
  EXPECT_TRUE(std::isnan(gyro::min(1.0f, kNan)));
  EXPECT_EQ(gyro::max(kNan, 1.0f), 1.0f);
  EXPECT_TRUE(std::isnan(gyro::max(1.0f, kNan)));
  // Signed zeros compare equal, so the second operand wins there too.
  EXPECT_EQ(bits(gyro::min(-0.0f, 0.0f)), bits(0.0f));
  EXPECT_EQ(bits(gyro::min(0.0f, -0.0f)), bits(-0.0f));
  EXPECT_EQ(bits(gyro::max(0.0f, -0.0f)), bits(-0.0f));
  // clamp keeps NaN (bad input stays visible) and limits everything else.
  EXPECT_TRUE(std::isnan(clamp(kNan, -1.0f, 1.0f)));
  EXPECT_EQ(clamp(2.0f, -1.0f, 1.0f), 1.0f);
  EXPECT_EQ(clamp(-2.0f, -1.0f, 1.0f), -1.0f);
  EXPECT_EQ(clamp(0.25f, -1.0f, 1.0f), 0.25f);
  EXPECT_EQ(clamp(kInf, -1.0f, 1.0f), 1.0f);
  EXPECT_EQ(clamp(-kInf, -1.0f, 1.0f), -1.0f);
}

TEST(VecScalar, LerpIsExactAtTheStartAndForEqualEnds) {
  SplitMix64 rng(101);
  for (int i = 0; i < 10000; ++i) {
    const float a = uniform(rng, -1e4, 1e4), b = uniform(rng, -1e4, 1e4), t = uniform(rng, 0, 1);
    ASSERT_EQ(lerp(a, b, 0.0f), a);
    ASSERT_EQ(lerp(a, a, t), a);
    ASSERT_TRUE(nearly_equal(lerp(a, b, 1.0f), b, 1e-3f, 0.0f));
  }
  EXPECT_EQ(lerp(2.0f, 4.0f, 0.5f), 3.0f);
  EXPECT_EQ(lerp(2.0f, 4.0f, 1.0f), 4.0f);
}

TEST(VecScalar, NearlyEqualIsAbsoluteBelowOneAndRelativeAbove) {
  // Near zero the book's CMP tolerance is absolute: eps itself.
  EXPECT_TRUE(nearly_equal(0.0f, 1e-7f));
  EXPECT_FALSE(nearly_equal(0.0f, 2e-7f));
  EXPECT_TRUE(nearly_equal(1e-30f, -1e-30f));  // a relative test would fail this
  EXPECT_TRUE(nearly_equal(1.0f, 1.0f + FLT_EPSILON));
  EXPECT_FALSE(nearly_equal(1.0f, 1.0f + 2 * FLT_EPSILON));
  // Above 1 it is relative: eps per unit of magnitude.
  EXPECT_TRUE(nearly_equal(1e6f, std::nextafter(1e6f, 2e6f)));
  EXPECT_FALSE(nearly_equal(1e6f, 1e6f + 1.0f));
  EXPECT_TRUE(nearly_equal(1e30f, std::nextafter(1e30f, 2e30f)));
  EXPECT_FALSE(nearly_equal(1e30f, 1e30f * (1.0f + 1e-6f)));
  EXPECT_FALSE(nearly_equal(-1e30f, 1e30f));
  // A wider eps.
  EXPECT_TRUE(nearly_equal(100.0f, 101.0f, 0.01f));
  EXPECT_FALSE(nearly_equal(100.0f, 102.0f, 0.01f));
  // Infinities and NaN.
  EXPECT_TRUE(nearly_equal(kInf, kInf));
  EXPECT_FALSE(nearly_equal(kInf, -kInf));
  EXPECT_FALSE(nearly_equal(kInf, FLT_MAX));
  EXPECT_FALSE(nearly_equal(FLT_MAX, kInf, 1.0f));
  EXPECT_FALSE(nearly_equal(kNan, kNan));
  EXPECT_FALSE(nearly_equal(kNan, 0.0f, 1e30f));
}

TEST(VecScalar, NearlyEqualWithSeparateAbsoluteAndRelativeTolerances) {
  // Near zero only the absolute tolerance can hold.
  EXPECT_TRUE(nearly_equal(0.0f, 1e-5f, 1e-4f, 1e-6f));
  EXPECT_FALSE(nearly_equal(0.0f, 1e-3f, 1e-4f, 1e-6f));
  EXPECT_FALSE(nearly_equal(0.0f, 1e-30f, 0.0f, 0.5f));  // relative-only never matches 0
  // At large magnitudes the relative one takes over.
  EXPECT_TRUE(nearly_equal(1e4f, 1e4f + 0.5f, 1e-4f, 1e-4f));
  EXPECT_FALSE(nearly_equal(1e4f, 1e4f + 2.0f, 1e-4f, 1e-4f));
  EXPECT_TRUE(nearly_equal(1e20f, 1.00001e20f, 1e-4f, 1e-4f));
  // And a relative tolerance works at tiny magnitudes, where the book's form cannot.
  EXPECT_TRUE(nearly_equal(1e-20f, 1.5e-20f, 0.0f, 0.5f));
  EXPECT_FALSE(nearly_equal(1e-20f, 3e-20f, 0.0f, 0.5f));
  EXPECT_TRUE(nearly_equal(kInf, kInf, 0.0f, 0.0f));
  EXPECT_FALSE(nearly_equal(kInf, 1.0f, 1e30f, 1e30f));
  EXPECT_FALSE(nearly_equal(kNan, kNan, 1.0f, 1.0f));
}

TEST(Vec, LayoutAndAggregateInitialisation) {
  static_assert(sizeof(vec2) == 8 && sizeof(vec3) == 12 && sizeof(vec4) == 16);
  constexpr vec3 zero{};
  EXPECT_EQ(zero.x, 0.0f);
  EXPECT_EQ(zero.z, 0.0f);
  vec4 v{1, 2, 3, 4};
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[3], 4.0f);
  v[2] = 7.0f;
  EXPECT_EQ(v.z, 7.0f);
  const vec3 arr[2] = {{1, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(reinterpret_cast<const float*>(arr)[4], 5.0f);  // no padding between elements
  EXPECT_EQ((vec2{0.0f, 1.0f}), (vec2{-0.0f, 1.0f}));       // IEEE equality, not bits
  EXPECT_NE((vec3{kNan, 0, 0}), (vec3{kNan, 0, 0}));
}

TEST(Vec, OperatorsAreExactOnSmallIntegers) {
  const vec3 a{1, 2, 3}, b{4, -5, 6};
  EXPECT_EQ(a + b, (vec3{5, -3, 9}));
  EXPECT_EQ(a - b, (vec3{-3, 7, -3}));
  EXPECT_EQ(a * b, (vec3{4, -10, 18}));
  EXPECT_EQ(b / a, (vec3{4, -2.5f, 2}));
  EXPECT_EQ(a * 2.0f, (vec3{2, 4, 6}));
  EXPECT_EQ(2.0f * a, (vec3{2, 4, 6}));
  EXPECT_EQ(a / 2.0f, (vec3{0.5f, 1, 1.5f}));
  EXPECT_EQ(-a, (vec3{-1, -2, -3}));
  vec3 c = a;
  c += b;
  EXPECT_EQ(c, a + b);
  c -= b;
  EXPECT_EQ(c, a);
  c *= 3.0f;
  EXPECT_EQ(c, (vec3{3, 6, 9}));
  c /= 3.0f;
  EXPECT_EQ(c, a);
  c *= b;
  EXPECT_EQ(c, a * b);
  c /= b;
  EXPECT_EQ(c, a);
  EXPECT_EQ(dot(a, b), 12.0f);
  EXPECT_EQ(cross(a, b), (vec3{27, 6, -13}));
  EXPECT_EQ(cross(vec3{1, 0, 0}, vec3{0, 1, 0}), (vec3{0, 0, 1}));
  EXPECT_EQ(cross(vec2{1, 0}, vec2{0, 1}), 1.0f);
  EXPECT_EQ(cross(vec2{0, 1}, vec2{1, 0}), -1.0f);
  EXPECT_EQ(dot(vec4{1, 2, 3, 4}, vec4{5, 6, 7, 8}), 70.0f);
  EXPECT_EQ(dot(vec2{3, 4}, vec2{3, 4}), 25.0f);
  EXPECT_EQ(length(vec2{3, 4}), 5.0f);
  EXPECT_EQ(length(vec4{1, 1, 1, 1}), 2.0f);
  EXPECT_EQ(length_squared(a), 14.0f);
  EXPECT_EQ(distance(vec3{1, 1, 1}, vec3{3, 4, 7}), 7.0f);
  EXPECT_EQ(distance_squared(vec3{1, 1, 1}, vec3{3, 4, 7}), 49.0f);
  EXPECT_EQ(gyro::min(a, b), (vec3{1, -5, 3}));
  EXPECT_EQ(gyro::max(a, b), (vec3{4, 2, 6}));
  EXPECT_EQ(gyro::abs(b), (vec3{4, 5, 6}));
  EXPECT_EQ(lerp(a, b, 0.5f), (vec3{2.5f, -1.5f, 4.5f}));
  EXPECT_TRUE(is_finite(a));
  EXPECT_FALSE(is_finite(vec3{0, kInf, 0}));
  EXPECT_FALSE(is_finite(vec4{0, 0, 0, kNan}));
  EXPECT_TRUE(nearly_equal(a, a + vec3{1e-7f, 0, 0}));
  EXPECT_FALSE(nearly_equal(a, a + vec3{0, 0, 1e-5f}));
  EXPECT_TRUE(nearly_equal(a, a + vec3{0, 0, 1e-5f}, 1e-4f, 0.0f));
}

// dot, cross and length against double: errors relative to |a| |b| (dot and cross can
// cancel, so their own magnitude is no scale) and to the length.
TEST(Vec, DotCrossLengthAgainstDouble) {
  SplitMix64 rng(102);
  MaxError dot_err{"dot: |err| / (|a||b|)", 2.5e-7}, cross_err{"cross: |err| / (|a||b|)", 2.5e-7},
      ortho_err{"cross(a,b).a / (|a|^2 |b|)", 2e-7}, len_err{"length: relative error", 2.5e-7},
      dist_err{"distance: relative error", 4e-7};
  for (int i = 0; i < 200000; ++i) {
    const vec3 a = random_scaled_vec3(rng, -3, 3), b = random_scaled_vec3(rng, -3, 3);
    const double la = dlen(d(a)), lb = dlen(d(b));
    const double e_dot = std::fabs(dot(a, b) - ddot(d(a), d(b))) / (la * lb);
    const vec3 c = cross(a, b);
    const D3 cd = dcross(d(a), d(b));
    const double e_cross = dlen({c.x - cd.x, c.y - cd.y, c.z - cd.z}) / (la * lb);
    const double e_ortho = std::fabs(ddot(d(c), d(a))) / (la * la * lb);
    const double e_len = std::fabs(length(a) - la) / la;
    const double e_dist = std::fabs(distance(a, b) - dlen({double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z})) /
                          dlen({double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z});
    dot_err.add(e_dot, i), cross_err.add(e_cross, i), ortho_err.add(e_ortho, i), len_err.add(e_len, i);
    dist_err.add(e_dist, i);
  }
}

TEST(Vec, NormalizedIsUnitLengthAndKeepsTheDirectionAtEveryMagnitude) {
  SplitMix64 rng(103);
  MaxError unit_err{"|normalized(v)| - 1 (v from 1e-44 to 1e38)", 3e-7},
      dir_err{"normalized vs double, abs per component (|v| > 1e-38)", 3e-7},
      tiny_dir_err{"normalized vs double, abs per component (|v| < 1e-38)", 2.5e-7};
  for (int i = 0; i < 200000; ++i) {
    // Magnitudes from subnormal to near FLT_MAX, where length() alone would fail.
    const vec3 v = random_scaled_vec3(rng, -44, 38);
    if (v == vec3{}) continue;
    const vec3 n = normalized(v);
    const double l = dlen(d(v));
    const double e_unit = std::fabs(dlen(d(n)) - 1.0);
    const double e_dir =
        std::fmax(std::fabs(n.x - v.x / l), std::fmax(std::fabs(n.y - v.y / l), std::fabs(n.z - v.z / l)));
    // Subnormal components carry fewer bits, hence the looser bound on direction there.
    unit_err.add(e_unit, i), (l < 1e-38 ? tiny_dir_err : dir_err).add(e_dir, i);
    vec3 w = v;
    normalize(w);
    ASSERT_EQ(w, n);
  }
  // The rescaling is by powers of two, so 3-4-5 triangles stay exact at any exponent.
  EXPECT_EQ(normalized(vec3{std::ldexp(3.0f, -120), 0, std::ldexp(4.0f, -120)}), (vec3{0.6f, 0, 0.8f}));
  EXPECT_EQ(normalized(vec3{std::ldexp(3.0f, 120), 0, std::ldexp(-4.0f, 120)}), (vec3{0.6f, 0, -0.8f}));
  EXPECT_EQ(normalized(vec3{1e-45f, 0, 0}), (vec3{1, 0, 0}));
  EXPECT_NEAR(normalized(vec3{FLT_MAX, FLT_MAX, 0}).x, std::sqrt(0.5), 1e-7);
  EXPECT_EQ(normalized(vec2{0, -7}), (vec2{0, -1}));
  EXPECT_EQ(normalized(vec4{2, 2, 2, 2}), (vec4{0.5f, 0.5f, 0.5f, 0.5f}));
}

TEST(Vec, NormalizedZeroIsZeroAndNonFiniteIsNan) {
  EXPECT_EQ(normalized(vec3{}), vec3{});
  const vec3 nz = normalized(vec3{-0.0f, -0.0f, -0.0f});
  EXPECT_EQ(bits(nz.x) | bits(nz.y) | bits(nz.z), 0u);  // +0: a clean zero vector
  EXPECT_EQ(normalized(vec2{}), vec2{});
  EXPECT_EQ(normalized(vec4{}), vec4{});
  EXPECT_TRUE(std::isnan(normalized(vec3{kNan, 1, 0}).x));
  EXPECT_TRUE(std::isnan(normalized(vec3{kInf, 1, 0}).x));
  vec3 z{};
  normalize(z);
  EXPECT_EQ(z, vec3{});
}

TEST(Vec, AngleOfOrthogonalVectorsIsHalfPi) {
  EXPECT_EQ(angle(vec3{1, 0, 0}, vec3{0, 1, 0}), kHalfPi);
  EXPECT_EQ(angle(vec3{0, 0, 5}, vec3{-3, 0, 0}), kHalfPi);
  EXPECT_EQ(angle(vec2{2, 0}, vec2{0, -1}), kHalfPi);
  EXPECT_EQ(angle(vec3{1, 0, 0}, vec3{-2, 0, 0}), kPi);
  SplitMix64 rng(104);
  MaxError err{"angle(a, c) - pi/2, c = a x b in double rounded", 4e-7};
  for (int i = 0; i < 100000; ++i) {
    const vec3 a = random_vec3(rng, 100), b = random_vec3(rng, 100);
    // The cross product in double, rounded once: orthogonal to a up to 6e-8 relative. (The
    // float cross of nearly parallel a and b cancels, and is orthogonal only to 1e-7 * |a||b|.)
    const D3 cd = dcross(d(a), d(b));
    const vec3 c{static_cast<float>(cd.x), static_cast<float>(cd.y), static_cast<float>(cd.z)};
    err.add(std::fabs(angle(a, c) - M_PI / 2), i);
  }
}

TEST(Vec, AngleAgainstDouble) {
  SplitMix64 rng(105);
  MaxError mid{"angle in [0.1, pi-0.1] vs double atan2, rad", 4e-6}, all{"angle anywhere vs double, rad", 0.00015};
  for (int i = 0; i < 200000; ++i) {
    const vec3 a = random_scaled_vec3(rng, -10, 10), b = random_scaled_vec3(rng, -10, 10);
    const double ref = std::atan2(dlen(dcross(d(a), d(b))), ddot(d(a), d(b)));
    const double e = std::fabs(angle(a, b) - ref);
    (ref > 0.1 && ref < M_PI - 0.1 ? mid : all).add(e, i);
  }
  // Near 0 and pi acos is ill-conditioned: a cosine 1 ulp below 1 is already 3.5e-4 rad.
  EXPECT_LE(angle(vec3{1, 2, 3}, vec3{2, 4, 6}), 7e-4f);
  EXPECT_NEAR(angle(vec3{1, 2, 3}, vec3{-1, -2, -3}), kPi, 7e-4f);
  EXPECT_EQ(angle(vec3{}, vec3{1, 2, 3}), 0.0f);
  EXPECT_EQ(angle(vec3{1, 2, 3}, vec3{}), 0.0f);
  EXPECT_TRUE(std::isnan(angle(vec3{kNan, 0, 0}, vec3{1, 0, 0})));
}

TEST(Vec, ProjectAndPerpendicularSplitAVector) {
  SplitMix64 rng(106);
  MaxError sum_err{"project + perpendicular - v, / |v|", 2.5e-7}, orth_err{"perpendicular . dir / (|v||dir|)", 6e-7},
      par_err{"|project x dir| / (|project||dir|)", 1.2e-7}, ref_err{"project vs double, / |v|", 6e-7};
  for (int i = 0; i < 200000; ++i) {
    const vec3 v = random_scaled_vec3(rng, -3, 3), dir = random_scaled_vec3(rng, -3, 3);
    const vec3 p = project(v, dir), q = perpendicular(v, dir);
    const double lv = dlen(d(v)), ld = dlen(d(dir)), lp = dlen(d(p));
    const vec3 s = p + q;
    const double e_sum = dlen({double(s.x) - v.x, double(s.y) - v.y, double(s.z) - v.z}) / lv;
    const double e_orth = std::fabs(ddot(d(q), d(dir))) / (lv * ld);
    const double e_par = lp == 0 ? 0 : dlen(dcross(d(p), d(dir))) / (lp * ld);
    const double k = ddot(d(v), d(dir)) / ddot(d(dir), d(dir));
    const double e_ref = dlen({p.x - k * dir.x, p.y - k * dir.y, p.z - k * dir.z}) / lv;
    sum_err.add(e_sum, i), orth_err.add(e_orth, i), par_err.add(e_par, i), ref_err.add(e_ref, i);
  }
  const vec3 v{3, 4, 5};
  EXPECT_EQ(project(v, vec3{0, 2, 0}), (vec3{0, 4, 0}));
  EXPECT_EQ(perpendicular(v, vec3{0, 2, 0}), (vec3{3, 0, 5}));
  EXPECT_EQ(project(v, vec3{}), vec3{});
  EXPECT_EQ(perpendicular(v, vec3{}), v);
  EXPECT_EQ(project(vec2{3, 4}, vec2{1, 0}), (vec2{3, 0}));
}

TEST(Vec, ReflectMirrorsAboutTheNormalPlane) {
  SplitMix64 rng(107);
  MaxError len_err{"|reflect| - |v|, / |v|", 1.5e-6}, dot_err{"reflect.n + v.n, / |v|", 1.5e-6},
      twice_err{"reflect twice - v, / |v|", 2.5e-6}, tan_err{"tangential part changed, / |v|", 8e-7};
  for (int i = 0; i < 200000; ++i) {
    const vec3 v = random_scaled_vec3(rng, -3, 3);
    const vec3 n = normalized(random_vec3(rng, 1));
    const vec3 r = reflect(v, n);
    const double lv = dlen(d(v));
    const double e_len = std::fabs(dlen(d(r)) - lv) / lv;
    const double e_dot = std::fabs(ddot(d(r), d(n)) + ddot(d(v), d(n))) / lv;
    const vec3 rr = reflect(r, n);
    const double e_twice = dlen({double(rr.x) - v.x, double(rr.y) - v.y, double(rr.z) - v.z}) / lv;
    const vec3 tr = perpendicular(r, n), tv = perpendicular(v, n);
    const double e_tan = dlen({double(tr.x) - tv.x, double(tr.y) - tv.y, double(tr.z) - tv.z}) / lv;
    len_err.add(e_len, i), dot_err.add(e_dot, i), twice_err.add(e_twice, i), tan_err.add(e_tan, i);
  }
  EXPECT_EQ(reflect(vec3{1, -1, 0}, vec3{0, 1, 0}), (vec3{1, 1, 0}));
  EXPECT_EQ(reflect(vec2{2, -3}, vec2{0, 1}), (vec2{2, 3}));
  EXPECT_EQ(reflect(vec3{1, 2, 3}, vec3{0, 0, -1}), (vec3{1, 2, -3}));
}

}  // namespace
}  // namespace gyro
