// A test kernel that runs every raycast and linetest lane template of ray_lanes.hpp over
// SoA inputs, one ray (or segment) and one primitive per lane, so each SIMD level can be
// compared with the scalar level bit for bit.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/shape_arrays.hpp"

#include <cstddef>

namespace gyro {

/// Outputs per element: t and the normal (x, y, z) for sphere, AABB, OBB, plane
/// (kRaycastProbeT + 4 * shape + {0: t, 1: nx, 2: ny, 3: nz}), then the four linetests
/// (1 or 0) in the same shape order.
enum : int {
  kRaycastProbeSphere = 0,
  kRaycastProbeAabb = 1,
  kRaycastProbeObb = 2,
  kRaycastProbePlane = 3,
  kRaycastProbeLinetest = 16,
  kRaycastProbeOutputs = 20,
};

struct RaycastProbeArgs {
  const float *ox, *oy, *oz, *dx, *dy, *dz, *tmin, *tmax;  // rays; segments run o -> o + d
  SpheresView spheres;
  AabbsView aabbs;
  ObbsView obbs;
  PlanesView planes;
  float* out[kRaycastProbeOutputs];
};

using raycast_probe_fn = void(const RaycastProbeArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(raycast_probe, raycast_probe_fn)

}  // namespace gyro
