// Boolean GJK's first step for a box pair, written once over lanes: instantiated with float
// it is gjk.cpp's (gjk_typed<box, box>), with a SIMD lane it is box_gjk's start() for one
// pair per lane. Both evaluate the same expressions in the same order, so a lane holds the
// float instantiation's bits for its pair.
//
// The six face normals are tried as separating axes before GJK's loop: for axis L (A's local
// axes e_k, then B's axes r_j, the rows of rot_b, both in A's frame), the gap between the
// pair's projections, gap = |centre distance along L| - (A's extent + B's extent), is held to
// GJK's own early-exit threshold (gap > 0 and gap^2 > threshold^2 |L|^2). B's extent along
// r_j is the sum over i of h_i |r_i . r_j|, exact for any linear B, so a pose that is not
// quite a rotation is still answered right. On N1's random boxes 98% of the separated pairs
// pass (a binary64 count: 163,300 of 166,170); GJK's first iteration had settled 65%, the
// others taking up to 8 iterations (37% of the intersect batch's iterations).
#pragma once

#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

/// Whether a face normal separates the pair (half extents ha, hb; B's rows rot and origin
/// pos in A's frame; sep_sq the squared threshold). Where one does, dir becomes the
/// direction towards B along the first that does (GJK's first support point is taken along
/// it); elsewhere dir is left as it was. The axes are tried in reverse, each taking over
/// where it passes, so the first passing one is kept.
template <class L>
inline auto box_face_probe(const V3<L>& ha, const V3<L>& hb, const L (&rot)[3][3], const L (&pos)[3], L sep_sq,
                           V3<L>& dir) {
  L ar[3][3];
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) ar[j][c] = abs(rot[j][c]);
  const L hav[3] = {ha.x, ha.y, ha.z};
  const V3<L> row[3] = {{rot[0][0], rot[0][1], rot[0][2]}, {rot[1][0], rot[1][1], rot[1][2]},
                        {rot[2][0], rot[2][1], rot[2][2]}};
  auto found = L(0.0f) > L(1.0f);
  for (int j = 2; j >= 0; --j) {
    const L c = (pos[0] * row[j].x + pos[1] * row[j].y) + pos[2] * row[j].z;
    const L ra = (ha.x * ar[j][0] + ha.y * ar[j][1]) + ha.z * ar[j][2];
    const L rb = (hb.x * abs(dot(row[0], row[j])) + hb.y * abs(dot(row[1], row[j]))) + hb.z * abs(dot(row[2], row[j]));
    const L gap = abs(c) - (ra + rb);
    const auto pass = (gap > L(0.0f)) && (gap * gap > sep_sq * dot(row[j], row[j]));
    dir = vselect(pass, row[j] * select(c >= L(0.0f), L(1.0f), L(-1.0f)), dir);
    found = found || pass;
  }
  for (int k = 2; k >= 0; --k) {
    const L rb = (hb.x * ar[0][k] + hb.y * ar[1][k]) + hb.z * ar[2][k];
    const L gap = abs(pos[k]) - (hav[k] + rb);
    const auto pass = (gap > L(0.0f)) && (gap * gap > sep_sq);
    const L sg = select(pos[k] >= L(0.0f), L(1.0f), L(-1.0f)), z(0.0f);
    dir = vselect(pass, V3<L>{k == 0 ? sg : z, k == 1 ? sg : z, k == 2 ? sg : z}, dir);
    found = found || pass;
  }
  return found;
}

}  // namespace gyro::GYRO_ARCH_NS
