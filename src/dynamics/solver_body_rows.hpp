// Solver bodies in lanes: a SolverBody is two rows of 8 floats, moved between memory and
// lanes by row loads and transposes. Included by kernel sources only (inside their level's
// namespace).
#pragma once

#include "core/lanes.hpp"
#include "dynamics/contact_solver.hpp"
#include "math/vec3_lanes.hpp"

#include <type_traits>

namespace gyro::GYRO_ARCH_NS {

using detail::SolverBody;

// A SolverBody is two rows of 8 floats: [v, w, dynamic flag, pad] and [dp, dtheta, pad, pad].
// A batch of W constraints reads a row of each of its W bodies and transposes the rows into 8
// lanes of W (and back to write v and w): W row loads and a few shuffles instead of one
// gather per field, and W row stores instead of 6 W scalar stores. Transposes move floats
// without arithmetic, so every level reads and writes the same bits as the float lane.
constexpr std::size_t kRowVw = 0, kRowMotion = 8;

template <class L> struct Rows8 {
  L c[8];  // c[f]: float f of the row, one lane per body
};

#if defined(GYRO_ARCH_AVX2) || defined(GYRO_ARCH_AVX512)
// 8 x 8 transpose within each 256-bit half (x86 AVX2: one half; AVX-512: rows k and k + 8
// share a register, low and high half). Its own inverse.
#if defined(GYRO_ARCH_AVX512)
using RowReg = __m512;
inline RowReg unpack_lo(RowReg a, RowReg b) { return _mm512_unpacklo_ps(a, b); }
inline RowReg unpack_hi(RowReg a, RowReg b) { return _mm512_unpackhi_ps(a, b); }
template <int Imm> inline RowReg shuf(RowReg a, RowReg b) { return _mm512_shuffle_ps(a, b, Imm); }
// Within each 256-bit half: the low 128 bits of a and of b (lo) or their high 128 bits (hi).
inline RowReg halves_lo(RowReg a, RowReg b) {
  return _mm512_permutex2var_ps(a, _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27), b);
}
inline RowReg halves_hi(RowReg a, RowReg b) {
  return _mm512_permutex2var_ps(a, _mm512_setr_epi32(4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31), b);
}
#else
using RowReg = __m256;
inline RowReg unpack_lo(RowReg a, RowReg b) { return _mm256_unpacklo_ps(a, b); }
inline RowReg unpack_hi(RowReg a, RowReg b) { return _mm256_unpackhi_ps(a, b); }
template <int Imm> inline RowReg shuf(RowReg a, RowReg b) { return _mm256_shuffle_ps(a, b, Imm); }
inline RowReg halves_lo(RowReg a, RowReg b) { return _mm256_permute2f128_ps(a, b, 0x20); }
inline RowReg halves_hi(RowReg a, RowReg b) { return _mm256_permute2f128_ps(a, b, 0x31); }
#endif

inline void transpose8(RowReg r[8]) {
  const RowReg t0 = unpack_lo(r[0], r[1]), t1 = unpack_hi(r[0], r[1]);
  const RowReg t2 = unpack_lo(r[2], r[3]), t3 = unpack_hi(r[2], r[3]);
  const RowReg t4 = unpack_lo(r[4], r[5]), t5 = unpack_hi(r[4], r[5]);
  const RowReg t6 = unpack_lo(r[6], r[7]), t7 = unpack_hi(r[6], r[7]);
  const RowReg u0 = shuf<0x44>(t0, t2), u1 = shuf<0xEE>(t0, t2), u2 = shuf<0x44>(t1, t3), u3 = shuf<0xEE>(t1, t3);
  const RowReg u4 = shuf<0x44>(t4, t6), u5 = shuf<0xEE>(t4, t6), u6 = shuf<0x44>(t5, t7), u7 = shuf<0xEE>(t5, t7);
  r[0] = halves_lo(u0, u4), r[1] = halves_lo(u1, u5), r[2] = halves_lo(u2, u6), r[3] = halves_lo(u3, u7);
  r[4] = halves_hi(u0, u4), r[5] = halves_hi(u1, u5), r[6] = halves_hi(u2, u6), r[7] = halves_hi(u3, u7);
}

inline const float* row_ptr(const SolverBody* bodies, uint32_t index, std::size_t row) {
  return reinterpret_cast<const float*>(bodies + index) + row;
}
inline float* row_ptr(SolverBody* bodies, uint32_t index, std::size_t row) {
  return reinterpret_cast<float*>(bodies + index) + row;
}
#endif

template <class L> inline Rows8<L> load_rows(const SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t row) {
  Rows8<L> out;
  if constexpr (std::is_same_v<L, float>) {
    const float* p = reinterpret_cast<const float*>(bodies + idx[i]) + row;
    for (int f = 0; f < 8; ++f) out.c[f] = p[f];
  } else {
#if defined(GYRO_ARCH_AVX512)
    RowReg r[8];
    for (int k = 0; k < 8; ++k) {
      const __m256 lo = _mm256_load_ps(row_ptr(bodies, idx[i + k], row));
      const __m256 hi = _mm256_load_ps(row_ptr(bodies, idx[i + k + 8], row));
      r[k] = _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castps_pd(_mm512_castps256_ps512(lo)), _mm256_castps_pd(hi), 1));
    }
    transpose8(r);
    for (int f = 0; f < 8; ++f) out.c[f] = L(typename L::batch_f(r[f]));
#elif defined(GYRO_ARCH_AVX2)
    RowReg r[8];
    for (int k = 0; k < 8; ++k) r[k] = _mm256_load_ps(row_ptr(bodies, idx[i + k], row));
    transpose8(r);
    for (int f = 0; f < 8; ++f) out.c[f] = L(typename L::batch_f(r[f]));
#else
    constexpr std::size_t W = width_v<L>;
    alignas(64) float buf[8][W];
    for (std::size_t k = 0; k < W; ++k) {
      const float* p = reinterpret_cast<const float*>(bodies + idx[i + k]) + row;
      for (int f = 0; f < 8; ++f) buf[f][k] = p[f];
    }
    for (int f = 0; f < 8; ++f) out.c[f] = load<L>(buf[f]);
#endif
  }
  return out;
}

// Writes all 8 floats of a row of the bodies idx[i + k] whose bit k is set in `lanes` (the
// bodies written must be distinct).
template <class L>
inline void store_rows(SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t row, const Rows8<L>& in,
                       uint32_t lanes = ~0u) {
  if constexpr (std::is_same_v<L, float>) {
    if (!(lanes & 1u)) return;
    float* p = reinterpret_cast<float*>(bodies + idx[i]) + row;
    for (int f = 0; f < 8; ++f) p[f] = in.c[f];
  } else {
#if defined(GYRO_ARCH_AVX512) || defined(GYRO_ARCH_AVX2)
    RowReg r[8];
    for (int f = 0; f < 8; ++f) r[f] = in.c[f].v;
    transpose8(r);
    for (int k = 0; k < 8; ++k) {
#if defined(GYRO_ARCH_AVX512)
      if (lanes & (1u << k)) _mm256_store_ps(row_ptr(bodies, idx[i + k], row), _mm512_castps512_ps256(r[k]));
      if (lanes & (1u << (k + 8)))
        _mm256_store_ps(row_ptr(bodies, idx[i + k + 8], row),
                        _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(r[k]), 1)));
#else
      if (lanes & (1u << k)) _mm256_store_ps(row_ptr(bodies, idx[i + k], row), r[k]);
#endif
    }
#else
    constexpr std::size_t W = width_v<L>;
    alignas(64) float buf[8][W];
    for (int f = 0; f < 8; ++f) store(buf[f], in.c[f]);
    for (std::size_t k = 0; k < W; ++k) {
      if (!(lanes & (1u << k))) continue;
      float* p = reinterpret_cast<float*>(bodies + idx[i + k]) + row;
      for (int f = 0; f < 8; ++f) p[f] = buf[f][k];
    }
#endif
  }
}

// Three consecutive floats of a row (v at 0, w at 3; dp at 0, dtheta at 3).
template <class L> inline V3<L> col3(const Rows8<L>& r, int f) { return {r.c[f], r.c[f + 1], r.c[f + 2]}; }

// Bit k set when body idx[i + k] is dynamic, from the flag lane of its first row as loaded.
template <class L> inline uint32_t dynamic_lanes(const Rows8<L>& row) {
#if defined(GYRO_ARCH_AVX512)
  if constexpr (!std::is_same_v<L, float>) {  // one integer compare into a mask register
    const __m512i flag = _mm512_castps_si512(row.c[6].v);
    return uint32_t(_mm512_cmpneq_epi32_mask(flag, _mm512_setzero_si512()));
  }
#elif defined(GYRO_ARCH_AVX2)
  if constexpr (!std::is_same_v<L, float>) {
    const __m256i zero_flag = _mm256_cmpeq_epi32(_mm256_castps_si256(row.c[6].v), _mm256_setzero_si256());
    return ~uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(zero_flag))) & 0xFFu;
  }
#endif
  alignas(64) uint32_t bits[width_v<L>];
  store_bits(bits, row.c[6]);
  uint32_t lanes = 0;
  for (std::size_t k = 0; k < width_v<L>; ++k) lanes |= (bits[k] != 0u ? 1u : 0u) << k;
  return lanes;
}

// Writes v and w back to the dynamic bodies among idx[i..i+width) (a colour names each
// dynamic body once; static, kinematic and padding lanes are skipped). `row` is the first
// row as loaded: its flag and pad lanes go back unchanged.
template <class L>
inline void store_vw(SolverBody* bodies, const uint32_t* idx, std::size_t i, const Rows8<L>& row, const V3<L>& v,
                     const V3<L>& w) {
  Rows8<L> out = row;
  out.c[0] = v.x, out.c[1] = v.y, out.c[2] = v.z, out.c[3] = w.x, out.c[4] = w.y, out.c[5] = w.z;
  store_rows(bodies, idx, i, kRowVw, out, dynamic_lanes(row));
}

}  // namespace gyro::GYRO_ARCH_NS
