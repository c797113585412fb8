// The box-box separating axis test written once over lanes: instantiated with float it is
// collide_boxes()'s test, with a SIMD lane it tests one pair of boxes per lane
// (box_sat_kernels.cpp). Both evaluate the same expressions in the same order, so a lane
// holds exactly the float instantiation's bits for its pair.
//
// Where the scalar test would stop at the first separating axis, the lanes go on (a lane
// cannot leave early); `hit` is false for such a pair and the other results are then
// meaningless, which is all the scalar test promises too.
#pragma once

#include "dynamics/narrowphase.hpp"
#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

template <class L> struct BoxLanes {
  V3<L> u[3];  ///< the box's axes (rows of its orientation)
  L e[3];      ///< half extents
};

template <class L> struct BoxSatLanes {
  decltype(L(0.0f) < L(0.0f)) hit;  ///< no axis separates by margin or more
  L sa, sb, se;  ///< largest separation over a's faces, b's faces, the edge pairs (-inf: none)
  L ia, jb;      ///< their axes, as floats 0..2
  L ie, je;      ///< the edge pair's axes (-1: no usable edge pair)
  V3<L> edge_normal;  ///< unit, from a to b, for the edge pair
};

/// The 15 axes of boxes a and b, d = b's centre - a's centre. Each separation is the gap
/// between the boxes' projections; ties go to the first axis.
template <class L> BoxSatLanes<L> box_sat(const BoxLanes<L>& fa, const BoxLanes<L>& fb, const V3<L>& d, L margin) {
  const L zero(0.0f), minus_inf(-__builtin_inff());
  L ar[3][3];  // |a_i . b_j|
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ar[i][j] = abs(dot(fa.u[i], fb.u[j]));

  BoxSatLanes<L> r;
  r.hit = zero == zero;
  r.sa = minus_inf, r.sb = minus_inf, r.se = minus_inf;
  r.ia = zero, r.jb = zero, r.ie = L(-1.0f), r.je = L(-1.0f);
  r.edge_normal = {zero, zero, zero};
  for (int i = 0; i < 3; ++i) {
    const L rb = (fb.e[0] * ar[i][0] + fb.e[1] * ar[i][1]) + fb.e[2] * ar[i][2];
    const L s = abs(dot(d, fa.u[i])) - (fa.e[i] + rb);
    r.hit = r.hit && s < margin;
    const auto up = s > r.sa;
    r.sa = select(up, s, r.sa), r.ia = select(up, L(float(i)), r.ia);
  }
  for (int j = 0; j < 3; ++j) {
    const L ra = (fa.e[0] * ar[0][j] + fa.e[1] * ar[1][j]) + fa.e[2] * ar[2][j];
    const L s = abs(dot(d, fb.u[j])) - (ra + fb.e[j]);
    r.hit = r.hit && s < margin;
    const auto up = s > r.sb;
    r.sb = select(up, s, r.sb), r.jb = select(up, L(float(j)), r.jb);
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const V3<L> c = cross(fa.u[i], fb.u[j]);
      const L len_sq = dot(c, c);
      // Nearly parallel edges have no usable cross axis (the face axes cover them).
      const auto usable = !(len_sq < L(detail::kParallelSq));
      // The projection radii along c (not normalised): |a_k . (a_i x b_j)| is |a_i' . b_j|
      // for the third axis i', so they come from the face terms.
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const L ra = fa.e[i1] * ar[i2][j] + fa.e[i2] * ar[i1][j];
      const L rb = fb.e[j1] * ar[i][j2] + fb.e[j2] * ar[i][j1];
      const L len = sqrt(select(usable, len_sq, L(1.0f)));
      const L dist = dot(d, c);
      const L s = (abs(dist) - (ra + rb)) / len;
      r.hit = r.hit && (!usable || s < margin);
      const auto up = usable && s > r.se;
      r.se = select(up, s, r.se), r.ie = select(up, L(float(i)), r.ie), r.je = select(up, L(float(j)), r.je);
      r.edge_normal = vselect(up, c * (select(dist < zero, L(-1.0f), L(1.0f)) / len), r.edge_normal);
    }
  }
  return r;
}

}  // namespace gyro::GYRO_ARCH_NS
