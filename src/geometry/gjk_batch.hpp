// The batch box-box GJK: the relative frames of many box pairs and GJK itself run over SIMD
// lanes, one pair per lane (gjk_kernels.cpp, compiled once per level). The lane loop
// performs gjk.cpp's gjk_typed<box, box> operation for operation, so every pair ends with
// the simplex, weights and flags the scalar query computes; gjk.cpp turns them into results
// (and runs EPA on the pairs that need it) with the scalar query's own code.
#pragma once

#include "core/dispatch.hpp"
#include "gyro/convex.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Outcome of up to kMax pairs, SoA; element k is pair begin + k.
struct BoxGjkBlock {
  static constexpr std::size_t kMax = 128;
  // The frame, exactly as gjk.cpp's make_frame computes it.
  float rot[9][kMax];  // B's rotation in A's frame, rot[3 * r + c] = rot_b.m[r][c]
  float pos[3][kMax];  // B's origin in A's frame
  float scale[kMax];   // the pair's size, at least 1e-30
  // kScalar: invalid or outside the range the batch handles (run the scalar query);
  // kDone: the fields below hold GJK's end state.
  uint32_t code[kMax];
  static constexpr uint32_t kScalar = 0, kDone = 1;
  // GJK's end state (GjkOut): simplex points on A and B in simplex order, their weights,
  // the closest point v and |v|^2, flags and the iteration count.
  float a[4][3][kMax], b[4][3][kMax];
  float lambda[4][kMax];
  float v[3][kMax], vv[kMax];
  uint32_t n[kMax], iterations[kMax], flags[kMax];
  static constexpr uint32_t kEnclosed = 1, kFull = 2, kEarly = 4, kLimit = 8;
  float nf[kMax];    // n as a float, for the lanes below
  // How GJK ended: 0 enclosing the origin; else with the cores apart: 1 converged,
  // 2 at the iteration limit, 3 at a separating axis (the boolean exit).
  float apart[kMax];
  // Distance and penetration mode: the result of a pair whose cores ended apart (gjk.cpp's
  // conclude, its first branch, over lanes), valid where done[k] is 1 (else the caller
  // forms the result itself: the origin enclosed, or an output not finite).
  float r_status[kMax], r_distance[kMax], r_normal[3][kMax], r_point_a[3][kMax], r_point_b[3][kMax], done[kMax];
};

/// The lanes' working state between rounds (one GJK iteration per round over the pairs
/// still running, packed to the front so every lane has work).
struct BoxGjkWork {
  static constexpr std::size_t kMax = BoxGjkBlock::kMax;
  uint32_t pair[kMax];  // block index k of the pair in this slot
  float ha[3][kMax], hb[3][kMax], rot[9][kMax], pos[3][kMax], sep_sq[kMax], abs_sq[kMax];
  // The simplex: its points on A and B and their weights where results are formed, else
  // (verdicts) only its points of A - B.
  float a[4][3][kMax], b[4][3][kMax], lambda[4][kMax], w[4][3][kMax], v[3][kMax], vv[kMax], n[kMax], it[kMax];
  uint32_t state[kMax];  // after a round: 0 still running, else kDone | BoxGjkBlock flags << 1
};

struct BoxGjkParams {
  float touch_tolerance = 1e-6f;
  uint32_t max_iterations = 64;
  bool boolean = true;  // GJK's early exit on a separating direction
  // convex_intersect: statuses only (else results are formed). The lanes then carry only the
  // simplex's points of A - B, and a pair that ends enclosing the origin with fewer than four
  // points (EPA's touching test needs the points on A and B) is left to the scalar query.
  bool verdict_only = true;
  bool penetration = false;  // results as convex_penetration's (else convex_distance's)
};

/// Pairs [begin, end), end - begin <= BoxGjkBlock::kMax.
using box_gjk_fn = void(const ConvexBoxPairs&, std::size_t begin, std::size_t end, const BoxGjkParams&,
                        BoxGjkBlock&, BoxGjkWork&);
GYRO_KERNEL(box_gjk, box_gjk_fn)

}  // namespace gyro
