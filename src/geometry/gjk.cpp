// Convex shapes and GJK: support functions, the shape builders, the distance subalgorithm
// and the three public queries (intersect, distance, penetration; EPA lives in epa.cpp).
//
// GJK (Gilbert, Johnson, Keerthi 1988) in van den Bergen's form: v is the point of the
// current simplex closest to the origin, w = support(-v) the next vertex; the distance lies
// between dot(v, w) / |v| and |v|, and the loop stops when the two meet, when w repeats,
// or when |v| stops decreasing (rounding has run out of progress: the previous simplex is
// kept, so a stall never makes the answer worse). The closest point of a simplex is found
// with the signed-volume subalgorithm of Montanari, Petrinic and Barbieri (2017): signed
// volumes / areas of the projection with the largest extent decide which face, edge or
// vertex holds the closest point, so nearly degenerate simplices (flat tetrahedra, thin
// triangles, the 2-point exits that break Johnson's determinants) still give a point.
//
// Determinism: + - * / sqrt and comparisons only, in a fixed order; ties go to the lowest
// index; no heap.
#include "core/error.hpp"
#include "core/validate.hpp"
#include "geometry/convex_support.hpp"

namespace gyro {
namespace detail {
namespace {

inline float absf(float x) { return x < 0.0f ? -x : x; }
inline bool same_sign(float a, float b) { return (a > 0.0f && b > 0.0f) || (a < 0.0f && b < 0.0f); }

// ---- the signed-volume subalgorithm (closest point of a simplex to the origin) ----

struct Sub {
  int idx[4];
  float lambda[4];
  int n = 0;
  vec3 v;
  float vv = 0.0f;
};

Sub vertex(const vec3* s, int i) {
  Sub r;
  r.n = 1, r.idx[0] = i, r.lambda[0] = 1.0f, r.v = s[i], r.vv = dot(s[i], s[i]);
  return r;
}

// Segment s[i0] s[i1].
Sub s1d(const vec3* s, int i0, int i1) {
  const vec3 t = s[i1] - s[i0];
  const float a0 = dot(s[i0], t), a1 = dot(s[i1], t);
  // The origin projects before s[i0] (or the segment is a point), or beyond s[i1].
  if (!(a0 < 0.0f)) return vertex(s, i0);
  if (!(a1 > 0.0f)) return vertex(s, i1);
  const float den = a1 - a0;  // = |t|^2, but consistent with a0, a1 so the weights sum to 1
  Sub r;
  r.n = 2, r.idx[0] = i0, r.idx[1] = i1;
  r.lambda[0] = a1 / den, r.lambda[1] = -a0 / den;
  r.v = s[i0] * r.lambda[0] + s[i1] * r.lambda[1];
  r.vv = dot(r.v, r.v);
  return r;
}

inline void keep_closer(Sub& best, const Sub& c) {
  if (best.n == 0 || c.vv < best.vv) best = c;
}

// Triangle s[i0] s[i1] s[i2].
Sub s2d(const vec3* s, int i0, int i1, int i2) {
  const vec3 n = cross(s[i1] - s[i0], s[i2] - s[i0]);
  const float nn = dot(n, n);
  const int id[3] = {i0, i1, i2};
  float c[3] = {0.0f, 0.0f, 0.0f}, total = 0.0f;
  if (nn > 0.0f) {
    // Project on the coordinate plane where the triangle's shadow is largest; there the
    // signed areas of (origin's projection, edge) are best conditioned.
    const float ax = absf(n.x), ay = absf(n.y), az = absf(n.z);
    const int k = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
    const int u = (k + 1) % 3, w = (k + 2) % 3;
    const vec3 p = n * (dot(n, s[i0]) / nn);  // origin projected on the plane
    total = n[k];
    for (int j = 0; j < 3; ++j) {
      const vec3& b = s[id[(j + 1) % 3]];
      const vec3& e = s[id[(j + 2) % 3]];
      // Twice the signed area of (p, b, e) in the (u, w) plane: p takes vertex j's place.
      c[j] = (b[u] - p[u]) * (e[w] - p[w]) - (b[w] - p[w]) * (e[u] - p[u]);
    }
    if (same_sign(c[0], total) && same_sign(c[1], total) && same_sign(c[2], total)) {
      const float sum = (c[0] + c[1]) + c[2];
      Sub r;
      r.n = 3;
      for (int j = 0; j < 3; ++j) r.idx[j] = id[j], r.lambda[j] = c[j] / sum;
      r.v = p;
      r.vv = dot(p, p);
      return r;
    }
  }
  // Outside an edge (or a degenerate triangle): the closest point is on an edge facing the
  // origin. Edge j is the one opposite vertex j.
  Sub best;
  for (int j = 0; j < 3; ++j)
    if (!same_sign(c[j], total)) keep_closer(best, s1d(s, id[(j + 1) % 3], id[(j + 2) % 3]));
  return best;
}

inline float triple(const vec3& a, const vec3& b, const vec3& c) { return dot(a, cross(b, c)); }

// Tetrahedron s[0..3]: n == 4 in the result means the origin is inside (v = 0).
Sub s3d(const vec3* s) {
  // Six times the signed volumes with the origin in place of vertex j; they sum to the
  // volume of the tetrahedron.
  const float c[4] = {triple(s[1], s[2], s[3]), -triple(s[0], s[2], s[3]), triple(s[0], s[1], s[3]),
                      -triple(s[0], s[1], s[2])};
  const float total = ((c[0] + c[1]) + c[2]) + c[3];
  if (same_sign(c[0], total) && same_sign(c[1], total) && same_sign(c[2], total) && same_sign(c[3], total)) {
    Sub r;
    r.n = 4;
    for (int j = 0; j < 4; ++j) r.idx[j] = j, r.lambda[j] = c[j] / total;
    r.v = {};
    r.vv = 0.0f;
    return r;
  }
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  Sub best;
  for (int j = 0; j < 4; ++j)
    if (!same_sign(c[j], total)) keep_closer(best, s2d(s, kFace[j][0], kFace[j][1], kFace[j][2]));
  return best;
}

Sub closest(const vec3* s, int n) {
  switch (n) {
    case 1: return vertex(s, 0);
    case 2: return s1d(s, 0, 1);
    case 3: return s2d(s, 0, 1, 2);
    default: return s3d(s);
  }
}

// ---- the GJK loop ----

struct GjkOut {
  Simplex simplex;
  vec3 v;               // closest point of the simplex (A's frame)
  float dist = 0.0f;    // |v|
  bool enclosed = false;  // the origin is inside or on the simplex
  bool full = false;      // ... and the simplex is a tetrahedron with the origin strictly inside
  bool early = false;     // boolean exit: separated by more than the threshold
  bool limit = false;     // iteration limit
  uint32_t iterations = 0;
};

// sep_threshold: in boolean mode, stop as soon as the lower bound on the distance exceeds it.
GjkOut gjk(const PairFrame& pair, bool boolean, float sep_threshold, uint32_t max_iterations) {
  GjkOut o;
  Simplex& sx = o.simplex;
  // Start towards B: A - B's centre is near -pos_b, so search along +pos_b first.
  vec3 d0 = pair.pos_b;
  if (!(dot(d0, d0) > 0.0f)) d0 = {1.0f, 0.0f, 0.0f};
  sx.p[0] = pair.support(d0);
  sx.lambda[0] = 1.0f;
  sx.n = 1;
  vec3 v = sx.p[0].w;
  float vv = dot(v, v);
  // A relative stop: the distance is known to 1e-6 of itself, or to about 8 float ulps of
  // the pair's size when the shapes nearly touch (rounding allows no better).
  const float abs_tol = 1e-6f * pair.scale;
  uint32_t it = 0;
  for (;; ++it) {
    if (vv == 0.0f) {
      o.enclosed = true;
      break;
    }
    if (it >= max_iterations) {
      o.limit = true;
      break;
    }
    const SupportPoint sp = pair.support(-v);
    const float vw = dot(v, sp.w);
    // Squared forms of "vw / |v| > threshold" and "gap <= abs_tol * |v|": no sqrt per step.
    if (boolean && vw > 0.0f && vw * vw > sep_threshold * sep_threshold * vv) {
      o.early = true;
      break;
    }
    const float gap = vv - vw;  // (upper - lower bound of the distance) * |v|
    if (gap <= 1e-6f * vv || gap * gap <= abs_tol * abs_tol * vv) break;
    bool repeat = false;
    for (int i = 0; i < sx.n; ++i) repeat = repeat || (sx.p[i].w == sp.w);
    if (repeat) break;

    vec3 pts[4];
    SupportPoint all[4];
    for (int i = 0; i < sx.n; ++i) all[i] = sx.p[i], pts[i] = sx.p[i].w;
    all[sx.n] = sp, pts[sx.n] = sp.w;
    const Sub r = closest(pts, sx.n + 1);
    if (r.n == 0) break;  // cannot happen with finite input; keep the last simplex
    if (r.n == 4) {
      for (int i = 0; i < 4; ++i) sx.p[i] = all[i], sx.lambda[i] = r.lambda[i];
      sx.n = 4;
      v = {};
      vv = 0.0f;
      o.enclosed = o.full = true;
      ++it;
      break;
    }
    if (!(r.vv < vv)) break;  // no progress: rounding floor reached, keep the previous simplex
    Simplex next;
    for (int i = 0; i < r.n; ++i) next.p[i] = all[r.idx[i]], next.lambda[i] = r.lambda[i];
    next.n = r.n;
    sx = next;
    v = r.v;
    vv = r.vv;
  }
  o.v = v;
  o.dist = std::sqrt(vv);
  o.iterations = it;
  return o;
}

// ---- frames, validation, results ----

float bound_radius(const ConvexShape& s) {
  switch (s.type) {
    case ConvexType::sphere: return s.radius;
    case ConvexType::box: return length(s.half_extents);
    case ConvexType::capsule: return s.half_height + s.radius;
    case ConvexType::cylinder: return s.half_height + s.radius;
    case ConvexType::triangle:
      return std::sqrt(max(max(dot(s.v[0], s.v[0]), dot(s.v[1], s.v[1])), dot(s.v[2], s.v[2])));
    case ConvexType::points: {
      if (!s.points || s.count == 0) return -1.0f;
      float m = 0.0f, bad = 0.0f;
      for (uint32_t i = 0; i < s.count; ++i) {
        const float q = dot(s.points[i], s.points[i]);
        m = q > m ? q : m;
        bad = bad + (q - q);  // NaN if any coordinate is NaN or infinite
      }
      return std::sqrt(m) + bad;
    }
  }
  return -1.0f;
}

bool sizes_ok(const ConvexShape& s) {
  return s.radius >= 0.0f && s.half_height >= 0.0f && s.half_extents.x >= 0.0f && s.half_extents.y >= 0.0f &&
         s.half_extents.z >= 0.0f;
}

bool finite_mat(const mat3& m) { return is_finite(row(m, 0)) && is_finite(row(m, 1)) && is_finite(row(m, 2)); }

// Builds B-in-A's frame; false if something is not finite or out of range.
bool make_frame(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                PairFrame& f) {
  if (!finite_mat(pa.rotation) || !finite_mat(pb.rotation) || !is_finite(pa.position) || !is_finite(pb.position))
    return false;
  if (!sizes_ok(a) || !sizes_ok(b)) return false;
  const float ra = bound_radius(a), rb = bound_radius(b);
  if (!(ra >= 0.0f) || !(rb >= 0.0f) || !is_finite(ra) || !is_finite(rb)) return false;
  f.a = &a, f.b = &b;
  // x_A = (x_world - pa) * Ra^T; x_world = x_B * Rb + pb.
  const mat3 ra_t = transpose(pa.rotation);
  f.rot_b = pb.rotation * ra_t;
  f.pos_b = (pb.position - pa.position) * ra_t;
  f.core = true;
  const float s = (ra + rb) + length(f.pos_b);
  if (!is_finite(f.rot_b.m[0][0] + f.pos_b.x + s)) return false;
  f.scale = s > 1e-30f ? s : 1e-30f;
  return true;
}

ConvexResult invalid() {
  fail(Status::non_finite, "convex query: a shape or pose is not finite, or a size is negative");
  ConvexResult r;
  r.status = ConvexStatus::invalid_input;
  return r;
}

// A's frame to the world.
vec3 to_world_point(const ConvexPose& pa, const vec3& p) { return p * pa.rotation + pa.position; }
vec3 to_world_dir(const ConvexPose& pa, const vec3& d) { return d * pa.rotation; }

void witnesses(const Simplex& sx, vec3& pa, vec3& pb) {
  pa = {}, pb = {};
  for (int i = 0; i < sx.n; ++i) pa += sx.p[i].a * sx.lambda[i], pb += sx.p[i].b * sx.lambda[i];
}

// Final result from A-frame quantities; guarantees finite output.
ConvexResult finish(const ConvexPose& pa, ConvexStatus st, float distance, const vec3& n, const vec3& wa,
                    const vec3& wb, uint32_t iterations) {
  ConvexResult r;
  r.status = st;
  r.distance = distance;
  r.normal = to_world_dir(pa, n);
  r.point_a = to_world_point(pa, wa);
  r.point_b = to_world_point(pa, wb);
  r.iterations = iterations;
  if (!is_finite(r.normal) || !is_finite(r.point_a) || !is_finite(r.point_b) || !detail::is_finite(distance))
    return invalid();
  return r;
}

enum class Mode { intersect, distance, penetration };

ConvexResult query(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                   const ConvexQueryOptions& opt, Mode mode) {
  PairFrame f;
  if (!make_frame(a, pa, b, pb, f)) return invalid();
  const float margins = margin_of(a) + margin_of(b);
  const float tol = opt.touch_tolerance * f.scale;
  const GjkOut g = gjk(f, mode == Mode::intersect, margins + tol, opt.max_gjk_iterations);
  vec3 wa, wb;
  witnesses(g.simplex, wa, wb);
  if (!g.enclosed) {
    // Cores apart: the gap is |v| minus the margins, along v.
    const vec3 n = normalized(-g.v);
    const vec3 sa = wa + n * margin_of(a), sb = wb - n * margin_of(b);
    const float dist = g.dist - margins;
    ConvexStatus st = dist > tol ? ConvexStatus::separated
                                 : (dist >= -tol ? ConvexStatus::touching : ConvexStatus::intersecting);
    if (g.limit) st = ConvexStatus::iteration_limit;
    if (g.early) st = ConvexStatus::separated;
    // Intersect and distance report 0 for intersecting pairs; penetration the depth, which
    // for cores apart by less than the margins is exact from the core distance.
    const float out = (st == ConvexStatus::intersecting && mode != Mode::penetration) ? 0.0f : dist;
    return finish(pa, st, out, n, sa, sb, g.iterations);
  }
  // The cores overlap. Intersect and distance only need to know whether by more than the
  // tolerance: a full tetrahedron around the origin, or margins, say so; an origin on a
  // lower simplex (symmetric shapes, touching faces) is settled by EPA.
  if (mode != Mode::penetration && (g.full || margins > tol)) {
    return finish(pa, ConvexStatus::intersecting, 0.0f, vec3{}, wa, wb, g.iterations);
  }
  const EpaOutcome e = epa(f, g.simplex, opt.max_epa_iterations);
  const float depth = e.depth + margins;
  const vec3 sa = e.point_a + e.normal * margin_of(a), sb = e.point_b - e.normal * margin_of(b);
  ConvexStatus st = depth <= tol ? ConvexStatus::touching : ConvexStatus::intersecting;
  if (!e.converged) st = ConvexStatus::iteration_limit;
  const float out = mode == Mode::penetration || st != ConvexStatus::intersecting ? -depth : 0.0f;
  return finish(pa, st, out, e.normal, sa, sb, g.iterations + e.iterations);
}

}  // namespace
}  // namespace detail

// ---- public: builders ----

namespace {
bool finite1(float x) { return detail::is_finite(x); }
Status bad_size(const char* what, float v) {
  if (!finite1(v)) return detail::fail(Status::non_finite, "%s is not finite", what);
  return detail::fail(Status::invalid_argument, "%s = %g is negative", what, double(v));
}
}  // namespace

Status make_sphere(float radius, ConvexShape& out) {
  if (!(radius >= 0.0f) || !finite1(radius)) return bad_size("sphere radius", radius);
  out = ConvexShape{};
  out.type = ConvexType::sphere, out.radius = radius;
  return Status::ok;
}

Status make_box(const vec3& h, ConvexShape& out) {
  if (!is_finite(h)) return detail::fail(Status::non_finite, "box half extents are not finite");
  if (h.x < 0.0f || h.y < 0.0f || h.z < 0.0f) return detail::fail(Status::invalid_argument, "box half extent is negative");
  out = ConvexShape{};
  out.type = ConvexType::box, out.half_extents = h;
  return Status::ok;
}

Status make_capsule(float radius, float half_height, ConvexShape& out) {
  if (!(radius >= 0.0f) || !finite1(radius)) return bad_size("capsule radius", radius);
  if (!(half_height >= 0.0f) || !finite1(half_height)) return bad_size("capsule half height", half_height);
  out = ConvexShape{};
  out.type = ConvexType::capsule, out.radius = radius, out.half_height = half_height;
  return Status::ok;
}

Status make_cylinder(float radius, float half_height, ConvexShape& out) {
  if (!(radius >= 0.0f) || !finite1(radius)) return bad_size("cylinder radius", radius);
  if (!(half_height >= 0.0f) || !finite1(half_height)) return bad_size("cylinder half height", half_height);
  out = ConvexShape{};
  out.type = ConvexType::cylinder, out.radius = radius, out.half_height = half_height;
  return Status::ok;
}

Status make_triangle(const vec3& a, const vec3& b, const vec3& c, ConvexShape& out) {
  if (!is_finite(a) || !is_finite(b) || !is_finite(c)) return detail::fail(Status::non_finite, "triangle corner is not finite");
  out = ConvexShape{};
  out.type = ConvexType::triangle, out.v[0] = a, out.v[1] = b, out.v[2] = c;
  return Status::ok;
}

Status make_convex_points(const vec3* points, std::size_t count, ConvexShape& out) {
  if (!points && count > 0) return detail::fail(Status::null_argument, "points is null");
  if (count == 0 || count > 0xffffffffu) return detail::fail(Status::invalid_count, "point count %zu: need 1 to 2^32-1", count);
  for (std::size_t i = 0; i < count; ++i)
    if (!is_finite(points[i])) return detail::fail(Status::non_finite, "points[%zu] is not finite", i);
  out = ConvexShape{};
  out.type = ConvexType::points, out.points = points, out.count = static_cast<uint32_t>(count);
  return Status::ok;
}

// ---- public: supports and queries ----

vec3 support(const ConvexShape& shape, const vec3& dir) { return detail::local_support(shape, dir, false); }

vec3 support(const ConvexShape& shape, const ConvexPose& pose, const vec3& dir) {
  const mat3& r = pose.rotation;
  const vec3 local{dot(dir, row(r, 0)), dot(dir, row(r, 1)), dot(dir, row(r, 2))};
  return detail::local_support(shape, local, false) * r + pose.position;
}

vec3 support_difference(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                        const vec3& dir) {
  return support(a, pa, dir) - support(b, pb, -dir);
}

ConvexResult convex_intersect(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                              const ConvexQueryOptions& o) {
  return detail::query(a, pa, b, pb, o, detail::Mode::intersect);
}

ConvexResult convex_distance(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                             const ConvexQueryOptions& o) {
  return detail::query(a, pa, b, pb, o, detail::Mode::distance);
}

ConvexResult convex_penetration(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b,
                                const ConvexPose& pb, const ConvexQueryOptions& o) {
  return detail::query(a, pa, b, pb, o, detail::Mode::penetration);
}

}  // namespace gyro
