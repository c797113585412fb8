// Box-box and box-plane manifolds, and the face clipping and point reduction the box-triangle
// manifold shares (narrowphase.hpp).
//
// Box-box: the separating axis test over 15 axes (each box's 3 face normals and the 9 cross
// products of their edge directions: Gottschalk's OBB test, Ericson 4.4.1), measured relative
// to a's centre so that boxes far from the origin lose only their own rounding. The axis of
// largest separation is the normal, except that a's faces are preferred to b's, and faces to
// edges, unless the other separates clearly more: a box resting on another keeps its
// reference face (and feature ids) instead of flipping on rounding noise, and a box rocking
// on an edge does not alternate between face and edge manifolds. A face axis gives the
// incident face (the other box's face most opposed to the normal) clipped against the
// reference face's side planes (Sutherland-Hodgman, as Box2D Lite and Bullet); an edge axis
// gives one point between the two supporting edges.
//
// The axis test itself is box_sat_lanes.hpp's, written once over lanes: collide_boxes() runs
// its float instantiation, the narrowphase runs it over many pairs at once (box_sat.hpp) and
// both finish in box_manifold().
//
// Determinism: a fixed sequence of + - * / sqrt and comparisons; every tie goes to the first
// candidate in a fixed order.
#include "dynamics/box_sat.hpp"
#include "dynamics/box_sat_lanes.hpp"
#include "dynamics/narrowphase.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

// Near-ties in the point reduction and the incident face go to the first candidate, so that
// rounding noise cannot change which points (feature ids) are kept: depths within this
// fraction of the polygon's size, distances and areas within this fraction of the largest.
constexpr float kDepthTie = 1e-5f;
constexpr float kRelTie = 1e-3f;
constexpr int kMaxClip = 12;  // a quad clipped by 4 planes has at most 8 vertices

float largest(const float e[3]) { return gyro::max(e[0], gyro::max(e[1], e[2])); }

// Face contact with face `axis` of box ref (outward normal sign * axis) as reference and the
// most opposed face of box inc as incident face. id_flag is kFeatureRefB when ref is b.
void box_face_contact(const vec3& ref_center, const BoxAxes& rf, int axis, float sign, const vec3& inc_center,
                      const BoxAxes& in, float margin, uint32_t id_flag, Manifold* out) {
  ClipSide sides[4];
  const FaceFrame f = box_face_frame(ref_center, rf, axis, sign, sides);
  ClipVertex poly[4];
  const uint32_t inc_face = box_incident_face(in, inc_center - ref_center, f, poly);
  const uint32_t ref_face = 2u * uint32_t(axis) + (sign < 0.0f ? 1u : 0u);
  clip_face_contact(f, poly, 4, sides, 4, margin, id_flag | ref_face << 9 | inc_face << 6, out);
}

// Sutherland-Hodgman against one side, given each vertex's signed distance d to it; the new
// vertices record the side's code.
int clip_side(const ClipVertex* in, const float* d, int n, uint8_t code, ClipVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    const ClipVertex& p = in[i];
    const bool p_in = d[i] <= 0.0f, q_in = d[j] <= 0.0f;
    if (p_in && m < kMaxClip) out[m++] = p;
    if (p_in != q_in && m < kMaxClip) {
      const ClipVertex& q = in[j];
      const float t = d[i] / (d[i] - d[j]);  // the signs differ, so the difference is not zero
      ClipVertex v{p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t, p.z + (q.z - p.z) * t, code, p.out};
      if (p_in) v.in = p.out, v.out = code;
      out[m++] = v;
    }
  }
  return m;
}

float cross2(float ax, float ay, float bx, float by) { return ax * by - ay * bx; }

// The first index whose value is within kRelTie of the largest, or -1 if the largest is not
// positive.
int first_near_max(const float* value, int n) {
  float best = 0.0f;
  for (int i = 0; i < n; ++i) best = gyro::max(best, value[i]);
  if (!(best > 0.0f)) return -1;
  int i = 0;
  while (i + 1 < n && value[i] < best * (1.0f - kRelTie)) ++i;
  return i;
}

// Picks at most 4 of the n > 4 points (in the face plane, with their separations): the
// deepest, the farthest from it, then the two that add the most area. Writes the picks in
// ascending order; returns how many.
int reduce(const float* x, const float* y, const float* sep, int n, int* pick) {
  float lo_x = x[0], hi_x = x[0], lo_y = y[0], hi_y = y[0], deepest = sep[0];
  for (int i = 1; i < n; ++i) {
    lo_x = gyro::min(lo_x, x[i]), hi_x = gyro::max(hi_x, x[i]);
    lo_y = gyro::min(lo_y, y[i]), hi_y = gyro::max(hi_y, y[i]);
    deepest = gyro::min(deepest, sep[i]);
  }
  const float depth_tie = kDepthTie * ((hi_x - lo_x) + (hi_y - lo_y));
  int p0 = 0;
  while (p0 + 1 < n && sep[p0] > deepest + depth_tie) ++p0;
  int count = 1;
  pick[0] = p0;

  float value[kMaxClip];
  for (int i = 0; i < n; ++i) {
    const float dx = x[i] - x[p0], dy = y[i] - y[p0];
    value[i] = dx * dx + dy * dy;
  }
  const int p1 = first_near_max(value, n);
  if (p1 >= 0) {
    pick[count++] = p1;
    for (int i = 0; i < n; ++i) value[i] = std::abs(cross2(x[p1] - x[p0], y[p1] - y[p0], x[i] - x[p0], y[i] - y[p0]));
    const int p2 = first_near_max(value, n);
    if (p2 >= 0) {
      pick[count++] = p2;
      // Orient the triangle counter-clockwise; a point's gain is how far it lies outside the
      // edge it is most outside of (twice the area it adds to the hull).
      int t[3] = {p0, p1, p2};
      if (cross2(x[p1] - x[p0], y[p1] - y[p0], x[p2] - x[p0], y[p2] - y[p0]) < 0.0f) t[1] = p2, t[2] = p1;
      for (int i = 0; i < n; ++i) {
        float gain = 0.0f;
        for (int e = 0; e < 3; ++e) {
          const int a = t[e], b = t[e == 2 ? 0 : e + 1];
          gain = gyro::max(gain, -cross2(x[b] - x[a], y[b] - y[a], x[i] - x[a], y[i] - y[a]));
        }
        value[i] = gain;
      }
      const int p3 = first_near_max(value, n);
      if (p3 >= 0) pick[count++] = p3;
    }
  }
  for (int i = 1; i < count; ++i)  // insertion sort of at most 4
    for (int j = i; j > 0 && pick[j - 1] > pick[j]; --j) {
      const int tmp = pick[j];
      pick[j] = pick[j - 1];
      pick[j - 1] = tmp;
    }
  return count;
}

}  // namespace

uint32_t box_support_edge(const BoxAxes& box, int k, const vec3& dir, vec3* center) {
  vec3 c{};
  uint32_t code = 4u * uint32_t(k);
  for (int step = 1; step <= 2; ++step) {
    const int m = (k + step) % 3;
    const bool negative = dot(box.u[m], dir) < 0.0f;
    c = c + box.u[m] * (negative ? -box.e[m] : box.e[m]);
    if (negative) code |= 1u << (step - 1);
  }
  *center = c;
  return code;
}

FaceFrame box_face_frame(const vec3& center, const BoxAxes& axes, int axis, float sign, ClipSide* sides) {
  const int k1 = (axis + 1) % 3, k2 = (axis + 2) % 3;
  FaceFrame f;
  f.origin = center;
  f.t1 = axes.u[k1];
  f.t2 = axes.u[k2];
  f.normal = axes.u[axis] * sign;
  f.height = axes.e[axis];
  sides[0] = {1.0f, 0.0f, axes.e[k1]};
  sides[1] = {-1.0f, 0.0f, axes.e[k1]};
  sides[2] = {0.0f, 1.0f, axes.e[k2]};
  sides[3] = {0.0f, -1.0f, axes.e[k2]};
  return f;
}

uint32_t box_incident_face(const BoxAxes& box, const vec3& center, const FaceFrame& f, ClipVertex* poly) {
  float q[3], best = 0.0f;
  for (int m = 0; m < 3; ++m) q[m] = dot(box.u[m], f.normal), best = gyro::max(best, std::abs(q[m]));
  int m = 0;
  while (m < 2 && std::abs(q[m]) < best * (1.0f - kRelTie)) ++m;
  const float tau = q[m] > 0.0f ? -1.0f : 1.0f;  // the face's outward normal opposes f.normal
  const int m1 = (m + 1) % 3, m2 = (m + 2) % 3;
  auto to_frame = [&](const vec3& w) { return vec3{dot(w, f.t1), dot(w, f.t2), dot(w, f.normal)}; };
  const vec3 c = to_frame(center + box.u[m] * (tau * box.e[m]));
  const vec3 u = to_frame(box.u[m1] * box.e[m1]), v = to_frame(box.u[m2] * box.e[m2]);
  const vec3 corner[4] = {(c + u) + v, (c - u) + v, (c - u) - v, (c + u) - v};
  for (int k = 0; k < 4; ++k) poly[k] = {corner[k].x, corner[k].y, corner[k].z, uint8_t((k + 3) & 3), uint8_t(k)};
  return 2u * uint32_t(m) + (tau < 0.0f ? 1u : 0u);
}

void clip_face_contact(const FaceFrame& frame, const ClipVertex* poly, int count, const ClipSide* sides, int side_count,
                       float margin, uint32_t id_base, Manifold* out) {
  ClipVertex buf[2][kMaxClip];
  for (int i = 0; i < count; ++i) buf[0][i] = poly[i];
  int n = count, cur = 0;
  for (int s = 0; s < side_count && n > 0; ++s) {
    float d[kMaxClip];
    bool cuts = false;
    for (int i = 0; i < n; ++i) {
      d[i] = (sides[s].nx * buf[cur][i].x + sides[s].ny * buf[cur][i].y) - sides[s].d;
      cuts = cuts || d[i] > 0.0f;
    }
    if (!cuts) continue;  // the usual case for a resting face: nothing to copy
    n = clip_side(buf[cur], d, n, uint8_t(4 + s), buf[cur ^ 1]);
    cur ^= 1;
  }
  const ClipVertex* v = buf[cur];
  float x[kMaxClip], y[kMaxClip], sep[kMaxClip];
  int keep[kMaxClip], kept = 0;
  for (int i = 0; i < n; ++i) {
    const float s = v[i].z - frame.height;
    if (!(s < margin)) continue;
    x[kept] = v[i].x, y[kept] = v[i].y, sep[kept] = s, keep[kept] = i;
    ++kept;
  }
  int pick[kMaxManifoldPoints] = {0, 1, 2, 3};
  const int m = kept > int(kMaxManifoldPoints) ? reduce(x, y, sep, kept, pick) : kept;
  for (int k = 0; k < m; ++k) {
    const int i = pick[k];
    const ClipVertex& c = v[keep[i]];
    ContactPoint& p = out->points[k];
    p.position = frame.origin + ((frame.t1 * c.x + frame.t2 * c.y) + frame.normal * (c.z - sep[i] * 0.5f));
    p.separation = sep[i];
    p.feature_id = id_base | uint32_t(c.in) << 3 | uint32_t(c.out);
  }
  out->count = uint32_t(m);
}

void edge_contact(const vec3& origin, const vec3& pa, const vec3& ha, const vec3& pb, const vec3& hb, float separation,
                  uint32_t feature_id, Manifold* out) {
  // Closest points pa + s ha and pb + t hb, s and t in [-1, 1] (Ericson 5.1.9), with zero
  // half-vectors (boxes of zero extent) handled without a division by zero.
  const vec3 r = pa - pb;
  const float a = dot(ha, ha), e = dot(hb, hb), b = dot(ha, hb), c = dot(ha, r), f = dot(hb, r);
  float s = 0.0f, t = 0.0f;
  if (a > 0.0f && e > 0.0f) {
    const float denom = a * e - b * b;
    s = denom > 0.0f ? clamp((b * f - c * e) / denom, -1.0f, 1.0f) : 0.0f;
    t = (b * s + f) / e;
    if (t < -1.0f || t > 1.0f) {
      t = clamp(t, -1.0f, 1.0f);
      s = clamp((b * t - c) / a, -1.0f, 1.0f);
    }
  } else if (e > 0.0f) {
    t = clamp(f / e, -1.0f, 1.0f);
  } else if (a > 0.0f) {
    s = clamp(-c / a, -1.0f, 1.0f);
  }
  ContactPoint& p = out->points[0];
  p.position = origin + ((pa + ha * s) + (pb + hb * t)) * 0.5f;
  p.separation = separation;
  p.feature_id = feature_id;
  out->count = 1;
}

void box_manifold(const vec3& ca, const BoxAxes& fa, const vec3& cb, const BoxAxes& fb, const BoxSat& sat, float margin,
                  Manifold* out) {
  out->count = 0;
  if (!sat.hit) return;
  const vec3 d = cb - ca;
  const float size = gyro::min(largest(fa.e), largest(fb.e));
  const bool ref_b = clearly_larger(sat.sb, sat.sa, kFaceRelTol, kFaceAbsTol * size);
  const float sf = ref_b ? sat.sb : sat.sa;
  const int ie = sat.ie, je = sat.je;
  auto edges = [&] {
    vec3 pa, pb;
    const uint32_t ea = box_support_edge(fa, ie, sat.edge_normal, &pa);
    const uint32_t eb = box_support_edge(fb, je, -sat.edge_normal, &pb);
    out->normal = sat.edge_normal;
    edge_contact(ca, pa, fa.u[ie] * fa.e[ie], d + pb, fb.u[je] * fb.e[je], sat.se, kFeatureEdge | ea << 4 | eb, out);
  };
  if (ie >= 0 && clearly_larger(sat.se, sf, kEdgeRelTol, kEdgeAbsTol * size)) return edges();

  if (ref_b) {
    const float sign = dot(d, fb.u[sat.jb]) < 0.0f ? 1.0f : -1.0f;  // b's face towards a
    box_face_contact(cb, fb, sat.jb, sign, ca, fa, margin, kFeatureRefB, out);
    out->normal = fb.u[sat.jb] * -sign;
  } else {
    const float sign = dot(d, fa.u[sat.ia]) < 0.0f ? -1.0f : 1.0f;  // a's face towards b
    box_face_contact(ca, fa, sat.ia, sign, cb, fb, margin, 0, out);
    out->normal = fa.u[sat.ia] * sign;
  }
  // Rounding at the rim of the reference face can clip a grazing incident face away;
  // then the best edge pair, if any, still gives a point.
  if (out->count == 0 && ie >= 0) edges();
}

void collide_boxes(const OBB& a, const OBB& b, float margin, Manifold* out) {
  const BoxAxes fa = box_axes(a), fb = box_axes(b);
  arch_scalar::BoxLanes<float> la, lb;
  for (int k = 0; k < 3; ++k) {
    la.u[k] = {fa.u[k].x, fa.u[k].y, fa.u[k].z}, la.e[k] = fa.e[k];
    lb.u[k] = {fb.u[k].x, fb.u[k].y, fb.u[k].z}, lb.e[k] = fb.e[k];
  }
  const vec3 d = b.center - a.center;
  const arch_scalar::BoxSatLanes<float> r = arch_scalar::box_sat(la, lb, {d.x, d.y, d.z}, margin);
  BoxSat sat;
  sat.hit = r.hit;
  sat.sa = r.sa, sat.sb = r.sb, sat.se = r.se;
  sat.ia = int(r.ia), sat.jb = int(r.jb), sat.ie = int(r.ie), sat.je = int(r.je);
  sat.edge_normal = {r.edge_normal.x, r.edge_normal.y, r.edge_normal.z};
  box_manifold(a.center, fa, b.center, fb, sat, margin, out);
}

void collide_box_plane(const OBB& a, const Plane& b, float margin, Manifold* out) {
  out->count = 0;
  const BoxAxes f = box_axes(a);
  const float center = dot(b.normal, a.center) - b.distance;
  float reach[3];
  for (int k = 0; k < 3; ++k) reach[k] = dot(b.normal, f.u[k]) * f.e[k];
  // Corner i is on the negative side of axis k when bit k is set; a zero extent makes two
  // corners coincide, and only the positive one is kept.
  float sep[8];
  int order[8], n = 0;
  for (int i = 0; i < 8; ++i) {
    if (((i & 1) && f.e[0] == 0.0f) || ((i & 2) && f.e[1] == 0.0f) || ((i & 4) && f.e[2] == 0.0f)) continue;
    sep[i] = ((center + ((i & 1) ? -reach[0] : reach[0])) + ((i & 2) ? -reach[1] : reach[1])) +
             ((i & 4) ? -reach[2] : reach[2]);
    if (!(sep[i] < margin)) continue;
    // Insertion by (separation, index), so the first four are the deepest.
    int j = n++;
    for (; j > 0 && sep[order[j - 1]] > sep[i]; --j) order[j] = order[j - 1];
    order[j] = i;
  }
  n = n < int(kMaxManifoldPoints) ? n : int(kMaxManifoldPoints);
  for (int i = 1; i < n; ++i)  // the kept corners in index order, which does not change as they rock
    for (int j = i; j > 0 && order[j - 1] > order[j]; --j) {
      const int tmp = order[j];
      order[j] = order[j - 1];
      order[j - 1] = tmp;
    }
  out->normal = -b.normal;
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    const vec3 corner = ((a.center + f.u[0] * ((i & 1) ? -f.e[0] : f.e[0])) + f.u[1] * ((i & 2) ? -f.e[1] : f.e[1])) +
                        f.u[2] * ((i & 4) ? -f.e[2] : f.e[2]);
    out->points[k].position = corner - b.normal * (sep[i] * 0.5f);
    out->points[k].separation = sep[i];
    out->points[k].feature_id = uint32_t(i);
  }
  out->count = uint32_t(n);
}

}  // namespace gyro::detail
