// Sphere and box manifolds against a double-sided triangle (the pieces of a static mesh).
//
// Sphere: the closest point of the triangle to the centre (Ericson 5.1.5's Voronoi regions),
// the region naming the feature. Box: the separating axis test over 13 axes (the box's 3
// faces, the triangle's normal, the 9 cross products of a box axis and a triangle edge),
// measured relative to the box centre, then as for two boxes: the triangle's face (preferred,
// being static and shared by the whole mesh) or a box face as reference, the other clipped
// against its side planes; an edge pair gives one point. Double-sided: along the triangle's
// normal the box is pushed back to the side its centre is on.
//
// A triangle whose normal is not usable (collinear or coincident corners, or so thin that
// |N|^2 <= kDegenerateSq * (longest edge)^4) is treated as its three edges: finite answers,
// no division by a vanishing area.
#include "dynamics/narrowphase.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

constexpr float kDegenerateSq = 1e-8f;
constexpr uint32_t kFace = 0, kEdge = 1, kVertex = 4;  // sphere-triangle feature ids: base + index

struct Tri {
  vec3 v[3];  // corners relative to the other shape's centre
  vec3 e[3];  // e[j] = v[j + 1] - v[j]
  vec3 n;     // unit normal of a, b, c's winding, or zero for a degenerate triangle
  float longest_sq = 0.0f;
};

Tri relative(const Triangle& t, const vec3& origin) {
  Tri r;
  r.v[0] = t.a - origin, r.v[1] = t.b - origin, r.v[2] = t.c - origin;
  for (int j = 0; j < 3; ++j) {
    r.e[j] = r.v[j == 2 ? 0 : j + 1] - r.v[j];
    r.longest_sq = gyro::max(r.longest_sq, dot(r.e[j], r.e[j]));
  }
  const vec3 n = cross(r.e[0], r.v[2] - r.v[0]);
  const float n_sq = dot(n, n);
  r.n = n_sq > kDegenerateSq * r.longest_sq * r.longest_sq ? n / std::sqrt(n_sq) : vec3{};
  return r;
}

float ratio01(float num, float den) { return den > 0.0f ? clamp(num / den, 0.0f, 1.0f) : 0.0f; }

vec3 region(uint32_t* feature, uint32_t id, const vec3& point) {
  *feature = id;
  return point;
}

// The point of the triangle closest to the origin and its feature (Ericson 5.1.5, with
// p = 0). The face region projects with the unit normal instead of dividing by the area.
vec3 closest_to_origin(const Tri& t, uint32_t* feature) {
  const vec3 ab = t.e[0], ac = t.v[2] - t.v[0];
  const float d1 = -dot(ab, t.v[0]), d2 = -dot(ac, t.v[0]);
  if (d1 <= 0.0f && d2 <= 0.0f) return region(feature, kVertex + 0, t.v[0]);
  const float d3 = -dot(ab, t.v[1]), d4 = -dot(ac, t.v[1]);
  if (d3 >= 0.0f && d4 <= d3) return region(feature, kVertex + 1, t.v[1]);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return region(feature, kEdge + 0, t.v[0] + ab * ratio01(d1, d1 - d3));
  const float d5 = -dot(ab, t.v[2]), d6 = -dot(ac, t.v[2]);
  if (d6 >= 0.0f && d5 <= d6) return region(feature, kVertex + 2, t.v[2]);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return region(feature, kEdge + 2, t.v[0] + ac * ratio01(d2, d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f)
    return region(feature, kEdge + 1, t.v[1] + t.e[1] * ratio01(d4 - d3, (d4 - d3) + (d5 - d6)));
  return region(feature, kFace, t.n * dot(t.v[0], t.n));
}

// The closest point over the three edges, for a triangle without a usable normal.
vec3 closest_on_edges(const Tri& t, uint32_t* feature) {
  vec3 best = t.v[0];
  float best_sq = __builtin_inff();
  *feature = kVertex + 0;  // stays only if every square overflowed
  for (int j = 0; j < 3; ++j) {
    const float s = ratio01(-dot(t.v[j], t.e[j]), dot(t.e[j], t.e[j]));
    const vec3 q = t.v[j] + t.e[j] * s;
    const float q_sq = dot(q, q);
    if (!(q_sq < best_sq)) continue;
    best = q, best_sq = q_sq;
    *feature = s == 0.0f   ? kVertex + uint32_t(j)
               : s == 1.0f ? kVertex + uint32_t(j == 2 ? 0 : j + 1)
                           : kEdge + uint32_t(j);
  }
  return best;
}

// The triangle's projection on a unit axis against a box of projection radius rb centred at
// 0: the separation, and the direction (+1: the triangle lies along +axis) from the box to it.
float axis_gap(const Tri& t, const vec3& axis, float rb, float* side, float* p) {
  for (int k = 0; k < 3; ++k) p[k] = dot(t.v[k], axis);
  const float lo = gyro::min(p[0], gyro::min(p[1], p[2])), hi = gyro::max(p[0], gyro::max(p[1], p[2]));
  // The side of the smaller overlap, which is the side of the box centre (0) from the
  // interval's middle; along the normal the interval is a point, hence double-sidedness.
  *side = lo + hi >= 0.0f ? 1.0f : -1.0f;
  return *side > 0.0f ? lo - rb : -rb - hi;
}

}  // namespace

void collide_sphere_triangle(const Sphere& a, const Triangle& b, float margin, Manifold* out) {
  out->count = 0;
  const Tri t = relative(b, a.center);
  const bool flat = t.n != vec3{};
  uint32_t feature = kFace;
  const vec3 q = flat ? closest_to_origin(t, &feature) : closest_on_edges(t, &feature);
  vec3 normal;
  float separation;
  if (feature == kFace) {
    const float h = dot(t.v[0], t.n);  // the plane's offset from the centre along n
    normal = h > 0.0f ? t.n : -t.n;
    separation = std::abs(h) - a.radius;
  } else {
    const float dist = std::sqrt(dot(q, q));
    separation = dist - a.radius;
    // A centre exactly on an edge or corner has no direction to it: the sphere leaves
    // through the front face, or upwards (-y from the sphere) for a degenerate triangle.
    normal = q != vec3{} ? normalized(q) : flat ? -t.n : vec3{0.0f, -1.0f, 0.0f};
  }
  if (!(separation < margin)) return;
  out->normal = normal;
  out->points[0].position = a.center + normal * (a.radius + separation * 0.5f);
  out->points[0].separation = separation;
  out->points[0].feature_id = feature;
  out->count = 1;
}

void collide_box_triangle(const OBB& a, const Triangle& b, float margin, Manifold* out) {
  out->count = 0;
  const BoxAxes box = box_axes(a);
  const Tri t = relative(b, a.center);
  const bool flat = t.n != vec3{};
  float p[3];

  // The triangle's normal.
  float st = -__builtin_inff(), side_t = 1.0f;
  if (flat) {
    const float rb = (box.e[0] * std::abs(dot(box.u[0], t.n)) + box.e[1] * std::abs(dot(box.u[1], t.n))) +
                     box.e[2] * std::abs(dot(box.u[2], t.n));
    st = axis_gap(t, t.n, rb, &side_t, p);
    if (!(st < margin)) return;
  }
  // The box's faces.
  float sb = -__builtin_inff(), side_b = 1.0f;
  int kb = 0;
  for (int k = 0; k < 3; ++k) {
    float side;
    const float s = axis_gap(t, box.u[k], box.e[k], &side, p);
    if (!(s < margin)) return;
    if (s > sb) sb = s, side_b = side, kb = k;
  }
  // Box axis x triangle edge. Only an axis along which the triangle's support towards the
  // box is the edge itself (not the opposite corner) can give an edge-edge contact; the
  // others still count as separating axes.
  float se = -__builtin_inff();
  int ke = -1, je = -1;
  vec3 edge_normal;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const vec3 c = cross(box.u[k], t.e[j]);
      const float len_sq = dot(c, c);
      if (!(len_sq > kParallelSq * dot(t.e[j], t.e[j]))) continue;
      const vec3 axis = c / std::sqrt(len_sq);
      const float rb = box.e[k1] * std::abs(dot(box.u[k1], axis)) + box.e[k2] * std::abs(dot(box.u[k2], axis));
      float side;
      const float s = axis_gap(t, axis, rb, &side, p);
      if (!(s < margin)) return;
      const float edge_lo = gyro::min(p[j], p[j == 2 ? 0 : j + 1]), edge_hi = gyro::max(p[j], p[j == 2 ? 0 : j + 1]);
      const float opposite = p[(j + 2) % 3];
      const bool supports = side > 0.0f ? edge_hi <= opposite : edge_lo >= opposite;
      if (supports && s > se) se = s, ke = k, je = j, edge_normal = axis * side;
    }
  }

  const float size = gyro::min(gyro::max(box.e[0], gyro::max(box.e[1], box.e[2])), 0.5f * std::sqrt(t.longest_sq));
  const bool ref_box = !flat || clearly_larger(sb, st, kFaceRelTol, kFaceAbsTol * size);
  const float sf = ref_box ? sb : st;
  auto edges = [&] {
    vec3 pa;
    const uint32_t ea = box_support_edge(box, ke, edge_normal, &pa);
    const int j1 = je == 2 ? 0 : je + 1;
    out->normal = edge_normal;
    edge_contact(a.center, pa, box.u[ke] * box.e[ke], (t.v[je] + t.v[j1]) * 0.5f, t.e[je] * 0.5f, se,
                 kFeatureEdge | ea << 4 | uint32_t(je), out);
  };
  if (ke >= 0 && clearly_larger(se, sf, kEdgeRelTol, kEdgeAbsTol * size)) return edges();

  if (ref_box) {
    // The box face towards the triangle; the triangle is the incident polygon.
    ClipSide sides[4];
    const FaceFrame f = box_face_frame(a.center, box, kb, side_b, sides);
    ClipVertex poly[3];
    for (int k = 0; k < 3; ++k)
      poly[k] = {dot(t.v[k], f.t1), dot(t.v[k], f.t2), dot(t.v[k], f.normal), uint8_t((k + 2) % 3), uint8_t(k)};
    const uint32_t ref_face = 2u * uint32_t(kb) + (side_b < 0.0f ? 1u : 0u);
    clip_face_contact(f, poly, 3, sides, 4, margin, ref_face << 9 | kTriangleFace << 6, out);
    out->normal = f.normal;
  } else {
    // The triangle's face towards the box (normal -side_t n) in a frame at corner a; its
    // edges' outward normals in that frame are the side planes.
    FaceFrame f;
    f.origin = b.a;
    f.normal = t.n * -side_t;
    f.t1 = normalized(t.e[0]);
    f.t2 = cross(f.normal, f.t1);
    float x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      const vec3 w = t.v[k] - t.v[0];
      x[k] = dot(w, f.t1), y[k] = dot(w, f.t2);
    }
    const float winding = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]) < 0.0f ? -1.0f : 1.0f;
    ClipSide sides[3];
    for (int j = 0; j < 3; ++j) {
      const int j1 = j == 2 ? 0 : j + 1;
      const float dx = x[j1] - x[j], dy = y[j1] - y[j];
      const float len = std::sqrt(dx * dx + dy * dy);  // > 0: the triangle has a usable normal
      const float nx = winding * dy / len, ny = -winding * dx / len;
      sides[j] = {nx, ny, nx * x[j] + ny * y[j]};
    }
    ClipVertex poly[4];
    const uint32_t inc_face = box_incident_face(box, -t.v[0], f, poly);
    clip_face_contact(f, poly, 4, sides, 3, margin, kFeatureRefB | kTriangleFace << 9 | inc_face << 6, out);
    out->normal = -f.normal;
  }
  if (out->count == 0 && ke >= 0) edges();
}

}  // namespace gyro::detail
