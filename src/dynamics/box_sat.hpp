// Box-box separating axis tests over many pairs at once: the narrowphase stages the box-box
// pairs of a chunk in columns, one kernel call tests them one pair per lane
// (box_sat_lanes.hpp), and the scalar code builds each touching pair's manifold from the
// result (box_manifold in collide_box.cpp). The test is ~60% of a resting box pile's
// narrowphase when run pair by pair: 15 axes of dot products with nothing to branch on.
#pragma once

#include "core/dispatch.hpp"
#include "dynamics/narrowphase.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

/// Input columns, per pair: a's axes (u0, u1, u2, xyz each) and half extents, b's, the
/// centre difference b - a, and the margin.
enum BoxSatInput : uint32_t {
  kSatUa = 0, kSatEa = 9, kSatUb = 12, kSatEb = 21, kSatD = 24, kSatMargin = 27,
  kSatInputs = 28,
};
/// Output columns, per pair: hit (1 or 0), the separations sa, sb, se, the axes ia, jb, ie,
/// je (as floats; -1: no edge pair) and the edge normal.
enum BoxSatOutput : uint32_t {
  kSatHit = 0, kSatSa, kSatSb, kSatSe, kSatIa, kSatJb, kSatIe, kSatJe, kSatNormal,
  kSatOutputs = kSatNormal + 3,
};

struct BoxSatArgs {
  const float* in = nullptr;  ///< column c at in + c * stride
  float* out = nullptr;       ///< column c at out + c * stride
  std::size_t stride = 0;
};

/// The separating axis test's result for one pair, as collide_boxes computes it.
struct BoxSat {
  bool hit = false;
  float sa = 0.0f, sb = 0.0f, se = 0.0f;
  int ia = 0, jb = 0, ie = -1, je = -1;
  vec3 edge_normal;
};

/// collide_boxes() after its separating axis test: the manifold of boxes with centres ca,
/// cb and axes fa, fb whose test gave `sat`.
void box_manifold(const vec3& ca, const BoxAxes& fa, const vec3& cb, const BoxAxes& fb, const BoxSat& sat, float margin,
                  Manifold* out);

}  // namespace detail

/// The separating axis test of the staged pairs [begin, end) (see BoxSatInput, BoxSatOutput).
using box_sat_batch_fn = void(const detail::BoxSatArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(box_sat_batch, box_sat_batch_fn)

}  // namespace gyro
