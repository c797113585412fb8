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

// Element `field` of the bodies named by idx[i..i+width).
template <class L> inline L gather(const SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t field) {
  if constexpr (std::is_same_v<L, float>) {
    return reinterpret_cast<const float*>(bodies + idx[i])[field];
  } else {
    alignas(64) float buf[width_v<L>];
    for (std::size_t k = 0; k < width_v<L>; ++k) buf[k] = reinterpret_cast<const float*>(bodies + idx[i + k])[field];
    return load<L>(buf);
  }
}

template <class L> inline V3<L> gather3(const SolverBody* bodies, const uint32_t* idx, std::size_t i, std::size_t field) {
  return {gather<L>(bodies, idx, i, field), gather<L>(bodies, idx, i, field + 1), gather<L>(bodies, idx, i, field + 2)};
}

constexpr std::size_t kV = 0, kW = 3, kDp = 6, kDq = 9;

// Writes v and w back to the dynamic bodies among idx[i..i+width).
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

// Symmetric 3x3 (xx xy xz yy yz zz) times a vector.
template <class L> struct Sym3 {
  L m[6];
  V3<L> operator*(const V3<L>& x) const {
    return {(m[0] * x.x + m[1] * x.y) + m[2] * x.z, (m[1] * x.x + m[3] * x.y) + m[4] * x.z,
            (m[2] * x.x + m[4] * x.y) + m[5] * x.z};
  }
};

template <class L> inline V3<L> rotate(const V3<L>& u, L w, const V3<L>& v) {
  const V3<L> t = cross(u, v) * L(2.0f);
  return (v + t * w) + cross(u, t);
}

template <class L> struct Lanes {
  const ContactKernelArgs& a;
  std::size_t i;
  L field(uint32_t f) const { return load<L>(a.f[f] + i); }
  void set(uint32_t f, L v) const { store(a.f[f] + i, v); }
  V3<L> field3(uint32_t f) const { return {field(f), field(f + 1), field(f + 2)}; }
  Sym3<L> sym(uint32_t f) const { return {{field(f), field(f + 1), field(f + 2), field(f + 3), field(f + 4), field(f + 5)}}; }
};

template <class L> struct Pair {
  V3<L> va, wa, vb, wb;
  L ma, mb;
  Sym3<L> ia, ib;

  // Applies impulse p at anchors ra, rb (equal and opposite).
  void apply(const V3<L>& p, const V3<L>& ra, const V3<L>& rb) {
    va = va - p * ma;
    wa = wa - ia * cross(ra, p);
    vb = vb + p * mb;
    wb = wb + ib * cross(rb, p);
  }
  V3<L> relative_velocity(const V3<L>& ra, const V3<L>& rb) const {
    return (vb + cross(wb, rb)) - (va + cross(wa, ra));
  }
};

template <class L> inline Pair<L> load_pair(const ContactKernelArgs& a, const Lanes<L>& c, std::size_t i) {
  Pair<L> p;
  p.va = gather3<L>(a.bodies, a.body_a, i, kV), p.wa = gather3<L>(a.bodies, a.body_a, i, kW);
  p.vb = gather3<L>(a.bodies, a.body_b, i, kV), p.wb = gather3<L>(a.bodies, a.body_b, i, kW);
  p.ma = c.field(cf::kMassA), p.mb = c.field(cf::kMassB);
  p.ia = c.sym(cf::kIa0), p.ib = c.sym(cf::kIb0);
  return p;
}

template <class L> inline void store_pair(const ContactKernelArgs& a, const Pair<L>& p, std::size_t i) {
  scatter_vw(a.bodies, a.body_a, i, p.va, p.wa);
  scatter_vw(a.bodies, a.body_b, i, p.vb, p.wb);
}

template <class L> void warm_start(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx), t1 = c.field3(cf::kT1x), t2 = c.field3(cf::kT2x);
  for (uint32_t j = 0; j < 4; ++j) {
    const V3<L> ra = c.field3(cf::point_field(j, cf::kRax)), rb = c.field3(cf::point_field(j, cf::kRbx));
    const V3<L> imp = (n * c.field(cf::point_field(j, cf::kNormalImpulse)) +
                       t1 * c.field(cf::point_field(j, cf::kTangentImpulse1))) +
                      t2 * c.field(cf::point_field(j, cf::kTangentImpulse2));
    p.apply(imp, ra, rb);
  }
  store_pair(a, p, i);
}

template <class L> void solve(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx), t1 = c.field3(cf::kT1x), t2 = c.field3(cf::kT2x);
  const L zero(0.0f);

  // Separation now, from the bodies' motion since the step began (anchors rotate with them).
  const V3<L> dpa = gather3<L>(a.bodies, a.body_a, i, kDp), dpb = gather3<L>(a.bodies, a.body_b, i, kDp);
  const V3<L> ua = gather3<L>(a.bodies, a.body_a, i, kDq), ub = gather3<L>(a.bodies, a.body_b, i, kDq);
  const L qwa = gather<L>(a.bodies, a.body_a, i, kDq + 3), qwb = gather<L>(a.bodies, a.body_b, i, kDq + 3);
  const auto immovable = p.ma == zero || p.mb == zero;
  const L bias_rate = select(immovable, L(a.soft_static.bias_rate), L(a.soft.bias_rate));
  const L mass_scale_soft = select(immovable, L(a.soft_static.mass_scale), L(a.soft.mass_scale));
  const L impulse_scale_soft = select(immovable, L(a.soft_static.impulse_scale), L(a.soft.impulse_scale));

  for (uint32_t step = 0; step < 4; ++step) {
    const uint32_t j = a.reverse ? 3 - step : step;
    const V3<L> ra = c.field3(cf::point_field(j, cf::kRax)), rb = c.field3(cf::point_field(j, cf::kRbx));
    const V3<L> d = (dpb - dpa) + (rotate(ub, qwb, rb) - rotate(ua, qwa, ra));
    const L s = dot(d, n) + c.field(cf::point_field(j, cf::kSeparation));
    const L speculative = s * L(a.inv_h);
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
    bias = select(ahead, speculative, bias);
    mass_scale = select(ahead, L(1.0f), mass_scale);
    impulse_scale = select(ahead, zero, impulse_scale);

    const uint32_t fi = cf::point_field(j, cf::kNormalImpulse);
    const L old = c.field(fi);
    const L vn = dot(p.relative_velocity(ra, rb), n);
    const L impulse = (zero - c.field(cf::point_field(j, cf::kNormalMass)) * mass_scale * (vn + bias)) - impulse_scale * old;
    const L total = max(old + impulse, zero);
    const L applied = total - old;
    c.set(fi, total);
    const uint32_t fm = cf::point_field(j, cf::kMaxNormalImpulse);
    c.set(fm, max(c.field(fm), applied));
    p.apply(n * applied, ra, rb);
  }

  const L mu = c.field(cf::kFriction);
  for (uint32_t step = 0; step < 4; ++step) {
    const uint32_t j = a.reverse ? 3 - step : step;
    const V3<L> ra = c.field3(cf::point_field(j, cf::kRax)), rb = c.field3(cf::point_field(j, cf::kRbx));
    const L limit = mu * c.field(cf::point_field(j, cf::kNormalImpulse));
    for (uint32_t k = 0; k < 2; ++k) {
      const V3<L>& t = k == 0 ? t1 : t2;
      const uint32_t fi = cf::point_field(j, k == 0 ? cf::kTangentImpulse1 : cf::kTangentImpulse2);
      const uint32_t fmass = cf::point_field(j, k == 0 ? cf::kTangentMass1 : cf::kTangentMass2);
      const L old = c.field(fi);
      const L vt = dot(p.relative_velocity(ra, rb), t);
      const L total = max(min(old - c.field(fmass) * vt, limit), zero - limit);
      const L applied = total - old;
      c.set(fi, total);
      p.apply(t * applied, ra, rb);
    }
  }
  store_pair(a, p, i);
}

template <class L> void restitution(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c{a, i};
  const L e = c.field(cf::kRestitution);
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  const L zero(0.0f);
  for (uint32_t j = 0; j < 4; ++j) {
    const V3<L> ra = c.field3(cf::point_field(j, cf::kRax)), rb = c.field3(cf::point_field(j, cf::kRbx));
    const L rel = c.field(cf::point_field(j, cf::kRelativeVelocity));
    const auto bounce = (rel < L(-a.restitution_threshold)) && (c.field(cf::point_field(j, cf::kMaxNormalImpulse)) > zero) &&
                        (e > zero);
    const uint32_t fi = cf::point_field(j, cf::kNormalImpulse);
    const L old = c.field(fi);
    const L vn = dot(p.relative_velocity(ra, rb), n);
    const L impulse = zero - c.field(cf::point_field(j, cf::kNormalMass)) * (vn + e * rel);
    const L total = select(bounce, max(old + impulse, zero), old);
    const L applied = total - old;
    c.set(fi, total);
    p.apply(n * applied, ra, rb);
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
