// gyro/point_tests.hpp: the float instantiation of the lane templates of point_lanes.hpp,
// so the scalar API gives the bits the batch kernels give at every SIMD level.
#include "gyro/point_tests.hpp"

#include "geometry/point_lanes.hpp"
#include "geometry/shapes_public.hpp"

namespace gyro {

namespace lanes = GYRO_ARCH_NS;

static_assert(kSurfaceAbsTolerance == lanes::kSurfaceAbsTolerance && kSurfaceRelTolerance == lanes::kSurfaceRelTolerance,
              "gyro/point_tests.hpp and point_lanes.hpp must state the same tolerance");

bool contains(const Sphere& sphere, const vec3& point) { return lanes::contains(lanes::lanes_of(sphere), lanes::lanes_of(point)); }
bool contains(const AABB& box, const vec3& point) { return lanes::contains(lanes::lanes_of(box), lanes::lanes_of(point)); }
bool contains(const OBB& box, const vec3& point) { return lanes::contains(lanes::lanes_of(box), lanes::lanes_of(point)); }
bool contains(const Plane& plane, const vec3& point) { return lanes::contains(lanes::lanes_of(plane), lanes::lanes_of(point)); }
bool contains(const Line& line, const vec3& point) { return lanes::contains(lanes::lanes_of(line), lanes::lanes_of(point)); }
bool contains(const Ray& ray, const vec3& point) { return lanes::contains(lanes::lanes_of(ray), lanes::lanes_of(point)); }

vec3 closest_point(const Sphere& sphere, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(sphere), lanes::lanes_of(point)));
}
vec3 closest_point(const AABB& box, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(box), lanes::lanes_of(point)));
}
vec3 closest_point(const OBB& box, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(box), lanes::lanes_of(point)));
}
vec3 closest_point(const Plane& plane, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(plane), lanes::lanes_of(point)));
}
vec3 closest_point(const Line& line, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(line), lanes::lanes_of(point)));
}
vec3 closest_point(const Ray& ray, const vec3& point) {
  return lanes::vec3_of(lanes::closest_point(lanes::lanes_of(ray), lanes::lanes_of(point)));
}

float signed_distance(const Plane& plane, const vec3& point) {
  return lanes::signed_distance(lanes::lanes_of(plane), lanes::lanes_of(point));
}
float signed_distance(const Sphere& sphere, const vec3& point) {
  return lanes::signed_distance(lanes::lanes_of(sphere), lanes::lanes_of(point));
}

}  // namespace gyro
