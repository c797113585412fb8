// triangle_probe at this translation unit's SIMD level: every triangle lane template, one
// case per lane.
#include "geometry/ray_triangle_lanes.hpp"
#include "geometry/triangle_lanes.hpp"
#include "triangle_probe.hpp"

namespace gyro::GYRO_ARCH_NS {

void triangle_probe(const TriangleProbeArgs& p, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const L one(1.0f), zero(0.0f);
    const TriangleL<L> t = load_triangle<L>(p.tri, i);
    const V3<L> q = load3<L>(p.px, p.py, p.pz, i);
    const V3<L> cp = closest_point(t, q);
    const V3<L> bary = barycentric(q, t);
    const RayL<L> ray{load3<L>(p.ox, p.oy, p.oz, i), load3<L>(p.dx, p.dy, p.dz, i)};
    L u, v;
    const L rt = ray_triangle_t(ray, t, load<L>(p.tmin + i), load<L>(p.tmax + i), u, v);
    const V3<L> n = triangle_normal_facing(t, ray.d);
    const L results[kTriangleProbeOutputs] = {
        select(contains(t, q), one, zero),
        cp.x, cp.y, cp.z,
        bary.x, bary.y, bary.z,
        select(overlaps(load_sphere<L>(p.sphere, i), t), one, zero),
        select(overlaps(load_aabb<L>(p.aabb, i), t), one, zero),
        select(overlaps(load_obb<L>(p.obb, i), t), one, zero),
        select(overlaps(load_plane<L>(p.plane, i), t), one, zero),
        select(overlaps(t, load_triangle<L>(p.other, i)), one, zero),
        rt, u, v,
        n.x, n.y, n.z};
    for (int k = 0; k < kTriangleProbeOutputs; ++k) store(p.out[k] + i, results[k]);
  });
}

}  // namespace gyro::GYRO_ARCH_NS
