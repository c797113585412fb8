#include "reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyro::testing {

RefHit ref_ray_spheres(double ox, double oy, double oz, double dx, double dy, double dz, double tmin, double tmax,
                       const SphereSet& s) {
  RefHit best;
  best.t = std::numeric_limits<double>::infinity();
  const double a = dx * dx + dy * dy + dz * dz;
  if (!(a > 0)) return best;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const double px = ox - s.cx[j], py = oy - s.cy[j], pz = oz - s.cz[j];
    const double b = px * dx + py * dy + pz * dz;
    const double r = s.r[j];
    const double c = px * px + py * py + pz * pz - r * r;
    const double disc = b * b - a * c;
    if (disc < 0) continue;
    const double sq = std::sqrt(disc);
    const double t0 = (-b - sq) / a, t1 = (-b + sq) / a;
    const double t = t0 >= tmin ? t0 : t1;
    if (t >= tmin && t <= tmax && t < best.t) best = {t, static_cast<int32_t>(j)};
  }
  return best;
}

std::vector<RefHit> ref_raycast_spheres(const RaySet& rays, std::size_t count, const SphereSet& spheres) {
  std::vector<RefHit> out(count);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t i = 0; i < count; ++i)
    out[i] = ref_ray_spheres(rays.ox[i], rays.oy[i], rays.oz[i], rays.dx[i], rays.dy[i], rays.dz[i], 0.0,
                             std::numeric_limits<double>::infinity(), spheres);
  return out;
}

RaycastError compare_raycast(const HitSet& hits, const std::vector<RefHit>& ref, std::size_t count) {
  RaycastError e;
  e.rays = count;
  for (std::size_t i = 0; i < count; ++i) {
    const bool hit = hits.primitive[i] >= 0, ref_hit = ref[i].primitive >= 0;
    e.hits += hit;
    e.ref_hits += ref_hit;
    if (hit) e.sum_t += static_cast<double>(hits.t[i]);
    if (ref_hit) e.ref_sum_t += static_cast<double>(static_cast<float>(ref[i].t));
    if (hit != ref_hit || hits.primitive[i] != ref[i].primitive) {
      ++e.disagreements;
      continue;
    }
    if (hit) {
      const double d = std::abs(static_cast<double>(hits.t[i]) - ref[i].t);
      e.max_abs_t = std::max(e.max_abs_t, d);
      e.max_rel_t = std::max(e.max_rel_t, d / std::max(1.0, std::abs(ref[i].t)));
    }
  }
  return e;
}

}  // namespace gyro::testing
