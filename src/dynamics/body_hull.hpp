// BodyHull: a world's own copy of a hull body's ConvexHull, moved into the hull's mass frame
// (centroid at the body origin, principal axes along the body axes) so that the body's
// inertia is diagonal in its frame like every other shape's, and the solver needs no
// inertia rotation. The caller's frame is kept as the shape frame (World::get_shape_frame).
#pragma once

#include "gyro/convex.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

namespace gyro::detail {

struct BodyHull {
  ConvexHull hull;      ///< in the mass frame
  vec3 shape_offset;    ///< the caller's hull frame in the body frame: origin ...
  quat shape_rotation;  ///< ... and rotation (rotate(shape_rotation, v) = principal_axes v)
  AABB local_bounds;    ///< of the vertices, in the mass frame
  float bound_radius = 0.0f;  ///< max |vertex|
  vec3 unit_inertia;    ///< principal moments per unit mass (ascending)
  float volume = 0.0f;
};

/// Builds the mass-frame copy of `hull` (a valid polyhedron from build_convex_hull).
/// invalid_argument when its mass properties cannot be computed (no volume).
Status make_body_hull(const ConvexHull& hull, BodyHull* out);

/// The rotation whose matrix (rows = the rotated x, y, z axes, to_mat3's convention) is m;
/// m must be a proper rotation. Shepperd's method: only + - * / sqrt.
quat quat_from_rows(const mat3& m);

}  // namespace gyro::detail
