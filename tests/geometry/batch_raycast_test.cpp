// Batch raycasts against every primitive type tie to the scalar API: closest hit = the
// nearest scalar raycast() hit (same t bits, same normal bits, lowest index on ties), any
// hit = the lowest-index scalar hit, at every SIMD level and thread count.
#include "gyro/batch_raycast.hpp"
#include "gyro/raycast.hpp"
#include "gyro/runtime.hpp"
#include "gyro/triangle.hpp"
#include "random_shapes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

namespace gyro {
namespace {

using namespace gyro::testing;

RaycastResult scalar_raycast(const RandomShapes& s, std::size_t k, const Ray& ray) {
  switch (s.type) {
    case ShapeType::sphere: return raycast(s.spheres[k], ray);
    case ShapeType::aabb: return raycast(s.aabbs[k], ray);
    case ShapeType::obb: return raycast(s.obbs[k], ray);
    case ShapeType::plane: return raycast(s.planes[k], ray);
    case ShapeType::triangle: return raycast(s.triangles[k], ray);
  }
  return {};
}

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

TEST(BatchRaycast, ClosestAndAnyHitEqualTheScalarApiForEveryType) {
  SplitMix64 rng(2024);
  const std::size_t nrays = 777, nprims = 97;
  RaySet rays;
  for (std::size_t i = 0; i < nrays; ++i)
    rays.push(float(6 * rng.u() - 1), float(6 * rng.u() - 1), float(6 * rng.u() - 1), float(rng.u() - 0.5),
              float(rng.u() - 0.5), float(rng.u() - 0.5));
  for (uint32_t type = 1; type <= 5; ++type) {
    const RandomShapes prims = random_shapes(ShapeType(type), nprims, rng);
    std::vector<int32_t> want_closest(nrays, -1), want_any(nrays, -1);
    std::vector<RaycastResult> best(nrays);
    std::vector<float> any_t(nrays, INFINITY);
    for (std::size_t i = 0; i < nrays; ++i) {
      const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
      for (std::size_t k = 0; k < nprims; ++k) {
        const RaycastResult r = scalar_raycast(prims, k, ray);
        if (!r.hit) continue;
        if (want_any[i] < 0) want_any[i] = int32_t(k), any_t[i] = r.t;
        if (want_closest[i] < 0 || r.t < best[i].t) want_closest[i] = int32_t(k), best[i] = r;
      }
    }
    std::size_t hits = 0;
    for (int32_t k : want_closest) hits += k >= 0;
    EXPECT_GT(hits, nrays / 20) << "type " << type << ": too few hits to be a test";
    for (uint32_t v = 1; v <= 5; ++v) {
      if (!simd_level_available(SimdLevel(v))) continue;
      set_simd_level(SimdLevel(v));
      for (uint32_t threads : {1u, 3u}) {
        set_thread_count(threads);
        HitSet h(nrays);
        ASSERT_EQ(raycast_closest(rays.view(), nrays, prims.view(), nprims, h.out()), Status::ok);
        for (std::size_t i = 0; i < nrays; ++i) {
          ASSERT_EQ(h.primitive[i], want_closest[i]) << "type " << type << " ray " << i << " " << simd_level_name(SimdLevel(v));
          if (want_closest[i] < 0) continue;
          EXPECT_EQ(bits(h.t[i]), bits(best[i].t)) << "type " << type << " ray " << i;
          EXPECT_EQ(bits(h.nx[i]), bits(best[i].normal.x)) << "type " << type << " ray " << i;
          EXPECT_EQ(bits(h.ny[i]), bits(best[i].normal.y));
          EXPECT_EQ(bits(h.nz[i]), bits(best[i].normal.z));
        }
        ASSERT_EQ(raycast_any(rays.view(), nrays, prims.view(), nprims, h.out(false)), Status::ok);
        for (std::size_t i = 0; i < nrays; ++i) {
          ASSERT_EQ(h.primitive[i], want_any[i]) << "any-hit, type " << type << " ray " << i;
          if (want_any[i] >= 0) {
            EXPECT_EQ(bits(h.t[i]), bits(any_t[i]));
          }
        }
      }
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

}  // namespace
}  // namespace gyro
