// The scalar triangle API (gyro/triangle.hpp): converts the public structs to float lanes
// and runs the lane templates the batch kernels also run, so both give the same bits.
#include "gyro/triangle.hpp"

#include "geometry/ray_triangle_lanes.hpp"
#include "geometry/shapes_public.hpp"
#include "geometry/triangle_lanes.hpp"

namespace gyro {

namespace lanes = GYRO_ARCH_NS;
using lanes::lanes_of;
using lanes::vec3_of;

bool contains(const Triangle& t, const vec3& p) { return lanes::contains(lanes_of(t), lanes_of(p)); }

vec3 closest_point(const Triangle& t, const vec3& p) { return vec3_of(lanes::closest_point(lanes_of(t), lanes_of(p))); }

vec3 barycentric(const vec3& p, const Triangle& t) { return vec3_of(lanes::barycentric(lanes_of(p), lanes_of(t))); }

bool overlaps(const Triangle& t, const Sphere& s) { return lanes::overlaps(lanes_of(s), lanes_of(t)); }
bool overlaps(const Sphere& s, const Triangle& t) { return lanes::overlaps(lanes_of(s), lanes_of(t)); }
bool overlaps(const Triangle& t, const AABB& b) { return lanes::overlaps(lanes_of(b), lanes_of(t)); }
bool overlaps(const AABB& b, const Triangle& t) { return lanes::overlaps(lanes_of(b), lanes_of(t)); }
bool overlaps(const Triangle& t, const OBB& b) { return lanes::overlaps(lanes_of(b), lanes_of(t)); }
bool overlaps(const OBB& b, const Triangle& t) { return lanes::overlaps(lanes_of(b), lanes_of(t)); }
bool overlaps(const Triangle& t, const Plane& p) { return lanes::overlaps(lanes_of(p), lanes_of(t)); }
bool overlaps(const Plane& p, const Triangle& t) { return lanes::overlaps(lanes_of(p), lanes_of(t)); }
bool overlaps(const Triangle& a, const Triangle& b) { return lanes::overlaps(lanes_of(a), lanes_of(b)); }

RaycastResult raycast(const Triangle& t, const Ray& ray, vec3* barycentric) {
  const auto r = lanes_of(ray);
  const auto tri = lanes_of(t);
  float u, v, w;
  const float th = lanes::ray_triangle_t(lanes::watertight_ray(r), tri, 0.0f, __builtin_inff(), u, v, w);
  RaycastResult out;
  if (!(th <= 3.40282347e38f)) {  // a miss is +infinity
    if (barycentric) *barycentric = vec3{};
    return out;
  }
  out.t = th;
  out.hit = true;
  out.point = vec3_of(r.o + r.d * th);
  out.normal = vec3_of(lanes::triangle_normal_facing(tri, r.d));
  if (barycentric) *barycentric = vec3{u, v, w};
  return out;
}

bool linetest(const Triangle& t, const Line& line) {
  const auto tri = lanes_of(t);
  const lanes::RayL<float> r{lanes_of(line.start), lanes_of(line.end) - lanes_of(line.start)};
  float u, v;
  const float th = lanes::ray_triangle_t(r, tri, 0.0f, 1.0f, u, v);
  if (th <= 1.0f) return true;
  return line.start == line.end && lanes::contains(tri, lanes_of(line.start));
}

}  // namespace gyro
