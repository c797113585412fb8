// Ray workloads with acceleration structures (BENCHMARKS.md R1 and R2, and gyro's own LIDAR
// and CAMERA over the R2 terrain): gyro against Embree 3 and Bullet on identical rays.
//
// Every line reports, over the rays it traced: hits (t in [0, tmax]), the checksum (sum of
// the float t over hits, in ray order, in binary64) and its error against a binary64
// reference:
//  - R1: the brute-force quadratic of tests/support/reference.hpp on the first 20,000 rays
//    (BENCHMARKS.md's surface semantics: a ray starting inside a sphere reports its exit);
//  - R2, LIDAR, CAMERA: a binary64 walk over the terrain's grid of cells (below), testing
//    every triangle of every cell the ray can cross, so it needs no BVH to trust.
// A ray disagrees when its hit/miss verdict differs from the reference, or its t differs by
// more than 1e-3 max(1, t_ref) (a leak through the surface hits something farther away);
// max_abs_dt is the largest |t - t_ref| over the agreeing hits. R1 and R2 also run any hit
// (occlusion, line of sight: gyro's raycast_any against Embree's rtcOccluded1/16), scored on
// the verdict alone, with the hit count as the checksum.
//
// gyro runs per thread count at its best SIMD level, or at each level --simd names (R1:
// every ray through a scene of 10,000 sphere models under its BVH, the line peers are
// compared with, and brute force on the reference subsample). Peers run per
// thread count; Bullet on one thread only, on a subsample of 100,000 rays (every k-th ray
// of the coherent LIDAR/CAMERA sets) or GYRO_BENCH_BULLET_RAYS, said in "rays". ratio_vs on
// a peer line = its throughput / gyro's (gyro's best level, same thread count): below 1,
// gyro is faster. A comment line before a line with errors names its first wrong rays.
#include "gyro/batch_raycast.hpp"
#include "gyro/scene.hpp"
#include "gyro/triangle_mesh.hpp"
#include "peers.hpp"
#include "reference.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>

namespace gyro::bench {
namespace {

using testing::RaySet;

constexpr std::size_t kR1ReferenceRays = 20000;  // R1's binary64 brute force, and gyro's
constexpr double kInf = std::numeric_limits<double>::infinity();

// Bullet traces at most this many rays (it is slow); GYRO_BENCH_BULLET_RAYS overrides it.
std::size_t bullet_rays() {
  const char* v = std::getenv("GYRO_BENCH_BULLET_RAYS");
  const long long n = v ? std::atoll(v) : 0;
  return n > 0 ? std::size_t(n) : 100000;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// One workload's rays, query range and binary64 reference (for rays [0, ref.size())).
struct RayCase {
  const char* workload = "";
  RaySet rays;
  float tmax = testing::kRayTmax;
  std::vector<double> ref;  // closest t, +inf on a miss
  bool ordered = false;     // rays are spatially coherent: subsample with a stride
  bool any_hit = false;     // also any-hit lines
};

/// Every stride-th ray (and its reference where there is one), count rays at most.
RayCase subsample(const RayCase& c, std::size_t count) {
  const std::size_t n = c.rays.size();
  if (n <= count) return c;
  const std::size_t stride = c.ordered ? (n + count - 1) / count : 1;
  RayCase s;
  s.workload = c.workload, s.tmax = c.tmax, s.ordered = c.ordered, s.any_hit = c.any_hit;
  for (std::size_t i = 0, k = 0; i < n && k < count; i += stride, ++k) {
    s.rays.push(c.rays.ox[i], c.rays.oy[i], c.rays.oz[i], c.rays.dx[i], c.rays.dy[i], c.rays.dz[i]);
    if (i < c.ref.size()) s.ref.push_back(c.ref[i]);
  }
  return s;
}

// ---------------------------------------------------------------- the terrain reference

/// Closest hit on the R2 terrain in binary64. The ray is clipped to the terrain's box, then
/// the columns of cells (x between grid lines i and i + 1) it crosses are visited in ray
/// order; in each column every cell whose z range the ray spans (plus one cell each side,
/// and a margin in x, to cover the float vertices' rounding) has both triangles tested with
/// the double-sided binary64 Moller-Trumbore test, unless the ray's height over the cell
/// misses the cell's height range. The walk stops at the first column that starts beyond
/// the best hit. Relies on r2_mesh()'s layout: cell (i, j) holds triangles 2(511 j + i) + {0, 1}.
class TerrainReference {
 public:
  explicit TerrainReference(const MeshData& mesh) : mesh_(mesh) {
    ymin_ = *std::min_element(mesh.y.begin(), mesh.y.end());
    ymax_ = *std::max_element(mesh.y.begin(), mesh.y.end());
    cell_lo_.resize(std::size_t(kCells) * kCells), cell_hi_.resize(cell_lo_.size());
    for (std::size_t c = 0; c < cell_lo_.size(); ++c) {
      float lo = mesh.y[mesh.indices[6 * c]], hi = lo;
      for (std::size_t k = 6 * c; k < 6 * c + 6; ++k)
        lo = std::min(lo, mesh.y[mesh.indices[k]]), hi = std::max(hi, mesh.y[mesh.indices[k]]);
      cell_lo_[c] = lo, cell_hi_[c] = hi;
    }
  }

  double closest(const RaySet& r, std::size_t i, double tmax) const {
    const double o[3] = {r.ox[i], r.oy[i], r.oz[i]}, d[3] = {r.dx[i], r.dy[i], r.dz[i]};
    const double lo[3] = {-kMargin, ymin_ - kMargin, -kMargin},
                 hi[3] = {kSize + kMargin, ymax_ + kMargin, kSize + kMargin};
    double ta = 0, tb = tmax;
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0) {
        if (o[k] < lo[k] || o[k] > hi[k]) return kInf;
        continue;
      }
      double t0 = (lo[k] - o[k]) / d[k], t1 = (hi[k] - o[k]) / d[k];
      if (t0 > t1) std::swap(t0, t1);
      ta = std::max(ta, t0), tb = std::min(tb, t1);
    }
    if (ta > tb) return kInf;
    const int ia = cell_of(o[0] + ta * d[0]), ib = cell_of(o[0] + tb * d[0]);
    const int step = d[0] >= 0 ? 1 : -1;
    const int first = std::clamp((step > 0 ? std::min(ia, ib) : std::max(ia, ib)) - step, 0, kCells - 1);
    const int last = std::clamp((step > 0 ? std::max(ia, ib) : std::min(ia, ib)) + step, 0, kCells - 1);
    double best = kInf;
    for (int ci = first;; ci += step) {
      double c0 = ta, c1 = tb;
      if (d[0] != 0) {
        double t0 = (kSize * ci / kCells - kMargin - o[0]) / d[0],
               t1 = (kSize * (ci + 1) / kCells + kMargin - o[0]) / d[0];
        if (t0 > t1) std::swap(t0, t1);
        c0 = std::max(c0, t0), c1 = std::min(c1, t1);
      }
      if (c0 > best) break;
      if (c0 <= c1) {
        const double za = o[2] + c0 * d[2], zb = o[2] + c1 * d[2];
        const int j0 = std::max(0, cell_of(std::min(za, zb)) - 1),
                  j1 = std::min(kCells - 1, cell_of(std::max(za, zb)) + 1);
        for (int cj = j0; cj <= j1; ++cj) {
          // Skip a cell when the ray's height over its rectangle misses the cell's heights
          // (its triangles lie within them); the margins dwarf the rounding of t and y.
          double r0 = c0, r1 = c1;
          if (d[2] != 0) {
            double t0 = (kSize * cj / kCells - kMargin - o[2]) / d[2],
                   t1 = (kSize * (cj + 1) / kCells + kMargin - o[2]) / d[2];
            if (t0 > t1) std::swap(t0, t1);
            r0 = std::max(r0, t0), r1 = std::min(r1, t1);
          }
          if (r0 > r1) continue;
          const double ya = o[1] + r0 * d[1], yb = o[1] + r1 * d[1];
          const std::size_t cell = std::size_t(cj) * kCells + std::size_t(ci);
          if (std::max(ya, yb) < double(cell_lo_[cell]) - 1e-6 || std::min(ya, yb) > double(cell_hi_[cell]) + 1e-6)
            continue;
          for (std::size_t tri = 2 * (std::size_t(cj) * kCells + std::size_t(ci)), e = tri + 2; tri < e; ++tri) {
            const double t = triangle_t(tri, o, d);
            if (t <= tmax && t < best) best = t;
          }
        }
      }
      if (ci == last) break;
    }
    return best;
  }

 private:
  static constexpr int kCells = 511;
  static constexpr double kSize = 100.0, kMargin = 1e-4;
  static int cell_of(double x) { return int(std::floor(x * (kCells / kSize))); }

  double triangle_t(std::size_t tri, const double o[3], const double d[3]) const {
    const uint32_t* v = &mesh_.indices[3 * tri];
    auto at = [&](uint32_t k) { return testing::d3(mesh_.x[k], mesh_.y[k], mesh_.z[k]); };
    return testing::ref_ray_triangle_t({o[0], o[1], o[2]}, {d[0], d[1], d[2]}, at(v[0]), at(v[1]), at(v[2]));
  }

  const MeshData& mesh_;
  double ymin_ = 0, ymax_ = 0;
  std::vector<float> cell_lo_, cell_hi_;  // height range of cell j*511 + i (both triangles)
};

std::vector<double> terrain_reference(const MeshData& mesh, const RaySet& rays, float tmax) {
  const TerrainReference ref(mesh);
  std::vector<double> t(rays.size());
  const std::ptrdiff_t n = std::ptrdiff_t(rays.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < n; ++i) t[std::size_t(i)] = ref.closest(rays, std::size_t(i), tmax);
  return t;
}

// ---------------------------------------------------------------- scoring and output

struct Score {
  std::size_t rays = 0, hits = 0, compared = 0, disagree = 0, ref_hits = 0;
  double checksum = 0, ref_checksum = 0, max_abs_dt = 0;
  bool verdicts = false;  // any hit: the verdicts alone, the hit count as the checksum
  std::string examples;   // the first three disagreeing rays, for a comment line
};

Score score(const float* t, std::size_t n, float tmax, const std::vector<double>& ref, bool verdicts = false) {
  Score s;
  s.rays = n;
  s.verdicts = verdicts;
  s.compared = std::min(n, ref.size());
  for (std::size_t i = 0; i < n; ++i) {
    const bool hit = t[i] >= 0.0f && t[i] <= tmax;
    if (hit) ++s.hits, s.checksum += verdicts ? 1.0 : double(t[i]);
    if (i >= s.compared) continue;
    const bool ref_hit = ref[i] <= double(tmax);
    if (ref_hit) ++s.ref_hits, s.ref_checksum += verdicts ? 1.0 : double(float(ref[i]));
    bool agree = hit == ref_hit;
    if (agree && hit && !verdicts) {
      const double dt = std::abs(double(t[i]) - ref[i]);
      agree = dt <= 1e-3 * std::max(1.0, ref[i]);
      if (agree) s.max_abs_dt = std::max(s.max_abs_dt, dt);
    }
    if (!agree && ++s.disagree <= 3) {
      char buf[96];
      std::snprintf(buf, sizeof buf, " ray %zu: t %.7g, ref %.9g;", i, double(t[i]), ref[i]);
      s.examples += buf;
    }
  }
  return s;
}

struct Line {
  const char* library;
  std::string method;
  std::string simd;
  uint32_t threads;
  double build_ms;
  std::size_t bytes;
  std::size_t primitives;  // triangles or spheres, for bytes per primitive
  double ms;
  int reps;
};

const char* error_metric(const RayCase& c, bool verdicts) {
  if (verdicts)
    return std::string(c.workload) == "R1" ? "rays whose hit/miss differs from the binary64 brute force"
                                           : "rays whose hit/miss differs from the binary64 grid walk";
  return std::string(c.workload) == "R1"
             ? "rays disagreeing with the binary64 brute force (hit/miss, or t beyond 1e-3 max(1,t))"
             : "rays disagreeing with the binary64 grid walk (hit/miss, or t beyond 1e-3 max(1,t))";
}

// Prints a line; returns its throughput (Mrays/s).
double emit(const RayCase& c, const Line& l, const Score& s, const char* per, double gyro_mrays = 0,
            const std::vector<std::pair<const char*, double>>& extra = {}) {
  const double mrays = double(s.rays) / l.ms / 1e3;
  if (s.disagree)
    std::printf("# %s %s %s: disagreeing%s\n", c.workload, l.library, l.method.c_str(), s.examples.c_str());
  JsonLine j;
  j.str("workload", c.workload)
      .str("library", l.library)
      .str("method", l.method)
      .str("simd", l.simd)
      .integer("threads", l.threads)
      .num("build_ms", l.build_ms, 4)
      .num("time_ms", l.ms, 5)
      .num("throughput", mrays, 4)
      .str("unit", "Mrays/s")
      .integer("hits", int64_t(s.hits))
      .num("checksum", s.checksum, 12)
      .num("error", double(s.disagree))
      .str("error_metric", error_metric(c, s.verdicts))
      .integer("error_rays", int64_t(s.compared))
      .num("max_abs_dt", s.max_abs_dt, 3)
      .integer("ref_hits", int64_t(s.ref_hits))
      .num("ref_checksum", s.ref_checksum, 12)
      .integer("rays", int64_t(s.rays))
      .integer("reps", l.reps);
  if (l.bytes) j.integer("bytes", int64_t(l.bytes)).num(per, double(l.bytes) / double(l.primitives), 4);
  if (gyro_mrays > 0) j.num("ratio_vs", mrays / gyro_mrays, 4);
  for (const auto& [key, value] : extra) j.num(key, value, 5);
  j.print();
  return mrays;
}

std::vector<float> tmax_column(const RayCase& c, std::size_t n) { return std::vector<float>(n, c.tmax); }

RaysView view_with_tmax(const RaySet& r, const std::vector<float>& tmax) {
  RaysView v = r.view();
  v.tmax = tmax.data();
  return v;
}

// ---------------------------------------------------------------- gyro

using GyroRates = std::map<uint32_t, double>;  // Mrays/s at the best level run, by threads
struct GyroRuns {
  GyroRates closest, any;
  // gyro's closest hits at its best level on one thread, on the tree the lines timed, for a
  // peer to alternate its reps with: the ratio then comes from the same minutes of this
  // noisy machine (a peer timed minutes after gyro's lines ran in another phase of it:
  // Bullet's R2 figure has moved 0.14-0.39 Mrays/s between runs, gyro's 4.0-5.0).
  std::function<void(const RaySet& rays, const std::vector<float>& tmax)> trace1;
};

// Sets gyro's best level and one thread for a paired trace, and back afterwards.
struct OneThreadBest {
  OneThreadBest() { set_simd_level(detected_simd_level()), set_thread_count(1); }
  ~OneThreadBest() { set_simd_level(SimdLevel::automatic), set_thread_count(0); }
};

// These workloads compare libraries, so by default gyro runs at its best level only
// (R1S and G1 compare the levels); --simd asks for others.
std::vector<SimdLevel> ray_levels(const Options& o) {
  return o.levels.empty() ? std::vector<SimdLevel>{detected_simd_level()} : levels_to_run(o);
}

GyroRuns run_gyro_mesh(const Options& o, const MeshData& mesh, const RayCase& c) {
  GyroRuns rates;
  TriangleMesh tm;
  // The build runs on the thread count of each line, as Embree's does (the same bytes at
  // every count; the last build serves the rays): the median of o.reps builds after a
  // warm-up, like the rays' times and Embree's builds (one cold build swung by half).
  std::map<uint32_t, double> build_ms;
  for (uint32_t threads : threads_to_run(o)) {
    set_thread_count(threads);
    Status st = Status::ok;
    // Each build into a mesh of its own, the last one's freed outside the clock (Embree's
    // scenes too are released after their timed commits): freeing 42 MB inside it had put
    // up to 70 ms of this VM's unmapping into a build of 150.
    TriangleMesh fresh;
    build_ms[threads] = median_ms(
        o.reps, [&] { st = TriangleMesh::create(mesh, fresh); }, [&] { tm = std::move(fresh); });
    if (st != Status::ok) {
      std::printf("# gyro TriangleMesh not available yet (%s: %s)\n", status_name(st), last_error());
      set_thread_count(0);
      return rates;
    }
  }
  const BvhStats stats = tm.stats();
  // TriangleMesh keeps its own copy of the mesh (Embree's bytes leave out the buffers it
  // shares with the caller): the BVH alone is the rest.
  const std::size_t copy = mesh.indices.size() * sizeof(uint32_t) + mesh.vertex_count() * 3 * sizeof(float);
  std::printf("# %s gyro BVH: %zu nodes, %zu leaves, depth %zu, %zu bytes (%.2f per triangle; without the mesh copy "
              "%.2f), SAH cost %.2f\n",
              c.workload, stats.nodes, stats.leaves, stats.max_depth, stats.bytes,
              double(stats.bytes) / double(mesh.triangle_count()),
              double(stats.bytes - std::min(copy, stats.bytes)) / double(mesh.triangle_count()), stats.sah_cost);
  const std::size_t n = c.rays.size();
  const std::vector<float> tmax = tmax_column(c, n);
  testing::HitSet hits(n);
  for (SimdLevel level : ray_levels(o)) {
    set_simd_level(level);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      Status qs = Status::ok;
      const double ms =
          median_ms(o.reps, [&] { qs = raycast_closest(tm, view_with_tmax(c.rays, tmax), n, hits.out(false)); });
      if (qs != Status::ok) {
        std::printf("# gyro raycast_closest failed (%s: %s)\n", status_name(qs), last_error());
        continue;
      }
      const Score s = score(hits.t.data(), n, c.tmax, c.ref);
      rates.closest[threads] = emit(c,
                                    {"gyro", "closest_hit_bvh", simd_level_name(level), threads, build_ms[threads],
                                     stats.bytes, mesh.triangle_count(), ms, o.reps},
                                    s, "bytes_per_triangle");
      if (!c.any_hit) continue;
      const double any_ms =
          median_ms(o.reps, [&] { qs = raycast_any(tm, view_with_tmax(c.rays, tmax), n, hits.out(false)); });
      if (qs != Status::ok) continue;
      rates.any[threads] = emit(c,
                                {"gyro", "any_hit_bvh", simd_level_name(level), threads, build_ms[threads], stats.bytes,
                                 mesh.triangle_count(), any_ms, o.reps},
                                score(hits.t.data(), n, c.tmax, c.ref, true), "bytes_per_triangle");
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
  const auto kept = std::make_shared<TriangleMesh>(std::move(tm));
  rates.trace1 = [kept, out = testing::HitSet(0)](const RaySet& rays, const std::vector<float>& tmax) mutable {
    if (out.t.size() != rays.size()) out = testing::HitSet(rays.size());
    const OneThreadBest one;
    raycast_closest(*kept, view_with_tmax(rays, tmax), rays.size(), out.out(false));
  };
  return rates;
}

GyroRates run_gyro_spheres_subsample(const Options& o, const testing::SphereSet& spheres, const RayCase& c) {
  GyroRates rates;
  const RayCase sub = [&] {
    RayCase s = c;
    for (auto* col : {&s.rays.ox, &s.rays.oy, &s.rays.oz, &s.rays.dx, &s.rays.dy, &s.rays.dz})
      col->resize(s.ref.size());
    return s;
  }();
  const std::size_t n = sub.rays.size();
  const std::vector<float> tmax = tmax_column(sub, n);
  testing::HitSet hits(n);
  for (SimdLevel level : ray_levels(o)) {
    set_simd_level(level);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      const double ms = median_ms(o.reps, [&] {
        raycast_spheres_closest(view_with_tmax(sub.rays, tmax), n, spheres.view(), spheres.size(), hits.out(false));
      });
      const Score s = score(hits.t.data(), n, sub.tmax, sub.ref);
      rates[threads] = emit(
          sub, {"gyro", "brute_force_subsample", simd_level_name(level), threads, 0.0, 0, spheres.size(), ms, o.reps},
          s, "bytes_per_sphere");
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
  return rates;
}

// R1 through gyro's scene: one sphere model per R1 sphere, every ray; under the scene's BVH
// (the default) and under the Cookbook's octree (SceneAccel::octree, its default OctreeDef),
// whose rays go through the same kernel, so the two lines compare the trees' shapes. The
// rates returned are the BVH's.
GyroRuns run_gyro_spheres_scene(const Options& o, const testing::SphereSet& spheres, const RayCase& c) {
  GyroRuns rates;
  for (const SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
    const bool bvh = accel == SceneAccel::bvh;
    const std::string tree = bvh ? "scene_bvh" : "scene_octree";
    // Adding the models and the first prepare(): the median of o.reps scenes after a warm-up.
    Scene scene, fresh;
    bool added = true;
    const double build_ms = median_ms(o.reps, [&] {
      SceneSettings settings;
      settings.accel = accel;
      fresh = Scene(settings);
      for (std::size_t i = 0; i < spheres.size() && added; ++i) {
        ModelDef d;
        d.shape = ModelShape::sphere;
        d.radius = spheres.r[i];
        d.transform.position = {spheres.cx[i], spheres.cy[i], spheres.cz[i]};
        ModelId id;
        added = fresh.add_model(d, &id) == Status::ok;
      }
      fresh.prepare();
    }, [&] { scene = std::move(fresh); });
    if (!added) {
      std::printf("# gyro scene: add_model failed (%s)\n", last_error());
      return rates;
    }
    const SceneStats st = scene.stats();
    if (!bvh)
      std::printf("# gyro octree: %zu nodes, %zu leaves, %zu references to %zu spheres, depth %zu\n", st.nodes,
                  st.leaves, st.references, st.tree_models, st.max_depth);
    const std::size_t n = c.rays.size();
    const std::vector<float> tmax = tmax_column(c, n);
    std::vector<float> t(n);
    std::vector<ModelId> model(n);
    std::vector<int32_t> prim(n);
    std::vector<float> nx(n), ny(n), nz(n);
    const SceneHitsOut out{t.data(), model.data(), prim.data()};
    const SceneHitsOut with_normals{t.data(), model.data(), prim.data(), nx.data(), ny.data(), nz.data()};
    for (SimdLevel level : ray_levels(o)) {
      set_simd_level(level);
      for (uint32_t threads : threads_to_run(o)) {
        set_thread_count(threads);
        const double ms = median_ms(o.reps, [&] { raycast_closest(scene, view_with_tmax(c.rays, tmax), n, out); });
        const double rate = emit(c,
                                 {"gyro", "closest_hit_" + tree, simd_level_name(level), threads, build_ms, st.bytes,
                                  spheres.size(), ms, o.reps},
                                 score(t.data(), n, c.tmax, c.ref), "bytes_per_sphere");
        if (bvh) rates.closest[threads] = rate;
        // With normals, as Embree's and Bullet's hits always carry them (without, a sphere
        // winner's details are never computed: the line above).
        if (bvh) {
          const double normals_ms =
              median_ms(o.reps, [&] { raycast_closest(scene, view_with_tmax(c.rays, tmax), n, with_normals); });
          emit(c,
               {"gyro", "closest_hit_" + tree + "+normals", simd_level_name(level), threads, build_ms, st.bytes,
                spheres.size(), normals_ms, o.reps},
               score(t.data(), n, c.tmax, c.ref), "bytes_per_sphere");
        }
        if (!c.any_hit) continue;
        const double any_ms = median_ms(o.reps, [&] { raycast_any(scene, view_with_tmax(c.rays, tmax), n, out); });
        const double any_rate = emit(c,
                                     {"gyro", "any_hit_" + tree, simd_level_name(level), threads, build_ms, st.bytes,
                                      spheres.size(), any_ms, o.reps},
                                     score(t.data(), n, c.tmax, c.ref, true), "bytes_per_sphere");
        if (bvh) rates.any[threads] = any_rate;
      }
    }
    if (bvh) {
      struct Hits {
        std::vector<float> t;
        std::vector<ModelId> model;
        std::vector<int32_t> prim;
      };
      const auto kept = std::make_shared<Scene>(std::move(scene));
      rates.trace1 = [kept, h = Hits{}](const RaySet& rays, const std::vector<float>& tmax) mutable {
        h.t.resize(rays.size()), h.model.resize(rays.size()), h.prim.resize(rays.size());
        const OneThreadBest one;
        raycast_closest(*kept, view_with_tmax(rays, tmax), rays.size(), {h.t.data(), h.model.data(), h.prim.data()});
      };
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
  return rates;
}

// Layers (ModelDef::layers, RaysView::mask): R1's odd spheres in layer 2 and every ray in
// layer 1, so the rays see the even spheres alone. Both lines are scored against the binary64
// brute force over the even spheres: the layered scene, and a scene holding the even spheres
// alone, whose time is what the hidden half would cost if it were not in the tree at all.
void run_gyro_spheres_layers(const Options& o, const testing::SphereSet& spheres, const RayCase& c) {
  testing::SphereSet even;
  for (std::size_t i = 0; i < spheres.size(); i += 2) {
    even.cx.push_back(spheres.cx[i]), even.cy.push_back(spheres.cy[i]), even.cz.push_back(spheres.cz[i]);
    even.r.push_back(spheres.r[i]);
  }
  RayCase cv = c;
  cv.ref.clear();
  for (const testing::RefHit& h : testing::ref_raycast_spheres(c.rays, kR1ReferenceRays, even)) cv.ref.push_back(h.t);
  const auto scene_of = [&](const testing::SphereSet& set, bool layered) {
    Scene scene;
    for (std::size_t i = 0; i < set.size(); ++i) {
      ModelDef d;
      d.shape = ModelShape::sphere;
      d.radius = set.r[i];
      d.transform.position = {set.cx[i], set.cy[i], set.cz[i]};
      d.layers = layered && i % 2 == 1 ? 2u : 1u;
      ModelId id;
      if (scene.add_model(d, &id) != Status::ok) std::printf("# gyro scene: add_model failed (%s)\n", last_error());
    }
    scene.prepare();
    return scene;
  };
  const Scene layered = scene_of(spheres, true), alone = scene_of(even, false);
  std::printf("# R1 layers: odd spheres in layer 2, rays of layer 1; error against the binary64 brute force over the "
              "%zu even spheres\n", even.size());
  const std::size_t n = c.rays.size();
  const std::vector<float> tmax = tmax_column(c, n);
  const std::vector<uint32_t> masks(n, 1u);
  std::vector<float> t(n);
  std::vector<ModelId> model(n);
  const SceneHitsOut out{t.data(), model.data()};
  for (SimdLevel level : ray_levels(o)) {
    set_simd_level(level);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      RaysView masked = view_with_tmax(c.rays, tmax);
      masked.mask = masks.data();
      const double ms = median_ms(o.reps, [&] { raycast_closest(layered, masked, n, out); });
      emit(cv,
           {"gyro", "closest_hit_scene_bvh_layers", simd_level_name(level), threads, 0.0, layered.stats().bytes,
            spheres.size(), ms, o.reps},
           score(t.data(), n, c.tmax, cv.ref), "bytes_per_sphere");
      const double alone_ms = median_ms(o.reps, [&] { raycast_closest(alone, view_with_tmax(c.rays, tmax), n, out); });
      emit(cv,
           {"gyro", "closest_hit_scene_bvh_visible_only", simd_level_name(level), threads, 0.0, alone.stats().bytes,
            even.size(), alone_ms, o.reps},
           score(t.data(), n, c.tmax, cv.ref), "bytes_per_sphere");
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

// ---------------------------------------------------------------- peers

enum class Geometry { triangles, spheres };

void run_embree(const Options& o, Geometry g, const MeshData* mesh, const testing::SphereSet* spheres, const RayCase& c,
                const GyroRuns& gyro) {
  if (!embree_available()) {
    std::printf("# Embree not built in (libembree-dev missing at configure time)\n");
    return;
  }
  std::printf("# Embree %s, rtcIntersect16 %s, build quality medium (Embree's default)\n", embree_version(),
              embree_native_ray16() ? "native (AVX-512)" : "emulated");
  const std::size_t n = c.rays.size();
  const char* per = g == Geometry::triangles ? "bytes_per_triangle" : "bytes_per_sphere";
  const std::size_t prims = g == Geometry::triangles ? mesh->triangle_count() : spheres->size();
  RayResults r;
  for (uint32_t threads : threads_to_run(o)) {
    for (bool robust : {false, true}) {
      if (robust && g == Geometry::spheres) continue;  // the flag only changes the triangle test
      // The median of o.reps builds after a warm-up, as gyro's; the last one serves the rays.
      PeerBuild b;
      std::unique_ptr<EmbreeScene> scene;
      std::vector<double> builds;
      for (int rep = 0; rep <= std::max(1, o.reps); ++rep) {
        scene = g == Geometry::triangles ? EmbreeScene::triangles(*mesh, robust, threads, b)
                                         : EmbreeScene::spheres(*spheres, threads, b);
        if (!scene) {
          std::printf("# Embree scene build failed\n");
          return;
        }
        if (rep > 0) builds.push_back(b.ms);
      }
      b.ms = median(std::move(builds));
      for (EmbreeMethod m : {EmbreeMethod::intersect1, EmbreeMethod::intersect16, EmbreeMethod::occluded1,
                             EmbreeMethod::occluded16}) {
        const bool occluded = m == EmbreeMethod::occluded1 || m == EmbreeMethod::occluded16;
        if (occluded && !c.any_hit) continue;
        std::string name = m == EmbreeMethod::intersect1    ? "rtcIntersect1"
                           : m == EmbreeMethod::intersect16 ? "rtcIntersect16"
                           : m == EmbreeMethod::occluded1   ? "rtcOccluded1"
                                                            : "rtcOccluded16";
        if (robust) name += "+robust";
        if (g == Geometry::spheres) name += " sphere_point";
        const double ms = median_ms(o.reps, [&] { scene->trace(c.rays, n, c.tmax, m, threads, r); });
        const GyroRates& vs = occluded ? gyro.any : gyro.closest;
        const auto it = vs.find(threads);
        emit(c, {"embree", name, "auto", threads, b.ms, b.bytes, prims, ms, o.reps},
             score(r.t.data(), n, c.tmax, c.ref, occluded), per, it == vs.end() ? 0.0 : it->second);
      }
    }
  }
}

void run_bullet(const Options& o, Geometry g, const MeshData* mesh, const testing::SphereSet* spheres, const RayCase& c,
                const GyroRuns& runs) {
  const GyroRates& gyro = runs.closest;
  if (!bullet_available()) {
    std::printf("# Bullet not built in (libbullet-dev missing at configure time)\n");
    return;
  }
  const auto ts = threads_to_run(o);
  if (std::find(ts.begin(), ts.end(), 1u) == ts.end()) {
    std::printf("# Bullet runs on one thread only (rayTest is not thread-safe): skipped\n");
    return;
  }
  const RayCase sub = subsample(c, bullet_rays());
  const std::size_t n = sub.rays.size();
  PeerBuild b;
  const auto world =
      g == Geometry::triangles ? BulletRayWorld::triangles(*mesh, b) : BulletRayWorld::spheres(*spheres, b);
  if (!world) return;
  RayResults r;
  const int reps = std::max(1, std::min(o.reps, 3));
  // Bullet's reps, each after one of gyro's on the same rays (both warmed up first).
  const std::vector<float> tmax = tmax_column(sub, n);
  std::vector<double> ms_all, paired;
  for (int rep = 0; rep <= reps; ++rep) {
    if (runs.trace1) {
      const auto a = std::chrono::steady_clock::now();
      runs.trace1(sub.rays, tmax);
      if (rep > 0) paired.push_back(ms_since(a));
    }
    const auto a = std::chrono::steady_clock::now();
    world->trace(sub.rays, n, sub.tmax, r);
    if (rep > 0) ms_all.push_back(ms_since(a));
  }
  const double ms = median(std::move(ms_all));
  std::vector<std::pair<const char*, double>> extra;
  if (!paired.empty()) {
    const double gyro_ms = median(std::move(paired));
    extra = {{"gyro_paired_ms", gyro_ms}, {"gyro_paired_speedup", ms / gyro_ms}};
  }
  const auto it = gyro.find(1);
  const char* method = g == Geometry::triangles ? "rayTest btBvhTriangleMeshShape" : "rayTest btSphereShape";
  emit(sub,
       {"bullet", method, "scalar", 1, b.ms, b.bytes,
        g == Geometry::triangles ? mesh->triangle_count() : spheres->size(), ms, reps},
       score(r.t.data(), n, sub.tmax, sub.ref), g == Geometry::triangles ? "bytes_per_triangle" : "bytes_per_sphere",
       it == gyro.end() ? 0.0 : it->second, extra);
  if (ts.size() > 1) std::printf("# Bullet: 1 thread only (rayTest is not thread-safe)\n");
}

void print_reference(const RayCase& c, double ms, const char* expected) {
  std::size_t hits = 0;
  double sum = 0;
  for (double t : c.ref)
    if (t <= double(c.tmax)) ++hits, sum += double(float(t));
  std::printf("# %s: %zu rays, tmax %g; binary64 reference on %zu rays (%.0f ms): %zu hits, sum t %.2f%s%s\n",
              c.workload, c.rays.size(), double(c.tmax), c.ref.size(), ms, hits, sum,
              expected[0] ? "; BENCHMARKS.md: " : "", expected);
}

void run_terrain(const Options& o, RayCase c, const char* expected) {
  const MeshData mesh = testing::r2_mesh();
  if (testing::mesh_vertices_fnv(mesh) != testing::kR2VerticesFnv ||
      testing::mesh_indices_fnv(mesh) != testing::kR2IndicesFnv)
    std::printf("# WARNING: R2 mesh hash mismatch: generator differs from BENCHMARKS.md\n");
  const auto start = std::chrono::steady_clock::now();
  c.ref = terrain_reference(mesh, c.rays, c.tmax);
  print_reference(c, ms_since(start), expected);
  std::printf("# ratio_vs = this line's throughput / gyro's (best SIMD level, same threads)\n");
  const GyroRuns gyro = run_gyro_mesh(o, mesh, c);
  if (!o.peers) return;
  run_embree(o, Geometry::triangles, &mesh, nullptr, c, gyro);
  run_bullet(o, Geometry::triangles, &mesh, nullptr, c, gyro);
}

}  // namespace

void run_r1(const Options& o) {
  const testing::SphereSet spheres = testing::r1_spheres();
  RayCase c;
  c.workload = "R1";
  c.any_hit = true;
  c.rays = testing::r1_rays();
  if (c.rays.fnv() != testing::kR1RaysFnv) std::printf("# WARNING: R1 rays hash mismatch\n");
  const auto start = std::chrono::steady_clock::now();
  for (const testing::RefHit& h : testing::ref_raycast_spheres(c.rays, kR1ReferenceRays, spheres)) c.ref.push_back(h.t);
  print_reference(c, ms_since(start), "368,880 hits and sum t 9,564,267.01 over all 1,000,000 rays");
  std::printf("# ratio_vs = this line's throughput / gyro's (best SIMD level, same threads)\n");
  const GyroRuns gyro = run_gyro_spheres_scene(o, spheres, c);
  run_gyro_spheres_subsample(o, spheres, c);
  run_gyro_spheres_layers(o, spheres, c);
  if (!o.peers) return;
  run_embree(o, Geometry::spheres, nullptr, &spheres, c, gyro);
  run_bullet(o, Geometry::spheres, nullptr, &spheres, c, gyro);
}

void run_r2(const Options& o) {
  RayCase c;
  c.workload = "R2";
  c.any_hit = true;
  c.rays = testing::r2_rays();
  if (c.rays.fnv() != testing::kR2RaysFnv) std::printf("# WARNING: R2 rays hash mismatch\n");
  run_terrain(o, std::move(c), "1,000,000 hits and sum t 39,910,570.77");
}

void run_lidar(const Options& o) {
  RayCase c;
  c.workload = "LIDAR";
  c.rays = testing::lidar_rays();
  c.tmax = testing::kLidarTmax;
  c.ordered = true;
  run_terrain(o, std::move(c), "");
}

void run_camera(const Options& o) {
  RayCase c;
  c.workload = "CAMERA";
  c.rays = testing::camera_rays();
  c.ordered = true;
  run_terrain(o, std::move(c), "");
}

}  // namespace gyro::bench
