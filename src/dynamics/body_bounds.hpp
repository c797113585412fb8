// The axis-aligned box around a body's shape at a given pose: one definition for the
// broadphase, the mesh narrowphase (in the mesh's frame) and the soft bodies' collider
// search, so a new shape is bounded in one place.
#pragma once

#include "dynamics/body_store.hpp"
#include "gyro/triangle_mesh.hpp"

namespace gyro::detail {

/// Planes have no box (callers treat them apart); the result is then the pose's point.
inline AABB shape_bounds(const BodyStore& s, uint32_t i, const vec3& p, const quat& q) {
  switch (BodyShape(s.shape[i])) {
    case BodyShape::sphere: return {p, {s.radius[i], s.radius[i], s.radius[i]}};
    case BodyShape::capsule: {
      const vec3 axis = rotate(q, vec3{0.0f, 1.0f, 0.0f});
      const float r = s.hx[i];
      return {p, abs(axis) * s.hy[i] + vec3{r, r, r}};
    }
    case BodyShape::mesh: {
      const AABB local = s.mesh[i]->bounds();
      return {rotate(q, local.center) + p, aabb_half_extents(to_mat3(q), local.half_extents)};
    }
    case BodyShape::hull: {
      const AABB& local = s.hull[i]->local_bounds;
      return {rotate(q, local.center) + p, aabb_half_extents(to_mat3(q), local.half_extents)};
    }
    case BodyShape::box: return {p, aabb_half_extents(to_mat3(q), vec3{s.hx[i], s.hy[i], s.hz[i]})};
    case BodyShape::plane: break;
  }
  return {p, vec3{}};
}

inline AABB shape_bounds(const BodyStore& s, uint32_t i) { return shape_bounds(s, i, s.position(i), s.orientation(i)); }

}  // namespace gyro::detail
