// The ray-sphere kernels (closest hit, brute force) over SoA arrays.
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

struct RaySphereArgs {
  const float *ox, *oy, *oz, *dx, *dy, *dz;
  const float* tmin;  // null: 0
  const float* tmax;  // null: +inf
  const float *cx, *cy, *cz, *r;
  std::size_t sphere_count;
  float* t_out;          // +inf on a miss
  uint32_t* index_out;   // 0xFFFFFFFF on a miss
};

/// Rays [begin, end) against all spheres.
using ray_sphere_closest_fn = void(const RaySphereArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(ray_sphere_closest, ray_sphere_closest_fn)

}  // namespace gyro
