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

// gjk.cpp's typed box supports (core_support<box>, CoreB<box>) over lanes.
template <class L> struct BoxSupports {
  V3<L> ha;       // A's half extents
  L rot[3][3];    // B's axes in A's frame (rows)
  L e[3][3];      // B's axes scaled by its half extents
  L pos[3];       // B's origin in A's frame
  V3<L> a(const V3<L>& d) const {
    return {select(d.x >= L(0.0f), ha.x, -ha.x), select(d.y >= L(0.0f), ha.y, -ha.y), select(d.z >= L(0.0f), ha.z, -ha.z)};
  }
  V3<L> b(const V3<L>& d) const {
    const auto s0 = dot(d, V3<L>{rot[0][0], rot[0][1], rot[0][2]}) <= L(0.0f);
    const auto s1 = dot(d, V3<L>{rot[1][0], rot[1][1], rot[1][2]}) <= L(0.0f);
    const auto s2 = dot(d, V3<L>{rot[2][0], rot[2][1], rot[2][2]}) <= L(0.0f);
    L c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = ((select(s0, e[0][k], -e[0][k]) + select(s1, e[1][k], -e[1][k])) + select(s2, e[2][k], -e[2][k])) + pos[k];
    return {c[0], c[1], c[2]};
  }
};


}  // namespace

GYRO_FLATTEN void box_frames(const ConvexBoxPairs& p, std::size_t begin, std::size_t end, float touch_tolerance,
                              bool early, BoxFrameBlock& out) {
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
    L code = select(ok, from_bits<L>(BoxFrameBlock::kFrame), from_bits<L>(BoxFrameBlock::kScalar));
    if (early && any(ok)) {
      // GJK's first two iterations (gjk_typed<box, box> in boolean mode; margins are 0, so
      // the separation threshold is the tolerance). A lane is decided only where the scalar
      // loop takes this same path to its early exit; any other turn leaves it to the loop.
      BoxSupports<L> sup;
      sup.ha = ha;
      for (int r = 0; r < 3; ++r) {
        const L h = r == 0 ? hb.x : (r == 1 ? hb.y : hb.z);
        for (int c = 0; c < 3; ++c) sup.rot[r][c] = rot[r][c], sup.e[r][c] = h * rot[r][c];
      }
      for (int c = 0; c < 3; ++c) sup.pos[c] = pos[c];
      const L tol = L(touch_tolerance) * scale;
      const L sep = L(0.0f) + tol;
      const L sep_sq = sep * sep;
      const L abs_tol = L(1e-6f) * scale;
      const L abs_sq = abs_tol * abs_tol;
      V3<L> d0{pos[0], pos[1], pos[2]};
      const auto zero_dir = !(dot(d0, d0) > L(0.0f));
      d0 = vselect(zero_dir, V3<L>{L(1.0f), L(0.0f), L(0.0f)}, d0);
      const V3<L> w0 = sup.a(d0) - sup.b(d0);
      const L vv0 = dot(w0, w0);
      // Iteration 0.
      const V3<L> d1 = -w0;
      const V3<L> w1 = sup.a(d1) - sup.b(d1);
      const L vw0 = dot(w0, w1);
      const auto early0 = (vv0 != L(0.0f)) && (vw0 > L(0.0f)) && (vw0 * vw0 > sep_sq * vv0);
      const L gap0 = vv0 - vw0;
      const auto stop0 = (vv0 == L(0.0f)) || (gap0 <= L(1e-6f) * vv0) || (gap0 * gap0 <= abs_sq * vv0) ||
                         ((w0.x == w1.x) && (w0.y == w1.y) && (w0.z == w1.z));
      // The segment w0 w1 (s1d): the vertex w0 means no progress (the loop stops there).
      const V3<L> t = w1 - w0;
      const L a0 = dot(w0, t), a1 = dot(w1, t);
      const auto on_w1 = !(a1 > L(0.0f));
      const L den = a1 - a0;
      const L l0 = a1 / den, l1 = -a0 / den;
      const V3<L> vs = w0 * l0 + w1 * l1;
      const V3<L> v = vselect(on_w1, w1, vs);
      const L vv = dot(v, v);
      const auto step0 = !early0 && !stop0 && (a0 < L(0.0f)) && (vv < vv0);
      // Iteration 1.
      const V3<L> d2 = -v;
      const V3<L> w2 = sup.a(d2) - sup.b(d2);
      const L vw = dot(v, w2);
      const auto early1 = step0 && (vv != L(0.0f)) && (vw > L(0.0f)) && (vw * vw > sep_sq * vv);
      code = select(ok && (early0 || early1), from_bits<L>(BoxFrameBlock::kSeparatedEarly), code);
    }
    store_bits(&out.code[k], code);
  });
}

}  // namespace gyro::GYRO_ARCH_NS
