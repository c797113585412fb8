// The scalar raycasts and linetests: the lane templates of ray_lanes.hpp with L = float.
#include "gyro/raycast.hpp"

#include "geometry/raycast_at.hpp"
#include "geometry/ray_lanes.hpp"
#include "geometry/shapes_public.hpp"

namespace gyro {
namespace {

namespace lanes = GYRO_ARCH_NS;

constexpr float kInf = __builtin_inff();

// A miss is the all-zero result; a hit's point is o + t d as the ray defines it.
template <class NormalFn> RaycastResult result(const Ray& ray, float t, NormalFn&& normal) {
  if (!(t < kInf)) return {};
  RaycastResult r;
  r.t = t;
  r.point = ray.origin + ray.direction * t;
  r.normal = lanes::vec3_of(normal());
  r.hit = true;
  return r;
}

}  // namespace

RaycastResult detail::raycast_at(const Sphere& sphere, const Ray& ray, float t) {
  const auto r = lanes::lanes_of(ray);
  const auto s = lanes::lanes_of(sphere);
  return result(ray, t, [&] { return lanes::ray_sphere_normal(r, s, t); });
}

RaycastResult detail::raycast_at(const OBB& box, const Ray& ray, float t) {
  const auto r = lanes::lanes_of(ray);
  const auto b = lanes::lanes_of(box);
  return result(ray, t, [&] { return lanes::ray_obb_normal(r, b, t); });
}

RaycastResult raycast(const Sphere& sphere, const Ray& ray) { return raycast(sphere, ray, 0.0f, kInf); }
RaycastResult raycast(const Sphere& sphere, const Ray& ray, float tmin, float tmax) {
  const float t = lanes::ray_sphere_t(lanes::lanes_of(ray), lanes::lanes_of(sphere), tmin, tmax);
  return detail::raycast_at(sphere, ray, t);
}

RaycastResult raycast(const AABB& box, const Ray& ray) { return raycast(box, ray, 0.0f, kInf); }
RaycastResult raycast(const AABB& box, const Ray& ray, float tmin, float tmax) {
  const auto r = lanes::lanes_of(ray);
  const auto b = lanes::lanes_of(box);
  const float t = lanes::ray_aabb_t(r, b, tmin, tmax);
  return result(ray, t, [&] { return lanes::ray_aabb_normal(r, b, t); });
}

RaycastResult raycast(const OBB& box, const Ray& ray) { return raycast(box, ray, 0.0f, kInf); }
RaycastResult raycast(const OBB& box, const Ray& ray, float tmin, float tmax) {
  const float t = lanes::ray_obb_t(lanes::lanes_of(ray), lanes::lanes_of(box), tmin, tmax);
  return detail::raycast_at(box, ray, t);
}

RaycastResult raycast(const Plane& plane, const Ray& ray) { return raycast(plane, ray, 0.0f, kInf); }
RaycastResult raycast(const Plane& plane, const Ray& ray, float tmin, float tmax) {
  const auto r = lanes::lanes_of(ray);
  const auto p = lanes::lanes_of(plane);
  const float t = lanes::ray_plane_t(r, p, tmin, tmax);
  return result(ray, t, [&] { return lanes::ray_plane_normal(r, p); });
}

bool linetest(const Sphere& sphere, const Line& line) { return lanes::linetest(lanes::lanes_of(sphere), lanes::lanes_of(line)); }
bool linetest(const AABB& box, const Line& line) { return lanes::linetest(lanes::lanes_of(box), lanes::lanes_of(line)); }
bool linetest(const OBB& box, const Line& line) { return lanes::linetest(lanes::lanes_of(box), lanes::lanes_of(line)); }
bool linetest(const Plane& plane, const Line& line) { return lanes::linetest(lanes::lanes_of(plane), lanes::lanes_of(line)); }

}  // namespace gyro
