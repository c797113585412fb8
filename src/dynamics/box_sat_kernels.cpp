// The box-box separating axis test at this translation unit's SIMD level, one pair per lane.
#include "dynamics/box_sat.hpp"
#include "dynamics/box_sat_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

template <class L> void test_pairs(const detail::BoxSatArgs& a, std::size_t i) {
  auto in = [&](uint32_t c) { return load<L>(a.in + c * a.stride + i); };
  auto out = [&](uint32_t c, L v) { store(a.out + c * a.stride + i, v); };
  BoxLanes<L> fa, fb;
  for (uint32_t k = 0; k < 3; ++k) {
    fa.u[k] = {in(detail::kSatUa + 3 * k), in(detail::kSatUa + 3 * k + 1), in(detail::kSatUa + 3 * k + 2)};
    fb.u[k] = {in(detail::kSatUb + 3 * k), in(detail::kSatUb + 3 * k + 1), in(detail::kSatUb + 3 * k + 2)};
    fa.e[k] = in(detail::kSatEa + k), fb.e[k] = in(detail::kSatEb + k);
  }
  const V3<L> d{in(detail::kSatD), in(detail::kSatD + 1), in(detail::kSatD + 2)};
  const BoxSatLanes<L> r = box_sat(fa, fb, d, in(detail::kSatMargin));
  out(detail::kSatHit, select(r.hit, L(1.0f), L(0.0f)));
  out(detail::kSatSa, r.sa), out(detail::kSatSb, r.sb), out(detail::kSatSe, r.se);
  out(detail::kSatIa, r.ia), out(detail::kSatJb, r.jb), out(detail::kSatIe, r.ie), out(detail::kSatJe, r.je);
  out(detail::kSatNormal, r.edge_normal.x), out(detail::kSatNormal + 1, r.edge_normal.y);
  out(detail::kSatNormal + 2, r.edge_normal.z);
}

}  // namespace

GYRO_FLATTEN void box_sat_batch(const detail::BoxSatArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { test_pairs<decltype(tag)>(a, i); });
}

}  // namespace gyro::GYRO_ARCH_NS
