// The contact solver's passes at this translation unit's SIMD level: one constraint (a
// manifold of up to 4 points) per lane. Body velocities are gathered from the SolverBody
// array, updated point by point (Gauss-Seidel inside the manifold, exactly as the scalar
// path does) and scattered back to the dynamic bodies. Unused points have zero masses and
// impulses, so they compute harmless zeros instead of branching.
#include "dynamics/contact_solver.hpp"
#include "math/vec3_lanes.hpp"

#include <type_traits>

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::ContactKernelArgs;
using detail::SolverBody;
namespace cf = detail;

// Element `field` of the bodies named by idx[i..i+width): one hardware gather on AVX2 and
// AVX-512 (xsimd 8.1's batch::gather inserts lane by lane there, measured 3x slower), lane by
// lane through a buffer elsewhere. Gathers move floats without arithmetic, so every level
// reads the same bits.
template <class L> inline L gather(const SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t field) {
  const float* base = reinterpret_cast<const float*>(bodies) + field;
  if constexpr (std::is_same_v<L, float>) {
    return base[std::size_t(idx[i]) * 16];
  } else {
#if defined(GYRO_ARCH_AVX512)
    const __m512i offsets = _mm512_slli_epi32(_mm512_loadu_si512(idx + i), 4);  // 16 floats a body
    return L(typename L::batch_f(_mm512_i32gather_ps(offsets, base, 4)));
#elif defined(GYRO_ARCH_AVX2)
    const __m256i offsets = _mm256_slli_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx + i)), 4);
    return L(typename L::batch_f(_mm256_i32gather_ps(base, offsets, 4)));
#else
    alignas(64) float buf[width_v<L>];
    for (std::size_t k = 0; k < width_v<L>; ++k) buf[k] = base[std::size_t(idx[i + k]) * 16];
    return load<L>(buf);
#endif
  }
}

template <class L> inline V3<L> gather3(const SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t field) {
  return {gather<L>(bodies, idx, i, field), gather<L>(bodies, idx, i, field + 1), gather<L>(bodies, idx, i, field + 2)};
}

constexpr std::size_t kV = 0, kW = 3, kDp = 6, kDtheta = 9;

// Writes v and w back to the dynamic bodies among idx[i..i+width) (a colour names each
// dynamic body once; static, kinematic and padding lanes are skipped). Lane by lane: an
// AVX-512 masked scatter measured no faster.
template <class L>
inline void scatter_vw(SolverBody* bodies, const uint32_t* idx, std::size_t i, const V3<L>& v, const V3<L>& w) {
  if constexpr (std::is_same_v<L, float>) {
    SolverBody& b = bodies[idx[i]];
    if (b.dynamic) b.v[0] = v.x, b.v[1] = v.y, b.v[2] = v.z, b.w[0] = w.x, b.w[1] = w.y, b.w[2] = w.z;
  } else {
    constexpr std::size_t W = width_v<L>;
    alignas(64) float buf[6][W];
    store(buf[0], v.x), store(buf[1], v.y), store(buf[2], v.z);
    store(buf[3], w.x), store(buf[4], w.y), store(buf[5], w.z);
    for (std::size_t k = 0; k < W; ++k) {
      SolverBody& b = bodies[idx[i + k]];
      if (!b.dynamic) continue;
      b.v[0] = buf[0][k], b.v[1] = buf[1][k], b.v[2] = buf[2][k];
      b.w[0] = buf[3][k], b.w[1] = buf[4][k], b.w[2] = buf[5][k];
    }
  }
}

template <class L> struct Lanes {
  const ContactKernelArgs& a;
  std::size_t i;
  L field(uint32_t f) const { return load<L>(a.f[f] + i); }
  void set(uint32_t f, L v) const { store(a.f[f] + i, v); }
  V3<L> field3(uint32_t f) const { return {field(f), field(f + 1), field(f + 2)}; }
};

template <class L> struct Pair {
  V3<L> va, wa, vb, wb;
  L ma, mb;

  // Velocity of b relative to a along the row at field `base` (direction dir).
  L along(const Lanes<L>& c, uint32_t base, const V3<L>& dir) const {
    return (dot(vb - va, dir) + dot(wb, c.field3(base + cf::kRowArmB))) - dot(wa, c.field3(base + cf::kRowArmA));
  }
  // Applies lambda along that row (equal and opposite).
  void apply(const Lanes<L>& c, uint32_t base, const V3<L>& dir, L lambda) {
    va = va - dir * (lambda * ma);
    wa = wa - c.field3(base + cf::kRowImpA) * lambda;
    vb = vb + dir * (lambda * mb);
    wb = wb + c.field3(base + cf::kRowImpB) * lambda;
  }
  // Angular-only impulse about the normal (twist friction).
  void twist(const Lanes<L>& c, L lambda) {
    wa = wa - c.field3(cf::kTwistImpA) * lambda;
    wb = wb + c.field3(cf::kTwistImpB) * lambda;
  }
};

template <class L> inline Pair<L> load_pair(const ContactKernelArgs& a, const Lanes<L>& c, std::size_t i) {
  Pair<L> p;
  p.va = gather3<L>(a.bodies, a.body_a, i, kV), p.wa = gather3<L>(a.bodies, a.body_a, i, kW);
  p.vb = gather3<L>(a.bodies, a.body_b, i, kV), p.wb = gather3<L>(a.bodies, a.body_b, i, kW);
  p.ma = c.field(cf::kMassA), p.mb = c.field(cf::kMassB);
  return p;
}

template <class L> inline void store_pair(const ContactKernelArgs& a, const Pair<L>& p, std::size_t i) {
  scatter_vw(a.bodies, a.body_a, i, p.va, p.wa);
  scatter_vw(a.bodies, a.body_b, i, p.vb, p.wb);
}

constexpr uint32_t kT1Row = cf::kFrictionBase, kT2Row = cf::kFrictionBase + 12;

template <class L> void warm_start(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  for (uint32_t j = 0; j < 4; ++j) p.apply(c, cf::point_field(j, 0), n, c.field(cf::point_field(j, cf::kNormalImpulse)));
  p.apply(c, kT1Row, c.field3(cf::kT1x), c.field(cf::kTangentImpulse1));
  p.apply(c, kT2Row, c.field3(cf::kT2x), c.field(cf::kTangentImpulse2));
  p.twist(c, c.field(cf::kTwistImpulse));
  store_pair(a, p, i);
}

template <class L> void solve(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  const L zero(0.0f);

  // Separation now, from the bodies' motion since the step began, to first order in the
  // rotation: s = s0 + dot(dpb - dpa, n) + dot(dthb, rb x n) - dot(dtha, ra x n).
  const bool biased = a.mode != detail::BiasMode::none;
  V3<L> dth_a{zero, zero, zero}, dth_b{zero, zero, zero};
  L ds = zero;
  if (biased) {
    const V3<L> dpa = gather3<L>(a.bodies, a.body_a, i, kDp), dpb = gather3<L>(a.bodies, a.body_b, i, kDp);
    dth_a = gather3<L>(a.bodies, a.body_a, i, kDtheta), dth_b = gather3<L>(a.bodies, a.body_b, i, kDtheta);
    ds = dot(dpb - dpa, n);
  }
  const auto immovable = p.ma == zero || p.mb == zero;
  const L bias_rate = select(immovable, L(a.soft_static.bias_rate), L(a.soft.bias_rate));
  const L mass_scale_soft = select(immovable, L(a.soft_static.mass_scale), L(a.soft.mass_scale));
  const L impulse_scale_soft = select(immovable, L(a.soft_static.impulse_scale), L(a.soft.impulse_scale));

  L total_normal = zero;
  for (uint32_t step = 0; step < 4; ++step) {
    const uint32_t j = a.reverse ? 3 - step : step;
    const uint32_t row = cf::point_field(j, 0);
    L s = c.field(row + cf::kSeparation);
    if (biased) s = ((ds + dot(dth_b, c.field3(row + cf::kArmB))) - dot(dth_a, c.field3(row + cf::kArmA))) + s;
    L bias = zero, mass_scale(1.0f), impulse_scale = zero;
    if (a.mode == detail::BiasMode::soft) {
      // No slop here: the soft constraint settles at a penetration of its own (well under a
      // millimetre per contact in a stack), and a slop would add to every contact of a stack.
      bias = max(bias_rate * s, L(-a.max_push));
      mass_scale = mass_scale_soft, impulse_scale = impulse_scale_soft;
    } else if (a.mode == detail::BiasMode::baumgarte) {
      bias = max(L(a.baumgarte_rate) * min(s + L(a.slop), zero), L(-a.max_push));
    }
    const auto ahead = s > zero;
    bias = select(ahead, s * L(a.inv_h), bias);
    mass_scale = select(ahead, L(1.0f), mass_scale);
    impulse_scale = select(ahead, zero, impulse_scale);

    const uint32_t fi = row + cf::kNormalImpulse;
    const L old = c.field(fi);
    const L vn = p.along(c, row, n);
    const L impulse = (zero - c.field(row + cf::kNormalMass) * mass_scale * (vn + bias)) - impulse_scale * old;
    const L total = max(old + impulse, zero);
    const L applied = total - old;
    c.set(fi, total);
    const uint32_t fm = row + cf::kMaxNormalImpulse;
    c.set(fm, max(c.field(fm), applied));
    p.apply(c, row, n, applied);
  }
  for (uint32_t j = 0; j < 4; ++j) total_normal = total_normal + c.field(cf::point_field(j, cf::kNormalImpulse));

  // Patch friction: the tangent impulse stays inside the circle of radius mu * total normal
  // impulse; the twist inside mu * radius * total.
  const L limit = c.field(cf::kFriction) * total_normal;
  const V3<L> t1 = c.field3(cf::kT1x), t2 = c.field3(cf::kT2x);
  const L old1 = c.field(cf::kTangentImpulse1), old2 = c.field(cf::kTangentImpulse2);
  L new1 = old1 - c.field(cf::kTangentMass1) * p.along(c, kT1Row, t1);
  L new2 = old2 - c.field(cf::kTangentMass2) * p.along(c, kT2Row, t2);
  const L len_sq = new1 * new1 + new2 * new2;
  const auto over = len_sq > limit * limit;
  const L scale = select(over, limit / sqrt(select(over, len_sq, L(1.0f))), L(1.0f));
  new1 = new1 * scale, new2 = new2 * scale;
  c.set(cf::kTangentImpulse1, new1), c.set(cf::kTangentImpulse2, new2);
  p.apply(c, kT1Row, t1, new1 - old1);
  p.apply(c, kT2Row, t2, new2 - old2);

  const L twist_limit = limit * c.field(cf::kTwistRadius);
  const L old_t = c.field(cf::kTwistImpulse);
  const L spin = dot(p.wb - p.wa, n);
  const L new_t = max(min(old_t - c.field(cf::kTwistMass) * spin, twist_limit), zero - twist_limit);
  c.set(cf::kTwistImpulse, new_t);
  p.twist(c, new_t - old_t);
  store_pair(a, p, i);
}

template <class L> void restitution(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  const L e = c.field(cf::kRestitution);
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  const L zero(0.0f);
  for (uint32_t j = 0; j < 4; ++j) {
    const uint32_t row = cf::point_field(j, 0);
    const L rel = c.field(row + cf::kRelativeVelocity);
    const auto bounce = (rel < L(-a.restitution_threshold)) && (c.field(row + cf::kMaxNormalImpulse) > zero) && (e > zero);
    const uint32_t fi = row + cf::kNormalImpulse;
    const L old = c.field(fi);
    const L vn = p.along(c, row, n);
    const L impulse = zero - c.field(row + cf::kNormalMass) * (vn + e * rel);
    const L total = select(bounce, max(old + impulse, zero), old);
    const L applied = total - old;
    c.set(fi, total);
    p.apply(c, row, n, applied);
  }
  store_pair(a, p, i);
}

}  // namespace

GYRO_FLATTEN void contact_warm_start(const ContactKernelArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { warm_start<decltype(tag)>(a, i); });
}
GYRO_FLATTEN void contact_solve(const ContactKernelArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { solve<decltype(tag)>(a, i); });
}
GYRO_FLATTEN void contact_restitution(const ContactKernelArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { restitution<decltype(tag)>(a, i); });
}

}  // namespace gyro::GYRO_ARCH_NS
