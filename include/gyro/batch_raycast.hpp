// Batch raycasts over arrays the caller owns (structure of arrays: one pointer per
// component), with no copy. Brute force over the primitives: for scenes, use a BVH.
//
// Ray semantics: a ray is o + t d with t in [tmin, tmax]; d need not be unit length (t is
// then in units of |d|). The hit is the smallest t in range where the ray crosses a
// primitive's surface: a ray that starts inside a sphere reports where it leaves.
// A ray whose |d|^2 is zero, subnormal or overflows never hits. Ties go to the lowest
// primitive index. Results are bit-identical at every SIMD level and thread count.
#pragma once

#include "gyro/shape_arrays.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Rays. tmin and tmax may be null, meaning 0 and +infinity for every ray.
struct RaysView {
  const float* ox = nullptr;
  const float* oy = nullptr;
  const float* oz = nullptr;
  const float* dx = nullptr;
  const float* dy = nullptr;
  const float* dz = nullptr;
  const float* tmin = nullptr;
  const float* tmax = nullptr;
};

/// Per-ray results. primitive is the index hit, or -1 (then t is +infinity and the
/// normal is 0). The normal arrays are optional: all three or none.
struct HitsOut {
  float* t = nullptr;
  int32_t* primitive = nullptr;
  float* nx = nullptr;
  float* ny = nullptr;
  float* nz = nullptr;
};

/// Closest hit of every ray against every sphere. Checks everything first: null arrays,
/// NaN or infinite coordinates (tmax may be +infinity), negative radii or tmin, counts
/// above 2^31 - 1: each returns its status and writes nothing.
Status raycast_spheres_closest(const RaysView& rays, std::size_t ray_count, const SpheresView& spheres,
                               std::size_t sphere_count, const HitsOut& hits);

}  // namespace gyro
