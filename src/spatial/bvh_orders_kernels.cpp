// bvh_orders_refresh at this translation unit's SIMD level (bvh_orders.hpp).
//
// The AVX levels ask, octant pair by octant pair (o and 7 - o, for o in 0 to 3), whether a
// node's stored orders certainly hold: the used slots' keys gathered in the stored order
// strictly ascend, the empty slots follow in slot order, and the opposite octant's order is
// the same used slots reversed. Strictly ascending keys cannot tie, and octant 7 - o's keys
// are octant o's negated (bvh_build.cpp, OrderKeys), so that is the sort's answer for both.
// A first test in binary32 (unclear_octants) clears most pairs; the rest are tested with the
// binary64 keys, OrderKeys' expressions lane by lane, so the same bits. A pair that fails (an
// order that no longer sorts, tied keys, a stored nibble naming a wrong slot) is sorted again
// by ranks, which writes what the build would; the checks only decide which pairs are sorted,
// so every level leaves the sort's bytes. The other levels call the portable check
// (detail::child_orders_hold) and sort.
#include "spatial/bvh_orders.hpp"

#include "core/lane_compact.hpp"

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
#include <immintrin.h>
#endif

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::BvhNode8;

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)

// The slots of a node, and the stored-order words its empty slots must end every order with.
struct Slots {
  unsigned used;     // bit k: slot k holds a child
  int m;             // how many do
  uint32_t empties;  // the empty slots' nibbles, in slot order, from nibble m up
  uint32_t tail;     // the nibbles from m up
};

inline Slots slots_in(const BvhNode8& n) {
  const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child));
  const unsigned empty = unsigned(_mm256_movemask_ps(
      _mm256_castsi256_ps(_mm256_cmpeq_epi32(child, _mm256_set1_epi32(int(detail::kEmptyChild))))));
  Slots s;
  s.used = ~empty & 255u;
  s.m = int(compact_count(s.used));
  // kCompact8: byte j the j-th empty slot (byte 0's high nibble a count, cleared here); the
  // bytes folded into nibbles.
  uint64_t v = kCompact8[empty] & 0x0707070707070707ull;
  v = (v | v >> 4) & 0x00FF00FF00FF00FFull;
  v = (v | v >> 8) & 0x0000FFFF0000FFFFull;
  v = (v | v >> 16) & 0xFFFFFFFFull;
  s.empties = s.m < 8 ? uint32_t(v) << (4 * s.m) : 0u;
  s.tail = s.m < 8 ? ~0u << (4 * s.m) : 0u;
  return s;
}

// The used slots' nibbles of `order` reversed (nibble j to m - 1 - j), the empty ones dropped.
inline uint32_t reversed_used(uint32_t order, int m) {
  uint32_t rev = __builtin_bswap32(order);
  rev = (rev & 0x0F0F0F0Fu) << 4 | (rev >> 4 & 0x0F0F0F0Fu);  // nibble j at 7 - j
  return rev >> (4 * (8 - m));                                 // 1 <= m <= 8
}

// Whether the stored order of octant o and 7 - o pass every test but the keys' (which the
// level's gather does): no nibble past 7, the empty slots last in slot order, the first
// nibble a used slot (with one used slot there is no pair to compare), and the opposite
// octant's order the used ones reversed.
inline bool words_fit(const Slots& s, uint32_t front, uint32_t back) {
  return ((front & 0x88888888u) | ((front & s.tail) ^ s.empties)) == 0 && (s.used >> (front & 7u) & 1u) != 0 &&
         back == (reversed_used(front, s.m) | s.empties);
}

// words_fit for the four octant pairs at once, lane o for o and 7 - o (the same integer
// tests, so the same answers): bit o set where the pair fits. For 1 <= m <= 8. Four pairs
// one by one were a third of a refit's order checks (R1M, every model moved).
inline unsigned words_fit4(const Slots& s, const BvhNode8& n) {
  const __m128i front = _mm_loadu_si128(reinterpret_cast<const __m128i*>(n.order));
  const __m128i back = _mm_shuffle_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(n.order + 4)), _MM_SHUFFLE(0, 1, 2, 3));
  const __m128i empties = _mm_set1_epi32(int(s.empties));
  const __m128i zero = _mm_setzero_si128();
  const __m128i bad = _mm_or_si128(_mm_and_si128(front, _mm_set1_epi32(int(0x88888888u))),
                                   _mm_xor_si128(_mm_and_si128(front, _mm_set1_epi32(int(s.tail))), empties));
  const __m128i first_used =
      _mm_and_si128(_mm_srlv_epi32(_mm_set1_epi32(int(s.used)), _mm_and_si128(front, _mm_set1_epi32(7))), _mm_set1_epi32(1));
  // reversed_used lane by lane: the bytes swapped, then the nibbles of each byte, then the
  // used nibbles shifted down.
  __m128i rev = _mm_shuffle_epi8(front, _mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12));
  const __m128i low = _mm_set1_epi32(0x0F0F0F0F);
  rev = _mm_or_si128(_mm_slli_epi32(_mm_and_si128(rev, low), 4), _mm_and_si128(_mm_srli_epi32(rev, 4), low));
  rev = _mm_srl_epi32(rev, _mm_cvtsi32_si128(4 * (8 - s.m)));
  const __m128i fit = _mm_and_si128(_mm_and_si128(_mm_cmpeq_epi32(bad, zero), _mm_cmpgt_epi32(first_used, zero)),
                                    _mm_cmpeq_epi32(back, _mm_or_si128(rev, empties)));
  return unsigned(_mm_movemask_ps(_mm_castsi128_ps(fit)));
}

// A node with no used slot: every order is the slots in slot order.
inline bool only_empties(const BvhNode8& n, const Slots& s) {
  for (const uint32_t order : n.order)
    if (order != s.empties) return false;
  return true;
}

// A first check in binary32, one lane a slot: the keys from the centres rounded to float
// (lo + hi) and summed in float stray from the binary64 keys by at most 4 * 2^-24 of S, the
// largest |cx| + |cy| + |cz| among the used slots; so where each next key in a stored order
// exceeds the one before by more than 2^-20 * S (the float difference and S's own rounding
// included, over twice that distance), the binary64 keys strictly ascend there too, and the
// order certainly holds. A node it cannot clear goes to the binary64 check. Most nodes of a
// refit pass here at a third of that check's instructions (R1M, every model moved: 3,030
// nodes a frame).
// Returns the octants o (bits 0-3, each for o and 7 - o) it could not clear.
inline unsigned unclear_octants(const BvhNode8& n, const Slots& s) {
  if (s.m == 0) return 15u;  // the binary64 check's case
  __m256 c[3];
  for (int a = 0; a < 3; ++a) c[a] = _mm256_add_ps(_mm256_load_ps(n.bounds[2 * a]), _mm256_load_ps(n.bounds[2 * a + 1]));
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const __m256 used = _mm256_castsi256_ps(_mm256_cmpgt_epi32(
      _mm256_and_si256(_mm256_set1_epi32(int(s.used)), _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128)), _mm256_setzero_si256()));
  __m256 size = _mm256_add_ps(_mm256_add_ps(_mm256_andnot_ps(sign, c[0]), _mm256_andnot_ps(sign, c[1])), _mm256_andnot_ps(sign, c[2]));
  size = _mm256_and_ps(size, used);  // an empty slot's NaN to 0
  __m128 m = _mm_max_ps(_mm256_castps256_ps128(size), _mm256_extractf128_ps(size, 1));
  m = _mm_max_ps(m, _mm_movehl_ps(m, m));
  m = _mm_max_ss(m, _mm_shuffle_ps(m, m, 1));
  const float margin = 0x1p-20f * _mm_cvtss_f32(m);
  // Not for an overflow or a NaN in a used slot, nor for centres so near 0 that flushed
  // subnormals (the float environment's FTZ and DAZ) could matter beside the margin.
  if (!(margin >= 0x1p-100f && margin < 0x1p100f)) return 15u;
  const __m256 gap = _mm256_set1_ps(margin);
  const __m256 key[4] = {_mm256_add_ps(_mm256_add_ps(c[0], c[1]), c[2]), _mm256_add_ps(_mm256_sub_ps(c[1], c[0]), c[2]),
                         _mm256_add_ps(_mm256_sub_ps(c[0], c[1]), c[2]),
                         _mm256_sub_ps(c[2], _mm256_add_ps(c[0], c[1]))};
  const unsigned want = (1u << (s.m - 1)) - 1u;
  const __m256i shifts = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
  const __m256i next = _mm256_setr_epi32(1, 2, 3, 4, 5, 6, 7, 7);
  unsigned clear = words_fit4(s, n);
  for (int o = 0; o < 4; ++o) {
    const uint32_t front = n.order[o];
    const __m256i slot = _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(front)), shifts), _mm256_set1_epi32(7));
    const __m256 g = _mm256_permutevar8x32_ps(key[o], slot);  // the keys in the stored order
    const __m256 rise = _mm256_sub_ps(_mm256_permutevar8x32_ps(g, next), g);
    clear &= ~(unsigned((unsigned(_mm256_movemask_ps(_mm256_cmp_ps(rise, gap, _CMP_GT_OQ))) & want) != want) << o);
  }
  return ~clear & 15u;
}

#if defined(GYRO_ARCH_AVX512)

// OrderKeys' keys of octants 0 to 3, lane k slot k (an empty slot's: NaN).
struct Keys {
  __m512d key[4];
  explicit Keys(const BvhNode8& n) {
    __m512d c[3];  // the centres' doubles, lo + hi (exact)
    for (int a = 0; a < 3; ++a)
      c[a] = _mm512_add_pd(_mm512_cvtps_pd(_mm256_load_ps(n.bounds[2 * a])), _mm512_cvtps_pd(_mm256_load_ps(n.bounds[2 * a + 1])));
    const __m512d zero = _mm512_setzero_pd();
    const __m512d px = _mm512_add_pd(zero, c[0]), nx = _mm512_sub_pd(zero, c[0]);
    key[0] = _mm512_add_pd(_mm512_add_pd(px, c[1]), c[2]);
    key[1] = _mm512_add_pd(_mm512_add_pd(nx, c[1]), c[2]);
    key[2] = _mm512_add_pd(_mm512_sub_pd(px, c[1]), c[2]);
    key[3] = _mm512_add_pd(_mm512_sub_pd(nx, c[1]), c[2]);
  }
};

// The node's slots and keys come from the caller, which hands the same ones to the sort.
// Of the octants in `which`, those whose stored orders do not certainly hold.
inline unsigned unsorted_octants(const BvhNode8& n, const Slots& s, const Keys& k, unsigned which) {
  if (s.m == 0) return only_empties(n, s) ? 0u : 15u;
  const __m512d* key = k.key;
  const unsigned want = (1u << (s.m - 1)) - 1u;  // the adjacent pairs among the used slots
  const __m256i shifts = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
  const __m512i next = _mm512_setr_epi64(1, 2, 3, 4, 5, 6, 7, 7);
  unsigned unsorted = 0;
  for (int o = 0; o < 4; ++o) {
    if (!(which >> o & 1u)) continue;
    const uint32_t front = n.order[o];
    if (!words_fit(s, front, n.order[7 - o])) {
      unsorted |= 1u << o;
      continue;
    }
    const __m256i slot = _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(front)), shifts), _mm256_set1_epi32(7));
    const __m512d g = _mm512_permutexvar_pd(_mm512_cvtepu32_epi64(slot), key[o]);  // the keys in the stored order
    const unsigned rising = unsigned(_mm512_cmp_pd_mask(g, _mm512_permutexvar_pd(next, g), _CMP_LT_OQ));
    unsorted |= unsigned((rising & want) != want) << o;
  }
  return unsorted;
}

// The octant orders by ranks, as set_orders() defines them: in octant o, used slot i goes to
// place #{j: key_j < key_i} + #{j < i: key_j == key_i}; in octant 7 - o (keys negated) to
// #{j: key_j > key_i} + #{j < i: key_j == key_i}. An empty slot's NaN key compares false with
// everything, so it counts for no one; the empty slots fill the places from m up in slot order.
inline void sort_orders(BvhNode8& n, const Slots& s, const Keys& k, unsigned which) {
  const __m512i one = _mm512_set1_epi64(1), slot = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
  const auto word = [&](__m512i place) {  // the used slots' nibbles at their places
    const __m512i nibbles = _mm512_maskz_sllv_epi64(__mmask8(s.used), slot, _mm512_slli_epi64(place, 2));
    return uint32_t(_mm512_reduce_or_epi64(nibbles)) | s.empties;
  };
  for (int o = 0; o < 4; ++o) {
    if (!(which >> o & 1u)) continue;
    const __m512d key = k.key[o];
    __m512i front = _mm512_setzero_si512(), back = _mm512_setzero_si512();
    for (int j = 0; j < 8; ++j) {
      if (!(s.used >> j & 1u)) continue;
      const __m512d kj = _mm512_permutexvar_pd(_mm512_set1_epi64(j), key);
      const __mmask8 after = __mmask8(0xFF00u >> (7 - j));  // the lanes i > j
      const __mmask8 tie = _mm512_cmp_pd_mask(kj, key, _CMP_EQ_OQ) & after;
      front = _mm512_mask_add_epi64(front, _mm512_cmp_pd_mask(kj, key, _CMP_LT_OQ) | tie, front, one);
      back = _mm512_mask_add_epi64(back, _mm512_cmp_pd_mask(kj, key, _CMP_GT_OQ) | tie, back, one);
    }
    n.order[o] = word(front), n.order[7 - o] = word(back);
  }
}

// Each octant pair is its own sort (order[o] and order[7 - o] from key o alone), so only the
// pairs that fail both checks are sorted again.
inline void refresh(BvhNode8& n) {
  const Slots s = slots_in(n);
  const unsigned unclear = unclear_octants(n, s);
  if (unclear == 0) return;
  const Keys k(n);
  if (const unsigned unsorted = unsorted_octants(n, s, k, unclear)) sort_orders(n, s, k, unsorted);
}

#else  // AVX2: eight doubles in two registers, gathered by 32-bit permutes of their halves

// OrderKeys' keys of octants 0 to 3, slots 0-3 in half 0 and 4-7 in half 1 (an empty slot's: NaN).
struct Keys {
  __m256d key[4][2];
  explicit Keys(const BvhNode8& n) {
    __m256d c[3][2];  // the centres' doubles, lo + hi (exact)
    for (int a = 0; a < 3; ++a) {
      const __m256 lo = _mm256_load_ps(n.bounds[2 * a]), hi = _mm256_load_ps(n.bounds[2 * a + 1]);
      c[a][0] = _mm256_add_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(lo)), _mm256_cvtps_pd(_mm256_castps256_ps128(hi)));
      c[a][1] = _mm256_add_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(lo, 1)), _mm256_cvtps_pd(_mm256_extractf128_ps(hi, 1)));
    }
    const __m256d zero = _mm256_setzero_pd();
    for (int h = 0; h < 2; ++h) {
      const __m256d px = _mm256_add_pd(zero, c[0][h]), nx = _mm256_sub_pd(zero, c[0][h]);
      key[0][h] = _mm256_add_pd(_mm256_add_pd(px, c[1][h]), c[2][h]);
      key[1][h] = _mm256_add_pd(_mm256_add_pd(nx, c[1][h]), c[2][h]);
      key[2][h] = _mm256_add_pd(_mm256_sub_pd(px, c[1][h]), c[2][h]);
      key[3][h] = _mm256_add_pd(_mm256_sub_pd(nx, c[1][h]), c[2][h]);
    }
  }
};

// Of the octants in `which`, those whose stored orders do not certainly hold.
inline unsigned unsorted_octants(const BvhNode8& n, const Slots& s, const Keys& k, unsigned which) {
  if (s.m == 0) return only_empties(n, s) ? 0u : 15u;
  const unsigned want = (1u << (s.m - 1)) - 1u;
  // 32-bit lane 2i + b of half h reads position 4h + i's slot, its half b.
  const __m256i shifts[2] = {_mm256_setr_epi32(0, 0, 4, 4, 8, 8, 12, 12), _mm256_setr_epi32(16, 16, 20, 20, 24, 24, 28, 28)};
  const __m256i odd = _mm256_setr_epi32(0, 1, 0, 1, 0, 1, 0, 1);
  unsigned unsorted = 0;
  for (int o = 0; o < 4; ++o) {
    if (!(which >> o & 1u)) continue;
    const uint32_t front = n.order[o];
    if (!words_fit(s, front, n.order[7 - o])) {
      unsorted |= 1u << o;
      continue;
    }
    const __m256i word = _mm256_set1_epi32(int(front));
    const __m256 key0 = _mm256_castpd_ps(k.key[o][0]), key1 = _mm256_castpd_ps(k.key[o][1]);
    __m256d g[2];  // the keys in the stored order, positions 0-3 and 4-7
    for (int h = 0; h < 2; ++h) {
      const __m256i slot = _mm256_and_si256(_mm256_srlv_epi32(word, shifts[h]), _mm256_set1_epi32(7));
      const __m256i lane = _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(slot, _mm256_set1_epi32(3)), 1), odd);
      const __m256 high = _mm256_castsi256_ps(_mm256_cmpgt_epi32(slot, _mm256_set1_epi32(3)));
      g[h] = _mm256_castps_pd(_mm256_blendv_ps(_mm256_permutevar8x32_ps(key0, lane), _mm256_permutevar8x32_ps(key1, lane), high));
    }
    // The next position's key: positions 1-4 and 5-7 (the last lane compares with itself).
    const __m256d n0 = _mm256_blend_pd(_mm256_permute4x64_pd(g[0], 0x39), _mm256_permute4x64_pd(g[1], 0x00), 0x8);
    const __m256d n1 = _mm256_permute4x64_pd(g[1], 0xF9);
    const unsigned rising = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(g[0], n0, _CMP_LT_OQ))) |
                            unsigned(_mm256_movemask_pd(_mm256_cmp_pd(g[1], n1, _CMP_LT_OQ))) << 4;
    unsorted |= unsigned((rising & want) != want) << o;
  }
  return unsorted;
}

// The octant orders by ranks, as AVX-512's sort_orders() computes them (the same rule,
// set_orders()'s), in two four-lane halves: slot j's key against every slot's, the counts
// in 64-bit lanes (a true compare is -1, subtracted). Six times fewer instructions than the
// portable insertion sorts.
inline void sort_orders(BvhNode8& n, const Slots& s, const Keys& k, unsigned which) {
  alignas(32) static constexpr int64_t kAfter[8][8] = {  // lanes i > j of slots 0-3, then 4-7
      {0, -1, -1, -1, -1, -1, -1, -1}, {0, 0, -1, -1, -1, -1, -1, -1}, {0, 0, 0, -1, -1, -1, -1, -1},
      {0, 0, 0, 0, -1, -1, -1, -1},    {0, 0, 0, 0, 0, -1, -1, -1},    {0, 0, 0, 0, 0, 0, -1, -1},
      {0, 0, 0, 0, 0, 0, 0, -1},       {0, 0, 0, 0, 0, 0, 0, 0}};
  const __m256i slot[2] = {_mm256_setr_epi64x(0, 1, 2, 3), _mm256_setr_epi64x(4, 5, 6, 7)};
  const __m256i used[2] = {
      _mm256_cmpgt_epi64(_mm256_and_si256(_mm256_set1_epi64x(int64_t(s.used)), _mm256_setr_epi64x(1, 2, 4, 8)), _mm256_setzero_si256()),
      _mm256_cmpgt_epi64(_mm256_and_si256(_mm256_set1_epi64x(int64_t(s.used)), _mm256_setr_epi64x(16, 32, 64, 128)),
                         _mm256_setzero_si256())};
  const auto word = [&](const __m256i (&place)[2]) {  // the used slots' nibbles at their places
    __m256i w = _mm256_setzero_si256();
    for (int h = 0; h < 2; ++h)
      w = _mm256_or_si256(w, _mm256_and_si256(used[h], _mm256_sllv_epi64(slot[h], _mm256_slli_epi64(place[h], 2))));
    const __m128i q = _mm_or_si128(_mm256_castsi256_si128(w), _mm256_extracti128_si256(w, 1));
    return uint32_t(_mm_cvtsi128_si64(_mm_or_si128(q, _mm_unpackhi_epi64(q, q)))) | s.empties;
  };
  for (int o = 0; o < 4; ++o) {
    if (!(which >> o & 1u)) continue;
    alignas(32) double key[8];
    _mm256_store_pd(key, k.key[o][0]);
    _mm256_store_pd(key + 4, k.key[o][1]);
    __m256i front[2] = {_mm256_setzero_si256(), _mm256_setzero_si256()};
    __m256i back[2] = {_mm256_setzero_si256(), _mm256_setzero_si256()};
    for (int j = 0; j < 8; ++j) {
      if (!(s.used >> j & 1u)) continue;
      const __m256d kj = _mm256_broadcast_sd(key + j);
      for (int h = 0; h < 2; ++h) {
        const __m256d after = _mm256_load_pd(reinterpret_cast<const double*>(kAfter[j] + 4 * h));
        const __m256d tie = _mm256_and_pd(_mm256_cmp_pd(kj, k.key[o][h], _CMP_EQ_OQ), after);
        front[h] = _mm256_sub_epi64(front[h], _mm256_castpd_si256(_mm256_or_pd(_mm256_cmp_pd(kj, k.key[o][h], _CMP_LT_OQ), tie)));
        back[h] = _mm256_sub_epi64(back[h], _mm256_castpd_si256(_mm256_or_pd(_mm256_cmp_pd(kj, k.key[o][h], _CMP_GT_OQ), tie)));
      }
    }
    n.order[o] = word(front), n.order[7 - o] = word(back);
  }
}

// Each octant pair is its own sort (order[o] and order[7 - o] from key o alone), so only the
// pairs that fail both checks are sorted again.
inline void refresh(BvhNode8& n) {
  const Slots s = slots_in(n);
  const unsigned unclear = unclear_octants(n, s);
  if (unclear == 0) return;
  const Keys k(n);
  if (const unsigned unsorted = unsorted_octants(n, s, k, unclear)) sort_orders(n, s, k, unsorted);
}

#endif

// Every octant pair sorted, whatever the node held (the build's nodes).
inline void set(BvhNode8& n) {
  const Slots s = slots_in(n);
  sort_orders(n, s, Keys(n), 15u);
}

#else  // the scalar and SSE2 levels: the portable check and sort

inline void refresh(BvhNode8& n) {
  if (!detail::child_orders_hold(n)) detail::set_child_orders(n);
}
inline void set(BvhNode8& n) { detail::set_child_orders(n); }

#endif

}  // namespace

void bvh_orders_refresh(BvhNode8* nodes, const uint32_t* which, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) refresh(nodes[which[i]]);
}

void bvh_orders_set(BvhNode8& node) { set(node); }

}  // namespace gyro::GYRO_ARCH_NS
