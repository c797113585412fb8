// gyro/overlap.hpp: the float instantiation of the lane templates of overlap_lanes.hpp
// (canonical pair order sphere < aabb < obb < plane), so the scalar API gives the bits the
// batch kernels give at every SIMD level.
#include "gyro/overlap.hpp"

#include "geometry/overlap_lanes.hpp"
#include "geometry/shapes_public.hpp"

namespace gyro {

namespace lanes = GYRO_ARCH_NS;

static_assert(kPlaneParallelSine == lanes::kPlaneParallelSine, "gyro/overlap.hpp and overlap_lanes.hpp must agree");

namespace {
template <class A, class B> bool test(const A& a, const B& b) { return lanes::overlaps(lanes::lanes_of(a), lanes::lanes_of(b)); }
}  // namespace

bool overlaps(const Sphere& a, const Sphere& b) { return test(a, b); }
bool overlaps(const Sphere& sphere, const AABB& box) { return test(sphere, box); }
bool overlaps(const AABB& box, const Sphere& sphere) { return test(sphere, box); }
bool overlaps(const Sphere& sphere, const OBB& box) { return test(sphere, box); }
bool overlaps(const OBB& box, const Sphere& sphere) { return test(sphere, box); }
bool overlaps(const Sphere& sphere, const Plane& plane) { return test(sphere, plane); }
bool overlaps(const Plane& plane, const Sphere& sphere) { return test(sphere, plane); }

bool overlaps(const AABB& a, const AABB& b) { return test(a, b); }
bool overlaps(const AABB& aabb, const OBB& obb) { return test(aabb, obb); }
bool overlaps(const OBB& obb, const AABB& aabb) { return test(aabb, obb); }
bool overlaps(const AABB& box, const Plane& plane) { return test(box, plane); }
bool overlaps(const Plane& plane, const AABB& box) { return test(box, plane); }

bool overlaps(const OBB& a, const OBB& b) { return test(a, b); }
bool overlaps(const OBB& box, const Plane& plane) { return test(box, plane); }
bool overlaps(const Plane& plane, const OBB& box) { return test(box, plane); }

bool overlaps(const Plane& a, const Plane& b) { return test(a, b); }

}  // namespace gyro
