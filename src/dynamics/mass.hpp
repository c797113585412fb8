// Mass properties of the body shapes: mass and the diagonal body-frame inertia of solid
// spheres and boxes of uniform density.
#pragma once

#include "gyro/status.hpp"
#include "gyro/world.hpp"

namespace gyro::detail {

struct MassProperties {
  float mass = 0.0f, inv_mass = 0.0f;
  vec3 inv_inertia;  ///< inverse of the diagonal body-frame inertia
};

/// Checks the shape (finite, sizes > 0; planes and meshes only on static bodies) and, for a
/// dynamic body, computes its mass from density or the mass override. Static and kinematic
/// bodies get zero inverse mass and inertia.
Status compute_mass(const BodyDef& def, MassProperties* out);

/// Radius of a sphere around the body's origin enclosing its shape (0 for planes).
float bounding_radius(const ShapeDef& shape);

}  // namespace gyro::detail
