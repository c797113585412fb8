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
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/box_face_lanes.hpp"
#include "geometry/convex_support.hpp"
#include "geometry/gjk_batch.hpp"
#include "gyro/runtime.hpp"

#include <bit>
#include <memory>
#include <new>

namespace gyro {
namespace detail {
namespace {

inline float absf(float x) { return x < 0.0f ? -x : x; }
inline bool same_sign(float a, float b) { return (a > 0.0f && b > 0.0f) || (a < 0.0f && b < 0.0f); }

// ---- the signed-volume subalgorithm (closest point of a simplex to the origin) ----
//
// The vertices are addressed by index into the caller's array; the result lists the indices
// it keeps, ascending, so the caller compacts its simplex in place.

// The simplex as the subalgorithm sees it: vertex i is *p[i] (the points stay in fixed
// slots; only this order changes).
struct SimplexView {
  const vec3* p[4];
  const vec3& operator[](int i) const { return *p[i]; }
};

struct Sub {
  int idx[4];
  float lambda[4];
  int n = 0;
  vec3 v;
  float vv = 0.0f;
};

inline void vertex(const SimplexView& s, int i, Sub& r) {
  r.n = 1, r.idx[0] = i, r.lambda[0] = 1.0f, r.v = s[i], r.vv = dot(s[i], s[i]);
}

// Segment s[i0] s[i1].
inline void s1d(const SimplexView& s, int i0, int i1, Sub& r) {
  const vec3 t = s[i1] - s[i0];
  const float a0 = dot(s[i0], t), a1 = dot(s[i1], t);
  // The origin projects before s[i0] (or the segment is a point), or beyond s[i1].
  if (!(a0 < 0.0f)) return vertex(s, i0, r);
  if (!(a1 > 0.0f)) return vertex(s, i1, r);
  const float den = a1 - a0;  // = |t|^2, but consistent with a0, a1 so the weights sum to 1
  r.n = 2, r.idx[0] = i0, r.idx[1] = i1;
  r.lambda[0] = a1 / den, r.lambda[1] = -a0 / den;
  r.v = s[i0] * r.lambda[0] + s[i1] * r.lambda[1];
  r.vv = dot(r.v, r.v);
}

// Edge (i0, i1) as a candidate: kept when nothing is kept yet or it is strictly closer.
inline void edge_candidate(const SimplexView& s, int i0, int i1, Sub& best) {
  if (best.n == 0) return s1d(s, i0, i1, best);
  Sub c;
  s1d(s, i0, i1, c);
  if (c.vv < best.vv) best = c;
}

template <int I> inline float comp(const vec3& v) {
  if constexpr (I == 0) return v.x;
  else if constexpr (I == 1) return v.y;
  else return v.z;
}

// The triangle's signed areas on the coordinate plane normal to axis K (K: the largest
// component of the normal n); false when the origin's projection is outside an edge.
template <int K>
inline bool s2d_inside(const SimplexView& s, const int id[3], const vec3& n, float nn, float c[3], float& total, Sub& r) {
  constexpr int u = (K + 1) % 3, w = (K + 2) % 3;
  const vec3 p = n * (dot(n, s[id[0]]) / nn);  // origin projected on the plane
  total = comp<K>(n);
  const float pu = comp<u>(p), pw = comp<w>(p);
  for (int j = 0; j < 3; ++j) {
    const vec3& b = s[id[j == 2 ? 0 : j + 1]];
    const vec3& e = s[id[j == 0 ? 2 : j - 1]];
    // Twice the signed area of (p, b, e) in the (u, w) plane: p takes vertex j's place.
    c[j] = (comp<u>(b) - pu) * (comp<w>(e) - pw) - (comp<w>(b) - pw) * (comp<u>(e) - pu);
  }
  if (same_sign(c[0], total) && same_sign(c[1], total) && same_sign(c[2], total)) {
    const float sum = (c[0] + c[1]) + c[2];
    r.n = 3;
    for (int j = 0; j < 3; ++j) r.idx[j] = id[j], r.lambda[j] = c[j] / sum;
    r.v = p;
    r.vv = dot(p, p);
    return true;
  }
  return false;
}

// Triangle s[i0] s[i1] s[i2].
inline void s2d(const SimplexView& s, int i0, int i1, int i2, Sub& r) {
  const vec3 n = cross(s[i1] - s[i0], s[i2] - s[i0]);
  const float nn = dot(n, n);
  const int id[3] = {i0, i1, i2};
  float c[3] = {0.0f, 0.0f, 0.0f}, total = 0.0f;
  if (nn > 0.0f) {
    // Project on the coordinate plane where the triangle's shadow is largest; there the
    // signed areas of (origin's projection, edge) are best conditioned.
    const float ax = absf(n.x), ay = absf(n.y), az = absf(n.z);
    bool inside;
    if (ax >= ay && ax >= az) inside = s2d_inside<0>(s, id, n, nn, c, total, r);
    else if (ay >= az) inside = s2d_inside<1>(s, id, n, nn, c, total, r);
    else inside = s2d_inside<2>(s, id, n, nn, c, total, r);
    if (inside) return;
  }
  // Outside an edge (or a degenerate triangle): the closest point is on an edge facing the
  // origin. Edge j is the one opposite vertex j; the first facing edge is taken, a later
  // one only when strictly closer.
  r.n = 0;
  if (!same_sign(c[0], total)) edge_candidate(s, i1, i2, r);
  if (!same_sign(c[1], total)) edge_candidate(s, i2, i0, r);
  if (!same_sign(c[2], total)) edge_candidate(s, i0, i1, r);
}

inline void face_candidate(const SimplexView& s, int i0, int i1, int i2, Sub& best) {
  if (best.n == 0) return s2d(s, i0, i1, i2, best);
  Sub c;
  s2d(s, i0, i1, i2, c);
  if (c.vv < best.vv) best = c;
}

inline float triple(const vec3& a, const vec3& b, const vec3& c) { return dot(a, cross(b, c)); }

// Tetrahedron s[0..3]: n == 4 in the result means the origin is inside (v = 0).
inline void s3d(const SimplexView& s, Sub& r) {
  // Six times the signed volumes with the origin in place of vertex j; they sum to the
  // volume of the tetrahedron.
  const float c[4] = {triple(s[1], s[2], s[3]), -triple(s[0], s[2], s[3]), triple(s[0], s[1], s[3]),
                      -triple(s[0], s[1], s[2])};
  const float total = ((c[0] + c[1]) + c[2]) + c[3];
  if (same_sign(c[0], total) && same_sign(c[1], total) && same_sign(c[2], total) && same_sign(c[3], total)) {
    r.n = 4;
    for (int j = 0; j < 4; ++j) r.idx[j] = j, r.lambda[j] = c[j] / total;
    r.v = {};
    r.vv = 0.0f;
    return;
  }
  r.n = 0;
  if (!same_sign(c[0], total)) face_candidate(s, 1, 2, 3, r);
  if (!same_sign(c[1], total)) face_candidate(s, 0, 2, 3, r);
  if (!same_sign(c[2], total)) face_candidate(s, 0, 1, 3, r);
  if (!same_sign(c[3], total)) face_candidate(s, 0, 1, 2, r);
}

// ---- typed core supports: the GJK loop is instantiated per pair of shape types ----

// Support of A's core in A's frame (core: spheres and capsules without their radius).
template <ConvexType T> inline vec3 core_support(const ConvexShape& s, const vec3& d) {
  if constexpr (T == ConvexType::sphere) return vec3{};
  else if constexpr (T == ConvexType::box)
    return {signed_by(s.half_extents.x, d.x), signed_by(s.half_extents.y, d.y), signed_by(s.half_extents.z, d.z)};
  else if constexpr (T == ConvexType::capsule) return vec3{0.0f, d.y >= 0.0f ? s.half_height : -s.half_height, 0.0f};
  else return local_support(s, d, true);
}

// B placed in A's frame, with B's type known. For a box, the rows of rot_b scaled by the
// half extents are formed once: (+-h) * r == +-(h * r) exactly, so lb * rot_b + pos_b
// keeps its bits with three selects and three additions per component.
template <ConvexType T> struct CoreB {
  const PairFrame& f;
  vec3 e[3];
  explicit CoreB(const PairFrame& frame) : f(frame) {
    if constexpr (T == ConvexType::box) {
      const vec3 h = f.b->half_extents;
      for (int c = 0; c < 3; ++c)
        e[0][c] = h.x * f.rot_b.m[0][c], e[1][c] = h.y * f.rot_b.m[1][c], e[2][c] = h.z * f.rot_b.m[2][c];
    }
  }
  // B's support along -d, in A's frame.
  vec3 operator()(const vec3& d) const {
    const mat3& r = f.rot_b;
    if constexpr (T == ConvexType::box) {
      // -dot(d, axis k) >= 0, written as dot(d, axis k) <= 0 (the same for every float, NaN included).
      // The sign as a factor: x * 1 and x * -1 are x and -x exactly.
      const float sx = dot(d, vec3{r.m[0][0], r.m[0][1], r.m[0][2]}) <= 0.0f ? 1.0f : -1.0f;
      const float sy = dot(d, vec3{r.m[1][0], r.m[1][1], r.m[1][2]}) <= 0.0f ? 1.0f : -1.0f;
      const float sz = dot(d, vec3{r.m[2][0], r.m[2][1], r.m[2][2]}) <= 0.0f ? 1.0f : -1.0f;
      return {((e[0].x * sx + e[1].x * sy) + e[2].x * sz) + f.pos_b.x,
              ((e[0].y * sx + e[1].y * sy) + e[2].y * sz) + f.pos_b.y,
              ((e[0].z * sx + e[1].z * sy) + e[2].z * sz) + f.pos_b.z};
    } else {
      const vec3 db{-dot(d, vec3{r.m[0][0], r.m[0][1], r.m[0][2]}), -dot(d, vec3{r.m[1][0], r.m[1][1], r.m[1][2]}),
                    -dot(d, vec3{r.m[2][0], r.m[2][1], r.m[2][2]})};
      return core_support<T>(*f.b, db) * r + f.pos_b;
    }
  }
};

// ---- the GJK loop ----

struct GjkOut {
  // The simplex: points in fixed slots (left uninitialised until written), in the order
  // ord[0 .. n), with their weights.
  union Slots {
    SupportPoint p[4];
    Slots() {}
  } slot;
  int ord[4] = {0, 1, 2, 3};
  float lambda[4] = {1.0f, 0.0f, 0.0f, 0.0f};
  int n = 0;
  vec3 v;               // closest point of the simplex (A's frame)
  float dist = 0.0f;    // |v|
  bool enclosed = false;  // the origin is inside or on the simplex
  bool full = false;      // ... and the simplex is a tetrahedron with the origin strictly inside
  bool early = false;     // boolean exit: separated by more than the threshold
  bool limit = false;     // iteration limit
  uint32_t iterations = 0;

  Simplex simplex() const {
    Simplex sx;
    for (int i = 0; i < n; ++i) sx.p[i] = slot.p[ord[i]], sx.lambda[i] = lambda[i];
    sx.n = n;
    return sx;
  }
};

// sep_threshold: in boolean mode, stop as soon as the lower bound on the distance exceeds it.
// The points live in four fixed slots; the simplex is the slot order ord[0 .. n): a new
// point goes into a free slot and the subalgorithm's result only reorders ord.
template <ConvexType TA, ConvexType TB>
void gjk_typed(const PairFrame& pair, bool boolean, float sep_threshold, uint32_t max_iterations, GjkOut& o) {
  const ConvexShape& sa = *pair.a;
  const CoreB<TB> support_b(pair);
  SupportPoint* const slot = o.slot.p;
  float* const lambda = o.lambda;
  int* const ord = o.ord;
  const float sep_sq = sep_threshold * sep_threshold;
  // Start towards B: A - B's centre is near -pos_b, so search along +pos_b first; a box
  // pair separated along a face normal starts along it and stops there.
  vec3 d0 = pair.pos_b;
  if (!(dot(d0, d0) > 0.0f)) d0 = {1.0f, 0.0f, 0.0f};
  bool face_axis = false;
  if constexpr (TA == ConvexType::box && TB == ConvexType::box) {
    if (boolean) {  // box_face_lanes.hpp, the float instantiation of box_gjk's
      using Lane = GYRO_ARCH_NS::V3<float>;
      const vec3 ha = pair.a->half_extents, hb = pair.b->half_extents;
      const float pos[3] = {pair.pos_b.x, pair.pos_b.y, pair.pos_b.z};
      Lane dir{d0.x, d0.y, d0.z};
      face_axis = GYRO_ARCH_NS::box_face_probe(Lane{ha.x, ha.y, ha.z}, Lane{hb.x, hb.y, hb.z}, pair.rot_b.m, pos, sep_sq, dir);
      d0 = {dir.x, dir.y, dir.z};
    }
  }
  slot[0].a = core_support<TA>(sa, d0);
  slot[0].b = support_b(d0);
  slot[0].w = slot[0].a - slot[0].b;
  int n = 1;
  vec3 v = slot[0].w;
  float vv = dot(v, v);
  // The exit as the loop's early exit leaves it, with this support point as the simplex.
  if (face_axis) {
    o.early = true;
    o.n = 1, o.v = v, o.dist = std::sqrt(vv), o.iterations = 0;
    return;
  }
  // A relative stop: the distance is known to 1e-6 of itself, or to about 8 float ulps of
  // the pair's size when the shapes nearly touch (rounding allows no better).
  const float abs_tol = 1e-6f * pair.scale;
  const float abs_sq = abs_tol * abs_tol;
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
    const vec3 d = -v;
    const vec3 pa = core_support<TA>(sa, d);
    const vec3 pb = support_b(d);
    const vec3 sw = pa - pb;
    const float vw = dot(v, sw);
    // Squared forms of "vw / |v| > threshold" and "gap <= abs_tol * |v|": no sqrt per step.
    if (boolean && vw > 0.0f && vw * vw > sep_sq * vv) {
      o.early = true;
      break;
    }
    const float gap = vv - vw;  // (upper - lower bound of the distance) * |v|
    if (gap <= 1e-6f * vv || gap * gap <= abs_sq * vv) break;
    bool repeat = false;
    for (int i = 0; i < n; ++i) repeat = repeat || (slot[ord[i]].w == sw);
    if (repeat) break;

    // ord[n .. 4) are the free slots; the new point takes ord[n].
    const int fresh = ord[n];
    slot[fresh] = {sw, pa, pb};
    SimplexView view;
    for (int i = 0; i < 4; ++i) view.p[i] = &slot[ord[i]].w;
    Sub r;
    switch (n) {
      case 1: s1d(view, 0, 1, r); break;
      case 2: s2d(view, 0, 1, 2, r); break;
      default: s3d(view, r); break;
    }
    if (r.n == 0) break;  // cannot happen with finite input; keep the last simplex
    if (r.n == 4) {
      for (int i = 0; i < 4; ++i) lambda[i] = r.lambda[i];
      n = 4;
      v = {};
      vv = 0.0f;
      o.enclosed = o.full = true;
      ++it;
      break;
    }
    if (!(r.vv < vv)) break;  // no progress: rounding floor reached, keep the previous simplex
    // The kept vertices in the subalgorithm's order, then the dropped ones (free slots).
    int next[4], used = 0;
    for (int i = 0; i < r.n; ++i) next[i] = ord[r.idx[i]], used |= 1 << r.idx[i], lambda[i] = r.lambda[i];
    int m = r.n;
    for (int i = 0; i < 4; ++i)
      if (!(used >> i & 1)) next[m++] = ord[i];
    for (int i = 0; i < 4; ++i) ord[i] = next[i];
    n = r.n;
    v = r.v;
    vv = r.vv;
  }
  o.n = n;
  o.v = v;
  o.dist = std::sqrt(vv);
  o.iterations = it;
}

template <ConvexType TA>
void gjk_b(const PairFrame& pair, bool boolean, float sep_threshold, uint32_t max_iterations, GjkOut& o) {
  switch (pair.b->type) {
    case ConvexType::sphere: return gjk_typed<TA, ConvexType::sphere>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::box: return gjk_typed<TA, ConvexType::box>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::capsule: return gjk_typed<TA, ConvexType::capsule>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::cylinder: return gjk_typed<TA, ConvexType::cylinder>(pair, boolean, sep_threshold, max_iterations, o);
    default: return gjk_typed<TA, ConvexType::points>(pair, boolean, sep_threshold, max_iterations, o);
  }
}

// The loop for this pair's types (triangles and point clouds share the generic support).
void gjk(const PairFrame& pair, bool boolean, float sep_threshold, uint32_t max_iterations, GjkOut& o) {
  switch (pair.a->type) {
    case ConvexType::sphere: return gjk_b<ConvexType::sphere>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::box: return gjk_b<ConvexType::box>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::capsule: return gjk_b<ConvexType::capsule>(pair, boolean, sep_threshold, max_iterations, o);
    case ConvexType::cylinder: return gjk_b<ConvexType::cylinder>(pair, boolean, sep_threshold, max_iterations, o);
    default: return gjk_b<ConvexType::points>(pair, boolean, sep_threshold, max_iterations, o);
  }
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
  return (s.radius >= 0.0f) & (s.half_height >= 0.0f) & (s.half_extents.x >= 0.0f) & (s.half_extents.y >= 0.0f) &
         (s.half_extents.z >= 0.0f);
}

// x - x is 0 for a finite x and NaN for a NaN or infinite one; sums of these are 0 exactly
// when every value is finite: one branch for many values.
inline float nonfinite_term(float x) { return x - x; }
inline float nonfinite_sum(const vec3& v) { return (nonfinite_term(v.x) + nonfinite_term(v.y)) + nonfinite_term(v.z); }
inline float nonfinite_sum(const mat3& m) {
  return (nonfinite_sum(row(m, 0)) + nonfinite_sum(row(m, 1))) + nonfinite_sum(row(m, 2));
}
inline bool finite_all(float sum) { return sum == 0.0f; }

// Builds B-in-A's frame; false if something is not finite or out of range.
bool make_frame(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                PairFrame& f) {
  if (!finite_all((nonfinite_sum(pa.rotation) + nonfinite_sum(pb.rotation)) +
                  (nonfinite_sum(pa.position) + nonfinite_sum(pb.position))))
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

void witnesses(const GjkOut& g, vec3& pa, vec3& pb) {
  pa = {}, pb = {};
  for (int i = 0; i < g.n; ++i) {
    const SupportPoint& p = g.slot.p[g.ord[i]];
    pa += p.a * g.lambda[i], pb += p.b * g.lambda[i];
  }
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
  if (!finite_all((nonfinite_sum(r.normal) + nonfinite_sum(r.point_a)) +
                  (nonfinite_sum(r.point_b) + nonfinite_term(distance))))
    return invalid();
  return r;
}

enum class Mode { intersect, distance, penetration };

// Whether conclude() runs EPA on this end state.
bool needs_epa(const PairFrame& f, const GjkOut& g, const ConvexQueryOptions& opt, Mode mode) {
  const float margins = margin_of(*f.a) + margin_of(*f.b);
  return g.enclosed && !(mode != Mode::penetration && (g.full || margins > opt.touch_tolerance * f.scale));
}

// conclude()'s end where EPA ran (e is its outcome on g's simplex).
ConvexResult conclude_epa(const ConvexPose& pa, const PairFrame& f, const GjkOut& g, const ConvexQueryOptions& opt,
                          Mode mode, const EpaOutcome& e) {
  const ConvexShape& a = *f.a;
  const ConvexShape& b = *f.b;
  const float margins = margin_of(a) + margin_of(b);
  const float tol = opt.touch_tolerance * f.scale;
  const float depth = e.depth + margins;
  const vec3 sa = e.point_a + e.normal * margin_of(a), sb = e.point_b - e.normal * margin_of(b);
  ConvexStatus st = depth <= tol ? ConvexStatus::touching : ConvexStatus::intersecting;
  if (!e.converged) st = ConvexStatus::iteration_limit;
  const float out = mode == Mode::penetration || st != ConvexStatus::intersecting ? -depth : 0.0f;
  return finish(pa, st, out, e.normal, sa, sb, g.iterations + e.iterations);
}

// The result from GJK's end state (shared by the scalar query and the batch calls, so both
// give the same bits from the same state).
ConvexResult conclude(const ConvexPose& pa, const PairFrame& f, const GjkOut& g, const ConvexQueryOptions& opt,
                      Mode mode) {
  const ConvexShape& a = *f.a;
  const ConvexShape& b = *f.b;
  const float margins = margin_of(a) + margin_of(b);
  const float tol = opt.touch_tolerance * f.scale;
  vec3 wa, wb;
  witnesses(g, wa, wb);
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
  return conclude_epa(pa, f, g, opt, mode, epa(f, g.simplex(), opt.max_epa_iterations));
}

// GJK's boolean exit (the first separating axis ends the loop): the intersect query, and the
// penetration query when the caller has no use for a separated pair's distance.
bool stops_early(Mode mode, const ConvexQueryOptions& opt) {
  return mode == Mode::intersect || (mode == Mode::penetration && !opt.separated_distance);
}

ConvexResult query(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                   const ConvexQueryOptions& opt, Mode mode) {
  PairFrame f;
  if (!make_frame(a, pa, b, pb, f)) return invalid();
  const float margins = margin_of(a) + margin_of(b);
  const float tol = opt.touch_tolerance * f.scale;
  GjkOut g;
  gjk(f, stops_early(mode, opt), margins + tol, opt.max_gjk_iterations, g);
  return conclude(pa, f, g, opt, mode);
}

// convex_intersect's status from GJK's end state for two boxes, without its witnesses (the
// batch checks beforehand that they would be finite).
ConvexStatus box_intersect_status(const PairFrame& f, const GjkOut& g, const ConvexQueryOptions& opt) {
  const float margins = 0.0f;
  const float tol = opt.touch_tolerance * f.scale;
  if (!g.enclosed) {
    if (g.early) return ConvexStatus::separated;
    if (g.limit) return ConvexStatus::iteration_limit;
    const float dist = g.dist - margins;
    return dist > tol ? ConvexStatus::separated : (dist >= -tol ? ConvexStatus::touching : ConvexStatus::intersecting);
  }
  if (g.full || margins > tol) return ConvexStatus::intersecting;
  const EpaOutcome e = epa(f, g.simplex(), opt.max_epa_iterations);
  if (!e.converged) return ConvexStatus::iteration_limit;
  const float depth = e.depth + margins;
  return depth <= tol ? ConvexStatus::touching : ConvexStatus::intersecting;
}

// One pair of a box batch: its shapes and poses, and where the lanes handled it, the frame
// and GJK's end state as the scalar loop leaves them.
struct BoxBatchPair {
  ConvexShape a, b;
  ConvexPose pa, pb;
  bool scalar = false;  // invalid or out of the lanes' range: run the scalar query
  PairFrame f;
  GjkOut g;
};

// Pair i (element k of the block) as the lanes left it.
void load_pair(const ConvexBoxPairs& p, std::size_t i, const BoxGjkBlock& blk, std::size_t k, BoxBatchPair& q) {
  q.a.type = q.b.type = ConvexType::box;
  q.a.half_extents = {p.a_half[0][i], p.a_half[1][i], p.a_half[2][i]};
  q.b.half_extents = {p.b_half[0][i], p.b_half[1][i], p.b_half[2][i]};
  q.pa.position = {p.a_center[0][i], p.a_center[1][i], p.a_center[2][i]};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q.pa.rotation.m[r][c] = p.a_rot[3 * r + c][i];
  q.scalar = blk.code[k] == BoxGjkBlock::kScalar;
  if (q.scalar) {
    q.pb.position = {p.b_center[0][i], p.b_center[1][i], p.b_center[2][i]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) q.pb.rotation.m[r][c] = p.b_rot[3 * r + c][i];
    return;
  }
  PairFrame& f = q.f;
  f.a = &q.a, f.b = &q.b;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f.rot_b.m[r][c] = blk.rot[3 * r + c][k];
  f.pos_b = {blk.pos[0][k], blk.pos[1][k], blk.pos[2][k]};
  f.core = true;
  f.scale = blk.scale[k];
  GjkOut& g = q.g;
  g.n = int(blk.n[k]);
  for (int s = 0; s < g.n; ++s) {
    SupportPoint& sp = g.slot.p[s];
    sp.a = {blk.a[s][0][k], blk.a[s][1][k], blk.a[s][2][k]};
    sp.b = {blk.b[s][0][k], blk.b[s][1][k], blk.b[s][2][k]};
    sp.w = sp.a - sp.b;  // the lanes kept a and b; w = a - b is how the loop formed it
  }
  for (int s = 0; s < 4; ++s) g.ord[s] = s, g.lambda[s] = blk.lambda[s][k];
  g.v = {blk.v[0][k], blk.v[1][k], blk.v[2][k]};
  g.dist = std::sqrt(blk.vv[k]);
  const uint32_t fl = blk.flags[k];
  g.enclosed = (fl & BoxGjkBlock::kEnclosed) != 0, g.full = (fl & BoxGjkBlock::kFull) != 0;
  g.early = (fl & BoxGjkBlock::kEarly) != 0, g.limit = (fl & BoxGjkBlock::kLimit) != 0;
  g.iterations = blk.iterations[k];
}

// Runs the lane GJK over the pairs, block by block, and calls on_block(begin, end, block)
// after each block. verdict_only: the caller needs only the intersect verdict (the lanes
// keep no witnesses and form no results).
// The lanes' state (61 KB, and about 0.4 MB for the pairs gathered for EPA, touched only as
// far as used) is the calling thread's, made once: callers with few pairs per
// call (the C ABI hands over 128 at a time) spent most of their time clearing fresh copies.
// A block leaves it dirty for the next one within a call already; a later call is no different.
struct BoxBatchState {
  BoxGjkBlock block;
  BoxGjkWork work;
  // Pairs that need EPA, gathered over several blocks and run together (epa_boxes): the more
  // pairs it has, the longer its slots stay full.
  static constexpr std::size_t kEpaMax = 4 * BoxGjkBlock::kMax;
  BoxBatchPair epa_pair[kEpaMax];
  const PairFrame* epa_frame[kEpaMax];
  Simplex epa_start[kEpaMax];
  EpaOutcome epa_out[kEpaMax];
  std::size_t epa_index[kEpaMax];
  std::size_t epa_count = 0;

  // Runs EPA on the gathered pairs and writes their results.
  void run_epa(ConvexResult* out, const ConvexQueryOptions& opt, Mode mode) {
    epa_boxes(epa_frame, epa_start, epa_count, opt.max_epa_iterations, epa_out);
    for (std::size_t j = 0; j < epa_count; ++j) {
      const BoxBatchPair& e = epa_pair[j];
      out[epa_index[j]] = conclude_epa(e.pa, e.f, e.g, opt, mode, epa_out[j]);
    }
    epa_count = 0;
  }
};

BoxBatchState& box_batch_state() {
  thread_local std::unique_ptr<BoxBatchState> state;
  if (!state) state = std::make_unique<BoxBatchState>();
  return *state;
}

template <class OnBlock>
void box_batch(const ConvexBoxPairs& p, std::size_t count, const ConvexQueryOptions& opt, Mode mode, bool verdict_only,
               OnBlock&& on_block) {
  BoxBatchState& state = box_batch_state();
  BoxGjkBlock* const block = &state.block;
  BoxGjkWork* const work = &state.work;
  BoxGjkParams prm;
  prm.touch_tolerance = opt.touch_tolerance, prm.max_iterations = opt.max_gjk_iterations;
  prm.boolean = stops_early(mode, opt), prm.verdict_only = verdict_only;
  prm.penetration = mode == Mode::penetration;
  box_gjk_fn* const kernel = GYRO_DISPATCH(box_gjk);
  for (std::size_t base = 0; base < count; base += BoxGjkBlock::kMax) {
    const std::size_t end = count - base < BoxGjkBlock::kMax ? count : base + BoxGjkBlock::kMax;
    kernel(p, base, end, prm, *block, *work);
    on_block(base, end, static_cast<const BoxGjkBlock&>(*block));
  }
}

// The scalar level: one lane computing every branch of the subalgorithm costs more than it
// saves, so there each pair runs the scalar loop (the same bits by construction).
bool lanes_pay() { return simd_level_width(simd_level()) > 1; }

void load_pair_scalar(const ConvexBoxPairs& p, std::size_t i, BoxBatchPair& q) {
  q.a.type = q.b.type = ConvexType::box;
  q.a.half_extents = {p.a_half[0][i], p.a_half[1][i], p.a_half[2][i]};
  q.b.half_extents = {p.b_half[0][i], p.b_half[1][i], p.b_half[2][i]};
  q.pa.position = {p.a_center[0][i], p.a_center[1][i], p.a_center[2][i]};
  q.pb.position = {p.b_center[0][i], p.b_center[1][i], p.b_center[2][i]};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q.pa.rotation.m[r][c] = p.a_rot[3 * r + c][i], q.pb.rotation.m[r][c] = p.b_rot[3 * r + c][i];
}

// convex_intersect's status for a pair at the scalar level: without witnesses where they
// are finite for sure (the lanes' range: rotation entries at most 2, far below overflow).
ConvexStatus box_intersect_scalar(BoxBatchPair& q, const ConvexQueryOptions& opt) {
  PairFrame& f = q.f;
  bool ok = make_frame(q.a, q.pa, q.b, q.pb, f);
  for (int r = 0; r < 3 && ok; ++r)
    for (int c = 0; c < 3; ++c)
      ok = ok && absf(q.pa.rotation.m[r][c]) <= 2.0f && absf(q.pb.rotation.m[r][c]) <= 2.0f;
  const vec3& ca = q.pa.position;
  ok = ok && f.scale * 64.0f + max(max(absf(ca.x), absf(ca.y)), absf(ca.z)) < 1e36f;
  if (!ok) return convex_intersect(q.a, q.pa, q.b, q.pb, opt).status;
  const float tol = opt.touch_tolerance * f.scale;
  GjkOut g;  // fresh: the loop only ever sets its flags
  gjk_typed<ConvexType::box, ConvexType::box>(f, true, 0.0f + tol, opt.max_gjk_iterations, g);
  return box_intersect_status(f, g, opt);
}

// convex_distance or convex_penetration over a box batch. Pairs whose cores ended apart
// come with their result formed in the lanes (conclude's first branch, same operations);
// the others go through conclude (EPA) or the scalar query.
void box_result_batch(const ConvexBoxPairs& p, std::size_t count, ConvexResult* out, const ConvexQueryOptions& opt,
                      Mode mode) {
  if (!lanes_pay()) {
    BoxBatchPair q;
    for (std::size_t i = 0; i < count; ++i) load_pair_scalar(p, i, q), out[i] = query(q.a, q.pa, q.b, q.pb, opt, mode);
    return;
  }
  BoxBatchState& st = box_batch_state();
  st.epa_count = 0;
  box_batch(p, count, opt, mode, false, [&](std::size_t base, std::size_t end, const BoxGjkBlock& blk) {
    for (std::size_t i = base; i < end; ++i) {
      const std::size_t k = i - base;
      if (blk.code[k] == BoxGjkBlock::kDone && blk.done[k] == 1.0f) {
        ConvexResult& r = out[i];
        r.status = ConvexStatus(uint32_t(blk.r_status[k]));
        r.distance = blk.r_distance[k];
        r.normal = {blk.r_normal[0][k], blk.r_normal[1][k], blk.r_normal[2][k]};
        r.point_a = {blk.r_point_a[0][k], blk.r_point_a[1][k], blk.r_point_a[2][k]};
        r.point_b = {blk.r_point_b[0][k], blk.r_point_b[1][k], blk.r_point_b[2][k]};
        r.iterations = blk.iterations[k];
        continue;
      }
      const std::size_t j = st.epa_count;
      BoxBatchPair& e = st.epa_pair[j];
      load_pair(p, i, blk, k, e);
      if (e.scalar) {
        out[i] = query(e.a, e.pa, e.b, e.pb, opt, mode);
      } else if (needs_epa(e.f, e.g, opt, mode)) {
        st.epa_frame[j] = &e.f, st.epa_start[j] = e.g.simplex(), st.epa_index[j] = i, st.epa_count = j + 1;
      } else {
        out[i] = conclude(e.pa, e.f, e.g, opt, mode);
      }
    }
    if (st.epa_count + BoxGjkBlock::kMax > BoxBatchState::kEpaMax) st.run_epa(out, opt, mode);  // room for a block
  });
  st.run_epa(out, opt, mode);
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

namespace gyro {

namespace detail {
namespace {

// convex_intersect_batch's statuses for pairs [0, count) of p, on the calling thread.
void intersect_status_batch(const ConvexBoxPairs& p, std::size_t count, ConvexStatus* out, const ConvexQueryOptions& opt) {
  BoxBatchPair q;
  if (!lanes_pay()) {
    for (std::size_t i = 0; i < count; ++i) load_pair_scalar(p, i, q), out[i] = box_intersect_scalar(q, opt);
    return;
  }
  box_batch(p, count, opt, Mode::intersect, true,
                    [&](std::size_t base, std::size_t end, const BoxGjkBlock& blk) {
    for (std::size_t i = base; i < end; ++i) {
      const std::size_t k = i - base;
      const uint32_t fl = blk.flags[k];
      if (blk.code[k] == BoxGjkBlock::kDone && !(fl & BoxGjkBlock::kEnclosed)) {
        // box_intersect_status's separated branch, without forming the pair (margins are 0).
        if (fl & BoxGjkBlock::kEarly) {
          out[i] = ConvexStatus::separated;
        } else if (fl & BoxGjkBlock::kLimit) {
          out[i] = ConvexStatus::iteration_limit;
        } else {
          const float tol = opt.touch_tolerance * blk.scale[k];
          const float dist = std::sqrt(blk.vv[k]) - 0.0f;
          out[i] = dist > tol ? ConvexStatus::separated
                              : (dist >= -tol ? ConvexStatus::touching : ConvexStatus::intersecting);
        }
        continue;
      }
      if (blk.code[k] == BoxGjkBlock::kDone && (fl & BoxGjkBlock::kFull)) {
        out[i] = ConvexStatus::intersecting;
        continue;
      }
      load_pair(p, i, blk, k, q);
      out[i] = q.scalar ? convex_intersect(q.a, q.pa, q.b, q.pb, opt).status : box_intersect_status(q.f, q.g, opt);
    }
  });
}

// The batches run in fixed chunks of pairs over the threads (parallel_for): a pair's result
// never depends on its neighbours, so neither the chunks nor the thread count change a bit.
// A chunk is a multiple of the lanes' block and holds several of epa_boxes' gatherings.
constexpr std::size_t kBatchChunk = 8 * BoxGjkBlock::kMax;

// p from pair b on: the columns advanced by b.
ConvexBoxPairs from_pair(const ConvexBoxPairs& p, std::size_t b) {
  ConvexBoxPairs q = p;
  for (int k = 0; k < 3; ++k) q.a_center[k] += b, q.a_half[k] += b, q.b_center[k] += b, q.b_half[k] += b;
  for (int k = 0; k < 9; ++k) q.a_rot[k] += b, q.b_rot[k] += b;
  return q;
}

// run(view, n, out + b) over the chunks. A chunk whose lane state cannot be allocated runs
// its pairs one at a time (scalar(i) for pair i: the same bits), so nothing escapes a worker
// thread. Then the first invalid pair's message is made on the calling thread (invalid()
// sets last_error() on the thread that meets the pair).
template <class T, class Run, class Scalar, class Invalid>
void batch_in_chunks(const ConvexBoxPairs& p, std::size_t count, T* out, Run&& run, Scalar&& scalar, Invalid&& invalid) {
  parallel_for(count, kBatchChunk, [&](std::size_t b, std::size_t e) {
    try {
      run(from_pair(p, b), e - b, out + b);
    } catch (const std::bad_alloc&) {
      for (std::size_t i = b; i < e; ++i) out[i] = scalar(i);
    }
  });
  for (std::size_t i = 0; i < count; ++i)
    if (invalid(out[i])) {
      (void)scalar(i);
      break;
    }
}

}  // namespace
}  // namespace detail

void convex_intersect_batch(const ConvexBoxPairs& p, std::size_t count, ConvexStatus* out,
                            const ConvexQueryOptions& opt) {
  detail::batch_in_chunks(
      p, count, out,
      [&](const ConvexBoxPairs& v, std::size_t n, ConvexStatus* o) { detail::intersect_status_batch(v, n, o, opt); },
      [&](std::size_t i) {
        detail::BoxBatchPair q;
        detail::load_pair_scalar(p, i, q);
        return detail::box_intersect_scalar(q, opt);
      },
      [](ConvexStatus st) { return st == ConvexStatus::invalid_input; });
}

namespace detail {
namespace {
void result_batch_in_chunks(const ConvexBoxPairs& p, std::size_t count, ConvexResult* out, const ConvexQueryOptions& opt,
                            Mode mode) {
  batch_in_chunks(
      p, count, out,
      [&](const ConvexBoxPairs& v, std::size_t n, ConvexResult* o) { box_result_batch(v, n, o, opt, mode); },
      [&](std::size_t i) {
        BoxBatchPair q;
        load_pair_scalar(p, i, q);
        return query(q.a, q.pa, q.b, q.pb, opt, mode);
      },
      [](const ConvexResult& r) { return r.status == ConvexStatus::invalid_input; });
}
}  // namespace
}  // namespace detail

void convex_intersect_batch(const ConvexBoxPairs& p, std::size_t count, ConvexResult* out,
                            const ConvexQueryOptions& opt) {
  detail::result_batch_in_chunks(p, count, out, opt, detail::Mode::intersect);
}

void convex_distance_batch(const ConvexBoxPairs& p, std::size_t count, ConvexResult* out,
                           const ConvexQueryOptions& opt) {
  detail::result_batch_in_chunks(p, count, out, opt, detail::Mode::distance);
}

void convex_penetration_batch(const ConvexBoxPairs& p, std::size_t count, ConvexResult* out,
                              const ConvexQueryOptions& opt) {
  detail::result_batch_in_chunks(p, count, out, opt, detail::Mode::penetration);
}

}  // namespace gyro
