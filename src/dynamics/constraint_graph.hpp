// Constraint graph colouring: constraints that share no dynamic body get the same colour, so
// a colour's constraints can be solved in parallel and in SIMD lanes, in any grouping, with
// the result of a sequential pass. Greedy, in constraint order (which is id order), so the
// colouring depends only on the constraints.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro::detail {

struct ColorPlan {
  std::vector<uint32_t> order;        ///< constraint indices, colour after colour
  std::vector<uint32_t> color_first;  ///< per colour, its first entry in `order` (+ one past the end)
  std::vector<uint32_t> padded_first; ///< per colour, its first slot in the padded layout (a multiple of align)
  std::vector<uint32_t> padded_end;   ///< per colour, one past the last slot a pass visits
  std::size_t padded_total = 0;       ///< slots in the padded layout (a multiple of align)
  uint32_t colors() const { return color_first.empty() ? 0 : uint32_t(color_first.size() - 1); }
};

/// body_a/body_b: solver body per constraint; writable[body] says whether it is dynamic (only
/// those constrain the colouring). Every colour starts at a multiple of `align`; a pass visits a
/// large colour's slots up to a multiple of `align`, a small one's up to a multiple of 4.
class ConstraintGraph {
 public:
  void color(const uint32_t* body_a, const uint32_t* body_b, std::size_t count, const uint8_t* writable,
             std::size_t body_count, std::size_t align, ColorPlan& plan);

 private:
  std::vector<uint64_t> used_;
  std::vector<uint32_t> color_of_, remaining_, next_;
  std::vector<uint32_t> counts_;
};

}  // namespace gyro::detail
