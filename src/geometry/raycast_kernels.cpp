// raycast_batch at this translation unit's SIMD level: for each ray (one per lane), the
// nearest primitive crossing in [tmin, tmax] (closest hit) or the lowest-index primitive
// crossed (any hit). Primitives are broadcast one at a time, in index order, in every
// lane; a hit replaces the best only when strictly nearer, so ties keep the lowest index.
// Any-hit stops when every lane has a hit (a uniform exit: each lane's answer is already
// its lowest-index hit). The per-primitive tests are the lane templates of ray_lanes.hpp
// and ray_triangle_lanes.hpp, the same code the scalar raycast() runs.
#include "geometry/ray_lanes.hpp"
#include "geometry/ray_triangle_lanes.hpp"
#include "geometry/raycast_batch.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

// The per-ray part of a test, computed once per batch of rays: the watertight shear and
// axis permutation for triangles, the ray itself for the others.
template <ShapeType T, class L> inline auto prepare(const RayL<L>& ray) {
  if constexpr (T == ShapeType::triangle) return watertight_ray(ray);
  else return ray;
}

template <ShapeType T, class L, class Ray>
inline L hit_t(const Ray& ray, const ShapeArray& p, std::size_t j, L tmin, L tmax) {
  if constexpr (T == ShapeType::sphere) return ray_sphere_t(ray, splat_sphere<L>(p.spheres, j), tmin, tmax);
  else if constexpr (T == ShapeType::aabb) return ray_aabb_t(ray, splat_aabb<L>(p.aabbs, j), tmin, tmax);
  else if constexpr (T == ShapeType::obb) return ray_obb_t(ray, splat_obb<L>(p.obbs, j), tmin, tmax);
  else if constexpr (T == ShapeType::plane) return ray_plane_t(ray, splat_plane<L>(p.planes, j), tmin, tmax);
  else {
    L u, v;
    return ray_triangle_t(ray, splat_triangle<L>(p.triangles, j), tmin, tmax, u, v);
  }
}

template <ShapeType T, bool AnyHit> void run(const RaycastArgs& a, std::size_t begin, std::size_t end) {
  const float inf = __builtin_inff();
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const auto ray = prepare<T>(RayL<L>{load3<L>(a.ox, a.oy, a.oz, i), load3<L>(a.dx, a.dy, a.dz, i)});
    const L tmin = a.tmin ? load<L>(a.tmin + i) : L(0.0f);
    const L tmax = a.tmax ? load<L>(a.tmax + i) : L(inf);
    L best_t(inf);
    L best_i = from_bits<L>(0xFFFFFFFFu);
    for (std::size_t j = 0; j < a.prim_count; ++j) {
      const L t = hit_t<T, L>(ray, a.prims, j, tmin, tmax);
      // Closest: take strictly nearer hits. Any: take only a lane's first hit, so its answer
      // is its lowest-index hit whatever the other lanes of its batch still search for.
      const auto take = AnyHit ? (t < L(inf)) && (best_t == L(inf)) : t < best_t;
      best_t = select(take, t, best_t);
      best_i = select(take, from_bits<L>(static_cast<uint32_t>(j)), best_i);
      if constexpr (AnyHit) {
        if (all(best_t < L(inf))) break;  // every lane has its answer
      }
    }
    store(a.t_out + i, best_t);
    store_bits(a.index_out + i, best_i);
  });
}

}  // namespace

GYRO_FLATTEN void raycast_batch(const RaycastArgs& a, std::size_t begin, std::size_t end) {
  auto go = [&]<ShapeType T>() { a.any_hit ? run<T, true>(a, begin, end) : run<T, false>(a, begin, end); };
  switch (a.prims.type) {
    case ShapeType::sphere: go.template operator()<ShapeType::sphere>(); break;
    case ShapeType::aabb: go.template operator()<ShapeType::aabb>(); break;
    case ShapeType::obb: go.template operator()<ShapeType::obb>(); break;
    case ShapeType::plane: go.template operator()<ShapeType::plane>(); break;
    case ShapeType::triangle: go.template operator()<ShapeType::triangle>(); break;
  }
}

}  // namespace gyro::GYRO_ARCH_NS
