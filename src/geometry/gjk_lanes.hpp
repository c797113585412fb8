// gjk.cpp's signed-volume subalgorithm (s1d, s2d, s3d) over lanes, one simplex per lane.
//
// Each lane must compute the bits gjk.cpp computes for its simplex, so the branches of the
// scalar code become selects between candidates computed in every lane (a candidate no
// lane needs is skipped): the same operations in the same order, and the same choice rule
// ("the first facing edge or face, a later one only when strictly closer"). The simplex is
// held by position (vertex i of the subalgorithm's view is W[i]); a result names the
// positions it keeps, in the subalgorithm's order, as exact small integers in float lanes.
// Included only by gjk_kernels.cpp (once per SIMD level).
#pragma once

#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace gjk_lanes {

template <class L> struct Sub {
  L n, i0, i1, i2;     // kept count and positions (n == 4: the origin is inside)
  L l0, l1, l2, l3;    // their weights
  V3<L> v;             // closest point
  L vv;                // |v|^2
};

template <class L> inline Sub<L> zero() {
  const L z(0.0f);
  return {z, z, z, z, z, z, z, z, V3<L>{z, z, z}, z};
}

template <class M, class L> inline void take(M m, Sub<L>& best, const Sub<L>& c) {
  best.n = select(m, c.n, best.n), best.i0 = select(m, c.i0, best.i0), best.i1 = select(m, c.i1, best.i1);
  best.i2 = select(m, c.i2, best.i2);
  best.l0 = select(m, c.l0, best.l0), best.l1 = select(m, c.l1, best.l1), best.l2 = select(m, c.l2, best.l2);
  best.l3 = select(m, c.l3, best.l3);
  best.v = vselect(m, c.v, best.v), best.vv = select(m, c.vv, best.vv);
}

template <class L> inline auto same_sign(L a, L b) {
  return ((a > L(0.0f)) && (b > L(0.0f))) || ((a < L(0.0f)) && (b < L(0.0f)));
}

// Segment W[I0] W[I1]; wv[i] = dot(W[i], W[i]) (a vertex's vv, as gjk.cpp's vertex()).
template <int I0, int I1, class L> inline Sub<L> s1d(const V3<L>* W, const L* wv) {
  const V3<L> t = W[I1] - W[I0];
  const L a0 = dot(W[I0], t), a1 = dot(W[I1], t);
  const auto m0 = !(a0 < L(0.0f));
  const auto m1 = !m0 && !(a1 > L(0.0f));
  const auto vert = m0 || m1;
  const L den = a1 - a0;
  const L l0 = a1 / den, l1 = -a0 / den;
  const V3<L> vs = W[I0] * l0 + W[I1] * l1;
  Sub<L> r;
  r.n = select(vert, L(1.0f), L(2.0f));
  r.i0 = select(m1, L(float(I1)), L(float(I0)));
  r.i1 = L(float(I1)), r.i2 = L(0.0f);
  r.l0 = select(vert, L(1.0f), l0), r.l1 = l1, r.l2 = L(0.0f), r.l3 = L(0.0f);
  r.v = vselect(m0, W[I0], vselect(m1, W[I1], vs));
  r.vv = select(m0, wv[I0], select(m1, wv[I1], dot(vs, vs)));
  return r;
}

// Folds candidate c (computed where `facing`) into best: the first facing one, later ones
// only when strictly closer.
template <class M, class L> inline void fold(M facing, M& have, Sub<L>& best, const Sub<L>& c) {
  take(facing && (!have || (c.vv < best.vv)), best, c);
  have = have || facing;
}

// Triangle W[I0] W[I1] W[I2]. Only the lanes in `need` use the result: a candidate none of
// them needs is skipped (the other lanes may hold no simplex of this size at all, and their
// stale points would ask for candidates nobody uses).
template <int I0, int I1, int I2, class L, class M> inline Sub<L> s2d(const V3<L>* W, const L* wv, M need) {
  const V3<L> n = cross(W[I1] - W[I0], W[I2] - W[I0]);
  const L nn = dot(n, n);
  const auto pos = nn > L(0.0f);
  const L ax = abs(n.x), ay = abs(n.y), az = abs(n.z);
  // The projection axis K (the normal's largest component); u, w the other two in order.
  const auto k0 = (ax >= ay) && (ax >= az);
  const auto k1 = !k0 && (ay >= az);
  auto U = [&](const V3<L>& q) { return select(k0, q.y, select(k1, q.z, q.x)); };
  auto Wc = [&](const V3<L>& q) { return select(k0, q.z, select(k1, q.x, q.y)); };
  const V3<L> p = n * (dot(n, W[I0]) / nn);
  const L pu = U(p), pw = Wc(p);
  const V3<L>* id[3] = {&W[I0], &W[I1], &W[I2]};
  L c[3];
  for (int j = 0; j < 3; ++j) {
    const V3<L>& b = *id[j == 2 ? 0 : j + 1];
    const V3<L>& e = *id[j == 0 ? 2 : j - 1];
    c[j] = select(pos, (U(b) - pu) * (Wc(e) - pw) - (Wc(b) - pw) * (U(e) - pu), L(0.0f));
  }
  const L total = select(pos, select(k0, n.x, select(k1, n.y, n.z)), L(0.0f));
  const auto f0 = !same_sign(c[0], total), f1 = !same_sign(c[1], total), f2 = !same_sign(c[2], total);
  const auto inside = pos && !f0 && !f1 && !f2;
  Sub<L> r;
  const L sum = (c[0] + c[1]) + c[2];
  r.n = L(3.0f), r.i0 = L(float(I0)), r.i1 = L(float(I1)), r.i2 = L(float(I2));
  r.l0 = c[0] / sum, r.l1 = c[1] / sum, r.l2 = c[2] / sum, r.l3 = L(0.0f);
  r.v = p, r.vv = dot(p, p);
  if (all(inside || !need)) return r;
  Sub<L> best = r;
  auto have = inside;  // inside lanes keep r: mark them as decided
  const auto out = need && !inside;
  if (any(out && f0)) fold(out && f0, have, best, s1d<I1, I2>(W, wv));
  if (any(out && f1)) fold(out && f1, have, best, s1d<I2, I0>(W, wv));
  if (any(out && f2)) fold(out && f2, have, best, s1d<I0, I1>(W, wv));
  return best;
}

template <class L> inline L triple(const V3<L>& a, const V3<L>& b, const V3<L>& c) { return dot(a, cross(b, c)); }

// Tetrahedron W[0..3], for the lanes in `need` (as s2d).
template <class L, class M> inline Sub<L> s3d(const V3<L>* W, const L* wv, M need) {
  const L c0 = triple(W[1], W[2], W[3]), c1 = -triple(W[0], W[2], W[3]), c2 = triple(W[0], W[1], W[3]),
          c3 = -triple(W[0], W[1], W[2]);
  const L total = ((c0 + c1) + c2) + c3;
  const auto f0 = !same_sign(c0, total), f1 = !same_sign(c1, total), f2 = !same_sign(c2, total),
             f3 = !same_sign(c3, total);
  const auto inside = !f0 && !f1 && !f2 && !f3;
  Sub<L> r;
  r.n = L(4.0f), r.i0 = L(0.0f), r.i1 = L(1.0f), r.i2 = L(2.0f);
  r.l0 = c0 / total, r.l1 = c1 / total, r.l2 = c2 / total, r.l3 = c3 / total;
  r.v = V3<L>{L(0.0f), L(0.0f), L(0.0f)}, r.vv = L(0.0f);
  if (all(inside || !need)) return r;
  Sub<L> best = r;
  auto have = inside;
  const auto out = need && !inside;
  if (any(out && f0)) fold(out && f0, have, best, s2d<1, 2, 3>(W, wv, out && f0));
  if (any(out && f1)) fold(out && f1, have, best, s2d<0, 2, 3>(W, wv, out && f1));
  if (any(out && f2)) fold(out && f2, have, best, s2d<0, 1, 3>(W, wv, out && f2));
  if (any(out && f3)) fold(out && f3, have, best, s2d<0, 1, 2>(W, wv, out && f3));
  return best;
}

}  // namespace gjk_lanes
}  // namespace gyro::GYRO_ARCH_NS
