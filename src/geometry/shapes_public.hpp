// Conversions between the public shape structs (gyro/shapes.hpp) and their float-lane
// forms, for the scalar API's implementation files. Generic (scalar-level) translation
// units only: kernel sources never include public math headers, so no inline function
// compiled with AVX flags can reach the scalar path.
#pragma once

#include "geometry/shapes_lanes.hpp"
#include "gyro/shapes.hpp"

#if !defined(GYRO_ARCH_SCALAR)
#error "shapes_public.hpp is for generic (scalar-level) translation units"
#endif

namespace gyro::GYRO_ARCH_NS {

inline V3<float> lanes_of(const vec3& v) { return {v.x, v.y, v.z}; }
inline vec3 vec3_of(const V3<float>& v) { return {v.x, v.y, v.z}; }
inline SphereL<float> lanes_of(const Sphere& s) { return {lanes_of(s.center), s.radius}; }
inline AabbL<float> lanes_of(const AABB& b) { return {lanes_of(b.center), lanes_of(b.half_extents)}; }
inline ObbL<float> lanes_of(const OBB& b) {
  const mat3& o = b.orientation;
  return {lanes_of(b.center),
          lanes_of(b.half_extents),
          {{o.m[0][0], o.m[0][1], o.m[0][2]}, {o.m[1][0], o.m[1][1], o.m[1][2]}, {o.m[2][0], o.m[2][1], o.m[2][2]}}};
}
inline PlaneL<float> lanes_of(const Plane& p) { return {lanes_of(p.normal), p.distance}; }
inline TriangleL<float> lanes_of(const Triangle& t) { return {lanes_of(t.a), lanes_of(t.b), lanes_of(t.c)}; }
inline RayL<float> lanes_of(const Ray& r) { return {lanes_of(r.origin), lanes_of(r.direction)}; }
inline SegmentL<float> lanes_of(const Line& l) { return {lanes_of(l.start), lanes_of(l.end)}; }

}  // namespace gyro::GYRO_ARCH_NS
