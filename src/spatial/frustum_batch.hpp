// The batch frustum-culling kernel: one shape per lane (spheres, AABBs or OBBs of one SoA
// array) against the six planes of one frustum, broadcast to every lane.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/batch_overlap.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

struct FrustumCullArgs {
  float planes[6][4];  // (nx, ny, nz, d) of left, right, bottom, top, near, far; normals inward
  ShapeArray shapes;   // sphere, aabb or obb
  uint32_t* visible_out;  // 1: intersecting or inside, 0: culled
};

/// Shapes [begin, end).
using frustum_cull_batch_fn = void(const FrustumCullArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(frustum_cull_batch, frustum_cull_batch_fn)

}  // namespace gyro
