// EPA's face plane, written once over lanes: instantiated with float it is epa.cpp's
// Polytope::add_face, with a SIMD lane it is epa_lanes.cpp's kernel for the faces of many
// polytopes. Both evaluate the same expressions in the same order (cross(), dot() and
// normalized() on vec3, written in scalars), so a lane holds the float instantiation's bits.
#pragma once

#include "core/lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

template <class L> struct FacePlane {
  L nx, ny, nz, d;  // unit normal and distance from the origin; all 0 for a sliver
  L sliver;         // 1 where the normal is not trusted, else 0
};

/// The plane of face (a, b, c): n = cross(b - a, c - a); a sliver when |n|^2 <= 1e-12 |b - a|^2
/// |c - a|^2 or |n|^2 is not positive; else normalized(n) (rescaled by 2^100 or 2^-100
/// outside [2^-100, 2^100], as normalized() does) and d = dot(n, a).
template <class L>
inline FacePlane<L> face_plane(L ax, L ay, L az, L bx, L by, L bz, L cx, L cy, L cz) {
  const L e1x = bx - ax, e1y = by - ay, e1z = bz - az;
  const L e2x = cx - ax, e2y = cy - ay, e2z = cz - az;
  const L nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
  const L nn = nx * nx + ny * ny + nz * nz;
  const L ee = (e1x * e1x + e1y * e1y + e1z * e1z) * (e2x * e2x + e2y * e2y + e2z * e2z);
  const auto sliver = !(nn > L(1e-12f) * ee) || !(nn > L(0.0f));
  const auto small = nn < L(0x1p-100f), big = nn > L(0x1p+100f);
  const L k = select(small, L(0x1p+100f), L(0x1p-100f));
  const L sx = select(small || big, nx * k, nx), sy = select(small || big, ny * k, ny),
          sz = select(small || big, nz * k, nz);
  const L sq = select(small || big, sx * sx + sy * sy + sz * sz, nn);
  const L len = sqrt(sq);
  const L zero(0.0f);
  const L ux = select(sliver, zero, sx / len), uy = select(sliver, zero, sy / len), uz = select(sliver, zero, sz / len);
  return {ux, uy, uz, select(sliver, zero, ux * ax + uy * ay + uz * az), select(sliver, L(1.0f), zero)};
}

}  // namespace gyro::GYRO_ARCH_NS
