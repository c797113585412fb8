// Batch raycasts over arrays the caller owns (structure of arrays: one pointer per
// component), with no copy. Brute force over the primitives: for scenes, use a BVH.
//
// Ray semantics: a ray is o + t d with t in [tmin, tmax]; d need not be unit length (t is
// then in units of |d|). The hit is the smallest t in range where the ray crosses a
// primitive's surface: a ray that starts inside a solid reports where it leaves; planes
// and triangles are double-sided. A ray whose |d|^2 is zero, subnormal or overflows never
// hits. Ties go to the lowest primitive index. Triangles are watertight: a ray through a
// shared edge or vertex of a closed mesh hits it. Results are bit-identical at every SIMD
// level and thread count, and equal to the scalar raycast() of gyro/raycast.hpp.
#pragma once

#include "gyro/batch_overlap.hpp"
#include "gyro/shape_arrays.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Every layer: the default of a ray's or a query's mask and of a scene model's layers.
inline constexpr uint32_t kAllLayers = 0xFFFFFFFFu;

/// Rays. tmin and tmax may be null, meaning 0 and +infinity for every ray. mask may be null,
/// meaning kAllLayers for every ray: in a Scene, ray i sees only the models whose
/// ModelDef::layers share a bit with mask[i] (Embree's ray and geometry masks). Queries
/// over primitives without masks (shape arrays, a TriangleMesh) ignore it.
struct RaysView {
  const float* ox = nullptr;
  const float* oy = nullptr;
  const float* oz = nullptr;
  const float* dx = nullptr;
  const float* dy = nullptr;
  const float* dz = nullptr;
  const float* tmin = nullptr;
  const float* tmax = nullptr;
  const uint32_t* mask = nullptr;
};

/// Per-ray results. primitive is the index hit, or -1 (then t is +infinity and the other
/// outputs 0). Optional outputs (null to skip): the unit normal (nx, ny, nz: all three or
/// none; outward for solids, facing the ray for planes and triangles) and, for triangles,
/// the barycentric coordinates u, v of the hit (point = a + u (b - a) + v (c - a); 0 for
/// other primitives).
struct HitsOut {
  float* t = nullptr;
  int32_t* primitive = nullptr;
  float* nx = nullptr;
  float* ny = nullptr;
  float* nz = nullptr;
  float* u = nullptr;
  float* v = nullptr;
};

/// Closest hit of every ray against every primitive of the array. Checks everything
/// first: null arrays, NaN or infinite coordinates (tmax may be +infinity), negative sizes,
/// tmin < 0, counts of 2^31 or more: each returns its status and writes nothing.
Status raycast_closest(const RaysView& rays, std::size_t ray_count, const ShapeArray& prims, std::size_t prim_count,
                       const HitsOut& hits);

/// Any hit (occlusion, line of sight): the lowest-index primitive the ray crosses in
/// [tmin, tmax], and its t. Stops early, so it is faster than closest hit.
Status raycast_any(const RaysView& rays, std::size_t ray_count, const ShapeArray& prims, std::size_t prim_count,
                   const HitsOut& hits);

/// raycast_closest against spheres.
inline Status raycast_spheres_closest(const RaysView& rays, std::size_t ray_count, const SpheresView& spheres,
                                      std::size_t sphere_count, const HitsOut& hits) {
  return raycast_closest(rays, ray_count, shape_array(spheres), sphere_count, hits);
}

}  // namespace gyro
