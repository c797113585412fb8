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
  // kSeparatedEarly: GJK's first two iterations (run in the lanes, exactly as the scalar loop
  // runs them) already found a separating direction; kFrame: valid, GJK continues per pair
  // from the frame; kScalar: invalid or outside the batch's range, run the scalar query.
  uint32_t code[kMax];
  static constexpr uint32_t kScalar = 0, kFrame = 1, kSeparatedEarly = 2;
};

/// Pairs [begin, end), end - begin <= BoxFrameBlock::kMax. With early (the options allow at
/// least two GJK iterations), pairs GJK separates in its first two iterations are decided.
using box_frames_fn = void(const ConvexBoxPairs&, std::size_t begin, std::size_t end, float touch_tolerance,
                           bool early, BoxFrameBlock&);
GYRO_KERNEL(box_frames, box_frames_fn)

}  // namespace gyro
