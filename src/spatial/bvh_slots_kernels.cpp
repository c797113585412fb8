// bvh_slots_store at this translation unit's SIMD level (bvh_slots.hpp).
#include "spatial/bvh_slots.hpp"

#include <bit>
#include <cstdint>

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
#include <immintrin.h>
#endif

namespace gyro::GYRO_ARCH_NS {

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)

namespace {

// min and max across the eight lanes (vminps and vmaxps return the second operand unless the
// first is strictly less or greater: no NaN here, so that is BoxUnion::grow's choice).
inline float lanes_min(__m256 v) {
  __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}
inline float lanes_max(__m256 v) {
  __m128 m = _mm_max_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_max_ps(m, _mm_movehl_ps(m, m));
  m = _mm_max_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}

}  // namespace

bool bvh_slots_store(detail::BvhNode8& node, const float (&rows)[6][8], float lo[3], float hi[3]) {
  __m256i differ = _mm256_setzero_si256();
  __m256 row[6];
  for (int r = 0; r < 6; ++r) {
    row[r] = _mm256_loadu_ps(rows[r]);
    const __m256i now = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.bounds[r]));
    differ = _mm256_or_si256(differ, _mm256_xor_si256(now, _mm256_castps_si256(row[r])));
  }
  const bool changed = !_mm256_testz_si256(differ, differ);
  if (changed)
    for (int r = 0; r < 6; ++r) _mm256_store_ps(node.bounds[r], row[r]);
  for (int a = 0; a < 3; ++a) lo[a] = lanes_min(row[2 * a]), hi[a] = lanes_max(row[2 * a + 1]);
  return changed;
}

#else  // the scalar, SSE2 and NEON levels: the same choices one slot at a time

bool bvh_slots_store(detail::BvhNode8& node, const float (&rows)[6][8], float lo[3], float hi[3]) {
  bool changed = false;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 8; ++k) changed = changed || std::bit_cast<uint32_t>(rows[r][k]) != std::bit_cast<uint32_t>(node.bounds[r][k]);
  if (changed)
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 8; ++k) node.bounds[r][k] = rows[r][k];
  for (int a = 0; a < 3; ++a) {
    float l = rows[2 * a][0], h = rows[2 * a + 1][0];
    for (int k = 1; k < 8; ++k) l = rows[2 * a][k] < l ? rows[2 * a][k] : l, h = h < rows[2 * a + 1][k] ? rows[2 * a + 1][k] : h;
    lo[a] = l, hi[a] = h;
  }
  return changed;
}

#endif

}  // namespace gyro::GYRO_ARCH_NS
