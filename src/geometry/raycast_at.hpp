// The hit a scalar raycast reports, from a t it already returned: for callers that found t
// another way with the same bits (the scene's ray kernel) and need the point and normal of
// the winner only.
#pragma once

#include "gyro/raycast.hpp"

namespace gyro::detail {

/// raycast(sphere, ray, tmin, tmax) when it returned t: the same bits, without solving for t
/// again. A t of +inf (or NaN) gives the miss.
RaycastResult raycast_at(const Sphere& sphere, const Ray& ray, float t);
/// raycast(box, ray, tmin, tmax) when it returned t, likewise.
RaycastResult raycast_at(const OBB& box, const Ray& ray, float t);

}  // namespace gyro::detail
