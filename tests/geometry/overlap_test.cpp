// Overlap tests (gyro/overlap.hpp): every pair of spheres, AABBs, OBBs and planes against
// an independent binary64 reference on 10^5 seeded cases per pair (touching, parallel
// faces and edges, zero sizes, containment, tiny, huge and far-from-origin shapes), both
// argument orders, containment implies overlap, and the per-level probe that proves every
// lane template of point_lanes.hpp and overlap_lanes.hpp gives the scalar bits.
//
// Tolerance band. For pairs decided by one distance (all but box-box and plane-plane) the
// reference computes the signed gap (distance minus radius, <= 0: overlapping) and the
// float verdict may differ only when |gap| <= 16 * 2^-24 * M, M the magnitude of the
// values the test rounds (stated per pair). Box-box pairs use a 15-axis SAT in world space
// in binary64 (no frame formulas, no slack): with g the gap along an axis (unnormalised,
// as the float test computes it), the float test must report separation when some axis
// has g > slack + err, and overlap when every axis has g < slack - err, where slack is
// obb_obb_lanes.hpp's 1e-6 per unit of the extents on that axis and err = 16 * 2^-24 *
// (|cb - ca| + sum of extents). Plane-plane: the sine band is 8 * 2^-24 around
// kPlaneParallelSine, the coincidence band 16 * 2^-24 * max(|d1|, |d2|).
#include "core/state_hash.hpp"
#include "gyro/overlap.hpp"
#include "gyro/point_tests.hpp"
#include "gyro/runtime.hpp"
#include "overlap_probe.hpp"
#include "workloads.hpp"

#include "opaque_float.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

namespace gyro {
namespace {

using gyro::testing::SplitMix64;

constexpr double kEps = 0x1p-24;
constexpr double kBandRoundings = 16;
constexpr double kSlack = 1e-6;  // obb_obb_lanes.hpp's kParallelSlack
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
double sum(const vec3& v) { return (double(v.x) + v.y) + v.z; }
double at(D3 v, int i) { return i == 0 ? v.x : i == 1 ? v.y : v.z; }
D3 row(const mat3& m, int i) { return {m.m[i][0], m.m[i][1], m.m[i][2]}; }

using testing::f32;
using testing::opaque;
vec3 f3(D3 v) { return {f32(v.x), f32(v.y), f32(v.z)}; }

// ---------------------------------------------------------------- seeded cases
constexpr double kFrames[][2] = {{1, 0}, {1e-3, 0}, {1e4, 0}, {1, 1e4}, {1e-3, 1}, {1e4, 1e7}};
constexpr double kDyadic[] = {0x1p-10, 1.0, 0x1p13};

struct Frame {
  double scale;
  D3 origin;
};

mat3 to_mat3(const double (&m)[3][3]) {
  mat3 out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out.m[r][c] = f32(m[r][c]);
  return out;
}

// Rotation (rows = axes) by angle a about unit axis k, in binary64.
void axis_angle(D3 k, double a, double (&m)[3][3]) {
  const double c = std::cos(a), s = std::sin(a), t = 1 - c;
  const double R[3][3] = {{t * k.x * k.x + c, t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y},
                          {t * k.x * k.y - s * k.z, t * k.y * k.y + c, t * k.y * k.z + s * k.x},
                          {t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, t * k.z * k.z + c}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = R[i][j];
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : r_(seed) {}
  double u() { return r_.u(); }
  double sym() { return 2 * r_.u() - 1; }
  int pick(int n) { return int(r_.next() % uint64_t(n)); }
  uint64_t bits() { return r_.next(); }
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
  float dyadic(double q) { return f32(q * double(pick(2049) - 1024)); }
  vec3 dyadic3(double q) { return {dyadic(q), dyadic(q), dyadic(q)}; }
  vec3 extents(const Frame& f) { return f3(D3{u(), u(), u()} * (2 * f.scale)); }
  // The identity, a turn about one world axis, a signed permutation, a tiny turn about a
  // random axis (nearly parallel to the world's), or a uniform random rotation.
  mat3 rotation() {
    const int kind = pick(12);
    if (kind == 0) return mat3{};
    if (kind <= 2) {
      double m[3][3];
      const int k = pick(3);
      axis_angle({k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0}, 6.283185307179586 * u(), m);
      return to_mat3(m);
    }
    if (kind == 3) return signed_permutation();
    if (kind == 4) {
      double m[3][3];
      const D3 axis = unit();
      axis_angle(axis, std::pow(10.0, -7 + 5 * u()), m);
      return to_mat3(m);
    }
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

  Sphere sphere(const Frame& f) { return {near(f, 2), f32(f.scale * 2 * u())}; }
  AABB aabb(const Frame& f) { return {near(f, 2), extents(f)}; }
  OBB obb(const Frame& f) { return {near(f, 2), extents(f), rotation()}; }
  Plane plane(const Frame& f) {
    Plane p;
    p.normal = f3(unit());
    p.distance = f32(dot(d3(p.normal), d3(near(f, 2))));
    return p;
  }

 private:
  SplitMix64 r_;
};

// ---------------------------------------------------------------- binary64 reference
// How the float verdict must come out: forced_sep / forced_overlap say the float test has
// no choice (the pair is farther than the band from touching); neither means in the band.
struct Verdict {
  bool overlap;          // the binary64 answer
  bool forced_sep;
  bool forced_overlap;
  double margin;         // the signed gap relative to the case's size, for the report
};

Verdict from_gap(double gap, double m) {
  const double band = kBandRoundings * kEps * m;
  return {gap <= 0, gap > band, gap < -band, gap / m};
}

// Signed distance of local point l to the box |l_i| <= e_i (negative inside).
double box_sd(D3 l, D3 e) {
  const D3 a{std::abs(l.x) - e.x, std::abs(l.y) - e.y, std::abs(l.z) - e.z};
  const D3 out{std::max(a.x, 0.0), std::max(a.y, 0.0), std::max(a.z, 0.0)};
  return len(out) + std::min(std::max({a.x, a.y, a.z}), 0.0);
}

struct Box {
  D3 c, e, u[3];
};
Box box_of(const AABB& b) { return {d3(b.center), d3(b.half_extents), {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}; }
Box box_of(const OBB& b) {
  return {d3(b.center), d3(b.half_extents), {row(b.orientation, 0), row(b.orientation, 1), row(b.orientation, 2)}};
}
D3 local(const Box& b, D3 p) {
  const D3 d = p - b.c;
  return {dot(d, b.u[0]), dot(d, b.u[1]), dot(d, b.u[2])};
}

Verdict ref_sphere_sphere(const Sphere& a, const Sphere& b) {
  const double dist = len(d3(b.center) - d3(a.center));
  return from_gap(dist - (double(a.radius) + b.radius), dist + a.radius + b.radius);
}

Verdict ref_sphere_box(const Sphere& s, const Box& b, double m) {
  return from_gap(box_sd(local(b, d3(s.center)), b.e) - s.radius, m);
}

Verdict ref_sphere_plane(const Sphere& s, const Plane& p) {
  const D3 n = d3(p.normal);
  const double dist = std::abs(dot(n, d3(s.center)) - p.distance) / len(n);
  return from_gap(dist - s.radius, std::max(max_abs(s.center), std::abs(double(p.distance))) + s.radius);
}

Verdict ref_box_plane(const Box& b, const Plane& p) {
  const D3 n = d3(p.normal);
  const double dist = std::abs(dot(n, b.c) - p.distance);
  const double radius = b.e.x * std::abs(dot(b.u[0], n)) + b.e.y * std::abs(dot(b.u[1], n)) + b.e.z * std::abs(dot(b.u[2], n));
  const double m = std::max({std::abs(b.c.x), std::abs(b.c.y), std::abs(b.c.z), std::abs(double(p.distance))}) +
                   (b.e.x + b.e.y + b.e.z);
  return from_gap((dist - radius) / len(n), m);
}

Verdict ref_aabb_aabb(const AABB& a, const AABB& b) {
  double gap = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    gap = std::max(gap, std::abs(at(d3(a.center), i) - at(d3(b.center), i)) -
                            (at(d3(a.half_extents), i) + at(d3(b.half_extents), i)));
  const double m = std::max({max_abs(a.center), max_abs(b.center), max_abs(a.half_extents), max_abs(b.half_extents)});
  return from_gap(gap, m);
}

// The separating axis theorem in world space: each of the 15 axes n (face normals of both
// boxes, cross products of their edges) is used as it is, unnormalised, with
// g = |d . n| - (sum ea_i |a_i . n| + sum eb_j |b_j . n|). Zero axes (exactly parallel
// edges) are skipped: along them both boxes project to a point.
Verdict ref_sat(const Box& a, const Box& b) {
  const D3 d = b.c - a.c;
  const double ea[3] = {a.e.x, a.e.y, a.e.z}, eb[3] = {b.e.x, b.e.y, b.e.z};
  const double sa = ea[0] + ea[1] + ea[2], sb = eb[0] + eb[1] + eb[2];
  const double m = std::max(len(d) + sa + sb, 1e-30);
  const double err = kBandRoundings * kEps * m;
  bool separated = false, forced_sep = false, forced_overlap = true;
  double best = -std::numeric_limits<double>::infinity();
  auto axis = [&](D3 n, double slack) {
    const double l = len(n);
    if (l == 0) return;
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) ra += ea[k] * std::abs(dot(a.u[k], n)), rb += eb[k] * std::abs(dot(b.u[k], n));
    const double g = std::abs(dot(d, n)) - (ra + rb);
    separated = separated || g > 0;
    forced_sep = forced_sep || g > slack + err;
    forced_overlap = forced_overlap && g < slack - err;
    best = std::max(best, g / l);
  };
  for (int i = 0; i < 3; ++i) axis(a.u[i], kSlack * sb);
  for (int j = 0; j < 3; ++j) axis(b.u[j], kSlack * sa);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      axis(cross(a.u[i], b.u[j]), kSlack * ((ea[(i + 1) % 3] + ea[(i + 2) % 3]) + (eb[(j + 1) % 3] + eb[(j + 2) % 3])));
  return {!separated, forced_sep, forced_overlap, best / m};
}

double surface_tol(double m) { return std::max(double(kSurfaceAbsTolerance), double(kSurfaceRelTolerance) * m); }

Verdict ref_plane_plane(const Plane& a, const Plane& b) {
  const D3 n1 = d3(a.normal), n2 = d3(b.normal);
  const double sine = len(cross(n1, n2)) / (len(n1) * len(n2));
  const double limit = double(kPlaneParallelSine);
  const bool parallel = sine <= limit;
  const double gap = dot(n1, n2) >= 0 ? double(a.distance) - b.distance : double(a.distance) + b.distance;
  const double dm = std::max(std::abs(double(a.distance)), std::abs(double(b.distance)));
  const double tol = surface_tol(dm);
  const bool coincident = std::abs(gap) <= tol;
  const bool overlap = !parallel || coincident;
  const bool sine_clear = std::abs(sine - limit) > 8 * kEps;
  const bool gap_clear = std::abs(std::abs(gap) - tol) > kBandRoundings * kEps * dm;
  const bool clear = sine_clear && (!parallel || gap_clear);
  // The report's margin: the sine's distance from the limit where that decides, else the gap's.
  const double margin = !sine_clear ? sine - limit : parallel ? (std::abs(gap) - tol) / std::max(dm, 1.0) : sine - limit;
  return {overlap, clear && !overlap, clear && overlap, margin};
}

// ---------------------------------------------------------------- tallies
struct PairTally {
  const char* name;
  bool order_may_differ = false;  // OBB-OBB: only within the band
  std::size_t cases = 0, hits = 0, in_band = 0, outside = 0, order_diff = 0, order_outside = 0, exact_touch = 0,
              exact_wrong = 0;
  double max_in_band = 0, max_outside = 0;

  void add(bool got, bool got_reversed, const Verdict& v, bool exact = false) {
    ++cases;
    hits += v.overlap;
    auto forbidden = [&](bool g) { return (g && v.forced_sep) || (!g && v.forced_overlap); };
    if (forbidden(got)) {
      ++outside;
      max_outside = std::max(max_outside, std::abs(v.margin));
    } else if (got != v.overlap) {
      ++in_band;
      max_in_band = std::max(max_in_band, std::abs(v.margin));
    }
    if (got != got_reversed) ++order_diff, order_outside += forbidden(got_reversed);
    if (exact) ++exact_touch, exact_wrong += !got;
  }
  void report_and_check() const {
    std::printf("  %-13s %zu cases (%zu overlapping): %zu disagreements within the band (max |gap| %.2g of size), "
                "%zu outside; argument orders differ in %zu (%zu outside the band); %zu exact touches, %zu missed\n",
                name, cases, hits, in_band, max_in_band, outside, order_diff, order_outside, exact_touch, exact_wrong);
    EXPECT_GE(cases, std::size_t(kCases)) << name;
    EXPECT_GT(hits, cases / 10) << name << ": the cases must exercise both answers";
    EXPECT_LT(hits, cases - cases / 10) << name;
    EXPECT_EQ(outside, 0u) << name << " (max |gap| " << max_outside << ")";
    EXPECT_EQ(order_outside, 0u) << name;
    if (!order_may_differ) {
      EXPECT_EQ(order_diff, 0u) << name << ": both argument orders give the same bits";
    }
    EXPECT_EQ(exact_wrong, 0u) << name << ": exactly touching shapes overlap";
  }
};

// ---------------------------------------------------------------- sphere pairs
TEST(Overlap, SphereSphereAgainstBinary64) {
  Rng g(201);
  PairTally t{"sphere-sphere"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Sphere a = g.sphere(f), b = g.sphere(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) b.center = f3(d3(a.center) + g.unit() * (double(a.radius) + b.radius));  // touching, rounded
    if (kind == 6) {  // touching exactly along an axis
      const double q = kDyadic[g.pick(3)];
      a = {g.dyadic3(q), f32(q * g.pick(512))}, b = {a.center, f32(q * g.pick(512))};
      (g.pick(3) == 0 ? b.center.x : g.pick(2) ? b.center.y : b.center.z) += (g.pick(2) ? 1 : -1) * (a.radius + b.radius);
      exact = true;
    }
    if (kind == 7) a.radius = 0, b.radius = g.pick(2) ? 0.0f : b.radius;  // points
    if (kind == 8) b.center = a.center;                                      // concentric
    if (kind == 9) b.center = g.near(f, 50);
    opaque(a, b);
    t.add(overlaps(a, b), overlaps(b, a), ref_sphere_sphere(a, b), exact);
  }
  t.report_and_check();
}

// The sphere touches the box from outside: the centre is r beyond a face point, an edge or
// a corner, in the box's own frame.
Sphere touching_sphere(Rng& g, const Box& b, float r) {
  D3 l{g.sym() * b.e.x, g.sym() * b.e.y, g.sym() * b.e.z};
  D3 out{0, 0, 0};
  const int k = g.pick(3);
  for (int i = 0; i < 3; ++i) {
    if (i == k || g.pick(3) == 0) {  // this coordinate on a face
      const double s = g.pick(2) ? 1 : -1;
      (i == 0 ? l.x : i == 1 ? l.y : l.z) = s * at(b.e, i);
      (i == 0 ? out.x : i == 1 ? out.y : out.z) = s;
    }
  }
  const D3 surface = b.c + b.u[0] * l.x + b.u[1] * l.y + b.u[2] * l.z;
  const D3 dir = b.u[0] * out.x + b.u[1] * out.y + b.u[2] * out.z;
  return {f3(surface + dir * (r / len(dir))), r};
}

TEST(Overlap, SphereAabbAgainstBinary64) {
  Rng g(202);
  PairTally t{"sphere-aabb"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Sphere s = g.sphere(f);
    AABB b = g.aabb(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) s = touching_sphere(g, box_of(b), s.radius);
    if (kind == 6) {  // a face touched exactly
      const double q = kDyadic[g.pick(3)];
      b = {g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}};
      s = {b.center, f32(q * g.pick(64))};
      s.center.y += b.half_extents.y + s.radius;
      exact = true;
    }
    if (kind == 7) s.radius = 0, b.half_extents.z = 0, b.half_extents.x = g.pick(2) ? 0.0f : b.half_extents.x;
    if (kind == 8) s.center = f3(d3(b.center) + D3{g.sym() * b.half_extents.x, g.sym() * b.half_extents.y, 0.0});
    if (kind == 9) s.center = g.near(f, 50);
    const double m = std::max({max_abs(s.center), max_abs(b.center), max_abs(b.half_extents)}) + s.radius;
    opaque(s, b);
    t.add(overlaps(s, b), overlaps(b, s), ref_sphere_box(s, box_of(b), m), exact);
  }
  t.report_and_check();
}

TEST(Overlap, SphereObbAgainstBinary64) {
  Rng g(203);
  PairTally t{"sphere-obb"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Sphere s = g.sphere(f);
    OBB b = g.obb(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) s = touching_sphere(g, box_of(b), s.radius);
    if (kind == 6) {  // signed-permutation axes: a face touched exactly
      const double q = kDyadic[g.pick(3)];
      b = {g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}, g.signed_permutation()};
      s = {b.center, f32(q * g.pick(64))};
      const int k = g.pick(3);
      s.center = f3(d3(b.center) + row(b.orientation, k) * (at(d3(b.half_extents), k) + s.radius));
      exact = true;
    }
    if (kind == 7) s.radius = 0, b.half_extents = {0, g.pick(2) ? 0.0f : b.half_extents.y, b.half_extents.z};
    if (kind == 8) s.center = b.center;
    if (kind == 9) s.center = g.near(f, 50);
    const Box bx = box_of(b);
    const double m = len(d3(s.center) - bx.c) + sum(b.half_extents) + s.radius;
    opaque(s, b);
    t.add(overlaps(s, b), overlaps(b, s), ref_sphere_box(s, bx, m), exact);
  }
  t.report_and_check();
}

TEST(Overlap, SpherePlaneAgainstBinary64) {
  Rng g(204);
  PairTally t{"sphere-plane"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Sphere s = g.sphere(f);
    Plane p = g.plane(f);
    const int kind = i % 10;
    bool exact = false;
    const D3 n = d3(p.normal);
    if (kind == 5) {  // tangent, rounded
      const D3 foot = d3(s.center) - n * (dot(n, d3(s.center)) - p.distance);
      s.center = f3(foot + n * (g.pick(2) ? double(s.radius) : -double(s.radius)));
    }
    if (kind == 6) {  // an axis normal, tangent exactly
      const double q = kDyadic[g.pick(3)];
      const int k = g.pick(3);
      p.normal = {k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? -1.0f : 0.0f};
      s = {g.dyadic3(q), f32(q * g.pick(512))};
      p.distance = f32(dot(d3(p.normal), d3(s.center)) + (g.pick(2) ? 1 : -1) * double(s.radius));
      exact = true;
    }
    if (kind == 7) s.radius = 0;
    if (kind == 9) s.center = g.near(f, 50);
    opaque(s, p);
    t.add(overlaps(s, p), overlaps(p, s), ref_sphere_plane(s, p), exact);
  }
  t.report_and_check();
}

// ---------------------------------------------------------------- box pairs
TEST(Overlap, AabbAabbAgainstBinary64) {
  Rng g(205);
  PairTally t{"aabb-aabb"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    AABB a = g.aabb(f), b = g.aabb(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) {  // touching on a face, an edge or a corner, rounded
      for (int k = 0; k < 3; ++k) {
        if (k == 0 || g.pick(2)) {
          const double s = g.pick(2) ? 1 : -1;
          const double c = at(d3(a.center), k) + s * (at(d3(a.half_extents), k) + at(d3(b.half_extents), k));
          (k == 0 ? b.center.x : k == 1 ? b.center.y : b.center.z) = f32(c);
        }
      }
    }
    if (kind == 6) {
      const double q = kDyadic[g.pick(3)];
      a = {g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}};
      b = {a.center, {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}};
      b.center.x += a.half_extents.x + b.half_extents.x;
      if (g.pick(2)) b.center.z -= a.half_extents.z + b.half_extents.z;
      exact = true;
    }
    if (kind == 7) a.half_extents = {0, 0, g.pick(2) ? 0.0f : a.half_extents.z}, b.half_extents.y = 0;
    if (kind == 8) b.center = a.center;
    if (kind == 9) b.center = g.near(f, 50);
    opaque(a, b);
    t.add(overlaps(a, b), overlaps(b, a), ref_aabb_aabb(a, b), exact);
  }
  t.report_and_check();
}

// OBB b placed against box a: sharing a's orientation with faces touching (parallel faces),
// or rotated about a's axis k (parallel edges) and touching along another.
void touch_face(Rng& g, const Box& a, OBB& b, bool same_orientation, const mat3& a_orientation) {
  const int k = g.pick(3);
  if (same_orientation) b.orientation = a_orientation;
  const Box bb = box_of(b);
  // Extent of b along a's axis k (exact for a shared orientation).
  double rb = 0;
  for (int j = 0; j < 3; ++j) rb += at(bb.e, j) * std::abs(dot(a.u[k], bb.u[j]));
  const double s = g.pick(2) ? 1 : -1;
  D3 c = a.c + a.u[k] * (s * (at(a.e, k) + rb));
  for (int j = 0; j < 3; ++j)
    if (j != k) c = c + a.u[j] * (g.sym() * at(a.e, j));
  b.center = f3(c);
}

TEST(Overlap, AabbObbAgainstBinary64) {
  Rng g(206);
  PairTally t{"aabb-obb"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    AABB a = g.aabb(f);
    OBB b = g.obb(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) touch_face(g, box_of(a), b, g.pick(2), mat3{});
    if (kind == 6) {  // signed-permutation axes, touching exactly
      const double q = kDyadic[g.pick(3)];
      a = {g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}};
      b = {a.center, {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}, g.signed_permutation()};
      const Box bb = box_of(b);
      double rb = 0;
      for (int j = 0; j < 3; ++j) rb += at(bb.e, j) * std::abs(bb.u[j].y);
      b.center.y += a.half_extents.y + f32(rb);
      exact = true;
    }
    if (kind == 7) a.half_extents.x = 0, b.half_extents = {g.pick(2) ? 0.0f : b.half_extents.x, 0, 0};
    if (kind == 8) b.center = a.center;
    if (kind == 9) b.center = g.near(f, 50);
    opaque(a, b);
    t.add(overlaps(a, b), overlaps(b, a), ref_sat(box_of(a), box_of(b)), exact);
  }
  t.report_and_check();
}

TEST(Overlap, ObbObbAgainstBinary64) {
  Rng g(207);
  PairTally t{"obb-obb"};
  t.order_may_differ = true;
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    OBB a = g.obb(f), b = g.obb(f);
    const int kind = i % 10;
    bool exact = false;
    if (kind == 5) touch_face(g, box_of(a), b, g.pick(2), a.orientation);
    if (kind == 6) {
      const double q = kDyadic[g.pick(3)];
      a = {g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}, g.signed_permutation()};
      b = {a.center, {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}, g.signed_permutation()};
      const Box ab = box_of(a), bb = box_of(b);
      const int k = g.pick(3);
      double rb = 0;
      for (int j = 0; j < 3; ++j) rb += at(bb.e, j) * std::abs(dot(ab.u[k], bb.u[j]));
      b.center = f3(ab.c + ab.u[k] * (at(ab.e, k) + rb));
      exact = true;
    }
    if (kind == 7) a.half_extents = {0, 0, a.half_extents.z}, b.half_extents.y = 0;
    if (kind == 8) b.center = a.center, b.orientation = g.pick(2) ? a.orientation : b.orientation;
    if (kind == 9) b.center = g.near(f, 50);
    opaque(a, b);
    t.add(overlaps(a, b), overlaps(b, a), ref_sat(box_of(a), box_of(b)), exact);
  }
  t.report_and_check();
}

template <class Shape> void box_plane_cases(const char* name, uint64_t seed, auto&& make_box) {
  Rng g(seed);
  PairTally t{name};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Shape b = make_box(g, f);
    Plane p = g.plane(f);
    const int kind = i % 10;
    bool exact = false;
    const Box bx = box_of(b);
    if (kind == 5) {  // a corner on the plane, the box on either side (rounded)
      const D3 n = d3(p.normal);
      double radius = 0;
      for (int k = 0; k < 3; ++k) radius += at(bx.e, k) * std::abs(dot(bx.u[k], n));
      p.distance = f32(dot(n, bx.c) + (g.pick(2) ? radius : -radius));
    }
    if (kind == 6) {  // a face normal, a face exactly on the plane
      const double q = kDyadic[g.pick(3)];
      b.center = g.dyadic3(q);
      b.half_extents = {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))};
      const Box by = box_of(b);
      const int k = g.pick(3);
      p.normal = f3(by.u[k] * (g.pick(2) ? 1.0 : -1.0));
      if (max_abs(p.normal) == 1.0 && std::abs(sum(p.normal)) == 1.0) {  // an exact unit axis
        p.distance = f32(dot(d3(p.normal), by.c) + at(by.e, k));
        exact = true;
      }
    }
    if (kind == 7) b.half_extents = {0, g.pick(2) ? 0.0f : b.half_extents.y, 0};
    if (kind == 9) b.center = g.near(f, 50);
    opaque(b, p);
    t.add(overlaps(b, p), overlaps(p, b), ref_box_plane(box_of(b), p), exact);
  }
  t.report_and_check();
}

TEST(Overlap, AabbPlaneAgainstBinary64) {
  box_plane_cases<AABB>("aabb-plane", 208, [](Rng& g, const Frame& f) { return g.aabb(f); });
}

TEST(Overlap, ObbPlaneAgainstBinary64) {
  box_plane_cases<OBB>("obb-plane", 209, [](Rng& g, const Frame& f) {
    OBB b = g.obb(f);
    if (g.pick(2)) b.orientation = g.signed_permutation();  // so kind 6 often gets an exact axis
    return b;
  });
}

// ---------------------------------------------------------------- planes
TEST(Overlap, PlanePlaneAgainstBinary64) {
  Rng g(210);
  PairTally t{"plane-plane"};
  for (int i = 0; i < kCases; ++i) {
    const Frame f = g.frame();
    Plane a = g.plane(f), b = g.plane(f);
    const int kind = i % 10;
    bool exact = false;
    const double tol = surface_tol(std::abs(double(a.distance)));
    if (kind >= 2 && kind <= 4) {  // parallel (the same normal): coincident or at a multiple of the tolerance
      b.normal = a.normal;
      const double k[] = {0, 0, 0.25, 0.5, 2, 4, 1e3};
      const double side = g.pick(2) ? 1 : -1;
      b.distance = f32(a.distance + side * k[g.pick(7)] * tol);
      exact = b.distance == a.distance;
    }
    if (kind == 5 || kind == 6) {  // antiparallel (the normal negated): coincident when d2 = -d1
      b.normal = -a.normal;
      b.distance = g.pick(2) ? -a.distance : f32(-a.distance + g.sym() * 1e3 * tol);
      exact = b.distance == -a.distance;
    }
    if (kind == 7 || kind == 8) {  // nearly parallel: 1e-8 to 1e-3 rad
      double m[3][3];
      const D3 axis = g.unit();
      axis_angle(axis, std::pow(10.0, -8 + 5 * g.u()), m);
      const D3 n = d3(a.normal);
      b.normal = f3({n.x * m[0][0] + n.y * m[1][0] + n.z * m[2][0], n.x * m[0][1] + n.y * m[1][1] + n.z * m[2][1],
                     n.x * m[0][2] + n.y * m[1][2] + n.z * m[2][2]});
      b.distance = g.pick(2) ? a.distance : f32(a.distance + f.scale * g.sym());
    }
    if (kind == 9) {  // axis normals, exact
      const int k = g.pick(3);
      a.normal = b.normal = {k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f};
      b.distance = g.pick(2) ? a.distance : a.distance + f32(f.scale);
      exact = b.distance == a.distance;
    }
    opaque(a, b);
    t.add(overlaps(a, b), overlaps(b, a), ref_plane_plane(a, b), exact);
  }
  t.report_and_check();
}

// ---------------------------------------------------------------- properties
// A solid containing the centre of another solid overlaps it; a solid containing a point
// overlaps the radius-0 sphere at that point. Exact by construction for a sphere whose
// centre is contained, AABB pairs, and the first OBB of a pair (see overlap_lanes.hpp);
// the other combinations hold with the SAT slack to spare. Centres are drawn inside the
// containing solid, at its centre, and exactly on its boundary (dyadic cases).
TEST(Overlap, ContainmentImpliesOverlap) {
  Rng g(211);
  std::size_t contained = 0, violations = 0, point_cases = 0, point_violations = 0;
  const double q = 0x1p-4;
  for (int i = 0; i < 60000; ++i) {
    const Frame f = g.frame();
    const bool dyadic = i % 4 == 0;
    Sphere s = dyadic ? Sphere{g.dyadic3(q), f32(q * g.pick(64))} : g.sphere(f);
    AABB a = dyadic ? AABB{g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}} : g.aabb(f);
    OBB o = dyadic ? OBB{g.dyadic3(q), {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}, g.signed_permutation()}
                   : g.obb(f);
    // A point of each containing solid: inside, its centre, or on its boundary.
    auto in_sphere = [&] {
      const int k = g.pick(3);
      if (k == 0) return s.center;
      if (k == 1 && dyadic) {
        vec3 p = s.center;
        p.x += s.radius;
        return p;
      }
      const D3 dir = g.unit();
      return f3(d3(s.center) + dir * (s.radius * g.u()));
    };
    auto in_aabb = [&] {
      const int k = g.pick(3);
      if (k == 0) return a.center;
      if (k == 1 && dyadic) return a.center + vec3{a.half_extents.x, -a.half_extents.y, 0};
      return f3(d3(a.center) + D3{g.sym() * a.half_extents.x, g.sym() * a.half_extents.y, g.sym() * a.half_extents.z});
    };
    auto in_obb = [&] {
      const Box b = box_of(o);
      const int k = g.pick(3);
      if (k == 0) return o.center;
      if (k == 1 && dyadic) return f3(b.c + b.u[0] * b.e.x - b.u[2] * b.e.z);
      const D3 l{g.sym() * b.e.x, g.sym() * b.e.y, g.sym() * b.e.z};
      return f3(b.c + b.u[0] * l.x + b.u[1] * l.y + b.u[2] * l.z);
    };
    auto check = [&](bool holds, bool overlap) {
      if (!holds) return;
      ++contained;
      violations += !overlap;
    };
    const Frame lf{f.scale, {}};
    // Containers: sphere s, aabb a, obb o; contents moved so their centre is the drawn point.
    {
      Sphere t = g.sphere(lf);
      t.center = in_sphere(), check(contains(s, t.center), overlaps(s, t));
      t.center = in_aabb(), check(contains(a, t.center), overlaps(a, t));
      t.center = in_obb(), check(contains(o, t.center), overlaps(o, t));
    }
    {
      AABB t = g.aabb(lf);
      t.center = in_sphere(), check(contains(s, t.center), overlaps(s, t));
      t.center = in_aabb(), check(contains(a, t.center), overlaps(a, t));
      t.center = in_obb(), check(contains(o, t.center), overlaps(o, t));
    }
    {
      OBB t = g.obb(lf);
      t.center = in_sphere(), check(contains(s, t.center), overlaps(s, t));
      t.center = in_aabb(), check(contains(a, t.center), overlaps(a, t));
      t.center = in_obb(), check(contains(o, t.center), overlaps(o, t));
    }
    for (const vec3& p : {in_sphere(), in_aabb(), in_obb(), g.near(f, 3)}) {
      const Sphere point{p, 0};
      point_cases += 3;
      point_violations += (contains(s, p) && !overlaps(s, point)) + (contains(a, p) && !overlaps(a, point)) +
                          (contains(o, p) && !overlaps(o, point));
      // And the converse for a point: overlapping the radius-0 sphere means containing it.
      point_violations += (overlaps(s, point) != contains(s, p)) + (overlaps(a, point) != contains(a, p)) +
                          (overlaps(o, point) != contains(o, p));
    }
  }
  std::printf("  %zu containments of a centre, %zu without overlap; %zu point checks, %zu where contains(shape, p) "
              "and overlaps(shape, radius-0 sphere at p) differ\n",
              contained, violations, point_cases, point_violations);
  EXPECT_GT(contained, 300000u);
  EXPECT_EQ(violations, 0u);
  EXPECT_EQ(point_violations, 0u);
}

// ---------------------------------------------------------------- hand-picked cases
TEST(Overlap, HandPickedCases) {
  const Sphere unit{{0, 0, 0}, 1};
  EXPECT_TRUE(overlaps(unit, Sphere{{2, 0, 0}, 1}));  // touching
  EXPECT_FALSE(overlaps(unit, Sphere{{2.0000002f, 0, 0}, 1}));
  EXPECT_TRUE(overlaps(unit, Sphere{{0.5f, 0, 0}, 0}));  // a point inside

  const AABB cube{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(overlaps(Sphere{{2, 0, 0}, 1}, cube));       // touching a face
  EXPECT_TRUE(overlaps(cube, Sphere{{2, 2, 1}, 1.4142137f}));  // just past sqrt(2) from an edge
  EXPECT_FALSE(overlaps(Sphere{{2, 2, 2}, 1.7f}, cube));   // the corner is sqrt(3) = 1.732 away
  EXPECT_TRUE(overlaps(cube, AABB{{2, 2, 2}, {1, 1, 1}}));  // corner to corner
  EXPECT_FALSE(overlaps(cube, AABB{{2, 2, 2.0000002f}, {1, 1, 1}}));
  EXPECT_TRUE(overlaps(cube, AABB{{0, 0, 0}, {0, 0, 0}}));  // a point at the centre

  mat3 turn;  // 45 degrees about z
  const float h = 0.70710678f;
  turn.m[0][0] = h, turn.m[0][1] = h, turn.m[1][0] = -h, turn.m[1][1] = h;
  const OBB diamond{{0, 0, 0}, {1, 1, 1}, turn};  // reaches x = sqrt(2) along world x
  EXPECT_TRUE(overlaps(diamond, AABB{{2.4f, 0, 0}, {1, 1, 1}}));
  EXPECT_FALSE(overlaps(AABB{{2.5f, 0, 0}, {1, 1, 1}}, diamond));
  EXPECT_TRUE(overlaps(Sphere{{1.4f, 0, 0}, 0.1f}, diamond));
  EXPECT_FALSE(overlaps(diamond, Sphere{{1.6f, 0, 0}, 0.1f}));
  EXPECT_TRUE(overlaps(diamond, OBB{{2.8f, 0, 0}, {1, 1, 1}, turn}));   // 2 sqrt(2) = 2.83 apart
  EXPECT_FALSE(overlaps(diamond, OBB{{2.9f, 0, 0}, {1, 1, 1}, turn}));

  const Plane ground{{0, 1, 0}, 0};
  EXPECT_TRUE(overlaps(ground, Sphere{{5, 1, 5}, 1}));  // resting on it
  EXPECT_FALSE(overlaps(Sphere{{5, 1.0000001f, 5}, 1}, ground));
  EXPECT_TRUE(overlaps(AABB{{0, 1, 0}, {1, 1, 1}}, ground));
  EXPECT_FALSE(overlaps(ground, AABB{{0, 1.5f, 0}, {1, 1, 1}}));
  EXPECT_TRUE(overlaps(diamond, Plane{{1, 0, 0}, 1.4f}));
  EXPECT_FALSE(overlaps(Plane{{1, 0, 0}, 1.5f}, diamond));
  EXPECT_TRUE(overlaps(AABB{{0, 0, 0}, {0, 0, 0}}, ground));  // a point on the plane

  EXPECT_TRUE(overlaps(ground, Plane{{1, 0, 0}, 7}));     // perpendicular: they meet
  EXPECT_TRUE(overlaps(ground, Plane{{0, 1, 0}, 0}));     // the same plane
  EXPECT_TRUE(overlaps(ground, Plane{{0, -1, 0}, 0}));    // the same plane, facing down
  EXPECT_FALSE(overlaps(ground, Plane{{0, 1, 0}, 1}));    // parallel and distinct
  EXPECT_FALSE(overlaps(ground, Plane{{0, -1, 0}, 1}));   // y = -1
  EXPECT_TRUE(overlaps(Plane{{0, 1, 0}, 3}, Plane{{0, -1, 0}, -3}));
  EXPECT_TRUE(overlaps(ground, Plane{{0, 1, 0}, 5e-7f}));  // within the surface tolerance
  const float s = 1e-4f, c = std::sqrt(1 - s * s);  // tilted 1e-4 rad: they meet 1e4 away
  EXPECT_TRUE(overlaps(ground, Plane{{s, c, 0}, 1}));
}

TEST(Overlap, NanInputsGiveDefinedResults) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Sphere ns{{nan, 0, 0}, 1};
  const AABB na{{0, 0, 0}, {nan, 1, 1}};
  OBB no{{0, 0, 0}, {1, 1, 1}, mat3{}};
  no.orientation.m[1][1] = nan;
  const Plane np{{0, nan, 0}, 0};
  const Sphere s{{0, 0, 0}, 1};
  // Any answer is allowed; it must be computed without trapping and be repeatable.
  const bool r[] = {overlaps(ns, s), overlaps(ns, na), overlaps(s, no), overlaps(ns, np), overlaps(na, na),
                    overlaps(na, no), overlaps(na, np), overlaps(no, no), overlaps(no, np), overlaps(np, np)};
  const bool again[] = {overlaps(ns, s), overlaps(ns, na), overlaps(s, no), overlaps(ns, np), overlaps(na, na),
                        overlaps(na, no), overlaps(na, np), overlaps(no, no), overlaps(no, np), overlaps(np, np)};
  for (int i = 0; i < 10; ++i) EXPECT_EQ(r[i], again[i]);
  EXPECT_FALSE(overlaps(ns, s));  // NaN distances compare false
}

// ---------------------------------------------------------------- per-level probe
// Every lane template at every available SIMD level against the scalar level, bit for bit:
// random overlapping and separated shapes at all frames, exact touches, zero sizes,
// identical shapes, and 10% of the rows with raw random bit patterns (NaN, infinities,
// subnormals) in some columns. The count is not a multiple of any lane width (tails).
TEST(OverlapProbe, EveryTemplateIsBitIdenticalAtEveryLevel) {
  constexpr std::size_t n = 20011;
  Rng g(212);
  std::vector<std::vector<float>> in(kProbeInputs, std::vector<float>(n));
  auto put3 = [&](int k, std::size_t i, const vec3& v) { in[k][i] = v.x, in[k + 1][i] = v.y, in[k + 2][i] = v.z; };
  auto put_sphere = [&](int k, std::size_t i, const Sphere& s) { put3(k, i, s.center), in[k + 3][i] = s.radius; };
  auto put_aabb = [&](int k, std::size_t i, const AABB& b) { put3(k, i, b.center), put3(k + 3, i, b.half_extents); };
  auto put_obb = [&](int k, std::size_t i, const OBB& b) {
    put3(k, i, b.center), put3(k + 3, i, b.half_extents);
    for (int a = 0; a < 3; ++a) put3(k + 6 + 3 * a, i, {b.orientation.m[a][0], b.orientation.m[a][1], b.orientation.m[a][2]});
  };
  auto put_plane = [&](int k, std::size_t i, const Plane& p) { put3(k, i, p.normal), in[k + 3][i] = p.distance; };
  for (std::size_t i = 0; i < n; ++i) {
    const Frame f = g.frame();
    Sphere sa = g.sphere(f), sb = g.sphere(f);
    AABB aa = g.aabb(f), ab = g.aabb(f);
    OBB oa = g.obb(f), ob = g.obb(f);
    Plane pa = g.plane(f), pb = g.plane(f);
    vec3 p = g.near(f, 3);
    Line seg{g.near(f, 2), g.near(f, 2)};
    switch (i % 8) {
      case 0: sb = sa, ab = aa, ob = oa, pb = pa, p = oa.center; break;  // identical shapes
      case 1:  // zero sizes
        sa.radius = sb.radius = 0, aa.half_extents = ab.half_extents = {0, 0, 0};
        oa.half_extents = {0, 0, 0}, ob.half_extents.y = 0, seg.end = seg.start, pb.normal = pa.normal;
        break;
      case 2: {  // exact touches
        const double q = kDyadic[g.pick(3)];
        sa = {g.dyadic3(q), f32(q * g.pick(64))}, sb = {sa.center, f32(q * g.pick(64))};
        sb.center.x += sa.radius + sb.radius;
        aa = {sa.center, {f32(q * g.pick(64)), f32(q * g.pick(64)), f32(q * g.pick(64))}};
        ab = {aa.center, aa.half_extents};
        ab.center.y += 2 * aa.half_extents.y;
        oa = {aa.center, aa.half_extents, g.signed_permutation()}, ob = {ab.center, ab.half_extents, g.signed_permutation()};
        pa = {{0, 1, 0}, aa.center.y + aa.half_extents.y}, pb = {{0, -1, 0}, -pa.distance};
        p = aa.center + aa.half_extents;
        break;
      }
      default: break;
    }
    put_sphere(kInSphereA, i, sa), put_sphere(kInSphereB, i, sb);
    put_aabb(kInAabbA, i, aa), put_aabb(kInAabbB, i, ab);
    put_obb(kInObbA, i, oa), put_obb(kInObbB, i, ob);
    put_plane(kInPlaneA, i, pa), put_plane(kInPlaneB, i, pb);
    put3(kInPoint, i, p), put3(kInSegment, i, seg.start), put3(kInSegment + 3, i, seg.end);
    if (g.pick(10) == 0) {  // raw bit patterns in a few columns
      const float specials[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                -std::numeric_limits<float>::infinity(), 1e-40f, -0.0f, 3.4e38f};
      for (int c = 0, count = 1 + g.pick(4); c < count; ++c) {
        const int col = g.pick(kProbeInputs);
        in[col][i] = g.pick(2) ? std::bit_cast<float>(uint32_t(g.bits())) : specials[g.pick(6)];
      }
    }
  }
  auto run = [&](SimdLevel level) {
    std::vector<std::vector<float>> out(kProbeOutputs, std::vector<float>(n, -7.0f));
    OverlapProbeArgs args{};
    for (int k = 0; k < kProbeInputs; ++k) args.in[k] = in[k].data();
    for (int k = 0; k < kProbeOutputs; ++k) args.out[k] = out[k].data();
    detail::overlap_probe_for(level)(args, 0, n);
    return out;
  };
  const auto ref = run(SimdLevel::scalar);
  // The scalar level is the public API: spot-check it against the scalar calls.
  for (std::size_t i = 0; i < n; i += 97) {
    auto v = [&](int k) { return vec3{in[k][i], in[k + 1][i], in[k + 2][i]}; };
    const Sphere sa{v(kInSphereA), in[kInSphereA + 3][i]}, sb{v(kInSphereB), in[kInSphereB + 3][i]};
    const OBB oa{v(kInObbA), v(kInObbA + 3), mat3{{{in[kInObbA + 6][i], in[kInObbA + 7][i], in[kInObbA + 8][i]},
                                                   {in[kInObbA + 9][i], in[kInObbA + 10][i], in[kInObbA + 11][i]},
                                                   {in[kInObbA + 12][i], in[kInObbA + 13][i], in[kInObbA + 14][i]}}}};
    const Plane pb{v(kInPlaneB), in[kInPlaneB + 3][i]};
    EXPECT_EQ(ref[kOutSphereSphere][i], overlaps(sa, sb) ? 1.0f : 0.0f);
    EXPECT_EQ(ref[kOutObbPlane][i], overlaps(oa, pb) ? 1.0f : 0.0f);
    EXPECT_EQ(ref[kOutContainsObb][i], contains(oa, v(kInPoint)) ? 1.0f : 0.0f);
    const vec3 q = closest_point(oa, v(kInPoint));
    EXPECT_EQ(detail::canonical_float_bits(ref[kOutClosestObb][i]), detail::canonical_float_bits(q.x));
  }
  std::size_t ones = 0;
  for (int k = kOutSphereSphere; k < kProbeOutputs; ++k)
    for (std::size_t i = 0; i < n; ++i) ones += ref[k][i] == 1.0f;
  EXPECT_GT(ones, n) << "the probe's overlap columns must hold both answers";
  int levels = 0;
  for (uint32_t v = 2; v <= 5; ++v) {
    const SimdLevel level = SimdLevel(v);
    if (!simd_level_available(level)) continue;
    ++levels;
    const auto got = run(level);
    std::size_t mismatches = 0;
    for (int k = 0; k < kProbeOutputs; ++k)
      for (std::size_t i = 0; i < n; ++i)
        if (detail::canonical_float_bits(got[k][i]) != detail::canonical_float_bits(ref[k][i])) {
          if (mismatches++ < 5) ADD_FAILURE() << simd_level_name(level) << ": output " << k << " row " << i;
        }
    std::printf("  probe at %s: %zu rows x %d outputs, %zu bits differ from scalar\n", simd_level_name(level), n,
                int(kProbeOutputs), mismatches);
    EXPECT_EQ(mismatches, 0u);
  }
  EXPECT_GE(levels, 1) << "no SIMD level available to compare";
}

}  // namespace
}  // namespace gyro
