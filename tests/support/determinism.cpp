#include "determinism.hpp"

#include "core/state_hash.hpp"
#include "gyro/batch_raycast.hpp"
#include "math/trig_batch.hpp"
#include "workloads.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace gyro::testing {
namespace {

// Every trig function over arguments that cover reduction boundaries, the polynomial
// ranges, special values and large inputs.
uint64_t scene_trig() {
  std::vector<float> x, y;
  for (int i = -20000; i <= 20000; ++i) x.push_back(static_cast<float>(i) * 0.000314159f);  // [-6.3, 6.3]
  for (int i = -4000; i <= 4000; ++i) x.push_back(static_cast<float>(i) * 1.37f);          // large angles
  for (int i = -2000; i <= 2000; ++i) x.push_back(static_cast<float>(i) / 2000.0f);        // asin/acos domain
  const float specials[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1e-45f, 3.0e38f, -3.0e38f, __builtin_inff(),
                            -__builtin_inff(), __builtin_nanf(""), 0.5f, -0.5f, 1.0f, -1.0f, 1.0000001f,
                            0.41421356f, 2.4142137f, 1.5707964f, 3.1415927f, 12582912.0f};
  for (float s : specials) x.push_back(s);
  SplitMix64 rng(7);
  for (int i = 0; i < 20000; ++i) x.push_back(static_cast<float>((rng.u() - 0.5) * 200.0));
  y.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[(i * 7919) % x.size()];
  std::vector<float> out(x.size());
  detail::StateHasher h;
  for (uint32_t op = 0; op <= static_cast<uint32_t>(TrigOp::atan2); ++op) {
    const TrigBatchArgs args{static_cast<TrigOp>(op), x.data(), y.data(), out.data()};
    GYRO_DISPATCH(trig_batch)(args, 0, x.size());
    h.add_floats(out);
  }
  return h.digest();
}

// The first 2,000 rays of R1 against the 10,000 R1 spheres (closest hit and normals).
uint64_t scene_r1s_2k() {
  static const SphereSet spheres = r1_spheres();
  static const RaySet rays = r1_rays(2000);
  HitSet hits(rays.size());
  if (raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), hits.out()) != Status::ok)
    return 0;
  detail::StateHasher h;
  h.add_floats(hits.t);
  h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz);
  for (int32_t p : hits.primitive) h.add_u32(static_cast<uint32_t>(p));
  return h.digest();
}

// Rays that start on, inside and tangent to spheres, parallel and degenerate directions.
uint64_t scene_rays_edge_cases() {
  SphereSet s;
  const float sph[][4] = {{0, 0, 0, 1}, {3, 0, 0, 0.5f}, {0, 5, 0, 0}, {1e4f, 1e4f, 1e4f, 2}, {-2, -2, -2, 1e-3f}};
  for (auto& v : sph) s.cx.push_back(v[0]), s.cy.push_back(v[1]), s.cz.push_back(v[2]), s.r.push_back(v[3]);
  RaySet r;
  const float rays[][6] = {{-5, 0, 0, 1, 0, 0},  {0, 0, 0, 1, 0, 0},   {1, 0, 0, 1, 0, 0},  {-5, 1, 0, 1, 0, 0},
                           {0, 5, -3, 0, 0, 1}, {0, 0, 0, 0, 0, 0},   {0, 0, 0, 1e-20f, 0, 0},
                           {-5, 0, 0, 1e3f, 0, 0}, {0, 0, 0, 0.577f, 0.577f, 0.577f}, {-2, -2, -3, 0, 0, 1}};
  for (auto& v : rays) r.push(v[0], v[1], v[2], v[3], v[4], v[5]);
  HitSet hits(r.size());
  if (raycast_spheres_closest(r.view(), r.size(), s.view(), s.size(), hits.out()) != Status::ok) return 0;
  detail::StateHasher h;
  h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz);
  for (int32_t p : hits.primitive) h.add_u32(static_cast<uint32_t>(p));
  return h.digest();
}

const DetScene kScenes[] = {
    {"trig", scene_trig, 0x69125c38406c536bull},
    {"r1s_2k", scene_r1s_2k, 0xe7b85af4156f94a1ull},
    {"rays_edge_cases", scene_rays_edge_cases, 0xe8bc1c3d106c89c5ull},
};

}  // namespace

std::span<const DetScene> determinism_scenes() { return kScenes; }

std::vector<SimdLevel> available_levels() {
  std::vector<SimdLevel> out;
  for (uint32_t v = 1; v <= 5; ++v)
    if (simd_level_available(static_cast<SimdLevel>(v))) out.push_back(static_cast<SimdLevel>(v));
  return out;
}

std::vector<DetRun> run_matrix(const DetScene& scene, std::span<const uint32_t> threads) {
  const SimdLevel saved_level = simd_level();
  const uint32_t saved_threads = thread_count();
  std::vector<DetRun> runs;
  for (SimdLevel level : available_levels()) {
    set_simd_level(level);
    for (uint32_t t : threads) {
      set_thread_count(t);
      runs.push_back({level, t, scene.run()});
    }
  }
  set_simd_level(saved_level);
  set_thread_count(saved_threads);
  return runs;
}

}  // namespace gyro::testing
