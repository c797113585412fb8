// The generators reproduce BENCHMARKS.md bit for bit (its check values and hashes).
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gyro::testing {
namespace {

TEST(Workloads, SplitMixCheckValues) {
  EXPECT_EQ(SplitMix64(0).next(), 0xe220a8397b1dcdafull);
  SplitMix64 one(1);
  EXPECT_EQ(SplitMix64(1).next(), 0x910a2dec89025cc1ull);
  EXPECT_NEAR(one.u(), 0.56656152, 1e-8);
  EXPECT_NEAR(one.u(), 0.74578172, 1e-8);
  EXPECT_NEAR(one.u(), 0.971002698, 1e-9);
}

TEST(Workloads, R1MatchesThePublishedHashes) {
  EXPECT_EQ(r1_spheres().fnv(), kR1SpheresFnv);
  EXPECT_EQ(r1_rays().fnv(), kR1RaysFnv);
}

TEST(Workloads, R2MatchesThePublishedHashes) {
  const MeshData mesh = r2_mesh();
  ASSERT_EQ(mesh.vertex_count(), 512u * 512u);
  ASSERT_EQ(mesh.triangle_count(), 522242u);
  EXPECT_EQ(mesh_vertices_fnv(mesh), kR2VerticesFnv);
  EXPECT_EQ(mesh_indices_fnv(mesh), kR2IndicesFnv);
  EXPECT_EQ(r2_rays().fnv(), kR2RaysFnv);
}

TEST(Workloads, R2TrianglesFaceUpAndTileTheSquare) {
  const MeshData mesh = r2_mesh();
  double area = 0;  // projected on y = 0: the cells tile [0, 100]^2 exactly once
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = mesh.triangle(t);
    const double ax = tri.b.x - tri.a.x, az = tri.b.z - tri.a.z, bx = tri.c.x - tri.a.x, bz = tri.c.z - tri.a.z;
    const double ny = az * bx - ax * bz;  // y of (b - a) x (c - a)
    ASSERT_GT(ny, 0.0) << "triangle " << t;
    area += 0.5 * ny;
  }
  EXPECT_NEAR(area, 100.0 * 100.0, 1e-6);
  // Vertex (i, j) = (511, 0) sits at x = 100, z = 0; its height is the formula's, in float.
  EXPECT_EQ(mesh.x[511], 100.0f);
  EXPECT_EQ(mesh.z[511], 0.0f);
  EXPECT_EQ(mesh.y[511], static_cast<float>(5 * std::sin(10.0) + 2 * std::sin(70.0)));
}

TEST(Workloads, R2RaysStartAbove20AndPointDown) {
  const RaySet rays = r2_rays(1000);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(rays.oy[i], 20.0f);
    const double len =
        std::sqrt(double(rays.dx[i]) * rays.dx[i] + double(rays.dy[i]) * rays.dy[i] + double(rays.dz[i]) * rays.dz[i]);
    EXPECT_NEAR(len, 1.0, 2e-7);
    // The target lies 30 below the origin and at most 100*sqrt(2) aside.
    EXPECT_LT(rays.dy[i], -0.2f);
  }
}

TEST(Workloads, LidarFanGeometry) {
  const RaySet rays = lidar_rays();
  ASSERT_EQ(rays.size(), std::size_t(kLidarChannels) * kLidarColumns);
  const double origin_y = -5.207117610639065 + 2;  // r2_height(50, 50) + 2, computed apart
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(rays.ox[i], 50.0f);
    ASSERT_EQ(rays.oz[i], 50.0f);
    ASSERT_NEAR(rays.oy[i], origin_y, 1e-6);
    const double len =
        std::sqrt(double(rays.dx[i]) * rays.dx[i] + double(rays.dy[i]) * rays.dy[i] + double(rays.dz[i]) * rays.dz[i]);
    ASSERT_NEAR(len, 1.0, 2e-7);
  }
  EXPECT_NEAR(rays.dy[0], -0.42261826174069944, 1e-7);  // sin(-25 deg), column 0
  EXPECT_NEAR(rays.dx[0], 0.90630778703665, 1e-7);
  EXPECT_NEAR(rays.dz[0], 0.0, 1e-7);
  EXPECT_NEAR(rays.dy[63], 0.25881904510252074, 1e-7);  // sin(15 deg)
  // Column 512 is a quarter turn: azimuth 90 degrees, towards +z.
  const std::size_t q = 512 * 64 + 63;
  EXPECT_NEAR(rays.dx[q], 0.0, 1e-7);
  EXPECT_NEAR(rays.dz[q], 0.9659258262890683, 1e-7);
}

TEST(Workloads, CameraRaysGeometry) {
  const RaySet rays = camera_rays();
  ASSERT_EQ(rays.size(), 1920u * 1080u);
  EXPECT_EQ(rays.ox[123456], 50.0f);
  EXPECT_EQ(rays.oy[123456], 30.0f);
  EXPECT_EQ(rays.oz[123456], 10.0f);
  // Top-left pixel, computed apart from the generator.
  EXPECT_NEAR(rays.dx[0], 0.6642563771396435, 1e-7);
  EXPECT_NEAR(rays.dy[0], -0.00029977222367308707, 1e-7);
  EXPECT_NEAR(rays.dz[0], 0.7475047662496406, 1e-7);
  // The four central pixels average to the forward axis, 30 degrees down.
  double m[3] = {0, 0, 0};
  for (std::size_t py : {539, 540})
    for (std::size_t px : {959, 960}) {
      const std::size_t i = py * 1920 + px;
      m[0] += rays.dx[i] / 4.0, m[1] += rays.dy[i] / 4.0, m[2] += rays.dz[i] / 4.0;
    }
  EXPECT_NEAR(m[0], 0.0, 1e-6);
  EXPECT_NEAR(m[1], -0.5, 1e-6);
  EXPECT_NEAR(m[2], std::sqrt(0.75), 1e-6);
  // Mirror symmetry about x = 50: pixel px and width-1-px differ only in the sign of dx.
  EXPECT_NEAR(rays.dx[777 * 1920 + 100], -rays.dx[777 * 1920 + 1819], 1e-7);
  EXPECT_NEAR(rays.dy[777 * 1920 + 100], rays.dy[777 * 1920 + 1819], 1e-7);
  EXPECT_GT(rays.dx[777 * 1920 + 100], 0.0f);  // +x on the image's left
}

}  // namespace
}  // namespace gyro::testing
