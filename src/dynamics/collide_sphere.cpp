// Sphere manifolds against spheres, boxes and planes (Cookbook chapter 15): one point each,
// midway between the sphere's deepest point and the other surface, with feature id 0 (a
// sphere touches with one point, which stays "the same" point however it rolls).
//
// Every point is written as c + n (r + separation / 2), c the sphere's centre and n the
// normal from it: the sphere's surface point is c + n r and the other surface's c + n (r +
// separation), so the formula holds for penetration and gap alike.
#include "dynamics/narrowphase.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

// The fallback normal when the direction is undefined (coincident centres): +y, "up", so
// that a stack resolves the way gravity would.
constexpr vec3 kUp{0.0f, 1.0f, 0.0f};

void one_point(const Sphere& s, const vec3& normal, float separation, Manifold* out) {
  out->normal = normal;
  out->points[0].position = s.center + normal * (s.radius + separation * 0.5f);
  out->points[0].separation = separation;
  out->points[0].feature_id = 0;
  out->count = 1;
}

}  // namespace

void collide_spheres(const Sphere& a, const Sphere& b, float margin, Manifold* out) {
  out->count = 0;
  const vec3 d = b.center - a.center;
  const float dist = std::sqrt(dot(d, d));
  const float separation = dist - (a.radius + b.radius);
  if (!(separation < margin)) return;
  // normalized() rescales tiny vectors, so any nonzero d (even one whose square underflows
  // to dist == 0) has a unit direction; only exactly coincident centres take the fallback.
  one_point(a, d == vec3{} ? kUp : normalized(d), separation, out);
}

void collide_sphere_box(const Sphere& a, const OBB& b, float margin, Manifold* out) {
  out->count = 0;
  // The centre in the box's frame, relative to the box centre.
  const vec3 rel = a.center - b.center;
  vec3 axis[3];
  float local[3], e[3];
  for (int k = 0; k < 3; ++k) {
    axis[k] = {b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]};
    local[k] = dot(rel, axis[k]);
    e[k] = b.half_extents[k];
  }
  const bool inside = std::abs(local[0]) <= e[0] && std::abs(local[1]) <= e[1] && std::abs(local[2]) <= e[2];
  if (!inside) {
    // From the centre to the closest point of the box; distinct floats differ, so delta is
    // not zero when some coordinate is outside.
    float delta[3];
    for (int k = 0; k < 3; ++k) delta[k] = clamp(local[k], -e[k], e[k]) - local[k];
    const vec3 dir = (axis[0] * delta[0] + axis[1] * delta[1]) + axis[2] * delta[2];
    const float dist = std::sqrt((delta[0] * delta[0] + delta[1] * delta[1]) + delta[2] * delta[2]);
    const float separation = dist - a.radius;
    if (!(separation < margin)) return;
    one_point(a, normalized(dir), separation, out);
    return;
  }
  // The centre is inside: leave through the nearest face (the first of equal ones); the box
  // moves away from the sphere, opposite to that face's outward normal.
  int k = 0;
  float depth = e[0] - std::abs(local[0]);
  for (int m = 1; m < 3; ++m) {
    const float dm = e[m] - std::abs(local[m]);
    if (dm < depth) depth = dm, k = m;
  }
  const float separation = -depth - a.radius;
  if (!(separation < margin)) return;  // only with a negative margin, which callers do not pass
  one_point(a, local[k] < 0.0f ? axis[k] : -axis[k], separation, out);
}

void collide_sphere_plane(const Sphere& a, const Plane& b, float margin, Manifold* out) {
  out->count = 0;
  const float separation = (dot(b.normal, a.center) - b.distance) - a.radius;
  if (!(separation < margin)) return;
  one_point(a, -b.normal, separation, out);
}

}  // namespace gyro::detail
