// GJK and EPA (gyro/convex.hpp) against references:
//  - N1 (BENCHMARKS.md, the first 10^5 pairs; 2*10^4 in a Debug build): the boolean verdict
//    agrees with the binary64 15-axis SAT (tests/support/reference.hpp) on every pair whose
//    SAT separation is outside the band |sep| <= 1e-4 (touching counts as overlapping);
//    EPA's depth agrees with the SAT depth to 1e-4, and the boxes' overlap along EPA's
//    normal (computed in binary64) equals that depth to 1e-4, so the normal is a
//    minimum-translation direction. No pair may end at an iteration limit.
//  - Random hull pairs: GJK distance against a binary64 brute force over all feature pairs
//    (vertex-triangle and edge-edge), to 2e-6 of the pair's size; witness points on the
//    hulls and distance apart.
//  - The degenerate set: touching (face, edge, vertex), 2-point exits, flat Minkowski
//    differences, 1e-4 thin boxes, 100:1 and 1000:1 sizes, coincident centres, identical
//    shapes, 1e4 from the origin, NaN input: no NaN and no wrong verdict.
//  - The box-pair batches: every output bit of the scalar query at every SIMD level.
//  - Determinism: a hash of every output bit over a fixed mixed set, pinned.
#include "gyro/convex.hpp"
#include "gyro/runtime.hpp"
#include "reference.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

#ifdef NDEBUG
constexpr std::size_t kN1Pairs = 100000;
#else
constexpr std::size_t kN1Pairs = 20000;
#endif

ConvexPose pose_of(const testing::BoxSet& s, std::size_t i) {
  ConvexPose p;
  p.position = {s.cx[i], s.cy[i], s.cz[i]};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) p.rotation.m[k][c] = s.r[3 * c + k][i];  // row k = local axis k = column k of R
  return p;
}

ConvexShape box_of(const testing::BoxSet& s, std::size_t i) {
  ConvexShape b;
  EXPECT_EQ(make_box({s.hx[i], s.hy[i], s.hz[i]}, b), Status::ok);
  return b;
}

bool finite_result(const ConvexResult& r) {
  return std::isfinite(r.distance) && is_finite(r.normal) && is_finite(r.point_a) && is_finite(r.point_b);
}

// Overlap of two boxes along unit axis n, in binary64: (ra + rb) - |d . n|.
double box_overlap_along(const testing::BoxSet& A, const testing::BoxSet& B, std::size_t i, const vec3& nf) {
  const double n[3] = {nf.x, nf.y, nf.z};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  auto radius = [&](const testing::BoxSet& s) {
    const double h[3] = {s.hx[i], s.hy[i], s.hz[i]};
    double r = 0;
    for (int k = 0; k < 3; ++k)
      r += h[k] * std::abs(s.r[k][i] * n[0] + s.r[3 + k][i] * n[1] + s.r[6 + k][i] * n[2]) / len;
    return r;
  };
  const double d = (double(B.cx[i]) - A.cx[i]) * n[0] + (double(B.cy[i]) - A.cy[i]) * n[1] +
                   (double(B.cz[i]) - A.cz[i]) * n[2];
  return radius(A) + radius(B) - std::abs(d / len);
}

TEST(GjkN1, VerdictsAndEpaDepthAgreeWithSat) {
  const testing::BoxPairs p = testing::n1_pairs(kN1Pairs);
  std::size_t ref_overlap = 0, gjk_overlap = 0, disagree = 0, disagree_band = 0, limits = 0, nan = 0;
  std::size_t epa_pairs = 0, depth_bad = 0, normal_bad = 0;
  double max_depth_err = 0, max_normal_err = 0;
  for (std::size_t i = 0; i < kN1Pairs; ++i) {
    const double sep = testing::ref_obb_obb_separation(p.a, i, p.b, i);
    const ConvexShape a = box_of(p.a, i), b = box_of(p.b, i);
    const ConvexPose pa = pose_of(p.a, i), pb = pose_of(p.b, i);
    const ConvexResult r = convex_intersect(a, pa, b, pb);
    nan += !finite_result(r);
    limits += r.status == ConvexStatus::iteration_limit;
    const bool hit = overlapping(r.status), ref = sep <= 0;
    ref_overlap += ref, gjk_overlap += hit;
    if (hit != ref) (std::abs(sep) <= 1e-4 ? disagree_band : disagree) += 1;
    if (sep < -1e-4) {
      const ConvexResult e = convex_penetration(a, pa, b, pb);
      ++epa_pairs;
      nan += !finite_result(e);
      limits += e.status == ConvexStatus::iteration_limit;
      const double depth = -double(e.distance), err = std::abs(depth - -sep);
      max_depth_err = std::max(max_depth_err, err);
      depth_bad += err > 1e-4;
      const double along = box_overlap_along(p.a, p.b, i, e.normal), nerr = std::abs(along - depth);
      max_normal_err = std::max(max_normal_err, nerr);
      normal_bad += nerr > 1e-4 || std::abs(length(e.normal) - 1.0f) > 1e-5f;
    }
  }
  std::printf("[ N1 %zu pairs ] SAT overlapping %zu, GJK overlapping %zu, disagreements %zu outside and %zu inside "
              "|sep| <= 1e-4, iteration limits %zu\n",
              kN1Pairs, ref_overlap, gjk_overlap, disagree, disagree_band, limits);
  std::printf("[ N1 EPA ] %zu pairs with depth > 1e-4: max depth error %.3g (%zu > 1e-4), max |overlap along normal - "
              "depth| %.3g (%zu > 1e-4)\n",
              epa_pairs, max_depth_err, depth_bad, max_normal_err, normal_bad);
  EXPECT_EQ(nan, 0u);
  EXPECT_EQ(limits, 0u);
  EXPECT_EQ(disagree, 0u);
  EXPECT_EQ(depth_bad, 0u);
  EXPECT_EQ(normal_bad, 0u);
}

// ---- binary64 brute-force distance between two polytopes ----

struct P3 {
  double x, y, z;
};
P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
P3 operator*(P3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
P3 p3(const vec3& v) { return {v.x, v.y, v.z}; }

// Ericson, Real-Time Collision Detection 5.1.5.
P3 closest_on_triangle(P3 p, P3 a, P3 b, P3 c) {
  const P3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const P3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const P3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double den = 1 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

// Ericson 5.1.9: squared distance between segments p1q1 and p2q2.
double segment_segment_sq(P3 p1, P3 q1, P3 p2, P3 q2) {
  const P3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s, t;
  if (a <= 1e-300 && e <= 1e-300) return dot(r, r);
  if (a <= 1e-300) {
    s = 0, t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 1e-300) {
      t = 0, s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), den = a * e - b * b;
      s = den != 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  const P3 x = (p1 + d1 * s) - (p2 + d2 * t);
  return dot(x, x);
}

struct WorldHull {
  std::vector<P3> v;
  std::vector<std::array<int, 3>> tri;
  std::vector<std::pair<int, int>> edges;
};

WorldHull world_hull(const ConvexHull& h, const ConvexPose& pose) {
  WorldHull w;
  for (const vec3& v : h.vertices) {
    const vec3 x = v * pose.rotation;  // rotation in float, translation in double
    w.v.push_back(P3{x.x, x.y, x.z} + p3(pose.position));
  }
  for (std::size_t f = 0; f < h.face_count(); ++f)
    for (uint32_t k = h.face_start[f] + 1; k + 1 < h.face_start[f + 1]; ++k)
      w.tri.push_back({int(h.face_vertices[h.face_start[f]]), int(h.face_vertices[k]), int(h.face_vertices[k + 1])});
  for (std::size_t e = 0; e < h.edge_count(); ++e) w.edges.push_back({int(h.edges[2 * e]), int(h.edges[2 * e + 1])});
  return w;
}

double brute_distance(const WorldHull& a, const WorldHull& b) {
  double best = 1e300;
  for (int pass = 0; pass < 2; ++pass) {
    const WorldHull& x = pass ? b : a;
    const WorldHull& y = pass ? a : b;
    for (const P3& p : x.v)
      for (const auto& t : y.tri) {
        const P3 q = closest_on_triangle(p, y.v[t[0]], y.v[t[1]], y.v[t[2]]) - p;
        best = std::min(best, dot(q, q));
      }
  }
  for (const auto& e : a.edges)
    for (const auto& f : b.edges) best = std::min(best, segment_segment_sq(a.v[e.first], a.v[e.second], b.v[f.first], b.v[f.second]));
  return std::sqrt(best);
}

mat3 random_rotation(SplitMix64& rng) {
  // A normalised random quaternion (only sqrt), to a rotation whose rows are the axes.
  double q[4], n = 0;
  for (double& c : q) c = 2 * rng.u() - 1, n += c * c;
  n = std::sqrt(n);
  const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
  mat3 m;
  m.m[0][0] = float(1 - 2 * (y * y + z * z)), m.m[0][1] = float(2 * (x * y + z * w)), m.m[0][2] = float(2 * (x * z - y * w));
  m.m[1][0] = float(2 * (x * y - z * w)), m.m[1][1] = float(1 - 2 * (x * x + z * z)), m.m[1][2] = float(2 * (y * z + x * w));
  m.m[2][0] = float(2 * (x * z + y * w)), m.m[2][1] = float(2 * (y * z - x * w)), m.m[2][2] = float(1 - 2 * (x * x + y * y));
  return m;
}

std::vector<vec3> random_cloud(SplitMix64& rng, int n, float scale) {
  std::vector<vec3> pts;
  while (int(pts.size()) < n) {
    const vec3 p{float(2 * rng.u() - 1), float(2 * rng.u() - 1), float(2 * rng.u() - 1)};
    if (dot(p, p) <= 1.0f) pts.push_back(p * scale);
  }
  return pts;
}

TEST(GjkDistance, RandomHullPairsMatchBinary64BruteForce) {
  SplitMix64 rng(81);
  double max_err = 0, max_witness = 0;
  int separated = 0, overlapping_pairs = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::vector<vec3> ca = random_cloud(rng, 6 + int(rng.u() * 20), 1.0f);
    // Draws first, in the order g++ evaluated these arguments (right to left; clang++ goes
    // left to right, and would test other pairs).
    const float scale_b = float(0.2 + rng.u());
    const int count_b = 6 + int(rng.u() * 20);
    const std::vector<vec3> cb = random_cloud(rng, count_b, scale_b);
    ConvexHull ha, hb;
    ASSERT_EQ(build_convex_hull(ca.data(), ca.size(), ha), Status::ok);
    ASSERT_EQ(build_convex_hull(cb.data(), cb.size(), hb), Status::ok);
    ConvexPose pa, pb;
    pa.rotation = random_rotation(rng), pb.rotation = random_rotation(rng);
    pa.position = {float(rng.u() * 4 - 2), float(rng.u() * 4 - 2), float(rng.u() * 4 - 2)};
    pb.position = pa.position + vec3{float(rng.u() * 5 - 2.5), float(rng.u() * 5 - 2.5), float(rng.u() * 5 - 2.5)};
    const ConvexShape sa = ha.shape(), sb = hb.shape();
    const ConvexResult r = convex_distance(sa, pa, sb, pb);
    ASSERT_TRUE(finite_result(r));
    const WorldHull wa = world_hull(ha, pa), wb = world_hull(hb, pb);
    const double ref = brute_distance(wa, wb);
    if (r.status == ConvexStatus::separated) {
      ++separated;
      const double err = std::abs(double(r.distance) - ref);
      max_err = std::max(max_err, err);
      EXPECT_LE(err, 2e-6 * 6) << "trial " << trial;
      // Witnesses: distance apart along the normal, and on their hulls (inside every plane).
      EXPECT_NEAR(distance(r.point_a, r.point_b), r.distance, 1e-5);
      auto outside = [](const ConvexHull& h, const ConvexPose& p, const vec3& w) {
        const vec3 local = (w - p.position) * transpose(p.rotation);
        float m = -1e30f;
        for (const Plane& pl : h.planes) m = std::max(m, dot(pl.normal, local) - pl.distance);
        return m;
      };
      max_witness = std::max({max_witness, double(outside(ha, pa, r.point_a)), double(outside(hb, pb, r.point_b))});
    } else {
      ++overlapping_pairs;
      // Overlapping hulls have no separating feature pair far apart; the brute force is
      // only a distance between boundaries there, so check the penetration instead.
      const ConvexResult e = convex_penetration(sa, pa, sb, pb);
      ASSERT_TRUE(finite_result(e));
      EXPECT_TRUE(overlapping(e.status) || e.status == ConvexStatus::separated);
      EXPECT_LE(e.distance, 1e-5f);
      // Moving B by depth along the normal (plus a margin) separates the hulls.
      ConvexPose moved = pb;
      moved.position = pb.position + e.normal * (-e.distance + 1e-3f);
      EXPECT_EQ(convex_intersect(sa, pa, sb, moved).status, ConvexStatus::separated) << "trial " << trial;
    }
  }
  std::printf("[ hull pairs ] %d separated (max |distance - binary64| %.3g, witnesses at most %.3g outside their hull), "
              "%d overlapping\n",
              separated, max_err, max_witness, overlapping_pairs);
  EXPECT_GT(separated, 100);
  EXPECT_GT(overlapping_pairs, 10);
  EXPECT_LE(max_witness, 1e-5);
}

// ---- the degenerate set ----

ConvexShape box(float x, float y, float z) {
  ConvexShape s;
  EXPECT_EQ(make_box({x, y, z}, s), Status::ok);
  return s;
}
ConvexPose at(float x, float y, float z) {
  ConvexPose p;
  p.position = {x, y, z};
  return p;
}
ConvexPose rotated_z45(float x, float y, float z) {
  ConvexPose p = at(x, y, z);
  const float c = 0.70710678f;
  p.rotation = mat3{{{c, c, 0}, {-c, c, 0}, {0, 0, 1}}};
  return p;
}

struct Case {
  const char* name;
  ConvexShape a;
  ConvexPose pa;
  ConvexShape b;
  ConvexPose pb;
  int expect;      // 0 separated, 1 touching (either touching or a depth/gap within tol), 2 intersecting
  float distance;  // expected signed distance (penetration: -depth)
  float tol;
};

void check_case(const Case& c, const vec3& shift) {
  ConvexPose pa = c.pa, pb = c.pb;
  pa.position += shift, pb.position += shift;
  const ConvexResult ri = convex_intersect(c.a, pa, c.b, pb);
  const ConvexResult rd = convex_distance(c.a, pa, c.b, pb);
  const ConvexResult rp = convex_penetration(c.a, pa, c.b, pb);
  for (const ConvexResult* r : {&ri, &rd, &rp}) {
    EXPECT_TRUE(finite_result(*r)) << c.name;
    EXPECT_NE(r->status, ConvexStatus::iteration_limit) << c.name;
    EXPECT_NE(r->status, ConvexStatus::invalid_input) << c.name;
    if (c.expect == 0) { EXPECT_EQ(r->status, ConvexStatus::separated) << c.name; }
    if (c.expect == 1) { EXPECT_TRUE(r->status == ConvexStatus::touching || std::abs(r->distance) <= c.tol) << c.name; }
    if (c.expect == 2) { EXPECT_EQ(r->status, ConvexStatus::intersecting) << c.name; }
  }
  EXPECT_NEAR(rp.distance, c.distance, c.tol) << c.name << " shifted by " << shift.x;
  if (c.expect == 0) { EXPECT_NEAR(rd.distance, c.distance, c.tol) << c.name; }
  if (rp.status == ConvexStatus::intersecting) {
    // The witnesses are depth apart along the normal.
    EXPECT_NEAR(dot(rp.point_b - rp.point_a, rp.normal), rp.distance, c.tol + 1e-5f * length(shift)) << c.name;
  }
}

std::vector<Case> degenerate_cases() {
  std::vector<Case> v;
  ConvexShape sph1, sph2, cap, cap2, cyl, tri1, tri2, pt, seg;
  make_sphere(1.0f, sph1), make_sphere(0.5f, sph2), make_capsule(0.5f, 1.0f, cap), make_capsule(0.25f, 2.0f, cap2);
  make_cylinder(1.0f, 1.0f, cyl);
  make_triangle({-1, 0, -1}, {1, 0, -1}, {0, 0, 1}, tri1), make_triangle({-1, 0, 1}, {1, 0, 1}, {0, 0, -1}, tri2);
  static const vec3 one_point[1] = {{0, 0, 0}};
  static const vec3 two_points[3] = {{-1, 0, 0}, {1, 0, 0}, {0.25f, 0, 0}};  // collinear cloud = segment
  make_convex_points(one_point, 1, pt), make_convex_points(two_points, 3, seg);
  const ConvexShape b1 = box(1, 1, 1);
  v.push_back({"faces touching", b1, at(0, 0, 0), b1, at(2, 0, 0), 1, 0.0f, 1e-5f});
  v.push_back({"faces touching, offset", b1, at(0, 0, 0), b1, at(2, 0.5f, 0.25f), 1, 0.0f, 1e-5f});
  v.push_back({"edge on face", b1, at(0, 0, 0), b1, rotated_z45(1 + 1.41421356f, 0, 0), 1, 0.0f, 1e-5f});
  v.push_back({"gap 1e-3", b1, at(0, 0, 0), b1, at(2.001f, 0, 0), 0, 0.001f, 1e-6f});
  v.push_back({"overlap 1e-3", b1, at(0, 0, 0), b1, at(1.999f, 0.3f, 0), 2, -0.001f, 1e-6f});
  v.push_back({"vertex to vertex", b1, at(0, 0, 0), b1, at(2, 2, 2), 1, 0.0f, 1e-5f});
  v.push_back({"2-point exit: edge to edge gap", b1, at(0, 0, 0), b1, rotated_z45(1 + 1.41421356f + 0.5f, 0, 0), 0, 0.5f, 1e-5f});
  v.push_back({"spheres apart", sph1, at(0, 0, 0), sph2, at(3, 0, 0), 0, 1.5f, 1e-6f});
  v.push_back({"spheres overlapping", sph1, at(0, 0, 0), sph2, at(1, 0, 0), 2, -0.5f, 1e-6f});
  v.push_back({"spheres concentric", sph1, at(0, 0, 0), sph2, at(0, 0, 0), 2, -1.5f, 1e-6f});
  v.push_back({"capsules parallel (segment exit)", cap, at(0, 0, 0), cap, at(1.5f, 0.5f, 0), 0, 0.5f, 1e-6f});
  v.push_back({"capsules crossing", cap, at(0, 0, 0), cap2, rotated_z45(0.2f, 0, 0), 2, -0.75f, 1e-5f});
  v.push_back({"sphere centre inside box", b1, at(0, 0, 0), sph2, at(0.8f, 0, 0), 2, -0.7f, 1e-5f});
  v.push_back({"cylinder on box", cyl, at(0, 0, 0), b1, at(0, 2.5f, 0), 0, 0.5f, 1e-5f});
  v.push_back({"cylinder side touching box", cyl, at(0, 0, 0), b1, at(2, 0, 0), 1, 0.0f, 1e-4f});
  v.push_back({"coplanar triangles (flat difference)", tri1, at(0, 0, 0), tri2, at(0, 0, 0), 1, 0.0f, 1e-5f});
  v.push_back({"triangle through box", tri1, at(0, 0.3f, 0), b1, at(0, 0, 0), 2, -0.7f, 1e-5f});
  v.push_back({"point in box", pt, at(0.5f, 0, 0), b1, at(0, 0, 0), 2, -0.5f, 1e-5f});
  v.push_back({"segment cloud vs box", seg, at(0, 1.25f, 0), b1, at(0, 0, 0), 0, 0.25f, 1e-6f});
  v.push_back({"point on point", pt, at(0, 0, 0), pt, at(0, 0, 0), 1, 0.0f, 1e-6f});
  const ConvexShape flat = box(1, 1e-4f, 1);
  v.push_back({"flat boxes apart", flat, at(0, 0, 0), flat, at(0.5f, 3e-4f, 0), 0, 1e-4f, 1e-6f});
  v.push_back({"flat boxes overlapping", flat, at(0, 0, 0), flat, at(0.5f, 1.5e-4f, 0), 2, -0.5e-4f, 1e-6f});
  v.push_back({"flat box on box", flat, at(0, 1.0001f, 0), b1, at(0, 0, 0), 1, 0.0f, 1e-5f});
  v.push_back({"ratio 100:1 apart", box(10, 10, 10), at(0, 0, 0), box(0.1f, 0.1f, 0.1f), at(10.11f, 3, 3), 0, 0.01f, 2e-5f});
  v.push_back({"ratio 100:1 overlap", box(10, 10, 10), at(0, 0, 0), box(0.1f, 0.1f, 0.1f), at(10.09f, 3, 3), 2, -0.01f, 2e-5f});
  v.push_back({"ratio 1000:1 apart", box(100, 100, 100), at(0, 0, 0), box(0.1f, 0.1f, 0.1f), rotated_z45(100.2f, 5, 5), 0, 0.2f - 0.141421356f, 2e-4f});
  v.push_back({"ratio 1000:1 overlap", box(100, 100, 100), at(0, 0, 0), box(0.1f, 0.1f, 0.1f), at(100.05f, 5, 5), 2, -0.05f, 2e-4f});
  v.push_back({"coincident boxes", b1, at(0, 0, 0), box(1, 2, 3), at(0, 0, 0), 2, -2.0f, 1e-5f});
  v.push_back({"identical boxes", box(0.5f, 1, 2), rotated_z45(0, 0, 0), box(0.5f, 1, 2), rotated_z45(0, 0, 0), 2, -1.0f, 1e-5f});
  v.push_back({"identical capsules", cap, at(0, 0, 0), cap, at(0, 0, 0), 2, -1.0f, 1e-5f});
  return v;
}

TEST(GjkDegenerate, NoNanNoWrongVerdict) {
  for (const Case& c : degenerate_cases()) {
    SCOPED_TRACE(c.name);
    check_case(c, vec3{});
  }
}

TEST(GjkDegenerate, FarFromOriginSameAnswers) {
  // 1e4 from the origin the float positions are multiples of 2^-10, so only cases whose
  // coordinates are such multiples are exact there; the tolerance grows by the ulp.
  for (Case c : degenerate_cases()) {
    SCOPED_TRACE(c.name);
    c.tol += 2e-3f;
    if (c.expect == 0 && c.distance < 3e-3f) continue;  // gap below the positions' resolution
    if (c.expect == 2 && -c.distance < 3e-3f) c.expect = 1;
    check_case(c, vec3{1e4f, -1e4f, 1e4f});
  }
}

TEST(GjkDegenerate, BadInputGivesInvalidInputAndNoNan) {
  const ConvexShape b1 = box(1, 1, 1);
  ConvexPose bad = at(0, 0, 0);
  bad.position.x = std::nanf("");
  for (const ConvexResult& r : {convex_intersect(b1, bad, b1, at(1, 0, 0)), convex_distance(b1, at(0, 0, 0), b1, bad),
                                convex_penetration(b1, bad, b1, bad)}) {
    EXPECT_EQ(r.status, ConvexStatus::invalid_input);
    EXPECT_TRUE(finite_result(r));
    EXPECT_STRNE(last_error(), "");
  }
  ConvexShape s;
  EXPECT_EQ(make_sphere(-1.0f, s), Status::invalid_argument);
  EXPECT_EQ(make_box({1, std::nanf(""), 1}, s), Status::non_finite);
  EXPECT_EQ(make_convex_points(nullptr, 3, s), Status::null_argument);
  EXPECT_EQ(make_convex_points(nullptr, 0, s), Status::invalid_count);
  ConvexShape raw = b1;
  raw.half_extents.y = -1.0f;  // filled by hand, bypassing make_box
  EXPECT_EQ(convex_penetration(raw, at(0, 0, 0), b1, at(0, 0, 0)).status, ConvexStatus::invalid_input);
}

TEST(GjkDegenerate, IterationLimitIsReportedNotSeparated) {
  // Enclosing the origin takes at least 3 iterations: one is not enough for overlapping clouds.
  SplitMix64 rng(5);
  const std::vector<vec3> cloud = random_cloud(rng, 200, 1.0f);
  ConvexShape s;
  ASSERT_EQ(make_convex_points(cloud.data(), cloud.size(), s), Status::ok);
  ConvexQueryOptions o;
  o.max_gjk_iterations = 1;
  const ConvexResult r = convex_distance(s, at(0, 0, 0), s, at(0.5f, 0.3f, 0.1f), o);
  EXPECT_EQ(r.status, ConvexStatus::iteration_limit);
  EXPECT_TRUE(finite_result(r));
  o.max_gjk_iterations = 64;
  o.max_epa_iterations = 1;
  const ConvexResult e = convex_penetration(s, at(0, 0, 0), s, at(0.5f, 0.3f, 0.1f), o);
  EXPECT_EQ(e.status, ConvexStatus::iteration_limit);
  EXPECT_TRUE(finite_result(e));
}

// ---- the batch queries ----

// N1 pairs plus hand-made ones: invalid (NaN, negative size), huge coordinates and a
// non-rotation (the scalar fallback), faces touching exactly and coincident boxes (EPA
// inside the batch), at a count that leaves a tail at every width.
testing::BoxPairs batch_pairs() {
  testing::BoxPairs p = testing::n1_pairs(20000 + 13);
  p.a.hx[0] = -1.0f;                    // negative size
  p.b.cy[1] = std::nanf("");            // NaN position
  p.a.cx[2] = 3e37f, p.b.cx[2] = 3e37f;  // beyond the batch's range
  p.b.r[0][3] = 5.0f;                   // not a rotation
  auto axis_aligned = [](testing::BoxSet& s, std::size_t i, float cx, float h) {
    s.cx[i] = cx, s.cy[i] = 0.0f, s.cz[i] = 0.0f, s.hx[i] = s.hy[i] = s.hz[i] = h;
    for (int e = 0; e < 9; ++e) s.r[e][i] = (e % 4 == 0) ? 1.0f : 0.0f;
  };
  axis_aligned(p.a, 4, 0.0f, 1.0f), axis_aligned(p.b, 4, 2.0f, 1.0f);  // faces touching
  axis_aligned(p.a, 5, 0.0f, 1.0f), axis_aligned(p.b, 5, 0.0f, 0.5f);  // same centre
  axis_aligned(p.a, 6, 0.0f, 1.0f), axis_aligned(p.b, 6, 1.0f, 1.0f);  // half overlapping
  return p;
}

ConvexBoxPairs soa_view(const testing::BoxPairs& p) {
  ConvexBoxPairs pairs;
  auto fill = [](const testing::BoxSet& s, const float* (&c)[3], const float* (&h)[3], const float* (&r)[9]) {
    c[0] = s.cx.data(), c[1] = s.cy.data(), c[2] = s.cz.data();
    h[0] = s.hx.data(), h[1] = s.hy.data(), h[2] = s.hz.data();
    for (int k = 0; k < 3; ++k)
      for (int col = 0; col < 3; ++col) r[3 * k + col] = s.r[3 * col + k].data();
  };
  fill(p.a, pairs.a_center, pairs.a_half, pairs.a_rot);
  fill(p.b, pairs.b_center, pairs.b_half, pairs.b_rot);
  return pairs;
}

ConvexShape raw_box(const testing::BoxSet& s, std::size_t i) {
  ConvexShape b;
  b.type = ConvexType::box;
  b.half_extents = {s.hx[i], s.hy[i], s.hz[i]};  // unchecked: the invalid ones must reach the query
  return b;
}

const SimdLevel kLevels[] = {SimdLevel::scalar, SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon};

TEST(GjkBatch, BoxPairsMatchScalarIntersectAtEveryLevel) {
  const testing::BoxPairs p = batch_pairs();
  const std::size_t n = p.a.cx.size();
  const ConvexBoxPairs pairs = soa_view(p);
  // The default options, and a GJK iteration limit low enough that some pairs reach it.
  ConvexQueryOptions short_opt;
  short_opt.max_gjk_iterations = 2;
  for (const ConvexQueryOptions& opt : {ConvexQueryOptions{}, short_opt}) {
    std::vector<ConvexStatus> ref(n);
    for (std::size_t i = 0; i < n; ++i)
      ref[i] = convex_intersect(raw_box(p.a, i), pose_of(p.a, i), raw_box(p.b, i), pose_of(p.b, i), opt).status;
    EXPECT_EQ(ref[0], ConvexStatus::invalid_input);
    EXPECT_EQ(ref[1], ConvexStatus::invalid_input);
    EXPECT_TRUE(overlapping(ref[4]) && overlapping(ref[5]) && overlapping(ref[6]));
    std::size_t overlapping_pairs = 0, limits = 0;
    for (ConvexStatus st : ref) overlapping_pairs += overlapping(st), limits += st == ConvexStatus::iteration_limit;
    // Two iterations decide the separated pairs; most overlapping ones need more.
    EXPECT_GT(opt.max_gjk_iterations == 2 ? limits : overlapping_pairs, 100u);
    int ran = 0;
    for (SimdLevel level : kLevels) {
      if (!simd_level_available(level)) continue;
      set_simd_level(level);
      ++ran;
      std::vector<ConvexStatus> out(n, ConvexStatus::iteration_limit);
      convex_intersect_batch(pairs, n, out.data(), opt);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < n; ++i) differ += out[i] != ref[i];
      EXPECT_EQ(differ, 0u) << simd_level_name(level) << " max_gjk_iterations " << opt.max_gjk_iterations;
    }
    set_simd_level(SimdLevel::automatic);
    EXPECT_GE(ran, 1);
  }
}

// The whole-result batches (convex_intersect_batch's ConvexResult form, convex_distance_batch
// and convex_penetration_batch): every output bit of the scalar query, at every level, with
// the default options, with a GJK iteration limit that some pairs reach (the lanes then form
// an iteration_limit result), and with separated_distance off (penetration's separated pairs
// stop at a separating axis).
TEST(GjkBatch, IntersectDistanceAndPenetrationMatchScalarAtEveryLevel) {
  const testing::BoxPairs p = batch_pairs();
  const std::size_t n = p.a.cx.size();
  const ConvexBoxPairs pairs = soa_view(p);
  ConvexQueryOptions short_opt, early_opt, early_short_opt;
  short_opt.max_gjk_iterations = 2;
  early_opt.separated_distance = false;
  early_short_opt.separated_distance = false, early_short_opt.max_gjk_iterations = 2;
  for (const ConvexQueryOptions& opt : {ConvexQueryOptions{}, short_opt, early_opt, early_short_opt}) {
    for (int mode = 0; mode < 3; ++mode) {  // intersect, distance, penetration
      std::vector<ConvexResult> ref(n);
      std::size_t limits = 0, separated = 0, overlapping_pairs = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const ConvexShape a = raw_box(p.a, i), b = raw_box(p.b, i);
        ref[i] = mode == 0 ? convex_intersect(a, pose_of(p.a, i), b, pose_of(p.b, i), opt)
                 : mode == 1 ? convex_distance(a, pose_of(p.a, i), b, pose_of(p.b, i), opt)
                             : convex_penetration(a, pose_of(p.a, i), b, pose_of(p.b, i), opt);
        limits += ref[i].status == ConvexStatus::iteration_limit;
        separated += ref[i].status == ConvexStatus::separated;
        overlapping_pairs += overlapping(ref[i].status);
      }
      EXPECT_EQ(ref[0].status, ConvexStatus::invalid_input);
      EXPECT_GT(separated, 100u);
      EXPECT_GT(opt.max_gjk_iterations == 2 ? limits : overlapping_pairs, 100u);
      for (SimdLevel level : kLevels) {
        if (!simd_level_available(level)) continue;
        set_simd_level(level);
        std::vector<ConvexResult> out(n);
        if (mode == 0) convex_intersect_batch(pairs, n, out.data(), opt);
        else if (mode == 1) convex_distance_batch(pairs, n, out.data(), opt);
        else convex_penetration_batch(pairs, n, out.data(), opt);
        std::size_t differ = 0;
        for (std::size_t i = 0; i < n; ++i) differ += std::memcmp(&out[i], &ref[i], sizeof(ConvexResult)) != 0;
        EXPECT_EQ(differ, 0u) << simd_level_name(level) << " mode " << mode
                              << " max_gjk_iterations " << opt.max_gjk_iterations << " separated_distance "
                              << opt.separated_distance;
      }
      set_simd_level(SimdLevel::automatic);
    }
  }
}

// separated_distance off changes only what a separated pair reports: every overlapping
// pair's result keeps its bits (GJK takes the same path to the enclosing simplex), every
// separated pair stays separated with a distance no smaller than the converged one (|v| only
// decreases along the way), and the early stop saves iterations.
TEST(GjkPenetration, SeparatedDistanceOffKeepsOverlapsBitForBit) {
  const testing::BoxPairs p = testing::n1_pairs(20000);
  ConvexQueryOptions early;
  early.separated_distance = false;
  std::size_t overlaps = 0, separated = 0, it_full = 0, it_early = 0;
  for (std::size_t i = 0; i < p.a.cx.size(); ++i) {
    const ConvexShape a = raw_box(p.a, i), b = raw_box(p.b, i);
    const ConvexResult full = convex_penetration(a, pose_of(p.a, i), b, pose_of(p.b, i));
    const ConvexResult fast = convex_penetration(a, pose_of(p.a, i), b, pose_of(p.b, i), early);
    ASSERT_NE(full.status, ConvexStatus::iteration_limit) << i;
    if (overlapping(full.status)) {
      ++overlaps;
      EXPECT_EQ(std::memcmp(&full, &fast, sizeof(ConvexResult)), 0) << i;
    } else {
      ++separated;
      EXPECT_EQ(fast.status, ConvexStatus::separated) << i;
      EXPECT_GE(fast.distance, full.distance) << i;
      it_full += full.iterations, it_early += fast.iterations;
    }
  }
  EXPECT_GT(overlaps, 1000u);
  EXPECT_GT(separated, 10000u);
  EXPECT_LT(double(it_early), 0.8 * double(it_full));
}

// Box pairs separated along one of their six face normals stop before GJK's loop (intersect,
// and penetration without a separated distance): their verdicts must be those of GJK run to
// convergence, for rotations and for poses that are not (B's axes sheared and scaled: the
// probe's extents hold for any linear B), flat boxes included. Where the probe answers, the
// reported distance is |w| for a point w of A - B: never below the converged distance.
// (convex_penetration is the converged reference: it has no early exit, and its distance is
// signed.)
TEST(GjkFaceAxes, ProbeVerdictsMatchConvergedGjk) {
  SplitMix64 rng(77);
  std::size_t separated = 0, first_exits = 0, overlapping_pairs = 0, sheared = 0, compared = 0;
  for (int i = 0; i < 20000; ++i) {
    ConvexShape a, b;
    const float flat = i % 10 == 0 ? 0.01f : 1.0f;  // every tenth A is a 100:1 plate
    ASSERT_EQ(make_box({0.1f + float(rng.u()), flat * (0.1f + float(rng.u())), 0.1f + float(rng.u())}, a), Status::ok);
    ASSERT_EQ(make_box({0.1f + float(rng.u()), 0.1f + float(rng.u()), 0.1f + float(rng.u())}, b), Status::ok);
    ConvexPose pa, pb;
    pa.rotation = random_rotation(rng), pb.rotation = random_rotation(rng);
    if (i % 3 == 0) {
      mat3 shear;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) shear.m[r][c] = r == c ? float(0.5 + rng.u()) : float(0.6 * (rng.u() - 0.5));
      pb.rotation = shear * pb.rotation;
      ++sheared;
    }
    pa.position = {float(3 * rng.u()), float(3 * rng.u()), float(3 * rng.u())};
    pb.position = {float(3 * rng.u()), float(3 * rng.u()), float(3 * rng.u())};
    const ConvexResult in = convex_intersect(a, pa, b, pb);
    const ConvexResult d = convex_penetration(a, pa, b, pb);  // converged: the signed distance
    ASSERT_NE(d.status, ConvexStatus::iteration_limit) << i;
    ASSERT_NE(in.status, ConvexStatus::iteration_limit) << i;
    if (std::fabs(d.distance) > 1e-4f) {  // outside the band around touching
      ++compared;
      EXPECT_EQ(overlapping(in.status), overlapping(d.status)) << i;
    }
    if (in.status == ConvexStatus::separated) {
      ++separated, first_exits += in.iterations == 0;
      EXPECT_GE(in.distance, d.distance * (1.0f - 1e-5f)) << i;
    } else {
      ++overlapping_pairs;
    }
  }
  EXPECT_GT(sheared, 6000u);
  EXPECT_GT(compared, 19000u);
  EXPECT_GT(overlapping_pairs, 1000u);
  EXPECT_GT(separated, 10000u);
  // Without the probe GJK's first iteration decided 41% of these separated pairs (5,737 of
  // 14,011); with it 94.7%.
  EXPECT_GT(double(first_exits), 0.9 * double(separated));
  std::printf("[ face axes ] %zu separated, %zu decided before GJK's second iteration\n", separated, first_exits);
}

// The batch runs EPA on up to 16 polytopes side by side (epa_boxes), with the supports, the
// planes, the closest-face search and the repeat test in lanes. Its outcome must be the
// scalar EPA's bit for bit on the hard cases too: 100:1 plates and 100:1 size ratios
// (sliver faces, coplanar closest faces), axis-aligned stacks (simplices of fewer than four
// points mixed into the queue), and an EPA iteration limit that many pairs reach.
TEST(GjkBatch, SideBySideEpaMatchesScalarOnHardPairs) {
  SplitMix64 rng(2026);
  constexpr std::size_t n = 3001;
  testing::BoxPairs p;
  for (testing::BoxSet* s : {&p.a, &p.b}) {
    for (auto* v : {&s->cx, &s->cy, &s->cz, &s->hx, &s->hy, &s->hz}) v->resize(n);
    for (auto& v : s->r) v.resize(n);
  }
  auto put = [](testing::BoxSet& s, std::size_t i, const vec3& c, const vec3& h, const mat3& rot) {
    s.cx[i] = c.x, s.cy[i] = c.y, s.cz[i] = c.z, s.hx[i] = h.x, s.hy[i] = h.y, s.hz[i] = h.z;
    for (int k = 0; k < 3; ++k)
      for (int c2 = 0; c2 < 3; ++c2) s.r[3 * c2 + k][i] = rot.m[k][c2];  // pose_of's inverse
  };
  for (std::size_t i = 0; i < n; ++i) {
    const int kind = int(i % 4);
    const float u = float(rng.u());
    vec3 ha{0.2f + float(rng.u()), 0.2f + float(rng.u()), 0.2f + float(rng.u())};
    vec3 hb{0.2f + float(rng.u()), 0.2f + float(rng.u()), 0.2f + float(rng.u())};
    mat3 ra = random_rotation(rng), rb = random_rotation(rng);
    vec3 cb{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
    if (kind == 1) ha.y *= 0.01f;                         // a 100:1 plate
    if (kind == 2) hb = hb * 0.01f, cb = cb * 2.0f;       // a 100:1 size ratio
    if (kind == 3) {                                      // axis-aligned stacks: flat contacts
      ra = rb = mat3{};
      cb = {0.5f * (u - 0.5f), ha.y + hb.y - 0.01f * u, 0.0f};
    }
    put(p.a, i, {0.0f, 0.0f, 0.0f}, ha, ra);
    put(p.b, i, cb, hb, rb);
  }
  const ConvexBoxPairs pairs = soa_view(p);
  ConvexQueryOptions limited;
  limited.max_epa_iterations = 2;
  for (const ConvexQueryOptions& opt : {ConvexQueryOptions{}, limited}) {
    std::vector<ConvexResult> ref(n);
    std::size_t epa_runs = 0, limits = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ref[i] = convex_penetration(raw_box(p.a, i), pose_of(p.a, i), raw_box(p.b, i), pose_of(p.b, i), opt);
      epa_runs += ref[i].distance <= 0.0f, limits += ref[i].status == ConvexStatus::iteration_limit;
    }
    EXPECT_GT(epa_runs, 2000u);
    if (opt.max_epa_iterations == 2) {
      EXPECT_GT(limits, 500u);
    }
    for (SimdLevel level : kLevels) {
      if (!simd_level_available(level)) continue;
      set_simd_level(level);
      std::vector<ConvexResult> out(n);
      convex_penetration_batch(pairs, n, out.data(), opt);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < n; ++i) differ += std::memcmp(&out[i], &ref[i], sizeof(ConvexResult)) != 0;
      EXPECT_EQ(differ, 0u) << simd_level_name(level) << " max_epa_iterations " << opt.max_epa_iterations;
    }
    set_simd_level(SimdLevel::automatic);
  }
}

// The batches cut the pairs into fixed chunks over the threads: every thread count gives the
// same bits (a count that leaves a partial chunk; invalid pairs in a chunk a worker runs),
// and the first invalid pair's message reaches the calling thread.
TEST(GjkBatch, SameBitsAtEveryThreadCount) {
  testing::BoxPairs p = testing::n1_pairs(5000 + 77);
  p.a.hx[4100] = -1.0f;  // invalid, in the fifth chunk
  p.b.cy[4500] = std::nanf("");
  const std::size_t n = p.a.cx.size();
  const ConvexBoxPairs pairs = soa_view(p);
  ConvexQueryOptions early;
  early.separated_distance = false;
  std::vector<ConvexResult> ref(n), out(n);
  std::vector<ConvexStatus> ref_st(n), out_st(n);
  for (int mode = 0; mode < 3; ++mode) {
    const auto call = [&](std::vector<ConvexResult>& r) {
      if (mode == 0) convex_distance_batch(pairs, n, r.data());
      else convex_penetration_batch(pairs, n, r.data(), mode == 1 ? ConvexQueryOptions{} : early);
    };
    set_thread_count(1);
    call(ref);
    convex_intersect_batch(pairs, n, ref_st.data());
    EXPECT_EQ(ref[4100].status, ConvexStatus::invalid_input);
    EXPECT_EQ(ref_st[4500], ConvexStatus::invalid_input);
    for (uint32_t threads : {2u, 3u, 4u}) {
      set_thread_count(threads);
      ConvexShape unused;
      ASSERT_NE(make_box({-1.0f, 1.0f, 1.0f}, unused), Status::ok);  // another message first
      ASSERT_EQ(std::string(last_error()).find("not finite"), std::string::npos);
      std::fill(out.begin(), out.end(), ConvexResult{});
      call(out);
      EXPECT_NE(std::string(last_error()).find("not finite"), std::string::npos) << last_error();
      ASSERT_NE(make_box({-1.0f, 1.0f, 1.0f}, unused), Status::ok);
      convex_intersect_batch(pairs, n, out_st.data());
      EXPECT_EQ(std::memcmp(out.data(), ref.data(), n * sizeof(ConvexResult)), 0) << "mode " << mode << " threads " << threads;
      EXPECT_EQ(out_st, ref_st) << threads;
      EXPECT_NE(std::string(last_error()).find("not finite"), std::string::npos) << last_error();
    }
  }
  set_thread_count(0);
}

TEST(GjkBatch, EmptyBatchWritesNothing) {
  const testing::BoxPairs p = testing::n1_pairs(1);
  const ConvexBoxPairs pairs = soa_view(p);
  ConvexResult r;
  r.distance = 42.0f;
  convex_distance_batch(pairs, 0, &r);
  convex_penetration_batch(pairs, 0, &r);
  EXPECT_EQ(r.distance, 42.0f);
}

// ---- determinism ----

uint64_t fnv(uint64_t h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

uint64_t hash_result(uint64_t h, const ConvexResult& r) {
  const uint32_t st = uint32_t(r.status);
  h = fnv(h, &st, 4);
  const float f[10] = {r.distance, r.normal.x, r.normal.y, r.normal.z, r.point_a.x, r.point_a.y, r.point_a.z,
                       r.point_b.x, r.point_b.y, r.point_b.z};
  for (float x : f) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    h = fnv(h, &bits, 4);
  }
  return fnv(h, &r.iterations, 4);
}

TEST(GjkDeterminism, PinnedHashOverMixedShapes) {
  SplitMix64 rng(1234);
  const std::vector<vec3> cloud = random_cloud(rng, 40, 0.8f);
  ConvexHull hull;
  ASSERT_EQ(build_convex_hull(cloud.data(), cloud.size(), hull), Status::ok);
  ConvexShape shapes[6];
  make_sphere(0.6f, shapes[0]), make_box({0.5f, 0.3f, 0.7f}, shapes[1]), make_capsule(0.3f, 0.6f, shapes[2]);
  make_cylinder(0.5f, 0.4f, shapes[3]), make_triangle({-1, 0, 0}, {1, 0.2f, 0}, {0, 0, 1}, shapes[4]);
  shapes[5] = hull.shape();
  uint64_t h = 0xcbf29ce484222325ull;
  for (int i = 0; i < 3000; ++i) {
    const ConvexShape& a = shapes[int(rng.u() * 6)];
    const ConvexShape& b = shapes[int(rng.u() * 6)];
    ConvexPose pa, pb;
    pa.rotation = random_rotation(rng), pb.rotation = random_rotation(rng);
    pa.position = {float(rng.u() * 2), float(rng.u() * 2), float(rng.u() * 2)};
    pb.position = {float(rng.u() * 2), float(rng.u() * 2), float(rng.u() * 2)};
    h = hash_result(h, convex_intersect(a, pa, b, pb));
    h = hash_result(h, convex_distance(a, pa, b, pb));
    h = hash_result(h, convex_penetration(a, pa, b, pb));
  }
  std::printf("[ determinism ] hash 0x%016llx\n", static_cast<unsigned long long>(h));
  // 0xc36c45e9bf7d8e1b since box pairs probe their face normals before GJK's loop in the
  // intersect query (was 0x4ca8044f2699d844, and before EPA placed its witnesses on the
  // coplanar face holding the origin's projection 0xa7743fe89d1ddc3e): separated box pairs
  // report the support point along the separating face normal (iterations 0); verdicts did
  // not change.
  EXPECT_EQ(h, 0xc36c45e9bf7d8e1bull);
}

}  // namespace
}  // namespace gyro
