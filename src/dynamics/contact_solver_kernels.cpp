// The contact solver's passes at this translation unit's SIMD level: one constraint (a
// manifold of up to 4 points) per lane. Body velocities are loaded from the SolverBody
// array as transposed rows, updated point by point (Gauss-Seidel inside the manifold, exactly
// as the scalar path does) and stored back to the dynamic bodies. Unused points have zero masses and
// impulses, so they compute harmless zeros instead of branching.
#include "dynamics/contact_solver.hpp"
#include "dynamics/solver_body_rows.hpp"
#include "math/vec3_lanes.hpp"

#include <type_traits>

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::ContactKernelArgs;
using detail::SolverBody;
namespace cf = detail;

// Fields of the constraints (or staged inputs) in lanes i..i+width: blocks of
// kConstraintAlign constraints, `fields` floats each, field f of a block contiguous.
template <class L> struct Lanes {
  float* base;  // field 0 of constraint i; field f lies f * kConstraintAlign floats further
  Lanes(float* data, uint32_t fields, std::size_t i)
      : base(data + ((i / detail::kConstraintAlign) * fields * detail::kConstraintAlign + i % detail::kConstraintAlign)) {}
  Lanes(const ContactKernelArgs& a, std::size_t i) : Lanes(a.f, cf::kConstraintFields, i) {}
  L field(uint32_t f) const { return load<L>(base + std::size_t(f) * detail::kConstraintAlign); }
  void set(uint32_t f, L v) const { store(base + std::size_t(f) * detail::kConstraintAlign, v); }
  V3<L> field3(uint32_t f) const { return {field(f), field(f + 1), field(f + 2)}; }
};
// A batch starts at a multiple of its width (colours and chunks start at multiples of
// kConstraintAlign), so it never straddles two blocks.
static_assert(detail::kConstraintAlign % width_v<Wide> == 0);

template <class L> struct Pair {
  V3<L> va, wa, vb, wb;
  L ma, mb;
  Rows8<L> row_a, row_b;  // as loaded (flag and pad lanes for the write-back)

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
  p.row_a = load_rows<L>(a.bodies, a.body_a, i, kRowVw), p.row_b = load_rows<L>(a.bodies, a.body_b, i, kRowVw);
  p.va = col3(p.row_a, 0), p.wa = col3(p.row_a, 3), p.vb = col3(p.row_b, 0), p.wb = col3(p.row_b, 3);
  p.ma = c.field(cf::kMassA), p.mb = c.field(cf::kMassB);
  return p;
}

template <class L> inline void store_pair(const ContactKernelArgs& a, const Pair<L>& p, std::size_t i) {
  store_vw(a.bodies, a.body_a, i, p.row_a, p.va, p.wa);
  store_vw(a.bodies, a.body_b, i, p.row_b, p.vb, p.wb);
}

constexpr uint32_t kT1Row = cf::kFrictionBase, kT2Row = cf::kFrictionBase + 12;

template <class L> void warm_start(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c(a, i);
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  for (uint32_t j = 0; j < 4; ++j) p.apply(c, cf::point_field(j, 0), n, c.field(cf::point_field(j, cf::kNormalImpulse)));
  p.apply(c, kT1Row, c.field3(cf::kT1x), c.field(cf::kTangentImpulse1));
  p.apply(c, kT2Row, c.field3(cf::kT2x), c.field(cf::kTangentImpulse2));
  p.twist(c, c.field(cf::kTwistImpulse));
  store_pair(a, p, i);
}

template <class L> void solve(const ContactKernelArgs& a, std::size_t i) {
  const Lanes<L> c(a, i);
  Pair<L> p = load_pair(a, c, i);
  const V3<L> n = c.field3(cf::kNx);
  const L zero(0.0f);

  // Separation now, from the bodies' motion since the step began, to first order in the
  // rotation: s = s0 + dot(dpb - dpa, n) + dot(dthb, rb x n) - dot(dtha, ra x n).
  const bool biased = a.mode != detail::BiasMode::none;
  V3<L> dth_a{zero, zero, zero}, dth_b{zero, zero, zero};
  L ds = zero;
  if (biased) {
    const Rows8<L> ma = load_rows<L>(a.bodies, a.body_a, i, kRowMotion), mb = load_rows<L>(a.bodies, a.body_b, i, kRowMotion);
    const V3<L> dpa = col3(ma, 0), dpb = col3(mb, 0);
    dth_a = col3(ma, 3), dth_b = col3(mb, 3);
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
    if (a.track_max_impulse) {
      const uint32_t fm = row + cf::kMaxNormalImpulse;
      c.set(fm, max(c.field(fm), applied));
    }
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
  const Lanes<L> c(a, i);
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


// The symmetric 3x3 matrix m (xx, xy, xz, yy, yz, zz) times x.
template <class L> inline V3<L> sym_mul(const L* m, const V3<L>& x) {
  return {(m[0] * x.x + m[1] * x.y) + m[2] * x.z, (m[1] * x.x + m[3] * x.y) + m[4] * x.z,
          (m[2] * x.x + m[4] * x.y) + m[5] * x.z};
}

// One constraint per lane. Points past the count, and padding lanes (count 0), get zeros.
template <class L> void prepare(const detail::ContactPrepareArgs& a, std::size_t i) {
  const Lanes<L> c(a.f, cf::kConstraintFields, i);
  const Lanes<L> st(const_cast<float*>(a.stage), cf::kStageFields, i);
  const L zero(0.0f), one(1.0f);
  const L count = st.field(cf::kStageCount);
  const auto has = count > zero;
  const V3<L> n = c.field3(cf::kNx);
  const L ma = c.field(cf::kMassA), mb = c.field(cf::kMassB);
  const V3<L> pa = st.field3(cf::kStagePa), pb = st.field3(cf::kStagePb);
  L ia[6], ib[6];
  for (uint32_t q = 0; q < 6; ++q) ia[q] = st.field(cf::kStageIa + q), ib[q] = st.field(cf::kStageIb + q);
  const Rows8<L> row_a = load_rows<L>(a.bodies, a.body_a, i, kRowVw), row_b = load_rows<L>(a.bodies, a.body_b, i, kRowVw);
  const V3<L> va = col3(row_a, 0), wa = col3(row_a, 3), vb = col3(row_b, 0), wb = col3(row_b, 3);

  // A deterministic friction basis from the normal alone (the same normal always gives the
  // same tangents, so impulses carried over from last step point the same way).
  const auto from_xy = abs(n.x) >= L(0.57735f);
  V3<L> t1{select(from_xy, n.y, zero), select(from_xy, -n.x, n.z), select(from_xy, zero, -n.y)};
  const L t_len = sqrt(dot(t1, t1));
  t1 = {t1.x / t_len, t1.y / t_len, t1.z / t_len};
  const V3<L> t2 = cross(n, t1);
  const V3<L> tangent[2] = {t1, t2};
  for (uint32_t q = 0; q < 2; ++q) {
    c.set(cf::kT1x + 3 * q, select(has, tangent[q].x, zero));
    c.set(cf::kT1y + 3 * q, select(has, tangent[q].y, zero));
    c.set(cf::kT1z + 3 * q, select(has, tangent[q].z, zero));
  }

  // A row along d with lever arms ra, rb: arms and inertia images at `base`, and its
  // effective mass (0 where the lane has no such row).
  auto row = [&](uint32_t base, const V3<L>& ra, const V3<L>& rb, const V3<L>& d, auto valid) {
    const V3<L> arm_a = cross(ra, d), arm_b = cross(rb, d);
    const V3<L> imp_a = sym_mul(ia, arm_a), imp_b = sym_mul(ib, arm_b);
    const V3<L> v[4] = {arm_a, arm_b, imp_a, imp_b};
    for (uint32_t q = 0; q < 4; ++q) {
      c.set(base + 3 * q, select(valid, v[q].x, zero));
      c.set(base + 3 * q + 1, select(valid, v[q].y, zero));
      c.set(base + 3 * q + 2, select(valid, v[q].z, zero));
    }
    const L kk = (ma + mb) + (dot(arm_a, imp_a) + dot(arm_b, imp_b));
    const auto ok = valid && kk > zero;
    return select(ok, one / select(ok, kk, one), zero);
  };

  V3<L> centre{zero, zero, zero};
  V3<L> points[4];
  for (uint32_t j = 0; j < 4; ++j) {
    const auto valid = L(float(j)) < count;
    const V3<L> p = st.field3(cf::kStagePoints + 3 * j);
    points[j] = p;
    const V3<L> ra = p - pa, rb = p - pb;
    centre = vselect(valid, centre + p, centre);
    c.set(cf::point_field(j, cf::kNormalMass), row(cf::point_field(j, 0), ra, rb, n, valid));
    const V3<L> dv = (vb + cross(wb, rb)) - (va + cross(wa, ra));
    c.set(cf::point_field(j, cf::kRelativeVelocity), select(valid, dot(dv, n), zero));
  }
  const L safe_count = select(has, count, one);
  centre = {centre.x / safe_count, centre.y / safe_count, centre.z / safe_count};
  L radius = zero;
  for (uint32_t j = 0; j < 4; ++j) {
    const V3<L> d = points[j] - centre;
    radius = select(L(float(j)) < count, radius + sqrt(dot(d, d)), radius);
  }
  c.set(cf::kTwistRadius, select(has, radius / safe_count, zero));
  c.set(cf::kTangentMass1, row(kT1Row, centre - pa, centre - pb, t1, has));
  c.set(cf::kTangentMass2, row(kT2Row, centre - pa, centre - pb, t2, has));
  const V3<L> twist_a = sym_mul(ia, n), twist_b = sym_mul(ib, n);
  c.set(cf::kTwistImpA, select(has, twist_a.x, zero)), c.set(cf::kTwistImpA + 1, select(has, twist_a.y, zero));
  c.set(cf::kTwistImpA + 2, select(has, twist_a.z, zero));
  c.set(cf::kTwistImpB, select(has, twist_b.x, zero)), c.set(cf::kTwistImpB + 1, select(has, twist_b.y, zero));
  c.set(cf::kTwistImpB + 2, select(has, twist_b.z, zero));
  const L kt = dot(n, twist_a) + dot(n, twist_b);
  const auto ok = has && kt > zero;
  c.set(cf::kTwistMass, select(ok, one / select(ok, kt, one), zero));
}

}  // namespace

GYRO_FLATTEN void contact_prepare(const detail::ContactPrepareArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { prepare<decltype(tag)>(a, i); });
}
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
