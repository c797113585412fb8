// GJK workload: the N1 pairs (BENCHMARKS.md, 10^6 OBB pairs) through generic convex
// queries: gyro's GJK intersection, GJK distance and GJK+EPA penetration (gyro/convex.hpp),
// then the box-pair batches (convex_intersect_batch, convex_distance_batch,
// convex_penetration_batch: GJK over SIMD lanes, per level, results bit-identical to the
// scalar queries; penetration also with separated_distance off, where separated pairs stop
// at a separating axis as libccd's and Bullet's penetration calls do), the C ABI's four pair
// calls (gyro_convex_*_pairs: box-box pairs over the lanes, from arrays of C structs), and
// with --peers libccd (GJK and MPR intersection, GJK+EPA and MPR penetration) and Bullet
// (btGjkEpaSolver2 Distance / Penetration, btGjkPairDetector with its GJK-EPA depth solver;
// box margins 0) on the same pairs in the same run.
//
// Every line carries its error against the binary64 15-axis SAT: verdicts disagreeing (and
// how many of those lie within 1e-4 of touching), the max depth error on pairs both call
// overlapping, and for distance methods the largest amount by which the reported distance
// falls below the SAT separation (a lower bound of the true distance).
#include "gyro.h"
#include "gyro/convex.hpp"
#include "peers.hpp"
#include "reference.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(GYRO_BENCH_HAS_BULLET)
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#endif

namespace gyro::bench {
namespace {

using testing::BoxPairs;
using testing::BoxSet;

struct Score {
  std::size_t hits = 0, disagree = 0, disagree_near = 0;
  double depth_sum = 0, max_depth_err = 0, max_below_sat = 0;
};

// hit_at(i), depth_at(i) (>= 0, for hits), dist_at(i) (signed distance, or NaN if none).
template <class Hit, class Depth, class Dist>
Score score(const std::vector<double>& sep, std::size_t n, Hit hit_at, Depth depth_at, Dist dist_at) {
  Score s;
  for (std::size_t i = 0; i < n; ++i) {
    const bool h = hit_at(i), ref = sep[i] <= 0;
    s.hits += h;
    if (h) s.depth_sum += depth_at(i);
    if (h != ref) {
      ++s.disagree;
      s.disagree_near += std::abs(sep[i]) <= 1e-4;
    } else if (h) {
      s.max_depth_err = std::max(s.max_depth_err, std::abs(depth_at(i) - -sep[i]));
    }
    const double d = dist_at(i);
    if (!h && ref == h && d == d) s.max_below_sat = std::max(s.max_below_sat, sep[i] - d);
  }
  return s;
}

void emit(const char* library, const char* method, const char* simd, double ms, std::size_t n, const Score& s,
          bool depth, bool dist, int reps, std::size_t limits = 0, uint32_t threads = 1) {
  JsonLine line;
  line.str("workload", "GJK").str("library", library).str("method", method).str("simd", simd).integer("threads", threads)
      .num("build_ms", 0).num("time_ms", ms, 5).num("throughput", double(n) / ms / 1e3, 5).str("unit", "Mpairs/s")
      .integer("hits", int64_t(s.hits)).num("checksum", depth ? s.depth_sum : 0.0, 10)
      .num("error", double(s.disagree)).str("error_metric", "verdicts disagreeing with binary64 SAT")
      .integer("disagree_within_1e-4", int64_t(s.disagree_near));
  if (depth) line.num("max_depth_error", s.max_depth_err, 4);
  if (dist) line.num("max_distance_below_sat", s.max_below_sat, 4);
  line.integer("iteration_limits", int64_t(limits)).integer("pairs", int64_t(n)).integer("reps", reps);
  line.print();
}

ConvexShape box_shape(const BoxSet& s, std::size_t i) {
  ConvexShape b;
  b.type = ConvexType::box;
  b.half_extents = {s.hx[i], s.hy[i], s.hz[i]};
  return b;
}

ConvexPose box_pose(const BoxSet& s, std::size_t i) {
  ConvexPose p;
  p.position = {s.cx[i], s.cy[i], s.cz[i]};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) p.rotation.m[k][c] = s.r[3 * c + k][i];  // row k = local axis k = column k of R
  return p;
}

const double kNan = std::nan("");

void run_gyro(const BoxPairs& p, const std::vector<double>& sep, std::size_t n, int reps) {
  std::vector<ConvexResult> out(n);
  const struct {
    const char* name;
    ConvexResult (*fn)(const ConvexShape&, const ConvexPose&, const ConvexShape&, const ConvexPose&,
                       const ConvexQueryOptions&);
    bool depth, dist;
  } methods[] = {{"gjk_intersect", convex_intersect, false, false},
                 {"gjk_distance", convex_distance, false, true},
                 {"gjk_epa_penetration", convex_penetration, true, true},
                 {"gjk_epa_penetration_overlaps_only", convex_penetration, true, false}};
  for (const auto& m : methods) {
    ConvexQueryOptions opt;
    opt.separated_distance = m.dist;  // without: separated pairs stop at a separating axis, as libccd's
    const double ms = median_ms(reps, [&] {
      for (std::size_t i = 0; i < n; ++i)
        out[i] = m.fn(box_shape(p.a, i), box_pose(p.a, i), box_shape(p.b, i), box_pose(p.b, i), opt);
    });
    std::size_t limits = 0;
    for (std::size_t i = 0; i < n; ++i) limits += out[i].status == ConvexStatus::iteration_limit;
    const Score s = score(
        sep, n, [&](std::size_t i) { return overlapping(out[i].status); },
        [&](std::size_t i) { return -double(out[i].distance); },
        [&](std::size_t i) { return m.dist ? double(out[i].distance) : kNan; });
    emit("gyro", m.name, "scalar", ms, n, s, m.depth, m.dist, reps, limits);
  }
}

// The box-pair batches (convex_intersect_batch, convex_distance_batch,
// convex_penetration_batch) over the SoA box columns, per SIMD level, on one thread (the
// peers' lines are one thread too): their results are the scalar queries' bit for bit at
// every level (a warning line says if the levels differ). Then, where the process has more
// threads, each batch again at the default level on all of them (the batches cut the pairs
// into fixed chunks, so the bits are the same; a warning line says if not).
void run_gyro_batch(const BoxPairs& p, const std::vector<double>& sep, std::size_t n, const Options& o) {
  ConvexBoxPairs pairs;
  auto fill = [](const BoxSet& s, const float* (&c)[3], const float* (&h)[3], const float* (&r)[9]) {
    c[0] = s.cx.data(), c[1] = s.cy.data(), c[2] = s.cz.data();
    h[0] = s.hx.data(), h[1] = s.hy.data(), h[2] = s.hz.data();
    for (int k = 0; k < 3; ++k)
      for (int col = 0; col < 3; ++col) r[3 * k + col] = s.r[3 * col + k].data();  // row k = column k of R
  };
  fill(p.a, pairs.a_center, pairs.a_half, pairs.a_rot);
  fill(p.b, pairs.b_center, pairs.b_half, pairs.b_rot);
  const uint32_t threads = thread_count();
  set_thread_count(1);
  std::vector<ConvexStatus> out(n), first;
  for (SimdLevel level : levels_to_run(o)) {
    set_simd_level(level);
    const double ms = median_ms(o.reps, [&] { convex_intersect_batch(pairs, n, out.data()); });
    if (first.empty()) first = out;
    std::size_t limits = 0;
    for (std::size_t i = 0; i < n; ++i) limits += out[i] == ConvexStatus::iteration_limit;
    const Score s = score(
        sep, n, [&](std::size_t i) { return overlapping(out[i]); }, [](std::size_t) { return 0.0; },
        [](std::size_t) { return kNan; });
    if (out != first) std::printf("# WARNING: gjk_intersect_batch verdicts differ between SIMD levels\n");
    emit("gyro", "gjk_intersect_batch", simd_level_name(level), ms, n, s, false, false, o.reps, limits);
  }
  const struct {
    const char* name;
    void (*fn)(const ConvexBoxPairs&, std::size_t, ConvexResult*, const ConvexQueryOptions&);
    bool depth, dist;
  } methods[] = {{"gjk_distance_batch", convex_distance_batch, false, true},
                 {"gjk_epa_penetration_batch", convex_penetration_batch, true, true},
                 {"gjk_epa_penetration_overlaps_only_batch", convex_penetration_batch, true, false}};
  std::vector<ConvexResult> res(n), res_first;
  for (const auto& m : methods) {
    res_first.clear();
    ConvexQueryOptions opt;
    opt.separated_distance = m.dist;
    for (SimdLevel level : levels_to_run(o)) {
      set_simd_level(level);
      const double ms = median_ms(o.reps, [&] { m.fn(pairs, n, res.data(), opt); });
      bool same = true;
      if (res_first.empty()) res_first = res;
      else
        for (std::size_t i = 0; i < n && same; ++i) same = std::memcmp(&res[i], &res_first[i], sizeof(ConvexResult)) == 0;
      if (!same) std::printf("# WARNING: %s results differ between SIMD levels\n", m.name);
      std::size_t limits = 0;
      for (std::size_t i = 0; i < n; ++i) limits += res[i].status == ConvexStatus::iteration_limit;
      const Score s = score(
          sep, n, [&](std::size_t i) { return overlapping(res[i].status); },
          [&](std::size_t i) { return -double(res[i].distance); },
          [&](std::size_t i) { return m.dist ? double(res[i].distance) : kNan; });
      emit("gyro", m.name, simd_level_name(level), ms, n, s, m.depth, m.dist, o.reps, limits);
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(threads);
  if (threads <= 1) return;
  const char* level = simd_level_name(simd_level());
  {
    const double ms = median_ms(o.reps, [&] { convex_intersect_batch(pairs, n, out.data()); });
    if (out != first) std::printf("# WARNING: gjk_intersect_batch verdicts differ between thread counts\n");
    const Score s = score(
        sep, n, [&](std::size_t i) { return overlapping(out[i]); }, [](std::size_t) { return 0.0; },
        [](std::size_t) { return kNan; });
    emit("gyro", "gjk_intersect_batch", level, ms, n, s, false, false, o.reps, 0, threads);
  }
  for (const auto& m : methods) {
    ConvexQueryOptions opt;
    opt.separated_distance = m.dist;
    res_first.resize(n);
    set_thread_count(1);  // one thread's answer, for the comparison
    m.fn(pairs, n, res_first.data(), opt);
    set_thread_count(threads);
    const double ms = median_ms(o.reps, [&] { m.fn(pairs, n, res.data(), opt); });
    if (std::memcmp(res.data(), res_first.data(), n * sizeof(ConvexResult)) != 0)
      std::printf("# WARNING: %s results differ between thread counts\n", m.name);
    const Score s = score(
        sep, n, [&](std::size_t i) { return overlapping(res[i].status); },
        [&](std::size_t i) { return -double(res[i].distance); },
        [&](std::size_t i) { return m.dist ? double(res[i].distance) : kNan; });
    emit("gyro", m.name, level, ms, n, s, m.depth, m.dist, o.reps, 0, threads);
  }
}

// The C ABI's pair calls on the same pairs (arrays of gyro_convex_shape and gyro_convex_pose),
// at the level the library picks: their box-box pairs run over SIMD lanes, the batches' bits.
void run_gyro_capi(const BoxPairs& p, const std::vector<double>& sep, std::size_t n, int reps) {
  std::vector<gyro_convex_shape> a(n), b(n);
  std::vector<gyro_convex_pose> pa(n), pb(n);
  const auto fill = [](const BoxSet& s, std::size_t i, gyro_convex_shape& shape, gyro_convex_pose& pose) {
    std::memset(&shape, 0, sizeof shape);
    shape.type = GYRO_CONVEX_BOX, shape.half_extents = {s.hx[i], s.hy[i], s.hz[i]};
    const ConvexPose q = box_pose(s, i);
    pose.position = {q.position.x, q.position.y, q.position.z};
    for (int k = 0; k < 3; ++k) pose.rotation[k] = {q.rotation.m[k][0], q.rotation.m[k][1], q.rotation.m[k][2]};
  };
  for (std::size_t i = 0; i < n; ++i) fill(p.a, i, a[i], pa[i]), fill(p.b, i, b[i], pb[i]);
  using PairsFn = gyro_status (*)(const gyro_convex_shape*, const gyro_convex_pose*, const gyro_convex_shape*,
                                  const gyro_convex_pose*, int32_t, gyro_convex_result*);
  const struct {
    const char* name;
    PairsFn fn;
    bool depth, dist;
  } methods[] = {{"capi_convex_intersect_pairs", gyro_convex_intersect_pairs, false, false},
                 {"capi_convex_distance_pairs", gyro_convex_distance_pairs, false, true},
                 {"capi_convex_penetration_pairs", gyro_convex_penetration_pairs, true, true},
                 {"capi_convex_contact_pairs", gyro_convex_contact_pairs, true, false}};
  const uint32_t threads = gyro_get_thread_count();
  gyro_set_thread_count(1);
  std::vector<gyro_convex_result> out(n);
  for (const auto& m : methods) {
    const double ms = median_ms(reps, [&] { m.fn(a.data(), pa.data(), b.data(), pb.data(), int32_t(n), out.data()); });
    std::size_t limits = 0;
    for (std::size_t i = 0; i < n; ++i) limits += out[i].status == GYRO_CONVEX_ITERATION_LIMIT;
    const auto hit = [&](std::size_t i) {
      return out[i].status == GYRO_CONVEX_INTERSECTING || out[i].status == GYRO_CONVEX_TOUCHING;
    };
    const Score s = score(
        sep, n, hit, [&](std::size_t i) { return -double(out[i].distance); },
        [&](std::size_t i) { return m.dist ? double(out[i].distance) : kNan; });
    emit("gyro", m.name, simd_level_name(simd_level()), ms, n, s, m.depth, m.dist, reps, limits);
  }
  gyro_set_thread_count(threads);
}

#if defined(GYRO_BENCH_HAS_BULLET)
btTransform bt_transform(const BoxSet& s, std::size_t k) {
  const btMatrix3x3 r(s.r[0][k], s.r[1][k], s.r[2][k], s.r[3][k], s.r[4][k], s.r[5][k], s.r[6][k], s.r[7][k], s.r[8][k]);
  return btTransform(r, btVector3(s.cx[k], s.cy[k], s.cz[k]));
}

enum class BulletMethod { epa2_distance, epa2_penetration, pair_detector };

struct Closest : btDiscreteCollisionDetectorInterface::Result {
  bool got = false;
  double distance = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar d) override {
    if (!got || d < distance) distance = d;
    got = true;
  }
};

// hit, depth (>= 0 on hits) and signed distance (NaN where the method gives none).
void bullet_run(const BoxPairs& p, std::size_t n, BulletMethod m, std::vector<uint8_t>& hit, std::vector<double>& depth,
                std::vector<double>& dist) {
  for (std::size_t i = 0; i < n; ++i) {
    btBoxShape a(btVector3(p.a.hx[i], p.a.hy[i], p.a.hz[i])), b(btVector3(p.b.hx[i], p.b.hy[i], p.b.hz[i]));
    a.setMargin(0), b.setMargin(0);  // exact boxes: the extents are kept, the rounding margin is removed
    const btTransform ta = bt_transform(p.a, i), tb = bt_transform(p.b, i);
    hit[i] = 0, depth[i] = 0, dist[i] = kNan;
    if (m == BulletMethod::pair_detector) {
      btVoronoiSimplexSolver simplex;
      btGjkEpaPenetrationDepthSolver epa;
      btGjkPairDetector detector(&a, &b, &simplex, &epa);
      btGjkPairDetector::ClosestPointInput in;
      in.m_transformA = ta, in.m_transformB = tb;
      Closest r;
      detector.getClosestPoints(in, r, nullptr);
      if (r.got) {
        hit[i] = r.distance <= 0;
        depth[i] = hit[i] ? -r.distance : 0.0;
        dist[i] = r.distance;
      }
      continue;
    }
    btGjkEpaSolver2::sResults res;
    const btVector3 guess = tb.getOrigin() - ta.getOrigin();
    if (m == BulletMethod::epa2_distance) {
      const bool separated = btGjkEpaSolver2::Distance(&a, ta, &b, tb, guess, res);
      hit[i] = !separated;
      if (separated) dist[i] = res.distance;
    } else {
      hit[i] = btGjkEpaSolver2::Penetration(&a, ta, &b, tb, guess, res, false);
      depth[i] = hit[i] ? -double(res.distance) : 0.0;
    }
  }
}
#endif

void run_bullet(const BoxPairs& p, const std::vector<double>& sep, std::size_t n, int reps) {
#if defined(GYRO_BENCH_HAS_BULLET)
  std::vector<uint8_t> hit(n);
  std::vector<double> depth(n), dist(n);
  const struct {
    BulletMethod m;
    const char* name;
    bool depth, dist;
  } methods[] = {{BulletMethod::epa2_distance, "btGjkEpaSolver2::Distance", false, true},
                 {BulletMethod::epa2_penetration, "btGjkEpaSolver2::Penetration", true, false},
                 {BulletMethod::pair_detector, "btGjkPairDetector+btGjkEpaPenetrationDepthSolver", true, true}};
  for (const auto& m : methods) {
    const double ms = median_ms(reps, [&] { bullet_run(p, n, m.m, hit, depth, dist); });
    const Score s = score(
        sep, n, [&](std::size_t i) { return hit[i] != 0; }, [&](std::size_t i) { return depth[i]; },
        [&](std::size_t i) { return dist[i]; });
    emit("bullet", m.name, "sse", ms, n, s, m.depth, m.dist, reps);
  }
#else
  (void)p, (void)sep, (void)n, (void)reps;
  std::printf("# bullet not installed\n");
#endif
}

void run_ccd(const BoxPairs& p, const std::vector<double>& sep, std::size_t n, int reps) {
  if (!ccd_available()) {
    std::printf("# libccd not installed\n");
    return;
  }
  PairResults r;
  const struct {
    CcdMethod m;
    const char* name;
    bool depth;
  } methods[] = {{CcdMethod::gjk_intersect, "ccdGJKIntersect", false},
                 {CcdMethod::mpr_intersect, "ccdMPRIntersect", false},
                 {CcdMethod::gjk_epa_penetration, "ccdGJKPenetration", true},
                 {CcdMethod::mpr_penetration, "ccdMPRPenetration", true}};
  for (const auto& m : methods) {
    const double ms = median_ms(reps, [&] { ccd_box_box(p, n, m.m, r); });
    const Score s = score(
        sep, n, [&](std::size_t i) { return r.hit[i] != 0; }, [&](std::size_t i) { return r.depth[i]; },
        [](std::size_t) { return kNan; });
    emit("libccd", m.name, "double", ms, n, s, m.depth, false, reps);
  }
}

}  // namespace

void run_gjk(const Options& o) {
  const std::size_t n = 1000000;
  const BoxPairs p = testing::n1_pairs(n);
  if (p.fnv() != testing::kN1BoxesFnv) std::printf("# WARNING: N1 boxes hash mismatch: generator differs from BENCHMARKS.md\n");
  std::vector<double> sep(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) sep[i] = testing::ref_obb_obb_separation(p.a, i, p.b, i);
  std::size_t overlapping_pairs = 0;
  for (double s : sep) overlapping_pairs += s <= 0;
  std::printf("# GJK: N1's %zu OBB pairs as generic convex shapes; binary64 SAT: %zu overlapping; 1 thread\n", n,
              overlapping_pairs);
  run_gyro(p, sep, n, o.reps);
  run_gyro_batch(p, sep, n, o);
  run_gyro_capi(p, sep, n, o.reps);
  if (!o.peers) return;
  const int peer_reps = std::max(1, std::min(o.reps, 3));
  run_ccd(p, sep, n, peer_reps);
  run_bullet(p, sep, n, peer_reps);
}

}  // namespace gyro::bench
