// Transforms, views and projections (include/gyro/math_transform.hpp): the right-hand
// rule of the basic rotations, the book's Euler order, scale * rotation * translation,
// look_at mapping the eye to the origin and the target onto +z (left-handed) or -z
// (right-handed), and projections mapping the near plane to depth 0 and the far plane to 1.
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

double max_diff(const vec3& a, const vec3& b) {
  return std::fmax(std::fabs(double(a.x) - b.x), std::fmax(std::fabs(double(a.y) - b.y), std::fabs(double(a.z) - b.z)));
}
template <class M>
double max_diff(const M& a, const M& b) {
  double e = 0;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) e = std::fmax(e, std::fabs(double(a.m[i][j]) - b.m[i][j]));
  return e;
}

struct D3 {
  double x, y, z;
};
/// Rodrigues' rotation in double (right-hand rule about a unit axis).
D3 drotate(D3 n, double a, D3 v) {
  const double c = std::cos(a), s = std::sin(a), k = (n.x * v.x + n.y * v.y + n.z * v.z) * (1 - c);
  const D3 x{n.y * v.z - n.z * v.y, n.z * v.x - n.x * v.z, n.x * v.y - n.y * v.x};
  return {v.x * c + x.x * s + n.x * k, v.y * c + x.y * s + n.y * k, v.z * c + x.z * s + n.z * k};
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

/// p through a projection matrix, divided by w; w itself is returned in *w.
vec3 project_point(const vec3& p, const mat4& proj, float* w) {
  const vec4 c = vec4{p.x, p.y, p.z, 1.0f} * proj;
  *w = c.w;
  return {c.x / c.w, c.y / c.w, c.z / c.w};
}

TEST(Transform, TranslationMovesPointsAndScaleScalesAxes) {
  const mat4 t = translation(vec3{1, -2, 3});
  EXPECT_EQ(t, translation(1, -2, 3));
  EXPECT_EQ(multiply_point(vec3{10, 20, 30}, t), (vec3{11, 18, 33}));
  EXPECT_EQ(multiply_vector(vec3{10, 20, 30}, t), (vec3{10, 20, 30}));
  EXPECT_EQ(translation_of(t), (vec3{1, -2, 3}));
  const mat4 s = scale(vec3{2, 3, 4});
  EXPECT_EQ(s, scale(2, 3, 4));
  EXPECT_EQ(multiply_point(vec3{1, 1, 1}, s), (vec3{2, 3, 4}));
  // Scale first, then translate: v * S * T.
  EXPECT_EQ(multiply_point(vec3{1, 1, 1}, s * t), (vec3{3, 1, 7}));
  EXPECT_EQ(multiply_point(vec3{1, 1, 1}, t * s), (vec3{4, -3, 16}));
}

TEST(Transform, BasicRotationsFollowTheRightHandRule) {
  const vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_LE(max_diff(multiply_vector(x, rotation_z(kHalfPi)), y), 1e-7);
  EXPECT_LE(max_diff(multiply_vector(y, rotation_x(kHalfPi)), z), 1e-7);
  EXPECT_LE(max_diff(multiply_vector(z, rotation_y(kHalfPi)), x), 1e-7);
  EXPECT_LE(max_diff(multiply_vector(y, rotation_z(kHalfPi)), -x), 1e-7);
  // Row i of a rotation is the image of axis i.
  EXPECT_EQ(row(rotation3_z(0.3f), 0), x * rotation3_z(0.3f));
  EXPECT_EQ(rotation3_x(0.0f), mat3::identity());
  EXPECT_EQ(rotation_axis_angle(vec3{}, 1.0f), mat4::identity());
  SplitMix64 rng(401);
  MaxError err{"rotation3_x/y/z vs rotation3_axis_angle", 1.2e-7},
      ref{"axis-angle rotation vs double Rodrigues, / |v|", 5e-7}, ortho{"R R^T - I (axis-angle and Euler)", 2.5e-6},
      det_err{"det(R) - 1", 1.5e-6};
  for (int it = 0; it < 100000; ++it) {
    const float a = uniform(rng, -7, 7);
    const double e = std::fmax(std::fmax(max_diff(rotation3_x(a), rotation3_axis_angle(x, a)),
                                         max_diff(rotation3_y(a), rotation3_axis_angle(y, a))),
                               max_diff(rotation3_z(a), rotation3_axis_angle(z, a)));
    err.add(e, it);
    ASSERT_EQ(rotation_x(a), to_mat4(rotation3_x(a)));
    const vec3 axis = random_vec3(rng, 1), v = random_vec3(rng, 10);
    const vec3 n = normalized(axis);
    const D3 r = drotate({n.x, n.y, n.z}, a, {v.x, v.y, v.z});
    const vec3 got = v * rotation3_axis_angle(axis, a);
    const double er =
        std::fmax(std::fabs(got.x - r.x), std::fmax(std::fabs(got.y - r.y), std::fabs(got.z - r.z))) / length(v);
    ref.add(er, it);
    for (const mat3& m :
         {rotation3_axis_angle(axis, a), rotation3_euler(a, uniform(rng, -4, 4), uniform(rng, -4, 4))}) {
      const double eo = max_diff(m * transpose(m), mat3::identity());
      ortho.add(eo, it);
      det_err.add(std::fabs(determinant(m) - 1.0), it);
    }
  }
}

TEST(Transform, EulerAnglesApplyRollThenPitchThenYaw) {
  SplitMix64 rng(402);
  MaxError ref{"rotation_euler vs double roll-pitch-yaw, / |v|", 4e-7};
  for (int it = 0; it < 100000; ++it) {
    const float p = uniform(rng, -4, 4), y = uniform(rng, -4, 4), r = uniform(rng, -4, 4);
    // As a product of the basic rotations, to the bit (the 4x4 adds only exact zeros).
    ASSERT_EQ(rotation_euler(p, y, r), rotation_z(r) * rotation_x(p) * rotation_y(y));
    ASSERT_EQ(rotation3_euler(p, y, r), rotation3_z(r) * rotation3_x(p) * rotation3_y(y));
    const vec3 v = random_vec3(rng, 10);
    D3 d{v.x, v.y, v.z};
    d = drotate({0, 0, 1}, r, d);
    d = drotate({1, 0, 0}, p, d);
    d = drotate({0, 1, 0}, y, d);
    const vec3 got = multiply_vector(v, rotation_euler(p, y, r));
    const double e =
        std::fmax(std::fabs(got.x - d.x), std::fmax(std::fabs(got.y - d.y), std::fabs(got.z - d.z))) / length(v);
    ref.add(e, it);
  }
}

TEST(Transform, TransformIsScaleThenRotationThenTranslation) {
  SplitMix64 rng(403);
  MaxError err{"TRS point vs rotate(q, p * s) + t, / (|p| |s| + |t|)", 2.5e-7};
  for (int it = 0; it < 20000; ++it) {
    const vec3 s{uniform(rng, 0.1, 10), uniform(rng, -10, 10), uniform(rng, 0.1, 10)};
    const vec3 e{uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, -4, 4)};
    const vec3 t = random_vec3(rng, 1000), axis = random_vec3(rng, 1);
    const float a = uniform(rng, -7, 7);
    const quat q = from_axis_angle(axis, a);
    // Built directly, equal to the product of the three matrices.
    ASSERT_EQ(transform(s, e, t), scale(s) * rotation_euler(e.x, e.y, e.z) * translation(t));
    ASSERT_EQ(transform(s, axis, a, t), scale(s) * rotation_axis_angle(axis, a) * translation(t));
    ASSERT_EQ(transform(s, q, t), scale(s) * to_mat4(q) * translation(t));
    const vec3 p = random_vec3(rng, 10);
    const vec3 expect = rotate(q, p * s) + t;
    err.add(max_diff(multiply_point(p, transform(s, q, t)), expect) / (length(p) * length(s) + length(t)), it);
  }
}

TEST(Transform, LookAtLeftHandedMapsEyeToOriginAndTargetToPlusZ) {
  EXPECT_EQ(look_at(vec3{}, vec3{0, 0, 5}, vec3{0, 1, 0}), mat4::identity());
  EXPECT_EQ(look_at_rh(vec3{}, vec3{0, 0, -5}, vec3{0, 1, 0}), mat4::identity());
  SplitMix64 rng(404);
  MaxError lh{"look_at: target - (0, 0, d), / (|eye| + d)", 5e-7},
      rh{"look_at_rh: target - (0, 0, -d), / (|eye| + d)", 5e-7}, rigid{"view R R^T - I", 1e-6},
      up_err{"up's view x / |up|", 5e-7}, eye_err{"inverse_rigid(view) origin - eye, / |eye| + d", 6e-7};
  for (int it = 0; it < 100000; ++it) {
    const vec3 eye = random_vec3(rng, 100), target = random_vec3(rng, 100), up = random_vec3(rng, 1);
    const vec3 f = target - eye;
    // Skip an up within ~6 degrees of the view direction: the camera's roll is ill-defined.
    if (length(cross(normalized(up), normalized(f))) < 0.1f) continue;
    const double dist = length(f), scale_ = length(eye) + dist;
    for (bool right_handed : {false, true}) {
      const mat4 v = right_handed ? look_at_rh(eye, target, up) : look_at(eye, target, up);
      // The eye goes to the origin exactly: the translation is minus the same dot products.
      ASSERT_EQ(multiply_point(eye, v), vec3{}) << it;
      const vec3 t = multiply_point(target, v);
      const double e = max_diff(t, vec3{0, 0, static_cast<float>(right_handed ? -dist : dist)}) / scale_;
      (right_handed ? rh : lh).add(e, it);
      // up lands in the +y half of the view's yz plane.
      const vec3 u = multiply_vector(up, v);
      ASSERT_GT(u.y, 0.0f);
      up_err.add(std::fabs(u.x) / length(up), it);
      // A proper rotation (det +1) plus translation, so inverse_rigid inverts it.
      const mat3 r = to_mat3(v);
      const double eo = max_diff(r * transpose(r), mat3::identity());
      rigid.add(eo, it);
      ASSERT_NEAR(determinant(r), 1.0f, 1e-6f);
      eye_err.add(max_diff(multiply_point(vec3{}, inverse_rigid(v)), eye) / scale_, it);
    }
  }
  // Handedness: looking down +z (LH) or -z (RH) with +y up, world +x is the camera's right.
  EXPECT_GT(multiply_point(vec3{1, 0, 0}, look_at(vec3{0, 0, -5}, vec3{}, vec3{0, 1, 0})).x, 0.0f);
  EXPECT_GT(multiply_point(vec3{1, 0, 0}, look_at_rh(vec3{0, 0, 5}, vec3{}, vec3{0, 1, 0})).x, 0.0f);
  // Looking down -z, a left-handed camera has world +x on its left.
  EXPECT_LT(multiply_point(vec3{1, 0, 0}, look_at(vec3{0, 0, 5}, vec3{}, vec3{0, 1, 0})).x, 0.0f);
}

TEST(Transform, PerspectiveMapsNearToDepthZeroAndFarToOne) {
  SplitMix64 rng(405);
  MaxError far_err{"depth at the far plane - 1", 5e-7}, edge_err{"frustum edge -> NDC x, y = +-1", 5e-7},
      near_xy{"near-plane point -> NDC x, y", 5e-7};
  for (int it = 0; it < 50000; ++it) {
    const float fov = uniform(rng, 0.2, 2.8), aspect = uniform(rng, 0.3, 3);
    const float n = uniform(rng, 0.01, 2), f = n * uniform(rng, 2, 1e4);
    const float u = uniform(rng, -1, 1), v = uniform(rng, -1, 1);
    const double th = std::tan(fov / 2.0);
    for (bool right_handed : {false, true}) {
      const mat4 p = right_handed ? perspective_rh(fov, aspect, n, f) : perspective(fov, aspect, n, f);
      const float sign = right_handed ? -1.0f : 1.0f;
      float w;
      // A point on the near plane, inside the frustum: depth exactly 0.
      const vec3 near_pt{static_cast<float>(u * n * th * aspect), static_cast<float>(v * n * th), sign * n};
      const vec3 a = project_point(near_pt, p, &w);
      ASSERT_EQ(a.z, 0.0f) << it;
      ASSERT_GT(w, 0.0f);
      near_xy.add(std::fmax(std::fabs(a.x - double(u)), std::fabs(a.y - double(v))), it);
      // On the far plane: depth 1 up to rounding.
      const vec3 far_pt{static_cast<float>(u * f * th * aspect), static_cast<float>(v * f * th), sign * f};
      const vec3 b = project_point(far_pt, p, &w);
      far_err.add(std::fabs(b.z - 1.0), it);
      const vec3 edge{static_cast<float>(f * th * aspect), static_cast<float>(-f * th), sign * f};
      const vec3 c = project_point(edge, p, &w);
      const double ee = std::fmax(std::fabs(c.x - 1.0), std::fabs(c.y + 1.0));
      edge_err.add(ee, it);
      // Depth grows monotonically from near to far, and stays in [0, 1].
      float last = 0.0f;
      for (int k = 1; k <= 16; ++k) {
        const float z = n + (f - n) * static_cast<float>(k) / 16.0f;
        const float depth = project_point(vec3{0, 0, sign * z}, p, &w).z;
        ASSERT_GE(depth, last) << it;
        ASSERT_LE(depth, 1.0f + 5e-7f) << it;
        last = depth;
      }
      // Behind the near plane depth is negative: clipped.
      ASSERT_LT(project_point(vec3{0, 0, sign * n * 0.5f}, p, &w).z, 0.0f);
    }
  }
}

TEST(Transform, OrthographicMapsTheBoxToTheUnitCube) {
  SplitMix64 rng(406);
  MaxError err{"box corners -> NDC corners, / offset scale", 4e-7};
  for (int it = 0; it < 50000; ++it) {
    const float l = uniform(rng, -100, 100), r = l + uniform(rng, 0.1, 200);
    const float b = uniform(rng, -100, 100), t = b + uniform(rng, 0.1, 200);
    const float n = uniform(rng, -10, 10), f = n + uniform(rng, 0.1, 1000);
    for (bool right_handed : {false, true}) {
      const mat4 p = right_handed ? orthographic_rh(l, r, b, t, n, f) : orthographic(l, r, b, t, n, f);
      const float sign = right_handed ? -1.0f : 1.0f;
      float w;
      const vec3 lo = project_point(vec3{l, b, sign * n}, p, &w);
      ASSERT_EQ(w, 1.0f);
      ASSERT_EQ(lo.z, 0.0f) << it;  // near plane: exactly 0
      const vec3 hi = project_point(vec3{r, t, sign * f}, p, &w);
      const double e = std::fmax(max_diff(lo, vec3{-1, -1, 0}), max_diff(hi, vec3{1, 1, 1}));
      // Relative to the box's offset from the origin: (l + r) / (l - r) cancels.
      const double scale_ =
          std::fmax(std::fabs(l) + std::fabs(r), std::fabs(b) + std::fabs(t)) / std::fmin(r - l, t - b) +
          std::fabs(n) / (f - n) + 1;
      err.add(e / scale_, it);
    }
  }
  EXPECT_EQ(orthographic(-1, 1, -1, 1, 0, 1), mat4::identity());
}

}  // namespace
}  // namespace gyro
