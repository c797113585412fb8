// Triangles (Cookbook chapter 10): containment, closest point, barycentric coordinates, and
// overlap with spheres, AABBs, OBBs, planes and triangles, written once over a lane type
// (float, or a SIMD batch with one primitive pair per lane).
//
// Every function computes all of its cases and picks with selects, so lane k of a batch gives
// exactly the bits the float instantiation gives for element k; sums run in written order.
//
// The normal n = (b - a) x (c - a) is computed with error-free products (Dekker's
// two-product, only + - *), so it is accurate to a few ulp even on long slivers, where
// the plain cross product cancels and loses its direction (error about eps / sin of the
// angle at a): a 1000:1 sliver would otherwise have its projections moved off it by 1e-4
// of its size. The edge vectors are exact differences whenever the corners' coordinates
// are within a factor 2 of each other (Sterbenz): any triangle away from the coordinate
// planes, however far from the origin.
//
// Degenerate triangles. A triangle counts as degenerate when its corners are collinear or
// coincident to float precision: |n|^2 <= 2^-36 |b - a|^2 |c - a|^2, that is sin^2 of its
// angle at a at most 2^-36 (an angle under about 3.8e-6 rad, 64 float epsilons). It is then
// narrower than about 4e-6 of its size, less than contains()'s tolerance, and its plane is
// decided by the rounding of its corners more than by their positions; such a triangle is
// treated as the segment (or point) it collapses to, which moves no answer by more than
// its width. Every function below uses this one rule, so they agree on which triangles are
// degenerate.
//
// Magnitudes: |n|^2 is a fourth power of the size, so sizes (edge lengths) are expected in
// about [1e-9, 1e9]; coordinates may be anywhere in float's range. Every test works on
// differences of nearby coordinates (corner - corner, corner - point, corner - box centre),
// so its accuracy does not degrade far from the origin.
#pragma once

#include "geometry/shapes_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

/// sin^2 of the angle at corner a at or below which a triangle is degenerate (see above).
inline constexpr float kTriangleDegenerateSin2 = 0x1p-36f;
/// contains(): a point is on the triangle when its distance to it is at most
/// kTriangleContainsRel * (largest side of the triangle's bounding box)
/// + kTriangleContainsUlp * (largest |coordinate| of the corners and the point).
inline constexpr float kTriangleContainsRel = 1e-5f;
inline constexpr float kTriangleContainsUlp = 0x1p-20f;  // 8 to 16 ulp of that coordinate

namespace detail_tri {

template <class L> using mask_of = decltype(L(0.0f) < L(0.0f));

// Edge vectors, the unnormalised normal n = ab x ac and the degeneracy rule, computed the
// same way by every function.
template <class L> struct Frame {
  V3<L> ab, ac, bc, n;
  L nn;  // |n|^2
  mask_of<L> degenerate;
};

// a = hi + lo exactly, hi holding the upper 12 bits of the significand (Veltkamp's split).
template <class L> struct Split {
  L v, hi, lo;
};
template <class L> inline Split<L> split(L a) {
  const L c = L(4097.0f) * a;
  const L hi = c - (c - a);
  return {a, hi, a - hi};
}

// x*y - z*w with both products' rounding errors recovered (Dekker's two-product, exact in
// float without FMA) and added back: a few ulp of the result even when the products cancel.
template <class L> inline L diff_of_products(const Split<L>& x, const Split<L>& y, const Split<L>& z, const Split<L>& w) {
  const L p = x.v * y.v, q = z.v * w.v;
  const L ep = (((x.hi * y.hi - p) + x.hi * y.lo) + x.lo * y.hi) + x.lo * y.lo;
  const L eq = (((z.hi * w.hi - q) + z.hi * w.lo) + z.lo * w.hi) + z.lo * w.lo;
  return (p - q) + (ep - eq);
}

// u x v with every component accurate to a few ulp (why: see the top of this file).
template <class L> inline V3<L> accurate_cross(const V3<L>& u, const V3<L>& v) {
  const Split<L> ux = split(u.x), uy = split(u.y), uz = split(u.z);
  const Split<L> vx = split(v.x), vy = split(v.y), vz = split(v.z);
  return {diff_of_products(uy, vz, uz, vy), diff_of_products(uz, vx, ux, vz), diff_of_products(ux, vy, uy, vx)};
}

template <class L> inline Frame<L> frame(const TriangleL<L>& t) {
  const V3<L> ab = t.b - t.a, ac = t.c - t.a, bc = t.c - t.b;
  const V3<L> n = accurate_cross(ab, ac);
  const L nn = dot(n, n);
  // Written as !(x > y) so that NaN corners also take the degenerate path.
  const auto degenerate = !(nn > (L(kTriangleDegenerateSin2) * length_sq(ab)) * length_sq(ac));
  return {ab, ac, bc, n, nn, degenerate};
}

template <class L> inline L max_abs(const V3<L>& v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }

// The point of the triangle nearest to p, both as a point q and as the offset q - p. The
// offset is formed from differences of nearby coordinates (a - p, t (b - a), ...), never
// from q itself, so its accuracy does not depend on how far from the origin the pair is:
// what contains() and the sphere test measure.
template <class L> struct Nearest {
  V3<L> q, offset;
};

// The point of segment [s, e] (E = e - s) nearest to p, from sp = s - p, s0 = E.(p - s)
// and s1 = E.(p - e). Between the ends s0 > 0 > s1, so s0 / (s0 - s1) lies in [0, 1] in
// float too; a zero-length edge gives s.
template <class L>
inline Nearest<L> segment_nearest(const V3<L>& s, const V3<L>& e, const V3<L>& E, const V3<L>& sp, const V3<L>& ep,
                                  L s0, L s1) {
  const L t = s0 / (s0 - s1);
  const auto at_s = s0 <= L(0.0f), at_e = s1 >= L(0.0f);
  return {vselect(at_s, s, vselect(at_e, e, s + E * t)), vselect(at_s, sp, vselect(at_e, ep, sp + E * t))};
}

template <class M, class L> inline Nearest<L> nselect(M m, const Nearest<L>& x, const Nearest<L>& y) {
  return {vselect(m, x.q, y.q), vselect(m, x.offset, y.offset)};
}

// Of three candidates, the nearest to p (the first on ties).
template <class L> inline Nearest<L> nearest_of(const Nearest<L>& n0, const Nearest<L>& n1, const Nearest<L>& n2) {
  const L d0 = length_sq(n0.offset), d1 = length_sq(n1.offset), d2 = length_sq(n2.offset);
  const auto take1 = d1 < d0;
  return nselect(d2 < select(take1, d1, d0), n2, nselect(take1, n1, n0));
}

// Ericson's Voronoi-region walk (Real-Time Collision Detection 5.1.5) with every region
// computed and picked by selects, in his order (vertex a, b, edge ab, vertex c, edge ac,
// edge bc, face). The edge regions use the edge functions n . ((b - p) x (c - p)) rather
// than the Lagrange-identity products of dot products, which cancel catastrophically on
// thin triangles; the face point is p projected on the plane. A degenerate triangle gives
// the nearest of its three edges' points, i.e. the point of the segment (or the point) it
// collapses to.
template <class L> inline Nearest<L> nearest(const TriangleL<L>& t, const V3<L>& p) {
  const auto f = frame(t);
  const V3<L> ap = p - t.a, bp = p - t.b, cp = p - t.c;
  const V3<L> pa = -ap, pb = -bp, pc = -cp;
  const L d1 = dot(f.ab, ap), d2 = dot(f.ac, ap);  // vertex a: both <= 0
  const L d3 = dot(f.ab, bp), e1 = dot(f.bc, bp);  // vertex b: d3 >= 0, e1 <= 0
  const L d6 = dot(f.ac, cp), e2 = dot(f.bc, cp);  // vertex c: d6 >= 0, e2 >= 0
  const Nearest<L> n_ab = segment_nearest(t.a, t.b, f.ab, pa, pb, d1, d3);
  const Nearest<L> n_ac = segment_nearest(t.a, t.c, f.ac, pa, pc, d2, d6);
  const Nearest<L> n_bc = segment_nearest(t.b, t.c, f.bc, pb, pc, e1, e2);
  // |n| times twice the signed area that p's projection spans with each edge.
  const L va = dot(f.n, cross(bp, cp)), vb = dot(f.n, cross(cp, ap)), vc = dot(f.n, cross(ap, bp));
  const L zero(0.0f);
  const V3<L> to_plane = f.n * (dot(ap, f.n) / f.nn);
  Nearest<L> r{p - to_plane, -to_plane};
  r = nselect((va <= zero) && (e1 >= zero) && (e2 <= zero), n_bc, r);
  r = nselect((vb <= zero) && (d2 >= zero) && (d6 <= zero), n_ac, r);
  r = nselect((d6 >= zero) && (e2 >= zero), Nearest<L>{t.c, pc}, r);
  r = nselect((vc <= zero) && (d1 >= zero) && (d3 <= zero), n_ab, r);
  r = nselect((d3 >= zero) && (e1 <= zero), Nearest<L>{t.b, pb}, r);
  r = nselect((d1 <= zero) && (d2 <= zero), Nearest<L>{t.a, pa}, r);
  return nselect(f.degenerate, nearest_of(n_ab, n_ac, n_bc), r);
}

// Whether the cross product c = u x v is usable as an axis: not degenerate (u and v
// parallel to float precision, or one of them zero). Symmetric in u and v.
template <class L> inline auto usable_axis(const V3<L>& c, const V3<L>& u, const V3<L>& v) {
  return length_sq(c) > L(kTriangleDegenerateSin2) * (length_sq(u) * length_sq(v));
}

// True where the triangle v0 v1 v2 and the box [-e, e] are separated along axis (touching is
// not separated). A zero axis projects everything to 0 and never separates.
template <class L>
inline auto box_separates(const V3<L>& e, const V3<L>& v0, const V3<L>& v1, const V3<L>& v2, const V3<L>& axis) {
  const L p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
  const L r = (e.x * abs(axis.x) + e.y * abs(axis.y)) + e.z * abs(axis.z);
  return (min(min(p0, p1), p2) > r) || (max(max(p0, p1), p2) < -r);
}

// Triangle v0 v1 v2 against the box [-e, e] in the box's own frame: the separating axis test
// of Akenine-Moller (2001) over 13 axes: the 3 box faces, the triangle normal, and the 9
// cross products of the box axes with the triangle edges, each with the fallback axis
// when the edge is parallel to the box axis. (For a flat triangle these 13 are complete;
// for a degenerate one, a segment or point, the face and edge axes still are.)
template <class L> inline auto triangle_box_overlap(const V3<L>& e, const V3<L>& v0, const V3<L>& v1, const V3<L>& v2) {
  auto sep = (min(min(v0.x, v1.x), v2.x) > e.x) || (max(max(v0.x, v1.x), v2.x) < -e.x);
  sep = sep || (min(min(v0.y, v1.y), v2.y) > e.y) || (max(max(v0.y, v1.y), v2.y) < -e.y);
  sep = sep || (min(min(v0.z, v1.z), v2.z) > e.z) || (max(max(v0.z, v1.z), v2.z) < -e.z);
  // Uniform early exit, taken only when every lane is separated: it cannot change a result.
  if (all(sep)) return !sep;
  const V3<L> f[3] = {v1 - v0, v2 - v1, v0 - v2};
  const V3<L> start[3] = {v0, v1, v2};
  sep = sep || box_separates(e, v0, v1, v2, cross(f[0], f[1]));
  const L zero(0.0f);
  for (int j = 0; j < 3; ++j) {
    const V3<L>& g = f[j];
    // box axis x edge: x = (1,0,0) x g, y = (0,1,0) x g, z = (0,0,1) x g; the fallback turns
    // toward the box centre (the origin here) from the edge's start.
    const V3<L> axes[3] = {{zero, -g.z, g.y}, {g.z, zero, -g.x}, {-g.y, g.x, zero}};
    const L limit = L(kTriangleDegenerateSin2) * length_sq(g);
    const auto usable0 = length_sq(axes[0]) > limit, usable1 = length_sq(axes[1]) > limit,
               usable2 = length_sq(axes[2]) > limit;
    // The fallback is formed only when some lane selects it: the same answer, cheaper.
    const bool any_fallback = any(!(usable0 && usable1 && usable2));
    const V3<L> fallback = any_fallback ? cross(g, cross(g, -start[j])) : axes[0];
    sep = sep || box_separates(e, v0, v1, v2, vselect(usable0, axes[0], fallback));
    sep = sep || box_separates(e, v0, v1, v2, vselect(usable1, axes[1], fallback));
    sep = sep || box_separates(e, v0, v1, v2, vselect(usable2, axes[2], fallback));
  }
  return !sep;
}

// True where two point sets of three are separated along axis.
template <class L> inline auto tri_tri_separates(const V3<L> (&a)[3], const V3<L> (&b)[3], const V3<L>& axis) {
  const L pa0 = dot(axis, a[0]), pa1 = dot(axis, a[1]), pa2 = dot(axis, a[2]);
  const L pb0 = dot(axis, b[0]), pb1 = dot(axis, b[1]), pb2 = dot(axis, b[2]);
  return (max(max(pa0, pa1), pa2) < min(min(pb0, pb1), pb2)) || (max(max(pb0, pb1), pb2) < min(min(pa0, pa1), pa2));
}

// The longest edge vector of a triangle (ab on ties, then ac): the direction of the
// segment a degenerate triangle collapses to.
template <class L> inline V3<L> longest_edge(const Frame<L>& f) {
  const L lab = length_sq(f.ab), lac = length_sq(f.ac), lbc = length_sq(f.bc);
  return vselect((lab >= lac) && (lab >= lbc), f.ab, vselect(lac >= lbc, f.ac, f.bc));
}

}  // namespace detail_tri

/// The point of the triangle nearest to p: Ericson's Voronoi regions, written branch-free
/// (see detail_tri::nearest). Degenerate triangle: the nearest point of the segment or
/// point it collapses to.
template <class L> inline V3<L> closest_point(const TriangleL<L>& t, const V3<L>& p) { return detail_tri::nearest(t, p).q; }

/// The distance within which contains() counts a point as on the triangle.
template <class L> inline L contains_tolerance(const TriangleL<L>& t, const V3<L>& p) {
  const V3<L> lo = vmin(vmin(t.a, t.b), t.c), hi = vmax(vmax(t.a, t.b), t.c);
  const V3<L> ext = hi - lo;
  const L size = max(max(ext.x, ext.y), ext.z);
  const L mag = max(max(detail_tri::max_abs(lo), detail_tri::max_abs(hi)), detail_tri::max_abs(p));
  return L(kTriangleContainsRel) * size + L(kTriangleContainsUlp) * mag;
}

/// True where p lies on the triangle: on its plane and inside its edges, both within
/// contains_tolerance() (the distance from p to closest_point() is at most that).
template <class L> inline auto contains(const TriangleL<L>& t, const V3<L>& p) {
  const L tol = contains_tolerance(t, p);
  return length_sq(detail_tri::nearest(t, p).offset) <= tol * tol;
}

/// Barycentric coordinates (u, v, w) of p's projection on the triangle's plane:
/// projection = u a + v b + w c with u = 1 - v - w. They are all >= 0 inside the triangle.
/// v and w are the signed areas n . ((c - p) x (a - p)) / |n|^2 and n . ((a - p) x (b - p)) / |n|^2.
/// Degenerate triangle: the coordinates of p's projection on the line of its longest edge,
/// with 0 for the third corner; all corners coincident: (1, 0, 0).
template <class L> inline V3<L> barycentric(const V3<L>& p, const TriangleL<L>& t) {
  using namespace detail_tri;
  const auto f = frame(t);
  const V3<L> ap = p - t.a, bp = p - t.b, cp = p - t.c;
  const L v = dot(f.n, cross(cp, ap)) / f.nn;
  const L w = dot(f.n, cross(ap, bp)) / f.nn;
  const V3<L> proper((L(1.0f) - v) - w, v, w);
  // Degenerate: s along the longest edge (ab on ties, then ac), from its first corner.
  const L lab = length_sq(f.ab), lac = length_sq(f.ac), lbc = length_sq(f.bc);
  const auto use_ab = (lab >= lac) && (lab >= lbc);
  const auto use_ac = !use_ab && (lac >= lbc);
  const auto use_bc = !use_ab && !use_ac;
  const V3<L> edge = vselect(use_ab, f.ab, vselect(use_ac, f.ac, f.bc));
  const L len2 = select(use_ab, lab, select(use_ac, lac, lbc));
  const L s = select(len2 > L(0.0f), dot(vselect(use_bc, bp, ap), edge) / len2, L(0.0f));
  const L r = L(1.0f) - s, zero(0.0f);
  const V3<L> collapsed(select(use_bc, zero, r), select(use_ab, s, select(use_ac, zero, r)), select(use_ab, zero, s));
  return vselect(f.degenerate, collapsed, proper);
}

/// Sphere and triangle overlap (or touch): the closest point is within the radius.
template <class L> inline auto overlaps(const SphereL<L>& s, const TriangleL<L>& t) {
  return length_sq(detail_tri::nearest(t, s.c).offset) <= s.r * s.r;
}

/// AABB and triangle overlap (or touch): 13-axis separating axis test in the box's frame.
template <class L> inline auto overlaps(const AabbL<L>& b, const TriangleL<L>& t) {
  return detail_tri::triangle_box_overlap(b.e, t.a - b.c, t.b - b.c, t.c - b.c);
}

/// OBB and triangle overlap (or touch): the corners are taken into the box's frame (dot
/// products with its axes), then the AABB test.
template <class L> inline auto overlaps(const ObbL<L>& b, const TriangleL<L>& t) {
  auto local = [&](const V3<L>& p) {
    const V3<L> d = p - b.c;
    return V3<L>(dot(d, b.u[0]), dot(d, b.u[1]), dot(d, b.u[2]));
  };
  return detail_tri::triangle_box_overlap(b.e, local(t.a), local(t.b), local(t.c));
}

/// Plane and triangle overlap (or touch): the corners' signed distances do not all have
/// the same strict sign.
template <class L> inline auto overlaps(const PlaneL<L>& p, const TriangleL<L>& t) {
  const L da = dot(p.n, t.a) - p.d, db = dot(p.n, t.b) - p.d, dc = dot(p.n, t.c) - p.d;
  return (min(min(da, db), dc) <= L(0.0f)) && (max(max(da, db), dc) >= L(0.0f));
}

/// Triangle and triangle overlap (or touch), by separating axes on the corners taken
/// relative to the midpoint of the two first corners (symmetric in A and B, so
/// overlaps(A, B) == overlaps(B, A) bit for bit):
///  - the 2 normals and the 9 edge-edge cross products; where an edge pair is parallel
///    its cross product vanishes and the book's fallback e x (e x w) is tested as well
///    (Cookbook 10, SatCrossEdge; w joins the edges' starts), for e each of the two edges;
///  - the 6 in-plane edge normals n x e. The 11 axes above all collapse onto the common
///    normal when the triangles are coplanar, so without these two coplanar triangles side
///    by side would be reported as overlapping; the fallback only covers parallel edges.
///  - for a degenerate triangle (a segment or a point) the in-plane normals use the other
///    triangle's normal, and lanes where either is degenerate also test the directions a
///    segment-segment, point-segment or point-point test needs: both segment directions,
///    the line between the centroids w, d x (d x w) for each segment d, and the in-plane
///    normals of two segments in their common plane.
template <class L> inline auto overlaps(const TriangleL<L>& A, const TriangleL<L>& B) {
  using namespace detail_tri;
  const auto fa = frame(A), fb = frame(B);
  const V3<L> o = (A.a + B.a) * L(0.5f);
  const V3<L> a[3] = {A.a - o, A.b - o, A.c - o};
  const V3<L> b[3] = {B.a - o, B.b - o, B.c - o};
  const V3<L> ea[3] = {fa.ab, fa.bc, -fa.ac};  // a->b, b->c, c->a
  const V3<L> eb[3] = {fb.ab, fb.bc, -fb.ac};
  auto sep = tri_tri_separates(a, b, fa.n) || tri_tri_separates(a, b, fb.n);
  if (all(sep)) return !sep;  // uniform early exit: every lane is already decided
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const V3<L> c = cross(ea[i], eb[j]);
      const auto usable = usable_axis(c, ea[i], eb[j]);
      sep = sep || tri_tri_separates(a, b, c);
      // Parallel edges: the fallback from each of the two edges (both, so that swapping A
      // and B tests the same axes). Masked to the lanes that use them, so skipping the
      // block when no lane does changes nothing (there c alone was tested: a zero or
      // near-zero axis, which is still a valid one).
      if (any(!usable && !sep)) {
        const V3<L> w = b[j] - a[i];
        const auto fallback_sep = tri_tri_separates(a, b, cross(ea[i], cross(ea[i], w))) ||
                                  tri_tri_separates(a, b, cross(eb[j], cross(eb[j], w)));
        sep = sep || (!usable && fallback_sep);
      }
    }
  if (all(sep)) return !sep;
  const V3<L> na = vselect(fa.degenerate, fb.n, fa.n), nb = vselect(fb.degenerate, fa.n, fb.n);
  for (int i = 0; i < 3; ++i) {
    sep = sep || tri_tri_separates(a, b, cross(na, ea[i]));
    sep = sep || tri_tri_separates(a, b, cross(nb, eb[i]));
  }
  const auto degenerate = fa.degenerate || fb.degenerate;
  // Only lanes with a degenerate triangle take these axes (through the mask), so whether
  // the block runs cannot change the other lanes: skipping it when no lane needs it is safe.
  if (any(degenerate && !sep)) {
    const V3<L> da = longest_edge(fa), db = longest_edge(fb);
    const V3<L> w = ((b[0] + b[1]) + b[2]) - ((a[0] + a[1]) + a[2]);  // 3 x centroid difference
    const V3<L> m = cross(da, db);
    const V3<L> extra[7] = {da, db, w, cross(da, cross(da, w)), cross(db, cross(db, w)), cross(m, da), cross(m, db)};
    auto extra_sep = L(0.0f) > L(0.0f);
    for (const V3<L>& axis : extra) extra_sep = extra_sep || tri_tri_separates(a, b, axis);
    sep = sep || (degenerate && extra_sep);
  }
  return !sep;
}

}  // namespace gyro::GYRO_ARCH_NS
