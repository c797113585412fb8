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

// Solver bodies are numbered in ascending slot order, so a batch whose first and last slots
// are width - 1 apart covers consecutive slots: one vector load or store instead of a lane
// at a time (whose narrow stores a wide load cannot forward from).
template <class L> bool consecutive(const uint32_t* slots, std::size_t i) {
  return slots[i + width_v<L> - 1] - slots[i] == width_v<L> - 1;
}
template <class L> L gather_slots(const float* column, const uint32_t* slots, std::size_t i) {
  if (consecutive<L>(slots, i)) return load<L>(column + slots[i]);
  alignas(64) float buf[width_v<L>];
  for (std::size_t k = 0; k < width_v<L>; ++k) buf[k] = column[slots[i + k]];
  return load<L>(buf);
}
template <class L> void scatter_slots(float* column, const uint32_t* slots, std::size_t i, L value) {
  if (consecutive<L>(slots, i)) return store(column + slots[i], value);
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


// ------------------------------------------------------------------ velocities

void integrate_velocity_one(const IntegrateArgs& a, std::size_t b) {
  SolverBody& sb = a.bodies[b];
  if (!sb.dynamic) return;
  const uint32_t i = a.slot_of_body[b];
  const float h = a.h;
  const float ld = 1.0f / (1.0f + h * a.linear_damping[i]);
  const float ad = 1.0f / (1.0f + h * a.angular_damping[i]);
  vec3 v{sb.v[0], sb.v[1], sb.v[2]}, w{sb.w[0], sb.w[1], sb.w[2]};
  v = (v + vec3{a.lin_acc[0][b], a.lin_acc[1][b], a.lin_acc[2][b]} * h) * ld;
  w = w + vec3{a.ang_acc[0][b], a.ang_acc[1][b], a.ang_acc[2][b]} * h;
  const float dx = a.inv_ix[i], dy = a.inv_iy[i], dz = a.inv_iz[i];
  if (!(dx == dy && dy == dz) && dx > 0.0f) {
    const quat q{a.qx[i], a.qy[i], a.qz[i], a.qw[i]};
    const vec3 wb = rotate(conjugate(q), w);
    const vec3 ib{1.0f / dx, 1.0f / dy, 1.0f / dz};
    const vec3 iw = ib * wb;
    const vec3 f = cross(wb, iw) * h;
    // J = I + h (skew(wb) I - skew(I wb))
    float j[3][3];
    const float skw[3][3] = {{0.0f, -wb.z, wb.y}, {wb.z, 0.0f, -wb.x}, {-wb.y, wb.x, 0.0f}};
    const float ski[3][3] = {{0.0f, -iw.z, iw.y}, {iw.z, 0.0f, -iw.x}, {-iw.y, iw.x, 0.0f}};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) j[r][c] = (r == c ? ib[r] : 0.0f) + h * (skw[r][c] * ib[c] - ski[r][c]);
    const float c00 = j[1][1] * j[2][2] - j[1][2] * j[2][1];
    const float c01 = j[1][2] * j[2][0] - j[1][0] * j[2][2];
    const float c02 = j[1][0] * j[2][1] - j[1][1] * j[2][0];
    const float det = (j[0][0] * c00 + j[0][1] * c01) + j[0][2] * c02;
    if (std::abs(det) > 0.0f && det - det == 0.0f) {  // det - det is 0 exactly when det is finite
      const float inv = 1.0f / det;
      // x = J^-1 f by the adjugate.
      const float m[3][3] = {{c00, j[0][2] * j[2][1] - j[0][1] * j[2][2], j[0][1] * j[1][2] - j[0][2] * j[1][1]},
                             {c01, j[0][0] * j[2][2] - j[0][2] * j[2][0], j[0][2] * j[1][0] - j[0][0] * j[1][2]},
                             {c02, j[0][1] * j[2][0] - j[0][0] * j[2][1], j[0][0] * j[1][1] - j[0][1] * j[1][0]}};
      const vec3 x{((m[0][0] * f.x + m[0][1] * f.y) + m[0][2] * f.z) * inv,
                   ((m[1][0] * f.x + m[1][1] * f.y) + m[1][2] * f.z) * inv,
                   ((m[2][0] * f.x + m[2][1] * f.y) + m[2][2] * f.z) * inv};
      w = rotate(q, wb - x);
    }
  }
  w = w * ad;
  sb.v[0] = v.x, sb.v[1] = v.y, sb.v[2] = v.z;
  sb.w[0] = w.x, sb.w[1] = w.y, sb.w[2] = w.z;
}

// rotate(q, v) of math_quat.hpp in lanes: v + t w + u x t with u = (x, y, z), t = 2 u x v.
template <class L> V3<L> rotate_lanes(const V3<L>& u, L qw, const V3<L>& v) {
  const V3<L> t = cross(u, v) * L(2.0f);
  return (v + t * qw) + cross(u, t);
}

template <class L> void integrate_velocity_lanes(const IntegrateArgs& a, std::size_t i) {
  if constexpr (std::is_same_v<L, float>) {
    integrate_velocity_one(a, i);
  } else {
    const uint32_t* slots = a.slot_of_body;
    const Rows8<L> r0 = load_rows<L>(a.bodies, a.solver_index, i, kRowVw);
    const L h(a.h), one(1.0f), zero(0.0f);
    const L ld = one / (one + h * gather_slots<L>(a.linear_damping, slots, i));
    const L ad = one / (one + h * gather_slots<L>(a.angular_damping, slots, i));
    const V3<L> la{load<L>(a.lin_acc[0] + i), load<L>(a.lin_acc[1] + i), load<L>(a.lin_acc[2] + i)};
    const V3<L> aa{load<L>(a.ang_acc[0] + i), load<L>(a.ang_acc[1] + i), load<L>(a.ang_acc[2] + i)};
    const V3<L> v = (col3(r0, 0) + la * h) * ld;
    V3<L> w = col3(r0, 3) + aa * h;
    const L dx = gather_slots<L>(a.inv_ix, slots, i), dy = gather_slots<L>(a.inv_iy, slots, i);
    const L dz = gather_slots<L>(a.inv_iz, slots, i);
    const auto gyro = !((dx == dy) && (dy == dz)) && (dx > zero);
    if (any(gyro)) {
      const L qx = gather_slots<L>(a.qx, slots, i), qy = gather_slots<L>(a.qy, slots, i);
      const L qz = gather_slots<L>(a.qz, slots, i), qw = gather_slots<L>(a.qw, slots, i);
      const V3<L> wb = rotate_lanes(V3<L>{-qx, -qy, -qz}, qw, w);
      const V3<L> ib{one / dx, one / dy, one / dz};
      const V3<L> iw{ib.x * wb.x, ib.y * wb.y, ib.z * wb.z};
      const V3<L> f = cross(wb, iw) * h;
      const L ibv[3] = {ib.x, ib.y, ib.z};
      const L skw[3][3] = {{zero, -wb.z, wb.y}, {wb.z, zero, -wb.x}, {-wb.y, wb.x, zero}};
      const L ski[3][3] = {{zero, -iw.z, iw.y}, {iw.z, zero, -iw.x}, {-iw.y, iw.x, zero}};
      L j[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) j[r][c] = (r == c ? ibv[r] : zero) + h * (skw[r][c] * ibv[c] - ski[r][c]);
      const L c00 = j[1][1] * j[2][2] - j[1][2] * j[2][1];
      const L c01 = j[1][2] * j[2][0] - j[1][0] * j[2][2];
      const L c02 = j[1][0] * j[2][1] - j[1][1] * j[2][0];
      const L det = (j[0][0] * c00 + j[0][1] * c01) + j[0][2] * c02;
      const auto solve = gyro && (abs(det) > zero) && (det - det == zero);
      const L inv = one / select(solve, det, one);
      const L m[3][3] = {{c00, j[0][2] * j[2][1] - j[0][1] * j[2][2], j[0][1] * j[1][2] - j[0][2] * j[1][1]},
                         {c01, j[0][0] * j[2][2] - j[0][2] * j[2][0], j[0][2] * j[1][0] - j[0][0] * j[1][2]},
                         {c02, j[0][1] * j[2][0] - j[0][0] * j[2][1], j[0][0] * j[1][1] - j[0][1] * j[1][0]}};
      const V3<L> x{((m[0][0] * f.x + m[0][1] * f.y) + m[0][2] * f.z) * inv,
                    ((m[1][0] * f.x + m[1][1] * f.y) + m[1][2] * f.z) * inv,
                    ((m[2][0] * f.x + m[2][1] * f.y) + m[2][2] * f.z) * inv};
      w = vselect(solve, rotate_lanes(V3<L>{qx, qy, qz}, qw, wb - x), w);
    }
    w = w * ad;
    store_vw(a.bodies, a.solver_index, i, r0, v, w);  // dynamic bodies only
  }
}

}  // namespace

GYRO_FLATTEN void integrate_velocities(const IntegrateArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { integrate_velocity_lanes<decltype(tag)>(a, i); });
}
GYRO_FLATTEN void integrate_positions(const IntegrateArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { integrate_lanes<decltype(tag)>(a, i); });
}

}  // namespace gyro::GYRO_ARCH_NS
