// Quaternions (include/gyro/math_quat.hpp): Hamilton's product, agreement with the
// axis-angle and Euler matrices of math_transform.hpp in the row-vector convention,
// rotation against a double Rodrigues reference, inverses, slerp/nlerp and integration.
// Each property prints its largest error; the bounds are about twice the measured maxima
// (GCC 12, x86-64).
#include "gyro/math.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace gyro {
namespace {

using testing::SplitMix64;

// Not inlined: with it inlined, GCC 12 -O3 (its SLP vectoriser) gave mat_test's double
// references values other than the rounded floats the code under test received (an
// adjugate product that is exactly zero came out as 2e-6; clang, and GCC with
// -fno-tree-slp-vectorize, were right). A call hands over the rounded float, once.
[[gnu::noinline]] float uniform(SplitMix64& rng, double lo, double hi) {
  return static_cast<float>(lo + (hi - lo) * rng.u());
}
vec3 random_vec3(SplitMix64& rng, double r) { return {uniform(rng, -r, r), uniform(rng, -r, r), uniform(rng, -r, r)}; }
quat random_unit(SplitMix64& rng) { return from_axis_angle(random_vec3(rng, 1), uniform(rng, -7, 7)); }

struct D3 {
  double x, y, z;
};
D3 dcross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double ddot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/// Rodrigues' rotation of v by angle about a unit axis, in double.
D3 drotate(D3 axis, double angle, D3 v) {
  const double n = std::sqrt(ddot(axis, axis));
  axis = {axis.x / n, axis.y / n, axis.z / n};
  const double c = std::cos(angle), s = std::sin(angle), k = ddot(axis, v) * (1 - c);
  const D3 x = dcross(axis, v);
  return {v.x * c + x.x * s + axis.x * k, v.y * c + x.y * s + axis.y * k, v.z * c + x.z * s + axis.z * k};
}
double max_diff(const mat3& a, const mat3& b) {
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e = std::fmax(e, std::fabs(double(a.m[i][j]) - b.m[i][j]));
  return e;
}
double max_diff(const vec3& a, const vec3& b) {
  return std::fmax(std::fabs(double(a.x) - b.x), std::fmax(std::fabs(double(a.y) - b.y), std::fabs(double(a.z) - b.z)));
}
double max_diff(const quat& a, const quat& b) {
  return std::fmax(std::fmax(std::fabs(double(a.x) - b.x), std::fabs(double(a.y) - b.y)),
                   std::fmax(std::fabs(double(a.z) - b.z), std::fabs(double(a.w) - b.w)));
}
/// The rotation angle between two unit quaternions, in double: the angle of conj(a) * b,
/// as 2 atan2(|vector part|, |scalar part|), which stays accurate near 0 (acos does not).
double rotation_angle(const quat& a, const quat& b) {
  const double ax = -double(a.x), ay = -double(a.y), az = -double(a.z), aw = a.w;
  const double x = aw * b.x + ax * b.w + ay * b.z - az * b.y, y = aw * b.y - ax * b.z + ay * b.w + az * b.x;
  const double z = aw * b.z + ax * b.y - ay * b.x + az * b.w, w = aw * b.w - ax * b.x - ay * b.y - az * b.z;
  return 2 * std::atan2(std::sqrt(x * x + y * y + z * z), std::fabs(w));
}

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

TEST(Quat, HamiltonProductOnTheBasis) {
  const quat i{1, 0, 0, 0}, j{0, 1, 0, 0}, k{0, 0, 1, 0}, one{};
  EXPECT_EQ(i * j, k);
  EXPECT_EQ(j * k, i);
  EXPECT_EQ(k * i, j);
  EXPECT_EQ(j * i, -k);
  EXPECT_EQ(i * i, -one);
  EXPECT_EQ(i * j * k, -one);  // i j k = -1
  EXPECT_EQ(quat{}, quat::identity());
  EXPECT_EQ(quat{}.w, 1.0f);
  EXPECT_EQ(conjugate(quat{1, 2, 3, 4}), (quat{-1, -2, -3, 4}));
  EXPECT_EQ(dot(quat{1, 2, 3, 4}, quat{1, 1, 1, 1}), 10.0f);
  EXPECT_EQ(length(quat{1, 1, 1, 1}), 2.0f);
  EXPECT_EQ(inverse(quat{0, 0, 0, 2}), (quat{0, 0, 0, 0.5f}));
  EXPECT_EQ(inverse(quat{0, 0, 0, 0}), (quat{0, 0, 0, 0}));
  EXPECT_EQ(normalized(quat{0, 0, 0, 0}), quat::identity());
  EXPECT_EQ(normalized(quat{0, 0, 3, 4}), (quat{0, 0, 0.6f, 0.8f}));
  EXPECT_EQ(normalized(quat{0, 0, 3e-30f, 0}), (quat{0, 0, 1, 0}));
  EXPECT_EQ(from_axis_angle(vec3{}, 1.0f), quat::identity());
  EXPECT_EQ(from_axis_angle(vec3{0, 0, 5}, 0.0f), quat::identity());
  SplitMix64 rng(301);
  for (int it = 0; it < 1000; ++it) {
    const quat q = random_unit(rng);
    ASSERT_EQ(quat::identity() * q, q);
    ASSERT_EQ(q * quat::identity(), q);
  }
}

TEST(Quat, ToMat3EqualsTheAxisAngleMatrix) {
  SplitMix64 rng(302);
  MaxError err{"to_mat3(from_axis_angle) - rotation3_axis_angle", 1.5e-6}, ortho{"to_mat3(q) * transpose - I", 2.5e-6},
      det_err{"det(to_mat3(q)) - 1", 3e-6};
  for (int it = 0; it < 100000; ++it) {
    const vec3 axis = random_vec3(rng, 1);
    const float a = uniform(rng, -7, 7);
    const mat3 m = to_mat3(from_axis_angle(axis, a));
    const double e = max_diff(m, rotation3_axis_angle(axis, a));
    err.add(e, it);
    ortho.add(max_diff(m * transpose(m), mat3::identity()), it);
    det_err.add(std::fabs(determinant(m) - 1.0), it);
    ASSERT_EQ(to_mat3(to_mat4(from_axis_angle(axis, a))), m);
  }
  // The right-hand rule, in the row-vector convention.
  const mat3 z90 = to_mat3(from_axis_angle(vec3{0, 0, 1}, kHalfPi));
  EXPECT_LE(max_diff(vec3{1, 0, 0} * z90, vec3{0, 1, 0}), 1e-7);
  EXPECT_LE(max_diff(row(z90, 0), vec3{0, 1, 0}), 1e-7);  // row 0 is the image of +x
}

TEST(Quat, RotateAgainstTheMatrixAndDoubleRodrigues) {
  SplitMix64 rng(303);
  MaxError mat_err{"rotate(q, v) - v * to_mat3(q), / |v|", 8e-7},
      ref_err{"rotate(q, v) vs double Rodrigues, / |v|", 1.5e-6},
      back_err{"rotate(inverse(q), rotate(q, v)) - v, / |v|", 1.5e-6},
      conj_err{"rotate(conjugate(q), rotate(q, v)) - v, / |v|", 2.5e-6};
  for (int it = 0; it < 200000; ++it) {
    const vec3 axis = random_vec3(rng, 1), v = random_vec3(rng, 100);
    const float a = uniform(rng, -7, 7);
    const quat q = from_axis_angle(axis, a);
    const double lv = length(v);
    const vec3 r = rotate(q, v);
    const D3 ref = drotate({axis.x, axis.y, axis.z}, a, {v.x, v.y, v.z});
    const double e_mat = max_diff(r, v * to_mat3(q)) / lv;
    const double e_ref =
        std::fmax(std::fabs(r.x - ref.x), std::fmax(std::fabs(r.y - ref.y), std::fabs(r.z - ref.z))) / lv;
    const double e_back = max_diff(rotate(inverse(q), r), v) / lv;
    const double e_conj = max_diff(rotate(conjugate(q), r), v) / lv;
    mat_err.add(e_mat, it), ref_err.add(e_ref, it), back_err.add(e_back, it), conj_err.add(e_conj, it);
  }
}

TEST(Quat, ProductComposesRotationsRightToLeft) {
  SplitMix64 rng(304);
  MaxError rot_err{"rotate(a*b, v) - rotate(a, rotate(b, v)), / |v|", 2e-6},
      mat_err{"to_mat3(a*b) - to_mat3(b)*to_mat3(a)", 2e-6}, inv_err{"q * inverse(q) - identity (non-unit q)", 5e-7},
      len_err{"|a*b| - 1", 5e-7};
  for (int it = 0; it < 100000; ++it) {
    const quat a = random_unit(rng), b = random_unit(rng);
    const vec3 v = random_vec3(rng, 10);
    const double e_rot = max_diff(rotate(a * b, v), rotate(a, rotate(b, v))) / length(v);
    const double e_mat = max_diff(to_mat3(a * b), to_mat3(b) * to_mat3(a));
    const quat c = a * uniform(rng, 0.1, 10);
    const double e_inv =
        std::fmax(max_diff(c * inverse(c), quat::identity()), max_diff(inverse(c) * c, quat::identity()));
    rot_err.add(e_rot, it), mat_err.add(e_mat, it), inv_err.add(e_inv, it);
    len_err.add(std::fabs(length(a * b) - 1.0), it);
  }
}

TEST(Quat, FromEulerEqualsRotationEuler) {
  SplitMix64 rng(305);
  MaxError err{"to_mat3(from_euler) - rotation3_euler", 1.5e-6};
  for (int it = 0; it < 100000; ++it) {
    const float p = uniform(rng, -4, 4), y = uniform(rng, -4, 4), r = uniform(rng, -4, 4);
    const double e = max_diff(to_mat3(from_euler(p, y, r)), rotation3_euler(p, y, r));
    err.add(e, it);
  }
  // Roll applies first: roll 90 degrees takes +x to +y, then yaw 90 degrees takes +y to +y.
  const quat q = from_euler(0.0f, kHalfPi, kHalfPi);
  EXPECT_LE(max_diff(rotate(q, vec3{1, 0, 0}), vec3{0, 1, 0}), 2.5e-7);
  EXPECT_LE(max_diff(rotate(q, vec3{0, 0, 1}), vec3{1, 0, 0}), 2.5e-7);
}

TEST(Quat, SlerpHitsItsEndpointsAtConstantSpeedAndUnitLength) {
  SplitMix64 rng(306);
  MaxError unit_err{"|slerp| - 1", 5e-7}, speed_err{"angle(a, slerp(t)) - t * angle(a, b), rad", 2e-6},
      near_end{"slerp endpoints when nearly parallel (nlerp branch)", 5e-7}, nlerp_unit{"|nlerp| - 1", 4e-7},
      nlerp_end{"nlerp endpoints", 5e-7};
  for (int it = 0; it < 50000; ++it) {
    const quat a = random_unit(rng);
    // Half the pairs far apart, half within the nlerp fallback's 3.6 degrees.
    const quat b = it % 2 ? random_unit(rng) : from_axis_angle(random_vec3(rng, 1), uniform(rng, -0.06, 0.06)) * a;
    const quat e = dot(a, b) < 0.0f ? -b : b;
    const double total = rotation_angle(a, b);
    if (std::fabs(dot(a, b)) <= 0.9995f) {
      ASSERT_EQ(slerp(a, b, 0.0f), a) << it;
      ASSERT_EQ(slerp(a, b, 1.0f), e) << it;
    } else {
      const double ne = std::fmax(max_diff(slerp(a, b, 0.0f), a), max_diff(slerp(a, b, 1.0f), e));
      near_end.add(ne, it);
    }
    // The shorter arc: -b is the same rotation and gives the same bits.
    ASSERT_EQ(slerp(a, -b, 0.3f), slerp(a, b, 0.3f));
    for (int k = 0; k <= 8; ++k) {
      const float t = static_cast<float>(k) / 8.0f;
      const quat s = slerp(a, b, t);
      const double eu = std::fabs(length(s) - 1.0);
      const double es = std::fabs(rotation_angle(a, s) - t * total);
      unit_err.add(eu, it), speed_err.add(es, it);
      nlerp_unit.add(std::fabs(length(nlerp(a, b, t)) - 1.0), it);
    }
    nlerp_end.add(std::fmax(max_diff(nlerp(a, b, 0.0f), a), max_diff(nlerp(a, b, 1.0f), e)), it);
  }
  // Halfway between the identity and a quarter turn is an eighth turn.
  const quat h = slerp(quat::identity(), from_axis_angle(vec3{0, 1, 0}, kHalfPi), 0.5f);
  EXPECT_LE(max_diff(h, from_axis_angle(vec3{0, 1, 0}, kHalfPi / 2)), 2e-7);
}

TEST(Quat, IntegrateConstantAngularVelocity) {
  SplitMix64 rng(307);
  MaxError step_err{"one step: angle vs 2 atan(|w| dt / 2), rad", 2e-7},
      long_err{"1000 steps vs 1000 exact steps, rad", 6e-5},
      true_err{"1000 steps vs the true rotation |w| T, rad", 6e-5}, axis_err{"a vector along w moved by", 5e-5};
  for (int it = 0; it < 200; ++it) {
    const quat q0 = random_unit(rng);
    const vec3 w = random_vec3(rng, 3);
    const float dt = 1.0f / 1000.0f;
    // One step turns about w's axis by 2 atan(|w| dt / 2).
    const quat q1 = integrate(q0, w, dt);
    const double turned = rotation_angle(q1, q0);
    const double expect = 2 * std::atan(length(w) * dt / 2);
    step_err.add(std::fabs(turned - expect), it);
    ASSERT_LE(std::fabs(length(q1) - 1.0f), 3e-7f);
    // 1000 steps against the rotation they should add up to: 1000 times that angle about w
    // (world frame, so applied after q0). What is left is rounding.
    quat q = q0;
    for (int s = 0; s < 1000; ++s) q = integrate(q, w, dt);
    const quat exact = from_axis_angle(w, static_cast<float>(1000 * expect)) * q0;
    const double e = rotation_angle(q, exact);
    long_err.add(e, it);
    // Against the true solution the first-order step lags by 2 (h - atan h) per step:
    // up to 1.2e-5 rad over these 1000 steps.
    true_err.add(rotation_angle(q, from_axis_angle(w, length(w) * 1.0f) * q0), it);
    // And the axis of the motion is w's: a vector along w does not move.
    const vec3 n = normalized(w);
    axis_err.add(max_diff(rotate(q, rotate(conjugate(q0), n)), n), it);
  }
  // No angular velocity: the orientation only gets normalised.
  const quat q{0.1f, 0.2f, 0.3f, 0.9f};
  EXPECT_EQ(integrate(q, vec3{}, 0.016f), normalized(q));
}

}  // namespace
}  // namespace gyro
