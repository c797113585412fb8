#include "core/lanes.hpp"
#include "lanes_probe.hpp"

namespace gyro::GYRO_ARCH_NS {

namespace {
template <class L> void probe_at(const LaneProbeArgs& p, std::size_t i) {
    const L a = load<L>(p.a + i), b = load<L>(p.b + i);
    const L one(1.0f), zero(0.0f);
    const L results[kLaneProbeOps] = {
        a + b, a - b, a * b, a / b, sqrt(a), abs(a), -a, copysign(a, b), min(a, b), max(a, b),
        select(a < b, one, zero), select(a <= b, one, zero), select(a > b, one, zero), select(a >= b, one, zero),
        select(a == b, one, zero), select(a != b, one, zero), select((a < b) && (b > zero), one, zero),
        select((a < b) || !(b > zero), one, zero), select(a < b, a, b), a + L(0.0f), a * L(0.0f),
        from_bits<L>(0x7f7fffffu) + a};
    for (int k = 0; k < kLaneProbeOps; ++k) store(p.out[k] + i, results[k]);
}
}  // namespace

void lanes_probe(const LaneProbeArgs& p, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { probe_at<decltype(tag)>(p, i); });
}

void oct_probe(const LaneProbeArgs& p, std::size_t begin, std::size_t end) {
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) probe_at<Oct>(p, i);
  for (; i < end; ++i) probe_at<float>(p, i);
}

void quad_probe(const LaneProbeArgs& p, std::size_t begin, std::size_t end) {
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) probe_at<Quad>(p, i);
  for (; i < end; ++i) probe_at<float>(p, i);
}

}  // namespace gyro::GYRO_ARCH_NS
