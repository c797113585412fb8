#include "dynamics/islands.hpp"

#include <utility>

namespace gyro::detail {

uint32_t Islands::find(uint32_t x) {
  while (parent_[x] != x) {
    parent_[x] = parent_[parent_[x]];
    x = parent_[x];
  }
  return x;
}

void Islands::build(const BodyStore& s, const std::vector<ContactRecord>& records) {
  const uint32_t n = s.size();
  parent_.resize(n);
  label_.resize(n);
  for (uint32_t i = 0; i < n; ++i) parent_[i] = i;
  for (const ContactRecord& r : records) {
    if (!s.is_dynamic(r.slot_a) || !s.is_dynamic(r.slot_b) || !r.touching()) continue;
    uint32_t x = find(r.slot_a), y = find(r.slot_b);
    if (x == y) continue;
    if (y < x) std::swap(x, y);
    parent_[y] = x;  // the lower slot is the root: the result depends only on the edges
  }
  count_ = 0;
  for (uint32_t i = 0; i < n; ++i) {
    if (!s.is_dynamic(i)) {
      label_[i] = kNone;
      continue;
    }
    const uint32_t root = find(i);
    label_[i] = root == i ? count_++ : label_[root];
  }
}

}  // namespace gyro::detail
