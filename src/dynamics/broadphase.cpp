// Broadphase: sweep-and-prune inside the cells of a coarse grid (contract: broadphase.hpp).
//
// 1. Bodies split into the active list (awake dynamic or kinematic) and the passive list
//    (the rest). A pair needs an active body, so passive-passive pairs are never looked
//    at, and a passive box outside the union of the active boxes is dropped at once.
// 2. The sweep axis is the one along which the box centres spread most (variance in
//    binary64, summed in slot order); the other two axes (u, w) are cut into bands a few
//    typical box sizes wide, making a coarse grid of cells. A box goes into every cell its
//    extent touches, so a 1D sweep along a wide pile only meets the boxes of its own cell,
//    not a whole slab of the scene, and a huge ground box costs one copy per cell, each of
//    which scans only that cell once (never a quadratic sweep). A pair that shares several
//    cells is reported only in the cell holding the low corner of the two boxes' overlap
//    on (u, w), so it is reported once.
// 3. Each list's boxes are radix-sorted by their min on the sweep axis (float bits mapped
//    to order-preserving uint32, so the order is the float order), then distributed to
//    their cells in that order (stable: each cell stays sorted). Each cell ends in a
//    sentinel whose min is +inf, so a scan stops with one compare.
// 4. Sweeps, cell by cell: active against active (each item scans forward while the others'
//    min <= its max), and active against passive (each side scans the other from the first
//    item at or after its own min; ties go to the active side, so each pair is met once).
//    Cells are independent and run in fixed chunks on gyro's threads (large scenes only).
// 5. Pairs are coded (rank of the lower key << bits | rank of the higher key) and
//    radix-sorted, which is the (key a, key b) order.
//
// Determinism: every step is a pure function of the inputs; the radix sorts are stable and
// which pairs are found does not depend on the order of equal keys, the grid, the axis
// choice or the threads (those only change the speed). The float arithmetic (centres, band
// index) only places boxes in cells; the overlap tests are exact comparisons (a 4-lane
// SSE2 compare gives the same booleans as the scalar one).
//
// Measured on B1 (100k boxes, one thread): structure-of-arrays items scanned four
// candidates per SSE2 step were 12% slower than these 48-byte items (more write streams
// while placing the copies, no faster sweep); the first version (bands on one axis, a
// branch per compare) took about twice as long.
#include "dynamics/broadphase.hpp"

#include "core/float_order.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>  // SSE2 is part of x86-64: no extra flag, no dispatch
#endif

namespace gyro::detail {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kMaxFinite = std::numeric_limits<float>::max();
constexpr uint32_t kMaxCells = 4096;
constexpr uint32_t kMinItemsPerCell = 32;
constexpr float kBandWidthInBoxes = 5.0f;  // band width in typical box extents (B1: flat from 4 to 8, 3 is 5% slower, 2 is 20%)
constexpr std::size_t kPrefetch = 8;       // how far ahead the gather prefetches
constexpr uint32_t kMaxSweepChunks = 64;   // cells are swept in at most this many parallel chunks
constexpr std::size_t kBuildChunk = 32768;  // boxes per parallel chunk while building the lists
constexpr std::size_t kParallelItems = 32768;  // fewer sweep items than this: one thread

inline float coord(const BroadphaseInput& in, bool max, int axis, uint32_t slot) {
  const float* const lo[3] = {in.min_x, in.min_y, in.min_z};
  const float* const hi[3] = {in.max_x, in.max_y, in.max_z};
  return (max ? hi : lo)[axis][slot];
}

/// Stable LSD radix sort of keys by their bits [lo_bit, lo_bit + bits); the other bits ride
/// along (a payload in the low bits). Digits of at most 12 bits, all histograms from one
/// read; a digit that is the same in every key costs no pass. Allocates only when the arrays
/// grow.
void radix_sort(std::vector<uint64_t>& keys, std::vector<uint64_t>& tmp, unsigned lo_bit, unsigned bits,
                std::vector<uint32_t>& counts) {
  const std::size_t n = keys.size();
  if (n < 2 || bits == 0) return;
  const unsigned passes = (bits + 11) / 12;
  const unsigned width = (bits + passes - 1) / passes;
  const std::size_t buckets = std::size_t{1} << width;
  const uint64_t digit_mask = buckets - 1;
  counts.assign(passes * buckets, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const uint64_t k = keys[i] >> lo_bit;
    for (unsigned p = 0; p < passes; ++p) ++counts[p * buckets + ((k >> (p * width)) & digit_mask)];
  }
  tmp.resize(n);
  for (unsigned p = 0; p < passes; ++p) {
    uint32_t* c = counts.data() + p * buckets;
    const unsigned shift = lo_bit + p * width;
    if (c[(keys[0] >> shift) & digit_mask] == n) continue;  // one digit value: order unchanged
    uint32_t sum = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
      const uint32_t v = c[b];
      c[b] = sum;
      sum += v;
    }
    for (std::size_t i = 0; i < n; ++i) tmp[c[(keys[i] >> shift) & digit_mask]++] = keys[i];
    keys.swap(tmp);
  }
}

}  // namespace

void Broadphase::choose_axes(const BroadphaseInput& in) {
  // Variance of the doubled centres (lo + hi) per axis, summed in list order in binary64.
  double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
  const std::size_t m = active_slots_.size() + passive_slots_.size();
  for (const std::vector<uint32_t>* list : {&active_slots_, &passive_slots_}) {
    for (uint32_t s : *list) {
      for (int a = 0; a < 3; ++a) {
        const double c = double(coord(in, false, a, s)) + double(coord(in, true, a, s));
        sum[a] += c;
        sq[a] += c * c;
      }
    }
  }
  double var[3];
  for (int a = 0; a < 3; ++a) var[a] = sq[a] / double(m) - (sum[a] / double(m)) * (sum[a] / double(m));
  int order[3] = {0, 1, 2};  // by decreasing variance, ties to the lower axis
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && var[order[j]] > var[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  for (int i = 0; i < 3; ++i) axis_[i] = order[i];

  // Bands on u and w: about kBandWidthInBoxes typical extents wide, where the typical extent
  // is the mean over the boxes no larger than a quarter of the centres' range (so a ground
  // box does not widen the bands); at most kMaxCells cells, at least kMinItemsPerCell boxes
  // per cell on average.
  double want[2] = {1.0, 1.0};
  float origin[2] = {0.0f, 0.0f};
  double range[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const int a = axis_[1 + k];
    float cmin = kInf, cmax = -kInf;
    for (const std::vector<uint32_t>* list : {&active_slots_, &passive_slots_}) {
      for (uint32_t s : *list) {
        const float c = (coord(in, false, a, s) + coord(in, true, a, s)) * 0.5f;
        cmin = c < cmin ? c : cmin;
        cmax = c > cmax ? c : cmax;
      }
    }
    origin[k] = cmin;
    range[k] = double(cmax) - double(cmin);
    if (!(range[k] > 0.0)) continue;
    double ext_sum = 0.0;
    std::size_t ext_n = 0;
    for (const std::vector<uint32_t>* list : {&active_slots_, &passive_slots_}) {
      for (uint32_t s : *list) {
        const double e = double(coord(in, true, a, s)) - double(coord(in, false, a, s));
        if (e <= 0.25 * range[k]) ext_sum += e, ++ext_n;
      }
    }
    if (ext_n == 0 || !(ext_sum > 0.0)) continue;
    want[k] = range[k] / (kBandWidthInBoxes * ext_sum / double(ext_n));
    if (want[k] < 1.0) want[k] = 1.0;
  }
  double cap = double(m / kMinItemsPerCell);
  if (cap > double(kMaxCells)) cap = double(kMaxCells);
  if (cap < 1.0) cap = 1.0;
  if (want[0] * want[1] > cap) {  // shrink both by the same factor, keeping at least 1 band
    const double f = std::sqrt(cap / (want[0] * want[1]));
    want[0] *= f, want[1] *= f;
    for (int k = 0; k < 2; ++k)
      if (want[k] < 1.0) want[k] = 1.0, want[1 - k] = cap;
  }
  Bands* bands[2] = {&band_u_, &band_w_};
  for (int k = 0; k < 2; ++k) {
    Bands& b = *bands[k];
    b.count = want[k] >= 2.0 ? static_cast<uint32_t>(want[k]) : 1u;
    b.origin = origin[k];
    b.scale = b.count > 1 ? static_cast<float>(double(b.count) / range[k]) : 0.0f;
  }
}

void Broadphase::compute_ranks(const BroadphaseInput& in) {
  const std::size_t n = in.count;
  rank_of_slot_.resize(n);
  slot_of_rank_.resize(n);
  rank_bits_ = n > 2 ? static_cast<unsigned>(std::bit_width(n - 1)) : 1u;
  bool increasing = true;  // the common case (no body ever destroyed): rank == slot
  for (std::size_t s = 1; s < n && increasing; ++s) increasing = in.key[s - 1] < in.key[s];
  if (increasing) {
    for (std::size_t s = 0; s < n; ++s) rank_of_slot_[s] = slot_of_rank_[s] = static_cast<uint32_t>(s);
    return;
  }
  sort_keys_.resize(n);
  uint32_t max_key = 0;
  for (std::size_t s = 0; s < n; ++s) {
    sort_keys_[s] = (uint64_t{in.key[s]} << 32) | s;
    max_key = in.key[s] > max_key ? in.key[s] : max_key;
  }
  radix_sort(sort_keys_, sort_tmp_, 32, static_cast<unsigned>(std::bit_width(max_key)), counts_);
  for (std::size_t r = 0; r < n; ++r) {
    const uint32_t s = static_cast<uint32_t>(sort_keys_[r]);
    slot_of_rank_[r] = s;
    rank_of_slot_[s] = static_cast<uint32_t>(r);
  }
}

void Broadphase::build_list(const BroadphaseInput& in, const std::vector<uint32_t>& slots, SweepList& out) {
  const float* const lo_of[3] = {in.min_x, in.min_y, in.min_z};
  const float* const hi_of[3] = {in.max_x, in.max_y, in.max_z};
  const float *xl = lo_of[axis_[0]], *xh = hi_of[axis_[0]];
  const float *ul = lo_of[axis_[1]], *uh = hi_of[axis_[1]];
  const float *wl = lo_of[axis_[2]], *wh = hi_of[axis_[2]];
  const uint32_t cells = band_u_.count * band_w_.count;

  // Per box: its item (in list order) and a sort key (sweep-axis min << 32 | box index).
  const std::size_t m = slots.size();
  box_scratch_.resize(m);
  sort_keys_.resize(m);
  parallel_for(m, kBuildChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t s = slots[k];
      SweepItem& b = box_scratch_[k];
      b.lo = xl[s], b.hi = xh[s];
      b.bounds[0] = ul[s], b.bounds[1] = wl[s], b.bounds[2] = -uh[s], b.bounds[3] = -wh[s];
      b.cell_lo = (band_u_.of(ul[s]) << 16) | band_w_.of(wl[s]);
      b.cell_hi = (band_u_.of(uh[s]) << 16) | band_w_.of(wh[s]);
      b.rank_dyn = (rank_of_slot_[s] << 1) | ((in.flags[s] & kBroadDynamic) ? 1u : 0u);
      b.category = in.category[s], b.mask = in.mask[s], b.unused = 0;
      sort_keys_[k] = (uint64_t{sortable_bits(b.lo)} << 32) | k;
    }
  });
  // Copies per cell.
  cell_count_.assign(cells, 0);
  std::size_t copies = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const SweepItem& b = box_scratch_[k];
    const uint32_t bu0 = b.cell_lo >> 16, bw0 = b.cell_lo & 0xFFFFu, bu1 = b.cell_hi >> 16, bw1 = b.cell_hi & 0xFFFFu;
    for (uint32_t bu = bu0; bu <= bu1; ++bu)
      for (uint32_t bw = bw0; bw <= bw1; ++bw) ++cell_count_[bu * band_w_.count + bw];
    copies += (bu1 - bu0 + 1) * (bw1 - bw0 + 1);
  }
  // Boxes in sweep order: sorted once by their min, however many cells they touch.
  radix_sort(sort_keys_, sort_tmp_, 32, 32, counts_);

  // Cell layout: each cell's copies, then its sentinel.
  out.items.resize(copies + cells);
  out.cell_begin.resize(cells + 1);
  uint32_t at = 0;
  for (uint32_t c = 0; c < cells; ++c) {
    out.cell_begin[c] = at;
    const uint32_t count = cell_count_[c];
    cell_count_[c] = at;  // now the cursor of cell c
    at += count + 1;
    SweepItem& sentinel = out.items[at - 1];
    sentinel = SweepItem{};
    sentinel.lo = kInf;
  }
  out.cell_begin[cells] = at;

  // Copies into their cells in sweep order (a stable distribution: each cell stays sorted).
  for (std::size_t r = 0; r < m; ++r) {
    if (r + kPrefetch < m) __builtin_prefetch(&box_scratch_[static_cast<uint32_t>(sort_keys_[r + kPrefetch])]);
    const SweepItem& b = box_scratch_[static_cast<uint32_t>(sort_keys_[r])];
    const uint32_t bu0 = b.cell_lo >> 16, bw0 = b.cell_lo & 0xFFFFu, bu1 = b.cell_hi >> 16, bw1 = b.cell_hi & 0xFFFFu;
    for (uint32_t bu = bu0; bu <= bu1; ++bu)
      for (uint32_t bw = bw0; bw <= bw1; ++bw) out.items[cell_count_[bu * band_w_.count + bw]++] = b;
  }
}

/// Calls on_overlap(j) for each item j = j0, j0+1, ... of o while o[j].lo <= q.hi (the sweep
/// axis) whose box overlaps q's on u and w (closed): every lane of o[j].bounds = {u_lo, w_lo,
/// -u_hi, -w_hi} <= the lane of q's {u_hi, w_hi, -u_lo, -w_lo} (negation is exact, so these
/// are the plain comparisons; SSE2 gives the same booleans as the scalar path).
template <class OnOverlap>
void Broadphase::scan(const SweepItem* o, std::size_t j, const SweepItem& q, OnOverlap&& on_overlap) {
  const float h = q.hi;
#if defined(__SSE2__)
  const __m128 neg = _mm_sub_ps(_mm_setzero_ps(), _mm_load_ps(q.bounds));  // +-0 compare equal
  const __m128 query = _mm_shuffle_ps(neg, neg, _MM_SHUFFLE(1, 0, 3, 2));
  for (; o[j].lo <= h; ++j)
    if (_mm_movemask_ps(_mm_cmple_ps(_mm_load_ps(o[j].bounds), query)) == 0xF) on_overlap(j);
#else
  const float query[4] = {-q.bounds[2], -q.bounds[3], -q.bounds[0], -q.bounds[1]};
  for (; o[j].lo <= h; ++j) {
    const float* b = o[j].bounds;
    if ((b[0] <= query[0]) & (b[1] <= query[1]) & (b[2] <= query[2]) & (b[3] <= query[3])) on_overlap(j);
  }
#endif
}

/// After the overlap: at least one dynamic body, the filter both ways, and the cell that
/// owns the pair (the one holding the low corner of the overlap: the max of the low cells).
inline void Broadphase::emit_if_accepted(const SweepItem& q, const SweepItem& o, uint32_t cell_u, uint32_t cell_w,
                                         std::vector<uint64_t>& out) const {
  if (((q.rank_dyn | o.rank_dyn) & 1u) == 0) return;
  if ((q.category & o.mask) == 0 || (o.category & q.mask) == 0) return;
  const uint32_t qu = q.cell_lo >> 16, ou = o.cell_lo >> 16, qw = q.cell_lo & 0xFFFFu, ow = o.cell_lo & 0xFFFFu;
  if ((qu > ou ? qu : ou) != cell_u || (qw > ow ? qw : ow) != cell_w) return;
  const uint64_t ra = q.rank_dyn >> 1, rb = o.rank_dyn >> 1;
  out.push_back(ra < rb ? (ra << rank_bits_) | rb : (rb << rank_bits_) | ra);
}

void Broadphase::sweep_cell(uint32_t cell, bool with_passive, std::vector<uint64_t>& out) const {
  const SweepItem* a = active_.items.data();
  const uint32_t cu = cell / band_w_.count, cw = cell % band_w_.count;
  const std::size_t a_begin = active_.cell_begin[cell], a_end = active_.cell_begin[cell + 1] - 1;  // a_end: the sentinel
  // Active against active: each item scans the ones after it.
  for (std::size_t i = a_begin; i < a_end; ++i)
    scan(a, i + 1, a[i], [&](std::size_t j) { emit_if_accepted(a[i], a[j], cu, cw, out); });
  if (!with_passive) return;
  const SweepItem* p = passive_.items.data();
  const std::size_t p_begin = passive_.cell_begin[cell], p_end = passive_.cell_begin[cell + 1] - 1;
  if (a_begin == a_end || p_begin == p_end) return;
  // Active items scan the passive ones whose min is >= theirs ...
  std::size_t first = p_begin;
  for (std::size_t i = a_begin; i < a_end; ++i) {
    while (p[first].lo < a[i].lo) ++first;  // the sentinel (+inf) stops it
    scan(p, first, a[i], [&](std::size_t j) { emit_if_accepted(a[i], p[j], cu, cw, out); });
  }
  // ... and passive items the active ones whose min is strictly greater.
  first = a_begin;
  for (std::size_t j = p_begin; j < p_end; ++j) {
    while (a[first].lo <= p[j].lo) ++first;
    scan(a, first, p[j], [&](std::size_t i) { emit_if_accepted(p[j], a[i], cu, cw, out); });
  }
}

void Broadphase::find_pairs(const BroadphaseInput& in, std::vector<BroadPair>& pairs) {
  pairs.clear();
  pair_keys_.clear();
  const std::size_t n = in.count;
  if (n < 2) return;

  // Active bodies and the union of their boxes.
  active_slots_.clear();
  passive_slots_.clear();
  float ulo[3] = {kInf, kInf, kInf}, uhi[3] = {-kInf, -kInf, -kInf};
  bool any_dynamic_active = false;
  // A box with a NaN or infinite bound (a body that blew up, e.g. under a huge force) takes
  // no part: the sweep's +inf sentinels and the band arithmetic need finite boxes.
  auto finite_box = [&](uint32_t s) {
    for (int a = 0; a < 3; ++a) {
      const float lo = coord(in, false, a, s), hi = coord(in, true, a, s);
      if (!(lo >= -kMaxFinite && lo <= kMaxFinite && hi >= -kMaxFinite && hi <= kMaxFinite)) return false;
    }
    return true;
  };
  for (uint32_t s = 0; s < n; ++s) {
    if (!(in.flags[s] & kBroadActive) || !finite_box(s)) continue;
    active_slots_.push_back(s);
    any_dynamic_active |= (in.flags[s] & kBroadDynamic) != 0;
    for (int a = 0; a < 3; ++a) {
      const float lo = coord(in, false, a, s), hi = coord(in, true, a, s);
      ulo[a] = lo < ulo[a] ? lo : ulo[a];
      uhi[a] = hi > uhi[a] ? hi : uhi[a];
    }
  }
  if (active_slots_.empty()) return;
  // Passive bodies that touch that union and could pair with an active one (a static body
  // needs an active dynamic one; a sleeping dynamic body pairs with any active body).
  for (uint32_t s = 0; s < n; ++s) {
    const uint8_t f = in.flags[s];
    if ((f & kBroadActive) || !(any_dynamic_active || (f & kBroadDynamic)) || !finite_box(s)) continue;
    bool touches = true;
    for (int a = 0; a < 3; ++a) touches &= coord(in, false, a, s) <= uhi[a] && coord(in, true, a, s) >= ulo[a];
    if (touches) passive_slots_.push_back(s);
  }
  if (active_slots_.size() + passive_slots_.size() < 2) return;

  compute_ranks(in);
  choose_axes(in);
  build_list(in, active_slots_, active_);
  const bool with_passive = !passive_slots_.empty();
  if (with_passive) build_list(in, passive_slots_, passive_);

  // Cells are independent: fixed chunks of cells, each with its own pair buffer, joined in
  // chunk order (a function of the cell count only, never of the thread count).
  // A small scene runs as one chunk: waking threads would cost more than the sweep.
  const uint32_t cells = band_u_.count * band_w_.count;
  const std::size_t items = active_.items.size() + (with_passive ? passive_.items.size() : 0);
  const uint32_t per_chunk = items < kParallelItems ? cells : (cells + kMaxSweepChunks - 1) / kMaxSweepChunks;
  const uint32_t chunks = (cells + per_chunk - 1) / per_chunk;
  if (chunk_pairs_.size() < chunks) chunk_pairs_.resize(chunks);
  parallel_for(cells, per_chunk, [&](std::size_t b, std::size_t e) {
    std::vector<uint64_t>& out = chunk_pairs_[b / per_chunk];
    out.clear();
    for (std::size_t c = b; c < e; ++c) sweep_cell(static_cast<uint32_t>(c), with_passive, out);
  });
  std::size_t total = 0;
  for (uint32_t k = 0; k < chunks; ++k) total += chunk_pairs_[k].size();
  pair_keys_.resize(total);
  total = 0;
  for (uint32_t k = 0; k < chunks; ++k) {
    std::copy(chunk_pairs_[k].begin(), chunk_pairs_[k].end(), pair_keys_.begin() + static_cast<std::ptrdiff_t>(total));
    total += chunk_pairs_[k].size();
  }

  radix_sort(pair_keys_, sort_tmp_, 0, 2 * rank_bits_, counts_);
  pairs.resize(pair_keys_.size());
  const uint64_t low_mask = (uint64_t{1} << rank_bits_) - 1;
  for (std::size_t i = 0; i < pair_keys_.size(); ++i) {
    const uint64_t c = pair_keys_[i];
    pairs[i] = {slot_of_rank_[c >> rank_bits_], slot_of_rank_[c & low_mask]};
  }
}

}  // namespace gyro::detail
