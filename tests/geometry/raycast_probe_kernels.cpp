// Per-level probe of the raycast and linetest templates (see raycast_probe.hpp).
#include "raycast_probe.hpp"

#include "geometry/ray_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

void raycast_probe(const RaycastProbeArgs& p, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const RayL<L> ray{load3<L>(p.ox, p.oy, p.oz, i), load3<L>(p.dx, p.dy, p.dz, i)};
    const SegmentL<L> seg{ray.o, ray.o + ray.d};
    const L tmin = load<L>(p.tmin + i), tmax = load<L>(p.tmax + i);
    const auto s = load_sphere<L>(p.spheres, i);
    const auto a = load_aabb<L>(p.aabbs, i);
    const auto b = load_obb<L>(p.obbs, i);
    const auto pl = load_plane<L>(p.planes, i);
    auto put = [&](int shape, L t, const V3<L>& n) {
      store(p.out[4 * shape] + i, t);
      store3(p.out[4 * shape + 1], p.out[4 * shape + 2], p.out[4 * shape + 3], i, n);
    };
    // Normals are evaluated at every t, misses (+inf) included: they must be lane-safe too.
    const L ts = ray_sphere_t(ray, s, tmin, tmax);
    put(kRaycastProbeSphere, ts, ray_sphere_normal(ray, s, ts));
    const L ta = ray_aabb_t(ray, a, tmin, tmax);
    put(kRaycastProbeAabb, ta, ray_aabb_normal(ray, a, ta));
    const L tb = ray_obb_t(ray, b, tmin, tmax);
    put(kRaycastProbeObb, tb, ray_obb_normal(ray, b, tb));
    const L tp = ray_plane_t(ray, pl, tmin, tmax);
    put(kRaycastProbePlane, tp, ray_plane_normal(ray, pl));
    const L one(1.0f), zero(0.0f);
    store(p.out[kRaycastProbeLinetest + 0] + i, select(linetest(s, seg), one, zero));
    store(p.out[kRaycastProbeLinetest + 1] + i, select(linetest(a, seg), one, zero));
    store(p.out[kRaycastProbeLinetest + 2] + i, select(linetest(b, seg), one, zero));
    store(p.out[kRaycastProbeLinetest + 3] + i, select(linetest(pl, seg), one, zero));
  });
}

}  // namespace gyro::GYRO_ARCH_NS
