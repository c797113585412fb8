#include "dynamics/constraint_graph.hpp"

#include <bit>

namespace gyro::detail {

void ConstraintGraph::color(const uint32_t* body_a, const uint32_t* body_b, std::size_t count, const uint8_t* writable,
                            std::size_t body_count, std::size_t align, ColorPlan& plan) {
  color_of_.resize(count);
  remaining_.resize(count);
  for (std::size_t i = 0; i < count; ++i) remaining_[i] = uint32_t(i);
  used_.resize(body_count);
  counts_.clear();
  // Rounds of 64 colours (one bit each per body); what does not fit goes to the next round.
  uint32_t base = 0;
  std::size_t left = count;
  while (left > 0) {
    for (std::size_t b = 0; b < body_count; ++b) used_[b] = 0;
    next_.clear();
    for (std::size_t k = 0; k < left; ++k) {
      const uint32_t i = remaining_[k];
      const uint32_t a = body_a[i], b = body_b[i];
      const uint64_t busy = (writable[a] ? used_[a] : 0) | (writable[b] ? used_[b] : 0);
      if (busy == ~uint64_t{0}) {
        next_.push_back(i);
        continue;
      }
      const uint32_t c = uint32_t(std::countr_one(busy));
      if (writable[a]) used_[a] |= uint64_t{1} << c;
      if (writable[b]) used_[b] |= uint64_t{1} << c;
      color_of_[i] = base + c;
      if (counts_.size() <= base + c) counts_.resize(base + c + 1, 0);
      ++counts_[base + c];
    }
    remaining_.assign(next_.begin(), next_.end());
    left = remaining_.size();
    base += 64;
  }
  // Drop empty colours (a round may leave gaps) and lay the colours out.
  const uint32_t ncolors = uint32_t(counts_.size());
  std::vector<uint32_t>& remap = next_;
  remap.assign(ncolors, 0);
  plan.color_first.clear();
  plan.padded_first.clear();
  plan.padded_end.clear();
  uint32_t first = 0, padded = 0, used = 0;
  for (uint32_t c = 0; c < ncolors; ++c) {
    if (counts_[c] == 0) continue;
    remap[c] = used++;
    plan.color_first.push_back(first);
    plan.padded_first.push_back(padded);
    first += counts_[c];
    // Small colours are visited up to a multiple of 4 only: a kernel runs its widest lanes
    // over whole batches and the float lane over the rest, with the same results, so visiting
    // 16 slots for a colour of 3 would only add work. The next colour still starts aligned
    // (the fields are laid out in blocks of `align`).
    const std::size_t pad = counts_[c] >= 4 * align ? align : 4;
    plan.padded_end.push_back(padded + uint32_t((counts_[c] + pad - 1) / pad * pad));
    padded += uint32_t((counts_[c] + align - 1) / align * align);
  }
  plan.color_first.push_back(first);
  plan.padded_first.push_back(padded);
  plan.padded_total = padded;
  plan.order.resize(count);
  // Counting sort by colour, stable in constraint order.
  std::vector<uint32_t>& cursor = counts_;
  for (uint32_t c = 0, k = 0; c < ncolors; ++c)
    if (cursor[c] != 0) cursor[c] = plan.color_first[k++];
  for (std::size_t i = 0; i < count; ++i) plan.order[cursor[color_of_[i]]++] = uint32_t(i);
  (void)remap;
}

}  // namespace gyro::detail
