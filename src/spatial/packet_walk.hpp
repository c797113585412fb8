// The packet walk over an 8-wide BVH, shared by the mesh kernel (bvh_kernels.cpp) and the
// scene kernel (scene_kernels.cpp), compiled at each including translation unit's level.
//
// Eight rays from one origin (a lidar column, a camera row) enter nearly the same nodes, so
// a packet walks the tree once for all of them: each child box is tested against the eight
// rays in one 8-wide lane (the kernel's `enter`, which computes its single walk's expression
// for each ray, so every (ray, box) pair gives the single walk's bits); a child is entered by
// the rays whose test passed; children are visited nearest first by the entry of the first
// ray in them (ties keep the slot order); the stack keeps each ray's entry distance, so a pop
// drops the rays whose limit has moved in front of their entry. Leaves go to the kernel's
// `visit`, which tests them ray by ray and lowers the rays' limits. A ray's answer is the
// single walk's: which nodes it visits, and in what order, only decides which subtrees its
// limit lets it skip, and its conservative box tests never skip the winner's (the exactness
// notes of bvh_kernels.cpp and scene.cpp). The traversal's bookkeeping is paid once per
// packet instead of once per ray.
#pragma once

#include "core/lanes.hpp"
#include "spatial/bvh.hpp"

#include <cstdint>

namespace gyro::GYRO_ARCH_NS::packet {

inline constexpr int kRays = 8;

struct Entry {
  float near[kRays];  // per ray: where it enters the box (meaningful where mask says)
  uint32_t code;
  unsigned mask;      // the rays that entered it
};

/// Walks the tree from the root for the rays in `rays` (bit r: ray r). limit[r] is ray r's
/// limit (an entry beyond it is skipped), lowered by `visit`; stack holds
/// detail::kBvhStackSize entries.
///   unsigned enter(const BvhNode8& node, int c, const Oct& limit, Oct& tn): each ray's
///     entry into child c's box in tn; returns bit r set where ray r enters it by its limit.
///   void visit(uint32_t leaf_code, unsigned mask): tests the leaf for the rays in mask and
///     lowers their limit[].
template <class Enter, class Visit>
inline void walk(const detail::BvhNode8* nodes, Entry* stack, float* limit, unsigned rays, Enter&& enter, Visit&& visit) {
  int sp = 0;
  uint32_t code = 0;
  unsigned mask = rays;
  for (;;) {
    if (code & detail::kLeafBit) {
      visit(code, mask);
    } else {
      const detail::BvhNode8& node = nodes[code];
      const Oct lim = load<Oct>(limit);
      alignas(32) float nears[8][kRays];
      unsigned entered[8];
      int order[8], n = 0;
      for (int c = 0; c < 8; ++c) {
        if (node.child[c] == detail::kEmptyChild) continue;
        Oct tn;
        const unsigned in = enter(node, c, lim, tn) & mask;
        if (in == 0) continue;
        store(nears[c], tn);
        entered[c] = in;
        const float key = nears[c][__builtin_ctz(in)];
        int j = n++;
        while (j > 0 && nears[order[j - 1]][__builtin_ctz(entered[order[j - 1]])] > key) order[j] = order[j - 1], --j;
        order[j] = c;
      }
      for (int j = n - 1; j > 0; --j) {  // farthest first, so the nearest pops first
        Entry& e = stack[sp++];
        const int c = order[j];
        for (int r = 0; r < kRays; ++r) e.near[r] = nears[c][r];
        e.code = node.child[c], e.mask = entered[c];
      }
      if (n > 0) {
        const int c = order[0];
        const unsigned live = entered[c] & lane_bits(load<Oct>(nears[c]) <= lim);
        if (live != 0) {
          code = node.child[c], mask = live;
          continue;
        }
      }
    }
    for (;;) {  // the next entry that some of its rays still enter within their limit
      if (sp == 0) return;
      const Entry& e = stack[--sp];
      const unsigned live = e.mask & lane_bits(load<Oct>(e.near) <= load<Oct>(limit));
      if (live == 0) continue;
      code = e.code, mask = live;
      break;
    }
  }
}

}  // namespace gyro::GYRO_ARCH_NS::packet
