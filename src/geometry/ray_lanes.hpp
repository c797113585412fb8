// Raycasts and linetests against spheres, AABBs, OBBs and planes (Cookbook chapter 10),
// written once over lanes: the scalar API (L = float) and the batch kernels (one ray per
// lane, the primitive broadcast or loaded per lane) run the same expressions.
//
// Ray semantics: the ray is o + t d with t in [tmin, tmax]; d need not be unit length, t
// is in units of |d|. The hit is the smallest t in [tmin, tmax] where the ray crosses the
// surface, so a ray that starts inside a solid reports where it leaves. A ray whose |d|^2
// is zero, subnormal or overflows (not in [FLT_MIN, FLT_MAX]) never hits. The ray_*_t
// functions return that t, or +infinity when there is no hit (a hit at t = -0 reads +0).
// A plane is hit where the ray crosses it; a ray parallel to it (dot(n, d) == 0 in float)
// never hits, even one lying in the plane.
//
// Normals (ray_*_normal, meaningful only for a t that ray_*_t returned as a hit): unit;
// outward for solids, facing the ray's origin side for the plane. A sphere of radius 0,
// or a hit at the very centre, has no outward direction: its normal is -d / |d|. A box
// hit's normal is the face whose slab gave t; at an edge or a corner, where slabs tie,
// the lowest axis wins (x, then y, then z).
//
// Linetests: true when the segment a-b touches the shape, a touching end included; for
// solids a segment that starts or lies inside counts. A zero-length segment is the point
// a. Inputs with NaN give some answer and never crash.
//
// Robust slabs (Williams et al. 2005, "An efficient and robust ray-box intersection
// algorithm"): each slab's near and far planes are chosen by the sign bit of d, so -0
// picks like a negative direction, and t is (distance to the plane) / d, which is +-inf
// when d is +-0. When the origin lies exactly on a slab plane and d is 0 along that axis
// the quotient is 0/0 = NaN: the ray lies in the face's plane, which touches the slab.
// Every slab value enters the running max/min as the FIRST operand, whose NaN the lanes'
// min/max ignore (the second operand wins), so such a slab constrains nothing.
// Distances to the planes are (c - o) -+ e, not (c -+ e) - o: for a small box far from the
// origin c - e would round at the scale of c.
#pragma once

#include "geometry/shapes_lanes.hpp"
#include "math/vec3_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {

namespace detail_ray {

template <class L> inline L inf() { return L(__builtin_inff()); }

// |d|^2 in [FLT_MIN, FLT_MAX]: the rays that can hit.
template <class L> inline auto direction_ok(const V3<L>& d) {
  const L dd = dot(d, d);
  return (dd >= L(0x1p-126f)) && (dd <= L(0x1.fffffep127f));
}

// The parametric interval [tn, tf] of the line o + t d inside one slab |x - c| <= e,
// where oc = c - o along the axis. NaN marks "no constraint" (see the header comment).
template <class L> struct Slab {
  L tn, tf;
};
template <class L> inline Slab<L> slab(L oc, L e, L d) {
  const auto negative = copysign(L(1.0f), d) < L(0.0f);
  const L lo = oc - e, hi = oc + e;  // distances from o to the low and high planes
  return {select(negative, hi, lo) / d, select(negative, lo, hi) / d};
}

// The line against a box at the origin of the frame where oc = c - o and d are given.
template <class L> struct Slabs {
  Slab<L> s[3];
  L tn, tf;  // entry and exit; the line meets the box iff tn <= tf
};
template <class L> inline Slabs<L> slabs(const V3<L>& oc, const V3<L>& e, const V3<L>& d) {
  Slabs<L> r;
  r.s[0] = slab(oc.x, e.x, d.x);
  r.s[1] = slab(oc.y, e.y, d.y);
  r.s[2] = slab(oc.z, e.z, d.z);
  r.tn = -inf<L>();
  r.tf = inf<L>();
  for (int i = 0; i < 3; ++i) {  // slab value first: its NaN is ignored
    r.tn = max(r.s[i].tn, r.tn);
    r.tf = min(r.s[i].tf, r.tf);
  }
  return r;
}

// The first surface crossing in [tmin, tmax] of a box given by its slabs.
template <class L> inline L box_t(const Slabs<L>& s, auto ray_ok, L tmin, L tmax) {
  const L t = select(s.tn >= tmin, s.tn, s.tf);
  const auto hit = ray_ok && (s.tn <= s.tf) && (t >= tmin) && (t <= tmax) && (t < inf<L>());
  return select(hit, t, inf<L>()) + L(0.0f);
}

// The outward normal, in the slabs' frame, of the face that gave t: the entry face when
// t is the entry, else the exit face; at ties the lowest axis.
template <class L> inline V3<L> box_normal_local(const Slabs<L>& s, const V3<L>& d, L t) {
  const auto entering = t == s.tn;
  const L dv[3] = {d.x, d.y, d.z};
  L n[3];
  auto taken = L(0.0f) > L(0.0f);  // all false
  for (int i = 0; i < 3; ++i) {
    const auto gave_t = select(entering, s.s[i].tn, s.s[i].tf) == t;
    const auto pick = i == 2 ? !taken : (gave_t && !taken);  // z when none matched (no hit)
    taken = taken || pick;
    // Entering through the near plane the outward normal opposes d; leaving, it follows d.
    const L out = copysign(L(1.0f), dv[i]);
    n[i] = select(pick, select(entering, -out, out), L(0.0f));
  }
  return {n[0], n[1], n[2]};
}

// The box's frame: oc = coordinates of c - o, d in the box's axes.
template <class L> inline V3<L> to_frame(const ObbL<L>& b, const V3<L>& v) {
  return {dot(v, b.u[0]), dot(v, b.u[1]), dot(v, b.u[2])};
}

}  // namespace detail_ray

// ---------------------------------------------------------------- sphere

/// The first crossing of the sphere's surface in [tmin, tmax], or +inf. The discriminant
/// is r^2 - |f|^2 with f from the centre to the line's closest point (no cancellation far
/// from the sphere) and the roots are c/q and q/|d|^2 (Ray Tracing Gems ch. 7), in the
/// same operations and order as gyro's first ray-sphere kernel (ray_sphere_kernels.cpp,
/// whose bits the pinned determinism hashes hold), so t is bit-identical to it except
/// where its c/q root is wild (the repair below): there that kernel reported hits off the
/// sphere.
/// What ray_sphere_t needs of the direction alone: a walk that tests one ray against many
/// leaves forms it once (a division off every leaf's critical path; the same bits).
template <class L> struct RayDd {
  L dd, inv_dd;
};
template <class L> inline RayDd<L> ray_dd(const V3<L>& d) {
  const L dd = (d.x * d.x + d.y * d.y) + d.z * d.z;
  return {dd, L(1.0f) / dd};
}

template <class L>
inline L ray_sphere_t(const RayL<L>& ray, const RayDd<L>& k, const SphereL<L>& s, L tmin, L tmax) {
  const V3<L>& d = ray.d;
  const L dd = k.dd, inv_dd = k.inv_dd;
  const auto ray_ok = (dd >= L(0x1p-126f)) && (dd <= L(0x1.fffffep127f));
  const V3<L> oc = ray.o - s.c;
  const L b = -((oc.x * d.x + oc.y * d.y) + oc.z * d.z);
  const L sc = b * inv_dd;
  const V3<L> f{oc.x + sc * d.x, oc.y + sc * d.y, oc.z + sc * d.z};
  const L r2 = s.r * s.r;
  const L h = r2 - ((f.x * f.x + f.y * f.y) + f.z * f.z);
  const auto crosses = h >= L(0.0f);
  if (!any(crosses)) return detail_ray::inf<L>();  // uniform: the answer is +inf either way
  const L c = dot(oc, oc) - r2;
  const L q = b + copysign(sqrt(dd * h), b);
  const L t1 = q / dd, t0_kernel = c / q;
  // The roots are symmetric about sc. c cancels when the origin is near the surface, and
  // if q is small too (the ray leaves the origin along the surface) c/q can land anywhere
  // (a "hit" thousands of radii away). Such a root, farther from sc than twice the other
  // one (plus 2^-16 |sc| for rounding), is replaced by the mirror image of t1.
  const L w1 = abs(t1 - sc);
  const auto wild = abs(t0_kernel - sc) > (w1 + w1) + L(0x1p-16f) * abs(sc);
  const L t0 = select(wild, sc - (t1 - sc), t0_kernel);
  const L tn = min(t0, t1), tf = max(t0, t1);  // q = 0 (tangent at the origin): t0 = NaN, t1 wins
  const L t = select(tn >= tmin, tn, tf);
  const auto hit = crosses && ray_ok && (t >= tmin) && (t <= tmax) && (t < detail_ray::inf<L>());
  return select(hit, t, detail_ray::inf<L>()) + L(0.0f);
}
template <class L> inline L ray_sphere_t(const RayL<L>& ray, const SphereL<L>& s, L tmin, L tmax) {
  return ray_sphere_t(ray, ray_dd(ray.d), s, tmin, tmax);
}

/// Outward unit normal at the hit ray.o + t ray.d. The offset from the centre is taken as
/// (o - c) + t d, which keeps its precision far from the origin (the first kernel's
/// (o + t d) - c lost it: a 1e-3 sphere at 1e4 got arbitrary normals), and scaled by its
/// largest component before normalising so tiny spheres do not underflow.
template <class L> inline V3<L> ray_sphere_normal(const RayL<L>& ray, const SphereL<L>& s, L t) {
  const V3<L> f = (ray.o - s.c) + ray.d * t;
  const L m = max(abs(f.x), max(abs(f.y), abs(f.z)));
  const V3<L> g{f.x / m, f.y / m, f.z / m};
  const V3<L> n = g * (L(1.0f) / sqrt(dot(g, g)));
  const V3<L> back = -ray.d * (L(1.0f) / sqrt(dot(ray.d, ray.d)));
  return vselect((s.r > L(0.0f)) && (m > L(0.0f)), n, back);
}

// ---------------------------------------------------------------- AABB

/// The first crossing of the box's surface in [tmin, tmax], or +inf (robust slabs).
template <class L> inline L ray_aabb_t(const RayL<L>& ray, const AabbL<L>& b, L tmin, L tmax) {
  const auto s = detail_ray::slabs(b.c - ray.o, b.e, ray.d);
  return detail_ray::box_t(s, detail_ray::direction_ok(ray.d), tmin, tmax);
}

/// Outward unit normal of the face that gave t (an axis, +-1); at edges the lowest axis.
template <class L> inline V3<L> ray_aabb_normal(const RayL<L>& ray, const AabbL<L>& b, L t) {
  const auto s = detail_ray::slabs(b.c - ray.o, b.e, ray.d);
  return detail_ray::box_normal_local(s, ray.d, t);
}

// ---------------------------------------------------------------- OBB

/// The first crossing of the box's surface in [tmin, tmax], or +inf: the ray is taken into
/// the box's frame (projections on its axes) and cut by the slabs there.
template <class L> inline L ray_obb_t(const RayL<L>& ray, const ObbL<L>& b, L tmin, L tmax) {
  const auto s = detail_ray::slabs(detail_ray::to_frame(b, b.c - ray.o), b.e, detail_ray::to_frame(b, ray.d));
  return detail_ray::box_t(s, detail_ray::direction_ok(ray.d), tmin, tmax);
}

/// Outward unit normal (+-one of the box's axes) of the face that gave t; at edges the
/// lowest axis.
template <class L> inline V3<L> ray_obb_normal(const RayL<L>& ray, const ObbL<L>& b, L t) {
  const V3<L> dl = detail_ray::to_frame(b, ray.d);
  const auto s = detail_ray::slabs(detail_ray::to_frame(b, b.c - ray.o), b.e, dl);
  const V3<L> k = detail_ray::box_normal_local(s, dl, t);
  return (b.u[0] * k.x + b.u[1] * k.y) + b.u[2] * k.z;
}

// ---------------------------------------------------------------- plane

/// Where the ray crosses the plane, if in [tmin, tmax], else +inf. Parallel rays
/// (dot(n, d) == 0) never hit.
template <class L> inline L ray_plane_t(const RayL<L>& ray, const PlaneL<L>& p, L tmin, L tmax) {
  const L nd = dot(p.n, ray.d);
  const L t = (p.d - dot(p.n, ray.o)) / nd;
  const auto hit = detail_ray::direction_ok(ray.d) && (nd != L(0.0f)) && (t >= tmin) && (t <= tmax) &&
                   (t < detail_ray::inf<L>());
  return select(hit, t, detail_ray::inf<L>()) + L(0.0f);
}

/// The plane's normal facing the ray's origin side: n when the ray runs against n, else -n
/// (decided by the direction, so a ray starting in the plane gets the side it came from).
template <class L> inline V3<L> ray_plane_normal(const RayL<L>& ray, const PlaneL<L>& p) {
  return vselect(dot(p.n, ray.d) < L(0.0f), p.n, -p.n);
}

// ---------------------------------------------------------------- linetests

/// The segment touches the sphere: its closest point to the centre is within r (a
/// zero-length segment is the point a: 0/0 clamps to 0).
template <class L> inline auto linetest(const SphereL<L>& s, const SegmentL<L>& seg) {
  const V3<L> d = seg.b - seg.a;
  const V3<L> ac = s.c - seg.a;
  const L u = min(max(dot(ac, d) / dot(d, d), L(0.0f)), L(1.0f));  // NaN -> 0
  const V3<L> f = ac - d * u;
  return dot(f, f) <= s.r * s.r;
}

/// The segment touches the box: the slab interval meets [0, 1]. A zero-length segment
/// gives +-inf or NaN per slab, which the slabs read as "the point is inside or not".
template <class L> inline auto linetest(const AabbL<L>& b, const SegmentL<L>& seg) {
  const auto s = detail_ray::slabs(b.c - seg.a, b.e, seg.b - seg.a);
  return (s.tn <= s.tf) && (s.tn <= L(1.0f)) && (s.tf >= L(0.0f));
}

/// The segment touches the oriented box (the AABB test in the box's frame).
template <class L> inline auto linetest(const ObbL<L>& b, const SegmentL<L>& seg) {
  const auto s = detail_ray::slabs(detail_ray::to_frame(b, b.c - seg.a), b.e, detail_ray::to_frame(b, seg.b - seg.a));
  return (s.tn <= s.tf) && (s.tn <= L(1.0f)) && (s.tf >= L(0.0f));
}

/// The segment touches the plane: its ends are not strictly on the same side. A segment
/// lying in the plane touches it.
template <class L> inline auto linetest(const PlaneL<L>& p, const SegmentL<L>& seg) {
  const L sa = dot(p.n, seg.a) - p.d, sb = dot(p.n, seg.b) - p.d;
  return !(((sa > L(0.0f)) && (sb > L(0.0f))) || ((sa < L(0.0f)) && (sb < L(0.0f))));
}

}  // namespace gyro::GYRO_ARCH_NS
