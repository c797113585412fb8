// The 2D primitives of Cookbook chapters 4-6 (gyro/geometry2d.hpp).
//
// Every public test first rejects invalid input (non-finite numbers, negative sizes), so
// the arithmetic below only ever sees finite shapes and a NaN can never slip through a
// clamp (gyro::clamp returns x when a bound is NaN) into a "true".
//
// Exact consistency between functions is kept where a property depends on it: contains()
// of a point and overlaps() with a zero-size circle at that point run the same arithmetic,
// as do contains() and linetest() with a zero-length segment, and the separating axis
// tests are written so that swapping the arguments negates the center difference exactly
// and leaves every other product and sum unchanged.
#include "gyro/geometry2d.hpp"

#include "gyro/math_scalar.hpp"
#include "gyro/math_trig.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gyro {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

bool finite(float v) { return std::isfinite(v); }
bool finite(const vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

bool valid(const vec2& p) { return finite(p); }
bool valid(const Line2D& l) { return finite(l.start) && finite(l.end) && finite(l.end - l.start); }
bool valid(const Circle& c) { return finite(c.center) && finite(c.radius) && c.radius >= 0.0f; }
bool valid(const Rectangle2D& r) {
  return finite(r.origin) && finite(r.size) && r.size.x >= 0.0f && r.size.y >= 0.0f && finite(r.origin + r.size);
}
bool valid(const OrientedRectangle& r) {
  return finite(r.center) && finite(r.half_extents) && finite(r.rotation) && r.half_extents.x >= 0.0f &&
         r.half_extents.y >= 0.0f;
}

/// The local axes of an oriented rectangle: u = (cos r, sin r), v = (-sin r, cos r).
struct Frame {
  vec2 u, v;
};
Frame frame_of(const OrientedRectangle& r) {
  float s = 0.0f, c = 0.0f;
  gyro::sincos(r.rotation, &s, &c);
  return {{c, s}, {-s, c}};
}
/// p in the rectangle's frame: (dot(p - center, u), dot(p - center, v)).
vec2 to_local(const OrientedRectangle& r, const Frame& f, const vec2& p) {
  const vec2 d = p - r.center;
  return {dot(d, f.u), dot(d, f.v)};
}

vec2 clamp2(const vec2& p, const vec2& lo, const vec2& hi) { return {clamp(p.x, lo.x, hi.x), clamp(p.y, lo.y, hi.y)}; }

/// Circle (c, r) against the box [lo, hi]: the distance to the clamped center.
bool circle_box(const vec2& c, float r, const vec2& lo, const vec2& hi) {
  const vec2 d = c - clamp2(c, lo, hi);
  return dot(d, d) <= r * r;
}

/// Segment s-e against the box with corners lo, hi, center c and half extents h: the
/// separating axis test on x, y and the segment's normal. The normal's test compares
/// |n . (c - s)| with the box's projected radius, so a zero-length segment (n = 0) passes
/// it and only the interval tests decide, exactly like a point containment test.
bool segment_box(const vec2& s, const vec2& e, const vec2& lo, const vec2& hi, const vec2& c, const vec2& h) {
  if (min(s.x, e.x) > hi.x || max(s.x, e.x) < lo.x) return false;
  if (min(s.y, e.y) > hi.y || max(s.y, e.y) < lo.y) return false;
  const vec2 ab = e - s;
  const vec2 n{-ab.y, ab.x};
  return std::abs(dot(n, c - s)) <= std::abs(n.x) * h.x + std::abs(n.y) * h.y;
}

/// True if the projections on `axis` of two boxes, whose centers differ by d, are apart.
/// `own` is the box's half extent along its own axis; the other box has axes ou, ov and
/// half extents oe. Swapping the boxes negates d and keeps every other term, so the
/// answer is symmetric bit for bit.
bool separated_on(const vec2& d, const vec2& axis, float own, const vec2& ou, const vec2& ov, const vec2& oe) {
  const float other = std::abs(dot(axis, ou)) * oe.x + std::abs(dot(axis, ov)) * oe.y;
  return !(std::abs(dot(d, axis)) <= own + other);
}

constexpr vec2 kAxisX{1.0f, 0.0f};
constexpr vec2 kAxisY{0.0f, 1.0f};

/// r's half extents and center (origin + size / 2).
vec2 half_of(const Rectangle2D& r) { return r.size * 0.5f; }
vec2 center_of(const Rectangle2D& r) { return r.origin + r.size * 0.5f; }

/// The length of v, computed so that tiny and huge vectors keep their precision.
float robust_length(const vec2& v) {
  const float m = max(std::abs(v.x), std::abs(v.y));
  if (m == 0.0f) return 0.0f;
  const vec2 s = v / m;
  return m * std::sqrt(dot(s, s));
}

}  // namespace

Rectangle2D rectangle_from_min_max(const vec2& lo, const vec2& hi) {
  // hi - lo is rounded to nearest, so lo + size can fall an ulp short of hi; one step up
  // restores it (the loop also ends at once on NaN, where the comparison fails).
  const auto fit = [](float l, float h) {
    float size = h - l;
    while (l + size < h) size = std::nextafter(size, kInf);
    return size;
  };
  return {lo, {fit(lo.x, hi.x), fit(lo.y, hi.y)}};
}

float length(const Line2D& line) { return gyro::length(line.end - line.start); }
float length_squared(const Line2D& line) { return gyro::length_squared(line.end - line.start); }

// ------------------------------------------------------------------ points

bool contains(const Line2D& line, const vec2& point) {
  if (!valid(line) || !valid(point)) return false;
  const vec2 ab = line.end - line.start;
  const vec2 d = point - line.start;
  const float dd = dot(ab, ab);
  const float t = dd > 0.0f ? clamp(dot(d, ab) / dd, 0.0f, 1.0f) : 0.0f;
  const vec2 off = d - ab * t;
  const float scale = max(max(max(std::abs(line.start.x), std::abs(line.start.y)),
                              max(std::abs(line.end.x), std::abs(line.end.y))),
                          max(std::abs(point.x), std::abs(point.y)));
  const float tol = kOnLineTolerance * scale;
  return dot(off, off) <= tol * tol;
}

bool contains(const Circle& circle, const vec2& point) {
  if (!valid(circle) || !valid(point)) return false;
  const vec2 d = point - circle.center;
  return dot(d, d) <= circle.radius * circle.radius;
}

bool contains(const Rectangle2D& rectangle, const vec2& point) {
  if (!valid(rectangle) || !valid(point)) return false;
  const vec2 lo = rectangle.origin, hi = rectangle.origin + rectangle.size;
  return lo.x <= point.x && point.x <= hi.x && lo.y <= point.y && point.y <= hi.y;
}

bool contains(const OrientedRectangle& rectangle, const vec2& point) {
  if (!valid(rectangle) || !valid(point)) return false;
  const vec2 l = to_local(rectangle, frame_of(rectangle), point);
  return std::abs(l.x) <= rectangle.half_extents.x && std::abs(l.y) <= rectangle.half_extents.y;
}

bool contains(const BoundingShape& shape, const vec2& point) {
  for (const Circle& c : shape.circles)
    if (contains(c, point)) return true;
  for (const Rectangle2D& r : shape.rectangles)
    if (contains(r, point)) return true;
  return false;
}

// ------------------------------------------------------------------ closest points

vec2 closest_point(const Line2D& line, const vec2& point) {
  if (!valid(line) || !valid(point)) return {kNaN, kNaN};
  const vec2 ab = line.end - line.start;
  const float dd = dot(ab, ab);
  const float t = dd > 0.0f ? clamp(dot(point - line.start, ab) / dd, 0.0f, 1.0f) : 0.0f;
  return line.start + ab * t;
}

vec2 closest_point(const Circle& circle, const vec2& point) {
  if (!valid(circle) || !valid(point)) return {kNaN, kNaN};
  const vec2 d = point - circle.center;
  if (dot(d, d) <= circle.radius * circle.radius) return point;
  return circle.center + normalized(d) * circle.radius;
}

vec2 closest_point(const Rectangle2D& rectangle, const vec2& point) {
  if (!valid(rectangle) || !valid(point)) return {kNaN, kNaN};
  return clamp2(point, rectangle.origin, rectangle.origin + rectangle.size);
}

vec2 closest_point(const OrientedRectangle& rectangle, const vec2& point) {
  if (!valid(rectangle) || !valid(point)) return {kNaN, kNaN};
  const Frame f = frame_of(rectangle);
  const vec2 e = rectangle.half_extents;
  const vec2 q = clamp2(to_local(rectangle, f, point), -e, e);
  // The offset first, then the center: far from the origin the offset keeps its bits.
  return rectangle.center + (f.u * q.x + f.v * q.y);
}

// ------------------------------------------------------------------ segments

bool linetest(const Circle& circle, const Line2D& line) {
  if (!valid(circle) || !valid(line)) return false;
  const vec2 ab = line.end - line.start;
  const vec2 d = circle.center - line.start;
  const float dd = dot(ab, ab);
  const float t = dd > 0.0f ? clamp(dot(d, ab) / dd, 0.0f, 1.0f) : 0.0f;
  const vec2 off = d - ab * t;
  return dot(off, off) <= circle.radius * circle.radius;
}

bool linetest(const Rectangle2D& rectangle, const Line2D& line) {
  if (!valid(rectangle) || !valid(line)) return false;
  return segment_box(line.start, line.end, rectangle.origin, rectangle.origin + rectangle.size, center_of(rectangle),
                     half_of(rectangle));
}

bool linetest(const OrientedRectangle& rectangle, const Line2D& line) {
  if (!valid(rectangle) || !valid(line)) return false;
  const Frame f = frame_of(rectangle);
  const vec2 e = rectangle.half_extents;
  return segment_box(to_local(rectangle, f, line.start), to_local(rectangle, f, line.end), -e, e, vec2{}, e);
}

bool linetest(const BoundingShape& shape, const Line2D& line) {
  for (const Circle& c : shape.circles)
    if (linetest(c, line)) return true;
  for (const Rectangle2D& r : shape.rectangles)
    if (linetest(r, line)) return true;
  return false;
}

// ------------------------------------------------------------------ pairs

bool overlaps(const Circle& a, const Circle& b) {
  if (!valid(a) || !valid(b)) return false;
  const vec2 d = b.center - a.center;
  const float r = a.radius + b.radius;
  return dot(d, d) <= r * r;
}

bool overlaps(const Circle& a, const Rectangle2D& b) {
  if (!valid(a) || !valid(b)) return false;
  return circle_box(a.center, a.radius, b.origin, b.origin + b.size);
}
bool overlaps(const Rectangle2D& a, const Circle& b) { return overlaps(b, a); }

bool overlaps(const Circle& a, const OrientedRectangle& b) {
  if (!valid(a) || !valid(b)) return false;
  const vec2 e = b.half_extents;
  return circle_box(to_local(b, frame_of(b), a.center), a.radius, -e, e);
}
bool overlaps(const OrientedRectangle& a, const Circle& b) { return overlaps(b, a); }

bool overlaps(const Rectangle2D& a, const Rectangle2D& b) {
  if (!valid(a) || !valid(b)) return false;
  const vec2 alo = a.origin, ahi = a.origin + a.size, blo = b.origin, bhi = b.origin + b.size;
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y;
}

bool overlaps(const Rectangle2D& a, const OrientedRectangle& b) {
  if (!valid(a) || !valid(b)) return false;
  const Frame f = frame_of(b);
  const vec2 ha = half_of(a), hb = b.half_extents;
  // d = rectangle center - oriented center, as contains(b, point) computes point - center,
  // so a zero-size rectangle's test on b's axes is exactly that containment test.
  const vec2 d = center_of(a) - b.center;
  if (separated_on(d, f.u, hb.x, kAxisX, kAxisY, ha)) return false;
  if (separated_on(d, f.v, hb.y, kAxisX, kAxisY, ha)) return false;
  if (separated_on(d, kAxisX, ha.x, f.u, f.v, hb)) return false;
  if (separated_on(d, kAxisY, ha.y, f.u, f.v, hb)) return false;
  return true;
}
bool overlaps(const OrientedRectangle& a, const Rectangle2D& b) { return overlaps(b, a); }

bool overlaps(const OrientedRectangle& a, const OrientedRectangle& b) {
  if (!valid(a) || !valid(b)) return false;
  const Frame fa = frame_of(a), fb = frame_of(b);
  const vec2 ea = a.half_extents, eb = b.half_extents;
  const vec2 d = b.center - a.center;
  if (separated_on(d, fa.u, ea.x, fb.u, fb.v, eb)) return false;
  if (separated_on(d, fa.v, ea.y, fb.u, fb.v, eb)) return false;
  if (separated_on(d, fb.u, eb.x, fa.u, fa.v, ea)) return false;
  if (separated_on(d, fb.v, eb.y, fa.u, fa.v, ea)) return false;
  return true;
}

// ------------------------------------------------------------------ bounding shapes

namespace {
template <class S>
bool any_part_overlaps(const BoundingShape& a, const S& b) {
  for (const Circle& c : a.circles)
    if (overlaps(c, b)) return true;
  for (const Rectangle2D& r : a.rectangles)
    if (overlaps(r, b)) return true;
  return false;
}
}  // namespace

bool overlaps(const BoundingShape& a, const Circle& b) { return any_part_overlaps(a, b); }
bool overlaps(const Circle& a, const BoundingShape& b) { return any_part_overlaps(b, a); }
bool overlaps(const BoundingShape& a, const Rectangle2D& b) { return any_part_overlaps(a, b); }
bool overlaps(const Rectangle2D& a, const BoundingShape& b) { return any_part_overlaps(b, a); }
bool overlaps(const BoundingShape& a, const OrientedRectangle& b) { return any_part_overlaps(a, b); }
bool overlaps(const OrientedRectangle& a, const BoundingShape& b) { return any_part_overlaps(b, a); }
bool overlaps(const BoundingShape& a, const BoundingShape& b) {
  for (const Circle& c : b.circles)
    if (any_part_overlaps(a, c)) return true;
  for (const Rectangle2D& r : b.rectangles)
    if (any_part_overlaps(a, r)) return true;
  return false;
}

// ------------------------------------------------------------------ containing shapes

Rectangle2D containing_rectangle(std::span<const vec2> points) {
  if (points.empty()) return {{0.0f, 0.0f}, {0.0f, 0.0f}};
  vec2 lo = points[0], hi = points[0];
  for (const vec2& p : points) {
    if (!finite(p)) return {{kNaN, kNaN}, {kNaN, kNaN}};
    lo = min(lo, p), hi = max(hi, p);
  }
  return rectangle_from_min_max(lo, hi);
}

namespace {

/// A circle during Welzl's algorithm, in coordinates relative to a reference point.
struct WCircle {
  vec2 c;
  float r;
};

/// The circle with segment a-b as its diameter; its radius covers both ends as rounded.
WCircle circle_of(const vec2& a, const vec2& b) {
  const vec2 c = (a + b) * 0.5f;
  return {c, max(robust_length(a - c), robust_length(b - c))};
}

/// The circle through a, b and c. When the three are collinear to within about a
/// millionth of a radian (only rounding brings Welzl's algorithm here: three exactly
/// collinear points never all lie on a circle) the circumcenter is meaningless and the
/// circle on the farthest pair, which then contains the third point, is taken instead.
WCircle circle_of(const vec2& a, const vec2& b, const vec2& c) {
  const vec2 ab = b - a, ac = c - a;
  const float cr = cross(ab, ac);
  const float lab = robust_length(ab), lac = robust_length(ac);
  if (!(std::abs(cr) > 0x1p-20f * (lab * lac))) {
    const float lbc = robust_length(c - b);
    if (lab >= lac && lab >= lbc) return circle_of(a, b);
    if (lac >= lbc) return circle_of(a, c);
    return circle_of(b, c);
  }
  const float ab2 = dot(ab, ab), ac2 = dot(ac, ac);
  const float den = 2.0f * cr;
  const vec2 u{(ac.y * ab2 - ab.y * ac2) / den, (ab.x * ac2 - ac.x * ab2) / den};
  const vec2 center = a + u;
  const float r = max(max(robust_length(a - center), robust_length(b - center)), robust_length(c - center));
  return {center, r};
}

/// splitmix64: the fixed pseudo-random sequence behind the canonical permutation.
uint64_t splitmix64(uint64_t& state) {
  state += 0x9E3779B97F4A7C15ull;
  uint64_t z = state;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

Circle containing_circle(std::span<const vec2> points) {
  if (points.empty()) return {{0.0f, 0.0f}, 0.0f};
  for (const vec2& p : points)
    if (!finite(p)) return {{kNaN, kNaN}, kNaN};

  // Canonical order: -0 made +0 (so equal points have equal bits), sorted, duplicates
  // dropped, then a fixed permutation. The result depends on the set of points only.
  std::vector<vec2> q(points.begin(), points.end());
  for (vec2& p : q) p = {p.x + 0.0f, p.y + 0.0f};
  std::sort(q.begin(), q.end(), [](const vec2& a, const vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  q.erase(std::unique(q.begin(), q.end()), q.end());
  uint64_t state = 0x67726f2d32642d77ull;  // any fixed seed
  for (std::size_t i = q.size() - 1; i > 0; --i) std::swap(q[i], q[splitmix64(state) % (i + 1)]);

  // Work relative to the bounding box's center: the algorithm then sees coordinates of
  // the set's own size, and far from the origin keeps the precision of its extent.
  vec2 lo = q[0], hi = q[0];
  for (const vec2& p : q) lo = min(lo, p), hi = max(hi, p);
  const vec2 ref = lo + (hi - lo) * 0.5f;
  float extent = 0.0f;
  for (vec2& p : q) {
    p = p - ref;
    extent = max(extent, max(std::abs(p.x), std::abs(p.y)));
  }
  // A point counts as inside a candidate circle up to 2^-22 of the extent (a few ulps), so
  // that rounding alone (a point on the rim computed a hair outside) does not restart the
  // loops; the final radius covers every point exactly anyway.
  const float slack = 0x1p-22f * extent;
  const auto inside = [slack](const WCircle& c, const vec2& p) {
    const vec2 d = p - c.c;
    const float r = c.r + slack;
    return dot(d, d) <= r * r;
  };

  WCircle c{q[0], 0.0f};
  for (std::size_t i = 1; i < q.size(); ++i) {
    if (inside(c, q[i])) continue;
    c = {q[i], 0.0f};
    for (std::size_t j = 0; j < i; ++j) {
      if (inside(c, q[j])) continue;
      c = circle_of(q[i], q[j]);
      for (std::size_t k = 0; k < j; ++k)
        if (!inside(c, q[k])) c = circle_of(q[i], q[j], q[k]);
    }
  }

  // Back to world coordinates; the radius is then the largest distance to an input point,
  // measured exactly as contains() does and raised until it covers the rounding of r * r.
  const vec2 center = ref + c.c;
  float r2 = 0.0f;
  for (const vec2& p : points) {
    const vec2 d = p - center;
    r2 = max(r2, dot(d, d));
  }
  float r = std::sqrt(r2);
  while (r * r < r2) r = std::nextafter(r, kInf);
  return {center, r};
}

}  // namespace gyro
