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

double ref_obb_obb_separation(const BoxSet& A, std::size_t i, const BoxSet& B, std::size_t j) {
  struct Box {
    double c[3], e[3], u[3][3];
  };
  auto get = [](const BoxSet& s, std::size_t k) {
    Box b;
    b.c[0] = s.cx[k], b.c[1] = s.cy[k], b.c[2] = s.cz[k];
    b.e[0] = s.hx[k], b.e[1] = s.hy[k], b.e[2] = s.hz[k];
    for (int axis = 0; axis < 3; ++axis)
      for (int comp = 0; comp < 3; ++comp) b.u[axis][comp] = s.r[3 * comp + axis][k];  // column = axis
    return b;
  };
  const Box a = get(A, i), b = get(B, j);
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const double d[3] = {b.c[0] - a.c[0], b.c[1] - a.c[1], b.c[2] - a.c[2]};
  double best = -INFINITY;
  auto test = [&](const double* axis) {
    const double len = std::sqrt(dot(axis, axis));
    if (len < 1e-2) return;  // gyro's definition: cross axes with |a x b|^2 < 1e-4 are skipped
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) ra += a.e[k] * std::abs(dot(a.u[k], axis)), rb += b.e[k] * std::abs(dot(b.u[k], axis));
    best = std::max(best, (std::abs(dot(d, axis)) - ra - rb) / len);
  };
  for (int k = 0; k < 3; ++k) test(a.u[k]), test(b.u[k]);
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      const double* x = a.u[p];
      const double* y = b.u[q];
      const double c[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
      test(c);
    }
  return best;
}

}  // namespace gyro::testing
