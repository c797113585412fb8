// overlap_batch at this translation unit's SIMD level.
//
// Inputs: two SoA shape arrays; pairs are (a[i], b[i]), or one side is a single shape
// broadcast to every lane. Output: one uint32 verdict per pair (and, for OBB pairs, the
// signed separation where asked). The shape tests are the lane templates the scalar API
// runs, so lane k computes exactly what the scalar overlaps() computes for pair k. The
// type dispatch happens once per call, outside the loops.
#include "geometry/overlap_batch.hpp"
#include "geometry/overlap_lanes.hpp"
#include "geometry/triangle_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

// Element i of an array (element 0 broadcast to every lane when the array is a single shape).
template <ShapeType T, class L> inline auto get_shape(const ShapeArray& v, bool single, std::size_t i) {
  if constexpr (T == ShapeType::sphere) return single ? splat_sphere<L>(v.spheres, 0) : load_sphere<L>(v.spheres, i);
  else if constexpr (T == ShapeType::aabb) return single ? splat_aabb<L>(v.aabbs, 0) : load_aabb<L>(v.aabbs, i);
  else if constexpr (T == ShapeType::obb) return single ? splat_obb<L>(v.obbs, 0) : load_obb<L>(v.obbs, i);
  else if constexpr (T == ShapeType::plane) return single ? splat_plane<L>(v.planes, 0) : load_plane<L>(v.planes, i);
  else return single ? splat_triangle<L>(v.triangles, 0) : load_triangle<L>(v.triangles, i);
}

// out[i] = kOverlapping / kSeparated, or kInvalidInput where an input is not finite or a
// size is negative (checked in the same pass: a separate pass would cost as much as the test).
template <ShapeType TA, ShapeType TB> void run_pairs(const OverlapArgs& args, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const auto a = get_shape<TA, L>(args.a, args.a_single, i);
    const auto b = get_shape<TB, L>(args.b, args.b_single, i);
    const auto hit = overlaps(a, b);
    const L verdict = select(hit, from_bits<L>(kOverlapping), from_bits<L>(kSeparated));
    store_bits(args.out + i, select(valid(a) && valid(b), verdict, from_bits<L>(kInvalidInput)));
  });
}

constexpr uint32_t pair_code(ShapeType a, ShapeType b) { return uint32_t(a) * 8u + uint32_t(b); }

}  // namespace

GYRO_FLATTEN void overlap_batch(const OverlapArgs& args, std::size_t begin, std::size_t end) {
  using T = ShapeType;
  if (args.out) {
    switch (pair_code(args.a.type, args.b.type)) {
#define GYRO_PAIR_(A, B)                   \
  case pair_code(T::A, T::B):              \
    run_pairs<T::A, T::B>(args, begin, end); \
    break;
      GYRO_PAIR_(sphere, sphere) GYRO_PAIR_(sphere, aabb) GYRO_PAIR_(sphere, obb) GYRO_PAIR_(sphere, plane)
      GYRO_PAIR_(aabb, aabb) GYRO_PAIR_(aabb, obb) GYRO_PAIR_(aabb, plane) GYRO_PAIR_(obb, obb)
      GYRO_PAIR_(obb, plane) GYRO_PAIR_(plane, plane) GYRO_PAIR_(sphere, triangle) GYRO_PAIR_(aabb, triangle)
      GYRO_PAIR_(obb, triangle) GYRO_PAIR_(plane, triangle) GYRO_PAIR_(triangle, triangle)
#undef GYRO_PAIR_
      default: break;
    }
  }
  if (args.separation && args.a.type == T::obb && args.b.type == T::obb) {
    for_lanes(begin, end, [&](auto tag, std::size_t i) {
      using L = decltype(tag);
      store(args.separation + i, obb_obb_separation(get_shape<T::obb, L>(args.a, args.a_single, i),
                                                    get_shape<T::obb, L>(args.b, args.b_single, i)));
    });
  }
}

}  // namespace gyro::GYRO_ARCH_NS
