// Broadphase: the pairs of bodies whose bounding boxes overlap, in id order.
//
// Input is SoA bounds (a box with a NaN or infinite bound is left out), the collision filter and per-body flags; output is the
// candidate pairs (slot a, slot b) with key[a] < key[b], sorted by (key[a], key[b]), where
// key is the body's id index (unique), so the list depends only on the bodies, never on
// slots, threads or SIMD width. A pair is reported when the closed boxes overlap, the
// filter passes ((cat[a] & mask[b]) && (cat[b] & mask[a])), at least one body is dynamic
// and at least one is active (awake dynamic or kinematic).
//
// The method (broadphase.cpp): sweep-and-prune along the axis of largest spread, inside the
// cells of a coarse grid on the other two axes (so a wide pile does not turn the sweep into
// slab scans, and a huge ground box is one cheap scan per cell), active bodies swept
// against themselves and against the passive ones (passive-passive pairs are never
// visited), radix sorts throughout (stable: the result is a pure function of the input).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro::detail {

inline constexpr uint8_t kBroadDynamic = 1;  ///< the body is dynamic
inline constexpr uint8_t kBroadActive = 2;   ///< the body moves this step (awake dynamic, or kinematic)

struct BroadphaseInput {
  std::size_t count = 0;
  const float *min_x = nullptr, *min_y = nullptr, *min_z = nullptr;
  const float *max_x = nullptr, *max_y = nullptr, *max_z = nullptr;
  const uint32_t* category = nullptr;
  const uint32_t* mask = nullptr;
  const uint8_t* flags = nullptr;  ///< kBroadDynamic | kBroadActive
  const uint32_t* key = nullptr;   ///< unique per body (the id index)
};

struct BroadPair {
  uint32_t a, b;  ///< slots, key[a] < key[b]
};

/// Keeps its scratch between calls: after warm-up, find_pairs allocates only when the body
/// or pair count grows.
class Broadphase {
 public:
  /// Replaces `pairs` with the sorted pair list.
  void find_pairs(const BroadphaseInput& in, std::vector<BroadPair>& pairs);

 private:
  /// One box in one cell, as the sweep reads it (48 bytes, one stream per cell). The bounds
  /// on the two axes that are not swept (u, w) are stored as {u_lo, w_lo, -u_hi, -w_hi}, so
  /// one 4-lane compare tests both overlaps.
  struct alignas(16) SweepItem {
    float lo, hi;        ///< on the sweep axis
    uint32_t cell_lo;    ///< the cell of the box's low corner: band on u << 16 | band on w
    uint32_t rank_dyn;   ///< key rank << 1 | dynamic
    float bounds[4];
    uint32_t category, mask;
    uint32_t cell_hi;    ///< the cell of the high corner (used while placing the copies)
    uint32_t unused;
  };
  /// One list (active or passive) in sweep order, cell by cell. Each cell is closed by a
  /// sentinel whose lo is +inf, so a scan stops there with one compare.
  struct SweepList {
    std::vector<SweepItem> items;
    std::vector<uint32_t> cell_begin;  ///< items of cell c: [cell_begin[c], cell_begin[c+1] - 1)
  };
  /// Bands along one axis: band(x) = clamp(floor((x - origin) * scale), 0, count - 1).
  struct Bands {
    uint32_t count = 1;
    float origin = 0.0f, scale = 0.0f;
    uint32_t of(float x) const {
      const float f = (x - origin) * scale;
      if (!(f > 0.0f)) return 0;
      if (f >= static_cast<float>(count)) return count - 1;
      const uint32_t b = static_cast<uint32_t>(f);
      return b < count ? b : count - 1;
    }
  };

  void compute_ranks(const BroadphaseInput& in);
  void choose_axes(const BroadphaseInput& in);
  void build_list(const BroadphaseInput& in, const std::vector<uint32_t>& slots, SweepList& out);
  void sweep_cell(uint32_t cell, bool with_passive, std::vector<uint64_t>& out) const;
  template <class OnOverlap> static void scan(const SweepItem* o, std::size_t j, const SweepItem& q,
                                              OnOverlap&& on_overlap);
  void emit_if_accepted(const SweepItem& q, const SweepItem& o, uint32_t cell_u, uint32_t cell_w,
                        std::vector<uint64_t>& out) const;

  // Per-call settings.
  int axis_[3] = {0, 1, 2};  ///< sweep axis, u, w
  Bands band_u_, band_w_;
  unsigned rank_bits_ = 1;

  // Scratch, kept between calls so a warm call allocates nothing.
  std::vector<uint32_t> active_slots_, passive_slots_;
  std::vector<uint32_t> rank_of_slot_, slot_of_rank_;
  std::vector<uint64_t> sort_keys_, sort_tmp_;
  std::vector<uint32_t> counts_, cell_count_;
  std::vector<SweepItem> box_scratch_;  ///< per box, in list order
  SweepList active_, passive_;
  std::vector<std::vector<uint64_t>> chunk_pairs_;  ///< per sweep chunk
  std::vector<uint64_t> pair_keys_;
};

}  // namespace gyro::detail
