// N1 (BENCHMARKS.md): 10^6 random OBB pairs. gyro's batch separating-axis test per SIMD
// level and thread count (boolean, and with the separation/depth), a plain scalar 15-axis
// loop, and the peers installed: Bullet's btBoxBoxDetector, libccd GJK/MPR (intersect)
// and EPA/MPR (penetration). Every line carries its error against the binary64 SAT:
// verdict disagreements (and how many lie within 1e-4 of touching), and the max depth error.
#include "gyro/batch_overlap.hpp"
#include "peers.hpp"
#include "reference.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace gyro::bench {
namespace {

using testing::BoxPairs;

struct Reference {
  std::vector<double> sep;  // binary64 separation per pair
  std::size_t overlapping = 0;
  double depth_sum = 0;
};

Reference reference(const BoxPairs& p, std::size_t n) {
  Reference r;
  r.sep.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) r.sep[i] = testing::ref_obb_obb_separation(p.a, i, p.b, i);
  for (std::size_t i = 0; i < n; ++i)
    if (r.sep[i] <= 0) ++r.overlapping, r.depth_sum += -r.sep[i];
  return r;
}

struct Score {
  std::size_t hits = 0, disagree = 0, disagree_near = 0;
  double depth_sum = 0, max_depth_err = 0;
};

// Compares verdicts (and depths when given) with the reference; "near" = within 1e-4 of touching.
template <class HitAt, class DepthAt> Score score(const Reference& r, std::size_t n, HitAt hit_at, DepthAt depth_at) {
  Score s;
  for (std::size_t i = 0; i < n; ++i) {
    const bool h = hit_at(i), ref = r.sep[i] <= 0;
    s.hits += h;
    if (h) s.depth_sum += depth_at(i);
    if (h != ref) {
      ++s.disagree;
      s.disagree_near += std::abs(r.sep[i]) <= 1e-4;
    } else if (h) {
      s.max_depth_err = std::max(s.max_depth_err, std::abs(depth_at(i) - (-r.sep[i])));
    }
  }
  return s;
}

void emit(const char* library, const char* method, const char* simd, uint32_t threads, double ms, std::size_t n,
          const Score& s, bool with_depth, int reps, double ratio_ref_ms = 0, const char* ratio_name = nullptr) {
  JsonLine line;
  line.str("workload", "N1").str("library", library).str("method", method).str("simd", simd)
      .integer("threads", threads).num("build_ms", 0).num("time_ms", ms, 5).num("throughput", double(n) / ms / 1e3, 5)
      .str("unit", "Mpairs/s").integer("hits", int64_t(s.hits)).num("checksum", with_depth ? s.depth_sum : 0.0, 10)
      .num("error", double(s.disagree)).str("error_metric", "verdicts disagreeing with binary64 SAT")
      .integer("disagree_within_1e-4", int64_t(s.disagree_near));
  if (with_depth) line.num("max_depth_error", s.max_depth_err, 4);
  line.integer("reps", reps);
  if (ratio_name) line.num(ratio_name, ratio_ref_ms / ms, 4);
  line.print();
}

// The plain scalar loop BENCHMARKS.md quotes (32 Mpairs/s): 15 axes, early exit.
bool plain_sat(const testing::BoxSet& A, const testing::BoxSet& B, std::size_t i) {
  float a[3][3], b[3][3];
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) a[k][c] = A.r[3 * c + k][i], b[k][c] = B.r[3 * c + k][i];
  const float ea[3] = {A.hx[i], A.hy[i], A.hz[i]}, eb[3] = {B.hx[i], B.hy[i], B.hz[i]};
  const float d[3] = {B.cx[i] - A.cx[i], B.cy[i] - A.cy[i], B.cz[i] - A.cz[i]};
  float R[3][3], AR[3][3], t[3];
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      R[k][j] = a[k][0] * b[j][0] + a[k][1] * b[j][1] + a[k][2] * b[j][2];
      AR[k][j] = std::abs(R[k][j]) + 1e-6f;
    }
    t[k] = d[0] * a[k][0] + d[1] * a[k][1] + d[2] * a[k][2];
  }
  for (int k = 0; k < 3; ++k)
    if (std::abs(t[k]) > ea[k] + eb[0] * AR[k][0] + eb[1] * AR[k][1] + eb[2] * AR[k][2]) return false;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t[0] * R[0][j] + t[1] * R[1][j] + t[2] * R[2][j]) > ea[0] * AR[0][j] + ea[1] * AR[1][j] + ea[2] * AR[2][j] + eb[j])
      return false;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const float ra = ea[k1] * AR[k2][j] + ea[k2] * AR[k1][j], rb = eb[j1] * AR[k][j2] + eb[j2] * AR[k][j1];
      if (std::abs(t[k2] * R[k1][j] - t[k1] * R[k2][j]) > ra + rb) return false;
    }
  }
  return true;
}

}  // namespace

void run_n1(const Options& o) {
  const std::size_t n = 1000000;
  const BoxPairs p = testing::n1_pairs(n);
  if (p.fnv() != testing::kN1BoxesFnv) std::printf("# WARNING: N1 boxes hash mismatch: generator differs from BENCHMARKS.md\n");
  const Reference ref = reference(p, n);
  std::printf("# N1: %zu OBB pairs; binary64 SAT: %zu overlapping, depth sum %.3f\n", n, ref.overlapping, ref.depth_sum);
  const ShapeArray a = shape_array(p.a.view()), b = shape_array(p.b.view());
  std::vector<uint32_t> out(n);
  std::vector<float> sep(n);
  std::map<uint32_t, double> scalar_ms;
  for (SimdLevel level : levels_to_run(o)) {
    set_simd_level(level);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      const double ms = median_ms(o.reps, [&] { overlap_pairwise(a, b, n, out.data()); });
      if (level == SimdLevel::scalar) scalar_ms[threads] = ms;
      const Score s = score(ref, n, [&](std::size_t i) { return out[i] == kOverlapping; }, [](std::size_t) { return 0.0; });
      emit("gyro", "sat_boolean", simd_level_name(level), threads, ms, n, s, false, o.reps, scalar_ms[threads],
           "ratio_vs_scalar");
      const double dms = median_ms(o.reps, [&] { obb_separation_pairwise(p.a.view(), p.b.view(), n, sep.data()); });
      const Score ds = score(ref, n, [&](std::size_t i) { return sep[i] <= 0.0f; }, [&](std::size_t i) { return -double(sep[i]); });
      emit("gyro", "sat_depth", simd_level_name(level), threads, dms, n, ds, true, o.reps);
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);

  std::vector<uint8_t> plain(n);
  const double plain_ms = median_ms(o.reps, [&] {
    for (std::size_t i = 0; i < n; ++i) plain[i] = plain_sat(p.a, p.b, i);
  });
  emit("plain_loop", "sat_boolean_f32", "compiler", 1, plain_ms, n,
       score(ref, n, [&](std::size_t i) { return plain[i] != 0; }, [](std::size_t) { return 0.0; }), false, o.reps);
  if (!o.peers) return;
  const int peer_reps = std::max(1, std::min(o.reps, 3));
  PairResults r;
  if (bullet_available()) {
    const double ms = median_ms(peer_reps, [&] { bullet_box_box(p, n, r); });
    emit("bullet", "btBoxBoxDetector", "sse", 1, ms, n,
         score(ref, n, [&](std::size_t i) { return r.hit[i] != 0; }, [&](std::size_t i) { return r.depth[i]; }), true,
         peer_reps);
  } else {
    std::printf("# bullet not installed\n");
  }
  if (ccd_available()) {
    const struct {
      CcdMethod m;
      const char* name;
      bool depth;
      std::size_t count;
    } methods[] = {{CcdMethod::gjk_intersect, "ccdGJKIntersect", false, n},
                   {CcdMethod::mpr_intersect, "ccdMPRIntersect", false, n},
                   {CcdMethod::gjk_epa_penetration, "ccdGJKPenetration", true, n / 4},
                   {CcdMethod::mpr_penetration, "ccdMPRPenetration", true, n}};
    for (const auto& m : methods) {
      const double ms = median_ms(1, [&] { ccd_box_box(p, m.count, m.m, r); });
      emit("libccd", m.name, "double", 1, ms, m.count,
           score(ref, m.count, [&](std::size_t i) { return r.hit[i] != 0; }, [&](std::size_t i) { return r.depth[i]; }),
           m.depth, 1);
    }
  } else {
    std::printf("# libccd not installed\n");
  }
}

}  // namespace gyro::bench
