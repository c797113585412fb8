// Triangles (gyro/triangle.hpp): every function against an independent binary64 reference
// on 10^5 seeded cases each, hard cases mixed in (touching, parallel faces and edges,
// zero-area and point triangles, slivers, zero-size boxes and spheres, rays parallel to the
// plane or through edges, scales 1e-3 to 1e4, positions up to 1e4 from the origin);
// properties (symmetry, containment implies overlap, the closest point is on the triangle
// and no sample of the triangle is nearer); the documented degenerate answers; and bit
// identity of the lane templates at every SIMD level.
//
// How float and binary64 may legitimately disagree (the "band"): a yes/no answer may flip
// only where moving the shapes by tol would flip it (touching to within tol); a computed
// point or parameter may be off by the few roundings of its inputs' magnitude ("tight")
// plus the conditioning of the case (thin triangles, far query points, grazing rays),
// stated per test. Each test counts disagreements inside the band (printed) and outside it
// (must be 0), and prints its largest error, also in units of its rounding bound.
#include "gyro/triangle.hpp"

#include "core/state_hash.hpp"
#include "gyro/runtime.hpp"
#include "triangle_probe.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <limits>
#include <vector>

namespace gyro {
namespace {

constexpr double kEps = 0x1p-24;  // float's unit roundoff
constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------ binary64 vectors
struct R3 {
  double x = 0, y = 0, z = 0;
};
R3 operator+(R3 a, R3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
R3 operator-(R3 a, R3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
R3 operator*(R3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(R3 a, R3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
R3 cross(R3 a, R3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(R3 a) { return std::sqrt(dot(a, a)); }
double maxabs(R3 a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }
R3 r3(const vec3& v) { return {v.x, v.y, v.z}; }
vec3 f3(R3 v) { return {float(v.x), float(v.y), float(v.z)}; }
double coord(R3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

struct RTri {
  R3 a, b, c;
  R3 corner(int k) const { return k == 0 ? a : (k == 1 ? b : c); }
};
RTri rtri(const Triangle& t) { return {r3(t.a), r3(t.b), r3(t.c)}; }

// The largest side of the triangle's bounding box, and its largest |coordinate|.
double tri_size(const RTri& t) {
  double s = 0;
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({coord(t.a, k), coord(t.b, k), coord(t.c, k)});
    const double hi = std::max({coord(t.a, k), coord(t.b, k), coord(t.c, k)});
    s = std::max(s, hi - lo);
  }
  return s;
}
double tri_mag(const RTri& t) { return std::max({maxabs(t.a), maxabs(t.b), maxabs(t.c)}); }

// 1 / sin of the angle at a: how much the float normal's direction is amplified.
double tri_kappa(const RTri& t) {
  const R3 ab = t.b - t.a, ac = t.c - t.a;
  const double n = norm(cross(ab, ac)), l = norm(ab) * norm(ac);
  return n > 0 ? l / n : kInf;
}

// The documented degeneracy rule, evaluated in binary64 (float evaluates it with rounding,
// so the two may differ within a factor of about 1 +- 1e-6 of the threshold).
double tri_sin2(const RTri& t) {
  const R3 ab = t.b - t.a, ac = t.c - t.a;
  const double l = dot(ab, ab) * dot(ac, ac);
  return l > 0 ? dot(cross(ab, ac), cross(ab, ac)) / l : 0.0;
}
constexpr double kDegenerateSin2 = 0x1p-36;
bool near_degenerate_threshold(const RTri& t) {
  const double s2 = tri_sin2(t);
  return s2 > kDegenerateSin2 * 0.5 && s2 < kDegenerateSin2 * 2;
}

// ------------------------------------------------------------------ binary64 references
R3 ref_segment_closest(R3 p, R3 a, R3 b) {
  const R3 ab = b - a;
  const double l = dot(ab, ab);
  const double t = l > 0 ? std::clamp(dot(p - a, ab) / l, 0.0, 1.0) : 0.0;
  return a + ab * t;
}

// The Cookbook's way, not Ericson's: project on the plane, keep the projection if it is
// inside (signs of the three edge functions), else the nearest of the three edge points.
R3 ref_closest(const RTri& t, R3 p) {
  const R3 qs[3] = {ref_segment_closest(p, t.a, t.b), ref_segment_closest(p, t.b, t.c), ref_segment_closest(p, t.c, t.a)};
  R3 best = qs[0];
  for (const R3& q : qs)
    if (norm(p - q) < norm(p - best)) best = q;
  const R3 ab = t.b - t.a, ac = t.c - t.a, n = cross(ab, ac);
  const double nn = dot(n, n);
  if (nn > 1e-28 * dot(ab, ab) * dot(ac, ac) && nn > 0) {
    const R3 q = p - n * (dot(p - t.a, n) / nn);
    const double ea = dot(n, cross(t.b - q, t.c - q)), eb = dot(n, cross(t.c - q, t.a - q)),
                 ec = dot(n, cross(t.a - q, t.b - q));
    if (ea >= 0 && eb >= 0 && ec >= 0) return q;
  }
  return best;
}
double ref_distance(const RTri& t, R3 p) { return norm(p - ref_closest(t, p)); }

// Closest points of two segments (Ericson 5.1.9) in binary64: their distance.
double ref_segment_segment(R3 p1, R3 q1, R3 p2, R3 q2) {
  const R3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return norm(p1 - p2);
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return norm((p1 + d1 * s) - (p2 + d2 * t));
}

// True when segment [p, q] crosses the plane of a non-degenerate triangle at a point inside it.
bool ref_segment_pierces(R3 p, R3 q, const RTri& t) {
  const R3 n = cross(t.b - t.a, t.c - t.a);
  const double nn = norm(n);
  if (!(nn > 0)) return false;
  const double sp = dot(p - t.a, n) / nn, sq = dot(q - t.a, n) / nn;
  if (sp * sq > 0 || (sp == 0 && sq == 0)) return false;
  const R3 x = p + (q - p) * (sp / (sp - sq));
  return dot(n, cross(t.b - x, t.c - x)) >= 0 && dot(n, cross(t.c - x, t.a - x)) >= 0 &&
         dot(n, cross(t.a - x, t.b - x)) >= 0;
}

// Distance between two triangles: 0 when an edge of one pierces the other, else the least
// of the 9 edge-edge and 6 vertex-triangle distances (where the distance of two disjoint
// convex polygons is attained).
double ref_triangle_distance(const RTri& A, const RTri& B) {
  for (int i = 0; i < 3; ++i) {
    if (ref_segment_pierces(A.corner(i), A.corner((i + 1) % 3), B)) return 0.0;
    if (ref_segment_pierces(B.corner(i), B.corner((i + 1) % 3), A)) return 0.0;
  }
  double d = kInf;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      d = std::min(d, ref_segment_segment(A.corner(i), A.corner((i + 1) % 3), B.corner(j), B.corner((j + 1) % 3)));
    d = std::min(d, ref_distance(B, A.corner(i)));
    d = std::min(d, ref_distance(A, B.corner(i)));
  }
  return d;
}

// Each corner moved towards the centroid by at most `by`.
RTri shrink(const RTri& t, double by) {
  const R3 g = (t.a + t.b + t.c) * (1.0 / 3.0);
  const double r = std::max({norm(t.a - g), norm(t.b - g), norm(t.c - g)});
  const double f = r > 0 ? std::min(1.0, by / r) : 0.0;
  return {g + (t.a - g) * (1 - f), g + (t.b - g) * (1 - f), g + (t.c - g) * (1 - f)};
}

// Triangle (corners in a box's frame) clipped by Sutherland-Hodgman to |x_k| <= e_k: not
// empty exactly when they overlap (closed sets: touching leaves a point). Clipped points
// are snapped onto the clipping plane so the next plane sees them exactly on it.
bool ref_clip_overlap(const std::array<R3, 3>& tri, R3 e) {
  std::vector<R3> poly(tri.begin(), tri.end()), next;
  for (int k = 0; k < 3; ++k) {
    for (double side : {1.0, -1.0}) {
      const double bound = side * coord(e, k);
      auto inside = [&](R3 p) { return side * coord(p, k) <= coord(e, k); };
      next.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const R3 cur = poly[i], nxt = poly[(i + 1) % poly.size()];
        if (inside(cur)) next.push_back(cur);
        if (inside(cur) != inside(nxt)) {
          const double s = (bound - coord(cur, k)) / (coord(nxt, k) - coord(cur, k));
          R3 x = cur + (nxt - cur) * s;
          (k == 0 ? x.x : (k == 1 ? x.y : x.z)) = bound;
          next.push_back(x);
        }
      }
      poly.swap(next);
      if (poly.empty()) return false;
    }
  }
  return true;
}

// Ray against triangle by Cramer's rule in binary64 (not the sheared edge functions):
// weights (u, v, w) of a, b, c and t; hit when all weights are >= 0 and t >= 0.
struct RefRay {
  bool hit = false;
  double t = kInf, u = 0, v = 0, w = 0;
  bool parallel = false;
};
RefRay ref_ray(R3 o, R3 d, const RTri& tr) {
  RefRay r;
  const R3 e1 = tr.b - tr.a, e2 = tr.c - tr.a, pv = cross(d, e2);
  const double det = dot(e1, pv);
  if (det == 0) {
    r.parallel = true;
    return r;
  }
  const R3 tv = o - tr.a, qv = cross(tv, e1);
  r.v = dot(tv, pv) / det;
  r.w = dot(d, qv) / det;
  r.u = 1 - r.v - r.w;
  r.t = dot(e2, qv) / det;
  r.hit = r.u >= 0 && r.v >= 0 && r.w >= 0 && r.t >= 0;
  return r;
}

// Distance from the half-line o + t d (t >= 0) to the triangle's boundary, approximated by
// a segment long enough to pass the triangle.
double ray_boundary_distance(R3 o, R3 d, const RTri& t) {
  const double reach = std::max({norm(t.a - o), norm(t.b - o), norm(t.c - o)}) * 4 + 1;
  const R3 far = o + d * (reach / norm(d));
  double best = kInf;
  for (int i = 0; i < 3; ++i) best = std::min(best, ref_segment_segment(o, far, t.corner(i), t.corner((i + 1) % 3)));
  return best;
}

// ------------------------------------------------------------------ seeded cases
// kDrawOrder: the operands of an overloaded operator (R3's + and *) are function
// arguments, which g++ evaluates right to left and clang++ left to right, so an expression
// with two random draws in it would test other cases on each compiler. Draws go into named
// values first, in the order g++ made them (so its cases are unchanged); braced lists and
// the operands of built-in operators on doubles need no care.
class Gen {
 public:
  explicit Gen(uint64_t seed) : rng_(seed) {}
  double u() { return rng_.u(); }
  double s() { return 2.0 * rng_.u() - 1.0; }
  int pick(int n) { return int(rng_.next() % uint64_t(n)); }
  R3 cube() { return {s(), s(), s()}; }
  R3 unit() {
    for (;;) {
      const R3 v = cube();
      const double l = norm(v);
      if (l > 0.1 && l <= 1) return v * (1 / l);
    }
  }

  // A new frame for the next case: scale 1e-3, 1 or 1e4; centred at the origin or up to
  // 1e3 or 1e4 away from it.
  double scale = 1;
  R3 offset;
  void new_frame() {
    const int k = pick(10);
    scale = k < 2 ? 1e-3 : (k < 8 ? 1.0 : 1e4);
    const int o = pick(10);
    offset = o < 6 ? R3{} : cube() * (o < 8 ? 1e3 : 1e4);
  }
  R3 at(R3 local) { return offset + local * scale; }
  vec3 fat(R3 local) { return f3(at(local)); }

  static constexpr int kTriangleKinds = 10;
  // Kinds: 0-2 general, 3 in an axis plane, 4 sliver, 5 corners collinear up to rounding,
  // 6 exactly collinear on an axis line, 7 two corners coincident, 8 a point, 9 a needle
  // (one edge 1e-4 of the others).
  Triangle triangle(int kind) {
    R3 a = cube(), b = cube(), c = cube();
    switch (kind) {
      case 3: {
        const int k = pick(3);
        const double v = s();
        for (R3* p : {&a, &b, &c}) (k == 0 ? p->x : (k == 1 ? p->y : p->z)) = v;
        break;
      }
      case 4: {
        const R3 ab = b - a;
        R3 perp = cross(ab, unit());
        perp = perp * (norm(ab) / std::max(norm(perp), 1e-300));
        // Draws into named values first (see kDrawOrder): g++ took the exponent first.
        const double ex = u(), along = u();
        c = a + ab * along + perp * std::pow(10.0, -2.0 - 4.0 * ex);
        break;
      }
      case 5: c = a + (b - a) * (1.5 * s()); break;
      case 6: b.y = c.y = a.y, b.z = c.z = a.z; break;
      case 7: b = a; break;
      case 8: b = c = a; break;
      case 9: b = a + cube() * 1e-4; break;
      default: break;
    }
    return {fat(a), fat(b), fat(c)};
  }
  Triangle triangle() { return triangle(pick(kTriangleKinds)); }

  // A point in the triangle, computed in binary64 and rounded once.
  R3 inside(const Triangle& t) {
    double x = u(), y = u();
    if (x + y > 1) x = 1 - x, y = 1 - y;
    const RTri r = rtri(t);
    return r.a + (r.b - r.a) * x + (r.c - r.a) * y;
  }
  // Query points: 0 near, 1 in the triangle, 2 on an edge, 3 a corner, 4 off the plane by
  // 1e-7..1e-2 of the size, 5 just outside an edge in the plane, 6 far (100 sizes).
  vec3 point(const Triangle& t) {
    const RTri r = rtri(t);
    const double size = std::max(tri_size(r), 1e-30);
    switch (pick(7)) {
      case 0: return fat(cube() * 1.5);
      case 1: return f3(inside(t));
      case 2: {
        const int k = pick(3);
        return f3(r.corner(k) + (r.corner((k + 1) % 3) - r.corner(k)) * u());
      }
      case 3: return pick(3) == 0 ? t.a : (pick(2) ? t.b : t.c);
      case 4: {
        R3 n = cross(r.b - r.a, r.c - r.a);
        n = norm(n) > 0 ? n * (1 / norm(n)) : unit();
        const double side = s(), ex = u();  // before inside(t)'s draws, as g++ ordered them
        return f3(inside(t) + n * (size * side * std::pow(10.0, -2.0 - 5.0 * ex)));
      }
      case 5: {
        const int k = pick(3);
        const R3 p = r.corner(k), q = r.corner((k + 1) % 3), o = r.corner((k + 2) % 3);
        const R3 e = q - p;
        R3 out = cross(cross(e, o - p), e);  // in-plane, towards o
        out = norm(out) > 0 ? out * (-1 / norm(out)) : unit();
        const double ex = u(), along = u();
        return f3(p + e * along + out * (size * std::pow(10.0, -1.0 - 6.0 * ex)));
      }
      default: return fat(cube() * 100.0);
    }
  }

 private:
  gyro::testing::SplitMix64 rng_;
};

// ------------------------------------------------------------------ statistics
void print_case(const char* what, const Triangle& t, const vec3& p) {
  std::printf("    %s: triangle (%.9g %.9g %.9g) (%.9g %.9g %.9g) (%.9g %.9g %.9g) point (%.9g %.9g %.9g)\n", what, t.a.x,
              t.a.y, t.a.z, t.b.x, t.b.y, t.b.z, t.c.x, t.c.y, t.c.z, p.x, p.y, p.z);
}

// A yes/no answer against the reference: agreement, disagreement inside the band (the case
// is within tol of flipping), disagreement outside it.
struct Verdicts {
  const char* name;
  std::size_t cases = 0, positives = 0, in_band = 0, outside = 0;
  // Returns true for a disagreement outside the band (the caller prints the first few).
  bool add(bool got, bool ref, bool band) {
    ++cases;
    positives += ref;
    if (got != ref) ++(band ? in_band : outside);
    return got != ref && !band && outside <= 5;
  }
  void print() const {
    std::printf("  %-26s %7zu cases (%zu overlapping/inside by the reference), disagreements: %zu inside the band, "
                "%zu outside\n",
                name, cases, positives, in_band, outside);
  }
};

// A computed quantity: errors up to `tight` are the expected rounding; up to `band` the
// conditioning of the case allows them; beyond is a failure. max_* in units of the scale.
struct Errors {
  const char* name;
  std::size_t cases = 0, in_band = 0, outside = 0;
  double max_err = 0, max_ratio = 0;  // absolute, and in units of the case's rounding bound
  // Returns true for an error outside the band (the caller prints the first few).
  bool add(double err, double tight, double band) {
    ++cases;
    const bool out = !(err <= tight) && !(err <= band);
    if (!(err <= tight)) ++(out ? outside : in_band);
    if (!(err <= max_err)) max_err = err;
    if (tight > 0 && !(err / tight <= max_ratio)) max_ratio = err / tight;
    return out && outside <= 5;
  }
  void print() const {
    std::printf("  %-26s %7zu cases, beyond rounding: %zu inside the band, %zu outside; max error %.3g, "
                "%.3g x its rounding bound\n",
                name, cases, in_band, outside, max_err, max_ratio);
  }
};

constexpr int kCases = 100000;

// ------------------------------------------------------------------ closest point, contains
// Closest point. Band: the float point must be on the triangle and as near to p as the
// reference point, both to within
//   tight = 16 eps (mag + D)             (roundings of the coordinates and of the offset D)
//   band  = tight + 16 eps kappa (D + size) + 4e-6 size
// where kappa = 1/sin(angle at a) amplifies the normal's rounding on thin triangles, and
// 4e-6 size covers the degenerate rule (a triangle under the 3.8e-6 rad threshold is
// answered by its boundary, at most its inradius away). Position error is also reported.
TEST(TriangleClosestPoint, AgreesWithReference) {
  Gen g(11);
  Errors on{"distance from triangle"}, dist{"|p - q| vs reference"}, pos{"position vs reference"};
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const vec3 p = g.point(t);
    const vec3 q = closest_point(t, p);
    const RTri rt = rtri(t);
    const R3 rp = r3(p), rq = r3(q);
    const R3 ref = ref_closest(rt, rp);
    const double D = norm(rp - ref), size = tri_size(rt), mag = std::max(tri_mag(rt), maxabs(rp));
    const double kappa = std::min(tri_kappa(rt), 1e30);
    const double tight = 16 * kEps * (mag + D);
    const double band = tight + 16 * kEps * kappa * (D + size) + 4e-6 * size;
    on.add(ref_distance(rt, rq), tight, band);
    dist.add(std::abs(norm(rp - rq) - D), tight, band);
    pos.add(norm(rq - ref), 16 * kEps * (mag + D), kInf);
  }
  on.print(), dist.print(), pos.print();
  EXPECT_EQ(on.outside, 0u);
  EXPECT_EQ(dist.outside, 0u);
}

// The closest point is on the triangle (contains) and no sample of the triangle is nearer
// (a 41 x 41 barycentric grid in binary64), for points within 10 sizes. Farther away the
// float projection carries eps * distance, which contains()'s size-relative tolerance does
// not cover; the reference test above measures those.
TEST(TriangleClosestPoint, IsOnTheTriangleAndNoSampleIsNearer) {
  Gen g(12);
  std::size_t not_contained = 0, nearer_samples = 0, checked = 0;
  double worst = 0;
  for (int i = 0; i < 3000; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const vec3 p = g.point(t);
    const RTri rt = rtri(t);
    const double size = tri_size(rt), mag = std::max(tri_mag(rt), maxabs(r3(p)));
    const vec3 q = closest_point(t, p);
    const double dq = norm(r3(p) - r3(q));
    if (dq > 10 * size) continue;
    ++checked;
    if (!contains(t, q)) ++not_contained;
    const double tol = 1e-5 * size + 64 * kEps * (mag + dq) + 16 * kEps * tri_kappa(rt) * (size + dq);
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; a + b <= 40; ++b) {
        const R3 s = rt.a + (rt.b - rt.a) * (a / 40.0) + (rt.c - rt.a) * (b / 40.0);
        const double ds = norm(r3(p) - s);
        if (ds < dq - tol) ++nearer_samples;
        if (size > 0) worst = std::max(worst, (dq - ds) / size);
      }
  }
  std::printf("  %zu points within 10 sizes: %zu closest points not contained, %zu samples nearer than the closest "
              "point beyond tolerance; largest (|p-q| - |p-sample|)/size %.3g\n",
              checked, not_contained, nearer_samples, worst);
  EXPECT_GT(checked, 2000u);
  EXPECT_EQ(not_contained, 0u);
  EXPECT_EQ(nearer_samples, 0u);
}

// contains(). Reference: binary64 distance D from the reference closest point, against the
// documented tolerance computed in binary64 from the same inputs. Band: |D - tol| within
// the closest point's error (above) plus 2 eps tol.
TEST(TriangleContains, AgreesWithReference) {
  Gen g(13);
  Verdicts v{"contains"};
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const vec3 p = g.point(t);
    const RTri rt = rtri(t);
    const R3 rp = r3(p);
    const double size = tri_size(rt), mag = std::max(tri_mag(rt), maxabs(rp));
    const double tol = 1e-5 * size + 0x1p-20 * mag;
    const double D = ref_distance(rt, rp);
    const double err = 16 * kEps * (mag + D) + 16 * kEps * std::min(tri_kappa(rt), 1e30) * (D + size) + 4e-6 * size;
    v.add(contains(t, p), D <= tol, std::abs(D - tol) <= err + 2 * kEps * tol);
  }
  v.print();
  EXPECT_EQ(v.outside, 0u);
  EXPECT_GT(v.positives, 20000u);  // the hard cases put many points on the triangle
}

TEST(TriangleContains, CornersEdgesAndInteriorPointsAreContained) {
  Gen g(14);
  std::size_t missed = 0, n = 0;
  for (int i = 0; i < 20000; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const RTri rt = rtri(t);
    for (const vec3& p : {t.a, t.b, t.c, f3((rt.a + rt.b) * 0.5), f3(g.inside(t))}) {
      ++n;
      if (!contains(t, p)) ++missed;
    }
  }
  std::printf("  %zu corners, edge midpoints and interior points (rounded to float once): %zu not contained\n", n,
              missed);
  EXPECT_EQ(missed, 0u);
}

// ------------------------------------------------------------------ barycentric
// Reference: the normal equations of p - a = v (b - a) + w (c - a) in binary64 (Gram
// matrix), a different formula from gyro's edge functions; for triangles degenerate by
// the documented rule, the documented projection on the longest edge. Band on each of u,
// v, w: tight = 64 eps (1 + max |weight|); band = tight + 16 x (how far the reference
// moves when the inputs move by 1 ulp) + 64 eps (R + size)^2 / |n|, with R = |p - a| and
// |n| twice the area: the signed areas v |n|, w |n| are cross products of vectors of
// length about R + size, rounded to eps of that squared (degenerate: 64 eps (R + size) /
// longest edge). A triangle within a factor 2 of the degeneracy threshold may be
// classified either way and is in the band. u + v + w = 1 within 4 eps (1 + max |weight|).
// The reference coordinates (see above) of p in t; `degenerate` picks the documented
// answer for degenerate triangles.
R3 ref_barycentric(R3 p, const RTri& t, bool degenerate) {
  const R3 ab = t.b - t.a, ac = t.c - t.a, bc = t.c - t.b, ap = p - t.a;
  if (degenerate) {
    const double lab = dot(ab, ab), lac = dot(ac, ac), lbc = dot(bc, bc);
    if (lab >= lac && lab >= lbc) {
      const double s = lab > 0 ? dot(ap, ab) / lab : 0;
      return {1 - s, s, 0};
    }
    if (lac >= lbc) {
      const double s = dot(ap, ac) / lac;
      return {1 - s, 0, s};
    }
    const double s = dot(p - t.b, bc) / lbc;
    return {0, 1 - s, s};
  }
  const double d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac), d20 = dot(ap, ab), d21 = dot(ap, ac);
  const double den = d00 * d11 - d01 * d01;
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1 - v - w, v, w};
}

// How far the reference moves when every input coordinate moves by up to 1 ulp of float:
// the conditioning of the case (float rounds b - a and p - a wherever the coordinates are
// not within a factor 2 of each other, which is exactly such a perturbation).
double barycentric_conditioning(Gen& g, R3 p, const RTri& t, bool degenerate, R3 ref) {
  auto jiggle = [&](R3 v) { return R3{v.x * (1 + 2 * kEps * g.s()), v.y * (1 + 2 * kEps * g.s()), v.z * (1 + 2 * kEps * g.s())}; };
  double worst = 0;
  for (int k = 0; k < 4; ++k) {
    const R3 q = ref_barycentric(jiggle(p), RTri{jiggle(t.a), jiggle(t.b), jiggle(t.c)}, degenerate);
    worst = std::max(worst, maxabs(q - ref));
  }
  return worst;
}

TEST(TriangleBarycentric, AgreesWithReference) {
  Gen g(15);
  Errors e{"barycentric (u, v, w)"};
  Errors sum{"|u + v + w - 1|"};
  std::size_t degenerate = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const vec3 p = g.point(t);
    const vec3 got = barycentric(p, t);
    const RTri rt = rtri(t);
    const R3 rp = r3(p);
    const bool deg = tri_sin2(rt) <= kDegenerateSin2;
    degenerate += deg;
    const R3 ref = ref_barycentric(rp, rt, deg);
    const R3 ab = rt.b - rt.a, ac = rt.c - rt.a, bc = rt.c - rt.b;
    const double size = tri_size(rt), R = norm(rp - rt.a), big = 1 + maxabs(ref);
    const double tight = 64 * kEps * big;
    double band = tight + 16 * barycentric_conditioning(g, rp, rt, deg, ref);
    if (deg) {
      const double lmax = std::max({norm(ab), norm(ac), norm(bc)});
      if (lmax > 0) band += 64 * kEps * (R + size) / lmax;
    } else {
      band += 64 * kEps * (R + size) * (R + size) / norm(cross(ab, ac));
    }
    if (near_degenerate_threshold(rt)) band = kInf;
    if (e.add(maxabs(r3(got) - ref), tight, band)) {
      print_case("barycentric outside the band", t, p);
      std::printf("      got (%.9g %.9g %.9g) reference (%.9g %.9g %.9g) kappa %.3g band %.3g\n", got.x, got.y, got.z,
                  ref.x, ref.y, ref.z, tri_kappa(rt), band);
    }
    sum.add(std::abs((double(got.x) + got.y + got.z) - 1), 4 * kEps * big, 4 * kEps * big);
  }
  e.print(), sum.print();
  std::printf("  (%zu of the triangles are degenerate by the rule)\n", degenerate);
  EXPECT_EQ(e.outside, 0u);
  EXPECT_EQ(sum.outside, 0u);
  EXPECT_GT(degenerate, 10000u);
}

TEST(TriangleBarycentric, DocumentedAnswers) {
  const Triangle t{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  EXPECT_EQ(barycentric(vec3{0, 0, 0}, t), (vec3{1, 0, 0}));
  EXPECT_EQ(barycentric(vec3{4, 0, 0}, t), (vec3{0, 1, 0}));
  EXPECT_EQ(barycentric(vec3{0, 4, 0}, t), (vec3{0, 0, 1}));
  EXPECT_EQ(barycentric(vec3{1, 1, 7}, t), (vec3{0.5f, 0.25f, 0.25f}));  // projection on the plane
  EXPECT_EQ(barycentric(vec3{-4, 0, 0}, t), (vec3{2, -1, 0}));           // outside: a weight < 0
  // Collinear corners: the projection on the longest edge (here a-c), 0 for b.
  const Triangle line{{0, 0, 0}, {1, 0, 0}, {4, 0, 0}};
  EXPECT_EQ(barycentric(vec3{3, 5, 0}, line), (vec3{0.25f, 0, 0.75f}));
  // Coincident corners: (1, 0, 0).
  const Triangle point{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  EXPECT_EQ(barycentric(vec3{5, 5, 5}, point), (vec3{1, 0, 0}));
}

TEST(TriangleClosestPoint, DegenerateTrianglesDocumentedAnswers) {
  const Triangle line{{0, 0, 0}, {1, 0, 0}, {4, 0, 0}};  // collapses to [0, 4] on x
  EXPECT_EQ(closest_point(line, vec3{3, 5, 0}), (vec3{3, 0, 0}));
  EXPECT_EQ(closest_point(line, vec3{-2, 1, 1}), (vec3{0, 0, 0}));
  EXPECT_EQ(closest_point(line, vec3{9, 0, 1}), (vec3{4, 0, 0}));
  EXPECT_TRUE(contains(line, vec3{2.5f, 0, 0}));
  EXPECT_FALSE(contains(line, vec3{2.5f, 1e-3f, 0}));
  const Triangle point{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  EXPECT_EQ(closest_point(point, vec3{5, 5, 5}), (vec3{1, 2, 3}));
  EXPECT_TRUE(contains(point, vec3{1, 2, 3}));
  EXPECT_FALSE(contains(point, vec3{1, 2, 3.001f}));
  // A proper triangle: each Voronoi region.
  const Triangle t{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  EXPECT_EQ(closest_point(t, vec3{1, 1, 3}), (vec3{1, 1, 0}));     // face
  EXPECT_EQ(closest_point(t, vec3{-1, -1, 2}), (vec3{0, 0, 0}));   // vertex a
  EXPECT_EQ(closest_point(t, vec3{5, -1, 0}), (vec3{4, 0, 0}));    // vertex b
  EXPECT_EQ(closest_point(t, vec3{-1, 5, 0}), (vec3{0, 4, 0}));    // vertex c
  EXPECT_EQ(closest_point(t, vec3{2, -3, 1}), (vec3{2, 0, 0}));    // edge ab
  EXPECT_EQ(closest_point(t, vec3{-3, 2, 1}), (vec3{0, 2, 0}));    // edge ac
  EXPECT_EQ(closest_point(t, vec3{3, 3, -1}), (vec3{2, 2, 0}));    // edge bc
}

// ------------------------------------------------------------------ overlaps
// The tolerance every overlap band is built on: 1e-5 of the pair's size, plus a few ulp of
// the largest coordinate (inputs far from the origin carry that much themselves).
double touch_tol(double size, double mag, double ulps = 8) { return 1e-5 * size + ulps * kEps * mag; }

// Sphere-triangle. Reference: binary64 distance D from the centre to the triangle <= r.
// Band: |D - r| <= touch_tol plus the closest point's conditioning term.
TEST(TriangleOverlapSphere, AgreesWithReference) {
  Gen g(21);
  Verdicts v{"sphere-triangle"};
  std::size_t asymmetric = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const vec3 c = g.point(t);
    const RTri rt = rtri(t);
    const double D = ref_distance(rt, r3(c));
    const double size = tri_size(rt);
    float r;
    switch (g.pick(4)) {
      case 0: r = 0; break;                                   // a point
      case 1: r = float(D * (1 + 1e-6 * g.s())); break;       // touching
      case 2: r = float(D + size * 1e-3 * g.s()); break;      // near touching
      default: r = float(g.scale * 2 * g.u()); break;
    }
    r = std::max(r, 0.0f);
    const Sphere s{c, r};
    const bool got = overlaps(s, t);
    asymmetric += got != overlaps(t, s);
    const double mag = std::max(tri_mag(rt), maxabs(r3(c)));
    const double err = touch_tol(size + r, mag) + 16 * kEps * std::min(tri_kappa(rt), 1e30) * (D + size);
    v.add(got, D <= r, std::abs(D - r) <= err);
  }
  v.print();
  EXPECT_EQ(v.outside, 0u);
  EXPECT_EQ(asymmetric, 0u);
}

// A random box pose: centre near the triangle, half extents with zero-size and flat cases,
// and for OBBs a random rotation (uniform quaternion, BENCHMARKS.md's N1 recipe), the
// identity, or a rotation about one axis only (faces parallel to axis-aligned triangles).
struct BoxCase {
  R3 c, e;
  R3 u[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

BoxCase random_box(Gen& g, const Triangle& t, bool oriented) {
  BoxCase b;
  const RTri rt = rtri(t);
  const double size = std::max(tri_size(rt), g.scale * 1e-3);
  const vec3 c = g.pick(3) == 0 ? f3(g.inside(t)) : g.fat(g.cube() * 1.5);
  b.c = r3(c);
  auto extent = [&]() {
    const int k = g.pick(8);
    return k == 0 ? 0.0 : double(float(size * (k == 1 ? 1e-3 : 0.7) * g.u()));
  };
  b.e = {extent(), extent(), extent()};
  if (oriented) {
    const int kind = g.pick(4);
    if (kind == 0) return b;
    double x, y, z, w;
    if (kind == 1) {
      const double a = 3.141592653589793 * g.u();
      x = 0, y = 0, z = std::sin(a), w = std::cos(a);
      if (g.pick(2)) std::swap(x, z);
    } else {
      const double u0 = g.u(), u1 = g.u(), u2 = g.u();
      const double s1 = std::sqrt(1 - u0), s2 = std::sqrt(u0), a = 6.283185307179586 * u1, c2 = 6.283185307179586 * u2;
      x = s1 * std::sin(a), y = s1 * std::cos(a), z = s2 * std::sin(c2), w = s2 * std::cos(c2);
    }
    const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int k = 0; k < 3; ++k) b.u[k] = r3(f3({R[k][0], R[k][1], R[k][2]}));
  }
  // Now and then move the box so that a face just touches the triangle's nearest corner
  // along one of its axes (parallel faces and touching).
  if (g.pick(4) == 0) {
    const int k = g.pick(3);
    const R3 corner = rt.corner(g.pick(3));
    const double along = dot(corner - b.c, b.u[k]);
    const double e = coord(b.e, k);
    const double shift = along - (along >= 0 ? e : -e) * (1 + 1e-7 * g.s());
    b.c = r3(f3(b.c + b.u[k] * shift));
  }
  return b;
}

std::array<R3, 3> in_box_frame(const RTri& t, const BoxCase& b) {
  std::array<R3, 3> out;
  for (int k = 0; k < 3; ++k) {
    const R3 d = t.corner(k) - b.c;
    out[k] = {dot(d, b.u[0]), dot(d, b.u[1]), dot(d, b.u[2])};
  }
  return out;
}

// AABB- and OBB-triangle. Reference: the triangle clipped to the box in binary64
// (Sutherland-Hodgman), not a separating axis test. Band: neither robustly separated (the
// box grown by tol still misses) nor robustly overlapping (the box shrunk by tol still
// meets the triangle moved by tol along any box axis): a touching pair, tol = touch_tol.
void box_reference_test(bool oriented, uint64_t seed) {
  Gen g(seed);
  Verdicts v{oriented ? "OBB-triangle" : "AABB-triangle"};
  std::size_t asymmetric = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const BoxCase b = random_box(g, t, oriented);
    const RTri rt = rtri(t);
    bool got;
    if (oriented) {
      OBB box{f3(b.c), f3(b.e), mat3{}};
      for (int k = 0; k < 3; ++k) box.orientation.m[k][0] = float(b.u[k].x), box.orientation.m[k][1] = float(b.u[k].y),
                                  box.orientation.m[k][2] = float(b.u[k].z);
      got = overlaps(box, t);
      asymmetric += got != overlaps(t, box);
    } else {
      const AABB box{f3(b.c), f3(b.e)};
      got = overlaps(box, t);
      asymmetric += got != overlaps(t, box);
    }
    const auto local = in_box_frame(rt, b);
    const double size = std::max(tri_size(rt), 2 * maxabs(b.e));
    const double tol = touch_tol(size, std::max(tri_mag(rt), maxabs(b.c)));
    const R3 grown = b.e + R3{tol, tol, tol};
    const R3 shrunk = {std::max(b.e.x - tol, 0.0), std::max(b.e.y - tol, 0.0), std::max(b.e.z - tol, 0.0)};
    const bool ref = ref_clip_overlap(local, b.e);
    bool band = false;
    if (got != ref) {  // only a disagreement needs its band
      // Robustly overlapping: the box shrunk by tol overlaps the triangle moved by tol along
      // any box axis (a flat or zero box cannot shrink, but the triangle can move off it).
      bool robust_overlap = ref_clip_overlap(local, shrunk);
      for (int k = 0; k < 3 && robust_overlap; ++k)
        for (double sgn : {-tol, tol}) {
          std::array<R3, 3> moved = local;
          for (R3& m : moved) (k == 0 ? m.x : (k == 1 ? m.y : m.z)) += sgn;
          robust_overlap = robust_overlap && ref_clip_overlap(moved, shrunk);
        }
      const bool robust_separation = !ref_clip_overlap(local, grown);
      band = !robust_overlap && !robust_separation;
    }
    if (v.add(got, ref, band)) {
      print_case(oriented ? "OBB outside the band" : "AABB outside the band", t, vec3{});
      std::printf("      box c (%.9g %.9g %.9g) e (%.9g %.9g %.9g) u0 (%.9g %.9g %.9g) u1 (%.9g %.9g %.9g) u2 (%.9g %.9g %.9g): got %d\n",
                  b.c.x, b.c.y, b.c.z, b.e.x, b.e.y, b.e.z, b.u[0].x, b.u[0].y, b.u[0].z, b.u[1].x, b.u[1].y, b.u[1].z,
                  b.u[2].x, b.u[2].y, b.u[2].z, int(got));
    }
  }
  v.print();
  EXPECT_EQ(v.outside, 0u);
  EXPECT_EQ(asymmetric, 0u);
  EXPECT_GT(v.positives, kCases / 10u);
  EXPECT_LT(v.positives, kCases * 9u / 10u);
}

TEST(TriangleOverlapAabb, AgreesWithReference) { box_reference_test(false, 22); }
TEST(TriangleOverlapObb, AgreesWithReference) { box_reference_test(true, 23); }

// Plane-triangle. Reference: the corners' binary64 signed distances change sign (or one is
// 0). Band: the least or greatest distance within touch_tol (16 ulp of the magnitude: the
// plane equation itself cancels far from the origin).
TEST(TriangleOverlapPlane, AgreesWithReference) {
  Gen g(24);
  Verdicts v{"plane-triangle"};
  std::size_t asymmetric = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const RTri rt = rtri(t);
    vec3 n;
    switch (g.pick(3)) {
      case 0: {  // an axis: exact, planes parallel to axis-plane triangles
        const int k = g.pick(3);
        n = vec3{k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f};
        break;
      }
      case 1: {  // the triangle's own normal: parallel to it
        const R3 m = cross(rt.b - rt.a, rt.c - rt.a);
        n = norm(m) > 0 ? f3(m * (1 / norm(m))) : f3(g.unit());
        break;
      }
      default: n = f3(g.unit());
    }
    const R3 rn = r3(n);
    float d;
    switch (g.pick(3)) {
      case 0: d = float(dot(rn, rt.corner(g.pick(3)))); break;  // through a corner
      case 1: d = float(dot(rn, r3(f3(g.inside(t))))); break;
      default: d = float(dot(rn, g.at(g.cube() * 1.5)));
    }
    const Plane p{n, d};
    const bool got = overlaps(p, t);
    asymmetric += got != overlaps(t, p);
    const double da = dot(rn, rt.a) - d, db = dot(rn, rt.b) - d, dc = dot(rn, rt.c) - d;
    const double lo = std::min({da, db, dc}), hi = std::max({da, db, dc});
    const double tol = touch_tol(tri_size(rt), std::max(tri_mag(rt), std::abs(double(d))), 16);
    v.add(got, lo <= 0 && hi >= 0, std::abs(lo) <= tol || std::abs(hi) <= tol);
  }
  v.print();
  EXPECT_EQ(v.outside, 0u);
  EXPECT_EQ(asymmetric, 0u);
}

// A second triangle related to the first: unrelated, sharing a corner or an edge, coplanar
// (same axis plane), crossing, or nearly touching; degenerate kinds included.
Triangle partner(Gen& g, const Triangle& t) {
  const RTri rt = rtri(t);
  Triangle o = g.triangle();
  switch (g.pick(7)) {
    case 0: o.a = t.b; break;                 // shared corner
    case 1: o.a = t.c, o.b = t.b; break;      // shared edge, reversed
    case 2: {  // exactly coplanar when t lies in an axis plane, else in t's plane to rounding
      for (int k = 0; k < 3; ++k) {
        const double v = coord(rt.a, k);
        if (coord(rt.b, k) != v || coord(rt.c, k) != v) continue;
        for (vec3* p : {&o.a, &o.b, &o.c}) (k == 0 ? p->x : (k == 1 ? p->y : p->z)) = float(v);
        return o;
      }
      auto on_plane = [&]() {
        const double sc = g.s(), sb = g.s();
        return f3(rt.a + (rt.b - rt.a) * (3 * sb) + (rt.c - rt.a) * (3 * sc));
      };
      o = {on_plane(), on_plane(), on_plane()};
      break;
    }
    case 3: {  // corners around a point of t: crossing it, more or less
      const R3 c = g.inside(t);
      const double size = std::max(tri_size(rt), g.scale * 1e-3);
      o = {f3(c + g.cube() * size), f3(c + g.cube() * size), f3(c + g.cube() * size)};
      break;
    }
    case 4: {  // a copy of t moved along its normal by a little (parallel planes)
      R3 n = cross(rt.b - rt.a, rt.c - rt.a);
      n = norm(n) > 0 ? n * (1 / norm(n)) : g.unit();
      const double ex = g.u(), side = g.s();
      const R3 off = n * (tri_size(rt) * std::pow(10.0, -1.0 - 6.0 * ex) * side);
      o = {f3(rt.a + off), f3(rt.b + off), f3(rt.c + off)};
      break;
    }
    default: break;
  }
  return o;
}

// Triangle-triangle. Reference: binary64 distance between the triangles (piercing edges,
// edge-edge and vertex-face distances), not a separating axis test. Band: distance in
// (0, tol] for a separated pair, or an overlapping pair that no longer overlaps once both
// are shrunk by tol and one is moved by tol along a normal or an axis (touching, crossing
// by less than tol, or coplanar to within tol).
TEST(TriangleOverlapTriangle, AgreesWithReferenceAndIsSymmetric) {
  Gen g(25);
  Verdicts v{"triangle-triangle"}, coplanar{"  of which exactly coplanar"};
  std::size_t asymmetric = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle a = g.pick(6) == 0 ? g.triangle(3) : g.triangle();  // more axis-plane ones: coplanar pairs
    const Triangle b = partner(g, a);
    const bool got = overlaps(a, b);
    asymmetric += got != overlaps(b, a);
    const RTri ra = rtri(a), rb = rtri(b);
    const double size = std::max(tri_size(ra), tri_size(rb));
    const double tol = touch_tol(size, std::max(tri_mag(ra), tri_mag(rb)));
    const double D = ref_triangle_distance(ra, rb);
    const bool ref = D <= 1e-12 * size;
    int coplanar_axis = -1;  // both in the same axis plane
    for (int k = 0; k < 3; ++k) {
      const double c = coord(ra.a, k);
      bool all = true;
      for (int j = 0; j < 3; ++j) all = all && coord(ra.corner(j), k) == c && coord(rb.corner(j), k) == c;
      if (all) coplanar_axis = k;
    }
    bool band = false;
    if (got != ref) {  // only a disagreement needs its band
      if (ref) {
        // Robustly overlapping: both shrunk by tol still meet with b moved by tol along
        // either normal or any axis (nearly coplanar pairs are touching-like).
        // Exactly coplanar pairs (an axis plane) are exact inputs: only in-plane moves.
        const RTri sa = shrink(ra, tol), sb = shrink(rb, tol);
        std::vector<R3> moves = {{0, 0, 0}};
        for (int k = 0; k < 3; ++k) {
          if (k == coplanar_axis) continue;
          R3 m{};
          (k == 0 ? m.x : (k == 1 ? m.y : m.z)) = tol;
          moves.push_back(m), moves.push_back(m * -1.0);
        }
        for (const RTri* t : {&ra, &rb}) {
          const R3 n = cross(t->b - t->a, t->c - t->a);
          if (norm(n) > 0 && coplanar_axis < 0) moves.push_back(n * (tol / norm(n))), moves.push_back(n * (-tol / norm(n)));
        }
        bool robust = true;
        for (const R3& m : moves)
          robust = robust && ref_triangle_distance(sa, RTri{sb.a + m, sb.b + m, sb.c + m}) <= 1e-12 * size;
        band = !robust;
      } else {
        band = D <= tol;
      }
    }
    if (coplanar_axis >= 0) coplanar.add(got, ref, band);
    if (v.add(got, ref, band)) {
      print_case("triangle-triangle outside the band: a", a, vec3{});
      print_case("b", b, vec3{});
      std::printf("      got %d, reference distance %.3g (tol %.3g)\n", int(got), D, tol);
    }
  }
  v.print(), coplanar.print();
  EXPECT_EQ(coplanar.outside, 0u);
  EXPECT_GT(coplanar.cases, 5000u);
  EXPECT_EQ(v.outside, 0u);
  EXPECT_EQ(asymmetric, 0u);
  EXPECT_GT(v.positives, kCases / 10u);
}

// Pairs that touch exactly in float (dyadic coordinates, so nothing rounds) must overlap;
// pairs a hair apart must not.
TEST(TriangleOverlap, ExactTouchingCountsAsOverlapping) {
  const Triangle t{{0, 0, 1}, {2, 0, 1}, {0, 2, 1}};
  // Face on a box face, an edge on a box face, a corner on a box face, an edge along a box edge.
  EXPECT_TRUE(overlaps(AABB{{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}}, t));
  EXPECT_TRUE(overlaps(AABB{{1, -0.5f, 1}, {0.25f, 0.5f, 0.25f}}, t));
  EXPECT_TRUE(overlaps(AABB{{-1, -1, 1}, {1, 1, 0.25f}}, t));
  EXPECT_TRUE(overlaps(AABB{{3, 0, 1}, {1, 0.5f, 0.5f}}, t));
  EXPECT_FALSE(overlaps(AABB{{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.4999f}}, t));
  EXPECT_TRUE(overlaps(OBB{{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, mat3{}}, t));
  // Zero-size boxes and spheres on the triangle.
  EXPECT_TRUE(overlaps(AABB{{0.5f, 0.5f, 1}, {0, 0, 0}}, t));
  EXPECT_TRUE(overlaps(Sphere{{0.5f, 0.5f, 1}, 0}, t));
  EXPECT_TRUE(overlaps(Sphere{{0.5f, 0.5f, 4}, 3}, t));
  EXPECT_FALSE(overlaps(Sphere{{0.5f, 0.5f, 4}, 2.999f}, t));
  EXPECT_TRUE(overlaps(Sphere{{-3, -4, 1}, 5}, t));  // touches corner a (3-4-5)
  // Plane through a corner, and the triangle's own plane.
  EXPECT_TRUE(overlaps(Plane{{1, 0, 0}, 2}, t));
  EXPECT_FALSE(overlaps(Plane{{1, 0, 0}, 2.001f}, t));
  EXPECT_TRUE(overlaps(Plane{{0, 0, 1}, 1}, t));
  // Triangles: shared corner, shared edge, corner on the face, coplanar edge contact,
  // coplanar apart (where the 11 classic axes all collapse onto the normal).
  EXPECT_TRUE(overlaps(t, Triangle{{2, 0, 1}, {3, 5, 2}, {4, -1, 7}}));
  EXPECT_TRUE(overlaps(t, Triangle{{2, 0, 1}, {0, 2, 1}, {2, 2, 5}}));
  EXPECT_TRUE(overlaps(t, Triangle{{0.5f, 0.5f, 1}, {1, 1, 3}, {0, 1, 4}}));
  EXPECT_TRUE(overlaps(t, Triangle{{1, 1, 1}, {3, 1, 1}, {1, 3, 1}}));
  EXPECT_FALSE(overlaps(t, Triangle{{1.001f, 1.001f, 1}, {3, 1.5f, 1}, {1.5f, 3, 1}}));
  EXPECT_FALSE(overlaps(t, Triangle{{2.5f, 0.25f, 1}, {4, 0.5f, 1}, {2.75f, 1, 1}}));
  // Degenerate partners: a segment through the face, a segment beside it in its plane, a
  // point on it, a point off it, collinear segments apart and overlapping.
  EXPECT_TRUE(overlaps(t, Triangle{{0.5f, 0.5f, 0}, {0.5f, 0.5f, 2}, {0.5f, 0.5f, 4}}));
  EXPECT_FALSE(overlaps(t, Triangle{{2, 2, 1}, {3, 3, 1}, {4, 4, 1}}));
  EXPECT_TRUE(overlaps(t, Triangle{{0.5f, 0.5f, 1}, {0.5f, 0.5f, 1}, {0.5f, 0.5f, 1}}));
  EXPECT_FALSE(overlaps(t, Triangle{{0.5f, 0.5f, 1.5f}, {0.5f, 0.5f, 1.5f}, {0.5f, 0.5f, 1.5f}}));
  const Triangle seg{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_FALSE(overlaps(seg, Triangle{{3, 0, 0}, {4, 0, 0}, {5, 0, 0}}));
  EXPECT_TRUE(overlaps(seg, Triangle{{2, 0, 0}, {4, 0, 0}, {5, 0, 0}}));
  EXPECT_FALSE(overlaps(seg, Triangle{{3, 0, 0}, {3, 0, 0}, {3, 0, 0}}));
  EXPECT_TRUE(overlaps(seg, Triangle{{1.5f, 0, 0}, {1.5f, 0, 0}, {1.5f, 0, 0}}));
  EXPECT_FALSE(overlaps(seg, Triangle{{0, 1, 0}, {1, 1, 0}, {2, 1, 0}}));          // parallel
  EXPECT_FALSE(overlaps(seg, Triangle{{1, 1, 0}, {1, 2, 0}, {1, 3, 0}}));          // a T, apart
  EXPECT_TRUE(overlaps(seg, Triangle{{1, 0, 0}, {1, 2, 0}, {1, 3, 0}}));           // a T, touching
  EXPECT_FALSE(overlaps(seg, Triangle{{1, 1, 1}, {1, 1, 2}, {1, 1, 3}}));          // skew
}

// Containment implies overlap: a triangle with a corner inside a box, an OBB or a sphere
// (with a margin of a few ulp, since the shapes' own coordinates are rounded); a plane
// through a corner along an axis; a triangle sharing a corner, or lying inside another in
// the same axis plane (exactly coplanar).
TEST(TriangleOverlap, ContainmentImpliesOverlap) {
  Gen g(26);
  std::size_t failures = 0, n = 0;
  for (int i = 0; i < 20000; ++i) {
    g.new_frame();
    Triangle t = g.triangle();
    const RTri rt = rtri(t);
    const double size = std::max(tri_size(rt), g.scale * 1e-3);
    const vec3 corner = g.pick(3) == 0 ? t.a : (g.pick(2) ? t.b : t.c);
    // A box around the corner: its centre rounded first, then half extents that reach the
    // corner (rounded up) plus a margin.
    const vec3 inner = f3(r3(corner) + R3{g.s(), g.s(), g.s()} * (0.5 * size));
    auto reach = [&](float c, float x) {
      return std::nextafter(float(std::abs(double(c) - x) + size * (0.01 + g.u())), 1e30f);
    };
    const vec3 e{reach(inner.x, corner.x), reach(inner.y, corner.y), reach(inner.z, corner.z)};
    const AABB box{inner, e};
    BoxCase bc = random_box(g, t, true);
    OBB obb{corner, e, mat3{}};
    for (int k = 0; k < 3; ++k)
      obb.orientation.m[k][0] = float(bc.u[k].x), obb.orientation.m[k][1] = float(bc.u[k].y),
      obb.orientation.m[k][2] = float(bc.u[k].z);
    // A sphere reaching the corner with a margin of 64 ulp of the coordinates.
    const double mag = std::max(tri_mag(rt), maxabs(r3(inner)));
    const Sphere s{inner, float(norm(r3(inner) - r3(corner)) * 1.001 + 64 * kEps * mag)};
    const int k = g.pick(3);
    const Plane p{{k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f},
                  k == 0 ? corner.x : (k == 1 ? corner.y : corner.z)};
    const Triangle shares{corner, g.fat(g.cube()), g.fat(g.cube())};
    const Triangle outer = g.triangle(3);  // in an axis plane; a sub-triangle of it:
    const Triangle sub{f3(g.inside(outer)), f3(g.inside(outer)), f3(g.inside(outer))};
    // (Rounding to float may push the sub-triangle's corners out of a tiny outer one: only
    // pairs with a corner still inside, by the reference, are contained.)
    const RTri router = rtri(outer), rsub = rtri(sub);
    const double outer_size = tri_size(router);
    const bool sub_inside = ref_distance(router, rsub.a) <= 1e-12 * outer_size ||
                            ref_distance(router, rsub.b) <= 1e-12 * outer_size ||
                            ref_distance(router, rsub.c) <= 1e-12 * outer_size;
    const bool ok[] = {overlaps(box, t), overlaps(obb, t), overlaps(s, t), overlaps(p, t), overlaps(t, shares),
                       overlaps(shares, t), overlaps(outer, sub) || !sub_inside,
                       overlaps(sub, outer) || !sub_inside, overlaps(t, t)};
    for (int k2 = 0; k2 < 9; ++k2) {
      ++n;
      if (!ok[k2]) {
        ++failures;
        if (failures < 10) {
          std::printf("    containment pair %d reported apart\n", k2);
          print_case("t", t, corner);
          print_case("outer", outer, vec3{});
          print_case("sub", sub, vec3{});
          std::printf("      box c (%.9g %.9g %.9g) e (%.9g %.9g %.9g) sphere r %.9g\n", box.center.x, box.center.y,
                      box.center.z, box.half_extents.x, box.half_extents.y, box.half_extents.z, s.radius);
        }
      }
    }
  }
  std::printf("  %zu containment pairs: %zu reported apart\n", n, failures);
  EXPECT_EQ(failures, 0u);
}

// ------------------------------------------------------------------ raycast, linetest
// Raycast. Reference: Cramer's rule in binary64 (hit when the weights are >= 0 and t >= 0).
// Band for hit/miss: the ray passes within tol of the triangle's boundary (near an edge,
// or grazing it), or starts within tol of the triangle; tol = touch_tol with 16 ulp of
// the magnitude of the corners, the origin and the distance travelled. t is compared for
// rays that hit in both, as the distance error |dt| |d|: tight = 32 eps (mag + |t d|),
// band = tight / cos(angle to the normal) (grazing rays) + the sheared algorithm's own
// conditioning: each corner's offset P from the ray's line carries eps |corner - o|, so
// the weights carry eps (PaPb + PbPc + PcPa) / (|n| cos) and t that times the corners'
// spread S along the ray (large only for a huge triangle seen from near it). Normal:
// against the binary64 unit normal, tight 16 eps. Barycentrics: reported. Hits on
// degenerate triangles: t between the corners' depths, as documented.
TEST(TriangleRaycast, AgreesWithReference) {
  Gen g(31);
  Verdicts v{"raycast hit"};
  Errors et{"raycast |dt| |d|, cos>=1e-3"}, eg{"raycast |dt| |d|, grazing"}, eb{"raycast barycentric"};
  Errors en{"raycast normal"};
  Verdicts lv{"linetest"};
  std::size_t bad_normals = 0, bad_points = 0, degenerate_hits = 0, bad_degenerate_hits = 0;
  for (int i = 0; i < kCases; ++i) {
    g.new_frame();
    const Triangle t = g.triangle();
    const RTri rt = rtri(t);
    const vec3 target = g.point(t);
    vec3 o;
    switch (g.pick(4)) {
      case 0: o = g.fat(g.cube() * 3.0); break;
      case 1: o = g.fat(g.cube() * 100.0); break;
      case 2: o = f3(g.inside(t)); break;  // starting on the triangle
      default: {  // in the triangle's plane: rays parallel to it
        const R3 n = cross(rt.b - rt.a, rt.c - rt.a);
        const R3 in_plane = norm(n) > 0 ? cross(n, g.unit()) : g.unit();
        o = f3(r3(target) + in_plane * (tri_size(rt) * 3 / std::max(norm(in_plane), 1e-300)));
      }
    }
    R3 d = r3(target) - r3(o);
    if (g.pick(10) == 0) d = g.unit();                  // random direction
    if (g.pick(20) == 0) d = d * std::pow(10.0, 6 * g.s());  // unnormalised lengths
    const Ray ray{o, f3(d)};
    vec3 bary;
    const RaycastResult got = raycast(t, ray, &bary);
    const R3 ro = r3(o), rd = r3(ray.direction);
    const RefRay ref = ref_ray(ro, rd, rt);
    const double size = tri_size(rt);
    const double travel = std::max({norm(rt.a - ro), norm(rt.b - ro), norm(rt.c - ro)});
    const double mag = std::max(tri_mag(rt), maxabs(ro));
    const double tol = touch_tol(size, mag + travel, 16);
    const bool band = ray_boundary_distance(ro, rd, rt) <= tol || ref_distance(rt, ro) <= tol;
    v.add(got.hit, ref.hit, band);
    if (got.hit && tri_sin2(rt) > 2 * kDegenerateSin2) {
      // The normal against the binary64 unit normal, oriented to face the origin: a few eps
      // when the edge vectors are exact; rounded edge vectors (corners not within a factor
      // 2 of each other) tilt it by up to eps mag / width, width = |n| / longest edge.
      R3 n = cross(rt.b - rt.a, rt.c - rt.a);
      n = n * ((dot(n, rd) > 0 ? -1 : 1) / norm(n));
      const double width = norm(cross(rt.b - rt.a, rt.c - rt.a)) /
                           std::max({norm(rt.b - rt.a), norm(rt.c - rt.a), norm(rt.c - rt.b)});
      const double cosang = std::abs(dot(n, rd)) / norm(rd);
      const double tight = 16 * kEps, tilt = 16 * kEps * tri_mag(rt) / width;
      // (Which way it faces is decided in float: a ray within the normal's own error of
      // grazing may see the other side.)
      const double err = cosang <= 1e-5 + tilt ? std::min(norm(r3(got.normal) - n), norm(r3(got.normal) + n))
                                               : norm(r3(got.normal) - n);
      if (en.add(err, tight, tight + tilt)) {
        print_case("normal outside the band", t, o);
        std::printf("      d (%.9g %.9g %.9g) normal (%.9g %.9g %.9g) reference (%.9g %.9g %.9g) cos %.3g tilt %.3g\n",
                    ray.direction.x, ray.direction.y, ray.direction.z, got.normal.x, got.normal.y, got.normal.z, n.x,
                    n.y, n.z, cosang, tilt);
      }
    }
    if (got.hit) {  // the normal is unit and faces the origin; the point is o + t d
      const R3 gn = r3(got.normal);
      // (Facing is decided in float: a ray in the plane to rounding may see either side.)
      if (!(std::abs(norm(gn) - 1) < 1e-6 && dot(gn, rd) <= 1e-5 * norm(rd)) && ++bad_normals < 4) {
        print_case("bad normal", t, o);
        std::printf("      d (%.9g %.9g %.9g) normal (%.9g %.9g %.9g) t %.9g\n", ray.direction.x, ray.direction.y,
                    ray.direction.z, got.normal.x, got.normal.y, got.normal.z, got.t);
      }
      if (norm(r3(got.point) - (ro + rd * double(got.t))) > 4 * kEps * (maxabs(ro) + got.t * norm(rd))) ++bad_points;
    }
    if (got.hit && tri_sin2(rt) <= 2 * kDegenerateSin2) {
      // No plane to compare t with: as documented, t lies between the corners' depths along
      // the ray's dominant axis.
      ++degenerate_hits;
      const int kz = std::abs(rd.x) >= std::abs(rd.y) && std::abs(rd.x) >= std::abs(rd.z)
                         ? 0
                         : (std::abs(rd.y) >= std::abs(rd.z) ? 1 : 2);
      double lo = kInf, hi = -kInf;
      for (int k = 0; k < 3; ++k) {
        const double depth = coord(rt.corner(k) - ro, kz) / coord(rd, kz);
        lo = std::min(lo, depth), hi = std::max(hi, depth);
      }
      const double slack = 64 * kEps * (mag + travel) / norm(rd);
      if (!(got.t >= lo - slack && got.t <= hi + slack) && ++bad_degenerate_hits < 4) {
        print_case("degenerate hit outside the depth range", t, o);
        std::printf("      d (%.9g %.9g %.9g) t %.9g range [%.9g, %.9g]\n", ray.direction.x, ray.direction.y,
                    ray.direction.z, got.t, lo, hi);
      }
    } else if (got.hit && ref.hit) {
      const double dl = norm(rd);
      const R3 n = cross(rt.b - rt.a, rt.c - rt.a);
      const double cosang = norm(n) > 0 ? std::abs(dot(n, rd)) / (norm(n) * dl) : 0;
      // The sheared corners' offsets P from the ray's line carry eps |corner - o| each, so
      // the weights carry eps (PaPb + PbPc + PcPa) / (|n| cos) and t that times the corners'
      // spread S along the ray, plus a few roundings of the travel.
      const R3 dn = rd * (1 / dl), hit = ro + rd * ref.t;
      double P[3], S = 0;
      for (int k = 0; k < 3; ++k) {
        P[k] = norm(cross(rt.corner(k) - ro, dn)) + kEps * norm(rt.corner(k) - ro);
        S = std::max(S, std::abs(dot(rt.corner(k) - hit, dn)));
      }
      const double weights = kEps * ((P[0] * P[1] + P[1] * P[2]) + P[2] * P[0]) / (norm(n) * cosang);
      const double tight = 32 * kEps * (mag + ref.t * dl);
      Errors& bucket = cosang >= 1e-3 ? et : eg;
      if (bucket.add(std::abs(got.t - ref.t) * dl, tight, cosang > 0 ? tight / cosang + 32 * weights * S : kInf)) {
        print_case("raycast t outside the band", t, o);
        std::printf("      d (%.9g %.9g %.9g) t %.9g reference %.9g cos %.3g\n", ray.direction.x, ray.direction.y,
                    ray.direction.z, got.t, ref.t, cosang);
      }
      eb.add(maxabs(r3(bary) - R3{ref.u, ref.v, ref.w}), 64 * kEps * (1 + maxabs(R3{ref.u, ref.v, ref.w})), kInf);
    }
    // linetest over the segment o -> o + d.
    const bool lt = linetest(t, Line{o, f3(ro + rd)});
    const RefRay lref = ref_ray(ro, r3(f3(ro + rd)) - ro, rt);
    const bool lref_hit = lref.hit && lref.t <= 1;
    const bool lband = band || ref_distance(rt, r3(f3(ro + rd))) <= tol;
    lv.add(lt, lref_hit, lband);
  }
  v.print(), et.print(), eg.print(), eb.print(), en.print(), lv.print();
  std::printf("  hits with a non-unit or back-facing normal: %zu, with point != o + t d: %zu\n", bad_normals,
              bad_points);
  std::printf("  hits on degenerate triangles (within rounding of the segment): %zu, of which t outside its depth range: %zu\n",
              degenerate_hits, bad_degenerate_hits);
  EXPECT_EQ(v.outside, 0u);
  EXPECT_EQ(et.outside, 0u);
  EXPECT_EQ(eg.outside, 0u);
  EXPECT_EQ(en.outside, 0u);
  EXPECT_EQ(lv.outside, 0u);
  EXPECT_EQ(bad_normals, 0u);
  EXPECT_EQ(bad_points, 0u);
  EXPECT_EQ(bad_degenerate_hits, 0u);
  EXPECT_GT(v.positives, kCases / 6u);
  // Hits whose edge functions cancelled get t in double (ray_triangle_lanes.hpp): off-grazing
  // t is then within a few roundings (measured: 5.6 x the tight bound at most, 14 cases of
  // 13k beyond it; in float alone 867 x and 450 cases).
  EXPECT_LE(et.max_ratio, 8.0);
  EXPECT_LE(et.in_band, et.cases / 500);
}

// Slivers (a third corner 1e-4 to 1e-3 of the length off the line of the other two), near
// and far from the origin, hit at random points from random directions: t against binary64
// on the float inputs, as the distance of the hit point from the triangle's plane, relative
// to the magnitudes involved (|origin| + t + edge). In float alone T / det weighs the
// corners' depths with weights that carry the cancelled bits' error: 3.6e-5 off here (1.6e-3
// on slivers down to 1e-7 thin), against 1.2e-7 on ordinary triangles. With the double path:
// 5.7e-7 near the origin, 8e-8 far (the rest: rays within rounding of an edge, where the
// weights' signs differ and the float answer stays).
TEST(TriangleRaycast, SliversHitNearTheirPlane) {
  std::mt19937_64 g(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst[2] = {0.0, 0.0};
  int hits[2] = {0, 0};
  for (int i = 0; i < 40000; ++i) {
    const int far = i % 2;
    const double spread = far ? 1e3 + 1e4 * u(g) : 0.0;
    const R3 c0{spread * (u(g) - 0.5), spread * (u(g) - 0.5), spread * (u(g) - 0.5)};
    const double size = 0.1 + 10.0 * u(g);
    const auto near_c0 = [&] { return c0 + R3{u(g) - 0.5, u(g) - 0.5, u(g) - 0.5} * size; };
    const R3 a = near_c0(), b = near_c0(), s = a + (b - a) * u(g);
    const R3 c = s + R3{u(g) - 0.5, u(g) - 0.5, u(g) - 0.5} * (1e-3 * size * (0.1 + 0.9 * u(g)));
    const Triangle t{f3(a), f3(b), f3(c)};
    const RTri rt = rtri(t);
    double w0 = u(g), w1 = u(g);
    if (w0 + w1 > 1.0) w0 = 1.0 - w0, w1 = 1.0 - w1;
    const R3 p = rt.a + (rt.b - rt.a) * w0 + (rt.c - rt.a) * w1;
    R3 dir{u(g) - 0.5, u(g) - 0.5, u(g) - 0.5};
    dir = dir * (1.0 / norm(dir));
    const Ray ray{f3(p - dir * (1.0 + 99.0 * u(g))), f3(dir)};
    const RaycastResult got = raycast(t, ray);
    if (!got.hit) continue;
    const R3 o = r3(ray.origin), d = r3(ray.direction), n = cross(rt.b - rt.a, rt.c - rt.a);
    if (!(norm(n) > 0.0)) continue;
    const double t_ref = dot(n, rt.a - o) / dot(n, d);
    const double cosang = std::abs(dot(n, d)) / (norm(n) * norm(d));
    const double err = std::abs(double(got.t) - t_ref) * norm(d) * cosang / (norm(o) + t_ref * norm(d) + norm(rt.b - rt.a));
    worst[far] = std::max(worst[far], err);
    ++hits[far];
  }
  std::printf("  slivers: %d hits near the origin, max error %.3g; %d far, max error %.3g (of the magnitudes)\n",
              hits[0], worst[0], hits[1], worst[1]);
  EXPECT_GT(hits[0], 15000);
  EXPECT_GT(hits[1], 10000);
  EXPECT_LE(worst[0], 1.5e-6);
  EXPECT_LE(worst[1], 1.5e-6);
}

TEST(TriangleRaycast, DocumentedAnswers) {
  const Triangle t{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  vec3 bary{9, 9, 9};
  // From above and from below: double-sided, the normal faces the origin.
  RaycastResult r = raycast(t, Ray{{1, 1, 5}, {0, 0, -1}}, &bary);
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.t, 5.0f);
  EXPECT_EQ(r.point, (vec3{1, 1, 0}));
  EXPECT_EQ(r.normal, (vec3{0, 0, 1}));
  EXPECT_EQ(bary, (vec3{0.5f, 0.25f, 0.25f}));
  r = raycast(t, Ray{{1, 1, -5}, {0, 0, 2}});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.t, 2.5f);  // units of |d|
  EXPECT_EQ(r.normal, (vec3{0, 0, -1}));
  // Through a corner and along an edge: hits (0 counts as inside).
  EXPECT_TRUE(raycast(t, Ray{{0, 0, 1}, {0, 0, -1}}).hit);
  EXPECT_TRUE(raycast(t, Ray{{2, 0, 1}, {0, 0, -1}}).hit);
  EXPECT_TRUE(raycast(t, Ray{{2, 2, 1}, {0, 0, -1}}).hit);
  EXPECT_FALSE(raycast(t, Ray{{2.001f, 2, 1}, {0, 0, -1}}).hit);
  // Behind the origin; zero direction; parallel to the plane (in it and beside it).
  EXPECT_FALSE(raycast(t, Ray{{1, 1, 5}, {0, 0, 1}}).hit);
  EXPECT_FALSE(raycast(t, Ray{{1, 1, 0}, {0, 0, 0}}).hit);
  EXPECT_FALSE(raycast(t, Ray{{-1, 1, 0}, {1, 0, 0}}).hit);
  EXPECT_FALSE(raycast(t, Ray{{-1, 1, 1}, {1, 0, 0}}).hit);
  // A miss leaves everything zero, the barycentric output included.
  r = raycast(t, Ray{{9, 9, 1}, {0, 0, -1}}, &bary);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.t, 0.0f);
  EXPECT_EQ(bary, (vec3{}));
  // Origin on the triangle: t = +0.
  r = raycast(t, Ray{{1, 1, 0}, {0, 0, 1}});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(std::signbit(r.t), false);
  EXPECT_EQ(r.t, 0.0f);
  // Linetest: [0, 1], and a zero-length segment is its point.
  EXPECT_TRUE(linetest(t, Line{{1, 1, 1}, {1, 1, -1}}));
  EXPECT_TRUE(linetest(t, Line{{1, 1, 1}, {1, 1, 0}}));
  EXPECT_FALSE(linetest(t, Line{{1, 1, 1}, {1, 1, 0.001f}}));
  EXPECT_TRUE(linetest(t, Line{{1, 1, 0}, {1, 1, 0}}));
  EXPECT_FALSE(linetest(t, Line{{1, 1, 0.5f}, {1, 1, 0.5f}}));
  // NaN input: no crash, no hit claimed with a NaN t.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  r = raycast(Triangle{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Ray{{0, 0, 1}, {0, 0, -1}});
  EXPECT_FALSE(r.hit && std::isnan(r.t));
  (void)closest_point(Triangle{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}}, vec3{});
  (void)overlaps(Triangle{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Triangle{});
}

// ------------------------------------------------------------------ SIMD levels
// The lane templates give the scalar level's bits at every SIMD level: 2 x 10^4 cases
// (random, the hard kinds above, and special values: NaN, infinities, zeros, huge and
// subnormal coordinates).
TEST(TriangleLanes, EverySimdLevelMatchesScalar) {
  constexpr int kColumns = 9 + 9 + 3 + 4 + 6 + 15 + 4 + 8;
  const std::size_t n = 20011;  // not a multiple of any width: the tails run too
  std::vector<std::vector<float>> in(kColumns, std::vector<float>(n));
  Gen g(41);
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                            1e-40f, 3e38f, -3e38f, 1e30f, 1e-30f};
  for (std::size_t i = 0; i < n; ++i) {
    g.new_frame();
    const Triangle t = g.triangle(), o = partner(g, t);
    const vec3 p = g.point(t);
    const BoxCase b = random_box(g, t, true);
    const vec3 q = g.point(t);
    const float row[kColumns] = {
        t.a.x, t.a.y, t.a.z, t.b.x, t.b.y, t.b.z, t.c.x, t.c.y, t.c.z,               // tri
        o.a.x, o.a.y, o.a.z, o.b.x, o.b.y, o.b.z, o.c.x, o.c.y, o.c.z,               // other
        p.x, p.y, p.z,                                                               // point
        q.x, q.y, q.z, float(g.scale * g.u()),                                       // sphere
        float(b.c.x), float(b.c.y), float(b.c.z), float(b.e.x), float(b.e.y), float(b.e.z),  // aabb
        float(b.c.x), float(b.c.y), float(b.c.z), float(b.e.x), float(b.e.y), float(b.e.z),  // obb
        float(b.u[0].x), float(b.u[0].y), float(b.u[0].z), float(b.u[1].x), float(b.u[1].y), float(b.u[1].z),
        float(b.u[2].x), float(b.u[2].y), float(b.u[2].z),
        float(b.u[1].x), float(b.u[1].y), float(b.u[1].z), float(dot(b.u[1], r3(q))),  // plane
        q.x, q.y, q.z, float(p.x - q.x), float(p.y - q.y), float(p.z - q.z), 0.0f, 1e30f};  // ray
    for (int k = 0; k < kColumns; ++k) in[k][i] = row[k];
    if (i % 7 == 0) in[g.pick(kColumns - 2)][i] = specials[g.pick(12)];  // now and then a special value
  }
  auto run = [&](SimdLevel level) {
    std::vector<std::vector<float>> out(kTriangleProbeOutputs, std::vector<float>(n));
    TriangleProbeArgs a{};
    const auto c = [&](int k) { return in[k].data(); };
    a.tri = {c(0), c(1), c(2), c(3), c(4), c(5), c(6), c(7), c(8)};
    a.other = {c(9), c(10), c(11), c(12), c(13), c(14), c(15), c(16), c(17)};
    a.px = c(18), a.py = c(19), a.pz = c(20);
    a.sphere = {c(21), c(22), c(23), c(24)};
    a.aabb = {c(25), c(26), c(27), c(28), c(29), c(30)};
    a.obb = {c(31), c(32), c(33), c(34), c(35), c(36), c(37), c(38), c(39), c(40), c(41), c(42), c(43), c(44), c(45)};
    a.plane = {c(46), c(47), c(48), c(49)};
    a.ox = c(50), a.oy = c(51), a.oz = c(52), a.dx = c(53), a.dy = c(54), a.dz = c(55), a.tmin = c(56), a.tmax = c(57);
    for (int k = 0; k < kTriangleProbeOutputs; ++k) a.out[k] = out[k].data();
    detail::triangle_probe_for(level)(a, 0, n);
    return out;
  };
  const auto ref = run(SimdLevel::scalar);
  // The scalar probe is the public API's arithmetic: spot-check that.
  for (std::size_t i = 0; i < n; i += 97) {
    const Triangle t{{in[0][i], in[1][i], in[2][i]}, {in[3][i], in[4][i], in[5][i]}, {in[6][i], in[7][i], in[8][i]}};
    const vec3 p{in[18][i], in[19][i], in[20][i]};
    const vec3 q = closest_point(t, p);
    EXPECT_EQ(detail::canonical_float_bits(q.x), detail::canonical_float_bits(ref[kTpClosestX][i]));
    EXPECT_EQ(contains(t, p), ref[kTpContains][i] == 1.0f);
  }
  int levels = 0;
  std::size_t mismatches = 0;
  for (uint32_t lv = 2; lv <= 5; ++lv) {
    const SimdLevel level = SimdLevel(lv);
    if (!simd_level_available(level)) continue;
    ++levels;
    const auto got = run(level);
    for (int k = 0; k < kTriangleProbeOutputs; ++k)
      for (std::size_t i = 0; i < n; ++i)
        if (detail::canonical_float_bits(got[k][i]) != detail::canonical_float_bits(ref[k][i])) {
          if (++mismatches < 10)
            ADD_FAILURE() << "output " << k << " case " << i << " at " << simd_level_name(level) << ": " << got[k][i]
                          << " vs scalar " << ref[k][i];
        }
  }
  std::printf("  %zu cases x %d outputs at %d SIMD levels besides scalar: %zu mismatches\n", n,
              int(kTriangleProbeOutputs), levels, mismatches);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GE(levels, 1) << "no SIMD level available to compare";
}

}  // namespace
}  // namespace gyro
