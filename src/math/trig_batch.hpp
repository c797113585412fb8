// Batch evaluation of gyro's trigonometry over arrays, at any SIMD level: what the
// determinism tests compare across levels, and what a caller with many angles uses.
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>

namespace gyro {

enum class TrigOp : uint32_t { sin, cos, tan, asin, acos, atan, atan2 };

struct TrigBatchArgs {
  TrigOp op;
  const float* x;  // for atan2: the x argument
  const float* y;  // atan2 only
  float* out;
};

using trig_batch_fn = void(const TrigBatchArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(trig_batch, trig_batch_fn)

}  // namespace gyro
