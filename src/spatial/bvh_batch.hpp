// The BVH raycast kernel: one ray at a time through the 8-wide BVH (the eight children of a
// node in one 8-wide lane, the four triangles of a leaf in one 4-wide lane), closest hit or
// any hit.
#pragma once

#include "core/dispatch.hpp"
#include "spatial/bvh.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

struct BvhRaycastArgs {
  const detail::Bvh8* bvh;
  const float *ox, *oy, *oz, *dx, *dy, *dz;
  const float* tmin;  // null: 0
  const float* tmax;  // null: +inf
  bool any_hit;
  float* t_out;         // +inf on a miss
  uint32_t* index_out;  // triangle index in input order, 0xFFFFFFFF on a miss
};

/// Rays [begin, end).
using bvh_raycast_fn = void(const BvhRaycastArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(bvh_raycast, bvh_raycast_fn)

}  // namespace gyro
