#include "dynamics/body_hull.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"

#include <cmath>

namespace gyro::detail {

quat quat_from_rows(const mat3& m) {
  // r[i][j] = m[j][i]: the column-vector matrix. Shepperd: divide by the largest of
  // 4w^2, 4x^2, 4y^2, 4z^2, so the square root is never of a small number.
  auto r = [&](int i, int j) { return m.m[j][i]; };
  const float t = (r(0, 0) + r(1, 1)) + r(2, 2);
  quat q;
  if (t >= r(0, 0) && t >= r(1, 1) && t >= r(2, 2)) {
    const float s = std::sqrt(1.0f + t) * 2.0f;  // 4w
    q = {(r(2, 1) - r(1, 2)) / s, (r(0, 2) - r(2, 0)) / s, (r(1, 0) - r(0, 1)) / s, 0.25f * s};
  } else if (r(0, 0) >= r(1, 1) && r(0, 0) >= r(2, 2)) {
    const float s = std::sqrt(((1.0f + r(0, 0)) - r(1, 1)) - r(2, 2)) * 2.0f;  // 4x
    q = {0.25f * s, (r(0, 1) + r(1, 0)) / s, (r(0, 2) + r(2, 0)) / s, (r(2, 1) - r(1, 2)) / s};
  } else if (r(1, 1) >= r(2, 2)) {
    const float s = std::sqrt(((1.0f + r(1, 1)) - r(0, 0)) - r(2, 2)) * 2.0f;  // 4y
    q = {(r(0, 1) + r(1, 0)) / s, 0.25f * s, (r(1, 2) + r(2, 1)) / s, (r(0, 2) - r(2, 0)) / s};
  } else {
    const float s = std::sqrt(((1.0f + r(2, 2)) - r(0, 0)) - r(1, 1)) * 2.0f;  // 4z
    q = {(r(0, 2) + r(2, 0)) / s, (r(1, 2) + r(2, 1)) / s, 0.25f * s, (r(1, 0) - r(0, 1)) / s};
  }
  if (q.w < 0.0f) q = {-q.x, -q.y, -q.z, -q.w};  // one of the two signs, always the same
  return normalized(q);
}

Status make_body_hull(const ConvexHull& hull, BodyHull* out) {
  ConvexMass mass;
  GYRO_TRY(convex_hull_mass(hull, mass));
  const mat3& p = mass.principal_axes;  // rows: principal axes in the hull's frame
  auto to_mass = [&](const vec3& v) {     // P v
    return vec3{dot(vec3{p.m[0][0], p.m[0][1], p.m[0][2]}, v), dot(vec3{p.m[1][0], p.m[1][1], p.m[1][2]}, v),
                dot(vec3{p.m[2][0], p.m[2][1], p.m[2][2]}, v)};
  };
  BodyHull b;
  b.hull = hull;
  vec3 lo{}, hi{};
  float r2 = 0.0f;
  for (std::size_t i = 0; i < b.hull.vertices.size(); ++i) {
    const vec3 v = to_mass(hull.vertices[i] - mass.centroid);
    b.hull.vertices[i] = v;
    lo = i == 0 ? v : min(lo, v);
    hi = i == 0 ? v : max(hi, v);
    const float d2 = dot(v, v);
    r2 = d2 > r2 ? d2 : r2;
  }
  for (Plane& pl : b.hull.planes) {
    const vec3 n = pl.normal;
    pl.distance = pl.distance - dot(n, mass.centroid);
    pl.normal = to_mass(n);
  }
  b.local_bounds = AABB{(lo + hi) * 0.5f, (hi - lo) * 0.5f};
  b.bound_radius = std::sqrt(r2);
  b.shape_offset = -to_mass(mass.centroid);
  // rotate(shape_rotation, v) = P v: its rows (rotated unit axes) are P's columns.
  mat3 cols;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cols.m[i][j] = p.m[j][i];
  b.shape_rotation = quat_from_rows(cols);
  b.volume = mass.volume;
  b.unit_inertia = mass.principal_moments * (1.0f / mass.volume);
  *out = std::move(b);
  return Status::ok;
}

}  // namespace gyro::detail
