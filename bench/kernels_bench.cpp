// Google Benchmark micro-benchmarks of the kernels, per SIMD level. Each reports an error
// counter beside its speed: trig functions their max ulp against long double on the
// benchmark's own inputs, the ray kernel its disagreements with the binary64 reference.
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"
#include "math/trig_batch.hpp"
#include "reference.hpp"
#include "workloads.hpp"

#include <benchmark/benchmark.h>

#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

namespace {
using namespace gyro;
using namespace gyro::testing;

double ulp_error(float got, long double ref) {
  const float rf = static_cast<float>(ref);
  const double ulp = std::fabs(rf) >= FLT_MIN ? std::ldexp(1.0, std::ilogb(rf) - 23) : std::ldexp(1.0, -149);
  return double(std::fabs(static_cast<long double>(got) - ref) / ulp);
}

void bm_trig(benchmark::State& state, SimdLevel level, TrigOp op) {
  const std::size_t n = 1 << 16;
  std::vector<float> x(n), y(n), out(n);
  SplitMix64 rng(5);
  const bool unit = op == TrigOp::asin || op == TrigOp::acos;
  for (std::size_t i = 0; i < n; ++i) x[i] = float(unit ? rng.u() * 2 - 1 : (rng.u() - 0.5) * 20), y[i] = float(rng.u() - 0.5);
  const TrigBatchArgs args{op, x.data(), y.data(), out.data()};
  auto* kernel = detail::trig_batch_for(level);
  for (auto _ : state) {
    kernel(args, 0, n);
    benchmark::DoNotOptimize(out.data());
  }
  double max_ulp = 0;
  for (std::size_t i = 0; i < n; ++i) {
    long double r;
    switch (op) {
      case TrigOp::sin: r = sinl(x[i]); break;
      case TrigOp::cos: r = cosl(x[i]); break;
      case TrigOp::tan: r = tanl(x[i]); break;
      case TrigOp::asin: r = asinl(x[i]); break;
      case TrigOp::acos: r = acosl(x[i]); break;
      case TrigOp::atan: r = atanl(x[i]); break;
      default: r = atan2l(y[i], x[i]); break;
    }
    max_ulp = std::max(max_ulp, ulp_error(out[i], r));
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
  state.counters["max_ulp"] = max_ulp;
}

void bm_ray_sphere(benchmark::State& state, SimdLevel level) {
  static const SphereSet spheres = r1_spheres(2000);
  static const RaySet rays = r1_rays(2048);
  static const auto ref = ref_raycast_spheres(rays, rays.size(), spheres);
  set_simd_level(level);
  set_thread_count(1);
  HitSet hits(rays.size());
  for (auto _ : state) {
    raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), hits.out(false));
    benchmark::DoNotOptimize(hits.t.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays.size() * spheres.size()));
  state.counters["disagreements"] = double(compare_raycast(hits, ref, rays.size()).disagreements);
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

const char* kOpNames[] = {"sin", "cos", "tan", "asin", "acos", "atan", "atan2"};

int register_all() {
  for (uint32_t v = 1; v <= 5; ++v) {
    const SimdLevel level = SimdLevel(v);
    if (!simd_level_available(level)) continue;
    const std::string lv = simd_level_name(level);
    for (uint32_t op = 0; op <= uint32_t(TrigOp::atan2); ++op)
      benchmark::RegisterBenchmark(("trig/" + std::string(kOpNames[op]) + "/" + lv).c_str(), bm_trig, level, TrigOp(op));
    benchmark::RegisterBenchmark(("ray_sphere_tests/" + lv).c_str(), bm_ray_sphere, level);
  }
  return 0;
}
const int registered = register_all();
}  // namespace

BENCHMARK_MAIN();
