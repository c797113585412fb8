// Static colliders shared by particles and soft bodies (see particle_colliders.hpp).
#include "dynamics/particle_colliders.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/raycast.hpp"

#include <algorithm>
#include <cmath>

namespace gyro::detail {

float max_abs3(const vec3& v) {
  const float x = std::abs(v.x), y = std::abs(v.y), z = std::abs(v.z);
  const float m = x > y ? x : y;
  return m > z ? m : z;
}

namespace {

// World <-> hull frame: local = (p - position) * rotation^T, world directions = local * rotation.
vec3 to_hull(const HullCollider& k, const vec3& p) { return (p - k.position) * transpose(k.rotation); }
vec3 hull_normal(const HullCollider& k, uint32_t face) { return k.hull->planes[face].normal * k.rotation; }

// The point of segment a-b closest to p (a for a point capsule).
vec3 closest_on_segment(const vec3& a, const vec3& b, const vec3& p) {
  const vec3 u = b - a;
  const float l2 = dot(u, u);
  if (!(l2 > 0.0f)) return a;
  const float w = dot(p - a, u) / l2;
  return a + u * (w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w));
}

// The capsule's first entry: the end spheres by gyro's raycast, the side by the ray against
// the infinite cylinder where it meets the segment's span. The side root is taken from the
// closest approach (t0 - sqrt((r^2 - |f|^2) / A), f the in-plane offset at t0) rather than
// from b^2 - ac, which cancels catastrophically for a long step past a thin capsule.
RaycastResult raycast_capsule(const CapsuleCollider& k, const vec3& s, const vec3& d) {
  RaycastResult best;
  const float r = k.radius;
  const vec3 q = closest_on_segment(k.a, k.b, s);
  if (dot(s - q, s - q) < r * r) return best;  // strictly inside: no entering crossing
  best.t = 2.0f;
  for (const vec3& end : {k.a, k.b}) {
    const RaycastResult h = raycast(Sphere{end, r}, Ray{s, d}, 0.0f, 1.0f);
    if (h.hit && h.t < best.t) best = h;
  }
  const vec3 u = k.b - k.a;
  const float l2 = dot(u, u);
  if (l2 > 0.0f) {
    const vec3 m = s - k.a;
    const vec3 mp = m - u * (dot(m, u) / l2), dp = d - u * (dot(d, u) / l2);  // across the axis
    const float a = dot(dp, dp);
    const float t0 = a > 0.0f ? -dot(mp, dp) / a : 0.0f;
    if (t0 > 0.0f) {  // moving towards the axis
      const vec3 f = mp + dp * t0;
      const float h2 = r * r - dot(f, f);
      if (h2 >= 0.0f) {
        float t = t0 - std::sqrt(h2 / a);
        if (t < 0.0f) t = 0.0f;  // s is not inside, so only rounding puts the root before it
        const float w = dot(m + d * t, u) / l2;
        const vec3 radial = mp + dp * t;
        const float len = length(radial);
        if (t <= 1.0f && t < best.t && w >= 0.0f && w <= 1.0f && len > 0.0f) {
          best.t = t, best.point = s + d * t, best.normal = radial / len;
          best.hit = true;
        }
      }
    }
  }
  return best;
}

// Cyrus-Beck: the segment is inside face f's moved-out plane where dist + t den <= 0; the
// entry is the latest entering plane, the exit the earliest leaving one.
RaycastResult raycast_hull(const HullCollider& k, const vec3& s, const vec3& d) {
  RaycastResult none;
  const ConvexHull& h = *k.hull;
  const vec3 sl = to_hull(k, s), dl = d * transpose(k.rotation);
  float t_in = -1.0f, t_out = 1.0f;
  int face = -1;
  bool inside = true;
  for (std::size_t f = 0; f < h.face_count(); ++f) {
    const Plane& p = h.planes[f];
    const float dist = dot(p.normal, sl) - (p.distance + k.margin);
    const float den = dot(p.normal, dl);
    inside = inside && dist < 0.0f;
    if (den < 0.0f) {
      const float t = dist / -den;
      if (t > t_in) t_in = t, face = int(f);
    } else if (den > 0.0f) {
      const float t = -dist / den;
      if (t < t_out) t_out = t;
    } else if (dist > 0.0f) {
      return none;  // parallel and outside
    }
  }
  if (inside || face < 0 || !(t_in >= 0.0f) || t_in > t_out) return none;
  RaycastResult r;
  r.hit = true, r.t = t_in + 0.0f, r.point = s + d * r.t, r.normal = hull_normal(k, uint32_t(face));
  return r;
}

}  // namespace

bool first_hit(const Collider& c, const vec3& s, const vec3& d, float* t, vec3* point, vec3* normal) {
  const Ray ray{s, d};
  RaycastResult r;
  switch (c.kind) {
    case ColliderKind::sphere: r = raycast(c.sphere, ray, 0.0f, 1.0f); break;
    case ColliderKind::aabb: r = raycast(c.aabb, ray, 0.0f, 1.0f); break;
    case ColliderKind::obb: r = raycast(c.obb, ray, 0.0f, 1.0f); break;
    case ColliderKind::plane: r = raycast(c.plane, ray, 0.0f, 1.0f); break;
    case ColliderKind::capsule: r = raycast_capsule(c.capsule, s, d); break;
    case ColliderKind::hull: r = raycast_hull(c.hull, s, d); break;
    default: return false;
  }
  if (!r.hit || !(dot(r.normal, d) < 0.0f)) return false;
  *t = r.t, *point = r.point, *normal = r.normal;
  return true;
}

vec3 push_out(const Collider& c, const vec3& p, float extra, vec3* normal) {
  switch (c.kind) {
    case ColliderKind::sphere: {
      const vec3 d = p - c.sphere.center;
      const float d2 = dot(d, d), r = c.sphere.radius;
      if (!(d2 < r * r)) return p;
      const float len = std::sqrt(d2);
      const vec3 n = len > 0.0f ? d / len : vec3{0.0f, 1.0f, 0.0f};
      const vec3 surface = c.sphere.center + n * r;
      if (normal) *normal = n;
      return surface + n * (skin_at(surface) + extra);
    }
    case ColliderKind::aabb:
    case ColliderKind::obb: {
      const bool oriented = c.kind == ColliderKind::obb;
      const vec3 center = oriented ? c.obb.center : c.aabb.center;
      const vec3 half = oriented ? c.obb.half_extents : c.aabb.half_extents;
      const vec3 axes[3] = {oriented ? vec3{c.obb.orientation[0][0], c.obb.orientation[0][1], c.obb.orientation[0][2]} : vec3{1, 0, 0},
                            oriented ? vec3{c.obb.orientation[1][0], c.obb.orientation[1][1], c.obb.orientation[1][2]} : vec3{0, 1, 0},
                            oriented ? vec3{c.obb.orientation[2][0], c.obb.orientation[2][1], c.obb.orientation[2][2]} : vec3{0, 0, 1}};
      const vec3 d = p - center;
      int best = -1;
      float best_depth = 0.0f, best_local = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float local = oriented ? dot(d, axes[k]) : d[k];
        const float depth = half[k] - std::abs(local);
        if (!(depth > 0.0f)) return p;  // outside or on the surface of this slab
        if (best < 0 || depth < best_depth) best = k, best_depth = depth, best_local = local;
      }
      const float side = best_local >= 0.0f ? 1.0f : -1.0f;
      const vec3 n = axes[best] * side;
      const vec3 surface = p + n * best_depth;
      if (normal) *normal = n;
      return surface + n * (skin_at(surface) + extra);
    }
    case ColliderKind::plane: {
      const float depth = c.plane.distance - dot(c.plane.normal, p);
      if (!(depth > 0.0f)) return p;
      const vec3 surface = p + c.plane.normal * depth;
      if (normal) *normal = c.plane.normal;
      return surface + c.plane.normal * (skin_at(surface) + extra);
    }
    case ColliderKind::capsule: {
      const CapsuleCollider& k = c.capsule;
      const vec3 q = closest_on_segment(k.a, k.b, p);
      const vec3 off = p - q;
      const float d2 = dot(off, off);
      if (!(d2 < k.radius * k.radius)) return p;
      const float len = std::sqrt(d2);
      vec3 n{0.0f, 1.0f, 0.0f};
      if (len > 0.0f) {
        n = off / len;
      } else if (!(k.a == k.b)) {
        // On the axis: across it, away from the world axis it is least aligned with.
        const vec3 u = k.b - k.a;
        const vec3 au{std::abs(u.x), std::abs(u.y), std::abs(u.z)};
        const int least = au.x <= au.y && au.x <= au.z ? 0 : (au.y <= au.z ? 1 : 2);
        const vec3 e{least == 0 ? 1.0f : 0.0f, least == 1 ? 1.0f : 0.0f, least == 2 ? 1.0f : 0.0f};
        n = normalized(cross(u, e));
      }
      const vec3 surface = q + n * k.radius;
      if (normal) *normal = n;
      return surface + n * (skin_at(surface) + extra);
    }
    case ColliderKind::hull: {
      const HullCollider& k = c.hull;
      const ConvexHull& h = *k.hull;
      const vec3 local = to_hull(k, p);
      int best = -1;
      float best_depth = 0.0f;
      for (std::size_t f = 0; f < h.face_count(); ++f) {
        const float depth = h.planes[f].distance + k.margin - dot(h.planes[f].normal, local);
        if (!(depth > 0.0f)) return p;  // on or outside this face's plane
        if (best < 0 || depth < best_depth) best = int(f), best_depth = depth;
      }
      if (best < 0) return p;
      const vec3 n = hull_normal(k, uint32_t(best));
      const vec3 surface = p + n * best_depth;
      if (normal) *normal = n;
      return surface + n * (skin_at(surface) + extra);
    }
    default: return p;
  }
}

namespace {

// The box of the vertices in the hull's frame, grown for the margin (see collider_bounds),
// then turned into the world as an OBB's box is.
bool hull_bounds(const HullCollider& k, vec3* lo, vec3* hi) {
  const ConvexHull& h = *k.hull;
  vec3 l = h.vertices[0], u = h.vertices[0], sum{};
  for (const vec3& v : h.vertices) {
    l = {std::min(l.x, v.x), std::min(l.y, v.y), std::min(l.z, v.z)};
    u = {std::max(u.x, v.x), std::max(u.y, v.y), std::max(u.z, v.z)};
    sum = sum + v;
  }
  if (k.margin > 0.0f) {
    // Moving every plane out by m stays inside the hull scaled about an inner point c by
    // 1 + m / r, r = the distance from c to the nearest plane: the scaled plane i sits at
    // h_i (1 + m / r) >= h_i + m from c, since h_i >= r.
    const vec3 c = sum / float(h.vertices.size());
    float r = h.planes[0].distance - dot(h.planes[0].normal, c);
    for (const Plane& p : h.planes) r = std::min(r, p.distance - dot(p.normal, c));
    if (!(r > 0.0f)) return false;
    const float s = 1.0f + k.margin / r;
    l = c + (l - c) * s, u = c + (u - c) * s;
  }
  const vec3 center = ((l + u) * 0.5f) * k.rotation + k.position;
  const vec3 e = aabb_half_extents(k.rotation, (u - l) * 0.5f);
  *lo = center - e, *hi = center + e;
  return true;
}

}  // namespace

bool collider_bounds(const Collider& c, vec3* lo, vec3* hi) {
  switch (c.kind) {
    case ColliderKind::sphere: {
      const vec3 r{c.sphere.radius, c.sphere.radius, c.sphere.radius};
      *lo = c.sphere.center - r, *hi = c.sphere.center + r;
      return true;
    }
    case ColliderKind::aabb: *lo = c.aabb.center - c.aabb.half_extents, *hi = c.aabb.center + c.aabb.half_extents; return true;
    case ColliderKind::obb: {
      const vec3 e = aabb_half_extents(c.obb.orientation, c.obb.half_extents);
      *lo = c.obb.center - e, *hi = c.obb.center + e;
      return true;
    }
    case ColliderKind::capsule: {
      const CapsuleCollider& k = c.capsule;
      const vec3 r{k.radius, k.radius, k.radius};
      *lo = vec3{std::min(k.a.x, k.b.x), std::min(k.a.y, k.b.y), std::min(k.a.z, k.b.z)} - r;
      *hi = vec3{std::max(k.a.x, k.b.x), std::max(k.a.y, k.b.y), std::max(k.a.z, k.b.z)} + r;
      return true;
    }
    case ColliderKind::hull: return hull_bounds(c.hull, lo, hi);
    default: return false;
  }
}

Collider inflated(const Collider& c, float t) {
  Collider out = c;
  switch (c.kind) {
    case ColliderKind::sphere: out.sphere.radius = c.sphere.radius + t; break;
    case ColliderKind::aabb: out.aabb.half_extents = c.aabb.half_extents + vec3{t, t, t}; break;
    case ColliderKind::obb: out.obb.half_extents = c.obb.half_extents + vec3{t, t, t}; break;
    case ColliderKind::plane: out.plane.distance = c.plane.distance + t; break;
    case ColliderKind::capsule: out.capsule.radius = c.capsule.radius + t; break;
    case ColliderKind::hull: out.hull.margin = c.hull.margin + t; break;
    default: break;
  }
  return out;
}

namespace {
// Rotations come from callers' quaternions and matrices: unit, orthogonal rows to 1e-3.
Status check_rows_orthonormal(const mat3& m, const char* what) {
  for (int r = 0; r < 3; ++r)
    for (int q = r; q < 3; ++q) {
      const vec3 a{m[r][0], m[r][1], m[r][2]}, b{m[q][0], m[q][1], m[q][2]};
      if (!(std::abs(dot(a, b) - (r == q ? 1.0f : 0.0f)) <= 1e-3f))
        return fail(Status::invalid_argument, "%s is not orthonormal (rows %d, %d)", what, r, q);
    }
  return Status::ok;
}
}  // namespace

Status to_collider(const Sphere& sphere, Collider* out) {
  if (!gyro::is_finite(sphere.center) || !is_finite(sphere.radius)) return fail(Status::non_finite, "sphere collider is not finite");
  if (sphere.radius < 0.0f) return fail(Status::invalid_argument, "sphere collider radius %g is negative", double(sphere.radius));
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::sphere, c.sphere = sphere;
  return Status::ok;
}

Status to_collider(const AABB& box, Collider* out) {
  if (!gyro::is_finite(box.center) || !gyro::is_finite(box.half_extents)) return fail(Status::non_finite, "AABB collider is not finite");
  if (box.half_extents.x < 0.0f || box.half_extents.y < 0.0f || box.half_extents.z < 0.0f)
    return fail(Status::invalid_argument, "AABB collider has a negative half extent");
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::aabb, c.aabb = box;
  return Status::ok;
}

Status to_collider(const OBB& box, Collider* out) {
  bool finite = gyro::is_finite(box.center) && gyro::is_finite(box.half_extents);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) finite = finite && is_finite(box.orientation[r][k]);
  if (!finite) return fail(Status::non_finite, "OBB collider is not finite");
  if (box.half_extents.x < 0.0f || box.half_extents.y < 0.0f || box.half_extents.z < 0.0f)
    return fail(Status::invalid_argument, "OBB collider has a negative half extent");
  GYRO_TRY(check_rows_orthonormal(box.orientation, "OBB collider orientation"));
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::obb, c.obb = box;
  return Status::ok;
}

Status to_collider(const Plane& plane, Collider* out) {
  if (!gyro::is_finite(plane.normal) || !is_finite(plane.distance)) return fail(Status::non_finite, "plane collider is not finite");
  const float len = length(plane.normal);
  if (!(len > 0.0f) || !is_finite(len)) return fail(Status::invalid_argument, "plane collider normal is zero or too large");
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::plane;
  c.plane = {plane.normal / len, plane.distance / len};
  return Status::ok;
}

Status to_collider(const CapsuleCollider& capsule, Collider* out) {
  if (!gyro::is_finite(capsule.a) || !gyro::is_finite(capsule.b) || !is_finite(capsule.radius))
    return fail(Status::non_finite, "capsule collider is not finite");
  if (capsule.radius < 0.0f) return fail(Status::invalid_argument, "capsule collider radius %g is negative", double(capsule.radius));
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::capsule, c.capsule = capsule;
  return Status::ok;
}

Status to_collider(const HullCollider& hull, Collider* out) {
  if (!hull.hull) return fail(Status::null_argument, "hull collider: the hull is null");
  const ConvexHull& h = *hull.hull;
  if (h.face_count() < 4 || h.vertices.size() < 4)
    return fail(Status::invalid_argument, "hull collider: the hull is empty (%zu faces, %zu vertices)", h.face_count(), h.vertices.size());
  bool finite = gyro::is_finite(hull.position) && is_finite(hull.margin);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) finite = finite && is_finite(hull.rotation[r][k]);
  if (!finite) return fail(Status::non_finite, "hull collider pose or margin is not finite");
  if (hull.margin < 0.0f) return fail(Status::invalid_argument, "hull collider margin %g is negative", double(hull.margin));
  GYRO_TRY(check_rows_orthonormal(hull.rotation, "hull collider rotation"));
  Collider& c = *out;
  c = Collider{};
  c.kind = ColliderKind::hull, c.hull = hull;
  return Status::ok;
}

void hash_collider(const Collider& c, StateHasher& h) {
  h.add_u32(static_cast<uint32_t>(c.kind));
  const float f[] = {c.sphere.center.x, c.sphere.center.y, c.sphere.center.z, c.sphere.radius,
                     c.aabb.center.x, c.aabb.center.y, c.aabb.center.z,
                     c.aabb.half_extents.x, c.aabb.half_extents.y, c.aabb.half_extents.z,
                     c.obb.center.x, c.obb.center.y, c.obb.center.z,
                     c.obb.half_extents.x, c.obb.half_extents.y, c.obb.half_extents.z,
                     c.plane.normal.x, c.plane.normal.y, c.plane.normal.z, c.plane.distance};
  h.add_floats(f);
  h.add_floats({c.obb.orientation.data(), 9});
  // Appended only for the new kinds, so existing colliders keep their hashes.
  if (c.kind == ColliderKind::capsule) {
    const CapsuleCollider& k = c.capsule;
    const float g[] = {k.a.x, k.a.y, k.a.z, k.b.x, k.b.y, k.b.z, k.radius};
    h.add_floats(g);
  } else if (c.kind == ColliderKind::hull) {
    const HullCollider& k = c.hull;
    const float g[] = {k.position.x, k.position.y, k.position.z, k.margin};
    h.add_floats(g);
    h.add_floats({k.rotation.data(), 9});
    h.add_u64(k.hull->vertices.size());
    for (const vec3& v : k.hull->vertices) {
      const float q[] = {v.x, v.y, v.z};
      h.add_floats(q);
    }
    h.add_u64(k.hull->planes.size());
    for (const Plane& p : k.hull->planes) {
      const float q[] = {p.normal.x, p.normal.y, p.normal.z, p.distance};
      h.add_floats(q);
    }
  }
}

}  // namespace gyro::detail
