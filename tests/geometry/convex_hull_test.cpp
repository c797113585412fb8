// Quickhull (gyro/convex.hpp build_convex_hull): exact answers on boxes with points on
// their faces, edges and inside (merged faces, dropped collinear and interior points,
// welded duplicates); on random clouds every input point inside every face plane to the
// tolerance, planar convex faces, V - E + F = 2; bad input gives a clear status and an
// empty hull; the same input gives the same bits.
#include "gyro/convex.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

// Checks the structural invariants and that every point lies inside (to tol).
void check_hull(const ConvexHull& h, const std::vector<vec3>& pts, float tol) {
  ASSERT_EQ(h.face_start.size(), h.face_count() + 1);
  EXPECT_EQ(long(h.vertices.size()) - long(h.edge_count()) + long(h.face_count()), 2);
  for (std::size_t f = 0; f < h.face_count(); ++f) {
    const Plane& pl = h.planes[f];
    EXPECT_NEAR(length(pl.normal), 1.0f, 1e-6f);
    const uint32_t b = h.face_start[f], e = h.face_start[f + 1];
    ASSERT_GE(e - b, 3u);
    for (uint32_t k = b; k < e; ++k) {
      // Planar and convex: corners on the plane, each turn counter-clockwise about the normal.
      const vec3 p0 = h.vertices[h.face_vertices[k]];
      const vec3 p1 = h.vertices[h.face_vertices[b + (k + 1 - b) % (e - b)]];
      const vec3 p2 = h.vertices[h.face_vertices[b + (k + 2 - b) % (e - b)]];
      EXPECT_NEAR(dot(pl.normal, p0), pl.distance, tol);
      EXPECT_GT(dot(cross(p1 - p0, p2 - p1), pl.normal), 0.0f) << "face " << f << " turns the wrong way or is straight";
    }
    for (const vec3& p : pts) EXPECT_LE(dot(pl.normal, p) - pl.distance, tol);
  }
}

TEST(ConvexHull, BoxWithFaceEdgeAndInteriorPoints) {
  std::vector<vec3> pts;
  // A 3 x 2 x 1 box sampled on a 5^3 grid: corners, edge points, face points, interior.
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) pts.push_back({-1.5f + 0.75f * i, -1.0f + 0.5f * j, -0.5f + 0.25f * k});
  ConvexHull h;
  ASSERT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_EQ(h.face_count(), 6u);
  EXPECT_EQ(h.edge_count(), 12u);
  for (std::size_t f = 0; f < h.face_count(); ++f) EXPECT_EQ(h.face_start[f + 1] - h.face_start[f], 4u);
  check_hull(h, pts, 1e-5f);
  // The vertices come in input order: the first is the grid's (0, 0, 0) corner.
  EXPECT_EQ(h.vertices[0], (vec3{-1.5f, -1.0f, -0.5f}));
}

TEST(ConvexHull, WeldsNearDuplicates) {
  std::vector<vec3> pts;
  SplitMix64 rng(3);
  for (int rep = 0; rep < 4; ++rep)
    for (int c = 0; c < 8; ++c) {
      const float j = float(rng.u() - 0.5) * 1e-7f;  // well inside the 1e-6 weld tolerance
      pts.push_back({(c & 1 ? 1.0f : -1.0f) + j, (c & 2 ? 1.0f : -1.0f) - j, (c & 4 ? 1.0f : -1.0f) + j});
    }
  ConvexHull h;
  ASSERT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_EQ(h.face_count(), 6u);
  check_hull(h, pts, 1e-5f);
}

TEST(ConvexHull, RandomCloudsOnAndInsideSpheres) {
  SplitMix64 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 4 + int(rng.u() * 300);
    std::vector<vec3> pts;
    const bool on_sphere = trial % 2 == 0;
    while (int(pts.size()) < n) {
      vec3 p{float(2 * rng.u() - 1), float(2 * rng.u() - 1), float(2 * rng.u() - 1)};
      if (dot(p, p) > 1.0f || dot(p, p) < 1e-2f) continue;
      if (on_sphere) p = normalized(p);
      pts.push_back(p * 3.0f + vec3{100.0f, -50.0f, 7.0f});
    }
    ConvexHull h;
    const Status s = build_convex_hull(pts.data(), pts.size(), h);
    ASSERT_EQ(s, Status::ok) << last_error() << " trial " << trial;
    check_hull(h, pts, 1e-4f);
    if (on_sphere) { EXPECT_GT(h.vertices.size(), std::size_t(n) * 9 / 10); }  // almost every point is a vertex
  }
}

TEST(ConvexHull, BadInputGivesClearStatus) {
  ConvexHull h;
  std::vector<vec3> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(build_convex_hull(three.data(), 3, h), Status::invalid_count);
  EXPECT_EQ(build_convex_hull(nullptr, 10, h), Status::null_argument);
  std::vector<vec3> same(10, vec3{1, 2, 3});
  EXPECT_EQ(build_convex_hull(same.data(), same.size(), h), Status::invalid_argument);
  EXPECT_NE(std::string(last_error()).find("coincide"), std::string::npos);
  std::vector<vec3> line;
  for (int i = 0; i < 10; ++i) line.push_back({float(i), 2.0f * i, 0.5f});
  EXPECT_EQ(build_convex_hull(line.data(), line.size(), h), Status::invalid_argument);
  EXPECT_NE(std::string(last_error()).find("collinear"), std::string::npos);
  std::vector<vec3> plane;
  for (int i = 0; i < 10; ++i) plane.push_back({float(i % 3), float(i / 3), 1.0f});
  EXPECT_EQ(build_convex_hull(plane.data(), plane.size(), h), Status::invalid_argument);
  EXPECT_NE(std::string(last_error()).find("coplanar"), std::string::npos);
  std::vector<vec3> nan{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, std::nanf("")}};
  EXPECT_EQ(build_convex_hull(nan.data(), nan.size(), h), Status::non_finite);
  EXPECT_TRUE(h.vertices.empty() && h.planes.empty() && h.edges.empty());
}

TEST(ConvexHull, SameInputSameBits) {
  SplitMix64 rng(99);
  std::vector<vec3> pts;
  for (int i = 0; i < 500; ++i) pts.push_back({float(rng.u()), float(rng.u()), float(rng.u())});
  ConvexHull a, b;
  ASSERT_EQ(build_convex_hull(pts.data(), pts.size(), a), Status::ok);
  ASSERT_EQ(build_convex_hull(pts.data(), pts.size(), b), Status::ok);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
  EXPECT_EQ(a.edges, b.edges);
  check_hull(a, pts, 1e-5f);
}

}  // namespace
}  // namespace gyro
