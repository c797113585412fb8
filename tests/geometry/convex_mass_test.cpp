// convex_hull_mass (gyro/convex.hpp): volume, centroid and inertia against closed forms
// (boxes, a right-corner tetrahedron, a regular prism, a finely tessellated sphere), the
// principal frame (a rotated box gives back its rotation; a cube keeps the hull's axes
// exactly), inertia == axes^T diag(moments) axes, bit-identical repeats, and failures that
// leave the output untouched.
//
// Conventions checked: moments ascending; axis k (row k of principal_axes) belongs to
// moment k; each axis's largest-magnitude component is positive, except that the last axis
// is negated when needed to make the frame right-handed (det +1).
#include "gyro/convex.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

ConvexHull hull_of(const std::vector<vec3>& pts) {
  ConvexHull h;
  EXPECT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  return h;
}

std::vector<vec3> box_corners(const vec3& center, const vec3& half, const mat3& rot = mat3{}) {
  std::vector<vec3> pts;
  for (int c = 0; c < 8; ++c) {
    const vec3 local{c & 1 ? half.x : -half.x, c & 2 ? half.y : -half.y, c & 4 ? half.z : -half.z};
    pts.push_back(local * rot + center);
  }
  return pts;
}

vec3 axis_of(const mat3& m, int k) { return {m.m[k][0], m.m[k][1], m.m[k][2]}; }

// A rotation from three angles (rows are the rotated axes).
mat3 rotation(double ax, double ay, double az) {
  const double cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay), cz = std::cos(az), sz = std::sin(az);
  const double rx[3][3] = {{1, 0, 0}, {0, cx, sx}, {0, -sx, cx}};
  const double ry[3][3] = {{cy, 0, -sy}, {0, 1, 0}, {sy, 0, cy}};
  const double rz[3][3] = {{cz, sz, 0}, {-sz, cz, 0}, {0, 0, 1}};
  double t[3][3] = {}, r[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) t[i][j] += rx[i][k] * ry[k][j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i][j] += t[i][k] * rz[k][j];
  mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.m[i][j] = float(r[i][j]);
  return m;
}

// Rows unit, orthogonal, det +1; inertia rebuilt from the frame within rel of the largest moment.
void check_frame(const ConvexMass& m, double rel = 1e-5) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(length(axis_of(m.principal_axes, k)), 1.0f, 1e-6f) << "axis " << k;
    for (int q = k + 1; q < 3; ++q) EXPECT_NEAR(dot(axis_of(m.principal_axes, k), axis_of(m.principal_axes, q)), 0.0f, 1e-6f);
  }
  EXPECT_NEAR(determinant(m.principal_axes), 1.0f, 1e-6f);
  EXPECT_LE(m.principal_moments.x, m.principal_moments.y);
  EXPECT_LE(m.principal_moments.y, m.principal_moments.z);
  const double big = m.principal_moments.z;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += double(m.principal_axes.m[k][i]) * m.principal_moments[k] * m.principal_axes.m[k][j];
      EXPECT_NEAR(s, m.inertia.m[i][j], rel * big) << "element " << i << ", " << j;
      EXPECT_EQ(m.inertia.m[i][j], m.inertia.m[j][i]);
    }
}

TEST(ConvexMass, BoxMatchesClosedForm) {
  const vec3 half{0.5f, 1.0f, 1.5f}, center{3.0f, -7.0f, 11.0f};
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(hull_of(box_corners(center, half)), m), Status::ok);
  const double v = 8.0 * 0.5 * 1.0 * 1.5;
  EXPECT_NEAR(m.volume, v, 1e-6 * v);
  EXPECT_NEAR(m.centroid.x, center.x, 1e-5f);
  EXPECT_NEAR(m.centroid.y, center.y, 1e-5f);
  EXPECT_NEAR(m.centroid.z, center.z, 1e-5f);
  // m/12 (b^2 + c^2) with full sides b = 2 hy, c = 2 hz, i.e. m/3 (hy^2 + hz^2).
  const double ix = v / 3.0 * (1.0 + 2.25), iy = v / 3.0 * (0.25 + 2.25), iz = v / 3.0 * (0.25 + 1.0);
  EXPECT_NEAR(m.inertia.m[0][0], ix, 1e-6 * ix);
  EXPECT_NEAR(m.inertia.m[1][1], iy, 1e-6 * iy);
  EXPECT_NEAR(m.inertia.m[2][2], iz, 1e-6 * iz);
  EXPECT_NEAR(m.inertia.m[0][1], 0.0f, 1e-6 * ix);
  EXPECT_NEAR(m.inertia.m[0][2], 0.0f, 1e-6 * ix);
  EXPECT_NEAR(m.inertia.m[1][2], 0.0f, 1e-6 * ix);
  // Ascending: z (smallest), y, x; the third axis is -x so the frame is right-handed.
  EXPECT_NEAR(m.principal_moments.x, iz, 1e-6 * ix);
  EXPECT_NEAR(m.principal_moments.y, iy, 1e-6 * ix);
  EXPECT_NEAR(m.principal_moments.z, ix, 1e-6 * ix);
  EXPECT_EQ(axis_of(m.principal_axes, 0), (vec3{0.0f, 0.0f, 1.0f}));
  EXPECT_EQ(axis_of(m.principal_axes, 1), (vec3{0.0f, 1.0f, 0.0f}));
  EXPECT_EQ(axis_of(m.principal_axes, 2), (vec3{-1.0f, 0.0f, 0.0f}));
  check_frame(m);
}

TEST(ConvexMass, CubeKeepsTheHullAxes) {
  // Three equal moments: any frame is principal; the diagonal tensor keeps the identity.
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(hull_of(box_corners({-4.0f, 2.5f, 100.0f}, {1.0f, 1.0f, 1.0f})), m), Status::ok);
  EXPECT_NEAR(m.volume, 8.0f, 1e-5f);
  EXPECT_EQ(m.principal_axes, mat3::identity());
  const float want = 8.0f / 3.0f * 2.0f;
  EXPECT_NEAR(m.principal_moments.x, want, 1e-5f * want);
  EXPECT_NEAR(m.principal_moments.z, want, 1e-5f * want);
  check_frame(m);
  // Two equal moments (a square plate across z): x and y keep their order, z is last.
  ASSERT_EQ(convex_hull_mass(hull_of(box_corners({0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 0.5f})), m), Status::ok);
  EXPECT_EQ(m.principal_axes, mat3::identity());
  check_frame(m);
}

TEST(ConvexMass, RotatedBoxGivesBackItsRotation) {
  const vec3 half{0.3f, 0.7f, 1.9f};
  const mat3 rot = rotation(0.4, -1.1, 2.3);
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(hull_of(box_corners({1.0f, 2.0f, -3.0f}, half, rot)), m), Status::ok);
  const double v = 8.0 * half.x * half.y * half.z;
  EXPECT_NEAR(m.volume, v, 1e-5 * v);
  EXPECT_NEAR(m.centroid.x, 1.0f, 1e-5f);
  EXPECT_NEAR(m.centroid.y, 2.0f, 1e-5f);
  EXPECT_NEAR(m.centroid.z, -3.0f, 1e-5f);
  // Smallest moment about the longest side (local z), largest about local x.
  const double hx2 = half.x * half.x, hy2 = half.y * half.y, hz2 = half.z * half.z;
  const double want[3] = {v / 3 * (hx2 + hy2), v / 3 * (hx2 + hz2), v / 3 * (hy2 + hz2)};
  const int local_axis[3] = {2, 1, 0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(m.principal_moments[k], want[k], 1e-5 * want[2]);
    // Up to sign: the principal axis is the box's local axis in the hull frame.
    EXPECT_NEAR(std::abs(dot(axis_of(m.principal_axes, k), axis_of(rot, local_axis[k]))), 1.0f, 1e-5f) << k;
  }
  check_frame(m);
}

TEST(ConvexMass, RightCornerTetrahedron) {
  // Corners o, o + a x, o + b y, o + c z: volume abc/6, centroid o + (a, b, c)/4, and about
  // the centroid I_xx = 3V/80 (b^2 + c^2), I_xy = V ab / 80 (products of inertia carry a
  // minus sign in the covariance, so the tensor's off-diagonal is + here).
  const double a = 1.0, b = 2.0, c = 3.0;
  const vec3 o{5.0f, -1.0f, 2.0f};
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(hull_of({o, o + vec3{1, 0, 0}, o + vec3{0, 2, 0}, o + vec3{0, 0, 3}}), m), Status::ok);
  const double v = a * b * c / 6.0;
  EXPECT_NEAR(m.volume, v, 1e-6);
  EXPECT_NEAR(m.centroid.x, o.x + a / 4, 1e-5);
  EXPECT_NEAR(m.centroid.y, o.y + b / 4, 1e-5);
  EXPECT_NEAR(m.centroid.z, o.z + c / 4, 1e-5);
  const double d[3] = {a, b, c};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double want = i == j ? 3.0 * v / 80.0 * (d[(i + 1) % 3] * d[(i + 1) % 3] + d[(i + 2) % 3] * d[(i + 2) % 3])
                                 : v * d[i] * d[j] / 80.0;
      EXPECT_NEAR(m.inertia.m[i][j], want, 1e-6) << i << ", " << j;
    }
  check_frame(m);
}

// An icosahedron subdivided `levels` times, projected onto the sphere.
std::vector<vec3> icosphere(const vec3& center, float radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4}, {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](std::array<double, 3> p) {
    const double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / l, p[1] / l, p[2] / l};
  };
  for (auto& p : v) p = unit(p);
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<int, 3>> next;
    auto mid = [&](int i, int j) {
      v.push_back(unit({v[i][0] + v[j][0], v[i][1] + v[j][1], v[i][2] + v[j][2]}));
      return int(v.size()) - 1;  // duplicates are welded by the hull
    };
    for (const auto& tri : f) {
      const int a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      next.push_back({tri[0], a, c}), next.push_back({tri[1], b, a}), next.push_back({tri[2], c, b}), next.push_back({a, b, c});
    }
    f = next;
  }
  std::vector<vec3> pts;
  for (const auto& p : v) pts.push_back(center + vec3{float(p[0]), float(p[1]), float(p[2])} * radius);
  return pts;
}

TEST(ConvexMass, IcosphereApproachesSolidSphere) {
  const float r = 2.0f;
  const vec3 center{-3.0f, 4.0f, 0.5f};
  const ConvexHull h = hull_of(icosphere(center, r, 3));
  ASSERT_EQ(h.vertices.size(), 642u);
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(h, m), Status::ok);
  const double pi = 3.14159265358979323846;
  // An inscribed polyhedron with 1280 faces: the volume is about 1% short.
  EXPECT_NEAR(m.volume, 4.0 / 3.0 * pi * r * r * r, 0.02 * (4.0 / 3.0 * pi * r * r * r));
  EXPECT_LT(m.volume, 4.0 / 3.0 * pi * r * r * r);
  EXPECT_NEAR(m.centroid.x, center.x, 1e-4f);
  EXPECT_NEAR(m.centroid.y, center.y, 1e-4f);
  EXPECT_NEAR(m.centroid.z, center.z, 1e-4f);
  // 2/5 m r^2 for the polyhedron's own mass: the shape error is under 1%.
  const double want = 0.4 * m.volume * r * r;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.principal_moments[k], want, 0.01 * want) << k;
  EXPECT_NEAR(m.principal_moments.z, m.principal_moments.x, 1e-3 * want);  // isotropic
  check_frame(m);
}

TEST(ConvexMass, RegularPrismMatchesClosedForm) {
  // An n-gon prism along y, circumradius R, height H: area A = n/2 R^2 sin(2 pi/n), polar
  // moment of the n-gon J = n R^4 / 12 sin(2 pi/n) (2 + cos(2 pi/n)); I_yy = H J and
  // I_xx = I_zz = H J / 2 + A H^3 / 12 (the cylinder's m(3R^2 + H^2)/12 as n grows).
  const int n = 48;
  const double R = 0.75, H = 3.0, pi = 3.14159265358979323846;
  std::vector<vec3> pts;
  for (int i = 0; i < n; ++i)
    for (int s = 0; s < 2; ++s) {
      const double a = 2.0 * pi * i / n;
      pts.push_back({float(R * std::cos(a)) + 1.0f, float(s ? H / 2 : -H / 2) - 2.0f, float(R * std::sin(a))});
    }
  const ConvexHull h = hull_of(pts);
  ASSERT_EQ(h.face_count(), std::size_t(n + 2));
  ConvexMass m;
  ASSERT_EQ(convex_hull_mass(h, m), Status::ok);
  const double area = n / 2.0 * R * R * std::sin(2 * pi / n);
  const double j = n * R * R * R * R / 12.0 * std::sin(2 * pi / n) * (2 + std::cos(2 * pi / n));
  const double iyy = H * j, ixx = H * j / 2 + area * H * H * H / 12;
  EXPECT_NEAR(m.volume, area * H, 1e-5 * area * H);
  EXPECT_NEAR(m.centroid.x, 1.0f, 1e-5f);
  EXPECT_NEAR(m.centroid.y, -2.0f, 1e-5f);
  EXPECT_NEAR(m.centroid.z, 0.0f, 1e-5f);
  EXPECT_NEAR(m.inertia.m[0][0], ixx, 1e-5 * ixx);
  EXPECT_NEAR(m.inertia.m[1][1], iyy, 1e-5 * ixx);
  EXPECT_NEAR(m.inertia.m[2][2], ixx, 1e-5 * ixx);
  // The axis (y) has the smallest moment: it comes first.
  EXPECT_NEAR(m.principal_moments.x, iyy, 1e-5 * ixx);
  EXPECT_NEAR(std::abs(m.principal_axes.m[0][1]), 1.0f, 1e-5f);
  check_frame(m);
}

TEST(ConvexMass, RandomHullsHaveConsistentFrames) {
  SplitMix64 rng(21);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<vec3> pts;
    const int count = 4 + int(rng.u() * 60);
    const vec3 scale{float(0.1 + 3 * rng.u()), float(0.1 + 3 * rng.u()), float(0.1 + 3 * rng.u())};
    const vec3 offset{float(20 * rng.u() - 10), float(20 * rng.u() - 10), float(20 * rng.u() - 10)};
    for (int i = 0; i < count; ++i)
      pts.push_back(offset + vec3{float(rng.u() - 0.5) * scale.x, float(rng.u() - 0.5) * scale.y, float(rng.u() - 0.5) * scale.z});
    ConvexHull h;
    if (build_convex_hull(pts.data(), pts.size(), h) != Status::ok) continue;
    ConvexMass m;
    ASSERT_EQ(convex_hull_mass(h, m), Status::ok) << "trial " << trial;
    EXPECT_GT(m.volume, 0.0f);
    // The centroid is inside: behind every face plane.
    for (const Plane& p : h.planes) EXPECT_LT(dot(p.normal, m.centroid) - p.distance, 0.0f);
    check_frame(m);
  }
}

TEST(ConvexMass, RepeatsBitForBit) {
  const ConvexHull h = hull_of(icosphere({1.0f, 2.0f, 3.0f}, 0.5f, 2));
  ConvexMass a, b;
  ASSERT_EQ(convex_hull_mass(h, a), Status::ok);
  ASSERT_EQ(convex_hull_mass(h, b), Status::ok);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
}

TEST(ConvexMass, BadHullsFailAndLeaveTheOutputAlone) {
  ConvexMass sentinel;
  sentinel.volume = 42.0f;
  sentinel.centroid = {1.0f, 2.0f, 3.0f};
  sentinel.principal_moments = {4.0f, 5.0f, 6.0f};
  ConvexMass out = sentinel;
  auto unchanged = [&] { return std::memcmp(&out, &sentinel, sizeof out) == 0; };

  EXPECT_EQ(convex_hull_mass(ConvexHull{}, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());
  EXPECT_NE(std::string(last_error()).find("convex hull mass"), std::string::npos);

  // A hull whose faces are wound inside out has a negative volume.
  ConvexHull inside_out = hull_of(box_corners({0, 0, 0}, {1, 1, 1}));
  for (std::size_t f = 0; f < inside_out.face_count(); ++f)
    std::reverse(inside_out.face_vertices.begin() + inside_out.face_start[f], inside_out.face_vertices.begin() + inside_out.face_start[f + 1]);
  EXPECT_EQ(convex_hull_mass(inside_out, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());

  // Malformed: a corner index past the vertices, a face with two corners.
  ConvexHull bad_index = hull_of(box_corners({0, 0, 0}, {1, 1, 1}));
  bad_index.face_vertices[5] = 99;
  EXPECT_EQ(convex_hull_mass(bad_index, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());
  ConvexHull short_face = hull_of(box_corners({0, 0, 0}, {1, 1, 1}));
  short_face.face_start[1] = 2;
  EXPECT_EQ(convex_hull_mass(short_face, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());

  // A flat "hull" (every vertex on one plane) has no volume.
  ConvexHull flat = hull_of(box_corners({0, 0, 0}, {1, 1, 1}));
  for (vec3& v : flat.vertices) v.z = 0.0f;
  EXPECT_EQ(convex_hull_mass(flat, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());

  // A non-finite vertex.
  ConvexHull nan = hull_of(box_corners({0, 0, 0}, {1, 1, 1}));
  nan.vertices[0].x = std::nanf("");
  EXPECT_EQ(convex_hull_mass(nan, out), Status::invalid_argument);
  EXPECT_TRUE(unchanged());
}

}  // namespace
}  // namespace gyro
