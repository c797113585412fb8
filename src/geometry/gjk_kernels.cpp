// box_gjk at this translation unit's SIMD level: for one box pair per lane, the relative
// frame (make_frame's operations in make_frame's order) and then GJK (gjk_typed<box, box>'s
// loop, operation for operation; the subalgorithm is gjk_lanes.hpp), so lane k ends with the
// bits the scalar query computes for pair k. The tails run the float instantiation.
//
// GJK runs in rounds of one iteration over the pairs still running, packed to the front of
// the work arrays after each round (a pair's lane never depends on its neighbours, so the
// packing changes no result), so lanes stay busy while iteration counts differ. In distance
// and penetration mode the results of pairs whose cores end apart are formed in the lanes
// too (conclude_apart); gjk.cpp forms the rest. gjk.cpp does not call the scalar level's
// instantiation for whole batches (one lane paying for every branch is slower than the
// scalar loop); it serves the tails of the SIMD levels.
#include "core/lane_compact.hpp"
#include "geometry/box_face_lanes.hpp"
#include "geometry/gjk_batch.hpp"
#include "geometry/gjk_lanes.hpp"


namespace gyro::GYRO_ARCH_NS {
namespace {

using gjk_lanes::Sub;

// A slot's state bit: its pair's outcome is in the block already (settled in start()).
constexpr uint32_t kSettled = 1u << 31;

// x - x is 0 for a finite x and NaN otherwise; summing keeps a NaN.
template <class L> inline L finite_acc(L acc, L x) { return acc + (x - x); }

template <class L> inline V3<L> ld3(const float (*col)[BoxGjkWork::kMax], std::size_t j) {
  return {load<L>(col[0] + j), load<L>(col[1] + j), load<L>(col[2] + j)};
}
template <class L> inline void st3(float (*col)[BoxGjkWork::kMax], std::size_t j, const V3<L>& v) {
  store(col[0] + j, v.x), store(col[1] + j, v.y), store(col[2] + j, v.z);
}

// B's axes scaled by its half extents, as CoreB<box> forms them: e[3r + c] = h_r * rot[3r + c].
template <class L> inline void scaled_axes(const V3<L>& hb, const L* rot, L* e) {
  for (int c = 0; c < 3; ++c) e[c] = hb.x * rot[c], e[3 + c] = hb.y * rot[3 + c], e[6 + c] = hb.z * rot[6 + c];
}

// Phase 1: frames, validity, and GJK's first support point (gjk_typed before its loop).
template <class L>
inline void start(const ConvexBoxPairs& p, std::size_t i, std::size_t k, const BoxGjkParams& prm, BoxGjkBlock& out,
                  BoxGjkWork& w) {
  L ra_m[3][3], rb_m[3][3];
  L acc(0.0f), big(0.0f);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      ra_m[r][c] = load<L>(p.a_rot[3 * r + c] + i), rb_m[r][c] = load<L>(p.b_rot[3 * r + c] + i);
      acc = finite_acc(acc, ra_m[r][c]), acc = finite_acc(acc, rb_m[r][c]);
      big = max(big, max(abs(ra_m[r][c]), abs(rb_m[r][c])));
    }
  const V3<L> ca = load3<L>(p.a_center[0], p.a_center[1], p.a_center[2], i);
  const V3<L> cb = load3<L>(p.b_center[0], p.b_center[1], p.b_center[2], i);
  const V3<L> ha = load3<L>(p.a_half[0], p.a_half[1], p.a_half[2], i);
  const V3<L> hb = load3<L>(p.b_half[0], p.b_half[1], p.b_half[2], i);
  acc = finite_acc(finite_acc(finite_acc(acc, ca.x), ca.y), ca.z);
  acc = finite_acc(finite_acc(finite_acc(acc, cb.x), cb.y), cb.z);
  // make_frame: sizes >= 0, bounding radii (|half extents|) >= 0 and finite.
  const L ra = sqrt(dot(ha, ha)), rb = sqrt(dot(hb, hb));
  auto sizes = (ha.x >= L(0.0f)) && (ha.y >= L(0.0f)) && (ha.z >= L(0.0f)) && (hb.x >= L(0.0f)) &&
               (hb.y >= L(0.0f)) && (hb.z >= L(0.0f)) && (ra >= L(0.0f)) && (rb >= L(0.0f));
  acc = finite_acc(finite_acc(acc, ra), rb);
  // rot_b = Rb * transpose(Ra): element (r, c) = sum over j of Rb[r][j] * Ra[c][j].
  L rot[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      L s = rb_m[r][0] * ra_m[c][0];
      s = s + rb_m[r][1] * ra_m[c][1];
      s = s + rb_m[r][2] * ra_m[c][2];
      rot[r][c] = s;
    }
  // pos_b = (pb - pa) * transpose(Ra).
  const V3<L> d = cb - ca;
  L pos[3];
  for (int c = 0; c < 3; ++c) {
    L s = d.x * ra_m[c][0];
    s = s + d.y * ra_m[c][1];
    s = s + d.z * ra_m[c][2];
    pos[c] = s;
  }
  const L s = (ra + rb) + sqrt((pos[0] * pos[0] + pos[1] * pos[1]) + pos[2] * pos[2]);
  acc = finite_acc(acc, (rot[0][0] + pos[0]) + s);
  const L scale = select(s > L(1e-30f), s, L(1e-30f));
  // The range where every output of the scalar query is finite for sure (rotation entries
  // at most 2, coordinates far below overflow): elsewhere the caller runs the scalar query.
  const L reach = scale * L(64.0f) + max(max(abs(ca.x), abs(ca.y)), abs(ca.z));
  const auto ok = sizes && (acc == L(0.0f)) && (big <= L(2.0f)) && (reach < L(1e36f));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) store(&out.rot[3 * r + c][k], rot[r][c]);
  for (int c = 0; c < 3; ++c) store(&out.pos[c][k], pos[c]);
  store(&out.scale[k], scale);
  store_bits(&out.code[k], select(ok, from_bits<L>(BoxGjkBlock::kDone), from_bits<L>(BoxGjkBlock::kScalar)));
  // The GJK state: thresholds (margins are 0, so the separation threshold is the tolerance),
  // B's axes scaled by its half extents (CoreB<box>), the first support point along pos_b.
  const L tol = L(prm.touch_tolerance) * scale;
  const L sep = L(0.0f) + tol;
  const L abs_tol = L(1e-6f) * scale;
  store(&w.sep_sq[k], sep * sep), store(&w.abs_sq[k], abs_tol * abs_tol);
  st3(w.ha, k, ha), st3(w.hb, k, hb);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) store(&w.rot[3 * r + c][k], rot[r][c]);
  for (int c = 0; c < 3; ++c) store(&w.pos[c][k], pos[c]);
  // The first support point (gjk_typed before its loop), along pos_b (+x if that is zero),
  // or in boolean mode along the first face normal that separates (box_face_lanes.hpp).
  V3<L> d0{pos[0], pos[1], pos[2]};
  d0 = vselect(!(dot(d0, d0) > L(0.0f)), V3<L>{L(1.0f), L(0.0f), L(0.0f)}, d0);
  auto face_axis = L(0.0f) > L(1.0f);
  if (prm.boolean) face_axis = box_face_probe(ha, hb, rot, pos, sep * sep, d0);
  // A pair separated along a face normal is done before the first round, as the loop's
  // early exit leaves it (it = 0, the first support point as the simplex): its outcome is
  // written to the block here, for every lane (a pair that runs on overwrites it when it
  // finishes), and pack() drops its slot without finishing it (kSettled).
  const L running = select(face_axis, from_bits<L>(BoxGjkBlock::kDone | BoxGjkBlock::kEarly << 1 | kSettled),
                           from_bits<L>(0u));
  store_bits(&w.state[k], select(ok, running, from_bits<L>(BoxGjkBlock::kDone)));
  store(out.apart + k, select(face_axis, L(3.0f), L(0.0f)));
  store_bits(out.n + k, from_bits<L>(1u)), store_bits(out.iterations + k, from_bits<L>(0u));
  store_bits(out.flags + k, from_bits<L>(BoxGjkBlock::kEarly)), store(out.nf + k, L(1.0f));
  L rb_flat[9], e[9];
  for (int q = 0; q < 9; ++q) rb_flat[q] = rot[q / 3][q % 3];
  scaled_axes(hb, rb_flat, e);
  const V3<L> a{select(d0.x >= L(0.0f), ha.x, -ha.x), select(d0.y >= L(0.0f), ha.y, -ha.y),
                select(d0.z >= L(0.0f), ha.z, -ha.z)};
  const auto s0 = dot(d0, V3<L>{rot[0][0], rot[0][1], rot[0][2]}) <= L(0.0f);
  const auto s1 = dot(d0, V3<L>{rot[1][0], rot[1][1], rot[1][2]}) <= L(0.0f);
  const auto s2 = dot(d0, V3<L>{rot[2][0], rot[2][1], rot[2][2]}) <= L(0.0f);
  L bc[3];
  for (int c = 0; c < 3; ++c)
    bc[c] = ((select(s0, e[c], -e[c]) + select(s1, e[3 + c], -e[3 + c])) + select(s2, e[6 + c], -e[6 + c])) + pos[c];
  const V3<L> b{bc[0], bc[1], bc[2]};
  const V3<L> v = a - b;
  const L vv = dot(v, v);
  st3(w.v, k, v);
  store(w.vv + k, vv), store(out.vv + k, vv);
  store(w.n + k, L(1.0f)), store(w.it + k, L(0.0f));
  if (prm.verdict_only) {
    st3(w.w[0], k, v);
    return;
  }
  st3(w.a[0], k, a), st3(w.b[0], k, b);
  st3(out.a[0], k, a), st3(out.b[0], k, b), st3(out.v, k, v);
  store(out.lambda[0] + k, L(1.0f)), store(out.lambda[1] + k, L(0.0f)), store(out.lambda[2] + k, L(0.0f));
  store(out.lambda[3] + k, L(0.0f));
  store(w.lambda[0] + k, L(1.0f)), store(w.lambda[1] + k, L(0.0f)), store(w.lambda[2] + k, L(0.0f));
  store(w.lambda[3] + k, L(0.0f));
}

// Lane k holds k, for the live-slot mask of a round's last, partial vector.
alignas(64) constexpr float kLaneIndex[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

// One GJK iteration (the body of gjk_typed's loop) for the pairs in slots [j, j + width);
// only slots below `active` run: the lanes past it compute on stale slots, and their
// stores land past the slots pack() reads. Witness: the simplex's points on A and B are
// carried (results are formed), else only its points of A - B (verdicts).
template <class L, bool Witness>
inline void round(std::size_t j, std::size_t active, const BoxGjkParams& prm, BoxGjkWork& w) {
  const V3<L> ha = ld3<L>(w.ha, j);
  L rot[9], e[9];
  for (int q = 0; q < 9; ++q) rot[q] = load<L>(w.rot[q] + j);
  scaled_axes(ld3<L>(w.hb, j), rot, e);
  const V3<L> pb0 = ld3<L>(w.pos, j);
  V3<L> A[4], B[4], W[4];
  L n = load<L>(w.n + j);
  const auto live = load<L>(kLaneIndex) < L(float(active - j));
  const auto n1 = n == L(1.0f), n2 = n == L(2.0f), n3 = n == L(3.0f);
  const int top = any(live && n3) ? 3 : (any(live && n2) ? 2 : 1);  // positions that may hold simplex points
  for (int q = 0; q < top; ++q) {
    if constexpr (Witness) A[q] = ld3<L>(w.a[q], j), B[q] = ld3<L>(w.b[q], j), W[q] = A[q] - B[q];
    else W[q] = ld3<L>(w.w[q], j);
  }
  V3<L> v = ld3<L>(w.v, j);
  L vv = load<L>(w.vv + j), it = load<L>(w.it + j);
  const L sep_sq = load<L>(w.sep_sq + j), abs_sq = load<L>(w.abs_sq + j);

  const auto enclosed0 = vv == L(0.0f);
  const auto limit0 = !enclosed0 && (it >= L(float(prm.max_iterations)));
  const auto run = live && !enclosed0 && !limit0;
  // Supports along d = -v: A's core_support<box>, B's CoreB<box> (signs as selects).
  const V3<L> d = -v;
  const V3<L> pa{select(d.x >= L(0.0f), ha.x, -ha.x), select(d.y >= L(0.0f), ha.y, -ha.y),
                 select(d.z >= L(0.0f), ha.z, -ha.z)};
  const auto s0 = dot(d, V3<L>{rot[0], rot[1], rot[2]}) <= L(0.0f);
  const auto s1 = dot(d, V3<L>{rot[3], rot[4], rot[5]}) <= L(0.0f);
  const auto s2 = dot(d, V3<L>{rot[6], rot[7], rot[8]}) <= L(0.0f);
  L pbc[3];
  for (int c = 0; c < 3; ++c)
    pbc[c] = ((select(s0, e[c], -e[c]) + select(s1, e[3 + c], -e[3 + c])) + select(s2, e[6 + c], -e[6 + c])) +
             (c == 0 ? pb0.x : (c == 1 ? pb0.y : pb0.z));
  const V3<L> pb{pbc[0], pbc[1], pbc[2]};
  const V3<L> sw = pa - pb;
  const L vw = dot(v, sw);
  const auto boolean = L(prm.boolean ? 1.0f : 0.0f) > L(0.0f);
  const auto early = run && boolean && (vw > L(0.0f)) && (vw * vw > sep_sq * vv);
  const L gap = vv - vw;
  const auto conv = (gap <= L(1e-6f) * vv) || (gap * gap <= abs_sq * vv);
  auto repeat = (W[0].x == sw.x) && (W[0].y == sw.y) && (W[0].z == sw.z);
  for (int q = 1; q < top; ++q)
    repeat = repeat || ((n > L(float(q))) && (W[q].x == sw.x) && (W[q].y == sw.y) && (W[q].z == sw.z));
  const auto go = run && !early && !conv && !repeat;
  // The new point at position n.
  for (int q = 1; q <= top; ++q) {
    const auto here = n == L(float(q));
    if constexpr (Witness) {
      if (q == top) A[q] = pa, B[q] = pb, W[q] = sw;
      else A[q] = vselect(here, pa, A[q]), B[q] = vselect(here, pb, B[q]), W[q] = vselect(here, sw, W[q]);
    } else {
      W[q] = q == top ? sw : vselect(here, sw, W[q]);
    }
  }
  L wv[4];
  for (int q = 0; q <= top; ++q) wv[q] = dot(W[q], W[q]);
  Sub<L> r = gjk_lanes::zero<L>();
  if (any(go && n1)) r = gjk_lanes::s1d<0, 1>(W, wv);
  if (top >= 2 && any(go && n2)) gjk_lanes::take(n2, r, gjk_lanes::s2d<0, 1, 2>(W, wv, go && n2));
  if (top >= 3 && any(go && n3)) gjk_lanes::take(n3, r, gjk_lanes::s3d(W, wv, go && n3));
  const auto full = go && (r.n == L(4.0f));
  const auto progress = go && !full && (r.vv < vv);
  // Kept points to the front, in the subalgorithm's order.
  auto pick = [&](const V3<L>* P, L idx) {
    const V3<L> hi = top == 1 ? P[1] : vselect(idx == L(1.0f), P[1], top == 2 ? P[2] : vselect(idx == L(2.0f), P[2], P[3]));
    return vselect(idx == L(0.0f), P[0], hi);
  };
  if (any(progress)) {
    const L idx[3] = {r.i0, r.i1, r.i2};
    for (int q = 0; q < 3; ++q) {
      if (q > top) break;  // a kept position never exceeds the points there were
      if constexpr (Witness) {
        st3(w.a[q], j, vselect(progress, pick(A, idx[q]), A[q]));
        st3(w.b[q], j, vselect(progress, pick(B, idx[q]), B[q]));
      } else {
        st3(w.w[q], j, vselect(progress, pick(W, idx[q]), W[q]));
      }
    }
  }
  if (top == 3 && any(full)) {  // the tetrahedron stays in place
    if constexpr (Witness) st3(w.a[3], j, A[3]), st3(w.b[3], j, B[3]);
    else st3(w.w[3], j, W[3]);
  }
  const auto upd = progress || full;
  if constexpr (Witness) {
    store(w.lambda[0] + j, select(upd, r.l0, load<L>(w.lambda[0] + j)));
    store(w.lambda[1] + j, select(upd, r.l1, load<L>(w.lambda[1] + j)));
    store(w.lambda[2] + j, select(upd, r.l2, load<L>(w.lambda[2] + j)));
    store(w.lambda[3] + j, select(upd, r.l3, load<L>(w.lambda[3] + j)));
  }
  n = select(upd, r.n, n);
  store(w.n + j, n);
  st3(w.v, j, vselect(upd, r.v, v));
  store(w.vv + j, select(upd, r.vv, vv));
  store(w.it + j, select(upd, it + L(1.0f), it));
  // Done unless progress; flags as BoxGjkBlock's, shifted over the done bit.
  const L none = from_bits<L>(0u);
  L st = select(progress, none, from_bits<L>(BoxGjkBlock::kDone));
  st = select(enclosed0, from_bits<L>(BoxGjkBlock::kDone | BoxGjkBlock::kEnclosed << 1), st);
  st = select(limit0, from_bits<L>(BoxGjkBlock::kDone | BoxGjkBlock::kLimit << 1), st);
  st = select(early, from_bits<L>(BoxGjkBlock::kDone | BoxGjkBlock::kEarly << 1), st);
  st = select(full, from_bits<L>(BoxGjkBlock::kDone | (BoxGjkBlock::kEnclosed | BoxGjkBlock::kFull) << 1), st);
  store_bits(w.state + j, st);
}

// Moves a finished slot's state to its pair's outcome. Verdicts need no simplex but where
// the origin is enclosed by fewer than four points (EPA's touching test): the lanes did not
// keep the points on A and B that test needs, so the pair goes to the scalar query.
void finish_slot(const BoxGjkWork& w, std::size_t j, bool verdict_only, BoxGjkBlock& out) {
  const std::size_t k = w.pair[j];
  const uint32_t n = uint32_t(w.n[j]), flags = w.state[j] >> 1;
  out.n[k] = n, out.iterations[k] = uint32_t(w.it[j]), out.flags[k] = flags;
  out.vv[k] = w.vv[j], out.nf[k] = w.n[j];
  out.apart[k] = (flags & BoxGjkBlock::kEnclosed) != 0 ? 0.0f
                 : (flags & BoxGjkBlock::kLimit) != 0  ? 2.0f
                 : (flags & BoxGjkBlock::kEarly) != 0  ? 3.0f
                                                       : 1.0f;
  if (verdict_only) {
    if ((flags & (BoxGjkBlock::kEnclosed | BoxGjkBlock::kFull)) == BoxGjkBlock::kEnclosed) out.code[k] = BoxGjkBlock::kScalar;
    return;
  }
  for (uint32_t q = 0; q < n; ++q)
    for (int c = 0; c < 3; ++c) out.a[q][c][k] = w.a[q][c][j], out.b[q][c][k] = w.b[q][c][j];
  for (int q = 0; q < 4; ++q) out.lambda[q][k] = w.lambda[q][j];
  for (int c = 0; c < 3; ++c) out.v[c][k] = w.v[c][j];
}

// Calls f(column) for every per-slot float column of the running state (verdicts: the
// points of A - B in place of those on A and B and their weights).
template <bool VerdictOnly, class F> inline void for_each_column(BoxGjkWork& w, F&& f) {
  for (int c = 0; c < 3; ++c) f(w.ha[c]), f(w.hb[c]), f(w.pos[c]), f(w.v[c]);
  for (int q = 0; q < 9; ++q) f(w.rot[q]);
  f(w.sep_sq), f(w.abs_sq), f(w.vv), f(w.n), f(w.it);
  for (int q = 0; q < 4; ++q) {
    if constexpr (VerdictOnly) {
      for (int c = 0; c < 3; ++c) f(w.w[q][c]);
    } else {
      f(w.lambda[q]);
      for (int c = 0; c < 3; ++c) f(w.a[q][c]), f(w.b[q][c]);
    }
  }
}

inline void finish_if_valid(const BoxGjkWork& w, std::size_t j, bool verdict_only, BoxGjkBlock& out) {
  // Settled in start() (separated along a face normal): the block holds its outcome. A slot
  // done before its first round without flags is an invalid pair: nothing to keep.
  if (w.state[j] & kSettled) return;
  if (w.state[j] >> 1 != 0 || out.code[w.pair[j]] == BoxGjkBlock::kDone) finish_slot(w, j, verdict_only, out);
}

#if defined(GYRO_ARCH_AVX512)
// Finishes the slots whose state says done and packs the others to the front, 16 slots at a
// time with AVX-512's compress-store (the order of the kept slots is kept).
template <bool VerdictOnly> std::size_t pack(BoxGjkWork& w, std::size_t count, BoxGjkBlock& out) {
  constexpr bool verdict_only = VerdictOnly;
  std::size_t m = 0;
  for (std::size_t j = 0; j < count; j += 16) {
    const std::size_t len = count - j < 16 ? count - j : 16;
    const __mmask16 valid = __mmask16((1u << len) - 1u);
    const __m512i st = _mm512_maskz_loadu_epi32(valid, w.state + j);
    const __mmask16 keep = _mm512_mask_cmpeq_epi32_mask(valid, st, _mm512_setzero_si512());
    for (unsigned bits = unsigned(valid & ~keep); bits != 0; bits &= bits - 1u)
      finish_if_valid(w, j + std::size_t(__builtin_ctz(bits)), verdict_only, out);
    const std::size_t kept = std::size_t(__builtin_popcount(unsigned(keep)));
    if (m != j || kept != len) {
      const __m512i pair = _mm512_maskz_loadu_epi32(valid, w.pair + j);
      _mm512_mask_compressstoreu_epi32(w.pair + m, keep, pair);
      for_each_column<VerdictOnly>(w, [&](float* col) {
        _mm512_mask_compressstoreu_ps(col + m, keep, _mm512_maskz_loadu_ps(valid, col + j));
      });
    }
    m += kept;
  }
  return m;
}
#elif defined(GYRO_ARCH_AVX2)
// pack() as the AVX-512 one, eight slots at a time: the kept lanes are permuted to the front
// and all eight stored at m; the lanes past the kept ones land on slots that a later block
// overwrites or that are past the end (m + 8 <= j + 8, so never on a slot not yet read).
template <bool VerdictOnly> std::size_t pack(BoxGjkWork& w, std::size_t count, BoxGjkBlock& out) {
  constexpr bool verdict_only = VerdictOnly;
  std::size_t m = 0;
  for (std::size_t j = 0; j < count; j += 8) {
    const std::size_t len = count - j < 8 ? count - j : 8;
    const unsigned valid = (1u << len) - 1u;
    // Lanes past count load as zeros (masked loads), as the AVX-512 pack's.
    const __m256i live = _mm256_cmpgt_epi32(_mm256_set1_epi32(int(len)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    const __m256i st = _mm256_maskload_epi32(reinterpret_cast<const int*>(w.state + j), live);
    const unsigned keep =
        valid & unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(st, _mm256_setzero_si256()))));
    for (unsigned bits = valid & ~keep; bits != 0; bits &= bits - 1u)
      finish_if_valid(w, j + std::size_t(__builtin_ctz(bits)), verdict_only, out);
    const std::size_t kept = compact_count(keep);
    if (m != j || kept != len) {
      const __m256i perm = compact_indices(keep);
      const __m256i pair = _mm256_maskload_epi32(reinterpret_cast<const int*>(w.pair + j), live);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(w.pair + m), _mm256_permutevar8x32_epi32(pair, perm));
      for_each_column<VerdictOnly>(w, [&](float* col) {
        _mm256_storeu_ps(col + m, _mm256_permutevar8x32_ps(_mm256_maskload_ps(col + j, live), perm));
      });
    }
    m += kept;
  }
  return m;
}
#else
// Copies slot j's running state to slot m (m < j).
template <bool VerdictOnly> void move_slot(BoxGjkWork& w, std::size_t j, std::size_t m) {
  w.pair[m] = w.pair[j];
  for_each_column<VerdictOnly>(w, [&](float* col) { col[m] = col[j]; });
}

// Finishes the slots whose state says done and packs the others to the front.
template <bool VerdictOnly> std::size_t pack(BoxGjkWork& w, std::size_t count, BoxGjkBlock& out) {
  constexpr bool verdict_only = VerdictOnly;
  std::size_t m = 0;
  for (std::size_t j = 0; j < count; ++j) {
    if (w.state[j] != 0) {
      finish_if_valid(w, j, verdict_only, out);
      continue;
    }
    if (m != j) move_slot<VerdictOnly>(w, j, m);
    ++m;
  }
  return m;
}
#endif

// conclude()'s first branch (gjk.cpp: the cores apart; both margins 0) for pair i, element
// k: witnesses from the simplex, the normal normalized(-v), status and distance, all taken
// to the world with A's pose (finish()), with the scalar code's operations in its order.
template <class L>
inline void conclude_apart(const ConvexBoxPairs& p, std::size_t i, std::size_t k, const BoxGjkParams& prm,
                           BoxGjkBlock& out) {
  const L nf = load<L>(out.nf + k);
  const L zero(0.0f);
  V3<L> wa{zero, zero, zero}, wb{zero, zero, zero};
  for (int q = 0; q < 4; ++q) {
    const auto in = nf > L(float(q));
    const L l = load<L>(out.lambda[q] + k);
    const V3<L> a{load<L>(out.a[q][0] + k), load<L>(out.a[q][1] + k), load<L>(out.a[q][2] + k)};
    const V3<L> b{load<L>(out.b[q][0] + k), load<L>(out.b[q][1] + k), load<L>(out.b[q][2] + k)};
    wa = vselect(in, wa + a * l, wa), wb = vselect(in, wb + b * l, wb);
  }
  // normalized(-v): rescaled by 2^100 or 2^-100 outside [2^-100, 2^100]; zero stays zero.
  const V3<L> u = -V3<L>{load<L>(out.v[0] + k), load<L>(out.v[1] + k), load<L>(out.v[2] + k)};
  const L sq0 = dot(u, u);
  const auto small = sq0 < L(0x1p-100f), big = !small && (sq0 > L(0x1p+100f));
  const auto is_zero = (u.x == zero) && (u.y == zero) && (u.z == zero);
  const V3<L> sc = vselect(small, u * L(0x1p+100f), vselect(big, u * L(0x1p-100f), u));
  const L sq = select(small || big, dot(sc, sc), sq0);
  const L len = sqrt(sq);
  V3<L> nrm{sc.x / len, sc.y / len, sc.z / len};
  nrm = vselect(small && is_zero, V3<L>{zero, zero, zero}, nrm);
  const V3<L> sa = wa + nrm * zero, sb = wb - nrm * zero;
  const L dist = sqrt(load<L>(out.vv + k)) - zero;
  const L tol = L(prm.touch_tolerance) * load<L>(out.scale + k);
  L st = select(dist > tol, L(0.0f), select(dist >= -tol, L(1.0f), L(2.0f)));
  const L limit_code = L(float(uint32_t(ConvexStatus::iteration_limit)));
  const L apart = load<L>(out.apart + k);
  st = select(apart == L(2.0f), limit_code, st);
  st = select(apart == L(3.0f), L(float(uint32_t(ConvexStatus::separated))), st);
  const L d_out = prm.penetration ? dist : select(st == L(2.0f), zero, dist);
  // finish(): A's frame to the world, p * rotation (+ position).
  L m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = load<L>(p.a_rot[3 * r + c] + i);
  const V3<L> pos = load3<L>(p.a_center[0], p.a_center[1], p.a_center[2], i);
  auto rotate = [&](const V3<L>& x) {
    return V3<L>{(x.x * m[0][0] + x.y * m[1][0]) + x.z * m[2][0], (x.x * m[0][1] + x.y * m[1][1]) + x.z * m[2][1],
                 (x.x * m[0][2] + x.y * m[1][2]) + x.z * m[2][2]};
  };
  const V3<L> wn = rotate(nrm), pa = rotate(sa) + pos, pb = rotate(sb) + pos;
  L acc = d_out - d_out;
  for (const V3<L>* x : {&wn, &pa, &pb}) acc = ((acc + (x->x - x->x)) + (x->y - x->y)) + (x->z - x->z);
  store(out.r_status + k, st), store(out.r_distance + k, d_out);
  for (int c = 0; c < 3; ++c) {
    store(out.r_normal[c] + k, c == 0 ? wn.x : (c == 1 ? wn.y : wn.z));
    store(out.r_point_a[c] + k, c == 0 ? pa.x : (c == 1 ? pa.y : pa.z));
    store(out.r_point_b[c] + k, c == 0 ? pb.x : (c == 1 ? pb.y : pb.z));
  }
  store(out.done + k, select((apart > L(0.5f)) && (acc == zero), L(1.0f), zero));
}

// GJK over the block's pairs: every pair's first support point, then rounds until none runs.
template <bool VerdictOnly>
inline void run(const ConvexBoxPairs& p, std::size_t begin, std::size_t end, const BoxGjkParams& prm, BoxGjkBlock& out,
                BoxGjkWork& w) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) { start<decltype(tag)>(p, i, i - begin, prm, out, w); });
  const std::size_t count = end - begin;
  for (std::size_t k = 0; k < count; ++k) w.pair[k] = uint32_t(k);
  std::size_t active = pack<VerdictOnly>(w, count, out);
  // A round's last vector runs with its lanes past `active` masked, not lane by lane: one
  // lane of the float instantiation computing every branch cost about half a full vector
  // (AVX2, callgrind), and AVX-512 leaves up to 15 such slots per round.
  constexpr std::size_t width = width_v<Wide>;
  static_assert(BoxGjkWork::kMax % width == 0 && width <= 16, "rounds run whole vectors");
  while (active > 0) {
    for (std::size_t j = 0; j < active; j += width) round<Wide, !VerdictOnly>(j, active, prm, w);
    active = pack<VerdictOnly>(w, active, out);
  }
  if constexpr (!VerdictOnly)
    for_lanes(begin, end, [&](auto tag, std::size_t i) { conclude_apart<decltype(tag)>(p, i, i - begin, prm, out); });
}

}  // namespace

GYRO_FLATTEN void box_gjk(const ConvexBoxPairs& p, std::size_t begin, std::size_t end, const BoxGjkParams& prm,
                          BoxGjkBlock& out, BoxGjkWork& w) {
  if (prm.verdict_only) run<true>(p, begin, end, prm, out, w);
  else run<false>(p, begin, end, prm, out, w);
}

}  // namespace gyro::GYRO_ARCH_NS
