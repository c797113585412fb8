// box_frames at this translation unit's SIMD level: the relative frame of box B in box A's
// frame for one pair per lane, with make_frame's operations in make_frame's order (gjk.cpp),
// so lane k holds the bits the scalar query computes for pair k. The tail runs the float
// instantiation.
#include "geometry/gjk_batch.hpp"
#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

// x - x is 0 for a finite x and NaN otherwise; summing keeps a NaN.
template <class L> inline L finite_acc(L acc, L x) { return acc + (x - x); }

}  // namespace

GYRO_FLATTEN void box_frames(const ConvexBoxPairs& p, std::size_t begin, std::size_t end, BoxFrameBlock& out) {
  for_lanes(begin, end, [&](auto tag, std::size_t i) {
    using L = decltype(tag);
    const std::size_t k = i - begin;
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
    store_bits(&out.ok[k], select(ok, from_bits<L>(1u), from_bits<L>(0u)));
  });
}

}  // namespace gyro::GYRO_ARCH_NS
