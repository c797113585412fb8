// overlap_probe at this translation unit's SIMD level: every point-test and overlap lane
// template over element i of the probe's input columns (see overlap_probe.hpp).
#include "geometry/overlap_lanes.hpp"
#include "geometry/point_lanes.hpp"
#include "overlap_probe.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

template <class L> struct Row {
  const OverlapProbeArgs& p;
  std::size_t i;
  L f(int k) const { return load<L>(p.in[k] + i); }
  V3<L> v(int k) const { return {f(k), f(k + 1), f(k + 2)}; }
  SphereL<L> sphere(int k) const { return {v(k), f(k + 3)}; }
  AabbL<L> aabb(int k) const { return {v(k), v(k + 3)}; }
  ObbL<L> obb(int k) const { return {v(k), v(k + 3), {v(k + 6), v(k + 9), v(k + 12)}}; }
  PlaneL<L> plane(int k) const { return {v(k), f(k + 3)}; }
  void put(int k, L x) const { store(p.out[k] + i, x); }
  void put(int k, const V3<L>& x) const { put(k, x.x), put(k + 1, x.y), put(k + 2, x.z); }
  template <class M> void put_mask(int k, M m) const { put(k, select(m, L(1.0f), L(0.0f))); }
};

}  // namespace

void overlap_probe(const OverlapProbeArgs& args, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const Row<L> r{args, i};
    const SphereL<L> sa = r.sphere(kInSphereA), sb = r.sphere(kInSphereB);
    const AabbL<L> aa = r.aabb(kInAabbA), ab = r.aabb(kInAabbB);
    const ObbL<L> oa = r.obb(kInObbA), ob = r.obb(kInObbB);
    const PlaneL<L> pa = r.plane(kInPlaneA), pb = r.plane(kInPlaneB);
    const V3<L> p = r.v(kInPoint);
    const SegmentL<L> seg{r.v(kInSegment), r.v(kInSegment + 3)};
    const RayL<L> ray{seg.a, seg.b};

    r.put_mask(kOutContainsSphere, contains(sa, p));
    r.put_mask(kOutContainsAabb, contains(aa, p));
    r.put_mask(kOutContainsObb, contains(oa, p));
    r.put_mask(kOutContainsPlane, contains(pa, p));
    r.put_mask(kOutContainsSegment, contains(seg, p));
    r.put_mask(kOutContainsRay, contains(ray, p));
    r.put(kOutClosestSphere, closest_point(sa, p));
    r.put(kOutClosestAabb, closest_point(aa, p));
    r.put(kOutClosestObb, closest_point(oa, p));
    r.put(kOutClosestPlane, closest_point(pa, p));
    r.put(kOutClosestSegment, closest_point(seg, p));
    r.put(kOutClosestRay, closest_point(ray, p));
    r.put(kOutSignedDistPlane, signed_distance(pa, p));
    r.put(kOutSignedDistSphere, signed_distance(sa, p));
    r.put(kOutDistSqAabb, distance_sq(aa, p));
    r.put(kOutDistSqObb, distance_sq(oa, p));

    r.put_mask(kOutSphereSphere, overlaps(sa, sb));
    r.put_mask(kOutSphereAabb, overlaps(sa, ab));
    r.put_mask(kOutSphereObb, overlaps(sa, ob));
    r.put_mask(kOutSpherePlane, overlaps(sa, pb));
    r.put_mask(kOutAabbAabb, overlaps(aa, ab));
    r.put_mask(kOutAabbObb, overlaps(aa, ob));
    r.put_mask(kOutAabbPlane, overlaps(aa, pb));
    r.put_mask(kOutObbObb, overlaps(oa, ob));
    r.put_mask(kOutObbPlane, overlaps(oa, pb));
    r.put_mask(kOutPlanePlane, overlaps(pa, pb));
  });
}

}  // namespace gyro::GYRO_ARCH_NS
