// The push of a node's entered children for walks whose rays take turns (scene_kernels.cpp,
// bvh_kernels.cpp), compiled at each including translation unit's level.
//
// Children are pushed in the node's stored front-to-back order for the ray's octant
// (BvhNode8::order), farthest first, so the nearest is on top; nothing sorts entry
// distances. Sorting them cost a chain of branches that depends on how many children a ray
// enters (one, two, several: each a coin toss on incoherent rays) plus an insertion sort,
// together over half of a scene walk's mispredicted branches (R1: 10 of 19.5 per ray). The
// push here has no branch: the entered slots in that order are compacted in one register
// (core/lane_compact.hpp; vpcompressd on AVX-512) and stored whole, codes and entry distances in two
// columns, and the depth grows by their count.
//
// A closest-hit answer does not depend on the visiting order (the kernels' exactness notes:
// ties go to the lower index, and a subtree is skipped only when entered beyond the best t
// by a margin), so this changes speed, never bits. An any-hit answer is the first hit in
// this order: a function of the tree and the ray alone, so the same at every level and
// thread count.
//
// The order is fixed per node and octant, so it is only approximately front to back for a
// ray that starts among the children. Rays walking alone still sort by entry distance, and
// so do the packets (packet_walk.hpp): pushed in this order, LIDAR's packets from a point
// inside the terrain ran 22% slower (CAMERA 4%).
#pragma once

#include "core/lane_compact.hpp"
#include "core/lanes.hpp"
#include "spatial/bvh.hpp"

#include <bit>
#include <cstdint>


namespace gyro::GYRO_ARCH_NS::order {

/// Entries a push may write beyond the new depth: the stack needs this much room past its
/// deepest entry.
inline constexpr int kOverhang = 8;

/// The ray's octant: bit k set when its direction is negative along axis k (the sign of
/// 1/d, so -0 counts as negative, as the slab rows do).
inline unsigned octant(const float inv[3]) {
  unsigned o = 0;
  for (int k = 0; k < 3; ++k) o |= (std::bit_cast<uint32_t>(inv[k]) >> 31) << k;
  return o;
}

/// Pushes the slots true in `entered` (an Oct mask) of `node` (entry distances in tn),
/// farthest first by `node.order[oct]`, onto codes/nears at depth sp; returns the new depth.
template <class Mask>
inline int push(const detail::BvhNode8& node, unsigned oct, const Oct& tn, Mask entered, uint32_t* codes, float* nears,
                int sp) {
#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
  // Lane i: the slot that is (7 - i)-th from the front, so the farthest comes first.
  const __m256i back_to_front = _mm256_and_si256(
      _mm256_srlv_epi32(_mm256_set1_epi32(int(node.order[oct])), _mm256_setr_epi32(28, 24, 20, 16, 12, 8, 4, 0)),
      _mm256_set1_epi32(7));
  const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
#if defined(GYRO_ARCH_AVX512)
  const __m256 in = entered.m;
  // The codes, distances and entered lanes taken in that order, then compacted by the
  // entered bits (vpcompressd): no table of indices, no mask through a general register, and
  // the count is a popcnt (avx512f implies it).
  const __mmask16 in_order = _mm512_mask_test_epi32_mask(
      0xFF, _mm512_castsi256_si512(_mm256_castps_si256(_mm256_permutevar8x32_ps(in, back_to_front))),
      _mm512_set1_epi32(-1));
  const __m512i codes8 = _mm512_castsi256_si512(_mm256_permutevar8x32_epi32(child, back_to_front));
  const __m512 nears8 = _mm512_castps256_ps512(_mm256_permutevar8x32_ps(tn.v, back_to_front));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(codes + sp),
                      _mm512_castsi512_si256(_mm512_maskz_compress_epi32(in_order, codes8)));
  _mm256_storeu_ps(nears + sp, _mm512_castps512_ps256(_mm512_maskz_compress_ps(in_order, nears8)));
  return sp + __builtin_popcount(unsigned(in_order));
#else
  // Bit i: whether that slot was entered (its mask bit moved to the lane's sign).
  const unsigned mask = lane_bits(entered);
  const unsigned in_order = unsigned(_mm256_movemask_ps(
      _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(int(mask)), back_to_front), 31))));
  const __m256i slots = _mm256_permutevar8x32_epi32(back_to_front, compact_indices(in_order));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(codes + sp), _mm256_permutevar8x32_epi32(child, slots));
  _mm256_storeu_ps(nears + sp, _mm256_permutevar8x32_ps(tn.v, slots));
  return sp + int(compact_count(in_order));
#endif
#else
  const unsigned mask = lane_bits(entered);
  alignas(32) float near[8];
  store(near, tn);
  const uint32_t o = node.order[oct];
  for (int j = 7; j >= 0; --j) {  // every slot written, the depth moved past the entered ones
    const unsigned s = o >> (4 * j) & 7u;
    codes[sp] = node.child[s], nears[sp] = near[s];
    sp += int(mask >> s & 1u);
  }
  return sp;
#endif
}

}  // namespace gyro::GYRO_ARCH_NS::order
