// Mass properties of the body shapes: mass and the diagonal body-frame inertia of solid
// spheres, boxes, capsules and hulls (in their mass frame) of uniform density.
#pragma once

#include "dynamics/body_hull.hpp"
#include "gyro/status.hpp"
#include "gyro/world.hpp"

namespace gyro::detail {

struct MassProperties {
  float mass = 0.0f, inv_mass = 0.0f;
  vec3 inv_inertia;  ///< inverse of the diagonal body-frame inertia
};

/// Checks the shape (finite, sizes > 0; planes and meshes only on static bodies; a hull
/// needs `hull`, the world's mass-frame copy of def.shape.hull) and, for a dynamic body,
/// computes its mass from density or the mass override. Static and kinematic bodies get
/// zero inverse mass and inertia.
Status compute_mass(const BodyDef& def, const BodyHull* hull, MassProperties* out);

/// Checks what compute_mass checks about the shape alone.
Status check_shape(const BodyDef& def);

/// Radius of a sphere around the body's origin enclosing its shape (0 for planes).
float bounding_radius(const ShapeDef& shape, const BodyHull* hull);

}  // namespace gyro::detail
