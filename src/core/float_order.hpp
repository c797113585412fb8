// A float's bits as an unsigned integer in the float's order, for sorting and for
// branch-free minimum searches over integer keys.
#pragma once

#include <bit>
#include <cstdint>

namespace gyro::detail {

/// Order-preserving map of a float's bits to uint32: a < b as floats (neither NaN) implies
/// sortable_bits(a) < sortable_bits(b). -0 maps just below +0 (callers that need the two
/// zeros to tie add +0.0f first, which turns -0 into +0).
inline uint32_t sortable_bits(float f) {
  const uint32_t u = std::bit_cast<uint32_t>(f);
  // Negative: every bit flipped (~u); otherwise the sign bit set. Without a branch.
  return u ^ (uint32_t(std::bit_cast<int32_t>(u) >> 31) | 0x80000000u);
}

}  // namespace gyro::detail
