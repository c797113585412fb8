// The batch overlap kernel: pairwise (a[i] with b[i]) or one against many (a[0] with
// b[i]) over SoA shape arrays, one pair per lane.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/batch_overlap.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

struct OverlapArgs {
  ShapeArray a, b;      // types in canonical order: a.type <= b.type
  bool a_single;        // a[0] against every b[i] (else pairwise)
  bool b_single;        // every a[i] against b[0]
  uint32_t* out;        // kOverlapping or kSeparated per pair; may be null
  float* separation;    // OBB pairs only, may be null: signed gap, < 0 is -penetration depth
};

/// True for the type pairs (in canonical order) the kernel implements.
inline bool overlap_pair_supported(ShapeType a, ShapeType b) { return a <= b; }

/// Elements [begin, end).
using overlap_batch_fn = void(const OverlapArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(overlap_batch, overlap_batch_fn)

}  // namespace gyro
