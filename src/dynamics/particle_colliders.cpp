// Static colliders shared by particles and soft bodies (see particle_colliders.hpp).
#include "dynamics/particle_colliders.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/raycast.hpp"

#include <cmath>

namespace gyro::detail {

float max_abs3(const vec3& v) {
  const float x = std::abs(v.x), y = std::abs(v.y), z = std::abs(v.z);
  const float m = x > y ? x : y;
  return m > z ? m : z;
}

bool first_hit(const Collider& c, const vec3& s, const vec3& d, float* t, vec3* point, vec3* normal) {
  const Ray ray{s, d};
  RaycastResult r;
  switch (c.kind) {
    case ColliderKind::sphere: r = raycast(c.sphere, ray, 0.0f, 1.0f); break;
    case ColliderKind::aabb: r = raycast(c.aabb, ray, 0.0f, 1.0f); break;
    case ColliderKind::obb: r = raycast(c.obb, ray, 0.0f, 1.0f); break;
    case ColliderKind::plane: r = raycast(c.plane, ray, 0.0f, 1.0f); break;
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
    default: return p;
  }
}


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
    default: return false;
  }
}

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
  for (int r = 0; r < 3; ++r) {
    for (int q = r; q < 3; ++q) {
      const vec3 a{box.orientation[r][0], box.orientation[r][1], box.orientation[r][2]};
      const vec3 b{box.orientation[q][0], box.orientation[q][1], box.orientation[q][2]};
      const float want = r == q ? 1.0f : 0.0f;
      if (!(std::abs(dot(a, b) - want) <= 1e-3f))
        return fail(Status::invalid_argument, "OBB collider orientation is not orthonormal (rows %d, %d)", r, q);
    }
  }
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
}

}  // namespace gyro::detail
