// Cameras (gyro/camera.hpp): projection matrices against hand-computed values and a
// binary64 reference, the view matrix against look_at and under a drifted orientation,
// the orbit controller (placement, clamping, wrapping, panning, bad input), picking rays
// through the centre and the corners against the frustum computed analytically in double,
// project / unproject round trips with measured errors, and check_camera's statuses.
#include "gyro/camera.hpp"

#include "core/error.hpp"
#include "gyro/frustum.hpp"
#include "gyro/math_transform.hpp"
#include "gyro/raycast.hpp"
#include "random_shapes.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

struct D3 {
  double x, y, z;
};
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(const D3& a) { return std::sqrt(dot(a, a)); }
D3 unit(const D3& a) { return a * (1.0 / norm(a)); }
D3 row(const mat3& m, int r) { return {m.m[r][0], m.m[r][1], m.m[r][2]}; }
double dist(const D3& a, const D3& b) { return norm(a - b); }
double dist(const vec3& a, const D3& b) { return norm(d3(a) - b); }

// The world point at view-space (x, y, z) of a camera, in double, from its (already
// orthonormal) float axes.
D3 view_to_world(const Camera& c, double x, double y, double z) {
  return d3(c.position) + row(c.orientation, 0) * x + row(c.orientation, 1) * y + row(c.orientation, 2) * z;
}

TEST(Camera, PerspectiveMatrixMatchesHandComputedValues) {
  // fov 90 degrees: cot(45 deg) = 1; aspect 2; near 1, far 11: far / (far - near) = 1.1.
  const mat4 p = projection_matrix(perspective_camera(kHalfPi, 2.0f, 1.0f, 11.0f));
  const float want[4][4] = {{0.5f, 0, 0, 0}, {0, 1.0f, 0, 0}, {0, 0, 1.1f, 1.0f}, {0, 0, -1.1f, 0}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(p.m[i][j], want[i][j], 2e-7) << i << "," << j;
  // The near plane goes to depth 0, the far plane to 1, the top edge to y = 1.
  auto ndc = [&](float x, float y, float z) {
    const vec4 c = vec4{x, y, z, 1.0f} * p;
    return vec3{c.x / c.w, c.y / c.w, c.z / c.w};
  };
  EXPECT_NEAR(ndc(0, 0, 1).z, 0.0f, 1e-7);
  EXPECT_NEAR(ndc(0, 0, 11).z, 1.0f, 1e-6);
  EXPECT_NEAR(ndc(0, 5, 5).y, 1.0f, 1e-6);
  EXPECT_NEAR(ndc(10, 0, 5).x, 1.0f, 1e-6);

  // A general lens against binary64 (std::tan is fine in a test).
  const double fov = 1.0471975511965976, aspect = 16.0 / 9.0, n = 0.1, f = 100.0;
  const mat4 q = projection_matrix(perspective_camera(float(fov), float(aspect), float(n), float(f)));
  const double cot = 1.0 / std::tan(fov / 2);
  EXPECT_NEAR(q.m[0][0], cot / aspect, 4e-7 * cot);
  EXPECT_NEAR(q.m[1][1], cot, 4e-7 * cot);
  EXPECT_NEAR(q.m[2][2], f / (f - n), 2e-7);
  EXPECT_NEAR(q.m[3][2], -n * f / (f - n), 2e-8);
  EXPECT_EQ(q.m[2][3], 1.0f);
  EXPECT_EQ(q.m[3][3], 0.0f);
}

TEST(Camera, OrthographicMatrixMatchesHandComputedValues) {
  // 4 x 2 units, depth [0.5, 10.5]: x / 2, y / 1, (z - 0.5) / 10.
  const mat4 p = projection_matrix(orthographic_camera(4.0f, 2.0f, 0.5f, 10.5f));
  const float want[4][4] = {{0.5f, 0, 0, 0}, {0, 1.0f, 0, 0}, {0, 0, 0.1f, 0}, {0, 0, -0.05f, 1.0f}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_FLOAT_EQ(p.m[i][j], want[i][j]) << i << "," << j;
  const vec4 corner = vec4{2.0f, -1.0f, 10.5f, 1.0f} * p;
  EXPECT_FLOAT_EQ(corner.x, 1.0f);
  EXPECT_FLOAT_EQ(corner.y, -1.0f);
  EXPECT_FLOAT_EQ(corner.z, 1.0f);
  EXPECT_EQ(corner.w, 1.0f);
}

TEST(Camera, ViewMatrixIsTheInverseOfTheWorldTransformAndMatchesLookAt) {
  Camera c;
  EXPECT_EQ(view_matrix(c), mat4::identity());
  const vec3 eye{3.0f, 4.0f, -5.0f}, target{0.0f, 1.0f, 2.0f}, up{0.0f, 1.0f, 0.0f};
  set_look_at(c, eye, target, up);
  const mat4 v = view_matrix(c), want = look_at(eye, target, up);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(v.m[i][j], want.m[i][j], 2e-6) << i << "," << j;
  const mat4 wv = world_matrix(c) * v;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(wv.m[i][j], i == j ? 1.0 : 0.0, 2e-6) << i << "," << j;
  // The eye goes to the origin and the target straight ahead at its distance.
  const vec3 t = multiply_point(target, v);
  EXPECT_NEAR(t.x, 0.0f, 2e-6);
  EXPECT_NEAR(t.y, 0.0f, 2e-6);
  EXPECT_NEAR(t.z, length(target - eye), 4e-6);
}

void expect_orthonormal(const mat4& view, const char* what) {
  const mat3 r = to_mat3(view);
  const mat3 rrt = r * transpose(r);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rrt.m[i][j], i == j ? 1.0 : 0.0, 1e-6) << what << " " << i << "," << j;
  EXPECT_NEAR(determinant(r), 1.0f, 1e-6) << what;
}

TEST(Camera, ViewMatrixReorthonormalisesADriftedOrientation) {
  SplitMix64 rng(12);
  for (int trial = 0; trial < 200; ++trial) {
    Camera c;
    c.position = {float(rng.u() * 10 - 5), float(rng.u() * 10 - 5), float(rng.u() * 10 - 5)};
    c.orientation = testing::random_rotation(rng);
    const D3 forward = unit(row(c.orientation, 2));
    // Drift: scale the rows and skew them by up to 5%.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c.orientation.m[i][j] = c.orientation.m[i][j] * float(1.0 + 0.05 * (rng.u() - 0.5)) +
                                                           float(0.05 * (rng.u() - 0.5));
    const mat4 v = view_matrix(c);
    expect_orthonormal(v, "drifted");
    // The forward axis keeps the direction of the drifted row 2 (column 2 of the view).
    const D3 f_drift = unit(row(c.orientation, 2));
    const D3 f_view{v.m[0][2], v.m[1][2], v.m[2][2]};
    EXPECT_LT(dist(f_view, f_drift), 1e-6);
    EXPECT_LT(dist(f_view, forward), 0.2);  // still roughly the original view
    // The position goes to the origin.
    const vec3 o = multiply_point(c.position, v);
    EXPECT_LT(length(o), 2e-5f);
  }
  // Degenerate: up parallel to forward, then right parallel too, then a zero forward.
  Camera c;
  c.orientation = from_rows(vec3{1, 0, 0}, vec3{0, 0, 2}, vec3{0, 0, 1});
  expect_orthonormal(view_matrix(c), "up parallel");
  EXPECT_EQ(row(to_mat3(transpose(view_matrix(c))), 0).x, 1.0);  // the old right axis is kept
  c.orientation = from_rows(vec3{0, 0, 1}, vec3{0, 0, 2}, vec3{0, 0, 1});
  expect_orthonormal(view_matrix(c), "right and up parallel");
  c.orientation = from_rows(vec3{1, 0, 0}, vec3{0, 1, 0}, vec3{0, 0, 0});
  expect_orthonormal(view_matrix(c), "zero forward");
  EXPECT_EQ(view_matrix(c), mat4::identity());
}

TEST(Camera, OrbitCameraPlacesTheEyeAndClampsPitchAndZoom) {
  OrbitCamera o;
  o.target = {1.0f, 2.0f, 3.0f};
  o.distance = 5.0f;
  EXPECT_LT(dist(orbit_eye(o), D3{1, 2, -2}), 1e-6);
  ASSERT_EQ(orbit_rotate(o, kHalfPi, 0.0f), Status::ok);
  EXPECT_LT(dist(orbit_eye(o), D3{-4, 2, 3}), 2e-6);  // yaw pi/2: looking along +x
  ASSERT_EQ(orbit_rotate(o, 0.0f, 0.5f), Status::ok);
  {
    const double y = o.yaw, p = o.pitch;
    const D3 f{std::sin(y) * std::cos(p), -std::sin(p), std::cos(y) * std::cos(p)};
    EXPECT_LT(dist(orbit_eye(o), D3{1, 2, 3} - f * 5.0), 4e-6);
    EXPECT_GT(orbit_eye(o).y, o.target.y);  // positive pitch: above, looking down
  }
  // The camera looks at the target: it sits straight ahead at the orbit distance.
  const Camera lens = perspective_camera(1.0f, 1.5f, 0.1f, 100.0f);
  Camera cam = orbit_camera(o, lens);
  EXPECT_EQ(cam.fov_y, lens.fov_y);
  const vec3 t = multiply_point(o.target, view_matrix(cam));
  EXPECT_NEAR(t.x, 0.0f, 2e-6);
  EXPECT_NEAR(t.y, 0.0f, 2e-6);
  EXPECT_NEAR(t.z, 5.0f, 4e-6);
  const vec3 px = project(o.target, {0, 0}, {600, 400}, view_matrix(cam), projection_matrix(cam));
  EXPECT_NEAR(px.x, 300.0f, 1e-3);
  EXPECT_NEAR(px.y, 200.0f, 1e-3);

  // Pitch clamps, yaw wraps.
  ASSERT_EQ(orbit_rotate(o, 0.0f, 100.0f), Status::ok);
  EXPECT_EQ(o.pitch, o.max_pitch);
  ASSERT_EQ(orbit_rotate(o, 0.0f, -200.0f), Status::ok);
  EXPECT_EQ(o.pitch, -o.max_pitch);
  const vec3 before = orbit_eye(o);
  ASSERT_EQ(orbit_rotate(o, 7.0f * kTwoPi, 0.0f), Status::ok);
  EXPECT_GE(o.yaw, -kPi);
  EXPECT_LE(o.yaw, kPi);
  EXPECT_LT(dist(orbit_eye(o), d3(before)), 1e-4);
  ASSERT_EQ(orbit_rotate(o, -3.0f, 0.0f), Status::ok);
  ASSERT_EQ(orbit_rotate(o, -3.0f, 0.0f), Status::ok);
  EXPECT_GE(o.yaw, -kPi);
  EXPECT_LE(o.yaw, kPi);

  // Zoom clamps to the limits.
  ASSERT_EQ(orbit_zoom(o, -100.0f), Status::ok);
  EXPECT_EQ(o.distance, o.min_distance);
  ASSERT_EQ(orbit_zoom(o, 1e6f), Status::ok);
  EXPECT_EQ(o.distance, o.max_distance);
  ASSERT_EQ(orbit_zoom(o, 10.0f - o.max_distance), Status::ok);
  EXPECT_EQ(o.distance, 10.0f);

  // Pan slides target and eye together along the camera's right and up axes.
  cam = orbit_camera(o, lens);
  const vec3 t0 = o.target, e0 = orbit_eye(o);
  ASSERT_EQ(orbit_pan(o, 1.5f, -2.0f), Status::ok);
  const D3 moved = row(cam.orientation, 0) * 1.5 + row(cam.orientation, 1) * -2.0;
  EXPECT_LT(dist(o.target, d3(t0) + moved), 2e-6);
  EXPECT_LT(dist(orbit_eye(o), d3(e0) + moved), 1e-5);
  EXPECT_EQ(o.distance, 10.0f);

  // Bad input changes nothing.
  OrbitCamera saved = o;
  EXPECT_EQ(orbit_rotate(o, kNaN, 0.0f), Status::non_finite);
  EXPECT_EQ(orbit_zoom(o, std::numeric_limits<float>::infinity()), Status::non_finite);
  EXPECT_EQ(orbit_pan(o, 0.0f, kNaN), Status::non_finite);
  EXPECT_STRNE(last_error(), "");
  EXPECT_EQ(std::memcmp(&saved, &o, sizeof o), 0);
  o.max_pitch = 2.0f;
  saved = o;
  EXPECT_EQ(orbit_rotate(o, 0.1f, 0.1f), Status::invalid_argument);
  o.max_pitch = 1.0f, o.min_distance = 5.0f, o.max_distance = 1.0f;
  saved = o;
  EXPECT_EQ(orbit_zoom(o, 1.0f), Status::invalid_argument);
  EXPECT_EQ(std::memcmp(&saved, &o, sizeof o), 0);
}

// A perspective camera looking from eye at target, 4:3.
Camera test_camera() {
  Camera c = perspective_camera(1.1f, 4.0f / 3.0f, 0.25f, 80.0f);
  set_look_at(c, {3.0f, 4.0f, -5.0f}, {0.0f, 1.0f, 2.0f}, {0.0f, 1.0f, 0.0f});
  return c;
}

TEST(Camera, PickingRayThroughTheCentreIsTheViewDirection) {
  const Camera c = test_camera();
  const Ray r = picking_ray(c, {400.0f, 300.0f}, {800.0f, 600.0f});
  const D3 f = unit(row(c.orientation, 2));
  EXPECT_LT(dist(r.direction, f), 1e-6);
  EXPECT_LT(dist(r.origin, d3(c.position) + f * c.z_near), 1e-6);
  EXPECT_NEAR(length(r.direction), 1.0f, 1e-6);

  Camera o = orthographic_camera(8.0f, 6.0f, -2.0f, 30.0f);
  o.position = c.position, o.orientation = c.orientation;
  const Ray ro = picking_ray(o, {400.0f, 300.0f}, {800.0f, 600.0f});
  EXPECT_LT(dist(ro.direction, f), 1e-6);
  EXPECT_LT(dist(ro.origin, d3(c.position) + f * -2.0), 2e-6);
}

TEST(Camera, PickingRaysThroughTheCornersRunAlongTheFrustumEdges) {
  const Camera c = test_camera();
  const vec2 size{800.0f, 600.0f};
  const double th = std::tan(double(c.fov_y) / 2), tw = th * double(c.aspect);
  vec3 corners[8];
  frustum_corners(frustum(c), corners);
  double worst_dir = 0, worst_origin = 0, worst_far = 0;
  // Screen corners (y down) and the frustum corner each meets: bit 0 right, bit 1 top.
  const struct {
    float x, y;
    int sx, sy, corner;
  } cases[4] = {{0, 0, -1, 1, 2}, {800, 0, 1, 1, 3}, {0, 600, -1, -1, 0}, {800, 600, 1, -1, 1}};
  for (const auto& k : cases) {
    const Ray r = picking_ray(c, {k.x, k.y}, size);
    // Analytic edge in double: view direction (sx tw, sy th, 1).
    const D3 near_pt = view_to_world(c, k.sx * tw * c.z_near, k.sy * th * c.z_near, c.z_near);
    const D3 far_pt = view_to_world(c, k.sx * tw * c.z_far, k.sy * th * c.z_far, c.z_far);
    const D3 dir = unit(far_pt - near_pt);
    worst_dir = std::max(worst_dir, dist(r.direction, dir));
    worst_origin = std::max(worst_origin, dist(r.origin, near_pt));
    // The frustum's own corners (from its planes) agree.
    EXPECT_LT(dist(corners[k.corner], near_pt), 1e-5);
    // The float projection holds the far plane to about 2^-24 (far - near)^2 / near.
    const double far_slack = 4 * 0x1p-24 * (c.z_far - c.z_near) * (c.z_far - c.z_near) / c.z_near;
    EXPECT_LT(dist(corners[k.corner + 4], far_pt), 1e-5 + far_slack);
    // Followed to the far plane's distance, the ray reaches the far corner.
    const double t = norm(far_pt - near_pt);
    worst_far = std::max(worst_far, norm(d3(r.origin) + d3(r.direction) * t - far_pt) / t);
  }
  std::printf("picking ray at the corners: direction error %.2e, origin error %.2e, far corner error %.2e (relative)\n",
              worst_dir, worst_origin, worst_far);
  EXPECT_LT(worst_dir, 2e-6);
  EXPECT_LT(worst_origin, 2e-6);
  EXPECT_LT(worst_far, 2e-6);
}

TEST(Camera, OrthographicPickingRaysAreParallelToForward) {
  Camera o = orthographic_camera(8.0f, 6.0f, 0.5f, 30.0f);
  SplitMix64 rng(7);
  o.orientation = testing::random_rotation(rng);
  o.position = {10.0f, -3.0f, 2.0f};
  const D3 f = unit(row(o.orientation, 2));
  for (int i = 0; i < 100; ++i) {
    const double sx = rng.u(), sy = rng.u();
    const Ray r = picking_ray(o, {float(sx * 800), float(sy * 600)}, {800.0f, 600.0f});
    EXPECT_LT(dist(r.direction, f), 1e-6);
    // It starts on the near plane at the pixel's offset from the centre (y down on screen).
    const D3 want = view_to_world(o, (sx - 0.5) * 8.0, (0.5 - sy) * 6.0, 0.5);
    EXPECT_LT(dist(r.origin, want), 4e-6);
  }
}

// Float world coordinates of magnitude M hold a point only to about 2^-24 M, and a depth
// near 1 only to 2^-24: so the round trips are held to 64 ulps of M seen at the point's
// depth (in pixels and in depth units), plus 1e-3 px, 4e-7 in depth and, for world
// points, 8 ulps of the depth turned into distance.
TEST(Camera, ProjectAndUnprojectAreInverses) {
  SplitMix64 rng(99);
  const vec2 origin{20.0f, 10.0f}, size{1920.0f, 1080.0f};
  constexpr double ulp = 0x1p-24;
  double worst_px = 0, worst_depth = 0, worst_world = 0, ratio[3] = {0, 0, 0};
  for (int cam = 0; cam < 40; ++cam) {
    const bool persp = cam % 2 == 0;
    Camera c = persp ? perspective_camera(float(0.2 + 2.5 * rng.u()), float(0.5 + 2 * rng.u()), float(0.05 + rng.u()),
                                          float(20 + 500 * rng.u()))
                     : orthographic_camera(float(1 + 20 * rng.u()), float(1 + 20 * rng.u()), float(-5 * rng.u()),
                                           float(10 + 100 * rng.u()));
    c.orientation = orthonormalized(testing::random_rotation(rng));
    c.position = {float(200 * rng.u() - 100), float(200 * rng.u() - 100), float(200 * rng.u() - 100)};
    const mat4 v = view_matrix(c), p = projection_matrix(c);
    const double n = c.z_near, f = c.z_far, a = f / (f - n), th = std::tan(double(c.fov_y) / 2);
    const D3 fwd = row(c.orientation, 2);
    // Pixels per world unit and depth units per world unit at view depth z.
    auto px_per_unit = [&](double z) { return size.y / 2 / (persp ? z * th : c.height / 2.0); };
    auto depth_per_unit = [&](double z) { return persp ? a * n / (z * z) : 1 / (f - n); };
    for (int i = 0; i < 250; ++i) {
      // Viewport points: pixels anywhere in the viewport, depth in [0, 0.99].
      const vec3 vp{float(origin.x + size.x * rng.u()), float(origin.y + size.y * rng.u()), float(0.99 * rng.u())};
      const vec3 w = unproject(vp, origin, size, v, p);
      const vec3 back = project(w, origin, size, v, p);
      const double m = norm(d3(c.position)) + norm(d3(w)) + 1;
      const double z = dot(d3(w) - d3(c.position), fwd);
      const double err_px = std::max(std::abs(double(back.x) - vp.x), std::abs(double(back.y) - vp.y));
      const double err_depth = std::abs(double(back.z) - vp.z);
      worst_px = std::max(worst_px, err_px);
      worst_depth = std::max(worst_depth, err_depth);
      ratio[0] = std::max(ratio[0], err_px / (1e-3 + 64 * ulp * m * px_per_unit(z)));
      ratio[1] = std::max(ratio[1], err_depth / (4e-7 + 64 * ulp * m * depth_per_unit(z)));
      // World points in front of the camera come back to themselves.
      const D3 q = view_to_world(c, 10 * rng.u() - 5, 10 * rng.u() - 5, n + (f - n) * rng.u());
      const vec3 qf{float(q.x), float(q.y), float(q.z)};
      const vec3 q2 = unproject(project(qf, origin, size, v, p), origin, size, v, p);
      const double zq = dot(d3(qf) - d3(c.position), fwd), mq = norm(d3(c.position)) + norm(d3(qf)) + 1;
      const double err = dist(q2, d3(qf));
      worst_world = std::max(worst_world, err / (norm(d3(qf) - d3(c.position)) + 1));
      ratio[2] = std::max(ratio[2], err / (64 * ulp * mq + 8 * ulp / depth_per_unit(zq)));
    }
  }
  std::printf("project(unproject(p)): max error %.2e px, %.2e in depth; unproject(project(q)): %.2e relative; "
              "worst error / bound: %.3f (pixels), %.3f (depth), %.3f (world)\n",
              worst_px, worst_depth, worst_world, ratio[0], ratio[1], ratio[2]);
  for (double r : ratio) EXPECT_LT(r, 1.0);
  // A singular projection gives NaN, not a crash.
  const vec3 bad = unproject({1, 1, 0.5f}, {0, 0}, {2, 2}, mat4::identity(), mat4::zero());
  EXPECT_TRUE(std::isnan(bad.x) && std::isnan(bad.y) && std::isnan(bad.z));
}

TEST(Camera, PickingRayHitsTheSphereDrawnUnderThePixel) {
  const Camera c = test_camera();
  const mat4 v = view_matrix(c), p = projection_matrix(c);
  SplitMix64 rng(5);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const D3 centre = view_to_world(c, 8 * rng.u() - 4, 6 * rng.u() - 3, 2 + 40 * rng.u());
    const Sphere s{{float(centre.x), float(centre.y), float(centre.z)}, float(0.01 + 0.2 * rng.u())};
    const vec3 px = project(s.center, {0, 0}, {800, 600}, v, p);
    if (!(px.x >= 0 && px.x <= 800 && px.y >= 0 && px.y <= 600)) continue;
    const RaycastResult r = raycast(s, picking_ray(c, {px.x, px.y}, {800, 600}));
    EXPECT_TRUE(r.hit) << i;
    hits += r.hit;
  }
  EXPECT_GT(hits, 200);
}

TEST(Camera, CheckCameraReportsBadParameters) {
  EXPECT_EQ(check_camera(Camera{}), Status::ok);
  EXPECT_EQ(check_camera(test_camera()), Status::ok);
  EXPECT_EQ(check_camera(orthographic_camera(2, 2, -1, 1)), Status::ok);
  const struct {
    Camera c;
    Status s;
  } bad[] = {
      {perspective_camera(0.0f, 1.0f, 0.1f, 10.0f), Status::invalid_argument},
      {perspective_camera(kPi, 1.0f, 0.1f, 10.0f), Status::invalid_argument},
      {perspective_camera(1.0f, 0.0f, 0.1f, 10.0f), Status::invalid_argument},
      {perspective_camera(1.0f, kNaN, 0.1f, 10.0f), Status::invalid_argument},
      {perspective_camera(1.0f, 1.0f, 0.0f, 10.0f), Status::invalid_argument},
      {perspective_camera(1.0f, 1.0f, 10.0f, 10.0f), Status::invalid_argument},
      {perspective_camera(1.0f, 1.0f, 0.1f, kNaN), Status::non_finite},
      {orthographic_camera(0.0f, 1.0f, 0.1f, 10.0f), Status::invalid_argument},
      {orthographic_camera(1.0f, -1.0f, 0.1f, 10.0f), Status::invalid_argument},
      {orthographic_camera(1.0f, 1.0f, 5.0f, -5.0f), Status::invalid_argument},
  };
  for (const auto& b : bad) {
    detail::clear_error();
    EXPECT_EQ(check_camera(b.c), b.s) << last_error();
    EXPECT_STRNE(last_error(), "");
  }
  Camera c;
  c.position.y = kNaN;
  EXPECT_EQ(check_camera(c), Status::non_finite);
  c = Camera{};
  c.orientation.m[2][2] = 0.0f;
  EXPECT_EQ(check_camera(c), Status::invalid_argument);
  c = Camera{};
  c.mode = ProjectionMode(7);
  EXPECT_EQ(check_camera(c), Status::invalid_argument);
}

}  // namespace
}  // namespace gyro
