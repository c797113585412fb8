// Position integration at this translation unit's SIMD level, one solver body per lane. The
// lanes compute exactly the scalar expressions (the quaternion product with its zero terms,
// normalized()'s sum order); a batch holding a quaternion whose squared length lies outside
// [2^-100, 2^100] (or is NaN), where normalized() rescales, runs the scalar code instead.
#include "dynamics/body_integrate.hpp"
#include "dynamics/solver_body_rows.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

using detail::IntegrateArgs;

void integrate_one(const IntegrateArgs& a, std::size_t b) {
  SolverBody& sb = a.bodies[b];
  const uint32_t i = a.slot_of_body[b];
  const float h = a.h;
  const vec3 v{sb.v[0], sb.v[1], sb.v[2]}, w{sb.w[0], sb.w[1], sb.w[2]};
  const vec3 dp = v * h;
  a.px[i] += dp.x, a.py[i] += dp.y, a.pz[i] += dp.z;
  sb.dp[0] += dp.x, sb.dp[1] += dp.y, sb.dp[2] += dp.z;
  const quat q{a.qx[i], a.qy[i], a.qz[i], a.qw[i]};
  const quat spin = quat{w.x, w.y, w.z, 0.0f} * q;
  const quat qn = normalized(q + spin * (0.5f * h));
  a.qx[i] = qn.x, a.qy[i] = qn.y, a.qz[i] = qn.z, a.qw[i] = qn.w;
  sb.dtheta[0] += w.x * h, sb.dtheta[1] += w.y * h, sb.dtheta[2] += w.z * h;
}

template <class L> L gather_slots(const float* column, const uint32_t* slots, std::size_t i) {
  alignas(64) float buf[width_v<L>];
  for (std::size_t k = 0; k < width_v<L>; ++k) buf[k] = column[slots[i + k]];
  return load<L>(buf);
}
template <class L> void scatter_slots(float* column, const uint32_t* slots, std::size_t i, L value) {
  alignas(64) float buf[width_v<L>];
  store(buf, value);
  for (std::size_t k = 0; k < width_v<L>; ++k) column[slots[i + k]] = buf[k];
}

template <class L> void integrate_lanes(const IntegrateArgs& a, std::size_t i) {
  if constexpr (std::is_same_v<L, float>) {
    integrate_one(a, i);
  } else {
    const uint32_t* slots = a.slot_of_body;
    const L qx = gather_slots<L>(a.qx, slots, i), qy = gather_slots<L>(a.qy, slots, i);
    const L qz = gather_slots<L>(a.qz, slots, i), qw = gather_slots<L>(a.qw, slots, i);
    const Rows8<L> r0 = load_rows<L>(a.bodies, a.solver_index, i, kRowVw);
    const L h(a.h), zero(0.0f);
    const L wx = r0.c[3], wy = r0.c[4], wz = r0.c[5];
    // quat{w, 0} * q, term by term as the scalar product computes it.
    const L sx = ((zero * qx + wx * qw) + wy * qz) - wz * qy;
    const L sy = ((zero * qy - wx * qz) + wy * qw) + wz * qx;
    const L sz = ((zero * qz + wx * qy) - wy * qx) + wz * qw;
    const L sw = ((zero * qw - wx * qx) - wy * qy) - wz * qz;
    const L half_h(0.5f * a.h);
    const L nx = qx + sx * half_h, ny = qy + sy * half_h, nz = qz + sz * half_h, nw = qw + sw * half_h;
    const L sq = ((nx * nx + ny * ny) + nz * nz) + nw * nw;
    if (!all(sq >= L(0x1p-100f) && sq <= L(0x1p+100f))) {
      for (std::size_t k = 0; k < width_v<L>; ++k) integrate_one(a, i + k);
      return;
    }
    const L len = sqrt(sq);
    scatter_slots<L>(a.qx, slots, i, nx / len), scatter_slots<L>(a.qy, slots, i, ny / len);
    scatter_slots<L>(a.qz, slots, i, nz / len), scatter_slots<L>(a.qw, slots, i, nw / len);
    const L dpx = r0.c[0] * h, dpy = r0.c[1] * h, dpz = r0.c[2] * h;
    scatter_slots<L>(a.px, slots, i, gather_slots<L>(a.px, slots, i) + dpx);
    scatter_slots<L>(a.py, slots, i, gather_slots<L>(a.py, slots, i) + dpy);
    scatter_slots<L>(a.pz, slots, i, gather_slots<L>(a.pz, slots, i) + dpz);
    Rows8<L> r1 = load_rows<L>(a.bodies, a.solver_index, i, kRowMotion);
    r1.c[0] = r1.c[0] + dpx, r1.c[1] = r1.c[1] + dpy, r1.c[2] = r1.c[2] + dpz;
    r1.c[3] = r1.c[3] + wx * h, r1.c[4] = r1.c[4] + wy * h, r1.c[5] = r1.c[5] + wz * h;
    store_rows<L>(a.bodies, a.solver_index, i, kRowMotion, r1);
  }
}

}  // namespace

GYRO_FLATTEN void integrate_positions(const IntegrateArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { integrate_lanes<decltype(tag)>(a, i); });
}

}  // namespace gyro::GYRO_ARCH_NS
