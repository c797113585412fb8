// Narrowphase manifolds: analytic cases with numbers for every pair; the conventions (unit
// normal from a to b, points midway, margin, swapping a and b); feature ids that survive tiny
// motions; a seeded property test of box-box against the separating axis test (gyro's
// overlaps() and obb_separation_pairwise(), and a binary64 15-axis reference); and
// TriangleMesh::triangles_overlapping against brute force.
#include "dynamics/box_sat.hpp"
#include "dynamics/narrowphase.hpp"
#include "gyro/batch_overlap.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/mesh.hpp"
#include "gyro/overlap.hpp"
#include "gyro/point_tests.hpp"
#include "gyro/runtime.hpp"
#include "gyro/triangle.hpp"
#include "gyro/triangle_mesh.hpp"
#include "random_shapes.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>
#include <vector>

namespace gyro::detail {
namespace {

using testing::SplitMix64;

constexpr float kTol = 1e-5f;
const float kHalfSqrt2 = std::sqrt(0.5f);

mat3 rotation(const vec3& axis, float degrees) {
  return to_mat3(from_axis_angle(normalized(axis), deg_to_rad(degrees)));
}
OBB box(const vec3& c, const vec3& e, const mat3& r = mat3{}) { return {c, e, r}; }

void expect_near3(const vec3& got, const vec3& want, float tol = kTol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// The invariants every manifold with points has: unit normal, finite points, count <= 4,
// distinct feature ids.
void expect_well_formed(const Manifold& m) {
  ASSERT_LE(m.count, kMaxManifoldPoints);
  if (m.count == 0) return;
  EXPECT_NEAR(length(m.normal), 1.0f, 1e-5f);
  for (uint32_t i = 0; i < m.count; ++i) {
    EXPECT_TRUE(is_finite(m.points[i].position));
    EXPECT_TRUE(std::isfinite(m.points[i].separation));
    for (uint32_t j = 0; j < i; ++j) EXPECT_NE(m.points[i].feature_id, m.points[j].feature_id);
  }
}

float deepest(const Manifold& m) {
  float s = __builtin_inff();
  for (uint32_t i = 0; i < m.count; ++i) s = std::min(s, m.points[i].separation);
  return s;
}

std::set<uint32_t> ids(const Manifold& m) {
  std::set<uint32_t> s;
  for (uint32_t i = 0; i < m.count; ++i) s.insert(m.points[i].feature_id);
  return s;
}

Manifold boxes(const OBB& a, const OBB& b, float margin = 0.0f) {
  Manifold m;
  collide_boxes(a, b, margin, &m);
  expect_well_formed(m);
  return m;
}

// How far a point may be from either shape: midway, half the depth of a penetration; for a
// gap, whose separation is along one axis and so a lower bound of the distance between the
// features (edges that pass each other, say), up to that separation.
float midway_tolerance(float separation) {
  return separation <= 0.0f ? -0.5f * separation + 2e-4f : separation + 2e-4f;
}

// Whether p lies in the box grown by tol (in the box's frame).
bool in_box(const OBB& b, const vec3& p, float tol) { return distance(closest_point(b, p), p) <= tol; }

// ---------------------------------------------------------------------------------------
// Spheres and planes

TEST(NarrowphaseSpheres, DepthNormalPoint) {
  Manifold m;
  collide_spheres({{0, 0, 0}, 1.0f}, {{1.5f, 0, 0}, 1.0f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {1, 0, 0});
  EXPECT_NEAR(m.points[0].separation, -0.5f, kTol);
  expect_near3(m.points[0].position, {0.75f, 0, 0});  // between 1 (a's surface) and 0.5 (b's)
  EXPECT_EQ(m.points[0].feature_id, 0u);

  Manifold s;
  collide_spheres({{1.5f, 0, 0}, 1.0f}, {{0, 0, 0}, 1.0f}, 0.0f, &s);
  ASSERT_EQ(s.count, 1u);
  expect_near3(s.normal, {-1, 0, 0});
  EXPECT_NEAR(s.points[0].separation, -0.5f, kTol);
  expect_near3(s.points[0].position, {0.75f, 0, 0});

  // Different radii, diagonal: the point is midway between the two surface points.
  collide_spheres({{1, 1, 1}, 0.5f}, {{1, 2, 1}, 0.75f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.25f, kTol);
  expect_near3(m.points[0].position, {1, 1.375f, 1});
}

TEST(NarrowphaseSpheres, CoincidentCentresGetUp) {
  Manifold m;
  collide_spheres({{3, 4, 5}, 1.0f}, {{3, 4, 5}, 0.5f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, 1, 0}, 0.0f);
  EXPECT_EQ(m.points[0].separation, -1.5f);
  EXPECT_TRUE(is_finite(m.points[0].position));
  // A nonzero offset whose square underflows still has a direction.
  collide_spheres({{0, 0, 0}, 1.0f}, {{1e-30f, 0, 0}, 1.0f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {1, 0, 0}, 0.0f);
}

TEST(NarrowphaseSpheres, Margin) {
  Manifold m;
  collide_spheres({{0, 0, 0}, 1.0f}, {{2.01f, 0, 0}, 1.0f}, 0.02f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  collide_spheres({{0, 0, 0}, 1.0f}, {{2.01f, 0, 0}, 1.0f}, 0.005f, &m);
  EXPECT_EQ(m.count, 0u);
}

TEST(NarrowphaseSpherePlane, DepthNormalPoint) {
  Manifold m;
  collide_sphere_plane({{2, 0.8f, -1}, 1.0f}, {{0, 1, 0}, 0.0f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.2f, kTol);
  expect_near3(m.points[0].position, {2, -0.1f, -1});
  // The plane y = 1 facing -y: its solid is above, and the centre at y = 1.5 is 0.5 inside.
  collide_sphere_plane({{0, 1.5f, 0}, 0.25f}, {{0, -1, 0}, -1.0f}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.75f, kTol);  // the centre is 0.5 inside, plus the radius
  // Margin.
  collide_sphere_plane({{0, 1.01f, 0}, 1.0f}, {{0, 1, 0}, 0.0f}, 0.02f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  collide_sphere_plane({{0, 1.01f, 0}, 1.0f}, {{0, 1, 0}, 0.0f}, 0.005f, &m);
  EXPECT_EQ(m.count, 0u);
}

// ---------------------------------------------------------------------------------------
// Sphere-box

TEST(NarrowphaseSphereBox, FaceEdgeCornerInside) {
  const OBB b = box({0, 0, 0}, {1, 1, 1});
  Manifold m;
  collide_sphere_box({{0.3f, 1.4f, -0.2f}, 0.5f}, b, 0.0f, &m);  // resting on the top face
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.1f, kTol);
  expect_near3(m.points[0].position, {0.3f, 0.95f, -0.2f});

  collide_sphere_box({{1.3f, 1.3f, 0}, 0.5f}, b, 0.0f, &m);  // on the edge x = y = 1
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {-kHalfSqrt2, -kHalfSqrt2, 0});
  EXPECT_NEAR(m.points[0].separation, 0.3f * std::sqrt(2.0f) - 0.5f, kTol);

  collide_sphere_box({{1.2f, -1.2f, 1.2f}, 0.5f}, b, 0.0f, &m);  // on the corner (1, -1, 1)
  ASSERT_EQ(m.count, 1u);
  const float r3 = 1.0f / std::sqrt(3.0f);
  expect_near3(m.normal, {-r3, r3, -r3});
  EXPECT_NEAR(m.points[0].separation, 0.2f * std::sqrt(3.0f) - 0.5f, kTol);
  const float mid = (1.2f * std::sqrt(3.0f) - 0.5f + std::sqrt(3.0f)) * 0.5f * r3;  // along the diagonal
  expect_near3(m.points[0].position, {mid, -mid, mid});

  // Centre inside, nearest to the +y face (0.3 away): leave through it.
  collide_sphere_box({{0.2f, 0.7f, 0.1f}, 0.5f}, b, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.8f, kTol);
  expect_near3(m.points[0].position, {0.2f, 0.6f, 0.1f});
  // Nearest to the -x face of a flat box: the least-penetration face, not the biggest one.
  collide_sphere_box({{-1.9f, 0.0f, 0.0f}, 0.25f}, box({0, 0, 0}, {2, 0.5f, 3}), 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {1, 0, 0});
  EXPECT_NEAR(m.points[0].separation, -0.35f, kTol);
}

TEST(NarrowphaseSphereBox, RotatedBoxAndMargin) {
  const mat3 r = rotation({0, 0, 1}, 30.0f);
  const OBB b = box({5, -2, 1}, {1, 0.5f, 2}, r);
  const vec3 up{r.m[1][0], r.m[1][1], r.m[1][2]};  // the box's local +y
  Manifold m;
  collide_sphere_box({b.center + up * 1.2f, 0.75f}, b, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, -up);
  EXPECT_NEAR(m.points[0].separation, -0.05f, kTol);
  collide_sphere_box({b.center + up * 1.51f, 1.0f}, b, 0.02f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, 2e-6f);
  collide_sphere_box({b.center + up * 1.51f, 1.0f}, b, 0.005f, &m);
  EXPECT_EQ(m.count, 0u);
}

// ---------------------------------------------------------------------------------------
// Box-box

TEST(NarrowphaseBoxes, FaceToFaceGivesFourPoints) {
  const OBB ground = box({0, 0, 0}, {2, 0.5f, 2});
  const OBB top = box({0.3f, 0.99f, -0.2f}, {0.5f, 0.5f, 0.5f});
  const Manifold m = boxes(ground, top);
  ASSERT_EQ(m.count, 4u);
  expect_near3(m.normal, {0, 1, 0});
  std::set<std::pair<int, int>> corners;
  for (uint32_t i = 0; i < 4; ++i) {
    const ContactPoint& p = m.points[i];
    EXPECT_NEAR(p.separation, -0.01f, kTol);
    EXPECT_NEAR(p.position.y, 0.495f, kTol);
    EXPECT_NEAR(std::abs(p.position.x - 0.3f), 0.5f, kTol);
    EXPECT_NEAR(std::abs(p.position.z + 0.2f), 0.5f, kTol);
    corners.insert({p.position.x > 0.3f, p.position.z > -0.2f});
  }
  EXPECT_EQ(corners.size(), 4u);

  // Swapped: the normal flips, the depth and the points stay.
  const Manifold s = boxes(top, ground);
  ASSERT_EQ(s.count, 4u);
  expect_near3(s.normal, {0, -1, 0});
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(s.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(s.points[i].position.y, 0.495f, kTol);
  }
}

TEST(NarrowphaseBoxes, RotatedBoxGivesFourPointsOfTheOctagon) {
  // Equal squares 45 degrees apart overlap in a regular octagon; four of its corners remain.
  const OBB a = box({0, 0, 0}, {0.5f, 0.5f, 0.5f});
  const OBB b = box({0, 0.99f, 0}, {0.5f, 0.5f, 0.5f}, rotation({0, 1, 0}, 45.0f));
  const Manifold m = boxes(a, b);
  ASSERT_EQ(m.count, 4u);
  expect_near3(m.normal, {0, 1, 0});
  vec2 p[4];
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_TRUE(in_box(a, m.points[i].position, 0.006f)) << i;  // half the depth above a's face
    EXPECT_TRUE(in_box(b, m.points[i].position, 0.006f)) << i;
    // On the octagon's boundary: outside the inner circle of either square.
    p[i] = {m.points[i].position.x, m.points[i].position.z};
    EXPECT_GT(length(p[i]), 0.5f - kTol);
  }
  // The kept quadrilateral spans most of the octagon (area 0.828; the best four corners of
  // a regular octagon give 0.586).
  vec2 c{};
  for (const vec2& q : p) c = c + q * 0.25f;
  std::sort(p, p + 4, [&](const vec2& u, const vec2& v) {
    return gyro::atan2(u.y - c.y, u.x - c.x) < gyro::atan2(v.y - c.y, v.x - c.x);
  });
  float area = 0.0f;
  for (int i = 0; i < 4; ++i) area += 0.5f * cross(p[i], p[(i + 1) % 4]);
  EXPECT_GT(area, 0.58f);
}

// Two unit cubes standing on edges that cross at right angles: a's top edge along x (a turned
// 45 degrees about x), b's bottom edge along z (b turned about z), 0.02 deep.
TEST(NarrowphaseBoxes, CrossingEdgesGiveOnePoint) {
  const float h = kHalfSqrt2;  // the edge's height above the centre
  const OBB a = box({0, 0, 0}, {0.5f, 0.5f, 0.5f}, rotation({1, 0, 0}, 45.0f));
  const OBB b = box({0.1f, 2 * h - 0.02f, -0.15f}, {0.5f, 0.5f, 0.5f}, rotation({0, 0, 1}, 45.0f));
  const Manifold m = boxes(a, b);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.02f, kTol);
  expect_near3(m.points[0].position, {0.1f, h - 0.01f, 0.0f});
  EXPECT_NE(m.points[0].feature_id & kFeatureEdge, 0u);

  const Manifold s = boxes(b, a);
  ASSERT_EQ(s.count, 1u);
  expect_near3(s.normal, {0, -1, 0});
  EXPECT_NEAR(s.points[0].separation, -0.02f, kTol);
  expect_near3(s.points[0].position, m.points[0].position);
}

TEST(NarrowphaseBoxes, TiltedBoxOnBox) {
  // A cube tilted 20 degrees about z resting on one bottom edge on a wide slab: two points,
  // the ends of that edge.
  const OBB ground = box({0, -0.5f, 0}, {3, 0.5f, 3});
  const mat3 r = rotation({0, 0, 1}, 20.0f);
  const float c = gyro::cos(deg_to_rad(20.0f)), s = gyro::sin(deg_to_rad(20.0f));
  const float low = 0.5f * (c + s);  // the centre's height above the lowest edge
  const OBB cube = box({0.2f, low - 0.01f, 0.1f}, {0.5f, 0.5f, 0.5f}, r);
  const Manifold m = boxes(ground, cube);
  ASSERT_EQ(m.count, 2u);
  expect_near3(m.normal, {0, 1, 0});
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(m.points[i].position.y, -0.005f, kTol);
    EXPECT_NEAR(std::abs(m.points[i].position.z - 0.1f), 0.5f, kTol);
  }
  const Manifold sw = boxes(cube, ground);
  ASSERT_EQ(sw.count, 2u);
  expect_near3(sw.normal, {0, -1, 0});
  EXPECT_NEAR(deepest(sw), -0.01f, kTol);
}

TEST(NarrowphaseBoxes, Margin) {
  const OBB ground = box({0, 0, 0}, {2, 0.5f, 2});
  const OBB top = box({0, 1.01f, 0}, {0.5f, 0.5f, 0.5f}, rotation({0, 1, 0}, 10.0f));
  Manifold m = boxes(ground, top, 0.02f);
  ASSERT_EQ(m.count, 4u);
  for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, 0.01f, kTol);
  m = boxes(ground, top, 0.005f);
  EXPECT_EQ(m.count, 0u);
  // Touching with margin 0 reports nothing (points are kept while separation < margin).
  m = boxes(ground, box({0, 1.0f, 0}, {0.5f, 0.5f, 0.5f}), 0.0f);
  EXPECT_EQ(m.count, 0u);
}

TEST(NarrowphaseBoxes, FeatureIdsSurviveTinyMotions) {
  // A manifold reduced from more than 4 clipped points keeps the deepest one (to within
  // kDepthTie of the face's size), so a tilt that changes the depths by more than that may
  // change which 4 it keeps: those cases are only moved, not turned.
  struct Case {
    OBB a, b;
    uint32_t count;
    bool turn;
  };
  const float h = kHalfSqrt2;
  const Case cases[] = {
      {box({0, 0, 0}, {2, 0.5f, 2}), box({0.3f, 0.99f, -0.2f}, {0.5f, 0.5f, 0.5f}), 4, true},
      {box({0, 0, 0}, {0.5f, 0.5f, 0.5f}), box({0, 0.99f, 0}, {0.5f, 0.5f, 0.5f}, rotation({0, 1, 0}, 45.0f)), 4,
       false},
      {box({0, 0, 0}, {0.5f, 0.5f, 0.5f}, rotation({1, 0, 0}, 45.0f)),
       box({0.1f, 2 * h - 0.02f, -0.15f}, {0.5f, 0.5f, 0.5f}, rotation({0, 0, 1}, 45.0f)), 1, true},
      {box({0, 0, 0}, {1, 0.5f, 1}), box({0.8f, 0.99f, 0.1f}, {0.5f, 0.5f, 0.5f}, rotation({0, 1, 0}, 30.0f)), 4,
       false},
      {box({0, 0, 0}, {2, 0.5f, 2}), box({0.3f, 0.99f, -0.2f}, {0.5f, 0.5f, 0.5f}, rotation({1, 0, 0}, 0.2f)), 4, true},
  };
  const vec3 moves[] = {{1e-4f, 0, 0}, {0, 1e-4f, 0}, {0, 0, 1e-4f}, {-1e-4f, -1e-4f, 1e-4f}};
  const vec3 spins[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, -1}};
  for (const Case& c : cases) {
    const Manifold m0 = boxes(c.a, c.b);
    ASSERT_EQ(m0.count, c.count);
    for (const vec3& d : moves) {
      OBB b = c.b;
      b.center = b.center + d;
      EXPECT_EQ(ids(boxes(c.a, b)), ids(m0));
      EXPECT_EQ(ids(boxes(b, c.a)), ids(boxes(c.b, c.a)));
    }
    for (const vec3& axis : spins) {  // 1e-4 radians
      if (!c.turn) break;
      OBB b = c.b;
      b.orientation = b.orientation * rotation(axis, 1e-4f * 57.29578f);
      EXPECT_EQ(ids(boxes(c.a, b)), ids(m0));
    }
  }
}

// The binary64 separating axis test over the 15 axes (only exactly parallel edge pairs
// skipped): the signed separation, > 0 a gap, <= 0 minus the penetration depth.
double sat_reference(const OBB& a, const OBB& b) {
  double ua[3][3], ub[3][3], d[3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) ua[i][k] = a.orientation.m[i][k], ub[i][k] = b.orientation.m[i][k];
  for (int k = 0; k < 3; ++k) d[k] = double(b.center[k]) - double(a.center[k]);
  auto dot3 = [](const double* p, const double* q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  double best = -1e300;
  auto axis = [&](const double* l) {
    const double len = std::sqrt(dot3(l, l));
    if (len < 1e-9) return;
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k)
      ra += a.half_extents[k] * std::abs(dot3(ua[k], l)), rb += b.half_extents[k] * std::abs(dot3(ub[k], l));
    best = std::max(best, (std::abs(dot3(d, l)) - ra - rb) / len);
  };
  for (int i = 0; i < 3; ++i) axis(ua[i]), axis(ub[i]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double* p = ua[i];
      const double* q = ub[j];
      const double c[3] = {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
      axis(c);
    }
  return best;
}

// The gap between the boxes' projections on the unit direction n (b beyond a), binary64.
double gap_along(const OBB& a, const OBB& b, const vec3& n) {
  double ra = 0, rb = 0, d = 0;
  for (int k = 0; k < 3; ++k) {
    double pa = 0, pb = 0;
    for (int c = 0; c < 3; ++c) pa += double(a.orientation.m[k][c]) * n[c], pb += double(b.orientation.m[k][c]) * n[c];
    ra += a.half_extents[k] * std::abs(pa), rb += b.half_extents[k] * std::abs(pb);
    d += (double(b.center[k]) - double(a.center[k])) * n[k];
  }
  return d - ra - rb;
}

float separation_of(const OBB& a, const OBB& b) {
  float col[2][15];
  const OBB* box2[2] = {&a, &b};
  for (int s = 0; s < 2; ++s) {
    const OBB& o = *box2[s];
    const float v[15] = {o.center.x,
                         o.center.y,
                         o.center.z,
                         o.half_extents.x,
                         o.half_extents.y,
                         o.half_extents.z,
                         o.orientation.m[0][0],
                         o.orientation.m[0][1],
                         o.orientation.m[0][2],
                         o.orientation.m[1][0],
                         o.orientation.m[1][1],
                         o.orientation.m[1][2],
                         o.orientation.m[2][0],
                         o.orientation.m[2][1],
                         o.orientation.m[2][2]};
    std::copy(v, v + 15, col[s]);
  }
  auto view = [](const float* c) {
    return ObbsView{c,     c + 1, c + 2,  c + 3,  c + 4,  c + 5,  c + 6, c + 7,
                    c + 8, c + 9, c + 10, c + 11, c + 12, c + 13, c + 14};
  };
  float out = 0.0f;
  EXPECT_EQ(obb_separation_pairwise(view(col[0]), view(col[1]), 1, &out), Status::ok);
  return out;
}

// Random box pairs against the separating axis test. The normal is one of the 15 axes, and
// the manifold's deepest point is exactly as deep as the boxes overlap along it; that axis is
// the axis of least penetration (so the depth is the SAT depth) except where the preference
// for faces (kFaceRelTol, kEdgeRelTol) picked a nearly as good one, within that tolerance.
TEST(NarrowphaseBoxes, RandomPairsAgreeWithSeparatingAxes) {
  SplitMix64 rng(0x5eed'b0e5);
  constexpr float kMargin = 0.02f;
  int overlapping = 0, separated = 0, exact = 0, preferred = 0;
  for (int n = 0; n < 4000; ++n) {
    auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.u()); };
    const vec3 ca{u(-50, 50), u(-5, 5), u(-2, 2)};
    const OBB a = box(ca, {u(0.1f, 1.1f), u(0.1f, 1.1f), u(0.1f, 1.1f)}, testing::random_rotation(rng));
    const OBB b = box(ca + vec3{u(-1.6f, 1.6f), u(-1.6f, 1.6f), u(-1.6f, 1.6f)},
                      {u(0.1f, 1.1f), u(0.1f, 1.1f), u(0.1f, 1.1f)}, testing::random_rotation(rng));
    const double sat = sat_reference(a, b);
    const float gyro_sat = separation_of(a, b);
    const Manifold m = boxes(a, b, kMargin);
    SCOPED_TRACE(::testing::Message() << "pair " << n << " sat " << sat << " gyro " << gyro_sat);
    if (overlaps(a, b) && gyro_sat < -1e-4f) {
      ++overlapping;
      ASSERT_GT(m.count, 0u);
      EXPECT_LE(deepest(m), 0.0f);
    }
    if (gyro_sat > kMargin + 1e-4f) {
      ++separated;
      EXPECT_EQ(m.count, 0u);
    }
    if (m.count == 0) {
      EXPECT_GT(sat, kMargin - 1e-4);  // nothing reported only when apart by about the margin
      continue;
    }
    // From a to b: along the normal, b's centre is beyond a's.
    EXPECT_GE(dot(m.normal, b.center - a.center), 0.0f);
    const double along = gap_along(a, b, m.normal);
    const double size = std::min(std::max({a.half_extents.x, a.half_extents.y, a.half_extents.z}),
                                 std::max({b.half_extents.x, b.half_extents.y, b.half_extents.z}));
    // The normal is no worse than the best axis by more than the face preference allows.
    EXPECT_LE(along, sat + 1e-4);
    EXPECT_GE(along, sat - (0.08 * std::abs(sat) + 2e-3 * size) - 1e-4);
    // No point is deeper than the overlap along the normal; the deepest is that deep unless
    // the preferred face's deepest corner was clipped off by the other box's sides.
    EXPECT_GE(deepest(m), along - 1e-4);
    if (along >= sat - 1e-5) {
      ++exact;
      EXPECT_NEAR(deepest(m), sat, 1e-4);
      // Swapped, the same depth (the normal may be the other box's equally deep face).
      const Manifold s = boxes(b, a, kMargin);
      ASSERT_GT(s.count, 0u);
      if (gap_along(b, a, s.normal) >= sat - 1e-5) {
        EXPECT_NEAR(deepest(s), deepest(m), 1e-4);
      }
    } else {
      ++preferred;
    }
    for (uint32_t i = 0; i < m.count; ++i) {
      const float half = midway_tolerance(m.points[i].separation);
      EXPECT_TRUE(in_box(a, m.points[i].position, half)) << i;
      EXPECT_TRUE(in_box(b, m.points[i].position, half)) << i;
    }
  }
  // The sample covers both outcomes, and the least-penetration axis is the usual choice (the
  // preference acts on these deep random overlaps, about 1 in 7; resting contacts are shallow).
  EXPECT_GT(overlapping, 1000);
  EXPECT_GT(separated, 500);
  EXPECT_GT(exact, 4 * preferred);
}

// The narrowphase runs box-box separating axis tests one pair per lane (box_sat.hpp) and
// builds the manifold from the lanes' result: at every level, every bit of collide_boxes().
// Pairs: random, resting face on face (a's or b's face nearly tied), parallel and nearly
// parallel edges (around the cross axis cut-off), zero extents, far from the origin, apart.
TEST(NarrowphaseBoxes, LaneTestsGiveCollideBoxesBitsAtEveryLevel) {
  SplitMix64 rng(0xb0c5'5a71);
  auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.u()); };
  constexpr std::size_t kPairs = 3000, kStride = kPairs + 16;
  std::vector<OBB> a(kPairs), b(kPairs);
  std::vector<float> margin(kPairs);
  for (std::size_t n = 0; n < kPairs; ++n) {
    const vec3 c = n % 13 == 0 ? vec3{u(-1e5f, 1e5f), u(-1e3f, 1e3f), 3e4f} : vec3{u(-2, 2), u(-2, 2), u(-2, 2)};
    auto extent = [&] { return n % 17 == 0 ? 0.0f : u(0.05f, 1.2f); };
    a[n] = box(c, {extent(), extent(), extent()}, testing::random_rotation(rng));
    b[n] = box(c + vec3{u(-1.8f, 1.8f), u(-1.8f, 1.8f), u(-1.8f, 1.8f)}, {extent(), extent(), extent()},
               testing::random_rotation(rng));
    if (n % 5 == 1) b[n].orientation = a[n].orientation;
    if (n % 5 == 2) b[n].orientation = rotation({u(-1, 1), 1, u(-1, 1)}, u(0.0f, 0.2f)) * a[n].orientation;
    if (n % 5 == 3) {  // resting: b on a's top face, shifted sideways
      b[n].orientation = rotation({0, 1, 0}, u(-3, 3)) * a[n].orientation;
      const vec3 up{a[n].orientation.m[1][0], a[n].orientation.m[1][1], a[n].orientation.m[1][2]};
      b[n].center = a[n].center + up * (a[n].half_extents.y + b[n].half_extents.y + u(-0.01f, 0.01f)) +
                    vec3{a[n].orientation.m[0][0], a[n].orientation.m[0][1], a[n].orientation.m[0][2]} * u(-0.8f, 0.8f);
    }
    margin[n] = n % 3 == 0 ? 0.0f : (n % 3 == 1 ? 0.02f : 0.2f);
  }
  // Staged as the narrowphase stages them.
  std::vector<float> in(kSatInputs * kStride, 0.0f);
  for (std::size_t n = 0; n < kPairs; ++n) {
    for (uint32_t r = 0; r < 3; ++r)
      for (uint32_t c = 0; c < 3; ++c) {
        in[(kSatUa + 3 * r + c) * kStride + n] = a[n].orientation.m[r][c];
        in[(kSatUb + 3 * r + c) * kStride + n] = b[n].orientation.m[r][c];
      }
    const vec3 d = b[n].center - a[n].center;
    for (uint32_t c = 0; c < 3; ++c) {
      in[(kSatEa + c) * kStride + n] = a[n].half_extents[c];
      in[(kSatEb + c) * kStride + n] = b[n].half_extents[c];
      in[(kSatD + c) * kStride + n] = d[c];
    }
    in[kSatMargin * kStride + n] = margin[n];
  }
  auto bits = [](float f) { return std::bit_cast<uint32_t>(f); };
  int ran = 0;
  for (SimdLevel level : {SimdLevel::scalar, SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    ++ran;
    std::vector<float> out(kSatOutputs * kStride, -7.0f);
    box_sat_batch_for(level)(BoxSatArgs{in.data(), out.data(), kStride}, 0, kPairs);
    int touching = 0, edges = 0, ref_b = 0, differ = 0;
    for (std::size_t n = 0; n < kPairs; ++n) {
      auto o = [&](uint32_t c) { return out[c * kStride + n]; };
      BoxSat sat;
      sat.hit = o(kSatHit) != 0.0f;
      sat.sa = o(kSatSa), sat.sb = o(kSatSb), sat.se = o(kSatSe);
      sat.ia = int(o(kSatIa)), sat.jb = int(o(kSatJb)), sat.ie = int(o(kSatIe)), sat.je = int(o(kSatJe));
      sat.edge_normal = {o(kSatNormal), o(kSatNormal + 1), o(kSatNormal + 2)};
      Manifold got, want;
      box_manifold(a[n].center, box_axes(a[n]), b[n].center, box_axes(b[n]), sat, margin[n], &got);
      collide_boxes(a[n], b[n], margin[n], &want);
      bool same = got.count == want.count;
      if (same && want.count > 0)
        same = bits(got.normal.x) == bits(want.normal.x) && bits(got.normal.y) == bits(want.normal.y) &&
               bits(got.normal.z) == bits(want.normal.z);
      for (uint32_t k = 0; same && k < want.count; ++k) {
        const ContactPoint &p = got.points[k], &q = want.points[k];
        same = p.feature_id == q.feature_id && bits(p.separation) == bits(q.separation) &&
               bits(p.position.x) == bits(q.position.x) && bits(p.position.y) == bits(q.position.y) &&
               bits(p.position.z) == bits(q.position.z);
      }
      differ += !same;
      touching += want.count > 0;
      edges += want.count > 0 && (want.points[0].feature_id & kFeatureEdge) != 0;
      ref_b += want.count > 0 && (want.points[0].feature_id & kFeatureRefB) != 0;
    }
    EXPECT_EQ(differ, 0) << simd_level_name(level);
    // The sample reaches every branch of the manifold: apart, face on a, face on b, edges.
    EXPECT_GT(touching, 1000) << simd_level_name(level);
    EXPECT_LT(touching, 2900) << simd_level_name(level);
    EXPECT_GT(edges, 50) << simd_level_name(level);
    EXPECT_GT(ref_b, 100) << simd_level_name(level);
  }
  EXPECT_GE(ran, 1);
}

TEST(NarrowphaseBoxes, ZeroExtentsAndFarFromOrigin) {
  // A flat plate (zero thickness) on a box, and a pair a million units away.
  const OBB ground = box({0, 0, 0}, {2, 0.5f, 2});
  Manifold m = boxes(ground, box({0, 0.499f, 0}, {0.5f, 0.0f, 0.5f}));
  ASSERT_EQ(m.count, 4u);
  for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, -0.001f, kTol);
  const vec3 far{1e6f, -1e6f, 5e5f};  // where floats are 1/16 apart, so the offsets below are exact
  m = boxes(box(far, {2, 0.5f, 2}), box(far + vec3{0.25f, 0.9375f, 0}, {0.5f, 0.5f, 0.5f}));
  ASSERT_EQ(m.count, 4u);
  for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, -0.0625f, 0.0625f * 1e-3f);
}

// ---------------------------------------------------------------------------------------
// Box-plane

TEST(NarrowphaseBoxPlane, FlatEdgeAndCorner) {
  const Plane ground{{0, 1, 0}, 0.0f};
  Manifold m;
  collide_box_plane(box({1, 0.49f, 2}, {0.5f, 0.5f, 0.5f}), ground, 0.0f, &m);
  ASSERT_EQ(m.count, 4u);
  expect_near3(m.normal, {0, -1, 0});
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(m.points[i].position.y, -0.005f, kTol);
    EXPECT_NE(m.points[i].feature_id & 2u, 0u);  // the corners on the box's -y side
  }

  // Tilted about z: one bottom edge, two corners.
  const mat3 r = rotation({0, 0, 1}, 25.0f);
  const float c = gyro::cos(deg_to_rad(25.0f)), s = gyro::sin(deg_to_rad(25.0f));
  collide_box_plane(box({0, 0.5f * (c + s) - 0.01f, 0}, {0.5f, 0.5f, 0.5f}, r), ground, 0.0f, &m);
  ASSERT_EQ(m.count, 2u);
  for (uint32_t i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
  EXPECT_EQ(m.points[0].feature_id ^ m.points[1].feature_id, 4u);  // the same edge along z

  // Corner down: the cube's diagonal vertical.
  const mat3 diag = rotation({0, 0, 1}, 45.0f) * rotation({1, 0, 0}, 35.26439f);
  collide_box_plane(box({3, 0.5f * std::sqrt(3.0f) - 0.02f, -1}, {0.5f, 0.5f, 0.5f}, diag), ground, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_NEAR(m.points[0].separation, -0.02f, 1e-4f);
  expect_near3(m.points[0].position, {3, -0.01f, -1}, 1e-4f);

  // Margin, and stable ids.
  collide_box_plane(box({0, 0.51f, 0}, {0.5f, 0.5f, 0.5f}), ground, 0.02f, &m);
  ASSERT_EQ(m.count, 4u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  const auto before = ids(m);
  collide_box_plane(box({1e-4f, 0.51f, -1e-4f}, {0.5f, 0.5f, 0.5f}, rotation({1, 0, 1}, 0.01f)), ground, 0.02f, &m);
  EXPECT_EQ(ids(m), before);
  collide_box_plane(box({0, 0.51f, 0}, {0.5f, 0.5f, 0.5f}), ground, 0.005f, &m);
  EXPECT_EQ(m.count, 0u);
}

// ---------------------------------------------------------------------------------------
// Triangles

// The right triangle (0,0,0), (2,0,0), (0,0,2) in the y = 0 plane (its winding faces -y).
const Triangle kTri{{0, 0, 0}, {2, 0, 0}, {0, 0, 2}};

TEST(NarrowphaseSphereTriangle, FaceEdgeVertexRegions) {
  struct Case {
    vec3 centre;
    float radius;
    uint32_t feature;
    vec3 closest;
  };
  const Case cases[] = {
      {{0.5f, 0.4f, 0.5f}, 0.5f, 0, {0.5f, 0, 0.5f}},   // above the face
      {{0.5f, -0.4f, 0.5f}, 0.5f, 0, {0.5f, 0, 0.5f}},  // below: double-sided
      {{1, 0.3f, -0.4f}, 0.6f, 1, {1, 0, 0}},           // edge ab
      {{1.3f, 0.1f, 1.3f}, 0.5f, 2, {1, 0, 1}},         // edge bc
      {{-0.3f, 0.1f, 1}, 0.5f, 3, {0, 0, 1}},           // edge ca
      {{-0.3f, 0.2f, -0.3f}, 0.5f, 4, {0, 0, 0}},       // vertex a
      {{2.3f, 0.1f, -0.2f}, 0.5f, 5, {2, 0, 0}},        // vertex b
      {{-0.1f, 0.1f, 2.4f}, 0.5f, 6, {0, 0, 2}},        // vertex c
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.feature);
    Manifold m;
    collide_sphere_triangle({c.centre, c.radius}, kTri, 0.0f, &m);
    ASSERT_EQ(m.count, 1u);
    const float dist = distance(c.centre, c.closest);
    EXPECT_EQ(m.points[0].feature_id, c.feature);
    EXPECT_NEAR(m.points[0].separation, dist - c.radius, kTol);
    expect_near3(m.normal, (c.closest - c.centre) / dist);
    expect_near3(m.points[0].position, c.centre + m.normal * (c.radius + m.points[0].separation * 0.5f));
  }
  // Margin.
  Manifold m;
  collide_sphere_triangle({{0.5f, 0.51f, 0.5f}, 0.5f}, kTri, 0.02f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  collide_sphere_triangle({{0.5f, 0.51f, 0.5f}, 0.5f}, kTri, 0.005f, &m);
  EXPECT_EQ(m.count, 0u);
}

TEST(NarrowphaseSphereTriangle, DegenerateAndOnTheSurface) {
  Manifold m;
  // Centre in the triangle's plane: pushed out of the front face (the winding's side, -y).
  collide_sphere_triangle({{0.5f, 0, 0.5f}, 0.5f}, kTri, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.5f, kTol);
  // Collinear corners: the closest of the three edges.
  collide_sphere_triangle({{1, 0.3f, 0}, 0.5f}, {{0, 0, 0}, {1, 0, 0}, {3, 0, 0}}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.2f, kTol);
  // All corners at one point, and the centre on it.
  collide_sphere_triangle({{1, 1, 1}, 0.5f}, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, 0.0f, &m);
  ASSERT_EQ(m.count, 1u);
  EXPECT_TRUE(is_finite(m.normal) && is_finite(m.points[0].position));
  EXPECT_NEAR(length(m.normal), 1.0f, kTol);
}

// A triangle much larger than the box, in the y = 0 plane.
const Triangle kBig{{-10, 0, -10}, {0, 0, 10}, {10, 0, -10}};

Manifold box_tri(const OBB& b, const Triangle& t, float margin = 0.0f) {
  Manifold m;
  collide_box_triangle(b, t, margin, &m);
  expect_well_formed(m);
  return m;
}

TEST(NarrowphaseBoxTriangle, RestingFlatGivesFourPoints) {
  const OBB b = box({0.2f, 0.49f, 0.3f}, {0.5f, 0.5f, 0.5f}, rotation({0, 1, 0}, 20.0f));
  const Manifold m = box_tri(b, kBig);
  ASSERT_EQ(m.count, 4u);
  expect_near3(m.normal, {0, -1, 0});
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(m.points[i].position.y, -0.005f, kTol);
    EXPECT_EQ(m.points[i].feature_id & (kFeatureRefB | 7u << 9), kFeatureRefB | kTriangleFace << 9);
  }
  // Below the triangle: double-sided, pushed down.
  OBB below = b;
  below.center.y = -0.49f;
  const Manifold d = box_tri(below, kBig);
  ASSERT_EQ(d.count, 4u);
  expect_near3(d.normal, {0, 1, 0});
  EXPECT_NEAR(deepest(d), -0.01f, kTol);
  // Margin, and ids under tiny motions.
  OBB gap = b;
  gap.center.y = 0.51f;
  Manifold g = box_tri(gap, kBig, 0.02f);
  ASSERT_EQ(g.count, 4u);
  for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(g.points[i].separation, 0.01f, kTol);
  EXPECT_EQ(box_tri(gap, kBig, 0.005f).count, 0u);
  OBB moved = b;
  moved.center = moved.center + vec3{1e-4f, -1e-4f, 1e-4f};
  moved.orientation = moved.orientation * rotation({1, 0, 1}, 0.005f);
  EXPECT_EQ(ids(box_tri(moved, kBig)), ids(m));
}

TEST(NarrowphaseBoxTriangle, CornerDownGivesOnePoint) {
  const mat3 diag = rotation({0, 0, 1}, 45.0f) * rotation({1, 0, 0}, 35.26439f);
  const OBB b = box({1, 0.5f * std::sqrt(3.0f) - 0.02f, -2}, {0.5f, 0.5f, 0.5f}, diag);
  const Manifold m = box_tri(b, kBig);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0}, 1e-4f);
  EXPECT_NEAR(m.points[0].separation, -0.02f, 1e-4f);
  expect_near3(m.points[0].position, {1, -0.01f, -2}, 1e-4f);
}

TEST(NarrowphaseBoxTriangle, SmallTriangleUnderABoxFace) {
  // The box face is the reference when the triangle's normal is no better: the triangle's
  // corners, clipped by nothing, are the points.
  const Triangle small{{-0.2f, 0, -0.2f}, {0.2f, 0, -0.2f}, {0, 0, 0.3f}};
  const OBB b = box({0, 0.98f, 0}, {1, 1, 1});
  const Manifold m = box_tri(b, small);
  ASSERT_EQ(m.count, 3u);
  expect_near3(m.normal, {0, -1, 0});
  for (uint32_t i = 0; i < 3; ++i) EXPECT_NEAR(m.points[i].separation, -0.02f, kTol);
  // A triangle overhanging the box's face: clipped to it.
  const Triangle wide{{-3, 0, -0.5f}, {3, 0, -0.5f}, {0, 0, 0.5f}};
  const Manifold w = box_tri(box({0, 0.49f, 0}, {0.5f, 0.5f, 0.5f}), wide);
  ASSERT_GE(w.count, 3u);
  for (uint32_t i = 0; i < w.count; ++i) {
    EXPECT_LE(std::abs(w.points[i].position.x), 0.5f + kTol);
    EXPECT_NEAR(w.points[i].separation, -0.01f, kTol);
  }
}

TEST(NarrowphaseBoxTriangle, EdgeAcrossTriangleEdge) {
  // A standing triangle with its top edge along x at y = 0, and a cube turned 45 degrees
  // about z whose bottom edge (along z) crosses it 0.02 deep.
  const Triangle wall{{-2, 0, 0}, {2, 0, 0}, {0.5f, -3, 0}};
  const OBB b = box({0.3f, kHalfSqrt2 - 0.02f, 0.1f}, {0.5f, 0.5f, 0.5f}, rotation({0, 0, 1}, 45.0f));
  const Manifold m = box_tri(b, wall);
  ASSERT_EQ(m.count, 1u);
  expect_near3(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].separation, -0.02f, kTol);
  expect_near3(m.points[0].position, {0.3f, -0.01f, 0});
  EXPECT_EQ(m.points[0].feature_id & 0xF, 0u);  // triangle edge ab
  EXPECT_NE(m.points[0].feature_id & kFeatureEdge, 0u);
}

TEST(NarrowphaseBoxTriangle, RandomPairsAreConsistent) {
  // Against gyro's box-triangle overlap test: a pair overlapping by more than a little has
  // points with separation <= 0; a pair apart by more than the margin has none.
  SplitMix64 rng(77);
  int overlapping = 0;
  for (int n = 0; n < 3000; ++n) {
    auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.u()); };
    const OBB b =
        box({u(-1, 1), u(-1, 1), u(-1, 1)}, {u(0.1f, 1), u(0.1f, 1), u(0.1f, 1)}, testing::random_rotation(rng));
    const Triangle t{{u(-2, 2), u(-2, 2), u(-2, 2)}, {u(-2, 2), u(-2, 2), u(-2, 2)}, {u(-2, 2), u(-2, 2), u(-2, 2)}};
    const Manifold m = box_tri(b, t, 0.02f);
    // Shrunk by 1e-3 the box still overlaps: a clear overlap.
    OBB shrunk = b;
    shrunk.half_extents = shrunk.half_extents - vec3{1e-3f, 1e-3f, 1e-3f};
    OBB grown = b;
    grown.half_extents = grown.half_extents + vec3{0.03f, 0.03f, 0.03f};
    SCOPED_TRACE(n);
    if (overlaps(shrunk, t)) {
      ++overlapping;
      ASSERT_GT(m.count, 0u);
      EXPECT_LE(deepest(m), 0.0f);
    }
    if (!overlaps(grown, t)) {
      EXPECT_EQ(m.count, 0u);
    }
    for (uint32_t i = 0; i < m.count; ++i) {
      const float half = midway_tolerance(m.points[i].separation);
      EXPECT_TRUE(in_box(b, m.points[i].position, half));
      EXPECT_LE(distance(closest_point(t, m.points[i].position), m.points[i].position), half);
    }
  }
  EXPECT_GT(overlapping, 300);
}

// Zero extents, coincident shapes, radius 0, collinear and coincident triangle corners: a
// finite, well-formed answer every time.
TEST(NarrowphaseDegenerate, FiniteOnDegenerateInputs) {
  SplitMix64 rng(99);
  auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.u()); };
  auto extent = [&] { return rng.u() < 0.25 ? 0.0f : u(0.05f, 1.0f); };
  auto finite = [](const Manifold& m) {
    if (m.count == 0) return true;
    bool ok = is_finite(m.normal) && std::abs(length(m.normal) - 1.0f) < 1e-5f && m.count <= kMaxManifoldPoints;
    for (uint32_t i = 0; i < m.count; ++i) {
      ok = ok && is_finite(m.points[i].position) && std::isfinite(m.points[i].separation);
      for (uint32_t j = 0; j < i; ++j) ok = ok && m.points[i].feature_id != m.points[j].feature_id;
    }
    return ok;
  };
  int touching = 0;
  for (int n = 0; n < 3000; ++n) {
    const vec3 c{u(-1, 1), u(-1, 1), u(-1, 1)};
    const OBB a = box(c, {extent(), extent(), extent()}, testing::random_rotation(rng));
    OBB b = box(c + vec3{u(-1, 1), u(-1, 1), u(-1, 1)}, {extent(), extent(), extent()}, testing::random_rotation(rng));
    if (n % 10 == 0) b = a;                          // coincident
    if (n % 10 == 1) b.orientation = a.orientation;  // parallel edges everywhere
    vec3 p[3] = {c + vec3{u(-1, 1), u(-1, 1), u(-1, 1)}, c + vec3{u(-1, 1), u(-1, 1), u(-1, 1)}, c};
    switch (n % 4) {
      case 0:
        p[1] = p[0];
        break;  // two corners coincide
      case 1:
        p[2] = p[0] + (p[1] - p[0]) * 0.25f;
        break;  // collinear
      case 2:
        p[1] = p[2] = p[0];
        break;  // a point
      default:
        break;
    }
    const Triangle t{p[0], p[1], p[2]};
    const Sphere s{n % 3 == 0 ? a.center : c + vec3{u(-1, 1), u(-1, 1), u(-1, 1)}, n % 5 == 0 ? 0.0f : u(0, 1)};
    Manifold m[8];
    collide_boxes(a, b, 0.02f, &m[0]);
    collide_box_triangle(a, t, 0.02f, &m[1]);
    collide_sphere_triangle(s, t, 0.02f, &m[2]);
    collide_sphere_box(s, a, 0.02f, &m[3]);
    collide_box_plane(a, Plane{normalized(vec3{u(-1, 1), 1, u(-1, 1)}), u(-1, 1)}, 0.02f, &m[4]);
    collide_spheres(s, Sphere{n % 2 ? s.center : b.center, 0.0f}, 0.02f, &m[5]);
    collide_sphere_plane(s, Plane{{0, 1, 0}, c.y}, 0.02f, &m[6]);
    collide_boxes(b, a, 0.0f, &m[7]);
    for (int k = 0; k < 8; ++k) {
      EXPECT_TRUE(finite(m[k])) << "pair " << n << " kind " << k;
      touching += m[k].count > 0;
    }
    if (n % 10 == 0) {
      EXPECT_GT(m[0].count, 0u) << n;  // coincident boxes touch
    }
  }
  EXPECT_GT(touching, 5000);
}

// ---------------------------------------------------------------------------------------
// TriangleMesh::triangles_overlapping

float bumps(float x, float z, void*) { return 0.3f * x - 0.05f * x * z + 0.01f * z * z; }

std::vector<uint32_t> brute_force(const TriangleMesh& mesh, const AABB& box) {
  const vec3 lo = aabb_min(box), hi = aabb_max(box);
  std::vector<uint32_t> out;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
    const Triangle t = mesh.triangle(i);
    bool in = true;
    for (int a = 0; a < 3; ++a)
      in = in && std::min({t.a[a], t.b[a], t.c[a]}) <= hi[a] && lo[a] <= std::max({t.a[a], t.b[a], t.c[a]});
    if (in) out.push_back(uint32_t(i));
  }
  return out;
}

TEST(TriangleMeshOverlapping, MatchesBruteForceInAscendingOrder) {
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(make_grid_mesh(37, 23, 0.5f, bumps), mesh), Status::ok);
  SplitMix64 rng(4242);
  std::vector<uint32_t> got(4096);
  std::size_t nonempty = 0;
  for (int n = 0; n < 600; ++n) {
    auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.u()); };
    const AABB q{{u(-11, 11), u(-4, 4), u(-7, 7)}, {u(0, 2.5f), u(0, 2.5f), u(0, 2.5f)}};
    const std::vector<uint32_t> want = brute_force(mesh, q);
    nonempty += !want.empty();
    const std::size_t count = mesh.triangles_overlapping(q, got.data(), got.size());
    ASSERT_EQ(count, want.size());
    EXPECT_TRUE(std::equal(want.begin(), want.end(), got.begin()));
    // Truncated: the smallest indices, still ascending; capacity 0 only counts.
    for (std::size_t cap : {std::size_t{1}, std::size_t{5}, std::size_t{16}}) {
      std::vector<uint32_t> part(cap, 0xDEADBEEFu);
      ASSERT_EQ(mesh.triangles_overlapping(q, part.data(), cap), want.size());
      const std::size_t k = std::min(cap, want.size());
      EXPECT_TRUE(std::equal(want.begin(), want.begin() + k, part.begin()));
      for (std::size_t i = k; i < cap; ++i) EXPECT_EQ(part[i], 0xDEADBEEFu);
    }
    EXPECT_EQ(mesh.triangles_overlapping(q, nullptr, 0), want.size());
  }
  EXPECT_GT(nonempty, 200u);
}

TEST(TriangleMeshOverlapping, ClosedBoundsAndEdgeCases) {
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(make_grid_mesh(4, 4, 1.0f), mesh), Status::ok);  // flat, x and z in [-2, 2]
  uint32_t out[64];
  // A box whose bottom face touches the flat grid exactly: every triangle.
  EXPECT_EQ(mesh.triangles_overlapping(aabb_from_min_max({-5, 0, -5}, {5, 1, 5}), out, 64), 32u);
  for (int i = 0; i < 32; ++i) EXPECT_EQ(out[i], uint32_t(i));
  // Touching the grid's corner x = z = 2 from outside: the triangles there.
  const AABB corner = aabb_from_min_max({2, -1, 2}, {3, 1, 3});
  EXPECT_EQ(mesh.triangles_overlapping(corner, out, 64), brute_force(mesh, corner).size());
  EXPECT_GE(mesh.triangles_overlapping(corner, out, 64), 1u);
  // A zero-size box, a box just off the surface, a NaN box, a mesh never created.
  EXPECT_EQ(mesh.triangles_overlapping(AABB{{0.5f, 0, 0.25f}, {0, 0, 0}}, out, 64), 2u);
  EXPECT_EQ(mesh.triangles_overlapping(aabb_from_min_max({-5, 1e-6f, -5}, {5, 1, 5}), out, 64), 0u);
  const float nan = __builtin_nanf("");
  EXPECT_EQ(mesh.triangles_overlapping(AABB{{nan, 0, 0}, {1, 1, 1}}, out, 64), 0u);
  EXPECT_EQ(TriangleMesh{}.triangles_overlapping(AABB{{0, 0, 0}, {1, 1, 1}}, out, 64), 0u);
}

// Two parallel capsules side by side where b's segment lies wholly past one end of a's: the
// clip against a's span leaves nothing (the first plane once left an empty segment that the
// second read at index -1, found by the C ABI fuzzer). EPA's single point remains, at the
// true depth; both ends, so either clipping plane empties it first.
TEST(ConvexManifold, ParallelCapsulesPastTheEndOfEachOtherGiveOnePoint) {
  ConvexCollider a, b;
  ASSERT_EQ(make_capsule(0.5f, 1.0f, a.shape), Status::ok);  // segment y in [-1, 1]
  ASSERT_EQ(make_capsule(0.5f, 0.5f, b.shape), Status::ok);
  for (const float side : {-1.0f, 1.0f}) {
    b.pose.position = {0.9f, side * 1.51f, 0.0f};  // segment y in [1.01, 2.01] times side
    Manifold m;
    collide_convex_shapes(a, b, 0.02f, &m);
    ASSERT_EQ(m.count, 1u) << side;
    const float gap = std::sqrt(0.9f * 0.9f + 0.01f * 0.01f);
    EXPECT_NEAR(m.points[0].separation, gap - 1.0f, 1e-4f) << side;
    EXPECT_NEAR(m.normal.x, 0.9f / gap, 1e-3f) << side;
    EXPECT_NEAR(m.normal.y, side * 0.01f / gap, 1e-3f) << side;
  }
}

}  // namespace
}  // namespace gyro::detail
