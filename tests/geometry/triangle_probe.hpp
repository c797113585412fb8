// A test kernel that runs every triangle lane template (triangle_lanes.hpp and
// ray_triangle_lanes.hpp) over SoA inputs, one case per lane, so each SIMD level can be
// compared with the scalar level bit for bit.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/shape_arrays.hpp"

#include <cstddef>

namespace gyro {

/// Outputs, one float column each (masks as 1 or 0).
enum TriangleProbeOutput : int {
  kTpContains,
  kTpClosestX, kTpClosestY, kTpClosestZ,
  kTpBaryU, kTpBaryV, kTpBaryW,
  kTpSphere, kTpAabb, kTpObb, kTpPlane, kTpTriangle,
  kTpRayT, kTpRayU, kTpRayV,
  kTpNormalX, kTpNormalY, kTpNormalZ,
  kTriangleProbeOutputs
};

struct TriangleProbeArgs {
  TrianglesView tri;    // the triangle of case i
  TrianglesView other;  // the second triangle of the triangle-triangle test
  const float *px, *py, *pz;  // the point of contains, closest_point, barycentric
  SpheresView sphere;
  AabbsView aabb;
  ObbsView obb;
  PlanesView plane;
  const float *ox, *oy, *oz, *dx, *dy, *dz, *tmin, *tmax;  // the ray
  float* out[kTriangleProbeOutputs];
};

using triangle_probe_fn = void(const TriangleProbeArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(triangle_probe, triangle_probe_fn)

}  // namespace gyro
