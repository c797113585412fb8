// overlap_batch at this translation unit's SIMD level.
//
// Inputs: two SoA shape arrays; pairs are (a[i], b[i]) or (a[0], b[i]). Output: one
// uint32 verdict per pair (and the signed separation where asked). The shape tests are
// the lane templates the scalar API also runs, so lane k computes exactly what the scalar
// call computes for pair k; the kind dispatch happens once per call, outside the loops.
#include "geometry/obb_obb_lanes.hpp"
#include "geometry/overlap_batch.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

// Element i of an array (i = 0 broadcast when the array is a single shape).
template <class L> inline ObbL<L> get_obb(const ShapeArray& v, bool single, std::size_t i) {
  return single ? splat_obb<L>(v.obbs, 0) : load_obb<L>(v.obbs, i);
}

// out[i] = kOverlapping / kSeparated, or kInvalidInput where an input is not finite or a
// size is negative (checked in the same pass: a separate pass would cost as much as the test).
template <class GetA, class GetB, class Test>
void run_pairs(const OverlapArgs& args, std::size_t begin, std::size_t end, GetA&& get_a, GetB&& get_b, Test&& test) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const auto a = get_a(tag, i);
    const auto b = get_b(tag, i);
    const auto hit = test(a, b);
    const L verdict = select(hit, from_bits<L>(kOverlapping), from_bits<L>(kSeparated));
    store_bits(args.out + i, select(valid(a) && valid(b), verdict, from_bits<L>(kInvalidInput)));
  });
}

}  // namespace

// flatten: inline the whole per-batch body, so shapes stay in registers instead of being
// returned through the stack (a 16-lane OBB is 960 bytes).
[[gnu::flatten]] void overlap_batch(const OverlapArgs& args, std::size_t begin, std::size_t end) {
  const ShapeType ta = args.a.type, tb = args.b.type;
  auto obb_a = [&](auto tag, std::size_t i) { return get_obb<decltype(tag)>(args.a, args.a_single, i); };
  auto obb_b = [&](auto tag, std::size_t i) { return get_obb<decltype(tag)>(args.b, args.b_single, i); };
  if (ta == ShapeType::obb && tb == ShapeType::obb) {
    if (args.out)
      run_pairs(args, begin, end, obb_a, obb_b, [](const auto& a, const auto& b) { return obb_obb_overlap(a, b); });
    if (args.separation) {
      for_lanes(begin, end, [&](auto tag, std::size_t i) {
        store(args.separation + i, obb_obb_separation(obb_a(tag, i), obb_b(tag, i)));
      });
    }
  }
}

}  // namespace gyro::GYRO_ARCH_NS
