// Islands: groups of dynamic bodies connected by touching contacts. An island sleeps as a
// whole when every body in it has rested long enough, and wakes as a whole when any body in
// it is disturbed, so a resting pile costs nothing and never sleeps half-way.
#pragma once

#include "dynamics/body_store.hpp"
#include "dynamics/contacts.hpp"

#include <cstdint>
#include <vector>

namespace gyro::detail {

class Islands {
 public:
  /// Union-find over the dynamic bodies joined by touching records; islands are numbered in
  /// order of their lowest slot.
  void build(const BodyStore& bodies, const std::vector<ContactRecord>& records);
  uint32_t count() const { return count_; }
  uint32_t island_of(uint32_t slot) const { return label_[slot]; }  ///< kNone for static/kinematic
  static constexpr uint32_t kNone = 0xFFFFFFFFu;

 private:
  uint32_t find(uint32_t x);
  std::vector<uint32_t> parent_, label_;
  uint32_t count_ = 0;
};

}  // namespace gyro::detail
