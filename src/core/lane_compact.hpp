// Compaction of eight 32-bit lanes by a mask, for the AVX2 and AVX-512 kernels: the lanes
// whose mask bit is set moved to the front, in order, with one permute. Shared by the GJK
// lanes' pack (gjk_kernels.cpp) and, at the AVX2 level, the BVH walks' ordered push (spatial/bvh_order.hpp;
// AVX-512 compacts there with vpcompressd).
#pragma once

#include "core/arch.hpp"

#include <array>
#include <cstdint>

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
#include <immintrin.h>

namespace gyro::GYRO_ARCH_NS {

// kCompact8[m]: byte k holds the position of m's k-th set bit; byte 0's high nibble holds the
// count (a permute reads only an index's low three bits).
inline constexpr std::array<uint64_t, 256> kCompact8 = [] {
  std::array<uint64_t, 256> t{};
  for (unsigned m = 0; m < 256; ++m) {
    uint64_t v = 0;
    unsigned n = 0;
    for (unsigned i = 0; i < 8; ++i)
      if (m >> i & 1u) v |= uint64_t(i) << (8 * n++);
    t[m] = v | uint64_t(n) << 4;
  }
  return t;
}();

/// The permutation (for _mm256_permutevar8x32_*) that moves mask's lanes to the front.
inline __m256i compact_indices(unsigned mask) {
  return _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(int64_t(kCompact8[mask & 255u])));
}

/// How many lanes mask keeps (no popcnt instruction at the AVX2 level's flags).
inline unsigned compact_count(unsigned mask) { return unsigned(kCompact8[mask & 255u] >> 4 & 15u); }

}  // namespace gyro::GYRO_ARCH_NS

#endif
