// Soft-body passes at this translation unit's SIMD level (see soft_solver.hpp). A spring's
// two particles come from unit-stride loads in a contiguous run and from gathers otherwise;
// both move the same bits, so a run's path never changes a result.
#include "dynamics/soft_solver.hpp"
#include "math/vec3_lanes.hpp"

#include <type_traits>

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::SoftKernelArgs;
using detail::SpringRun;

// The first n lanes (n <= width) of loads, stores, gathers and scatters: a run's last block
// is as wide as the others, with the lanes past its end masked off. Masked loads read no
// memory past the run (another thread may be writing it), masked lanes hold zeros, which
// every pass turns into a skipped spring; stores and scatters write the first n lanes only.
// Each lane still computes exactly what the scalar path computes, so bits do not change.
#if defined(GYRO_ARCH_AVX512)
inline __mmask16 first_lanes(std::size_t n) { return static_cast<__mmask16>((1u << n) - 1u); }
#elif defined(GYRO_ARCH_AVX2)
inline __m256i first_lanes(std::size_t n) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<int>(n)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}
#endif

template <class L> inline L load_n(const float* p, std::size_t n) {
  if constexpr (std::is_same_v<L, float>) {
    return *p;
  } else {
    if (n == width_v<L>) return load<L>(p);
#if defined(GYRO_ARCH_AVX512)
    return L(typename L::batch_f(_mm512_maskz_loadu_ps(first_lanes(n), p)));
#elif defined(GYRO_ARCH_AVX2)
    return L(typename L::batch_f(_mm256_maskload_ps(p, first_lanes(n))));
#else
    alignas(64) float buf[width_v<L>] = {};
    for (std::size_t k = 0; k < n; ++k) buf[k] = p[k];
    return load<L>(buf);
#endif
  }
}

template <class L> inline void store_n(float* p, L v, std::size_t n) {
  if constexpr (std::is_same_v<L, float>) {
    *p = v;
  } else {
    if (n == width_v<L>) return store(p, v);
#if defined(GYRO_ARCH_AVX512)
    _mm512_mask_storeu_ps(p, first_lanes(n), v.v);
#elif defined(GYRO_ARCH_AVX2)
    _mm256_maskstore_ps(p, first_lanes(n), v.v);
#else
    alignas(64) float buf[width_v<L>];
    store(buf, v);
    for (std::size_t k = 0; k < n; ++k) p[k] = buf[k];
#endif
  }
}

// Elements base[idx[k]]: one hardware gather on AVX2 and AVX-512 (xsimd 8.1 inserts lane by
// lane there), through a buffer elsewhere.
template <class L> inline L gather_n(const float* base, const uint32_t* idx, std::size_t n) {
  if constexpr (std::is_same_v<L, float>) {
    return base[*idx];
  } else {
#if defined(GYRO_ARCH_AVX512)
    if (n == width_v<L>) return L(typename L::batch_f(_mm512_i32gather_ps(_mm512_loadu_si512(idx), base, 4)));
    const __mmask16 m = first_lanes(n);
    return L(typename L::batch_f(_mm512_mask_i32gather_ps(_mm512_setzero_ps(), m, _mm512_maskz_loadu_epi32(m, idx), base, 4)));
#elif defined(GYRO_ARCH_AVX2)
    if (n == width_v<L>)
      return L(typename L::batch_f(_mm256_i32gather_ps(base, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx)), 4)));
    const __m256i m = first_lanes(n);
    const __m256i lanes = _mm256_maskload_epi32(reinterpret_cast<const int*>(idx), m);
    return L(typename L::batch_f(_mm256_mask_i32gather_ps(_mm256_setzero_ps(), base, lanes, _mm256_castsi256_ps(m), 4)));
#else
    alignas(64) float buf[width_v<L>] = {};
    for (std::size_t k = 0; k < n; ++k) buf[k] = base[idx[k]];
    return load<L>(buf);
#endif
  }
}

template <class L> inline void scatter_n(float* base, const uint32_t* idx, L v, std::size_t n) {
  if constexpr (std::is_same_v<L, float>) {
    base[*idx] = v;
  } else {
    alignas(64) float buf[width_v<L>];
    store(buf, v);
    for (std::size_t k = 0; k < n; ++k) base[idx[k]] = buf[k];
  }
}

/// One end of a block of springs: particles p0 + k (contiguous) or idx[k] (gathered); a
/// masked block uses only its first n lanes.
template <class L, bool kContiguous, bool kMasked> struct End {
  uint32_t p0;
  const uint32_t* idx;
  std::size_t n;
  L get(const float* base) const {
    if constexpr (kContiguous) return kMasked ? load_n<L>(base + p0, n) : load<L>(base + p0);
    else return gather_n<L>(base, idx, kMasked ? n : width_v<L>);
  }
  /// A per-spring field at solve-order index s.
  L spring(const float* base, std::size_t s) const { return kMasked ? load_n<L>(base + s, n) : load<L>(base + s); }
  V3<L> get3(const float* x, const float* y, const float* z) const { return {get(x), get(y), get(z)}; }
  void put(float* base, L v) const {
    if constexpr (kContiguous) {
      if constexpr (kMasked) store_n<L>(base + p0, v, n);
      else store(base + p0, v);
    } else {
      scatter_n<L>(base, idx, v, kMasked ? n : width_v<L>);
    }
  }
  void put_spring(float* base, std::size_t s, L v) const {
    if constexpr (kMasked) store_n<L>(base + s, v, n);
    else store(base + s, v);
  }
  void put3(float* x, float* y, float* z, const V3<L>& v) const { put(x, v.x), put(y, v.y), put(z, v.z); }
};

// XPBD distance constraint C = |xb - xa| - rest with compliance alpha = 1/k and damping b:
//   dlambda = (-C - alpha~ lambda - gamma n.((xb - qb) - (xa - qa))) / ((1 + gamma)(wa + wb) + alpha~),
//   alpha~ = alpha / h^2, gamma = alpha b / h; xa -= wa dlambda n, xb += wb dlambda n.
// A spring of zero length has no direction and both-pinned springs no mass: both skip.
// Without damping (kDamped false) the gamma terms and the start positions are not read;
// with one pass per sub-step (kAccumulate false) lambda starts at 0 and is not kept.
template <bool kAccumulate, bool kDamped, class E>
inline void xpbd_block(const SoftKernelArgs& g, std::size_t s, const E& ea, const E& eb) {
  using L = decltype(ea.get(g.w));
  const V3<L> xa = ea.get3(g.px, g.py, g.pz), xb = eb.get3(g.px, g.py, g.pz);
  const L wa = ea.get(g.w), wb = eb.get(g.w);
  const V3<L> d = xb - xa;
  const L len = sqrt(dot(d, d));
  const L compliance = ea.spring(g.compliance, s);
  const L at = compliance * L(g.inv_h2);
  L denom = (wa + wb) + at;
  L gamma(0.0f);
  if constexpr (kDamped) {
    gamma = (compliance * ea.spring(g.damping, s)) * L(g.inv_h);
    denom = (L(1.0f) + gamma) * (wa + wb) + at;
  }
  const auto ok = (len > L(0.0f)) && (denom > L(0.0f));
  const V3<L> n = d * (L(1.0f) / select(ok, len, L(1.0f)));
  L num = ea.spring(g.rest, s) - len;
  if constexpr (kDamped) {
    const V3<L> qa = ea.get3(g.qx, g.qy, g.qz), qb = eb.get3(g.qx, g.qy, g.qz);
    num = num - gamma * dot(n, (xb - qb) - (xa - qa));
  }
  L lambda(0.0f);
  if constexpr (kAccumulate) {
    lambda = ea.spring(g.lambda, s);
    num = num - at * lambda;
  }
  const L dl = select(ok, num / select(ok, denom, L(1.0f)), L(0.0f));
  if constexpr (kAccumulate) ea.put_spring(g.lambda, s, lambda + dl);
  ea.put3(g.px, g.py, g.pz, xa - n * (wa * dl));
  eb.put3(g.px, g.py, g.pz, xb + n * (wb * dl));
}

// The book's damped Hooke spring as an impulse over the sub-step: tension f = k C + b dv.n
// pulls a towards b and b towards a.
template <class E> inline void spring_block(const SoftKernelArgs& g, std::size_t s, const E& ea, const E& eb) {
  using L = decltype(ea.get(g.w));
  const V3<L> xa = ea.get3(g.px, g.py, g.pz), xb = eb.get3(g.px, g.py, g.pz);
  const V3<L> va = ea.get3(g.vx, g.vy, g.vz), vb = eb.get3(g.vx, g.vy, g.vz);
  const L wa = ea.get(g.w), wb = eb.get(g.w);
  const V3<L> d = xb - xa;
  const L len = sqrt(dot(d, d));
  const auto ok = len > L(0.0f);
  const V3<L> n = d * (L(1.0f) / select(ok, len, L(1.0f)));
  const L c = len - ea.spring(g.rest, s);
  const L f = ea.spring(g.stiffness, s) * c + ea.spring(g.damping, s) * dot(vb - va, n);
  const L j = select(ok, f * L(g.h), L(0.0f));
  ea.put3(g.vx, g.vy, g.vz, va + n * (wa * j));
  eb.put3(g.vx, g.vy, g.vz, vb - n * (wb * j));
}

template <bool kAccumulate, bool kDamped> struct XpbdOp {
  template <class E> void operator()(const SoftKernelArgs& g, std::size_t s, const E& a, const E& b) const {
    xpbd_block<kAccumulate, kDamped>(g, s, a, b);
  }
};
struct SpringOp {
  template <class E> void operator()(const SoftKernelArgs& g, std::size_t s, const E& a, const E& b) const { spring_block(g, s, a, b); }
};

// Full blocks first, then the run's last, masked block.
template <class Op> void run_blocks(const SoftKernelArgs& g, const SpringRun* runs, std::size_t begin, std::size_t end, Op op) {
  constexpr std::size_t W = width_v<Wide>;
  for (std::size_t r = begin; r < end; ++r) {
    const SpringRun& run = runs[r];
    std::size_t k = 0;
    if (run.contiguous) {
      for (; k + W <= run.count; k += W)
        op(g, run.first + k, End<Wide, true, false>{uint32_t(run.a0 + k), nullptr, W}, End<Wide, true, false>{uint32_t(run.b0 + k), nullptr, W});
      if constexpr (W > 1)
        if (k < run.count)
          op(g, run.first + k, End<Wide, true, true>{uint32_t(run.a0 + k), nullptr, run.count - k},
             End<Wide, true, true>{uint32_t(run.b0 + k), nullptr, run.count - k});
    } else {
      for (; k + W <= run.count; k += W)
        op(g, run.first + k, End<Wide, false, false>{0, g.a + run.first + k, W}, End<Wide, false, false>{0, g.b + run.first + k, W});
      if constexpr (W > 1)
        if (k < run.count)
          op(g, run.first + k, End<Wide, false, true>{0, g.a + run.first + k, run.count - k},
             End<Wide, false, true>{0, g.b + run.first + k, run.count - k});
    }
  }
}

}  // namespace

void soft_predict(const SoftKernelArgs& g, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const auto free = load<L>(g.w + i) > L(0.0f);
    const V3<L> x = load3<L>(g.px, g.py, g.pz, i);
    const V3<L> v0 = load3<L>(g.vx, g.vy, g.vz, i);
    const V3<L> gh{L(g.gx), L(g.gy), L(g.gz)};
    const V3<L> v = vselect(free, (v0 + gh) * L(g.damp), V3<L>{L(0.0f), L(0.0f), L(0.0f)});
    store3(g.qx, g.qy, g.qz, i, x);
    store3(g.vx, g.vy, g.vz, i, v);
    store3(g.px, g.py, g.pz, i, x + v * L(g.h));
  });
}

void soft_update_velocity(const SoftKernelArgs& g, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const auto free = load<L>(g.w + i) > L(0.0f);
    const V3<L> x = load3<L>(g.px, g.py, g.pz, i);
    const V3<L> q = load3<L>(g.qx, g.qy, g.qz, i);
    const V3<L> v = (x - q) * (L(g.inv_h) * L(g.damp));
    store3(g.vx, g.vy, g.vz, i, vselect(free, v, V3<L>{L(0.0f), L(0.0f), L(0.0f)}));
  });
}

void soft_xpbd_runs(const SoftKernelArgs& g, const SpringRun* runs, std::size_t begin, std::size_t end) {
  if (g.accumulate) {
    if (g.damped) run_blocks(g, runs, begin, end, XpbdOp<true, true>{});
    else run_blocks(g, runs, begin, end, XpbdOp<true, false>{});
  } else {
    if (g.damped) run_blocks(g, runs, begin, end, XpbdOp<false, true>{});
    else run_blocks(g, runs, begin, end, XpbdOp<false, false>{});
  }
}

void soft_spring_runs(const SoftKernelArgs& g, const SpringRun* runs, std::size_t begin, std::size_t end) {
  run_blocks(g, runs, begin, end, SpringOp{});
}

}  // namespace gyro::GYRO_ARCH_NS
