// Colouring and runs of a soft body's springs (see soft_plan.hpp).
#include "dynamics/soft_plan.hpp"

namespace gyro::detail {

namespace {

/// Greedy first-fit colours in creation order, as 64-colour masks per particle (more words
/// when a particle needs more colours). Creation order is a function of the body alone, so
/// the colouring is too.
std::vector<uint32_t> color_springs(std::span<const uint32_t> a, std::span<const uint32_t> b, std::size_t particles,
                                    uint32_t* color_count) {
  std::size_t words = 1;
  std::vector<uint64_t> used(particles, 0);
  std::vector<uint32_t> color(a.size());
  uint32_t colors = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::size_t pa = a[k], pb = b[k];
    uint32_t c = 0;
    for (;;) {
      std::size_t w = 0;
      for (; w < words; ++w) {
        const uint64_t free_bits = ~(used[pa * words + w] | used[pb * words + w]);
        if (free_bits) {
          c = static_cast<uint32_t>(w * 64 + static_cast<uint32_t>(__builtin_ctzll(free_bits)));
          break;
        }
      }
      if (w < words) break;
      // Every colour so far is taken at one end: widen the masks by a word.
      std::vector<uint64_t> wider(particles * (words + 1), 0);
      for (std::size_t p = 0; p < particles; ++p)
        for (std::size_t v = 0; v < words; ++v) wider[p * (words + 1) + v] = used[p * words + v];
      used.swap(wider);
      ++words;
    }
    used[pa * words + c / 64] |= uint64_t{1} << (c % 64);
    used[pb * words + c / 64] |= uint64_t{1} << (c % 64);
    color[k] = c;
    if (c + 1 > colors) colors = c + 1;
  }
  *color_count = colors;
  return color;
}

}  // namespace

SoftPlan build_soft_plan(std::span<const uint32_t> a, std::span<const uint32_t> b, std::size_t particles) {
  SoftPlan plan;
  uint32_t colors = 0;
  const std::vector<uint32_t> color = color_springs(a, b, particles, &colors);

  // Counting sort by colour, stable: within a colour, creation order.
  std::vector<uint32_t> start(colors + 1, 0);
  for (uint32_t c : color) ++start[c + 1];
  for (uint32_t c = 0; c < colors; ++c) start[c + 1] += start[c];
  plan.order.resize(a.size());
  {
    std::vector<uint32_t> at(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < a.size(); ++k) plan.order[at[color[k]]++] = static_cast<uint32_t>(k);
  }

  plan.color_runs.push_back(0);
  for (uint32_t c = 0; c < colors; ++c) {
    SpringRun gathered;  // the open indexed run of this colour, if any
    auto close_gathered = [&] {
      if (gathered.count) plan.runs.push_back(gathered);
      gathered = SpringRun{};
    };
    uint32_t k = start[c];
    while (k < start[c + 1]) {
      uint32_t n = 1;
      while (k + n < start[c + 1] && a[plan.order[k + n]] == a[plan.order[k]] + n && b[plan.order[k + n]] == b[plan.order[k]] + n) ++n;
      if (n >= kMinContiguousRun) {
        close_gathered();
        plan.runs.push_back({k, n, a[plan.order[k]], b[plan.order[k]], 1});
      } else {
        if (!gathered.count) gathered.first = k;
        gathered.count += n;
      }
      k += n;
    }
    close_gathered();
    plan.color_runs.push_back(static_cast<uint32_t>(plan.runs.size()));
  }
  return plan;
}

}  // namespace gyro::detail
