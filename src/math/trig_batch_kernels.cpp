// trig_batch at this translation unit's SIMD level: out[i] = op(x[i]) (atan2: op(y[i], x[i])).
#include "math/trig_batch.hpp"
#include "math/trig_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

void trig_batch(const TrigBatchArgs& a, std::size_t begin, std::size_t end) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const L x = load<L>(a.x + i);
    L r;
    switch (a.op) {
      case TrigOp::sin: r = sin(x); break;
      case TrigOp::cos: r = cos(x); break;
      case TrigOp::tan: r = tan(x); break;
      case TrigOp::asin: r = asin(x); break;
      case TrigOp::acos: r = acos(x); break;
      case TrigOp::atan: r = atan(x); break;
      case TrigOp::atan2: r = atan2(load<L>(a.y + i), x); break;
      default: r = x; break;
    }
    store(a.out + i, r);
  });
}

}  // namespace gyro::GYRO_ARCH_NS
