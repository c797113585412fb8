// Generic convex manifolds (the appendix's GJK/EPA plus a stable multi-point manifold): the
// pair's normal and depth come from GJK (separated within the margin) or EPA (overlapping);
// then each shape's supporting feature along the normal (a face, a capsule's segment or a
// point) is found and the incident feature clipped against the reference face's sides, as
// box-box does (Gregorius, "Robust contact creation for physics simulations", GDC 2015).
// One general path serves every pair with a capsule, a hull or a triangle against them.
//
// Why clip instead of using EPA's single point: a face resting on a face needs its corners
// held at once, or it rocks from point to point; clipping gives them in one frame.
#include "dynamics/narrowphase.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

constexpr int kMaxPoly = 64;  // clipping buffers; larger hull faces keep their first vertices
// A face is used as the reference only when its normal is within ~3 degrees of the pair's
// normal: otherwise the contact is edge-like and EPA's single point is the right answer.
constexpr float kFaceAlign = 0.9985f;
// A capsule's segment is a supporting feature when within ~3 degrees of perpendicular.
constexpr float kSegmentPerp = 0.05f;
// Near-ties in choosing faces and reducing points go to the first candidate, so rounding
// noise does not flip the feature ids from frame to frame.
constexpr float kAlignTie = 1e-4f;
constexpr float kRelTie = 1e-3f;

struct Feature {
  vec3 v[kMaxPoly];  // world-space core points, counter-clockwise about normal for faces
  int count = 0;
  vec3 normal;        // faces: outward unit normal
  float radius = 0.0f;  // the core's margin (spheres, capsules)
  uint32_t id = 0;
};

vec3 row(const mat3& m, int k) { return {m.m[k][0], m.m[k][1], m.m[k][2]}; }
vec3 to_world(const ConvexPose& p, const vec3& local) { return local * p.rotation + p.position; }
vec3 dir_to_world(const ConvexPose& p, const vec3& local) { return local * p.rotation; }
// A world direction in the shape's frame: its components along the rows (local axes).
vec3 dir_to_local(const ConvexPose& p, const vec3& d) {
  return {dot(row(p.rotation, 0), d), dot(row(p.rotation, 1), d), dot(row(p.rotation, 2), d)};
}

// The box face most aligned with d (the first of near-equal ones).
void box_feature(const ConvexCollider& c, const vec3& d, Feature* f) {
  int best = 0;
  float best_dot = -2.0f, sign = 1.0f;
  for (int k = 0; k < 3; ++k) {
    const float x = dot(row(c.pose.rotation, k), d);
    const float ax = x < 0.0f ? -x : x;
    if (ax > best_dot + kAlignTie) best_dot = ax, best = k, sign = x < 0.0f ? -1.0f : 1.0f;
  }
  const int k1 = (best + 1) % 3, k2 = (best + 2) % 3;
  const vec3 u = row(c.pose.rotation, best), u1 = row(c.pose.rotation, k1), u2 = row(c.pose.rotation, k2);
  const vec3 e = c.shape.half_extents;
  const vec3 centre = c.pose.position + u * (sign * e[best]);
  const vec3 a = u1 * e[k1], b = u2 * e[k2];
  // Counter-clockwise about sign * u: (u1, u2, u) is right-handed.
  const float s = sign;
  f->v[0] = centre + a + b * s;
  f->v[1] = centre - a + b * s;
  f->v[2] = centre - a - b * s;
  f->v[3] = centre + a - b * s;
  f->count = 4;
  f->normal = u * sign;
  f->id = 2u * uint32_t(best) + (sign < 0.0f ? 1u : 0u);
}

void hull_feature(const ConvexCollider& c, const vec3& d, Feature* f) {
  const ConvexHull& h = *c.hull;
  const vec3 dl = dir_to_local(c.pose, d);
  std::size_t best = 0;
  float best_dot = -2.0f;
  for (std::size_t i = 0; i < h.planes.size(); ++i) {
    const float x = dot(h.planes[i].normal, dl);
    if (x > best_dot + kAlignTie) best_dot = x, best = i;
  }
  const uint32_t first = h.face_start[best], end = h.face_start[best + 1];
  int n = 0;
  for (uint32_t j = first; j < end && n < kMaxPoly; ++j) f->v[n++] = to_world(c.pose, h.vertices[h.face_vertices[j]]);
  f->count = n;
  f->normal = dir_to_world(c.pose, h.planes[best].normal);
  f->id = uint32_t(best);
}

void triangle_feature(const ConvexCollider& c, const vec3& d, Feature* f) {
  const vec3 a = to_world(c.pose, c.shape.v[0]), b = to_world(c.pose, c.shape.v[1]), e = to_world(c.pose, c.shape.v[2]);
  const vec3 n = cross(b - a, e - a);
  const float nn = dot(n, n);
  if (!(nn > 0.0f)) {  // degenerate: its corner furthest along d
    const float da = dot(a, d), db = dot(b, d), de = dot(e, d);
    f->v[0] = da >= db && da >= de ? a : db >= de ? b : e;
    f->count = 1;
    f->id = 9;
    return;
  }
  const vec3 unit = n * (1.0f / std::sqrt(nn));
  if (dot(unit, d) >= 0.0f) {
    f->v[0] = a, f->v[1] = b, f->v[2] = e, f->normal = unit, f->id = 7;
  } else {
    f->v[0] = a, f->v[1] = e, f->v[2] = b, f->normal = -unit, f->id = 8;
  }
  f->count = 3;
}

// The supporting feature of c along world direction d (unit).
void supporting_feature(const ConvexCollider& c, const vec3& d, Feature* f) {
  f->radius = 0.0f;
  switch (c.shape.type) {
    case ConvexType::sphere:
      f->v[0] = c.pose.position, f->count = 1, f->radius = c.shape.radius, f->id = 0;
      return;
    case ConvexType::capsule: {
      const vec3 axis = row(c.pose.rotation, 1);
      const vec3 top = c.pose.position + axis * c.shape.half_height, bottom = c.pose.position - axis * c.shape.half_height;
      const float x = dot(axis, d);
      f->radius = c.shape.radius;
      if ((x < 0.0f ? -x : x) <= kSegmentPerp) {
        f->v[0] = bottom, f->v[1] = top, f->count = 2, f->id = 0;
      } else {
        f->v[0] = x > 0.0f ? top : bottom, f->count = 1, f->id = x > 0.0f ? 2u : 1u;
      }
      return;
    }
    case ConvexType::box: box_feature(c, d, f); return;
    case ConvexType::triangle: triangle_feature(c, d, f); return;
    case ConvexType::points:
      if (c.hull) {
        hull_feature(c, d, f);
        return;
      }
      break;
    case ConvexType::cylinder: break;
  }
  f->v[0] = to_world(c.pose, support(c.shape, dir_to_local(c.pose, d)));
  f->count = 1;
  f->id = 0;
}

// A clipped point with the codes of what made it (for the feature id).
struct ClipPoint {
  vec3 p;
  uint32_t code;
};

// Sutherland-Hodgman of a closed polygon (or, with closed false, a segment) against the
// half-space dot(side, x - origin) <= 0. New points get (side code << 5 | the index of the
// edge they cut), 10 bits: feature ids need only be equal for the same configuration.
int clip(const ClipPoint* in, int n, bool closed, const vec3& side, const vec3& origin, uint32_t side_code,
         ClipPoint* out) {
  // A segment clipped away by the first side plane leaves nothing for the second.
  if (n <= 0) return 0;
  int m = 0;
  const int edges = closed ? n : n - 1;
  float dist[kMaxPoly + 8];
  for (int i = 0; i < n; ++i) dist[i] = dot(side, in[i].p - origin);
  if (!closed && n == 1) {
    if (dist[0] <= 0.0f) out[m++] = in[0];
    return m;
  }
  for (int i = 0; i < edges; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    const bool p_in = dist[i] <= 0.0f, q_in = dist[j] <= 0.0f;
    if (p_in && m < kMaxPoly) out[m++] = in[i];
    if (p_in != q_in && m < kMaxPoly) {
      const float t = dist[i] / (dist[i] - dist[j]);
      out[m++] = {in[i].p + (in[j].p - in[i].p) * t, ((side_code & 31u) << 5) | (uint32_t(i) & 31u)};
    }
  }
  if (!closed && dist[n - 1] <= 0.0f && m < kMaxPoly) out[m++] = in[n - 1];
  return m;
}

// The first index within kRelTie of the largest value, -1 if the largest is not positive.
int first_near_max(const float* value, int n) {
  float best = 0.0f;
  for (int i = 0; i < n; ++i) best = value[i] > best ? value[i] : best;
  if (!(best > 0.0f)) return -1;
  int i = 0;
  while (i + 1 < n && value[i] < best * (1.0f - kRelTie)) ++i;
  return i;
}

// At most 4 of n points spanning the most area with the deepest kept: the deepest, the
// farthest from it, the one making the largest triangle, the one adding the most area.
// Picks come out in ascending index order.
int reduce(const vec3* p, const float* sep, int n, const vec3& normal, int* pick) {
  if (n <= 4) {
    for (int i = 0; i < n; ++i) pick[i] = i;
    return n;
  }
  float deepest = sep[0];
  for (int i = 1; i < n; ++i) deepest = sep[i] < deepest ? sep[i] : deepest;
  int p0 = 0;
  const float tie = 1e-6f + 1e-5f * (deepest < 0.0f ? -deepest : deepest);
  while (p0 + 1 < n && sep[p0] > deepest + tie) ++p0;
  int count = 0;
  pick[count++] = p0;
  float value[kMaxPoly];
  for (int i = 0; i < n; ++i) value[i] = dot(p[i] - p[p0], p[i] - p[p0]);
  const int p1 = first_near_max(value, n);
  if (p1 >= 0) {
    pick[count++] = p1;
    for (int i = 0; i < n; ++i) {
      const float a = dot(cross(p[p1] - p[p0], p[i] - p[p0]), normal);
      value[i] = a < 0.0f ? -a : a;
    }
    const int p2 = first_near_max(value, n);
    if (p2 >= 0) {
      pick[count++] = p2;
      int t[3] = {p0, p1, p2};
      if (dot(cross(p[p1] - p[p0], p[p2] - p[p0]), normal) < 0.0f) t[1] = p2, t[2] = p1;
      for (int i = 0; i < n; ++i) {
        float gain = 0.0f;
        for (int e = 0; e < 3; ++e) {
          const int a = t[e], b = t[e == 2 ? 0 : e + 1];
          const float g = -dot(cross(p[b] - p[a], p[i] - p[a]), normal);
          gain = g > gain ? g : gain;
        }
        value[i] = gain;
      }
      const int p3 = first_near_max(value, n);
      if (p3 >= 0) pick[count++] = p3;
    }
  }
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && pick[j - 1] > pick[j]; --j) {
      const int tmp = pick[j];
      pick[j] = pick[j - 1];
      pick[j - 1] = tmp;
    }
  return count;
}

// Writes the points of incident feature `inc` clipped to reference feature `ref` (a face,
// or with ref.count == 2 a segment, its sides the planes through its ends) whose separation
// along ref_normal (outward from ref) is below margin. Returns how many were written.
int clip_features(const Feature& ref, const vec3& ref_normal, const Feature& inc, float margin, uint32_t id_base,
                  bool ref_is_a, Manifold* out) {
  ClipPoint buf[2][kMaxPoly];
  int n = inc.count;
  for (int i = 0; i < n; ++i) buf[0][i] = {inc.v[i], uint32_t(i)};
  int cur = 0;
  const bool closed = inc.count >= 3;
  if (ref.count >= 3) {
    for (int j = 0; j < ref.count && n > 0; ++j) {
      const vec3 a = ref.v[j], b = ref.v[j + 1 == ref.count ? 0 : j + 1];
      const vec3 side = cross(b - a, ref_normal);  // outward for a counter-clockwise face
      n = clip(buf[cur], n, closed, side, a, uint32_t(j) + 1u, buf[cur ^ 1]);
      cur ^= 1;
    }
  } else {
    const vec3 axis = ref.v[1] - ref.v[0];
    n = clip(buf[cur], n, closed, -axis, ref.v[0], 1u, buf[cur ^ 1]);
    cur ^= 1;
    n = clip(buf[cur], n, closed, axis, ref.v[1], 2u, buf[cur ^ 1]);
    cur ^= 1;
  }
  vec3 pos[kMaxPoly];
  float sep[kMaxPoly];
  uint32_t code[kMaxPoly];
  int kept = 0;
  const float plane = dot(ref.v[0], ref_normal) + ref.radius;
  for (int i = 0; i < n; ++i) {
    const vec3 surface = buf[cur][i].p - ref_normal * inc.radius;  // incident surface point
    const float s = dot(surface, ref_normal) - plane;
    if (!(s < margin)) continue;
    pos[kept] = surface - ref_normal * (0.5f * s);
    sep[kept] = s;
    code[kept] = buf[cur][i].code;
    ++kept;
  }
  int pick[4];
  const int m = reduce(pos, sep, kept, ref_normal, pick);
  out->normal = ref_is_a ? ref_normal : -ref_normal;
  for (int k = 0; k < m; ++k) {
    out->points[k].position = pos[pick[k]];
    out->points[k].separation = sep[pick[k]];
    out->points[k].feature_id = id_base | (code[pick[k]] & 0x3FFu);
  }
  out->count = uint32_t(m);
  return m;
}

// EPA's normal, or for coincident cores (no defined direction) the line of the centres,
// else +y (as spheres do).
vec3 pair_normal(const ConvexResult& r, const ConvexCollider& a, const ConvexCollider& b) {
  if (dot(r.normal, r.normal) > 0.5f) return r.normal;
  const vec3 d = b.pose.position - a.pose.position;
  return d == vec3{} ? vec3{0.0f, 1.0f, 0.0f} : normalized(d);
}

void single_point(const ConvexResult& r, const vec3& normal, uint32_t id, Manifold* out) {
  out->normal = normal;
  out->points[0].position = (r.point_a + r.point_b) * 0.5f;
  out->points[0].separation = r.distance;
  out->points[0].feature_id = id;
  out->count = 1;
}

}  // namespace

void collide_convex_shapes(const ConvexCollider& a, const ConvexCollider& b, float margin, Manifold* out) {
  out->count = 0;
  const ConvexResult r = convex_penetration(a.shape, a.pose, b.shape, b.pose);
  if (r.status == ConvexStatus::invalid_input) return;
  if (!(r.distance < margin)) return;
  const vec3 n = pair_normal(r, a, b);
  Feature fa, fb;
  supporting_feature(a, n, &fa);
  supporting_feature(b, -n, &fb);
  const float align_a = fa.count >= 3 ? dot(fa.normal, n) : -1.0f;
  const float align_b = fb.count >= 3 ? dot(fb.normal, -n) : -1.0f;
  // Feature id: a's feature (bits 22-31), b's (12-21), reference on b (11), single point
  // (10), the clip code (0-9).
  const uint32_t pair_id = (fa.id & 0x3FFu) << 22 | (fb.id & 0x3FFu) << 12;
  // A's face is preferred (b's must be clearly better) so a resting pair keeps its reference.
  if (align_a >= kFaceAlign && align_a + kAlignTie >= align_b && fb.count >= 2) {
    if (clip_features(fa, fa.normal, fb, margin, pair_id, true, out) > 0) return;
  } else if (align_b >= kFaceAlign && fa.count >= 2) {
    if (clip_features(fb, fb.normal, fa, margin, pair_id | 1u << 11, false, out) > 0) return;
  } else if (fa.count == 2 && fb.count == 2) {
    // Two capsules side by side: b's segment clipped to a's span, separations along n.
    Feature ref = fa;
    if (clip_features(ref, n, fb, margin, pair_id, true, out) > 0) return;
  }
  single_point(r, n, pair_id | 1u << 10, out);
}

void collide_convex_plane(const ConvexCollider& a, const Plane& b, float margin, Manifold* out) {
  out->count = 0;
  const vec3 n = b.normal;  // the solid lies behind it: a is pushed along +n, the normal a->b is -n
  vec3 pos[kMaxPoly];
  float sep[kMaxPoly];
  uint32_t id[kMaxPoly];
  int kept = 0;
  auto consider = [&](const vec3& core, float radius, uint32_t fid) {
    if (kept == kMaxPoly) return;
    const vec3 surface = core - n * radius;
    const float s = dot(n, surface) - b.distance;
    if (!(s < margin)) return;
    pos[kept] = surface - n * (0.5f * s), sep[kept] = s, id[kept] = fid;
    ++kept;
  };
  switch (a.shape.type) {
    case ConvexType::capsule: {
      const vec3 axis = row(a.pose.rotation, 1) * a.shape.half_height;
      consider(a.pose.position - axis, a.shape.radius, 1);
      consider(a.pose.position + axis, a.shape.radius, 2);
      break;
    }
    case ConvexType::points:
      if (a.hull) {
        // Every vertex within the margin (the first kMaxPoly of them).
        const std::size_t nv = a.hull->vertices.size();
        for (std::size_t i = 0; i < nv; ++i) consider(to_world(a.pose, a.hull->vertices[i]), 0.0f, uint32_t(i));
        break;
      }
      [[fallthrough]];
    default: {
      Feature f;
      supporting_feature(a, -n, &f);
      for (int i = 0; i < f.count; ++i) consider(f.v[i], f.radius, uint32_t(i));
    }
  }
  int pick[4];
  const int m = reduce(pos, sep, kept, n, pick);
  out->normal = -n;
  for (int k = 0; k < m; ++k) {
    out->points[k].position = pos[pick[k]];
    out->points[k].separation = sep[pick[k]];
    out->points[k].feature_id = id[pick[k]];
  }
  out->count = uint32_t(m);
}

}  // namespace gyro::detail

namespace gyro::detail {
namespace {

// Points kept over frames break when the surfaces drift apart along the normal beyond the
// margin or sideways by more than this (Bullet's and the book's contact breaking threshold),
// and a new point within it of a kept one replaces that one.
constexpr float kBreakDistance = 0.02f;

vec3 to_local(const ConvexPose& p, const vec3& w) { return dir_to_local(p, w - p.position); }

// Twice the area of the quadrilateral-ish set of 4 points seen along n: the largest of the
// three ways to pair its diagonals, so the order of the points does not matter.
float quad_area(const vec3& p0, const vec3& p1, const vec3& p2, const vec3& p3, const vec3& n) {
  const float a = dot(cross(p1 - p0, p3 - p2), n), b = dot(cross(p2 - p0, p3 - p1), n), c = dot(cross(p3 - p0, p2 - p1), n);
  const float x = a < 0.0f ? -a : a, y = b < 0.0f ? -b : b, z = c < 0.0f ? -c : c;
  return x > y ? (x > z ? x : z) : (y > z ? y : z);
}

}  // namespace

void collide_convex_incremental(const ConvexCollider& a, const ConvexCollider& b, float margin, const Manifold* old,
                                const ContactAnchors* old_anchors, Manifold* out, ContactAnchors* anchors) {
  out->count = 0;
  const ConvexResult r = convex_penetration(a.shape, a.pose, b.shape, b.pose);
  if (r.status == ConvexStatus::invalid_input || !(r.distance < margin)) return;
  const vec3 n = pair_normal(r, a, b);
  struct Candidate {
    vec3 la, lb, mid;
    float sep;
    uint32_t id;
  };
  Candidate c[kMaxManifoldPoints + 1];
  int count = 0;
  uint32_t next_id = 1;
  const vec3 new_a = r.point_a;
  const float merge_sq = kBreakDistance * kBreakDistance;
  uint32_t new_id = 0;
  if (old && old_anchors) {
    for (uint32_t k = 0; k < old->count; ++k) {
      const uint32_t id = old->points[k].feature_id;
      next_id = id >= next_id ? id + 1 : next_id;
      const vec3 wa = to_world(a.pose, old_anchors->a[k]), wb = to_world(b.pose, old_anchors->b[k]);
      const vec3 d = wb - wa;
      const float sep = dot(d, n);
      const vec3 slide = d - n * sep;
      if (!(sep < margin) || dot(slide, slide) > merge_sq) continue;  // broken
      const vec3 near = wa - new_a;
      if (new_id == 0 && dot(near, near) <= merge_sq) {
        new_id = id;  // the new point replaces this one and keeps its id (and impulse)
        continue;
      }
      c[count++] = {old_anchors->a[k], old_anchors->b[k], (wa + wb) * 0.5f, sep, id};
    }
  }
  if (next_id == 0) next_id = 1;  // wrapped
  c[count++] = {to_local(a.pose, r.point_a), to_local(b.pose, r.point_b), (r.point_a + r.point_b) * 0.5f, r.distance,
                new_id != 0 ? new_id : next_id};
  if (count > int(kMaxManifoldPoints)) {
    // Keep the new point and the three old ones spanning the most area.
    int drop = 0;
    float best = -1.0f;
    for (int j = 0; j < count - 1; ++j) {
      vec3 q[4];
      int m = 0;
      for (int i = 0; i < count; ++i)
        if (i != j) q[m++] = c[i].mid;
      const float area = quad_area(q[0], q[1], q[2], q[3], n);
      if (area > best) best = area, drop = j;
    }
    for (int i = drop; i + 1 < count; ++i) c[i] = c[i + 1];
    --count;
  }
  out->normal = n;
  for (int i = 0; i < count; ++i) {
    out->points[i].position = c[i].mid;
    out->points[i].separation = c[i].sep;
    out->points[i].feature_id = c[i].id;
    anchors->a[i] = c[i].la;
    anchors->b[i] = c[i].lb;
  }
  out->count = uint32_t(count);
}

}  // namespace gyro::detail
