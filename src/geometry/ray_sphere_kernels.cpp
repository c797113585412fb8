// ray_sphere_closest: for each ray (one per lane), the nearest sphere surface crossing.
//
// Inputs: ray origins, directions, optional [tmin, tmax]; sphere centres and radii (SoA,
// the spheres broadcast one at a time). Outputs: t and sphere index per ray.
//
// Precision: the discriminant is r^2 - |f|^2 with f the vector from the centre to the
// closest point of the line, not b^2 - ac, so it does not cancel for rays far from the
// sphere; the two roots are c/q and q/a with q = b + sign(b) sqrt(disc), so neither is a
// difference of nearly equal numbers (Haines et al., Ray Tracing Gems, ch. 7).
// Determinism: lanes are rays, the sphere loop runs in index order in every lane, and a
// hit replaces the best only when strictly nearer, so ties keep the lowest index.
#include "geometry/ray_sphere.hpp"

#include "core/lanes.hpp"

#include <cfloat>

namespace gyro::GYRO_ARCH_NS {

void ray_sphere_closest(const RaySphereArgs& a, std::size_t begin, std::size_t end) {
  const float inf = __builtin_inff();
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const L ox = load<L>(a.ox + i), oy = load<L>(a.oy + i), oz = load<L>(a.oz + i);
    const L dx = load<L>(a.dx + i), dy = load<L>(a.dy + i), dz = load<L>(a.dz + i);
    const L tmin = a.tmin ? load<L>(a.tmin + i) : L(0.0f);
    const L tmax = a.tmax ? load<L>(a.tmax + i) : L(inf);
    const L dd = (dx * dx + dy * dy) + dz * dz;
    const auto ray_ok = (dd >= L(FLT_MIN)) && (dd <= L(FLT_MAX));
    const L inv_dd = L(1.0f) / dd;
    L best_t = L(inf);
    L best_i = from_bits<L>(0xFFFFFFFFu);
    for (std::size_t j = 0; j < a.sphere_count; ++j) {
      const L ocx = ox - L(a.cx[j]), ocy = oy - L(a.cy[j]), ocz = oz - L(a.cz[j]);
      const L b = -((ocx * dx + ocy * dy) + ocz * dz);
      const L s = b * inv_dd;
      const L fx = ocx + s * dx, fy = ocy + s * dy, fz = ocz + s * dz;
      const L r = L(a.r[j]);
      const L r2 = r * r;
      const L h = r2 - ((fx * fx + fy * fy) + fz * fz);
      const auto crosses = h >= L(0.0f);
      if (!any(crosses)) continue;
      const L c = ((ocx * ocx + ocy * ocy) + ocz * ocz) - r2;
      const L q = b + copysign(sqrt(dd * h), b);
      const L t0 = c / q, t1 = q / dd;
      const L tn = min(t0, t1), tf = max(t0, t1);
      const L t = select(tn >= tmin, tn, tf);
      const auto nearer = crosses && ray_ok && (t >= tmin) && (t <= tmax) && (t < best_t);
      best_t = select(nearer, t, best_t);
      best_i = select(nearer, from_bits<L>(static_cast<uint32_t>(j)), best_i);
    }
    store(a.t_out + i, best_t + L(0.0f));  // a hit at t = -0 reads as +0
    store_bits(a.index_out + i, best_i);
  });
}

}  // namespace gyro::GYRO_ARCH_NS
