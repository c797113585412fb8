// Batch ray-sphere raycasts: against the double-precision reference (R1S and random
// scenes, with hard cases), bit identity across SIMD levels and threads, and bad input.
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"
#include "reference.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace gyro {
namespace {

using namespace gyro::testing;

class RaySphere : public ::testing::Test {
 protected:
  void TearDown() override {
    set_simd_level(SimdLevel::automatic);
    set_thread_count(0);
  }
};

// BENCHMARKS.md: the first 10,000 R1 rays against the 10,000 spheres give 3,721 hits and
// sum t = 98,113.8377 in double precision (t rounded to float).
// Error model: for a ray that crosses a sphere well inside its rim, t is well conditioned
// and float should be within a few ulp of |t|; for a grazing ray (chord half-length
// s = sqrt(r^2 - d^2) small) t moves by r*dr/s when the inputs move by an ulp, so only
// about sqrt(eps) * r can be asked for. Both are measured and bounded separately.
TEST_F(RaySphere, R1SAgreesWithTheDoubleReference) {
  const SphereSet spheres = r1_spheres();
  const RaySet rays = r1_rays(10000);
  HitSet hits(rays.size());
  ASSERT_EQ(raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), hits.out()), Status::ok);
  const auto ref = ref_raycast_spheres(rays, rays.size(), spheres);
  const RaycastError e = compare_raycast(hits, ref, rays.size());
  double worst_clean = 0, worst_graze = 0;
  std::size_t grazing = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const int32_t k = hits.primitive[i];
    if (k < 0 || k != ref[i].primitive) continue;
    // Distance from the sphere centre to the ray's line, in double.
    const double ox = rays.ox[i] - spheres.cx[k], oy = rays.oy[i] - spheres.cy[k], oz = rays.oz[i] - spheres.cz[k];
    const double b = ox * rays.dx[i] + oy * rays.dy[i] + oz * rays.dz[i];
    const double d2 = ox * ox + oy * oy + oz * oz - b * b;
    const double r = spheres.r[k];
    const double half_chord = std::sqrt(std::max(0.0, r * r - d2));
    const double err = std::abs(hits.t[i] - ref[i].t);
    if (half_chord > 0.05 * r) {
      worst_clean = std::max(worst_clean, err / std::max(1.0, ref[i].t));
    } else {
      ++grazing;
      worst_graze = std::max(worst_graze, err / r);
    }
  }
  std::printf("  R1S: %zu hits (reference %zu), %zu disagreements, sum t %.4f (reference %.4f)\n"
              "       max |dt|/max(1,t) %.3g on crossing hits, max |dt|/r %.3g on %zu grazing hits\n",
              e.hits, e.ref_hits, e.disagreements, e.sum_t, e.ref_sum_t, worst_clean, worst_graze, grazing);
  EXPECT_EQ(e.ref_hits, 3721u);
  EXPECT_NEAR(e.ref_sum_t, 98113.8377, 1e-3);
  EXPECT_EQ(e.disagreements, 0u);
  EXPECT_LT(std::abs(e.sum_t - e.ref_sum_t) / e.ref_sum_t, 1e-6);
  EXPECT_LT(worst_clean, 2e-6);                    // a few ulp
  EXPECT_LT(worst_graze, 4.0 * std::sqrt(0x1p-24)); // the sqrt(eps) conditioning limit
}

// Random scenes at several scales and offsets, far from the origin included: every
// disagreement with the reference must be a near-tie or a graze (explained below).
TEST_F(RaySphere, RandomScenesAgreeUpToGrazesAndTies) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    for (double offset : {0.0, 1e4}) {
      SplitMix64 rng(uint64_t(scale * 1000 + offset));
      SphereSet s;
      for (int i = 0; i < 300; ++i) {
        s.cx.push_back(float(offset + scale * 10 * rng.u())), s.cy.push_back(float(scale * 10 * rng.u()));
        s.cz.push_back(float(scale * 10 * rng.u())), s.r.push_back(float(scale * (0.05 + rng.u())));
      }
      RaySet r;
      for (int i = 0; i < 4000; ++i) {
        const double z = 1 - 2 * rng.u(), phi = 6.283185307179586 * rng.u(), rad = std::sqrt(1 - z * z);
        r.push(float(offset + scale * 10 * rng.u()), float(scale * 10 * rng.u()), float(scale * 10 * rng.u()),
               float(rad * std::cos(phi)), float(rad * std::sin(phi)), float(z));
      }
      HitSet hits(r.size());
      ASSERT_EQ(raycast_spheres_closest(r.view(), r.size(), s.view(), s.size(), hits.out()), Status::ok);
      const auto ref = ref_raycast_spheres(r, r.size(), s);
      std::size_t unexplained = 0, disagreements = 0;
      double max_rel = 0;
      for (std::size_t i = 0; i < r.size(); ++i) {
        // Relative to the scene's size, the distance float can resolve here:
        const double tol = 1e-5 * scale * 10 + 4e-7 * offset;
        if (hits.primitive[i] == ref[i].primitive) {
          if (hits.primitive[i] >= 0) max_rel = std::max(max_rel, std::abs(hits.t[i] - ref[i].t) / (scale * 10));
          continue;
        }
        ++disagreements;
        // A disagreement is explained if the ray grazes the sphere one side picked (its
        // distance to the centre is within tol of the radius) or two candidates tie in t.
        auto grazes = [&](int32_t k) {
          if (k < 0) return false;
          const double ox = r.ox[i] - s.cx[k], oy = r.oy[i] - s.cy[k], oz = r.oz[i] - s.cz[k];
          const double b = ox * r.dx[i] + oy * r.dy[i] + oz * r.dz[i];
          const double a = double(r.dx[i]) * r.dx[i] + double(r.dy[i]) * r.dy[i] + double(r.dz[i]) * r.dz[i];
          const double px = ox - b / a * r.dx[i], py = oy - b / a * r.dy[i], pz = oz - b / a * r.dz[i];
          const double dist = std::sqrt(px * px + py * py + pz * pz);
          const double start = std::sqrt(ox * ox + oy * oy + oz * oz);
          return std::abs(dist - s.r[k]) <= tol || std::abs(start - s.r[k]) <= tol;
        };
        const bool tie = hits.primitive[i] >= 0 && ref[i].primitive >= 0 && std::abs(hits.t[i] - ref[i].t) <= tol;
        if (!(tie || grazes(hits.primitive[i]) || grazes(ref[i].primitive))) ++unexplained;
      }
      std::printf("  scale %g offset %g: %zu disagreements of %zu rays, all explained: %s, max |dt|/size %.2g\n",
                  scale, offset, disagreements, r.size(), unexplained ? "no" : "yes", max_rel);
      EXPECT_EQ(unexplained, 0u);
      EXPECT_LT(max_rel, offset > 0 ? 1e-3 : 1e-5);
    }
  }
}

TEST_F(RaySphere, HardCases) {
  // Unit sphere at the origin, one sphere of radius 0 (a point), one far away.
  const float cx[] = {0, 5, 1e6f}, cy[] = {0, 0, 50}, cz[] = {0, 0, 0}, r[] = {1, 0, 2};
  const SpheresView s{cx, cy, cz, r};
  struct Case {
    float o[3], d[3], tmin, tmax;
    int32_t prim;
    float t;
  } cases[] = {
      {{-3, 0, 0}, {1, 0, 0}, 0, INFINITY, 0, 2.0f},        // head on
      {{0, 0, 0}, {1, 0, 0}, 0, INFINITY, 0, 1.0f},         // from the centre: the exit
      {{1, 0, 0}, {1, 0, 0}, 0, INFINITY, 0, 0.0f},         // on the surface, leaving
      {{-3, 1, 0}, {1, 0, 0}, 0, INFINITY, 0, 3.0f},        // tangent
      {{-3, 1.0001f, 0}, {1, 0, 0}, 0, INFINITY, -1, INFINITY},  // just misses (point sphere at y=0)
      {{-3, 0, 0}, {2, 0, 0}, 0, INFINITY, 0, 1.0f},        // unnormalised d: t in units of |d|
      {{-3, 0, 0}, {1, 0, 0}, 2.5f, INFINITY, 0, 4.0f},     // tmin past the entry: the exit
      {{-3, 0, 0}, {1, 0, 0}, 0, 1.5f, -1, INFINITY},       // tmax before the entry
      {{-3, 0, 0}, {1, 0, 0}, 0, 2.0f, 0, 2.0f},            // tmax exactly at the entry
      {{-3, 0, 0}, {0, 0, 0}, 0, INFINITY, -1, INFINITY},   // zero direction never hits
      {{-3, 0, 0}, {1e-25f, 0, 0}, 0, INFINITY, -1, INFINITY},  // subnormal |d|^2
      {{3, 0, 0}, {1, 0, 0}, 0, INFINITY, 1, 2.0f},         // the point sphere, dead on
      {{1e6f - 10, 50, 0}, {1, 0, 0}, 0, INFINITY, 2, 8.0f}, // far from the origin
      {{0, 3, 0}, {0, 1, 0}, 0, INFINITY, -1, INFINITY},    // pointing away
  };
  for (const Case& c : cases) {
    float t = -1, nx = 9, ny = 9, nz = 9;
    int32_t prim = -7;
    const RaysView rays{&c.o[0], &c.o[1], &c.o[2], &c.d[0], &c.d[1], &c.d[2], &c.tmin, &c.tmax};
    ASSERT_EQ(raycast_spheres_closest(rays, 1, s, 3, {&t, &prim, &nx, &ny, &nz}), Status::ok);
    EXPECT_EQ(prim, c.prim) << "origin " << c.o[0] << "," << c.o[1] << " dir " << c.d[0];
    if (c.prim >= 0) {
      EXPECT_NEAR(t, c.t, 1e-5f * std::max(1.0f, c.t));
      EXPECT_NEAR(std::sqrt(nx * nx + ny * ny + nz * nz), 1.0f, 1e-6f);
    } else {
      EXPECT_EQ(t, INFINITY);
      EXPECT_EQ(nx, 0.0f);
    }
  }
}

TEST_F(RaySphere, TiesGoToTheLowestIndex) {
  const float cx[] = {0, 0, 0}, cy[] = {0, 0, 0}, cz[] = {0, 0, 0}, r[] = {1, 1, 1};
  const float o[] = {-5, 0, 0}, d[] = {1, 0, 0};
  float t;
  int32_t prim;
  ASSERT_EQ(raycast_spheres_closest({&o[0], &o[1], &o[2], &d[0], &d[1], &d[2]}, 1, {cx, cy, cz, r}, 3,
                                    {&t, &prim, nullptr, nullptr, nullptr}),
            Status::ok);
  EXPECT_EQ(prim, 0);
}

TEST_F(RaySphere, BitIdenticalAcrossLevelsThreadsAndBatchSplits) {
  const SphereSet spheres = r1_spheres(2000);
  const RaySet rays = r1_rays(3001);  // not a multiple of any lane count
  HitSet ref(rays.size());
  set_simd_level(SimdLevel::scalar);
  set_thread_count(1);
  ASSERT_EQ(raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), ref.out()), Status::ok);
  for (uint32_t v = 2; v <= 5; ++v) {
    if (!simd_level_available(SimdLevel(v))) continue;
    set_simd_level(SimdLevel(v));
    for (uint32_t threads : {1u, 2u, 3u, 8u}) {
      set_thread_count(threads);
      HitSet h(rays.size());
      ASSERT_EQ(raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), h.out()), Status::ok);
      EXPECT_EQ(std::memcmp(h.t.data(), ref.t.data(), h.t.size() * 4), 0) << simd_level_name(SimdLevel(v)) << threads;
      EXPECT_EQ(h.primitive, ref.primitive);
      EXPECT_EQ(std::memcmp(h.nx.data(), ref.nx.data(), h.nx.size() * 4), 0);
    }
  }
  // One ray at a time (scalar tail only) gives the same bits as the whole batch.
  set_simd_level(SimdLevel::automatic);
  for (std::size_t i = 0; i < 50; ++i) {
    const std::size_t k = (i * 61) % rays.size();
    RaysView one = rays.view();
    one.ox += k, one.oy += k, one.oz += k, one.dx += k, one.dy += k, one.dz += k;
    float t;
    int32_t prim;
    ASSERT_EQ(raycast_spheres_closest(one, 1, spheres.view(), spheres.size(), {&t, &prim, nullptr, nullptr, nullptr}),
              Status::ok);
    EXPECT_EQ(std::bit_cast<uint32_t>(t), std::bit_cast<uint32_t>(ref.t[k]));
    EXPECT_EQ(prim, ref.primitive[k]);
  }
}

TEST_F(RaySphere, BadInputGetsAStatusAndWritesNothing) {
  const SphereSet spheres = r1_spheres(10);
  RaySet rays = r1_rays(40);
  auto untouched = [](const HitSet& h) {
    for (std::size_t i = 0; i < h.t.size(); ++i)
      if (std::bit_cast<uint32_t>(h.t[i]) != 0x7fc0deadu || h.primitive[i] != 12345) return false;
    return true;
  };
  auto poisoned = [&] {
    HitSet h(rays.size());
    for (auto& t : h.t) t = std::bit_cast<float>(0x7fc0deadu);
    for (auto& p : h.primitive) p = 12345;
    return h;
  };
  auto run = [&](const RaysView& r, std::size_t n, const SpheresView& s, std::size_t m, HitsOut out) {
    return raycast_spheres_closest(r, n, s, m, out);
  };
  {
    HitSet h = poisoned();
    RaysView r = rays.view();
    r.dy = nullptr;
    EXPECT_EQ(run(r, rays.size(), spheres.view(), spheres.size(), h.out()), Status::null_argument);
    EXPECT_TRUE(untouched(h));
    EXPECT_NE(std::strstr(last_error(), "rays.dy"), nullptr) << last_error();
  }
  {
    HitSet h = poisoned();
    rays.oz[17] = NAN;
    EXPECT_EQ(run(rays.view(), rays.size(), spheres.view(), spheres.size(), h.out()), Status::non_finite);
    EXPECT_NE(std::strstr(last_error(), "rays.oz[17]"), nullptr) << last_error();
    EXPECT_TRUE(untouched(h));
    rays.oz[17] = INFINITY;
    EXPECT_EQ(run(rays.view(), rays.size(), spheres.view(), spheres.size(), h.out()), Status::non_finite);
    rays.oz[17] = 1.0f;
  }
  {
    HitSet h = poisoned();
    SphereSet bad = spheres;
    bad.r[3] = -1.0f;
    EXPECT_EQ(run(rays.view(), rays.size(), bad.view(), bad.size(), h.out()), Status::invalid_argument);
    bad.r[3] = NAN;
    EXPECT_EQ(run(rays.view(), rays.size(), bad.view(), bad.size(), h.out()), Status::non_finite);
    EXPECT_TRUE(untouched(h));
  }
  {
    HitSet h = poisoned();
    std::vector<float> tmin(rays.size(), 0.0f), tmax(rays.size(), INFINITY);
    RaysView r = rays.view();
    r.tmin = tmin.data(), r.tmax = tmax.data();
    tmax[5] = NAN;
    EXPECT_EQ(run(r, rays.size(), spheres.view(), spheres.size(), h.out()), Status::invalid_argument);
    tmax[5] = 1.0f, tmin[6] = -1.0f;
    EXPECT_EQ(run(r, rays.size(), spheres.view(), spheres.size(), h.out()), Status::invalid_argument);
    EXPECT_TRUE(untouched(h));
  }
  {
    HitSet h = poisoned();
    HitsOut out = h.out();
    out.ny = nullptr;  // normals: all three or none
    EXPECT_EQ(run(rays.view(), rays.size(), spheres.view(), spheres.size(), out), Status::null_argument);
    out = h.out();
    out.t = nullptr;
    EXPECT_EQ(run(rays.view(), rays.size(), spheres.view(), spheres.size(), out), Status::null_argument);
    EXPECT_EQ(run(rays.view(), std::size_t(1) << 31, spheres.view(), spheres.size(), h.out()), Status::invalid_count);
    EXPECT_TRUE(untouched(h));
  }
  {
    // No spheres: every ray misses; no rays: nothing to do.
    HitSet h = poisoned();
    EXPECT_EQ(run(rays.view(), rays.size(), SpheresView{}, 0, h.out()), Status::ok);
    for (std::size_t i = 0; i < h.t.size(); ++i) EXPECT_EQ(h.primitive[i], -1);
    EXPECT_EQ(run(RaysView{}, 0, SpheresView{}, 0, HitsOut{}), Status::ok);
  }
}

}  // namespace
}  // namespace gyro
