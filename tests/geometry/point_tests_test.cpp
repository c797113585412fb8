// Point tests (gyro/point_tests.hpp): contains, closest_point and signed_distance of
// spheres, AABBs, OBBs, planes, segments and rays against an independent binary64
// reference on 10^5 seeded cases per shape (hard cases included), closest points checked
// by brute-force sampling, and the exactness the header promises. The per-level probe of
// these templates is OverlapProbe in overlap_test.cpp (one kernel runs both families).
//
// Tolerance band: the float answer may legitimately differ from binary64 by the rounding of
// its inputs and operations, at most a few ulp of M, the largest input magnitude of a case
// (coordinates and sizes). The band is 16 roundings, 16 * 2^-24 * M (about 1e-6 * M): a
// contains() verdict may differ from the reference only for a point within the band of the
// boundary, and a closest point may be at most the band away from the reference's.
#include "gyro/point_tests.hpp"
#include "workloads.hpp"

#include "opaque_float.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace gyro {
namespace {

using gyro::testing::SplitMix64;

constexpr double kEps = 0x1p-24;
constexpr double kBandRoundings = 16;
constexpr int kCases = 100000;

// ---------------------------------------------------------------- binary64 vectors
struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(D3 a) { return std::sqrt(dot(a, a)); }
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
double max_abs(const vec3& v) { return std::max({std::abs(double(v.x)), std::abs(double(v.y)), std::abs(double(v.z))}); }
double at(D3 v, int i) { return i == 0 ? v.x : i == 1 ? v.y : v.z; }
D3 row(const mat3& m, int i) { return {m.m[i][0], m.m[i][1], m.m[i][2]}; }

using testing::f32;
using testing::opaque;
vec3 f3(D3 v) { return {f32(v.x), f32(v.y), f32(v.z)}; }

// ---------------------------------------------------------------- seeded cases
// Scales and distances from the origin the cases are drawn at: unit, tiny and huge shapes
// near the origin, and the same far from it.
constexpr double kFrames[][2] = {{1, 0}, {1e-3, 0}, {1e4, 0}, {1, 1e4}, {1e-3, 1}, {1e4, 1e7}};
// Powers of two for the exact (dyadic) cases, where every float operation is exact.
constexpr double kDyadic[] = {0x1p-10, 1.0, 0x1p13};

struct Frame {
  double scale;
  D3 origin;
};

class Rng {
 public:
  explicit Rng(uint64_t seed) : r_(seed) {}
  double u() { return r_.u(); }
  double sym() { return 2 * r_.u() - 1; }
  int pick(int n) { return int(r_.next() % uint64_t(n)); }
  D3 unit() {
    const double z = sym(), phi = 6.283185307179586 * u(), s = std::sqrt(1 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
  D3 cube() { return {sym(), sym(), sym()}; }
  Frame frame() {
    const auto& f = kFrames[pick(6)];
    return {f[0], unit() * f[1]};
  }
  vec3 near(const Frame& f, double spread) { return f3(f.origin + cube() * (f.scale * spread)); }
  // An integer multiple of the dyadic step q, |k| <= 1024.
  float dyadic(double q) { return f32(q * double(pick(2049) - 1024)); }
  vec3 dyadic3(double q) { return {dyadic(q), dyadic(q), dyadic(q)}; }
  // Rows are the axes: the identity, a turn about one world axis (faces parallel to the
  // world's), a signed permutation (exact), or a uniform random rotation.
  mat3 rotation() {
    const int kind = pick(10);
    if (kind == 0) return mat3{};
    if (kind <= 2) {
      const double a = 6.283185307179586 * u(), c = std::cos(a), s = std::sin(a);
      const int k = pick(3), i = (k + 1) % 3, j = (k + 2) % 3;
      double m[3][3] = {};
      m[k][k] = 1, m[i][i] = c, m[i][j] = s, m[j][i] = -s, m[j][j] = c;
      return to_mat3(m);
    }
    if (kind == 3) return signed_permutation();
    const double u0 = u(), s1 = std::sqrt(1 - u0), s2 = std::sqrt(u0), a = 6.283185307179586 * u(),
                 b = 6.283185307179586 * u();
    const double x = s1 * std::sin(a), y = s1 * std::cos(a), z = s2 * std::sin(b), w = s2 * std::cos(b);
    const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                            {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                            {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
    return to_mat3(m);
  }
  mat3 signed_permutation() {
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const int* p = perms[pick(6)];
    double m[3][3] = {};
    for (int r = 0; r < 3; ++r) m[r][p[r]] = pick(2) ? 1.0 : -1.0;
    return to_mat3(m);
  }

 private:
  static mat3 to_mat3(const double (&m)[3][3]) {
    mat3 out;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.m[r][c] = f32(m[r][c]);
    return out;
  }
  SplitMix64 r_;
};

// ---------------------------------------------------------------- binary64 reference
double clampd(double v, double lo, double hi) { return std::min(hi, std::max(lo, v)); }

// Signed distance of local point l to the box |l_i| <= e_i (negative inside).
double box_sd(D3 l, D3 e) {
  const D3 a{std::abs(l.x) - e.x, std::abs(l.y) - e.y, std::abs(l.z) - e.z};
  const D3 out{std::max(a.x, 0.0), std::max(a.y, 0.0), std::max(a.z, 0.0)};
  return len(out) + std::min(std::max({a.x, a.y, a.z}), 0.0);
}

struct Ref {
  bool inside;    // the reference's contains()
  double margin;  // signed distance to the contains() boundary (<= 0: contained)
  D3 closest;
};

Ref ref_sphere(const Sphere& s, D3 p) {
  const D3 c = d3(s.center), d = p - c;
  const double l = len(d), r = s.radius;
  return {l <= r, l - r, l <= r ? p : c + d * (r / l)};
}

Ref ref_aabb(const AABB& b, D3 p) {
  const D3 c = d3(b.center), e = d3(b.half_extents);
  const double sd = box_sd(p - c, e);
  return {sd <= 0, sd, {clampd(p.x, c.x - e.x, c.x + e.x), clampd(p.y, c.y - e.y, c.y + e.y), clampd(p.z, c.z - e.z, c.z + e.z)}};
}

Ref ref_obb(const OBB& b, D3 p) {
  const D3 c = d3(b.center), e = d3(b.half_extents), d = p - c;
  const D3 u[3] = {row(b.orientation, 0), row(b.orientation, 1), row(b.orientation, 2)};
  const D3 l{dot(d, u[0]), dot(d, u[1]), dot(d, u[2])};
  const double sd = box_sd(l, e);
  const D3 q = c + u[0] * clampd(l.x, -e.x, e.x) + u[1] * clampd(l.y, -e.y, e.y) + u[2] * clampd(l.z, -e.z, e.z);
  return {sd <= 0, sd, q};
}

// The surface tolerance of gyro/point_tests.hpp, in binary64.
double surface_tol(double m) { return std::max(double(kSurfaceAbsTolerance), double(kSurfaceRelTolerance) * m); }

Ref ref_plane(const Plane& pl, const vec3& pf) {
  const D3 n = d3(pl.normal), p = d3(pf);
  const double nn = dot(n, n), sd = dot(n, p) - pl.distance;
  const double dist = std::abs(sd) / std::sqrt(nn);  // exact geometry, even for |n| 1 ulp off
  const double tol = surface_tol(std::max(max_abs(pf), std::abs(double(pl.distance))));
  return {dist <= tol, dist - tol, p - n * (sd / nn)};
}

D3 ref_segment_closest(D3 a, D3 b, D3 p) {
  const D3 ab = b - a;
  const double l2 = dot(ab, ab);
  if (l2 == 0) return a;
  return a + ab * clampd(dot(p - a, ab) / l2, 0, 1);
}

Ref ref_line(const Line& s, const vec3& pf) {
  const D3 p = d3(pf), q = ref_segment_closest(d3(s.start), d3(s.end), p);
  const double tol = surface_tol(std::max({max_abs(pf), max_abs(s.start), max_abs(s.end)}));
  const double dist = len(p - q);
  return {dist <= tol, dist - tol, q};
}

D3 ref_ray_closest(D3 o, D3 d, D3 p) {
  const double l2 = dot(d, d);
  if (l2 == 0) return o;
  return o + d * std::max(0.0, dot(p - o, d) / l2);
}

Ref ref_ray(const Ray& r, const vec3& pf) {
  const D3 p = d3(pf), q = ref_ray_closest(d3(r.origin), d3(r.direction), p);
  const double tol = surface_tol(std::max(max_abs(pf), max_abs(r.origin)));
  const double dist = len(p - q);
  return {dist <= tol, dist - tol, q};
}

// ---------------------------------------------------------------- tallies
struct Tally {
  const char* name;
  std::size_t cases = 0, verdict_in_band = 0, verdict_outside = 0, point_outside = 0, exact_wrong = 0;
  double max_verdict_margin = 0;  // largest |margin| / M among verdict disagreements
  double max_point_err = 0;       // largest |closest - reference| / M
  double max_dist_err = 0;        // largest |signed_distance - reference| / M (where measured)

  void check(bool got, const vec3& got_closest, const Ref& ref, double m) {
    ++cases;
    const double band = kBandRoundings * kEps * m;
    if (got != ref.inside) {
      (std::abs(ref.margin) <= band ? verdict_in_band : verdict_outside)++;
      max_verdict_margin = std::max(max_verdict_margin, std::abs(ref.margin) / m);
    }
    const double err = len(d3(got_closest) - ref.closest);
    if (!(err <= band)) ++point_outside;
    max_point_err = std::max(max_point_err, err / m);
  }
  void print() const {
    std::printf("  %-8s %zu cases; contains: %zu disagreements within the band, %zu outside (max |margin| %.2g M); "
                "closest: %zu outside the band, max error %.2g M",
                name, cases, verdict_in_band, verdict_outside, max_verdict_margin, point_outside, max_point_err);
    if (max_dist_err > 0) std::printf("; signed distance max error %.2g M", max_dist_err);
    std::printf("\n");
  }
  void expect_clean() const {
    EXPECT_GE(cases, std::size_t(kCases));
    EXPECT_EQ(verdict_outside, 0u) << name;
    EXPECT_EQ(point_outside, 0u) << name;
    EXPECT_EQ(exact_wrong, 0u) << name << ": exact (dyadic) cases";
  }
};

double m_of(std::initializer_list<double> v) { return std::max(1e-30, std::max(v)); }

// ---------------------------------------------------------------- spheres
TEST(PointTests, SphereAgreesWithBinary64) {
  Rng rng(101);
  Tally t{"sphere"};
  std::size_t solid_fixed_wrong = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    Sphere s{rng.near(f, 2), f32(f.scale * 2 * rng.u())};
    vec3 p = rng.near(f, 3);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 4) p = f3(d3(s.center) + rng.unit() * s.radius);  // on the surface, rounded
    if (kind == 5) p = s.center;
    if (kind == 6) s.radius = 0, p = rng.pick(2) ? s.center : p;
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 8) {
      const D3 dir = rng.unit();
      p = f3(d3(s.center) + dir * (s.radius * rng.u()));
    }
    if (kind == 9) {  // exactly on the surface, all float arithmetic exact
      const double q = kDyadic[rng.pick(3)];
      s = {rng.dyadic3(q), f32(q * (1 + rng.pick(512)))};
      p = s.center;
      (rng.pick(3) == 0 ? p.x : rng.pick(2) ? p.y : p.z) += (rng.pick(2) ? s.radius : -s.radius);
      exact = true;
    }
    opaque(s, p);
    const bool got = contains(s, p);
    const vec3 q = closest_point(s, p);
    const Ref ref = ref_sphere(s, d3(p));
    const double m = m_of({max_abs(s.center), double(s.radius), max_abs(p)});
    t.check(got, q, ref, m);
    t.max_dist_err = std::max(t.max_dist_err, std::abs(double(signed_distance(s, p)) - ref.margin) / m);
    if (exact && !got) ++t.exact_wrong;
    if (got && !(q == p)) ++solid_fixed_wrong;
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(solid_fixed_wrong, 0u) << "a contained point must be its own closest point";
  EXPECT_LT(t.max_dist_err, kBandRoundings * kEps);
}

// ---------------------------------------------------------------- AABBs
TEST(PointTests, AabbAgreesWithBinary64) {
  Rng rng(102);
  Tally t{"aabb"};
  std::size_t closest_not_contained = 0, solid_fixed_wrong = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    AABB b{rng.near(f, 2), f3(D3{rng.u(), rng.u(), rng.u()} * (2 * f.scale))};
    vec3 p = rng.near(f, 3);
    const int kind = i % 10;
    bool exact = false;
    const vec3 lo = b.center - b.half_extents, hi = b.center + b.half_extents;  // float bounds
    if (kind == 4) {  // on a face: exactly on the float bound, the other coordinates inside
      p = f3(d3(b.center) + D3{rng.sym() * b.half_extents.x, rng.sym() * b.half_extents.y, rng.sym() * b.half_extents.z});
      const int k = rng.pick(3);
      (k == 0 ? p.x : k == 1 ? p.y : p.z) = rng.pick(2) ? (k == 0 ? hi.x : k == 1 ? hi.y : hi.z) : (k == 0 ? lo.x : k == 1 ? lo.y : lo.z);
    }
    if (kind == 5) p = rng.pick(2) ? b.center : (rng.pick(2) ? hi : lo);
    if (kind == 6) {  // a rectangle, a segment or a point
      const int zeros = 1 + rng.pick(3);
      b.half_extents.x = 0;
      if (zeros > 1) b.half_extents.y = 0;
      if (zeros > 2) b.half_extents.z = 0;
      if (rng.pick(2)) p.x = b.center.x;
    }
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 9) {  // dyadic: touching a face or a corner exactly
      const double q = kDyadic[rng.pick(3)];
      b = {rng.dyadic3(q), {f32(q * rng.pick(64)), f32(q * rng.pick(64)), f32(q * rng.pick(64))}};
      const vec3 bh = b.center + b.half_extents;
      p = {bh.x, rng.pick(2) ? bh.y : b.center.y, rng.pick(2) ? bh.z : b.center.z};
      exact = true;
    }
    opaque(b, p);
    const bool got = contains(b, p);
    const vec3 q = closest_point(b, p);
    const Ref ref = ref_aabb(b, d3(p));
    t.check(got, q, ref, m_of({max_abs(b.center), max_abs(b.half_extents), max_abs(p)}));
    if (exact && !got) ++t.exact_wrong;
    if (!contains(b, q)) ++closest_not_contained;
    if (got && !(q == p)) ++solid_fixed_wrong;
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(closest_not_contained, 0u) << "the clamped point lies on the same float bounds contains() uses";
  EXPECT_EQ(solid_fixed_wrong, 0u);
}

// ---------------------------------------------------------------- OBBs
TEST(PointTests, ObbAgreesWithBinary64) {
  Rng rng(103);
  Tally t{"obb"};
  std::size_t solid_fixed_wrong = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    OBB b{rng.near(f, 2), f3(D3{rng.u(), rng.u(), rng.u()} * (2 * f.scale)), rng.rotation()};
    vec3 p = rng.near(f, 3);
    const int kind = i % 10;
    bool exact = false;
    const D3 u[3] = {row(b.orientation, 0), row(b.orientation, 1), row(b.orientation, 2)};
    const D3 e = d3(b.half_extents);
    if (kind == 4) {  // near a face
      const int k = rng.pick(3);
      D3 l{rng.sym() * e.x, rng.sym() * e.y, rng.sym() * e.z};
      (k == 0 ? l.x : k == 1 ? l.y : l.z) = (rng.pick(2) ? 1 : -1) * at(e, k);
      p = f3(d3(b.center) + u[0] * l.x + u[1] * l.y + u[2] * l.z);
    }
    if (kind == 5) p = rng.pick(2) ? b.center : f3(d3(b.center) + u[0] * e.x - u[1] * e.y + u[2] * e.z);
    if (kind == 6) {
      b.half_extents = {0, rng.pick(2) ? 0.0f : b.half_extents.y, b.half_extents.z};
      if (rng.pick(2)) p = b.center;
    }
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 8) {
      const D3 l{e.x * rng.sym(), e.y * rng.sym(), e.z * rng.sym()};
      p = f3(d3(b.center) + u[0] * l.x + u[1] * l.y + u[2] * l.z);
    }
    if (kind == 9) {  // signed-permutation axes, dyadic: a face touched exactly
      const double q = kDyadic[rng.pick(3)];
      b = {rng.dyadic3(q), {f32(q * rng.pick(64)), f32(q * rng.pick(64)), f32(q * rng.pick(64))}, rng.signed_permutation()};
      const D3 v[3] = {row(b.orientation, 0), row(b.orientation, 1), row(b.orientation, 2)};
      const int k = rng.pick(3);
      p = f3(d3(b.center) + v[k] * at(d3(b.half_extents), k));
      exact = true;
    }
    opaque(b, p);
    const bool got = contains(b, p);
    const vec3 q = closest_point(b, p);
    const Ref ref = ref_obb(b, d3(p));
    t.check(got, q, ref, m_of({max_abs(b.center), max_abs(b.half_extents), max_abs(p)}));
    if (exact && !got) ++t.exact_wrong;
    if (got && !(q == p)) ++solid_fixed_wrong;
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(solid_fixed_wrong, 0u);
}

// ---------------------------------------------------------------- planes
TEST(PointTests, PlaneAgreesWithBinary64) {
  Rng rng(104);
  Tally t{"plane"};
  std::size_t foot_not_on_plane = 0, near_cases = 0, closest_rejected = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    const int kind = i % 10;
    Plane pl;
    pl.normal = f3(rng.unit());
    if (kind == 6) pl.normal = {0, 0, 0}, (rng.pick(3) == 0 ? pl.normal.x : rng.pick(2) ? pl.normal.y : pl.normal.z) = rng.pick(2) ? 1.0f : -1.0f;
    const D3 on = d3(rng.near(f, 2));
    pl.distance = f32(dot(d3(pl.normal), on));
    vec3 p = rng.near(f, 3);
    bool exact = false, near = false;
    const D3 n = d3(pl.normal);
    const double m0 = std::max(max_abs(f3(on)), std::abs(double(pl.distance)));
    if (kind == 4) p = f3(on - n * ((dot(n, on) - pl.distance) / dot(n, n))), near = true;  // on the plane, rounded
    if (kind == 5) p = f3(on + n * (surface_tol(m0) * (rng.pick(2) ? 0.5 : 2.0)));        // either side of the tolerance
    if (kind == 6) {  // an axis normal and a dyadic point exactly on the plane
      const double q = kDyadic[rng.pick(3)];
      p = rng.dyadic3(q);
      pl.distance = f32(dot(n, d3(p)));
      exact = true;
    }
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 8) p = {0, 0, 0};
    opaque(pl, p);
    const bool got = contains(pl, p);
    const vec3 q = closest_point(pl, p);
    const Ref ref = ref_plane(pl, p);
    const double m = m_of({max_abs(pl.normal), std::abs(double(pl.distance)), max_abs(p)});
    t.check(got, q, ref, m);
    const double sd_ref = dot(n, d3(p)) - pl.distance;
    t.max_dist_err = std::max(t.max_dist_err, std::abs(double(signed_distance(pl, p)) - sd_ref) / m);
    if (exact && !(got && q == p)) ++t.exact_wrong;
    if (near) ++near_cases, foot_not_on_plane += !got;
    closest_rejected += !contains(pl, q);
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(foot_not_on_plane, 0u) << "points rounded from the plane are within the tolerance";
  EXPECT_EQ(closest_rejected, 0u) << "contains(plane, closest_point(plane, p)), p near or far";
  EXPECT_GT(near_cases, 0u);
  EXPECT_LT(t.max_dist_err, kBandRoundings * kEps);
}

// ---------------------------------------------------------------- segments
TEST(PointTests, SegmentAgreesWithBinary64) {
  Rng rng(105);
  Tally t{"segment"};
  std::size_t on_segment_rejected = 0, endpoint_wrong = 0, closest_rejected = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    Line s{rng.near(f, 2), rng.near(f, 2)};
    vec3 p = rng.near(f, 3);
    const int kind = i % 10;
    bool on = false, beyond_end = false;
    const D3 a = d3(s.start), b = d3(s.end);
    if (kind == 4) p = f3(a + (b - a) * rng.u()), on = true;  // on the segment, rounded
    if (kind == 5) p = rng.pick(2) ? s.start : s.end, on = true;
    if (kind == 6) s.end = s.start, p = rng.pick(2) ? s.start : p;  // a point
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 8) {  // off the middle by twice the tolerance, perpendicular
      const D3 ab = b - a, perp = cross(ab, rng.unit());
      const double tol = surface_tol(std::max({max_abs(s.start), max_abs(s.end), max_abs(f3(a + ab * 0.5))}));
      if (len(perp) > 0) p = f3(a + ab * 0.5 + perp * (2 * tol / len(perp)));
    }
    if (kind == 9) {  // on the line beyond the end: the closest point is end, exactly
      const double q = kDyadic[rng.pick(3)];
      s = {rng.dyadic3(q), rng.dyadic3(q)};
      p = f3(d3(s.end) + (d3(s.end) - d3(s.start)) * 0.5);
      beyond_end = true;
    }
    opaque(s, p);
    const bool got = contains(s, p);
    const vec3 q = closest_point(s, p);
    const Ref ref = ref_line(s, p);
    t.check(got, q, ref, m_of({max_abs(s.start), max_abs(s.end), max_abs(p)}));
    if (on && !got) ++on_segment_rejected;
    if (beyond_end && !(q == s.end)) ++endpoint_wrong;
    if (kind == 6 && !(q == s.start)) ++endpoint_wrong;
    closest_rejected += !contains(s, q);
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(on_segment_rejected, 0u);
  EXPECT_EQ(closest_rejected, 0u) << "contains(line, closest_point(line, p))";
  EXPECT_EQ(endpoint_wrong, 0u) << "beyond an end the closest point is that end exactly; a point segment gives start";
}

// ---------------------------------------------------------------- rays
TEST(PointTests, RayAgreesWithBinary64) {
  Rng rng(106);
  Tally t{"ray"};
  std::size_t on_ray_rejected = 0, origin_wrong = 0, closest_rejected = 0;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = rng.frame();
    // Directions of any length: t is in units of |d|.
    const vec3 origin = rng.near(f, 2);
    const D3 dir = rng.unit();
    const double length = std::pow(10.0, 2 * rng.sym());
    Ray r{origin, f3(dir * (length * (rng.pick(2) ? 1 : f.scale)))};
    vec3 p = rng.near(f, 3);
    const int kind = i % 10;
    bool on = false, behind = false;
    const D3 o = d3(r.origin), d = d3(r.direction);
    if (kind == 4) p = f3(o + d * (f.scale * 3 * rng.u() / len(d))), on = true;
    if (kind == 5) p = r.origin, on = true;
    if (kind == 6) r.direction = {0, 0, 0}, p = rng.pick(2) ? r.origin : p;
    if (kind == 7) p = rng.near(f, 300);
    if (kind == 8) {
      const double t_along = f.scale * rng.u() / len(d);
      p = f3(o + d * t_along + cross(d, rng.unit()) * (f.scale / len(d)));
    }
    if (kind == 9) p = f3(o - d * (f.scale * (0.1 + rng.u()) / len(d))), behind = true;
    opaque(r, p);
    const bool got = contains(r, p);
    const vec3 q = closest_point(r, p);
    const Ref ref = ref_ray(r, p);
    t.check(got, q, ref, m_of({max_abs(r.origin), max_abs(p)}));
    if (on && !got) ++on_ray_rejected;
    if ((behind || kind == 6) && !(q == r.origin)) ++origin_wrong;
    closest_rejected += !contains(r, q);
  }
  t.print();
  t.expect_clean();
  EXPECT_EQ(on_ray_rejected, 0u);
  EXPECT_EQ(closest_rejected, 0u) << "contains(ray, closest_point(ray, p))";
  EXPECT_EQ(origin_wrong, 0u) << "behind the origin, or for a zero direction, the closest point is the origin";
}

// ---------------------------------------------------------------- closest points by sampling
// A closest point lies in the shape (binary64 distance to the shape within the band) and no
// sampled point of the shape is closer to the query than it (by more than the band).
TEST(PointTests, ClosestPointsAreClosestBySampling) {
  Rng rng(107);
  constexpr int kShapes = 3000, kSamples = 64;
  std::size_t outside_shape = 0, beaten = 0, checks = 0;
  double worst_beat = 0;
  auto check = [&](const vec3& p, const vec3& q, double dist_q_to_shape, double m, auto&& sample) {
    const double band = kBandRoundings * kEps * m;
    if (!(dist_q_to_shape <= band)) ++outside_shape;
    const double dq = len(d3(p) - d3(q));
    for (int k = 0; k < kSamples; ++k) {
      const double ds = len(d3(p) - sample());
      ++checks;
      if (ds < dq - band) ++beaten;
      worst_beat = std::max(worst_beat, (dq - ds) / m);
    }
  };
  for (int i = 0; i < kShapes; ++i) {
    const Frame f = rng.frame();
    const vec3 p = rng.near(f, 4);
    {
      const Sphere s{rng.near(f, 2), f32(f.scale * 2 * rng.u())};
      opaque(s, p);
      const vec3 q = closest_point(s, p);
      const double m = m_of({max_abs(s.center), double(s.radius), max_abs(p)});
      check(p, q, std::max(0.0, ref_sphere(s, d3(q)).margin), m, [&] {
        const D3 dir = rng.unit();
        return d3(s.center) + dir * (s.radius * (rng.pick(2) ? 1.0 : std::cbrt(rng.u())));
      });
    }
    {
      const AABB b{rng.near(f, 2), f3(D3{rng.u(), rng.u(), rng.u()} * (2 * f.scale))};
      opaque(b, p);
      const vec3 q = closest_point(b, p);
      const double m = m_of({max_abs(b.center), max_abs(b.half_extents), max_abs(p)});
      check(p, q, std::max(0.0, ref_aabb(b, d3(q)).margin), m, [&] {
        D3 l{rng.sym(), rng.sym(), rng.sym()};
        if (rng.pick(2)) (rng.pick(3) == 0 ? l.x : rng.pick(2) ? l.y : l.z) = rng.pick(2) ? 1 : -1;  // on a face
        return d3(b.center) + D3{l.x * b.half_extents.x, l.y * b.half_extents.y, l.z * b.half_extents.z};
      });
    }
    {
      const OBB b{rng.near(f, 2), f3(D3{rng.u(), rng.u(), rng.u()} * (2 * f.scale)), rng.rotation()};
      opaque(b, p);
      const vec3 q = closest_point(b, p);
      const double m = m_of({max_abs(b.center), max_abs(b.half_extents), max_abs(p)});
      const D3 u[3] = {row(b.orientation, 0), row(b.orientation, 1), row(b.orientation, 2)};
      check(p, q, std::max(0.0, ref_obb(b, d3(q)).margin), m, [&] {
        D3 l{rng.sym(), rng.sym(), rng.sym()};
        if (rng.pick(2)) (rng.pick(3) == 0 ? l.x : rng.pick(2) ? l.y : l.z) = rng.pick(2) ? 1 : -1;
        return d3(b.center) + u[0] * (l.x * b.half_extents.x) + u[1] * (l.y * b.half_extents.y) + u[2] * (l.z * b.half_extents.z);
      });
    }
    {
      Plane pl;
      pl.normal = f3(rng.unit());
      pl.distance = f32(dot(d3(pl.normal), d3(rng.near(f, 2))));
      opaque(pl, p);
      const vec3 q = closest_point(pl, p);
      const D3 n = d3(pl.normal), foot = ref_plane(pl, p).closest;
      const double m = m_of({std::abs(double(pl.distance)), max_abs(p)});
      check(p, q, std::abs(dot(n, d3(q)) - pl.distance) / len(n), m, [&] {
        const D3 tangent = cross(n, rng.unit());
        return foot + tangent * (f.scale * rng.sym());
      });
    }
    {
      const Line s{rng.near(f, 2), rng.pick(8) ? rng.near(f, 2) : p};
      opaque(s, p);
      const vec3 q = closest_point(s, p);
      const D3 a = d3(s.start), b = d3(s.end);
      const double m = m_of({max_abs(s.start), max_abs(s.end), max_abs(p)});
      check(p, q, len(d3(q) - ref_segment_closest(a, b, d3(q))), m, [&] {
        const int k = rng.pick(8);
        return a + (b - a) * (k == 0 ? 0.0 : k == 1 ? 1.0 : rng.u());
      });
    }
    {
      const Ray r{rng.near(f, 2), f3(rng.unit() * f.scale)};
      opaque(r, p);
      const vec3 q = closest_point(r, p);
      const D3 o = d3(r.origin), d = d3(r.direction);
      const double m = m_of({max_abs(r.origin), max_abs(p)});
      check(p, q, len(d3(q) - ref_ray_closest(o, d, d3(q))), m, [&] { return o + d * (rng.pick(8) ? 10 * rng.u() : 0.0); });
    }
  }
  std::printf("  %zu sampled comparisons over %d shapes of each kind: %zu closest points outside their shape, %zu beaten "
              "by a sample (max advantage %.2g M)\n",
              checks, kShapes, outside_shape, beaten, worst_beat);
  EXPECT_EQ(outside_shape, 0u);
  EXPECT_EQ(beaten, 0u);
}

// ---------------------------------------------------------------- hand-picked cases
TEST(PointTests, HandPickedCases) {
  const Sphere unit{{0, 0, 0}, 1};
  EXPECT_TRUE(contains(unit, {1, 0, 0}));  // on the surface: closed
  EXPECT_FALSE(contains(unit, {1.0000001f, 0, 0}));
  EXPECT_EQ(closest_point(unit, {0.5f, 0, 0}), (vec3{0.5f, 0, 0}));  // inside: itself
  EXPECT_EQ(closest_point(unit, {0, 3, 0}), (vec3{0, 1, 0}));
  EXPECT_EQ(closest_point(Sphere{{1, 2, 3}, 0}, {1, 2, 3}), (vec3{1, 2, 3}));  // radius 0 at its centre: no NaN
  EXPECT_EQ(closest_point(Sphere{{1, 2, 3}, 0}, {5, 2, 3}), (vec3{1, 2, 3}));
  EXPECT_EQ(signed_distance(unit, {0, 0, 3}), 2.0f);
  EXPECT_EQ(signed_distance(unit, {0, 0, 0}), -1.0f);

  const AABB box{{1, 1, 1}, {1, 2, 0}};  // a rectangle in z = 1
  EXPECT_TRUE(contains(box, {2, 3, 1}));  // a corner
  EXPECT_FALSE(contains(box, {2, 3, 1.0000001f}));
  EXPECT_EQ(closest_point(box, {5, -5, 7}), (vec3{2, -1, 1}));

  mat3 turn;  // 90 degrees about z: axes (0, 1, 0), (-1, 0, 0), (0, 0, 1)
  turn.m[0][0] = 0, turn.m[0][1] = 1, turn.m[1][0] = -1, turn.m[1][1] = 0;
  const OBB obb{{0, 0, 0}, {2, 1, 1}, turn};
  EXPECT_TRUE(contains(obb, {0, 2, 0}));   // along the first axis, which is world y
  EXPECT_FALSE(contains(obb, {2, 0, 0}));  // world x is the second axis, half extent 1
  EXPECT_EQ(closest_point(obb, {3, 5, 0}), (vec3{1, 2, 0}));
  EXPECT_EQ(closest_point(obb, {0.5f, 0.25f, -0.5f}), (vec3{0.5f, 0.25f, -0.5f}));

  const Plane ground{{0, 1, 0}, 2};  // y = 2
  EXPECT_TRUE(contains(ground, {7, 2, -3}));
  EXPECT_TRUE(contains(ground, {0, 2 + 0.5e-6f, 0}));   // the tolerance here is 1e-6 * 2
  EXPECT_FALSE(contains(ground, {0, 2 + 1e-5f, 0}));    // 5x beyond it
  EXPECT_TRUE(contains(Plane{{0, 1, 0}, 0}, {0, 0.9e-6f, 0}));   // near the origin: the absolute 1e-6
  EXPECT_FALSE(contains(Plane{{0, 1, 0}, 0}, {0, 1.1e-6f, 0}));
  EXPECT_TRUE(contains(Plane{{0, 1, 0}, 1e4f}, {0, 1e4f + 5e-3f, 0}));   // relative: 1e-6 * 1e4 = 1e-2
  EXPECT_FALSE(contains(Plane{{0, 1, 0}, 1e4f}, {0, 1e4f + 2e-2f, 0}));
  EXPECT_EQ(closest_point(ground, {7, -1, 3}), (vec3{7, 2, 3}));
  EXPECT_EQ(signed_distance(ground, {0, -1, 0}), -3.0f);

  const Line seg{{0, 0, 0}, {4, 0, 0}};
  EXPECT_TRUE(contains(seg, {1, 0, 0}));
  EXPECT_FALSE(contains(seg, {5, 0, 0}));  // on the line, past the end
  EXPECT_FALSE(contains(seg, {1, 1e-4f, 0}));
  EXPECT_EQ(closest_point(seg, {2, 5, 0}), (vec3{2, 0, 0}));
  EXPECT_EQ(closest_point(seg, {-3, 1, 0}), (vec3{0, 0, 0}));
  EXPECT_EQ(closest_point(seg, {9, 1, 0}), (vec3{4, 0, 0}));
  EXPECT_EQ(closest_point(Line{{1, 1, 1}, {1, 1, 1}}, {3, 3, 3}), (vec3{1, 1, 1}));  // zero length
  EXPECT_TRUE(contains(Line{{1, 1, 1}, {1, 1, 1}}, {1, 1, 1}));

  const Ray ray{{0, 0, 0}, {0, 0, 2}};  // t in units of |d| = 2
  EXPECT_TRUE(contains(ray, {0, 0, 100}));
  EXPECT_FALSE(contains(ray, {0, 0, -1}));  // behind the origin
  EXPECT_EQ(closest_point(ray, {1, 0, 6}), (vec3{0, 0, 6}));
  EXPECT_EQ(closest_point(ray, {1, 0, -6}), (vec3{0, 0, 0}));
  EXPECT_EQ(closest_point(Ray{{1, 2, 3}, {0, 0, 0}}, {5, 5, 5}), (vec3{1, 2, 3}));  // zero direction: the origin
}

// NaN in, a defined result out and no trap (the build does not enable FP exceptions, but
// the guarded divisions must not produce NaN from finite input either).
TEST(PointTests, NanInputsGiveDefinedResults) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const vec3 np{nan, 0, 0};
  EXPECT_FALSE(contains(Sphere{{0, 0, 0}, 1}, np));
  EXPECT_FALSE(contains(AABB{{0, 0, 0}, {1, 1, 1}}, np));
  EXPECT_FALSE(contains(OBB{{0, 0, 0}, {1, 1, 1}, mat3{}}, np));
  EXPECT_FALSE(contains(Plane{{0, 1, 0}, 0}, vec3{0, nan, 0}));
  EXPECT_FALSE(contains(Line{{0, 0, 0}, {1, 0, 0}}, np));
  EXPECT_FALSE(contains(Ray{{0, 0, 0}, {1, 0, 0}}, np));
  EXPECT_TRUE(std::isnan(closest_point(AABB{{0, 0, 0}, {1, 1, 1}}, np).x));  // NaN propagates through the clamp
  EXPECT_TRUE(std::isnan(closest_point(Line{{0, 0, 0}, {1, 0, 0}}, np).x));
  EXPECT_FALSE(contains(Sphere{{0, 0, 0}, nan}, vec3{0, 0, 0}));
  // Degenerate but finite shapes never make NaN.
  for (const vec3& p : {vec3{0, 0, 0}, vec3{1, 2, 3}, vec3{-1e-30f, 0, 0}}) {
    const vec3 q[] = {closest_point(Sphere{{0, 0, 0}, 0}, p), closest_point(Line{{0, 0, 0}, {0, 0, 0}}, p),
                      closest_point(Ray{{0, 0, 0}, {0, 0, 0}}, p), closest_point(OBB{{0, 0, 0}, {0, 0, 0}, mat3{}}, p)};
    for (const vec3& v : q) EXPECT_FALSE(std::isnan(v.x) || std::isnan(v.y) || std::isnan(v.z));
  }
}

}  // namespace
}  // namespace gyro
