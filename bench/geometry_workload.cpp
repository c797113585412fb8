// G1: the geometry batch kernels one by one, per SIMD level (1 thread): pairwise overlap
// tests on 10^6 random pairs and brute-force raycasts of 4,096 rays against 1,024
// primitives. Each line gives elements/s, the speed-up over the scalar level, and its error
// against a binary64 reference: verdicts that differ outside a 1e-5 band around touching
// (must be 0) and inside it, or for raycasts the rays whose hit primitive differs and the
// max |dt| on the others.
#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"
#include "reference.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <cmath>
#include <functional>
#include <string>

namespace gyro::bench {
namespace {

using testing::D3;
using testing::SplitMix64;

// SoA storage for up to 15 columns, with the typed views the batch calls take.
struct Columns {
  std::vector<float> c[15];
  explicit Columns(std::size_t n) {
    for (auto& v : c) v.resize(n);
  }
  SpheresView spheres() const { return {c[0].data(), c[1].data(), c[2].data(), c[3].data()}; }
  AabbsView aabbs() const { return {c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(), c[5].data()}; }
  TrianglesView triangles() const {
    return {c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(), c[5].data(), c[6].data(), c[7].data(), c[8].data()};
  }
  D3 d(int k, std::size_t i) const { return {c[k][i], c[k + 1][i], c[k + 2][i]}; }
};

void fill_spheres(Columns& s, SplitMix64& rng, double box) {
  for (std::size_t i = 0; i < s.c[0].size(); ++i) {
    for (int k = 0; k < 3; ++k) s.c[k][i] = float(box * rng.u());
    s.c[3][i] = float(0.1 + 0.9 * rng.u());
  }
}
void fill_aabbs(Columns& s, SplitMix64& rng, double box) {
  for (std::size_t i = 0; i < s.c[0].size(); ++i) {
    for (int k = 0; k < 3; ++k) s.c[k][i] = float(box * rng.u());
    for (int k = 3; k < 6; ++k) s.c[k][i] = float(0.1 + 0.9 * rng.u());
  }
}
void fill_triangles(Columns& s, SplitMix64& rng, double box) {
  for (std::size_t i = 0; i < s.c[0].size(); ++i) {
    double c[3];
    for (double& v : c) v = box * rng.u();
    for (int k = 0; k < 9; ++k) s.c[k][i] = float(c[k % 3] + 2.0 * (rng.u() - 0.5));
  }
}

struct Level {
  SimdLevel level;
  double ms;
};

void overlap_line(const char* method, std::size_t n, double ms, double scalar_ms, std::size_t hits, std::size_t outside,
                  std::size_t inside, int reps, SimdLevel level) {
  JsonLine line;
  line.str("workload", "G1").str("library", "gyro").str("method", method).str("simd", simd_level_name(level))
      .integer("threads", 1).num("build_ms", 0).num("time_ms", ms, 5).num("throughput", double(n) / ms / 1e3, 5)
      .str("unit", "Mpairs/s").integer("hits", int64_t(hits)).num("checksum", 0)
      .num("error", double(outside)).str("error_metric", "verdicts differing from binary64 farther than 1e-5 from touching")
      .integer("differ_within_1e-5", int64_t(inside)).num("ratio_vs_scalar", scalar_ms / ms, 4).integer("reps", reps)
      .print();
}

// Runs a pairwise overlap benchmark; gap(i) is the binary64 signed gap of pair i.
void bench_overlap(const Options& o, const char* method, const ShapeArray& a, const ShapeArray& b, std::size_t n,
                   const std::function<double(std::size_t)>& gap) {
  std::vector<uint32_t> out(n);
  std::vector<double> ref(n);
  for (std::size_t i = 0; i < n; ++i) ref[i] = gap(i);
  double scalar_ms = 0;
  for (SimdLevel level : levels_to_run(o)) {
    set_simd_level(level);
    const double ms = median_ms(o.reps, [&] { overlap_pairwise(a, b, n, out.data()); });
    if (level == SimdLevel::scalar) scalar_ms = ms;
    std::size_t hits = 0, outside = 0, inside = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool hit = out[i] == kOverlapping;
      hits += hit;
      if (hit != (ref[i] <= 0)) (std::abs(ref[i]) <= 1e-5 ? inside : outside)++;
    }
    overlap_line(method, n, ms, scalar_ms ? scalar_ms : ms, hits, outside, inside, o.reps, level);
  }
}

// Brute-force raycasts: ref_t(i, k) is the binary64 t of ray i against primitive k (inf: miss).
void bench_raycast(const Options& o, const char* method, const testing::RaySet& rays, const ShapeArray& prims,
                   std::size_t m, const std::function<double(std::size_t, std::size_t)>& ref_t) {
  const std::size_t n = rays.size();
  std::vector<int32_t> ref_k(n, -1);
  std::vector<double> ref_best(n, INFINITY);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < m; ++k) {
      const double t = ref_t(i, k);
      if (t < ref_best[i]) ref_best[i] = t, ref_k[i] = int32_t(k);
    }
  testing::HitSet hits(n);
  double scalar_ms = 0;
  for (SimdLevel level : levels_to_run(o)) {
    set_simd_level(level);
    const double ms = median_ms(o.reps, [&] { raycast_closest(rays.view(), n, prims, m, hits.out(false)); });
    if (level == SimdLevel::scalar) scalar_ms = ms;
    std::size_t nhits = 0, differ = 0;
    double max_dt = 0, sum_t = 0;
    for (std::size_t i = 0; i < n; ++i) {
      nhits += hits.primitive[i] >= 0;
      if (hits.primitive[i] >= 0) sum_t += hits.t[i];
      if (hits.primitive[i] != ref_k[i]) ++differ;
      else if (ref_k[i] >= 0) max_dt = std::max(max_dt, std::abs(hits.t[i] - ref_best[i]) / std::max(1.0, ref_best[i]));
    }
    JsonLine line;
    line.str("workload", "G1").str("library", "gyro").str("method", method).str("simd", simd_level_name(level))
        .integer("threads", 1).num("build_ms", 0).num("time_ms", ms, 5)
        .num("throughput", double(n) / ms / 1e3, 5).str("unit", "Mrays/s")
        .num("tests_per_s", double(n) * double(m) / ms / 1e3, 5).integer("hits", int64_t(nhits)).num("checksum", sum_t, 10)
        .num("error", double(differ)).str("error_metric", "rays whose hit primitive differs from binary64")
        .num("max_rel_dt", max_dt, 3).num("ratio_vs_scalar", (scalar_ms ? scalar_ms : ms) / ms, 4).integer("reps", o.reps)
        .print();
  }
}

}  // namespace

void run_g1(const Options& o) {
  const std::size_t n = 1000000;
  SplitMix64 rng(41);
  std::printf("# G1: pairwise overlap kernels on %zu random pairs (10 m box), raycasts 4096 rays x 1024 primitives\n", n);
  set_thread_count(1);
  {
    Columns a(n), b(n);
    fill_spheres(a, rng, 10), fill_spheres(b, rng, 10);
    bench_overlap(o, "overlap_sphere_sphere", shape_array(a.spheres()), shape_array(b.spheres()), n, [&](std::size_t i) {
      return testing::ref_sphere_sphere_gap(a.d(0, i), a.c[3][i], b.d(0, i), b.c[3][i]);
    });
  }
  {
    Columns a(n), b(n);
    fill_spheres(a, rng, 10), fill_aabbs(b, rng, 10);
    bench_overlap(o, "overlap_sphere_aabb", shape_array(a.spheres()), shape_array(b.aabbs()), n, [&](std::size_t i) {
      return testing::ref_sphere_aabb_gap(a.d(0, i), a.c[3][i], b.d(0, i), b.d(3, i));
    });
  }
  {
    Columns a(n), b(n);
    fill_aabbs(a, rng, 10), fill_aabbs(b, rng, 10);
    bench_overlap(o, "overlap_aabb_aabb", shape_array(a.aabbs()), shape_array(b.aabbs()), n, [&](std::size_t i) {
      return testing::ref_aabb_aabb_gap(a.d(0, i), a.d(3, i), b.d(0, i), b.d(3, i));
    });
  }
  const testing::RaySet rays = testing::r1_rays(4096);  // origins in a 100 m cube, isotropic
  const std::size_t m = 1024;
  {
    Columns s(m);
    fill_spheres(s, rng, 100);
    bench_raycast(o, "raycast_spheres", rays, shape_array(s.spheres()), m, [&](std::size_t i, std::size_t k) {
      return testing::ref_ray_spheres(rays.ox[i], rays.oy[i], rays.oz[i], rays.dx[i], rays.dy[i], rays.dz[i], 0.0,
                                      INFINITY, testing::SphereSet{{s.c[0][k]}, {s.c[1][k]}, {s.c[2][k]}, {s.c[3][k]}})
          .t;
    });
  }
  {
    Columns s(m);
    fill_aabbs(s, rng, 100);
    bench_raycast(o, "raycast_aabbs", rays, shape_array(s.aabbs()), m, [&](std::size_t i, std::size_t k) {
      return testing::ref_ray_aabb_t(testing::d3(rays.ox[i], rays.oy[i], rays.oz[i]),
                                     testing::d3(rays.dx[i], rays.dy[i], rays.dz[i]), s.d(0, k), s.d(3, k));
    });
  }
  {
    Columns s(m);
    fill_triangles(s, rng, 100);
    bench_raycast(o, "raycast_triangles", rays, shape_array(s.triangles()), m, [&](std::size_t i, std::size_t k) {
      return testing::ref_ray_triangle_t(testing::d3(rays.ox[i], rays.oy[i], rays.oz[i]),
                                         testing::d3(rays.dx[i], rays.dy[i], rays.dz[i]), s.d(0, k), s.d(3, k), s.d(6, k));
    });
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

}  // namespace gyro::bench
