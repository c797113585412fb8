// Contact manifolds: what the narrowphase hands the solver for one pair of shapes.
//
// Conventions (every collide_* function in narrowphase.hpp follows them):
//  - The normal is a unit vector pointing from shape A to shape B.
//  - A point lies midway between the two surfaces; separation is the signed gap along the
//    normal (< 0: penetration depth). Points are reported while separation < margin, so the
//    solver can stop bodies that would close the gap within the step (speculative contacts).
//  - Up to 4 points. feature_id names the pair of features a point comes from (e.g. the
//    incident vertex or the clipped edge pair) and stays the same from frame to frame while
//    the configuration persists; the solver matches it to carry accumulated impulses over.
//  - count == 0 means no contact within the margin; the other fields are then unspecified.
//  - Deterministic: a pure function of its inputs, no libm.
#pragma once

#include "gyro/math_vec.hpp"

#include <cstdint>

namespace gyro::detail {

inline constexpr uint32_t kMaxManifoldPoints = 4;

struct ContactPoint {
  vec3 position;       ///< world space, midway between the surfaces
  float separation = 0.0f;
  uint32_t feature_id = 0;
};

/// Where a manifold's points sit on each body, in the bodies' frames (kept only by the
/// incremental convex manifolds, which re-measure old points in later frames).
struct ContactAnchors {
  vec3 a[kMaxManifoldPoints], b[kMaxManifoldPoints];
};

struct Manifold {
  vec3 normal;  ///< unit, from A to B
  uint32_t count = 0;
  ContactPoint points[kMaxManifoldPoints];
};

}  // namespace gyro::detail
