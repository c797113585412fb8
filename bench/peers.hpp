// Peer libraries measured side by side on the same inputs (BENCHMARKS.md). Each peer is
// compiled only when its library is installed; its functions report availability.
#pragma once

#include "workloads.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro::bench {

/// Verdict (and depth where the method gives one) for every N1 pair. Depth > 0 means
/// penetration; 0 when the method reports none.
struct PairResults {
  std::vector<uint8_t> hit;
  std::vector<double> depth;
};

enum class CcdMethod { gjk_intersect, mpr_intersect, gjk_epa_penetration, mpr_penetration };

bool bullet_available();
/// btBoxBoxDetector on pairs [0, n).
void bullet_box_box(const testing::BoxPairs& pairs, std::size_t n, PairResults& out);

bool ccd_available();
void ccd_box_box(const testing::BoxPairs& pairs, std::size_t n, CcdMethod method, PairResults& out);

}  // namespace gyro::bench
