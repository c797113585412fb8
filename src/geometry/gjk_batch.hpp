// The batch box-box GJK: the relative frames of many box pairs formed over SIMD lanes (one
// pair per lane; the kernel file is compiled once per level), then GJK per pair in gjk.cpp.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/convex.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Frames of up to kMax pairs, SoA; element k is pair begin + k. Computed exactly as
/// gjk.cpp's make_frame computes them (same operations in the same order).
struct BoxFrameBlock {
  static constexpr std::size_t kMax = 128;
  float rot[9][kMax];  // B's rotation in A's frame, rot[3 * r + c] = rot_b.m[r][c]
  float pos[3][kMax];  // B's origin in A's frame
  float scale[kMax];   // the pair's size, at least 1e-30
  uint32_t ok[kMax];   // 1: valid and in the range where the batch answer is exact; 0: run the scalar query
};

/// Pairs [begin, end), end - begin <= BoxFrameBlock::kMax.
using box_frames_fn = void(const ConvexBoxPairs&, std::size_t begin, std::size_t end, BoxFrameBlock&);
GYRO_KERNEL(box_frames, box_frames_fn)

}  // namespace gyro
