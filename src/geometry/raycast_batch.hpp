// The batch raycast kernel: rays (one per lane) against every primitive of one SoA array
// (each broadcast in turn), closest hit or any hit.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/batch_overlap.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

struct RaycastArgs {
  const float *ox, *oy, *oz, *dx, *dy, *dz;
  const float* tmin;  // null: 0
  const float* tmax;  // null: +inf
  ShapeArray prims;
  std::size_t prim_count;
  bool any_hit;        // stop at the first primitive (lowest index) hit in range
  float* t_out;        // +inf on a miss
  uint32_t* index_out; // 0xFFFFFFFF on a miss
};

/// Rays [begin, end).
using raycast_batch_fn = void(const RaycastArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(raycast_batch, raycast_batch_fn)

}  // namespace gyro
