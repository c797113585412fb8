// The 2D primitives of Cookbook chapters 4-6 (gyro/geometry2d.hpp) against an independent
// binary64 reference written here, on seeded random and hard cases, plus properties.
//
// How float and double are compared. Every boolean test is checked against a reference
// computed in double from the same float inputs, with different algorithms where that
// matters (segments against rectangles by half-plane clipping, rectangle pairs by
// projecting corners onto every edge normal; gyro uses separating axes with centers and
// radii). Near touching, float rounding may legitimately flip the answer, so each case
// is also evaluated with every solid grown and shrunk by a band delta = K * M, where M is
// the largest magnitude among the case's coordinates and sizes (float rounding is
// relative to it: at 1e4 from the origin an ulp is 1e-3). If the grown and shrunk answers
// agree the case is clear and gyro must match it: a disagreement there is "outside the
// band" and must never happen. Otherwise the case is within delta of touching and a
// disagreement is counted and printed as "inside the band". For every disagreement the
// smallest delta that explains it is found by bisection; its maximum over all cases, as
// a multiple of M, is printed as the measured error.
//
// Case mix (per function, >= 10^5 cases): scales 1e-3, 1 and 1e4 (times 0.5 to 1.5),
// positions at the origin, near it, and 1e4 to 2e4 away; zero radius, zero size and zero
// extent in one axis; rotations 0, +-pi/2, pi, pi/4, 3pi/4, random and large; segments
// of zero length and parallel to the axes; and half of all cases moved into touching:
// the second shape slides along a random, axis or diagonal direction to the position
// where the double reference flips (bisection to 1e-16), then is rounded to float.
#include "gyro/geometry2d.hpp"
#include "gyro/math_scalar.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

namespace gyro {
namespace {

using gyro::testing::SplitMix64;

constexpr double kDInf = std::numeric_limits<double>::infinity();
constexpr float kFNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kFInf = std::numeric_limits<float>::infinity();

// ====================================================================== binary64 reference

struct D2 {
  double x = 0, y = 0;
};
D2 operator+(D2 a, D2 b) { return {a.x + b.x, a.y + b.y}; }
D2 operator-(D2 a, D2 b) { return {a.x - b.x, a.y - b.y}; }
D2 operator*(D2 a, double s) { return {a.x * s, a.y * s}; }
double ddot(D2 a, D2 b) { return a.x * b.x + a.y * b.y; }
double dlen(D2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }  // magnitudes here stay far from overflow
double dclamp(double x, double lo, double hi) { return std::max(lo, std::min(hi, x)); }
D2 dv(const vec2& v) { return {v.x, v.y}; }

struct DCircle {
  D2 c;
  double r;
};
struct DRect {
  D2 lo, hi;
};
struct DORect {
  D2 c, e, u, v;
};
struct DSeg {
  D2 a, b;
};
struct DShape {  // a BoundingShape of up to four circles and four rectangles, copied without allocation
  std::array<DCircle, 4> c;
  std::array<DRect, 4> r;
  int nc = 0, nr = 0;
  std::span<const DCircle> circles() const { return {c.data(), std::size_t(nc)}; }
  std::span<const DRect> rects() const { return {r.data(), std::size_t(nr)}; }
  std::span<DCircle> circles() { return {c.data(), std::size_t(nc)}; }
  std::span<DRect> rects() { return {r.data(), std::size_t(nr)}; }
};

DCircle dref(const Circle& s) { return {dv(s.center), s.radius}; }
DRect dref(const Rectangle2D& s) {
  return {dv(s.origin), {double(s.origin.x) + double(s.size.x), double(s.origin.y) + double(s.size.y)}};
}
DORect dref(const OrientedRectangle& s) {
  const double r = s.rotation;
  return {dv(s.center), dv(s.half_extents), {std::cos(r), std::sin(r)}, {-std::sin(r), std::cos(r)}};
}
DSeg dref(const Line2D& l) { return {dv(l.start), dv(l.end)}; }
D2 dref(const vec2& p) { return dv(p); }
DShape dref(const BoundingShape& s) {
  DShape d;
  EXPECT_LE(s.circles.size(), 4u);
  EXPECT_LE(s.rectangles.size(), 4u);
  for (const Circle& c : s.circles) d.c[std::size_t(d.nc++)] = dref(c);
  for (const Rectangle2D& r : s.rectangles) d.r[std::size_t(d.nr++)] = dref(r);
  return d;
}

// Growing by delta moves every boundary outwards by delta (negative: inwards; a shape
// shrunk past zero is empty). Points and segments do not grow: the solid they meet does.
DCircle grow(DCircle s, double d) { return {s.c, s.r + d}; }
DRect grow(DRect s, double d) { return {{s.lo.x - d, s.lo.y - d}, {s.hi.x + d, s.hi.y + d}}; }
DORect grow(DORect s, double d) { return {s.c, {s.e.x + d, s.e.y + d}, s.u, s.v}; }
DSeg grow(DSeg s, double) { return s; }
D2 grow(D2 p, double) { return p; }
DShape grow(DShape s, double d) {
  for (DCircle& c : s.circles()) c = grow(c, d);
  for (DRect& r : s.rects()) r = grow(r, d);
  return s;
}

DCircle moved(DCircle s, D2 t) { return {s.c + t, s.r}; }
DRect moved(DRect s, D2 t) { return {s.lo + t, s.hi + t}; }
DORect moved(DORect s, D2 t) { return {s.c + t, s.e, s.u, s.v}; }
DSeg moved(DSeg s, D2 t) { return {s.a + t, s.b + t}; }
D2 moved(D2 p, D2 t) { return p + t; }

D2 anchor(const DCircle& s) { return s.c; }
D2 anchor(const DRect& s) { return (s.lo + s.hi) * 0.5; }
D2 anchor(const DORect& s) { return s.c; }
D2 anchor(const DSeg& s) { return (s.a + s.b) * 0.5; }
D2 anchor(const D2& p) { return p; }

/// A length of the order of the shape's size.
double extent(const DCircle& s) { return s.r; }
double extent(const DRect& s) { return (s.hi.x - s.lo.x) + (s.hi.y - s.lo.y); }
double extent(const DORect& s) { return s.e.x + s.e.y; }
double extent(const DSeg& s) { return dlen(s.b - s.a); }
double extent(const D2&) { return 0; }

D2 anchor(const DShape& s) {
  if (s.nc > 0) return s.c[0].c;
  if (s.nr > 0) return anchor(s.r[0]);
  return {};
}
double extent(const DShape& s) {
  const D2 a = anchor(s);
  double e = 0;
  for (const DCircle& c : s.circles()) e += extent(c) + dlen(anchor(c) - a);
  for (const DRect& r : s.rects()) e += extent(r) + dlen(anchor(r) - a);
  return e;
}
DShape moved(DShape s, D2 t) {
  for (DCircle& c : s.circles()) c = moved(c, t);
  for (DRect& r : s.rects()) r = moved(r, t);
  return s;
}

bool empty(const DCircle& s) { return s.r < 0; }
bool empty(const DRect& s) { return s.lo.x > s.hi.x || s.lo.y > s.hi.y; }
bool empty(const DORect& s) { return s.e.x < 0 || s.e.y < 0; }

double dist_point_segment(D2 p, const DSeg& s) {
  const D2 ab = s.b - s.a;
  const double dd = ddot(ab, ab);
  const double t = dd > 0 ? dclamp(ddot(p - s.a, ab) / dd, 0, 1) : 0;
  return dlen(p - (s.a + ab * t));
}

bool ref_contains(const DCircle& s, D2 p) { return !empty(s) && dlen(p - s.c) <= s.r; }
bool ref_contains(const DRect& s, D2 p) { return s.lo.x <= p.x && p.x <= s.hi.x && s.lo.y <= p.y && p.y <= s.hi.y; }
bool ref_contains(const DORect& s, D2 p) {
  const D2 d = p - s.c;
  return !empty(s) && std::abs(ddot(d, s.u)) <= s.e.x && std::abs(ddot(d, s.v)) <= s.e.y;
}
bool ref_contains(const DShape& s, D2 p) {
  for (const DCircle& c : s.circles())
    if (ref_contains(c, p)) return true;
  for (const DRect& r : s.rects())
    if (ref_contains(r, p)) return true;
  return false;
}

/// A convex shape as four half-planes dot(n, p) <= k (exact normals, so a zero-size box
/// still has well-defined sides).
struct HalfPlanes {
  std::array<D2, 4> n;
  std::array<double, 4> k;
};
HalfPlanes half_planes(const DRect& s) {
  return {{D2{1, 0}, D2{-1, 0}, D2{0, 1}, D2{0, -1}}, {s.hi.x, -s.lo.x, s.hi.y, -s.lo.y}};
}
HalfPlanes half_planes(const DORect& s) {
  const double cu = ddot(s.c, s.u), cv = ddot(s.c, s.v);
  return {{s.u, s.u * -1.0, s.v, s.v * -1.0}, {cu + s.e.x, -cu + s.e.x, cv + s.e.y, -cv + s.e.y}};
}
/// Cyrus-Beck: clip the segment's parameter range [0, 1] against every half-plane.
bool ref_segment_convex(const HalfPlanes& h, const DSeg& s) {
  const D2 d = s.b - s.a;
  double t0 = 0, t1 = 1;
  for (int i = 0; i < 4; ++i) {
    const double num = h.k[i] - ddot(h.n[i], s.a);  // inside at t iff t * dn <= num
    const double dn = ddot(h.n[i], d);
    if (dn == 0) {
      if (num < 0) return false;
    } else if (dn > 0) {
      t1 = std::min(t1, num / dn);
    } else {
      t0 = std::max(t0, num / dn);
    }
  }
  return t0 <= t1;
}

std::array<D2, 4> corners(const DRect& s) { return {s.lo, D2{s.hi.x, s.lo.y}, s.hi, D2{s.lo.x, s.hi.y}}; }
std::array<D2, 4> corners(const DORect& s) {
  const D2 a = s.u * s.e.x, b = s.v * s.e.y;
  return {s.c - a - b, s.c + a - b, s.c + a + b, s.c - a + b};
}
std::array<D2, 2> axes(const DRect&) { return {D2{1, 0}, D2{0, 1}}; }
std::array<D2, 2> axes(const DORect& s) { return {s.u, s.v}; }

/// Separating axis test on corner projections onto both shapes' edge normals.
template <class A, class B>
bool ref_sat(const A& a, const B& b) {
  if (empty(a) || empty(b)) return false;
  const auto ca = corners(a), cb = corners(b);
  std::array<D2, 4> ax{axes(a)[0], axes(a)[1], axes(b)[0], axes(b)[1]};
  for (const D2& n : ax) {
    double amin = kDInf, amax = -kDInf, bmin = kDInf, bmax = -kDInf;
    for (const D2& p : ca) amin = std::min(amin, ddot(p, n)), amax = std::max(amax, ddot(p, n));
    for (const D2& p : cb) bmin = std::min(bmin, ddot(p, n)), bmax = std::max(bmax, ddot(p, n));
    if (amax < bmin || bmax < amin) return false;
  }
  return true;
}

D2 local_of(const DORect& s, D2 p) { return {ddot(p - s.c, s.u), ddot(p - s.c, s.v)}; }

bool ref_linetest(const DCircle& c, const DSeg& s) { return !empty(c) && dist_point_segment(c.c, s) <= c.r; }
bool ref_linetest(const DRect& r, const DSeg& s) { return ref_segment_convex(half_planes(r), s); }
bool ref_linetest(const DORect& r, const DSeg& s) { return ref_segment_convex(half_planes(r), s); }
bool ref_linetest(const DShape& sh, const DSeg& s) {
  for (const DCircle& c : sh.circles())
    if (ref_linetest(c, s)) return true;
  for (const DRect& r : sh.rects())
    if (ref_linetest(r, s)) return true;
  return false;
}

bool ref_overlaps(const DCircle& a, const DCircle& b) {
  return !empty(a) && !empty(b) && dlen(b.c - a.c) <= a.r + b.r;
}
bool ref_overlaps(const DCircle& a, const DRect& b) {
  if (empty(a) || empty(b)) return false;
  const D2 q{dclamp(a.c.x, b.lo.x, b.hi.x), dclamp(a.c.y, b.lo.y, b.hi.y)};
  return dlen(a.c - q) <= a.r;
}
bool ref_overlaps(const DCircle& a, const DORect& b) {
  if (empty(a) || empty(b)) return false;
  const D2 l = local_of(b, a.c);
  const D2 q{dclamp(l.x, -b.e.x, b.e.x), dclamp(l.y, -b.e.y, b.e.y)};
  return dlen(l - q) <= a.r;
}
bool ref_overlaps(const DRect& a, const DRect& b) {
  return !empty(a) && !empty(b) && a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}
bool ref_overlaps(const DRect& a, const DORect& b) { return ref_sat(a, b); }
bool ref_overlaps(const DORect& a, const DORect& b) { return ref_sat(a, b); }
template <class S>
bool ref_overlaps(const DShape& a, const S& b) {
  for (const DCircle& c : a.circles())
    if (ref_overlaps(c, b)) return true;
  for (const DRect& r : a.rects()) {
    if constexpr (std::is_same_v<S, DCircle>) {
      if (ref_overlaps(b, r)) return true;
    } else {
      if (ref_overlaps(r, b)) return true;
    }
  }
  return false;
}
bool ref_overlaps(const DShape& a, const DShape& b) {
  for (const DCircle& c : b.circles())
    if (ref_overlaps(a, c)) return true;
  for (const DRect& r : b.rects())
    if (ref_overlaps(a, r)) return true;
  return false;
}

// ====================================================================== magnitudes

double mag(const vec2& p) { return std::max(std::abs(double(p.x)), std::abs(double(p.y))); }
double mag(const Circle& s) { return std::max(mag(s.center), double(s.radius)); }
double mag(const Rectangle2D& s) { return std::max({mag(s.origin), mag(s.size), mag(s.origin + s.size)}); }
double mag(const OrientedRectangle& s) { return std::max(mag(s.center), mag(s.half_extents)); }
double mag(const Line2D& l) { return std::max(mag(l.start), mag(l.end)); }
double mag(const BoundingShape& s) {
  double m = 0;
  for (const Circle& c : s.circles) m = std::max(m, mag(c));
  for (const Rectangle2D& r : s.rectangles) m = std::max(m, mag(r));
  return m;
}

// Float shapes moved by a double translation, rounded once.
float f32(double v) { return static_cast<float>(v); }
vec2 fmove(const vec2& p, D2 t) { return {f32(p.x + t.x), f32(p.y + t.y)}; }
Circle fmoved(Circle s, D2 t) { return {fmove(s.center, t), s.radius}; }
Rectangle2D fmoved(Rectangle2D s, D2 t) { return {fmove(s.origin, t), s.size}; }
OrientedRectangle fmoved(OrientedRectangle s, D2 t) { return {fmove(s.center, t), s.half_extents, s.rotation}; }
Line2D fmoved(Line2D s, D2 t) { return {fmove(s.start, t), fmove(s.end, t)}; }
vec2 fmoved(vec2 p, D2 t) { return fmove(p, t); }
BoundingShape fmoved(BoundingShape s, D2 t) {
  for (Circle& c : s.circles) c = fmoved(c, t);
  for (Rectangle2D& r : s.rectangles) r = fmoved(r, t);
  return s;
}

// ====================================================================== generators

/// A neighbourhood where a case lives: scale s, offset o.
struct Place {
  double s;
  D2 o;
};

class Gen {
 public:
  explicit Gen(uint64_t seed) : rng_(seed) {}
  double u() { return rng_.u(); }
  double sym() { return 2 * rng_.u() - 1; }
  int pick(int n) { return int(rng_.next() % uint64_t(n)); }

  Place place() {
    static constexpr double kScales[] = {1e-3, 1.0, 1e4};
    const double s = kScales[pick(3)] * (0.5 + u());
    switch (pick(4)) {
      case 0: return {s, {0, 0}};
      case 1: return {s, {5 * s * sym(), 5 * s * sym()}};
      case 2: return {s, {far(), far()}};
      default: return {s, {(1 + u()) * 1e4, 0.25 * s * sym()}};
    }
  }
  /// 1e4 to 2e4 from the origin, either side (draws in a fixed order, whatever the compiler).
  double far() {
    const double d = (1 + u()) * 1e4;
    return pick(2) ? d : -d;
  }
  vec2 point(const Place& p) { return {f32(p.o.x + 2 * p.s * sym()), f32(p.o.y + 2 * p.s * sym())}; }
  /// A size: zero one time in eight, else up to 2 s.
  float size(const Place& p) { return pick(8) == 0 ? 0.0f : f32(2 * p.s * u()); }
  float angle() {
    switch (pick(10)) {
      case 0: return 0.0f;
      case 1: return kHalfPi;
      case 2: return -kHalfPi;
      case 3: return kPi;
      case 4: return kPi * 0.25f;
      case 5: return kPi * 0.75f;
      case 6: return f32(100 * sym());
      default: return f32(kPi * sym());
    }
  }
  Circle circle(const Place& p) { return {point(p), size(p) * 0.5f}; }
  Rectangle2D rect(const Place& p) { return {point(p), {size(p), size(p)}}; }
  OrientedRectangle orect(const Place& p) { return {point(p), {size(p) * 0.5f, size(p) * 0.5f}, angle()}; }
  Line2D line(const Place& p) {
    Line2D l{point(p), point(p)};
    switch (pick(8)) {
      case 0: l.end = l.start; break;
      case 1: l.end.x = l.start.x; break;
      case 2: l.end.y = l.start.y; break;
      default: break;
    }
    return l;
  }
  BoundingShape shape(const Place& p) {
    BoundingShape s;
    const int nc = pick(4), nr = pick(4);
    for (int i = 0; i < nc; ++i) s.circles.push_back(circle(p));
    for (int i = 0; i < nr; ++i) s.rectangles.push_back(rect(p));
    return s;
  }
  /// A direction to slide along: random, an axis, or a diagonal.
  D2 direction() {
    switch (pick(4)) {
      case 0: {
        static constexpr D2 kAxes[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        return kAxes[pick(4)];
      }
      case 1: {
        const double h = std::sqrt(0.5);
        return {pick(2) ? h : -h, pick(2) ? h : -h};
      }
      default: {
        const double a = 2 * M_PI * u();
        return {std::cos(a), std::sin(a)};
      }
    }
  }

  // Generic entry points used by the harness.
  vec2 make(const Place& p, const vec2*) { return point(p); }
  Circle make(const Place& p, const Circle*) { return circle(p); }
  Rectangle2D make(const Place& p, const Rectangle2D*) { return rect(p); }
  OrientedRectangle make(const Place& p, const OrientedRectangle*) { return orect(p); }
  Line2D make(const Place& p, const Line2D*) { return line(p); }
  BoundingShape make(const Place& p, const BoundingShape*) { return shape(p); }

 private:
  SplitMix64 rng_;
};

/// b slid along a direction to where the double reference `ref(a, b)` flips, rounded.
template <class A, class B, class Ref>
B touching(const A& a, const B& b, Gen& g, Ref ref) {
  const auto da = dref(a);
  const auto db = dref(b);
  const D2 start = anchor(da) - anchor(db);
  if (!ref(da, moved(db, start))) return b;  // an empty shape (never for valid inputs)
  const D2 w = g.direction();
  double lo = 0, hi = 4 * (extent(da) + extent(db)) + 1e-300;
  if (ref(da, moved(db, start + w * hi))) return b;
  for (int i = 0; i < 64 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (ref(da, moved(db, start + w * mid)) ? lo : hi) = mid;
  }
  const double t = g.pick(2) ? lo : hi;
  return fmoved(b, start + w * t);
}

// ====================================================================== the harness

struct BoolStats {
  long cases = 0, positives = 0, ambiguous = 0, in_band = 0, out_band = 0, asymmetric = 0;
  double max_needed = 0;  // the largest delta / M that explains a disagreement
};

void print_stats(const char* name, const BoolStats& s, double k) {
  std::printf("  %-38s %6ld cases (%5ld true), %5ld within %.1e*M of touching: %5ld disagree inside the band, %ld "
              "outside; largest delta explaining one %.2e*M\n",
              name, s.cases, s.positives, s.ambiguous, k, s.in_band, s.out_band, s.max_needed);
}

/// Checks one case of a boolean function f(a, b) against ref(a, b) (double, shapes grown).
template <class A, class B, class F, class Ref>
void check_case(BoolStats& st, const A& a, const B& b, F f, Ref ref, double k) {
  const bool got = f(a, b);
  const auto da = dref(a);
  const auto db = dref(b);
  const double m = std::max(mag(a), mag(b));
  const double band = k * m;
  const bool exact = ref(da, db);
  const bool grown = ref(grow(da, band), grow(db, band));
  const bool shrunk = ref(grow(da, -band), grow(db, -band));
  ++st.cases;
  st.positives += exact;
  st.ambiguous += grown != shrunk;
  if (got == exact) return;
  if (grown == shrunk) {
    if (++st.out_band <= 5) std::printf("    disagreement outside the band (gyro %d, reference %d)\n", got, exact);
  } else {
    ++st.in_band;
  }
  const double sign = got ? 1 : -1;
  double lo = 0, hi = m;
  for (int i = 0; i < 40; ++i) {  // to 2^-40 * M, far below float's resolution
    const double mid = 0.5 * (lo + hi);
    (ref(grow(da, sign * mid), grow(db, sign * mid)) == got ? hi : lo) = mid;
  }
  if (m > 0) st.max_needed = std::max(st.max_needed, hi / m);
}

/// n cases of f(a, b): random pairs, one in `touch_every` slid into touching.
template <class A, class B, class F, class Ref>
BoolStats run_bool(uint64_t seed, long n, F f, Ref ref, double k, int touch_every = 2) {
  Gen g(seed);
  BoolStats st;
  for (long i = 0; i < n; ++i) {
    const Place p = g.place();
    const A a = g.make(p, static_cast<const A*>(nullptr));
    B b = g.make(p, static_cast<const B*>(nullptr));
    if (g.pick(touch_every) == 0) b = touching(a, b, g, ref);
    check_case(st, a, b, f, ref, k);
    if constexpr (requires { overlaps(b, a); }) {
      st.asymmetric += overlaps(a, b) != overlaps(b, a);
    }
  }
  return st;
}

constexpr long kCases = 100000;
// The band, as a multiple of the case's magnitude M: 2^-22, four float roundings at M (the
// largest disagreement measured needs about one).
constexpr double kBand = 0x1p-22;

#define EXPECT_CLEAN(st)             \
  do {                               \
    EXPECT_EQ((st).out_band, 0);     \
    EXPECT_EQ((st).asymmetric, 0);   \
    EXPECT_LT((st).max_needed, kBand); \
  } while (0)

// ====================================================================== reference tests

TEST(Geometry2DReference, PointContainment) {
  std::printf("  point containment, %ld cases each, band delta = %.2g * M:\n", kCases, kBand);
  const auto f = [](const auto& s, const vec2& p) { return contains(s, p); };
  const auto rc = [](const auto& s, const D2& p) { return ref_contains(s, p); };
  const BoolStats c = run_bool<Circle, vec2>(11, kCases, f, rc, kBand);
  const BoolStats r = run_bool<Rectangle2D, vec2>(12, kCases, f, rc, kBand);
  const BoolStats o = run_bool<OrientedRectangle, vec2>(13, kCases, f, rc, kBand);
  print_stats("contains(Circle, point)", c, kBand);
  print_stats("contains(Rectangle2D, point)", r, kBand);
  print_stats("contains(OrientedRectangle, point)", o, kBand);
  for (const BoolStats* s : {&c, &r, &o}) {
    EXPECT_CLEAN(*s);
    EXPECT_GT(s->positives, kCases / 10);
    EXPECT_GT(s->ambiguous, kCases / 100);  // the hard cases are really there
  }
}

// contains(Line2D, p) with its documented tolerance: on the segment when the distance is
// at most kOnLineTolerance * (largest |coordinate|). The reference applies that definition
// in double; the band is a quarter of the tolerance, so a float point computed on the
// segment (a few roundings away) is a clear case that must say true.
TEST(Geometry2DReference, PointOnLine) {
  const double k = kBand;
  Gen g(21);
  BoolStats st;
  long on_segment = 0, on_segment_rejected = 0;
  // The definition in double: the tolerance scales with the float inputs' magnitude.
  const auto tolerance = [](const Line2D& l, const vec2& p) {
    return double(kOnLineTolerance) * std::max(mag(l), mag(p));
  };
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const Line2D l = g.line(pl);
    const DSeg ds = dref(l);
    vec2 p = g.point(pl);
    const int mode = g.pick(4);
    if (mode == 0) {  // on the segment, as float computes a point on it: a clear "true"
      p = lerp(l.start, l.end, f32(g.u()));
      ++on_segment;
      on_segment_rejected += !contains(l, p);
    } else if (mode == 1) {  // on the edge of the tolerance tube, then rounded to float
      const double tol = tolerance(l, p);
      const D2 w = g.direction(), base = ds.a + (ds.b - ds.a) * g.u();
      double lo = 0, hi = 4 * tol + 1e-300;
      for (int it = 0; it < 64; ++it) {
        const double mid = 0.5 * (lo + hi);
        (dist_point_segment(base + w * mid, ds) <= tol ? lo : hi) = mid;
      }
      const D2 q = base + w * (g.pick(2) ? lo : hi);
      p = {f32(q.x), f32(q.y)};
    }
    const double m = std::max(mag(l), mag(p)), tol = tolerance(l, p), band = k * m;
    const double dist = dist_point_segment(dref(p), ds);
    const bool got = contains(l, p), exact = dist <= tol;
    // The segment cannot grow; the tube's radius does instead.
    const bool grown = dist <= tol + band, shrunk = dist <= tol - band;
    ++st.cases;
    st.positives += exact;
    st.ambiguous += grown != shrunk;
    if (got != exact) {
      (grown == shrunk ? st.out_band : st.in_band)++;
      if (m > 0) st.max_needed = std::max(st.max_needed, std::abs(dist - tol) / m);
    }
  }
  print_stats("contains(Line2D, point)", st, k);
  std::printf("    %ld float points computed on the segment: %ld rejected\n", on_segment, on_segment_rejected);
  EXPECT_EQ(st.out_band, 0);
  EXPECT_EQ(on_segment_rejected, 0);
  EXPECT_LT(st.max_needed, k);
  EXPECT_GT(st.ambiguous, kCases / 100);
}

TEST(Geometry2DReference, Linetests) {
  const auto f = [](const auto& s, const Line2D& l) { return linetest(s, l); };
  const auto rl = [](const auto& s, const DSeg& l) { return ref_linetest(s, l); };
  const BoolStats c = run_bool<Circle, Line2D>(31, kCases, f, rl, kBand);
  const BoolStats r = run_bool<Rectangle2D, Line2D>(32, kCases, f, rl, kBand);
  const BoolStats o = run_bool<OrientedRectangle, Line2D>(33, kCases, f, rl, kBand);
  print_stats("linetest(Circle, Line2D)", c, kBand);
  print_stats("linetest(Rectangle2D, Line2D)", r, kBand);
  print_stats("linetest(OrientedRectangle, Line2D)", o, kBand);
  for (const BoolStats* s : {&c, &r, &o}) {
    EXPECT_CLEAN(*s);
    EXPECT_GT(s->positives, kCases / 10);
    EXPECT_GT(s->ambiguous, kCases / 100);
  }
}

TEST(Geometry2DReference, PairwiseOverlaps) {
  const auto f = [](const auto& a, const auto& b) { return overlaps(a, b); };
  const auto ro = [](const auto& a, const auto& b) { return ref_overlaps(a, b); };
  const BoolStats cc = run_bool<Circle, Circle>(41, kCases, f, ro, kBand);
  const BoolStats cr = run_bool<Circle, Rectangle2D>(42, kCases, f, ro, kBand);
  const BoolStats co = run_bool<Circle, OrientedRectangle>(43, kCases, f, ro, kBand);
  const BoolStats rr = run_bool<Rectangle2D, Rectangle2D>(44, kCases, f, ro, kBand);
  const BoolStats ro_ = run_bool<Rectangle2D, OrientedRectangle>(45, kCases, f, ro, kBand);
  const BoolStats oo = run_bool<OrientedRectangle, OrientedRectangle>(46, kCases, f, ro, kBand);
  print_stats("overlaps(Circle, Circle)", cc, kBand);
  print_stats("overlaps(Circle, Rectangle2D)", cr, kBand);
  print_stats("overlaps(Circle, OrientedRectangle)", co, kBand);
  print_stats("overlaps(Rectangle2D, Rectangle2D)", rr, kBand);
  print_stats("overlaps(Rectangle2D, OrientedRect.)", ro_, kBand);
  print_stats("overlaps(OrientedRect., OrientedRect.)", oo, kBand);
  for (const BoolStats* s : {&cc, &cr, &co, &rr, &ro_, &oo}) {
    EXPECT_CLEAN(*s);
    EXPECT_GT(s->positives, kCases / 10);
    EXPECT_GT(s->ambiguous, kCases / 100);
  }
}

TEST(Geometry2DReference, BoundingShape) {
  const auto fc = [](const BoundingShape& s, const vec2& p) { return contains(s, p); };
  const auto rc = [](const DShape& s, const D2& p) { return ref_contains(s, p); };
  const auto fl = [](const BoundingShape& s, const Line2D& l) { return linetest(s, l); };
  const auto rl = [](const DShape& s, const DSeg& l) { return ref_linetest(s, l); };
  const auto fo = [](const auto& a, const auto& b) { return overlaps(a, b); };
  const auto ro = [](const auto& a, const auto& b) { return ref_overlaps(a, b); };
  // The parts' tests are covered above; here one case in six touches, for run time.
  const BoolStats c = run_bool<BoundingShape, vec2>(51, kCases, fc, rc, kBand, 6);
  const BoolStats l = run_bool<BoundingShape, Line2D>(52, kCases, fl, rl, kBand, 6);
  const BoolStats oc = run_bool<BoundingShape, Circle>(53, kCases, fo, ro, kBand, 6);
  const BoolStats orr = run_bool<BoundingShape, Rectangle2D>(54, kCases, fo, ro, kBand, 6);
  const BoolStats oo = run_bool<BoundingShape, OrientedRectangle>(55, kCases, fo, ro, kBand, 6);
  const BoolStats ob = run_bool<BoundingShape, BoundingShape>(56, kCases, fo, ro, kBand, 6);
  print_stats("contains(BoundingShape, point)", c, kBand);
  print_stats("linetest(BoundingShape, Line2D)", l, kBand);
  print_stats("overlaps(BoundingShape, Circle)", oc, kBand);
  print_stats("overlaps(BoundingShape, Rectangle2D)", orr, kBand);
  print_stats("overlaps(BoundingShape, OrientedRect.)", oo, kBand);
  print_stats("overlaps(BoundingShape, BoundingShape)", ob, kBand);
  for (const BoolStats* s : {&c, &l, &oc, &orr, &oo, &ob}) {
    EXPECT_CLEAN(*s);
    EXPECT_GT(s->positives, kCases / 10);
  }
}

// ====================================================================== closest points

/// A sample of points of the solid shape (interior and boundary), in double.
std::vector<D2> samples(const DCircle& s, Gen& g, int n) {
  std::vector<D2> out;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * g.u(), r = (i % 2) ? s.r : s.r * std::sqrt(g.u());
    out.push_back(s.c + D2{std::cos(a), std::sin(a)} * r);
  }
  return out;
}
std::vector<D2> samples(const DRect& s, Gen& g, int n) {
  std::vector<D2> out;
  for (int i = 0; i < n; ++i) {
    D2 q{s.lo.x + (s.hi.x - s.lo.x) * g.u(), s.lo.y + (s.hi.y - s.lo.y) * g.u()};
    if (i % 2) {  // on an edge
      if (g.pick(2))
        q.x = g.pick(2) ? s.hi.x : s.lo.x;
      else
        q.y = g.pick(2) ? s.hi.y : s.lo.y;
    }
    out.push_back(q);
  }
  for (const D2& c : corners(s)) out.push_back(c);
  return out;
}
std::vector<D2> samples(const DORect& s, Gen& g, int n) {
  std::vector<D2> out;
  for (int i = 0; i < n; ++i) {
    D2 l{s.e.x * g.sym(), s.e.y * g.sym()};
    if (i % 2) {  // on an edge
      if (g.pick(2))
        l.x = g.pick(2) ? s.e.x : -s.e.x;
      else
        l.y = g.pick(2) ? s.e.y : -s.e.y;
    }
    out.push_back(s.c + s.u * l.x + s.v * l.y);
  }
  for (const D2& c : corners(s)) out.push_back(c);
  return out;
}
std::vector<D2> samples(const DSeg& s, Gen& g, int n) {
  std::vector<D2> out{s.a, s.b};
  for (int i = 0; i < n; ++i) out.push_back(s.a + (s.b - s.a) * g.u());
  return out;
}

D2 ref_closest(const DCircle& s, D2 p) {
  const D2 d = p - s.c;
  const double l = dlen(d);
  return l <= s.r ? p : s.c + d * (s.r / l);
}
D2 ref_closest(const DRect& s, D2 p) { return {dclamp(p.x, s.lo.x, s.hi.x), dclamp(p.y, s.lo.y, s.hi.y)}; }
D2 ref_closest(const DORect& s, D2 p) {
  const D2 l = local_of(s, p);
  return s.c + s.u * dclamp(l.x, -s.e.x, s.e.x) + s.v * dclamp(l.y, -s.e.y, s.e.y);
}
D2 ref_closest(const DSeg& s, D2 p) {
  const D2 ab = s.b - s.a;
  const double dd = ddot(ab, ab);
  return s.a + ab * (dd > 0 ? dclamp(ddot(p - s.a, ab) / dd, 0, 1) : 0);
}
double ref_distance(const DCircle& s, D2 p) { return std::max(0.0, dlen(p - s.c) - s.r); }
double ref_distance(const DRect& s, D2 p) { return dlen(p - ref_closest(s, p)); }
double ref_distance(const DORect& s, D2 p) {
  const D2 l = local_of(s, p);
  return dlen(D2{l.x - dclamp(l.x, -s.e.x, s.e.x), l.y - dclamp(l.y, -s.e.y, s.e.y)});
}
double ref_distance(const DSeg& s, D2 p) { return dist_point_segment(p, s); }

struct ClosestStats {
  long cases = 0, sampled = 0, too_far = 0, outside = 0, beaten = 0, float_outside = 0;
  double max_err = 0;      // |gyro - reference| / M
  double max_outside = 0;  // distance of gyro's point from the shape / M
};

/// Closest points: error against the analytic double reference, the point in the shape,
/// and no sampled point of the shape closer (the first 5000 cases, 64 samples each).
template <class S>
ClosestStats run_closest(uint64_t seed, long n) {
  Gen g(seed);
  ClosestStats st;
  for (long i = 0; i < n; ++i) {
    const Place pl = g.place();
    const S s = g.make(pl, static_cast<const S*>(nullptr));
    vec2 p = g.point(pl);
    if (g.pick(4) == 0) {  // on or near the boundary
      if constexpr (std::is_same_v<S, Line2D>) {
        p = lerp(s.start, s.end, f32(g.u()));
      } else {
        p = touching(s, p, g, [](const auto& a, const D2& q) { return ref_contains(a, q); });
      }
    }
    const vec2 q = closest_point(s, p);
    const auto ds = dref(s);
    const D2 dp = dref(p), dq = dref(q);
    const double m = std::max({mag(s), mag(p), 1e-300});
    const D2 r = ref_closest(ds, dp);
    ++st.cases;
    const double err = dlen(dq - r) / m;
    st.max_err = std::max(st.max_err, err);
    st.too_far += err > 0x1p-20;
    const double out = ref_distance(ds, dq) / m;
    st.max_outside = std::max(st.max_outside, out);
    st.outside += out > 0x1p-21;
    if constexpr (!std::is_same_v<S, Line2D>) st.float_outside += !contains(s, q);
    if (i < 5000) {
      ++st.sampled;
      const double dist = dlen(dq - dp);
      for (const D2& x : samples(ds, g, 64))
        if (dlen(x - dp) < dist - 0x1p-20 * m) {
          ++st.beaten;
          break;
        }
    }
  }
  return st;
}

void print_closest(const char* name, const ClosestStats& s) {
  std::printf("  %-40s %7ld cases: max |gyro - ref| %.2e*M (%ld > 2^-20*M), max distance outside %.2e*M (%ld > "
              "2^-21*M), float contains() false on %ld; %ld sampled, %ld beaten\n",
              name, s.cases, s.max_err, s.too_far, s.max_outside, s.outside, s.float_outside, s.sampled, s.beaten);
}

TEST(Geometry2DReference, ClosestPoints) {
  const ClosestStats l = run_closest<Line2D>(61, kCases);
  const ClosestStats c = run_closest<Circle>(62, kCases);
  const ClosestStats r = run_closest<Rectangle2D>(63, kCases);
  const ClosestStats o = run_closest<OrientedRectangle>(64, kCases);
  print_closest("closest_point(Line2D, point)", l);
  print_closest("closest_point(Circle, point)", c);
  print_closest("closest_point(Rectangle2D, point)", r);
  print_closest("closest_point(OrientedRectangle, point)", o);
  for (const ClosestStats* s : {&l, &c, &r, &o}) {
    EXPECT_EQ(s->too_far, 0);
    EXPECT_EQ(s->outside, 0);
    EXPECT_EQ(s->beaten, 0);
  }
  EXPECT_EQ(r.float_outside, 0);  // a clamp: exactly inside
}

// The closest point of a segment is on it by contains(Line2D)'s own tolerance.
TEST(Geometry2DProperties, ClosestPointOfASegmentIsOnIt) {
  Gen g(65);
  long off = 0;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const Line2D l = g.line(pl);
    off += !contains(l, closest_point(l, g.point(pl)));
  }
  EXPECT_EQ(off, 0);
}

// ====================================================================== properties

// A point contained in a shape gives an overlap with the zero-size shapes at that point
// (same arithmetic, so exactly) and a hit for the zero-length segment there.
TEST(Geometry2DProperties, ContainmentImpliesOverlap) {
  Gen g(71);
  long contained = 0, broken = 0, flips_in_band = 0, flips_clear = 0;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const Circle c = g.circle(pl);
    const Rectangle2D r = g.rect(pl);
    const OrientedRectangle o = g.orect(pl);
    vec2 p = g.point(pl);
    switch (g.pick(4)) {
      case 0: p = touching(c, p, g, [](const DCircle& s, const D2& q) { return ref_contains(s, q); }); break;
      case 1: p = touching(r, p, g, [](const DRect& s, const D2& q) { return ref_contains(s, q); }); break;
      case 2: p = touching(o, p, g, [](const DORect& s, const D2& q) { return ref_contains(s, q); }); break;
      default: break;
    }
    const Circle pc{p, 0.0f};
    const Rectangle2D pr{p, {0.0f, 0.0f}};
    const OrientedRectangle po{p, {0.0f, 0.0f}, g.angle()};
    const Line2D pl2{p, p};
    // Where the point is a rotated zero-size rectangle the test runs in another frame
    // (the point's own axes, or x and y against a rotated box), so rounding may flip a
    // point on the boundary; such a flip must be within the band of the boundary.
    const auto inexact = [&](const auto& s, bool overlap) {
      if (overlap) return;
      const bool clear_inside = ref_contains(grow(dref(s), -kBand * std::max(mag(s), mag(p))), dref(p));
      (clear_inside ? flips_clear : flips_in_band)++;
    };
    if (contains(c, p)) {
      ++contained;
      broken += !overlaps(c, pc) + !overlaps(c, pr) + !linetest(c, pl2);
      inexact(c, overlaps(c, po));
    }
    if (contains(r, p)) {
      ++contained;
      broken += !overlaps(r, pc) + !overlaps(r, pr) + !linetest(r, pl2);
      inexact(r, overlaps(r, po));
    }
    if (contains(o, p)) {
      ++contained;
      broken += !overlaps(o, pc) + !linetest(o, pl2);
      inexact(o, overlaps(o, pr));
      inexact(o, overlaps(o, po));
    }
  }
  std::printf("  %ld containments: %ld exact implications broken; zero-size rectangles in another frame: %ld "
              "flips within the band of the boundary, %ld clearly inside\n",
              contained, broken, flips_in_band, flips_clear);
  EXPECT_GT(contained, kCases / 2);
  EXPECT_EQ(broken, 0);
  EXPECT_EQ(flips_clear, 0);
}

// Symmetry bit for bit, on pairs at the same place (many overlapping and touching).
TEST(Geometry2DProperties, OverlapsIsSymmetric) {
  Gen g(72);
  long asym = 0, checked = 0;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const Circle c1 = g.circle(pl), c2 = g.circle(pl);
    const Rectangle2D r1 = g.rect(pl), r2 = g.rect(pl);
    const OrientedRectangle o1 = g.orect(pl), o2 = g.orect(pl);
    const BoundingShape b = g.shape(pl);
    asym += overlaps(c1, c2) != overlaps(c2, c1);
    asym += overlaps(r1, r2) != overlaps(r2, r1);
    asym += overlaps(o1, o2) != overlaps(o2, o1);
    asym += overlaps(c1, r1) != overlaps(r1, c1);
    asym += overlaps(c1, o1) != overlaps(o1, c1);
    asym += overlaps(r1, o1) != overlaps(o1, r1);
    asym += overlaps(b, c1) != overlaps(c1, b);
    asym += overlaps(b, r1) != overlaps(r1, b);
    asym += overlaps(b, o1) != overlaps(o1, b);
    checked += 9;
  }
  std::printf("  %ld symmetric pairs checked, %ld asymmetric\n", checked, asym);
  EXPECT_EQ(asym, 0);
}

// A shape with a point clearly inside another shape overlaps it: every shape of every
// type built around a point well inside (by the band) every other type.
TEST(Geometry2DProperties, ShapesAroundAContainedPointOverlap) {
  Gen g(73);
  long n = 0, broken = 0;
  const auto inside = [](const auto& s, const vec2& p) {
    return ref_contains(grow(dref(s), -kBand * std::max(mag(s), mag(p))), dref(p));
  };
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const Circle c = g.circle(pl);
    const Rectangle2D r = g.rect(pl);
    const OrientedRectangle o = g.orect(pl);
    const vec2 p = g.point(pl);
    const Circle pc{p, g.size(pl)};
    const Rectangle2D pr{p, {g.size(pl), g.size(pl)}};  // p is its minimum corner
    const OrientedRectangle po{p, {g.size(pl), g.size(pl)}, g.angle()};
    const Line2D ps{p, g.point(pl)};
    if (inside(c, p)) ++n, broken += !overlaps(c, pc) + !overlaps(c, pr) + !overlaps(c, po) + !linetest(c, ps);
    if (inside(r, p)) ++n, broken += !overlaps(r, pc) + !overlaps(r, pr) + !overlaps(r, po) + !linetest(r, ps);
    if (inside(o, p)) ++n, broken += !overlaps(o, pc) + !overlaps(o, pr) + !overlaps(o, po) + !linetest(o, ps);
  }
  std::printf("  %ld shapes with a point clearly inside another: %ld missed overlaps\n", n, broken);
  EXPECT_GT(n, kCases / 20);
  EXPECT_EQ(broken, 0);
}

// ====================================================================== containing shapes

struct DC {
  D2 c;
  double r;
};

/// The minimum enclosing circle by brute force in double: every circle on two points as a
/// diameter and every circumcircle of three, the smallest that contains all the points
/// (up to 1e-12 of the magnitude, double rounding).
DC brute_mec(const std::vector<D2>& pts) {
  double m = 0;
  for (const D2& p : pts) m = std::max({m, std::abs(p.x), std::abs(p.y)});
  const double tol = 1e-12 * (m + 1e-300);
  const auto covers = [&](const DC& c) {
    for (const D2& p : pts)
      if (dlen(p - c.c) > c.r + tol) return false;
    return true;
  };
  DC best{pts[0], pts.size() == 1 ? 0.0 : kDInf};
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const DC c{(pts[i] + pts[j]) * 0.5, dlen(pts[i] - pts[j]) * 0.5};
      if (c.r < best.r && covers(c)) best = c;
      for (std::size_t k = j + 1; k < n; ++k) {
        const D2 a = pts[j] - pts[i], b = pts[k] - pts[i];
        const double d = 2 * (a.x * b.y - a.y * b.x);
        if (d == 0) continue;
        const double a2 = ddot(a, a), b2 = ddot(b, b);
        const D2 u{(b.y * a2 - a.y * b2) / d, (a.x * b2 - b.x * a2) / d};
        const DC t{pts[i] + u, dlen(u)};
        if (t.r < best.r && covers(t)) best = t;
      }
    }
  return best;
}

/// Convex hull (Andrew's monotone chain, collinear points dropped), in double.
std::vector<D2> hull(std::vector<D2> p) {
  std::sort(p.begin(), p.end(), [](D2 a, D2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](D2 a, D2 b) { return a.x == b.x && a.y == b.y; }), p.end());
  if (p.size() < 3) return p;
  std::vector<D2> h(2 * p.size());
  std::size_t k = 0;
  const auto turn = [](D2 o, D2 a, D2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

/// A point set of one of several hard kinds, n points, at place pl.
std::vector<vec2> point_set(Gen& g, const Place& pl, std::size_t n) {
  std::vector<vec2> pts;
  int kind = g.pick(7);
  if (kind == 0 && n > 32) kind = 6;  // the hull brute force is O(h^4): co-circular sets stay small
  const double s = pl.s;
  const vec2 a = g.point(pl), b = g.point(pl);
  for (std::size_t i = 0; i < n; ++i) {
    switch (kind) {
      case 0: {  // on a circle (co-circular up to float rounding)
        const double t = 2 * M_PI * g.u();
        pts.push_back({f32(pl.o.x + s * std::cos(t)), f32(pl.o.y + s * std::sin(t))});
        break;
      }
      case 1: pts.push_back(lerp(a, b, f32(g.u()))); break;                       // collinear, rounded
      case 2: pts.push_back({a.x, f32(pl.o.y + s * g.sym())}); break;             // exactly collinear, vertical
      case 3: pts.push_back(i % 3 == 0 || pts.empty() ? g.point(pl) : pts[g.pick(int(pts.size()))]); break;  // repeats
      case 4:  // a grid
        pts.push_back({f32(pl.o.x + s * g.pick(4)), f32(pl.o.y + s * g.pick(4))});
        break;
      case 5: pts.push_back(a); break;  // all the same point
      default: pts.push_back(g.point(pl)); break;
    }
  }
  return pts;
}

struct MecStats {
  long sets = 0, uncontained = 0, worse = 0, order_dependent = 0;
  double max_excess = 0, min_excess = 0, max_center = 0;  // (r - r_opt) / M, |c - c_opt| / M
};

void check_mec(MecStats& st, Gen& g, const std::vector<vec2>& pts, bool brute_on_hull) {
  const Circle c = containing_circle(pts);
  ++st.sets;
  double m = 0;
  std::vector<D2> dp;
  for (const vec2& p : pts) {
    st.uncontained += !contains(c, p);
    m = std::max(m, mag(p));
    dp.push_back(dref(p));
  }
  const DC ref = brute_mec(brute_on_hull ? hull(dp) : dp);
  m = std::max({m, ref.r, 1e-300});
  const double excess = (double(c.radius) - ref.r) / m;
  st.max_excess = std::max(st.max_excess, excess);
  st.min_excess = std::min(st.min_excess, excess);
  st.max_center = std::max(st.max_center, dlen(dref(c.center) - ref.c) / m);
  st.worse += excess > 0x1p-19;
  // The same points in another order give the same bits.
  std::vector<vec2> shuffled = pts;
  for (std::size_t i = shuffled.size(); i > 1; --i) std::swap(shuffled[i - 1], shuffled[g.pick(int(i))]);
  if (g.pick(2)) for (vec2& p : shuffled) p = {p.x == 0 ? -0.0f : p.x, p.y};
  const Circle c2 = containing_circle(shuffled);
  st.order_dependent += std::memcmp(&c, &c2, sizeof c) != 0;
}

void print_mec(const char* name, const MecStats& s) {
  std::printf("  %-34s %6ld sets: %ld points outside, radius - optimum in [%.2e, %.2e]*M (%ld above 2^-19*M), "
              "center error %.2e*M, %ld order-dependent\n",
              name, s.sets, s.uncontained, s.min_excess, s.max_excess, s.worse, s.max_center, s.order_dependent);
}

TEST(Geometry2DReference, ContainingCircleIsTheMinimumEnclosingCircle) {
  Gen g(81);
  MecStats small, large;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    check_mec(small, g, point_set(g, pl, 1 + std::size_t(g.pick(8))), false);
  }
  for (long i = 0; i < 300; ++i) {
    const Place pl = g.place();
    check_mec(large, g, point_set(g, pl, 9 + std::size_t(g.pick(i % 3 == 0 ? 24 : 1000))), true);
  }
  print_mec("containing_circle, 1-8 points", small);
  print_mec("containing_circle, 9-1008 points", large);
  for (const MecStats* s : {&small, &large}) {
    EXPECT_EQ(s->uncontained, 0);
    EXPECT_EQ(s->worse, 0);
    EXPECT_EQ(s->order_dependent, 0);
    EXPECT_GT(s->min_excess, -0x1p-20);
  }
}

// The book's containing circle (centroid, farthest point) is never smaller than ours.
TEST(Geometry2DReference, ContainingCircleBeatsTheCentroidCircle) {
  Gen g(82);
  double ratio_sum = 0, worst = 0;
  long n = 0, larger = 0;
  for (long i = 0; i < 10000; ++i) {
    const Place pl{1.0, {0, 0}};
    std::vector<vec2> pts;
    for (int k = 0, count = 2 + g.pick(50); k < count; ++k) pts.push_back(g.point(pl));
    D2 mean{};
    for (const vec2& p : pts) mean = mean + dref(p) * (1.0 / double(pts.size()));
    double r = 0;
    for (const vec2& p : pts) r = std::max(r, dlen(dref(p) - mean));
    const double ours = containing_circle(pts).radius;
    larger += ours > r * (1 + 1e-6);
    ratio_sum += ours / r, worst = std::max(worst, ours / r), ++n;
  }
  std::printf("  radius / centroid circle's radius: mean %.3f, max %.3f over %ld sets\n", ratio_sum / double(n), worst, n);
  EXPECT_EQ(larger, 0);
  EXPECT_LT(ratio_sum / double(n), 0.95);
}

TEST(Geometry2DReference, ContainingRectangle) {
  Gen g(83);
  long uncovered = 0, not_tight = 0, wrong_min = 0;
  double max_slack = 0;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    const std::vector<vec2> pts = point_set(g, pl, 1 + std::size_t(g.pick(16)));
    const Rectangle2D r = containing_rectangle(pts);
    D2 lo{kDInf, kDInf}, hi{-kDInf, -kDInf};
    for (const vec2& p : pts) {
      uncovered += !contains(r, p);
      lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y))};
      hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y))};
    }
    wrong_min += double(r.origin.x) != lo.x || double(r.origin.y) != lo.y;
    const vec2 top = rectangle_max(r);
    // Tight: the rounded hi - lo, or one float more where that fell short of hi.
    for (int a = 0; a < 2; ++a) {
      const float h = float(a ? hi.y : hi.x), l = r.origin[a], nearest = h - l;
      if (!(r.size[a] == nearest || (l + nearest < h && r.size[a] == std::nextafter(nearest, kFInf)))) ++not_tight;
    }
    const double m = std::max({mag(r.origin), mag(top), 1e-300});
    max_slack = std::max({max_slack, (double(top.x) - hi.x) / m, (double(top.y) - hi.y) / m});
  }
  std::printf("  containing_rectangle: %ld sets, %ld points outside, %ld origins off the minimum, %ld sizes not "
              "tight, max corner slack %.2e*M\n",
              kCases, uncovered, wrong_min, not_tight, max_slack);
  EXPECT_EQ(uncovered, 0);
  EXPECT_EQ(wrong_min, 0);
  EXPECT_EQ(not_tight, 0);
  EXPECT_LE(max_slack, 0x1p-21);  // an ulp or two of the magnitude
}

// ====================================================================== explicit cases

TEST(Geometry2D, BasicAnswers) {
  const Circle unit{{0, 0}, 1};
  EXPECT_TRUE(contains(unit, vec2{1, 0}));  // on the rim
  EXPECT_FALSE(contains(unit, vec2{std::nextafter(1.0f, 2.0f), 0}));
  EXPECT_TRUE(overlaps(unit, Circle{{2, 0}, 1}));  // touching
  EXPECT_FALSE(overlaps(unit, Circle{{2.0001f, 0}, 1}));
  const Rectangle2D box{{0, 0}, {2, 1}};
  EXPECT_TRUE(contains(box, vec2{2, 1}));
  EXPECT_TRUE(overlaps(box, Rectangle2D{{2, 1}, {1, 1}}));  // corner to corner
  EXPECT_FALSE(overlaps(box, Rectangle2D{{2, 1.0001f}, {1, 1}}));
  EXPECT_TRUE(overlaps(box, Circle{{3, 0.5f}, 1}));
  EXPECT_TRUE(linetest(box, Line2D{{-1, 1}, {3, 1}}));  // along the top edge
  EXPECT_FALSE(linetest(box, Line2D{{-1, 1.0001f}, {3, 1.0001f}}));
  EXPECT_TRUE(linetest(box, Line2D{{0.5f, 0.5f}, {0.5f, 0.5f}}));  // a point inside
  EXPECT_TRUE(linetest(unit, Line2D{{-2, 1}, {2, 1}}));            // tangent
  // A quarter turn swaps the extents (up to the float rotation's 4e-8 tilt).
  const OrientedRectangle turned{{0, 0}, {2, 1}, kHalfPi};
  EXPECT_TRUE(contains(turned, vec2{0.9f, 1.9f}));
  EXPECT_FALSE(contains(turned, vec2{1.9f, 0.9f}));
  EXPECT_TRUE(overlaps(turned, Rectangle2D{{0.99f, -1}, {1, 1}}));
  EXPECT_FALSE(overlaps(turned, Rectangle2D{{1.01f, -1}, {1, 1}}));
  const OrientedRectangle diamond{{0, 0}, {1, 1}, kPi * 0.25f};
  EXPECT_TRUE(contains(diamond, vec2{1.4f, 0}));
  EXPECT_FALSE(contains(diamond, vec2{1, 1}));
  EXPECT_FALSE(overlaps(diamond, OrientedRectangle{{3, 0}, {1, 1}, kPi * 0.25f}));  // 2 sqrt(2) < 3
  EXPECT_TRUE(overlaps(diamond, OrientedRectangle{{2.8f, 0}, {1, 1}, kPi * 0.25f}));
  EXPECT_TRUE(overlaps(diamond, Circle{{1.9f, 0}, 0.5f}));
  // Points on a segment, vertical ones included (the book's y = mx + b misses those).
  const Line2D vertical{{3, -1}, {3, 5}};
  EXPECT_TRUE(contains(vertical, vec2{3, 2}));
  EXPECT_TRUE(contains(vertical, vec2{3, 5}));
  EXPECT_FALSE(contains(vertical, vec2{3, 5.01f}));
  EXPECT_FALSE(contains(vertical, vec2{3.001f, 2}));
  EXPECT_FLOAT_EQ(length(Line2D{{0, 0}, {3, 4}}), 5.0f);
  EXPECT_FLOAT_EQ(length_squared(Line2D{{0, 0}, {3, 4}}), 25.0f);
  EXPECT_EQ(closest_point(unit, vec2{0.5f, 0}), (vec2{0.5f, 0}));
  EXPECT_EQ(closest_point(unit, vec2{4, 0}), (vec2{1, 0}));
  EXPECT_EQ(closest_point(box, vec2{5, -3}), (vec2{2, 0}));
  EXPECT_EQ(closest_point(Line2D{{0, 0}, {2, 0}}, vec2{1, 7}), (vec2{1, 0}));
  EXPECT_EQ(closest_point(Line2D{{1, 1}, {1, 1}}, vec2{1, 7}), (vec2{1, 1}));
}

TEST(Geometry2D, DegenerateShapes) {
  const Circle dot{{1, 1}, 0};
  EXPECT_TRUE(contains(dot, vec2{1, 1}));
  EXPECT_FALSE(contains(dot, vec2{1, std::nextafter(1.0f, 2.0f)}));
  EXPECT_TRUE(overlaps(dot, Circle{{1, 1}, 0}));
  EXPECT_TRUE(overlaps(dot, Rectangle2D{{1, 0}, {0, 2}}));  // a point on a segment-rectangle
  const Rectangle2D seg{{0, 0}, {4, 0}};
  EXPECT_TRUE(contains(seg, vec2{2, 0}));
  EXPECT_TRUE(overlaps(seg, Rectangle2D{{2, -1}, {0, 2}}));  // two crossing segments
  EXPECT_TRUE(linetest(seg, Line2D{{1, -1}, {3, 1}}));
  EXPECT_FALSE(linetest(seg, Line2D{{1, 0.1f}, {3, 1}}));
  const OrientedRectangle flat{{0, 0}, {2, 0}, kPi * 0.25f};  // a diagonal segment
  EXPECT_TRUE(contains(flat, vec2{0, 0}));
  EXPECT_TRUE(overlaps(flat, OrientedRectangle{{0, 0}, {2, 0}, -kPi * 0.25f}));  // an X
  EXPECT_TRUE(linetest(flat, Line2D{{-1, 1}, {1, -1}}));
  EXPECT_TRUE(linetest(Circle{{0, 0}, 1}, Line2D{{0.5f, 0}, {0.5f, 0}}));
  EXPECT_FALSE(linetest(Circle{{0, 0}, 1}, Line2D{{1.5f, 0}, {1.5f, 0}}));
  EXPECT_EQ(containing_circle({}).radius, 0.0f);
  const vec2 one[] = {{3, 4}};
  EXPECT_EQ(containing_circle(one).center, (vec2{3, 4}));
  EXPECT_EQ(containing_circle(one).radius, 0.0f);
  EXPECT_EQ(containing_rectangle(one).size, (vec2{0, 0}));
  const BoundingShape none;
  EXPECT_FALSE(contains(none, vec2{0, 0}));
  EXPECT_FALSE(overlaps(none, none));
  EXPECT_FALSE(linetest(none, Line2D{}));
  const BoundingShape two{{Circle{{0, 0}, 1}}, {Rectangle2D{{5, 5}, {1, 1}}}};
  EXPECT_TRUE(contains(two, vec2{5.5f, 5.5f}));
  EXPECT_FALSE(contains(two, vec2{3, 3}));
  EXPECT_TRUE(overlaps(two, OrientedRectangle{{3, 3}, {3, 0.1f}, kPi * 0.25f}));
  EXPECT_TRUE(overlaps(two, two));
}

// rectangle_from_min_max covers both corners even where hi - lo rounds down.
TEST(Geometry2D, RectangleFromMinMaxCoversItsCorners) {
  Gen g(91);
  long uncovered = 0, rounded_up = 0;
  for (long i = 0; i < kCases; ++i) {
    const Place pl = g.place();
    vec2 lo = g.point(pl), hi = g.point(pl);
    const vec2 a = min(lo, hi), b = max(lo, hi);
    const Rectangle2D r = rectangle_from_min_max(a, b);
    uncovered += !contains(r, a) + !contains(r, b);
    rounded_up += r.size != b - a;
    EXPECT_EQ(r.origin, a);
  }
  std::printf("  rectangle_from_min_max: %ld of %ld sizes rounded up to cover hi; %ld corners uncovered\n",
              rounded_up, kCases, uncovered);
  EXPECT_EQ(uncovered, 0);
  EXPECT_GT(rounded_up, 0);
}

// Invalid input: NaN, infinity, negative sizes. Every test is false, closest points NaN,
// containing shapes NaN; nothing crashes.
TEST(Geometry2D, InvalidInputGivesDefinedAnswers) {
  const float bad_values[] = {kFNaN, kFInf, -kFInf};
  const Circle c{{0, 0}, 1};
  const Rectangle2D r{{-1, -1}, {2, 2}};
  const OrientedRectangle o{{0, 0}, {1, 1}, 0.3f};
  const Line2D l{{-2, 0}, {2, 0}};
  const vec2 p{0, 0};
  long wrong = 0, cases = 0;
  const auto all_false = [&](const auto& s) {
    ++cases;
    wrong += contains(s, p) + overlaps(s, c) + overlaps(c, s) + overlaps(s, r) + overlaps(r, s) + overlaps(s, o) +
             overlaps(o, s) + linetest(s, l) + !std::isnan(closest_point(s, p).x);
  };
  for (float v : bad_values) {
    for (int f = 0; f < 3; ++f) {
      Circle bc = c;
      (f == 0 ? bc.center.x : f == 1 ? bc.center.y : bc.radius) = v;
      if (!(f == 2 && v == kFInf)) all_false(bc);
      Rectangle2D br = r;
      (f == 0 ? br.origin.x : f == 1 ? br.origin.y : br.size.y) = v;
      all_false(br);
      OrientedRectangle bo = o;
      (f == 0 ? bo.center.y : f == 1 ? bo.half_extents.x : bo.rotation) = v;
      all_false(bo);
    }
    const vec2 bp{v, 0};
    const Line2D bl{{0, 0}, {0, v}};
    ++cases;
    wrong += contains(c, bp) + contains(r, bp) + contains(o, bp) + contains(l, bp) + linetest(c, bl) +
             linetest(r, bl) + linetest(o, bl) + contains(bl, p) + !std::isnan(closest_point(r, bp).y);
    const vec2 pts[] = {{0, 0}, bp};
    wrong += !std::isnan(containing_circle(pts).radius) + !std::isnan(containing_rectangle(pts).size.x);
  }
  // Infinite radius: not finite, so invalid too.
  all_false(Circle{{0, 0}, kFInf});
  // Negative sizes: empty shapes.
  all_false(Circle{{0, 0}, -1});
  all_false(Rectangle2D{{0, 0}, {-1, 1}});
  all_false(OrientedRectangle{{0, 0}, {1, -0.5f}, 0});
  // Coordinates whose difference overflows.
  wrong += linetest(r, Line2D{{-3e38f, 0}, {3e38f, 0}});
  std::printf("  %ld invalid shapes and points: %ld answers that were not false / NaN\n", cases, wrong);
  EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace gyro
