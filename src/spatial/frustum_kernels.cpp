// frustum_cull_batch at this translation unit's SIMD level: visible_out[i] = 0 when shape
// i lies entirely outside one frustum plane, else 1. One shape per lane; the frustum is
// broadcast once per call. The test is frustum_side() of frustum_lanes.hpp, the template
// whose float instantiation is the scalar intersects(), so every level and the scalar API
// agree bit for bit; tails run the float instantiation.
#include "spatial/frustum_batch.hpp"
#include "spatial/frustum_lanes.hpp"

#include <type_traits>

namespace gyro::GYRO_ARCH_NS {
namespace {

template <ShapeType T, class L> inline auto load_shape(const ShapeArray& a, std::size_t i) {
  if constexpr (T == ShapeType::sphere) return load_sphere<L>(a.spheres, i);
  else if constexpr (T == ShapeType::aabb) return load_aabb<L>(a.aabbs, i);
  else return load_obb<L>(a.obbs, i);
}

template <ShapeType T> void run(const FrustumCullArgs& a, std::size_t begin, std::size_t end) {
  const FrustumL<Wide> wide = splat_frustum<Wide>(a.planes);
  const FrustumL<float> one = splat_frustum<float>(a.planes);
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const FrustumL<L>* f;
    if constexpr (std::is_same_v<L, float>) f = &one;
    else f = &wide;
    const auto side = frustum_side(*f, load_shape<T, L>(a.shapes, i));
    store_bits(a.visible_out + i, select(side.outside, from_bits<L>(0u), from_bits<L>(1u)));
  });
}

}  // namespace

GYRO_FLATTEN void frustum_cull_batch(const FrustumCullArgs& a, std::size_t begin, std::size_t end) {
  switch (a.shapes.type) {
    case ShapeType::sphere: run<ShapeType::sphere>(a, begin, end); break;
    case ShapeType::aabb: run<ShapeType::aabb>(a, begin, end); break;
    case ShapeType::obb: run<ShapeType::obb>(a, begin, end); break;
    default: break;  // the caller checked the type
  }
}

}  // namespace gyro::GYRO_ARCH_NS
