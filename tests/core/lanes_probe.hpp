// A test kernel that applies every lane operation to pairs of inputs, so each SIMD level
// can be compared with the scalar lane bit for bit (special values included).
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>

namespace gyro {

inline constexpr int kLaneProbeOps = 22;

struct LaneProbeArgs {
  const float* a;
  const float* b;
  float* out[kLaneProbeOps];
};

using lanes_probe_fn = void(const LaneProbeArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(lanes_probe, lanes_probe_fn)
/// The same operations on Quad, the fixed 4-wide lane (four floats at the scalar level).
GYRO_KERNEL(quad_probe, lanes_probe_fn)
/// The same on Oct, the fixed 8-wide lane (one AVX register, or two Quads).
GYRO_KERNEL(oct_probe, lanes_probe_fn)

}  // namespace gyro
