// R1S (BENCHMARKS.md): the first 10,000 rays of R1 against all 10,000 R1 spheres, closest
// hit, brute force. Per SIMD level x thread count: median time, rays/s, the speed-up over
// the scalar level at the same thread count, the checksum (sum of t over hits, in ray
// order, in binary64) and the error against the double-precision reference.
#include "gyro/batch_raycast.hpp"
#include "reference.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include "core/state_hash.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace gyro::bench {

void run_r1s(const Options& o) {
  using namespace gyro::testing;
  const SphereSet spheres = r1_spheres();
  const RaySet rays = r1_rays(10000);
  const auto ref = ref_raycast_spheres(rays, rays.size(), spheres);
  std::printf("# R1S: %zu rays x %zu spheres (brute force), reference: binary64 quadratic\n", rays.size(),
              spheres.size());
  std::map<uint32_t, double> scalar_ms;  // by thread count
  for (SimdLevel level : levels_to_run(o)) {
    set_simd_level(level);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      HitSet hits(rays.size());
      auto cast = [&] {
        raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), hits.out(false));
      };
      const double ms = median_ms(o.reps, cast);
      const RaycastError e = compare_raycast(hits, ref, rays.size());
      detail::StateHasher h;
      h.add_floats(hits.t);
      for (int32_t p : hits.primitive) h.add_u32(uint32_t(p));
      if (level == SimdLevel::scalar) scalar_ms[threads] = ms;
      JsonLine line;
      line.str("workload", "R1S").str("library", "gyro").str("method", "closest_hit_brute_force")
          .str("simd", simd_level_name(level)).integer("threads", threads).num("build_ms", 0.0)
          .num("time_ms", ms, 5).num("throughput", double(rays.size()) / ms / 1e3, 5).str("unit", "Mrays/s")
          .integer("hits", int64_t(e.hits)).num("checksum", e.sum_t, 12)
          .num("error", double(e.disagreements)).str("error_metric", "rays disagreeing with binary64 (hit, sphere)")
          .num("max_rel_dt", e.max_rel_t, 3).num("ref_checksum", e.ref_sum_t, 12).hex("result_hash", h.digest())
          .integer("reps", o.reps);
      if (scalar_ms.count(threads)) line.num("ratio_vs_scalar", scalar_ms[threads] / ms, 4);
      line.print();
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
  if (o.peers) std::printf("# R1S is brute force by definition: peers run R1 with their BVHs (issue: spatial)\n");
}

}  // namespace gyro::bench
