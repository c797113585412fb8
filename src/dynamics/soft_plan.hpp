// The solve order of a soft body's springs: greedy colouring in creation order (springs of
// one colour share no particle, so a colour can be solved in any grouping with the same
// bits), and within a colour, runs: maximal stretches where both particle indices rise by
// one from spring to spring. A contiguous run is solved with unit-stride loads and stores
// (a cloth grid's layout makes every spring family such runs); what is left is gathered in
// indexed runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gyro::detail {

/// Springs [first, first + count) of the solve order. Contiguous: spring first + k joins
/// particles a0 + k and b0 + k; indexed: the solve-order index columns name them.
struct SpringRun {
  uint32_t first = 0, count = 0;
  uint32_t a0 = 0, b0 = 0;
  uint32_t contiguous = 0;
};

struct SoftPlan {
  std::vector<uint32_t> order;        ///< order[k]: creation index of the k-th spring solved
  std::vector<uint32_t> color_runs;   ///< runs of colour c: [color_runs[c], color_runs[c + 1])
  std::vector<SpringRun> runs;
  std::size_t colors() const { return color_runs.empty() ? 0 : color_runs.size() - 1; }
};

/// Contiguous stretches shorter than this are gathered instead (a run per spring would cost
/// more in loop overhead than the gathers save).
inline constexpr uint32_t kMinContiguousRun = 4;

/// Builds the plan for springs (a[k], b[k]) over `particles` particles (a[k] != b[k]).
SoftPlan build_soft_plan(std::span<const uint32_t> a, std::span<const uint32_t> b, std::size_t particles);

}  // namespace gyro::detail
