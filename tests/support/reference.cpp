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

double ref_sphere_sphere_gap(D3 c1, double r1, D3 c2, double r2) {
  const double dx = c1.x - c2.x, dy = c1.y - c2.y, dz = c1.z - c2.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz) - (r1 + r2);
}

double ref_sphere_aabb_gap(D3 c, double r, D3 bc, D3 be) {
  auto axis = [](double p, double center, double half) {
    const double lo = center - half, hi = center + half;
    const double q = p < lo ? lo : (p > hi ? hi : p);
    return p - q;
  };
  const double dx = axis(c.x, bc.x, be.x), dy = axis(c.y, bc.y, be.y), dz = axis(c.z, bc.z, be.z);
  return std::sqrt(dx * dx + dy * dy + dz * dz) - r;
}

double ref_aabb_aabb_gap(D3 ac, D3 ae, D3 bc, D3 be) {
  const double gx = std::abs(ac.x - bc.x) - (ae.x + be.x), gy = std::abs(ac.y - bc.y) - (ae.y + be.y),
               gz = std::abs(ac.z - bc.z) - (ae.z + be.z);
  return std::max(gx, std::max(gy, gz));
}

double ref_ray_aabb_t(D3 o, D3 d, D3 bc, D3 be) {
  double t0 = -INFINITY, t1 = INFINITY;
  const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z}, c[3] = {bc.x, bc.y, bc.z}, e[3] = {be.x, be.y, be.z};
  for (int k = 0; k < 3; ++k) {
    const double lo = c[k] - e[k], hi = c[k] + e[k];
    if (dd[k] == 0) {
      if (oo[k] < lo || oo[k] > hi) return INFINITY;
      continue;
    }
    double a = (lo - oo[k]) / dd[k], b = (hi - oo[k]) / dd[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  if (t0 > t1 || t1 < 0) return INFINITY;
  return t0 >= 0 ? t0 : t1;
}

double ref_ray_triangle_t(D3 o, D3 d, D3 a, D3 b, D3 c) {
  const double e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
  const double dd[3] = {d.x, d.y, d.z};
  const double p[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
  const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (det == 0) return INFINITY;
  const double s[3] = {o.x - a.x, o.y - a.y, o.z - a.z};
  const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
  const double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  const double v = (dd[0] * q[0] + dd[1] * q[1] + dd[2] * q[2]) / det;
  if (u < 0 || v < 0 || u + v > 1) return INFINITY;
  const double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
  return t >= 0 ? t : INFINITY;
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
