// A test kernel that runs every lane template of point_lanes.hpp and overlap_lanes.hpp
// over SoA inputs, so each SIMD level can be compared with the scalar level bit for bit.
//
// Element i reads column k of the input at in[k][i]; the columns hold two spheres, two
// AABBs, two OBBs, two planes, a point and a segment (read as a ray too: o = a, d = b).
// Every template writes one output column per float (masks as 1.0f / 0.0f).
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>

namespace gyro {

// Input columns.
enum OverlapProbeIn : int {
  kInSphereA = 0,    // cx cy cz r
  kInSphereB = 4,
  kInAabbA = 8,      // cx cy cz ex ey ez
  kInAabbB = 14,
  kInObbA = 20,      // cx cy cz ex ey ez u0 u1 u2 (xyz each)
  kInObbB = 35,
  kInPlaneA = 50,    // nx ny nz d
  kInPlaneB = 54,
  kInPoint = 58,     // x y z
  kInSegment = 61,   // ax ay az bx by bz
  kProbeInputs = 67,
};

// Output columns: point tests, then overlaps (canonical order).
enum OverlapProbeOut : int {
  kOutContainsSphere = 0,
  kOutContainsAabb,
  kOutContainsObb,
  kOutContainsPlane,
  kOutContainsSegment,
  kOutContainsRay,
  kOutClosestSphere,  // x y z
  kOutClosestAabb = kOutClosestSphere + 3,
  kOutClosestObb = kOutClosestAabb + 3,
  kOutClosestPlane = kOutClosestObb + 3,
  kOutClosestSegment = kOutClosestPlane + 3,
  kOutClosestRay = kOutClosestSegment + 3,
  kOutSignedDistPlane = kOutClosestRay + 3,
  kOutSignedDistSphere,
  kOutDistSqAabb,
  kOutDistSqObb,
  kPointProbeOutputs,
  kOutSphereSphere = kPointProbeOutputs,
  kOutSphereAabb,
  kOutSphereObb,
  kOutSpherePlane,
  kOutAabbAabb,
  kOutAabbObb,
  kOutAabbPlane,
  kOutObbObb,
  kOutObbPlane,
  kOutPlanePlane,
  kProbeOutputs,
};

struct OverlapProbeArgs {
  const float* in[kProbeInputs];
  float* out[kProbeOutputs];
};

using overlap_probe_fn = void(const OverlapProbeArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(overlap_probe, overlap_probe_fn)

}  // namespace gyro
