// Raycasts and linetests against spheres, AABBs, OBBs and planes.
//
//  - Hard cases with exact answers: origins inside and on faces, rays along face planes
//    with +0 and -0 direction components (the robust-slab NaN case), corners and edges
//    (the normal's tie rule), degenerate shapes, zero/subnormal/overflowing directions.
//  - 10^5 seeded random rays (and segments) per shape against binary64 references written
//    here (the quadratic for spheres, slabs for boxes, the ray taken into the OBB's frame,
//    the plane equation; for linetests the closest point of the segment, slabs, and the
//    ends' sides), over scales 1e-3 to 1e4, far from the origin, unnormalised d.
//  - Properties: scaling d by 2^k scales t by 2^-k and keeps the normal, bit for bit; a
//    segment touches a shape iff its reverse does; a raycast hit in [0, 1] is a linetest
//    hit; sphere hit points lie on the sphere.
//  - ray_sphere_t gives the legacy ray-sphere kernel's bits (the pinned hashes) except
//    where it repairs that kernel's wild root; the batch call gives raycast()'s bits at
//    every level; a per-level probe runs every template against the scalar level's bits.
//
// Tolerance band of the raycasts: float cannot tell touching from missing, nor place a
// grazing hit, better than a few ulps of the distances involved allow. A float answer is
// inside the band when it is the exact answer of a problem perturbed backward by at most
// tol = kBandUlps * 2^-24 * M, where M is the problem's scale (|o - c| + size for solids,
// |o| + |plane distance| for planes): the shape grown or shrunk by up to tol (a sphere
// shrunk below radius 0 is empty; a box's extents stop at 0), tmin and tmax moved by
// tol / |d|, direction components below 16 ulps of |d| read as zero (in the box's frame,
// or along the plane's normal), and the origin and direction taken in the shape's frame
// as float rounds them (a move and a turn of a few ulps). t(growth) is followed through
// every branch switch by bisection, so a grazing hit's t is bracketed exactly. Every
// hit/miss disagreement with the reference and every t more than 8 ulps off must be
// explained that way; the rest are counted "outside" and must be 0. Linetests: the band is
// |depth| <= kLineBandUlps * 2^-24 * M, the signed depth of the segment in the shape (the
// minimum translation that separates them, or minus their distance) in binary64.
#include "gyro/raycast.hpp"

#include "core/state_hash.hpp"
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"
#include "raycast_probe.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace gyro {
namespace {

using gyro::testing::SplitMix64;

constexpr double kEps = 0x1p-24;
constexpr double kBandUlps = 16;     // raycasts: the backward perturbations of the band
constexpr double kLineBandUlps = 2;  // linetests: |depth| of the segment in the shape
constexpr float kInf = INFINITY;
constexpr int kRandomCases = 100000;

// ---------------------------------------------------------------- binary64 vectors
struct D3 {
  double x = 0, y = 0, z = 0;
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(D3 a) { return std::sqrt(dot(a, a)); }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return a * (1.0 / norm(a)); }
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
vec3 f3(D3 v) { return {float(v.x), float(v.y), float(v.z)}; }
D3 row(const OBB& b, int k) { return {b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]}; }

// ---------------------------------------------------------------- references
struct Perturb {
  double grow = 0;           // shape grown by this distance (plane: moved along n)
  double dtmin = 0, dtmax = 0;
  bool zero_tiny = false;    // direction components below 16 ulps of |d| read as 0
  bool rounded = false;      // the origin relative to the shape's centre rounded to float, as computed
};

// o - c, exactly or as float rounds it (a move of the origin by at most half an ulp per axis).
D3 rel(const vec3& o, const vec3& c, const Perturb& p) { return p.rounded ? d3(o - c) : d3(o) - d3(c); }

struct Ref {
  bool hit = false;
  double t = INFINITY;
  D3 n;                 // unit normal at the hit
  int axis = -1;        // boxes: the face's axis; its sign is in n
  bool entering = true;
  double cosine = 1;    // |cos| between d and the surface normal at the hit: conditioning
  double slab_near[3] = {-INFINITY, -INFINITY, -INFINITY};  // boxes: each slab's entry and exit t
  double slab_far[3] = {INFINITY, INFINITY, INFINITY};
  double slab_d[3] = {0, 0, 0};                       // boxes: d in the box's frame
};

// The documented rule, in float as documented: |d|^2 in [FLT_MIN, FLT_MAX].
bool ray_ok(const Ray& r) {
  const vec3& d = r.direction;
  const float dd = (d.x * d.x + d.y * d.y) + d.z * d.z;
  return dd >= FLT_MIN && dd <= FLT_MAX;
}

Ref ref_sphere(const Sphere& s, const Ray& ray, double tmin, double tmax, const Perturb& p = {}) {
  Ref out;
  if (!ray_ok(ray)) return out;
  tmin += p.dtmin, tmax += p.dtmax;
  const D3 d = d3(ray.direction);
  // Shrinking a sphere is moving the line away from its centre: below radius 0 it is empty.
  const double r = double(s.radius) + p.grow;
  if (r < 0) return out;
  const double a = dot(d, d);
  const D3 oc = rel(ray.origin, s.center, p);
  const double b = dot(oc, d);
  const D3 f = oc - d * (b / a);
  const double h = r * r - dot(f, f);
  if (h < 0) return out;
  const double q = -(b + std::copysign(std::sqrt(a * h), b));  // |o + t d - c|^2 = r^2: a t^2 + 2bt + cc
  const double cc = dot(oc, oc) - r * r;
  const double t0 = q / a, t1 = q != 0 ? cc / q : q / a;
  const double tn = std::min(t0, t1), tf = std::max(t0, t1);
  const double t = tn >= tmin ? tn : tf;
  if (!(t >= tmin && t <= tmax)) return out;
  out.hit = true, out.t = t, out.entering = tn >= tmin;
  const D3 pc = oc + d * t;
  out.n = r > 0 && norm(pc) > 0 ? unit(pc) : d * (-1.0 / norm(d));
  out.cosine = r > 0 ? std::sqrt(h) / r : 0;  // half chord / r
  return out;
}

// The line O + t D against the box |x_i| <= E_i (box frame), t in [tmin, tmax].
Ref ref_box_frame(D3 O, D3 D, D3 E, double dlen, double tmin, double tmax, const Perturb& p, bool ok) {
  Ref out;
  if (!ok) return out;
  tmin += p.dtmin, tmax += p.dtmax;
  double o[3] = {O.x, O.y, O.z}, d[3] = {D.x, D.y, D.z}, e[3] = {E.x, E.y, E.z};
  double tn = -INFINITY, tf = INFINITY, near[3], far[3];
  int an = -1, af = -1;
  for (int i = 0; i < 3; ++i) {
    e[i] = std::max(0.0, e[i] + p.grow);
    if (p.zero_tiny && std::abs(d[i]) <= 16 * kEps * dlen) d[i] = 0;
    out.slab_d[i] = d[i];
    if (d[i] == 0) {
      if (std::abs(o[i]) > e[i]) return out;
      near[i] = -INFINITY, far[i] = INFINITY;
      continue;
    }
    const double t1 = (-e[i] - o[i]) / d[i], t2 = (e[i] - o[i]) / d[i];
    near[i] = std::min(t1, t2), far[i] = std::max(t1, t2);
    if (near[i] > tn) tn = near[i], an = i;  // strict: the lowest axis keeps a tie
    if (far[i] < tf) tf = far[i], af = i;
  }
  if (tn > tf) return out;
  out.entering = tn >= tmin;
  const double t = out.entering ? tn : tf;
  if (!(t >= tmin && t <= tmax) || !std::isfinite(t)) return out;
  out.hit = true, out.t = t;
  out.axis = out.entering ? an : af;
  const double sgn = std::copysign(1.0, d[out.axis]) * (out.entering ? -1.0 : 1.0);
  double n[3] = {0, 0, 0};
  n[out.axis] = sgn;
  out.n = {n[0], n[1], n[2]};
  out.cosine = std::abs(d[out.axis]) / dlen;
  for (int i = 0; i < 3; ++i) out.slab_near[i] = near[i], out.slab_far[i] = far[i];
  return out;
}

Ref ref_aabb(const AABB& b, const Ray& ray, double tmin, double tmax, const Perturb& p = {}) {
  const D3 d = d3(ray.direction);
  return ref_box_frame(rel(ray.origin, b.center, p), d, d3(b.half_extents), norm(d), tmin, tmax, p, ray_ok(ray));
}

D3 to_frame(const OBB& b, D3 v) { return {dot(v, row(b, 0)), dot(v, row(b, 1)), dot(v, row(b, 2))}; }

// The box frame as float computes it: (x u_x + y u_y) + z u_z, rounded at each step. Using
// it is a backward perturbation: the ray moved and turned by a few ulps.
D3 to_frame_float(const OBB& b, const vec3& v) {
  float r[3];
  for (int i = 0; i < 3; ++i) {
    const float* u = b.orientation.m[i];
    r[i] = (v.x * u[0] + v.y * u[1]) + v.z * u[2];
  }
  return {r[0], r[1], r[2]};
}

Ref ref_obb(const OBB& b, const Ray& ray, double tmin, double tmax, const Perturb& p = {}) {
  const D3 d = d3(ray.direction);
  const D3 O = p.rounded ? to_frame_float(b, b.center - ray.origin) * -1.0 : to_frame(b, d3(ray.origin) - d3(b.center));
  const D3 D = p.rounded ? to_frame_float(b, ray.direction) : to_frame(b, d);
  Ref r = ref_box_frame(O, D, d3(b.half_extents), norm(d), tmin, tmax, p, ray_ok(ray));
  if (r.hit) r.n = (row(b, 0) * r.n.x + row(b, 1) * r.n.y) + row(b, 2) * r.n.z;
  return r;
}

Ref ref_plane(const Plane& pl, const Ray& ray, double tmin, double tmax, const Perturb& p = {}) {
  Ref out;
  if (!ray_ok(ray)) return out;
  tmin += p.dtmin, tmax += p.dtmax;
  const D3 n = d3(pl.normal), o = d3(ray.origin), d = d3(ray.direction);
  // rounded: dot(n, d) and d - dot(n, o) as float computes them (the ray turned and the
  // plane moved by a few ulps).
  const vec3 &nf = pl.normal, &of = ray.origin, &df = ray.direction;
  double nd = p.rounded ? double((nf.x * df.x + nf.y * df.y) + nf.z * df.z) : dot(n, d);
  const double num = p.rounded ? double(pl.distance - ((nf.x * of.x + nf.y * of.y) + nf.z * of.z))
                               : double(pl.distance) - dot(n, o);
  if (p.zero_tiny && std::abs(nd) <= 16 * kEps * norm(d) * norm(n)) nd = 0;
  if (nd == 0) return out;
  const double t = (num + p.grow) / nd;
  if (!(t >= tmin && t <= tmax) || !std::isfinite(t)) return out;
  out.hit = true, out.t = t;
  out.n = nd < 0 ? n : n * -1.0;
  out.cosine = std::abs(nd) / (norm(n) * norm(d));
  return out;
}

// Linetests: the segment a-b touches the shape; and the signed depth of the segment in
// the shape (> 0: the minimum translation that separates them; < 0: minus their distance,
// for boxes the largest gap over the separating axes): |depth| is how far the answer is
// from changing, the band test.
double depth_sphere(const Sphere& s, const Line& l) {
  const D3 a = d3(l.start), d = d3(l.end) - a, c = d3(s.center);
  const double dd = dot(d, d);
  const double u = dd > 0 ? std::clamp(dot(c - a, d) / dd, 0.0, 1.0) : 0.0;
  return s.radius - norm(a + d * u - c);
}
bool ref_line_sphere(const Sphere& s, const Line& l) { return depth_sphere(s, l) >= 0; }

// Segment O -> O + D against the box |x_i| <= E_i, by the separating axes of a box and a
// segment (Ericson 5.3.3): the three face normals and the three edges crossed with D.
double depth_box_frame(D3 O, D3 D, D3 E) {
  const D3 B = O + D;
  double depth = INFINITY;
  auto axis = [&](D3 n, bool face) {
    const double len = norm(n);
    if (!face && !(len > 1e-6 * norm(D))) return;  // D (nearly) along the edge: the face axes cover it
    const double pa = dot(O, n), pb = dot(B, n);
    const double R = E.x * std::abs(n.x) + E.y * std::abs(n.y) + E.z * std::abs(n.z);
    depth = std::min(depth, std::min(std::max(pa, pb) + R, R - std::min(pa, pb)) / len);
  };
  const D3 ax[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const D3& n : ax) axis(n, true);
  for (const D3& n : ax) axis(cross(n, D), false);
  return depth;
}
// The exact answer, by slabs (closed: touching counts).
bool ref_line_box_frame(D3 O, D3 D, D3 E) {
  double tn = -INFINITY, tf = INFINITY;
  for (int i = 0; i < 3; ++i) {
    if (D[i] == 0) {
      if (std::abs(O[i]) > E[i]) return false;
      continue;
    }
    const double t1 = (-E[i] - O[i]) / D[i], t2 = (E[i] - O[i]) / D[i];
    tn = std::max(tn, std::min(t1, t2)), tf = std::min(tf, std::max(t1, t2));
  }
  return tn <= tf && tn <= 1 && tf >= 0;
}
D3 to_frame(const OBB& b, D3 v);
bool ref_line_aabb(const AABB& b, const Line& l) {
  return ref_line_box_frame(d3(l.start) - d3(b.center), d3(l.end) - d3(l.start), d3(b.half_extents));
}
double depth_aabb(const AABB& b, const Line& l) {
  return depth_box_frame(d3(l.start) - d3(b.center), d3(l.end) - d3(l.start), d3(b.half_extents));
}
bool ref_line_obb(const OBB& b, const Line& l) {
  return ref_line_box_frame(to_frame(b, d3(l.start) - d3(b.center)), to_frame(b, d3(l.end) - d3(l.start)),
                            d3(b.half_extents));
}
double depth_obb(const OBB& b, const Line& l) {
  return depth_box_frame(to_frame(b, d3(l.start) - d3(b.center)), to_frame(b, d3(l.end) - d3(l.start)),
                         d3(b.half_extents));
}
// Plane: the ends' signed distances sa, sb; touching iff min <= 0 <= max.
double depth_plane(const Plane& p, const Line& l) {
  const double sa = dot(d3(p.normal), d3(l.start)) - p.distance;
  const double sb = dot(d3(p.normal), d3(l.end)) - p.distance;
  return std::min(std::max(sa, sb), -std::min(sa, sb));
}
bool ref_line_plane(const Plane& p, const Line& l) { return depth_plane(p, l) >= 0; }

// ---------------------------------------------------------------- random cases
double uni(SplitMix64& g, double a, double b) { return a + (b - a) * g.u(); }
int pick(SplitMix64& g, int n) { return int(g.next() % uint64_t(n)); }
bool chance(SplitMix64& g, double p) { return g.u() < p; }
D3 rand_unit(SplitMix64& g) {
  const double z = uni(g, -1, 1), phi = 6.283185307179586 * g.u(), r = std::sqrt(1 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}
D3 perpendicular(SplitMix64& g, D3 n) {
  for (;;) {
    const D3 c = cross(n, rand_unit(g));
    if (norm(c) > 0.1) return unit(c);
  }
}

enum Kind { kSphere = 0, kAabb = 1, kObb = 2, kPlane = 3 };
const char* const kKindName[] = {"sphere", "AABB", "OBB", "plane"};

// One random frame (scale and place) and one shape of each kind in it.
struct Shapes {
  double S = 1;  // the scale
  Sphere sphere;
  AABB aabb;
  OBB obb;
  Plane plane;
};

mat3 random_rotation(SplitMix64& g) {
  mat3 m;
  const int how = pick(g, 5);
  if (how == 0) return m;                   // identity
  if (how == 1) {                           // a signed permutation: exact 0 and +-1
    const int p = pick(g, 3), q = pick(g, 2);
    const int idx[3] = {p, (p + 1 + q) % 3, (p + 2 - q) % 3};
    m = mat3::zero();
    for (int r = 0; r < 3; ++r) m.m[r][idx[r]] = chance(g, 0.5) ? 1.0f : -1.0f;
    return m;
  }
  const double u1 = g.u(), u2 = g.u(), u3 = g.u(), kTwoPi = 6.283185307179586;  // uniform quaternion
  const double s1 = std::sqrt(1 - u1), s2 = std::sqrt(u1), a = kTwoPi * u2, b = kTwoPi * u3;
  const double x = s1 * std::sin(a), y = s1 * std::cos(a), z = s2 * std::sin(b), w = s2 * std::cos(b);
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.m[r][c] = float(R[r][c]);
  return m;
}

Shapes random_shapes(SplitMix64& g) {
  Shapes s;
  const double scales[] = {1e-3, 1.0, 1e4};
  s.S = scales[pick(g, 3)] * uni(g, 0.5, 2);
  const D3 off = chance(g, 0.3) ? rand_unit(g) * uni(g, 5e3, 2e4) : D3{};  // far from the origin
  // A grid on which c +- e is exact in float, so origins can sit exactly on faces.
  const double far = norm(off) + 8 * s.S;
  const double grid = chance(g, 0.5) ? std::max(std::exp2(std::floor(std::log2(s.S)) - 8),
                                                std::exp2(std::floor(std::log2(far)) - 21))
                                     : 0;
  auto q = [&](double v) { return grid > 0 ? std::round(v / grid) * grid : v; };
  auto size = [&] { return chance(g, 0.06) ? 0.0 : s.S * uni(g, 0.05, 1); };
  auto place = [&] {
    const D3 c = off + D3{uni(g, -1, 1), uni(g, -1, 1), uni(g, -1, 1)} * s.S;
    return f3({q(c.x), q(c.y), q(c.z)});
  };
  s.sphere = {place(), float(size())};
  s.aabb = {place(), f3({q(size()), q(size()), q(size())})};
  if (chance(g, 0.03)) s.aabb.half_extents = {};
  s.obb.center = place();
  s.obb.half_extents = f3({q(size()), q(size()), q(size())});
  s.obb.orientation = random_rotation(g);
  const D3 n = chance(g, 0.2) ? D3{0, 0, 0} : rand_unit(g);
  if (norm(n) == 0) {
    s.plane.normal = {};
    s.plane.normal[pick(g, 3)] = chance(g, 0.5) ? 1.0f : -1.0f;
  } else {
    s.plane.normal = f3(n);
  }
  s.plane.distance = float(dot(d3(s.plane.normal), off) + s.S * uni(g, -1, 1));
  return s;
}

struct Surface {
  D3 q, n, tangent;  // a surface point, the outward normal there, a tangent direction
};

// A box's point in its frame -> world.
D3 box_world(D3 c, const D3 (&u)[3], D3 l) { return ((c + u[0] * l.x) + u[1] * l.y) + u[2] * l.z; }

void box_axes(Kind k, const Shapes& s, D3& c, D3& e, D3 (&u)[3]) {
  if (k == kAabb) {
    c = d3(s.aabb.center), e = d3(s.aabb.half_extents), u[0] = {1, 0, 0}, u[1] = {0, 1, 0}, u[2] = {0, 0, 1};
  } else {
    c = d3(s.obb.center), e = d3(s.obb.half_extents);
    for (int i = 0; i < 3; ++i) u[i] = row(s.obb, i);
  }
}

D3 shape_center(Kind k, const Shapes& s) {
  switch (k) {
    case kSphere: return d3(s.sphere.center);
    case kAabb: return d3(s.aabb.center);
    case kObb: return d3(s.obb.center);
    default: return d3(s.plane.normal) * s.plane.distance;
  }
}
double shape_size(Kind k, const Shapes& s) {
  switch (k) {
    case kSphere: return s.sphere.radius;
    case kAabb: return norm(d3(s.aabb.half_extents));
    case kObb: return norm(d3(s.obb.half_extents));
    default: return s.S;
  }
}

D3 sample_inside(Kind k, const Shapes& s, SplitMix64& g) {
  if (k == kSphere) return d3(s.sphere.center) + rand_unit(g) * (s.sphere.radius * std::cbrt(g.u()));
  if (k == kPlane) return shape_center(k, s) + rand_unit(g) * (s.S * uni(g, 0, 2));
  D3 c, e, u[3];
  box_axes(k, s, c, e, u);
  return box_world(c, u, {e.x * uni(g, -1, 1), e.y * uni(g, -1, 1), e.z * uni(g, -1, 1)});
}

Surface sample_surface(Kind k, const Shapes& s, SplitMix64& g) {
  Surface f;
  if (k == kSphere) {
    f.n = rand_unit(g);
    f.q = d3(s.sphere.center) + f.n * s.sphere.radius;
    f.tangent = perpendicular(g, f.n);
  } else if (k == kPlane) {
    f.n = d3(s.plane.normal);
    f.tangent = perpendicular(g, f.n);
    f.q = f.n * s.plane.distance + perpendicular(g, f.n) * (s.S * uni(g, -3, 3));
  } else {
    D3 c, e, u[3];
    box_axes(k, s, c, e, u);
    const int a = pick(g, 3), b = (a + 1) % 3, cc = (a + 2) % 3;
    const double sg = chance(g, 0.5) ? 1 : -1;
    double l[3];
    const double ev[3] = {e.x, e.y, e.z};
    l[a] = sg * ev[a];
    l[b] = chance(g, 0.2) ? (chance(g, 0.5) ? ev[b] : -ev[b]) : ev[b] * uni(g, -1, 1);  // on an edge
    l[cc] = chance(g, 0.1) ? (chance(g, 0.5) ? ev[cc] : -ev[cc]) : ev[cc] * uni(g, -1, 1);
    f.q = box_world(c, u, {l[0], l[1], l[2]});
    f.n = u[a] * sg;
    // Along a face: one other axis exactly, or a mix of both.
    const double m = chance(g, 0.3) ? double(pick(g, 2)) : g.u();
    f.tangent = u[b] * (m * (chance(g, 0.5) ? 1 : -1)) + u[cc] * ((1 - m) * (chance(g, 0.5) ? 1 : -1));
    if (norm(f.tangent) == 0) f.tangent = u[b];
  }
  return f;
}

struct RayCase {
  Ray ray;
  float tmin = 0, tmax = kInf;
};

// A ray aimed at shape kind k: origins near, inside, on the surface or far; directions
// isotropic, aimed inside, grazing (tangent at a surface point), along axes with +-0
// components; |d| from 1e-3 to 1e3.
RayCase random_ray(Kind k, const Shapes& s, SplitMix64& g) {
  const D3 c = shape_center(k, s);
  const double size = std::max(shape_size(k, s), s.S * 0.05);
  D3 o, d;
  const int how = pick(g, 10);
  if (how <= 1) {  // grazing: o = q - L tangent, d = tangent, nudged off the surface by up to ~1e-6
    const Surface f = sample_surface(k, s, g);
    const double nudge = chance(g, 0.5) ? 0 : size * uni(g, -1e-6, 1e-6);
    d = f.tangent;
    o = (f.q + f.n * nudge) - d * (size * uni(g, 0.5, 4));
  } else if (how == 2) {  // origin on the surface, any direction
    const Surface f = sample_surface(k, s, g);
    o = f.q, d = chance(g, 0.5) ? rand_unit(g) : f.tangent;
  } else if (how == 3) {  // origin inside
    o = sample_inside(k, s, g), d = rand_unit(g);
  } else if (how == 4) {  // axis-aligned, +-0 in the other components, often on a face plane
    const Surface f = chance(g, 0.5) ? sample_surface(k, s, g) : Surface{sample_inside(k, s, g), {}, {}};
    const int a = pick(g, 3);
    double dv[3] = {chance(g, 0.5) ? 0.0 : -0.0, chance(g, 0.5) ? 0.0 : -0.0, chance(g, 0.5) ? 0.0 : -0.0};
    dv[a] = chance(g, 0.5) ? 1 : -1;
    d = {dv[0], dv[1], dv[2]};
    o = f.q - d * (size * uni(g, -3, 3));
  } else if (how == 5) {  // far away, aimed at the shape
    o = c + rand_unit(g) * (size * uni(g, 10, 100));
    d = sample_inside(k, s, g) - o;
  } else if (how == 6) {  // isotropic from nearby
    o = c + D3{uni(g, -3, 3), uni(g, -3, 3), uni(g, -3, 3)} * size;
    d = rand_unit(g);
  } else {  // aimed at an inside point from nearby
    o = c + D3{uni(g, -3, 3), uni(g, -3, 3), uni(g, -3, 3)} * size;
    d = sample_inside(k, s, g) - o;
  }
  if (norm(d) == 0) d = {1, 0, 0};
  d = unit(d);
  if (chance(g, 0.15)) {  // one zero component (keeping the signed zero of +-0 * x)
    const int a = pick(g, 3);
    d = {a == 0 ? 0.0 : d.x, a == 1 ? 0.0 : d.y, a == 2 ? 0.0 : d.z};
    if (norm(d) == 0) d = {0, 0, 1};
  }
  // |d| in [1e-3, 1e3], or a power of two.
  const double mag = chance(g, 0.5) ? 1 : (chance(g, 0.5) ? std::pow(10.0, uni(g, -3, 3)) : std::exp2(pick(g, 9) - 4));
  RayCase rc;
  rc.ray.origin = f3(o);
  rc.ray.direction = f3(d * mag);
  if (chance(g, 0.25)) {
    const double T = (norm(o - c) + size) / norm(d3(rc.ray.direction));
    rc.tmin = float(T * uni(g, 0, 1));
    rc.tmax = float(rc.tmin + T * uni(g, 0, 2));
  }
  return rc;
}

// Every input of a case in hex floats, for reproducing a failure.
std::string dump(const Shapes& s, const RayCase& rc) {
  char buf[1200];
  const OBB& b = s.obb;
  std::snprintf(buf, sizeof buf,
                "\n  Sphere{{%a,%a,%a},%a} AABB{{%a,%a,%a},{%a,%a,%a}}\n  OBB{{%a,%a,%a},{%a,%a,%a},mat3{{{%a,%a,%a},{%a,%a,%a},{%a,"
                "%a,%a}}}} Plane{{%a,%a,%a},%a}\n  Ray{{%a,%a,%a},{%a,%a,%a}} tmin %a tmax %a",
                s.sphere.center.x, s.sphere.center.y, s.sphere.center.z, s.sphere.radius, s.aabb.center.x,
                s.aabb.center.y, s.aabb.center.z, s.aabb.half_extents.x, s.aabb.half_extents.y, s.aabb.half_extents.z,
                b.center.x, b.center.y, b.center.z, b.half_extents.x, b.half_extents.y, b.half_extents.z,
                b.orientation.m[0][0], b.orientation.m[0][1], b.orientation.m[0][2], b.orientation.m[1][0],
                b.orientation.m[1][1], b.orientation.m[1][2], b.orientation.m[2][0], b.orientation.m[2][1],
                b.orientation.m[2][2], s.plane.normal.x, s.plane.normal.y, s.plane.normal.z, s.plane.distance,
                rc.ray.origin.x, rc.ray.origin.y, rc.ray.origin.z, rc.ray.direction.x, rc.ray.direction.y,
                rc.ray.direction.z, rc.tmin, rc.tmax);
  return buf;
}

// ---------------------------------------------------------------- judging
// The problem scale M of the band (see the top of the file).
double scale_of(Kind k, const Shapes& s, const Ray& r) {
  if (k == kPlane) return norm(d3(r.origin)) + std::abs(double(s.plane.distance));
  return norm(d3(r.origin) - shape_center(k, s)) + shape_size(k, s);
}

Ref ref_of(Kind k, const Shapes& s, const RayCase& rc, const Perturb& p = {}) {
  switch (k) {
    case kSphere: return ref_sphere(s.sphere, rc.ray, rc.tmin, rc.tmax, p);
    case kAabb: return ref_aabb(s.aabb, rc.ray, rc.tmin, rc.tmax, p);
    case kObb: return ref_obb(s.obb, rc.ray, rc.tmin, rc.tmax, p);
    default: return ref_plane(s.plane, rc.ray, rc.tmin, rc.tmax, p);
  }
}

RaycastResult cast(Kind k, const Shapes& s, const RayCase& rc) {
  switch (k) {
    case kSphere: return raycast(s.sphere, rc.ray, rc.tmin, rc.tmax);
    case kAabb: return raycast(s.aabb, rc.ray, rc.tmin, rc.tmax);
    case kObb: return raycast(s.obb, rc.ray, rc.tmin, rc.tmax);
    default: return raycast(s.plane, rc.ray, rc.tmin, rc.tmax);
  }
}

struct Judgement {
  bool explained = false;  // the float answer is the exact answer of a problem within the band
  Ref ref;                 // the (perturbed) reference that explains it
};

// Is the float answer (hit at t, or miss) the exact answer of a perturbed problem? For
// each move of tmin, tmax and each treatment of tiny direction components, the shape's
// growth g runs continuously over [-tol, tol]: t(g) is sampled at -tol, 0, tol and, where
// the answer changes branch between samples (hit or miss, entry or exit, a box's face), on
// both sides of the switch found by bisection (a grazing ray's t at the tangent point, an
// origin on the surface at t = 0). A hit is explained when its t lies within the
// range of those t (plus a few ulps of slack).
template <class RefFn> Judgement explain(bool hit, double t, double dlen, double M, RefFn&& ref) {
  const double tol = kBandUlps * kEps * M, tt = tol / dlen;
  const double slack = 8 * kEps * (std::abs(t) + M / dlen);
  const double shifts[3] = {0, -tt, tt};
  // Every combination of the discrete moves: float rounding, tiny components, tmin, tmax.
  for (int combo = 0; combo < 36; ++combo) {
    const bool rounded = combo >= 18, zt = combo % 18 >= 9;
    const double a = shifts[combo % 9 / 3], b = shifts[combo % 3];
    auto at = [&](double g) { return ref(Perturb{g, a, b, zt, rounded}); };
    const double grows[3] = {-tol, 0, tol};
    std::vector<Ref> r = {at(grows[0]), at(grows[1]), at(grows[2])};
    // The branch: hit or not, entry or exit, and a box's face.
    auto same = [](const Ref& x, const Ref& y) {
      return x.hit == y.hit && (!x.hit || (x.entering == y.entering && x.axis == y.axis));
    };
    for (int i = 0; i < 2; ++i) {
      // Every switch between the two samples (a grazing ray can go miss -> entry -> exit).
      double from = grows[i];
      Ref state = r[i];
      for (int switches = 0; switches < 4 && !same(state, r[i + 1]); ++switches) {
        double lo = from, hi = grows[i + 1];
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          (same(at(mid), state) ? lo : hi) = mid;
        }
        r.push_back(at(lo)), r.push_back(at(hi));
        from = hi, state = at(hi);
      }
    }
    if (!hit) {
      for (const Ref& x : r)
        if (!x.hit) return {true, x};
      continue;
    }
    double lo = INFINITY, hi = -INFINITY;
    int best = -1;
    for (int i = 0; i < int(r.size()); ++i)
      if (r[i].hit) {
        lo = std::min(lo, r[i].t), hi = std::max(hi, r[i].t);
        if (best < 0 || std::abs(r[i].t - t) < std::abs(r[best].t - t)) best = i;
      }
    if (best >= 0 && t >= lo - slack && t <= hi + slack) return {true, r[best]};
  }
  return {};
}

// A hit far from every discontinuity: the surface is crossed at a healthy angle and the
// answer keeps its branch (entry or exit) when the shape or [tmin, tmax] move by the band.
template <class RefFn> bool well_conditioned(const Ref& r0, double dlen, double M, RefFn&& ref) {
  if (!(r0.cosine >= 0.2)) return false;
  const double tol = kBandUlps * kEps * M, tt = tol / dlen;
  const Perturb moves[] = {{-tol, 0, 0, false}, {tol, 0, 0, false}, {0, -tt, 0, false},
                           {0, tt, 0, false},   {0, 0, -tt, false}, {0, 0, tt, false}};
  for (const Perturb& p : moves) {
    const Ref r = ref(p);
    if (!r.hit || r.entering != r0.entering || r.axis != r0.axis) return false;
  }
  return true;
}

struct Tally {
  std::size_t cases = 0, hits = 0, ref_hits = 0;
  std::size_t disagree_band = 0, disagree_outside = 0;  // hit/miss
  std::size_t t_band = 0, t_outside = 0;                // agreed hits whose t is off by more than a few ulps
  std::size_t normal_band = 0, normal_outside = 0;
  std::size_t well = 0, graze = 0, branch = 0;
  double max_dt_well = 0, max_dt_graze = 0;  // |dt| |d| / M
  double max_dn_graze = 0;                   // |dt| |d| cos / M: the grazing error across the surface
  double max_dn_well = 0;                    // |n - n_ref| on well-conditioned hits
  std::size_t on_face_zero_d = 0;            // origin exactly on a slab plane with d = 0 along it
  void print(const char* what) const {
    std::printf("  %-22s %zu cases, %zu hits (reference %zu); hit/miss disagreements: %zu inside the band, %zu "
                "outside\n"
                "  %-22s t: %zu off by more than 8 ulp but inside the band, %zu outside; max |dt||d|/M %.3g on %zu "
                "well-conditioned hits, %.3g on %zu grazing (%.3g across the surface: |dt||d|cos/M; %zu more took the exit for an entry at ~0)\n"
                "  %-22s normals: max |dn| %.3g (well-conditioned), %zu differ inside the band (edges, ties), %zu "
                "outside%s\n",
                what, cases, hits, ref_hits, disagree_band, disagree_outside, "", t_band, t_outside, max_dt_well, well,
                max_dt_graze, graze, max_dn_graze, branch, "", max_dn_well, normal_band, normal_outside,
                on_face_zero_d ? (", " + std::to_string(on_face_zero_d) + " rays on a face plane with d = 0 along it")
                                     .c_str()
                               : "");
  }
};

// Which of the box's axes a float normal is (+-1 along it), or -1.
int box_axis_of(Kind k, const Shapes& s, vec3 n, double& sign) {
  for (int i = 0; i < 3; ++i) {
    const double c = k == kAabb ? double(n[i]) : dot(d3(n), row(s.obb, i));
    if (std::abs(std::abs(c) - 1) < 1e-6) {
      sign = c > 0 ? 1 : -1;
      return i;
    }
  }
  return -1;
}

// The normal of a hit the reference agrees with. Boxes: the same face, or a face whose
// slab gives the same t within the band (an edge or corner). Spheres: the direction from
// the centre; planes: facing the origin's side, unless the ray is parallel within the band.
bool normal_ok(Kind k, const Shapes& s, const RaycastResult& h, const Ref& r, double M, double dlen, bool& in_band) {
  in_band = false;
  const double len = norm(d3(h.normal));
  if (!(std::abs(len - 1) <= 1e-6)) return false;
  if (k == kSphere) return s.sphere.radius == 0 || dot(d3(h.normal), r.n) > 0.5 || (in_band = r.cosine < 0.05);
  if (k == kPlane) {
    if (dot(d3(h.normal), r.n) > 0.999) return true;
    return in_band = r.cosine <= 16 * kEps;
  }
  double sign = 0;
  const int a = box_axis_of(k, s, h.normal, sign);
  if (a < 0) return false;
  if (a == r.axis && dot(d3(h.normal), r.n) > 0.999) return true;
  // A tie: the float's face enters (or leaves) its slab at the same t within the band, and
  // its sign is that of entering (or leaving) through it.
  const double tol = kBandUlps * kEps * M;
  const double d = r.slab_d[a];
  if (d == 0) return false;
  const double tol_t = tol / std::abs(d) + tol / (std::max(r.cosine, 1e-30) * dlen);
  const bool as_entry = std::abs(r.slab_near[a] - r.t) <= tol_t && sign == -std::copysign(1.0, d);
  const bool as_exit = std::abs(r.slab_far[a] - r.t) <= tol_t && sign == std::copysign(1.0, d);
  return in_band = as_entry || as_exit;
}

void judge_ray(Kind k, const Shapes& s, const RayCase& rc, Tally& tally) {
  const RaycastResult h = cast(k, s, rc);
  const Ref r0 = ref_of(k, s, rc);
  const double dlen = norm(d3(rc.ray.direction));
  const double M = scale_of(k, s, rc.ray);
  ++tally.cases;
  tally.hits += h.hit, tally.ref_hits += r0.hit;
  if (!h.hit) {
    EXPECT_EQ(h.t, 0.0f);
    EXPECT_EQ(h.normal, vec3{});
  }
  auto fn = [&](const Perturb& p) { return ref_of(k, s, rc, p); };
  if (h.hit != r0.hit) {
    const Judgement j = explain(h.hit, h.t, dlen, M, fn);
    (j.explained ? tally.disagree_band : tally.disagree_outside)++;
    if (!j.explained && tally.disagree_outside <= 5)
      ADD_FAILURE() << kKindName[k] << ": hit " << h.hit << " t " << h.t << " reference " << r0.hit << " t " << r0.t
                    << " origin " << rc.ray.origin.x << "," << rc.ray.origin.y << "," << rc.ray.origin.z << " d "
                    << rc.ray.direction.x << "," << rc.ray.direction.y << "," << rc.ray.direction.z << " tmin "
                    << rc.tmin << " tmax " << rc.tmax << dump(s, rc);
    return;
  }
  if (!h.hit) return;
  // Agreed hit: t against the reference.
  const double dt = std::abs(double(h.t) - r0.t) * dlen / M;
  const bool well = well_conditioned(r0, dlen, M, fn);
  Ref used = r0;
  if (dt > 8 * kEps * (1 + std::abs(r0.t) * dlen / M)) {
    const Judgement j = explain(true, h.t, dlen, M, fn);
    (j.explained ? tally.t_band : tally.t_outside)++;
    if (!j.explained) {
      if (tally.t_outside <= 5)
        ADD_FAILURE() << kKindName[k] << ": t " << h.t << " reference " << r0.t << " cos " << r0.cosine << dump(s, rc);
      return;
    }
    used = j.ref;
  }
  if (well) {
    ++tally.well, tally.max_dt_well = std::max(tally.max_dt_well, dt);
  } else if (used.entering != r0.entering) {
    ++tally.branch;  // the origin within the band of the surface: entry at ~0 against the exit
  } else {
    ++tally.graze, tally.max_dt_graze = std::max(tally.max_dt_graze, dt);
    tally.max_dn_graze = std::max(tally.max_dn_graze, dt * r0.cosine);
  }
  bool band = false;
  const bool ok = normal_ok(k, s, h, used, M, dlen, band);
  if (!ok) {
    ++tally.normal_outside;
    if (tally.normal_outside <= 5)
      ADD_FAILURE() << kKindName[k] << ": normal " << h.normal.x << "," << h.normal.y << "," << h.normal.z
                    << " reference " << used.n.x << "," << used.n.y << "," << used.n.z << " t " << h.t << dump(s, rc);
  } else if (band) {
    ++tally.normal_band;
  }
  if (well && k == kSphere && s.sphere.radius > 0)
    tally.max_dn_well = std::max(tally.max_dn_well, norm(d3(h.normal) - used.n) * s.sphere.radius / M);
  if (well && k != kSphere) tally.max_dn_well = std::max(tally.max_dn_well, norm(d3(h.normal) - used.n));
}

// Origin exactly on a slab plane with d = 0 along that axis (the robust-slab NaN case).
bool on_face_with_zero_d(Kind k, const Shapes& s, const Ray& r) {
  if (k != kAabb && k != kObb) return false;
  for (int i = 0; i < 3; ++i) {
    float oc, e, d;
    if (k == kAabb) {
      oc = s.aabb.center[i] - r.origin[i], e = s.aabb.half_extents[i], d = r.direction[i];
    } else {
      const vec3 u{s.obb.orientation.m[i][0], s.obb.orientation.m[i][1], s.obb.orientation.m[i][2]};
      const vec3 v = s.obb.center - r.origin;
      oc = (v.x * u.x + v.y * u.y) + v.z * u.z, e = s.obb.half_extents[i];
      d = (r.direction.x * u.x + r.direction.y * u.y) + r.direction.z * u.z;
    }
    if (d == 0 && (oc - e == 0 || oc + e == 0)) return true;
  }
  return false;
}

void run_random_rays(Kind k, uint64_t seed) {
  SplitMix64 g(seed);
  Tally tally;
  for (int i = 0; i < kRandomCases; ++i) {
    const Shapes s = random_shapes(g);
    const RayCase rc = random_ray(k, s, g);
    tally.on_face_zero_d += on_face_with_zero_d(k, s, rc.ray);
    judge_ray(k, s, rc, tally);
  }
  tally.print((std::string("raycast ") + kKindName[k] + ":").c_str());
  EXPECT_EQ(tally.cases, std::size_t(kRandomCases));
  EXPECT_GT(tally.hits, tally.cases / 4) << "the generator should aim most rays at the shape";
  EXPECT_EQ(tally.disagree_outside, 0u);
  EXPECT_EQ(tally.t_outside, 0u);
  EXPECT_EQ(tally.normal_outside, 0u);
  EXPECT_GT(tally.well, tally.cases / 10);
  EXPECT_LT(tally.max_dt_well, 2e-6);  // about 32 ulp of the scale
  // Across the surface a grazing hit is as good as any (for OBBs and planes a turn of the
  // ray by an ulp moves a nearly parallel hit far along the surface: printed, not bounded).
  if (k == kSphere || k == kAabb) {
    EXPECT_LT(tally.max_dn_graze, kBandUlps * kEps);
  }
  if (k == kSphere) {
    EXPECT_LT(tally.max_dt_graze, 4 * std::sqrt(kEps));  // the sqrt(eps) conditioning limit
    EXPECT_LT(tally.max_dn_well, 1e-5);
  } else {
    EXPECT_EQ(tally.max_dn_well, 0.0);  // boxes and planes: exactly the face's axis
  }
  if (k == kAabb || k == kObb) {
    EXPECT_GT(tally.on_face_zero_d, 100u);
  }
}

// ---------------------------------------------------------------- hard cases with exact answers

struct Expect {
  bool hit;
  float t;
  vec3 n;
};

void expect_cast(const RaycastResult& h, const Expect& e, const char* what, float tol = 0) {
  EXPECT_EQ(h.hit, e.hit) << what;
  if (!e.hit) {
    EXPECT_EQ(h.t, 0.0f) << what;
    return;
  }
  EXPECT_NEAR(h.t, e.t, tol) << what;
  EXPECT_FALSE(std::signbit(h.t)) << what << ": a hit at t = -0 reads +0";
  EXPECT_NEAR(h.normal.x, e.n.x, tol + 1e-7f) << what;
  EXPECT_NEAR(h.normal.y, e.n.y, tol + 1e-7f) << what;
  EXPECT_NEAR(h.normal.z, e.n.z, tol + 1e-7f) << what;
}

TEST(RaycastSphere, HardCases) {
  const Sphere unit_sphere{{0, 0, 0}, 1};
  struct C {
    const char* what;
    Sphere s;
    Ray r;
    float tmin, tmax;
    Expect e;
  } cases[] = {
      {"head on", unit_sphere, {{-3, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"from the centre: the exit", unit_sphere, {{0, 0, 0}, {0, 1, 0}}, 0, kInf, {true, 1, {0, 1, 0}}},
      {"inside, off centre", unit_sphere, {{0.5f, 0, 0}, {-1, 0, 0}}, 0, kInf, {true, 1.5f, {-1, 0, 0}}},
      {"on the surface, leaving", unit_sphere, {{1, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 0, {1, 0, 0}}},
      {"on the surface, entering", unit_sphere, {{1, 0, 0}, {-1, 0, 0}}, 0, kInf, {true, 0, {1, 0, 0}}},
      {"tangent", unit_sphere, {{-3, 1, 0}, {1, 0, 0}}, 0, kInf, {true, 3, {0, 1, 0}}},
      {"just misses", unit_sphere, {{-3, 1.0001f, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"unnormalised d", unit_sphere, {{-3, 0, 0}, {2, 0, 0}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"tmin past the entry", unit_sphere, {{-3, 0, 0}, {1, 0, 0}}, 2.5f, kInf, {true, 4, {1, 0, 0}}},
      {"tmax before the entry", unit_sphere, {{-3, 0, 0}, {1, 0, 0}}, 0, 1.5f, {false, 0, {}}},
      {"tmax at the entry", unit_sphere, {{-3, 0, 0}, {1, 0, 0}}, 0, 2, {true, 2, {-1, 0, 0}}},
      {"zero direction", unit_sphere, {{0, 0, 0}, {0, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"subnormal |d|^2", unit_sphere, {{-3, 0, 0}, {1e-25f, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"overflowing |d|^2", unit_sphere, {{-3, 0, 0}, {1e20f, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"pointing away", unit_sphere, {{0, 3, 0}, {0, 1, 0}}, 0, kInf, {false, 0, {}}},
      {"radius 0: a point, dead on", {{5, 0, 0}, 0}, {{3, 0, 0}, {2, 0, 0}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"radius 0, from the point", {{5, 0, 0}, 0}, {{5, 0, 0}, {0, 0, -4}}, 0, kInf, {true, 0, {0, 0, 1}}},
      {"tiny sphere, normal still unit", {{0, 0, 0}, 1e-20f}, {{0, -1e-19f, 0}, {0, 1, 0}}, 0, kInf,
       {true, 0.9e-19f, {0, -1, 0}}},
      {"far from the origin", {{1e6f, 50, 0}, 2}, {{1e6f - 10, 50, 0}, {1, 0, 0}}, 0, kInf, {true, 8, {-1, 0, 0}}},
  };
  for (const C& c : cases) expect_cast(raycast(c.s, c.r, c.tmin, c.tmax), c.e, c.what, 1e-6f * std::max(1.0f, c.e.t));
  // The default range is [0, +inf), and the point is o + t d.
  const RaycastResult h = raycast(unit_sphere, Ray{{-3, 0.5f, 0}, {2, 0, 0}});
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.point, (vec3{-3, 0.5f, 0} + vec3{2, 0, 0} * h.t));
  EXPECT_NEAR(length(h.point), 1.0f, 1e-6f);
}

TEST(RaycastAabb, HardCases) {
  const AABB box{{0, 0, 0}, {1, 1, 1}};
  struct C {
    const char* what;
    AABB b;
    Ray r;
    float tmin, tmax;
    Expect e;
  } cases[] = {
      {"head on", box, {{-3, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"from the centre: the exit", box, {{0, 0, 0}, {0, 0, -1}}, 0, kInf, {true, 1, {0, 0, -1}}},
      {"along the y = 1 face, d.y = +0", box, {{-3, 1, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"along the y = 1 face, d.y = -0", box, {{-3, 1, 0}, {1, -0.0f, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"along the y = -1 face, d.y = +0", box, {{-3, -1, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"along the y = -1 face, d.y = -0", box, {{-3, -1, 0}, {1, -0.0f, -0.0f}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"along an edge line", box, {{-3, 1, -1}, {1, -0.0f, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"along the face, leaving", box, {{0.5f, 1, 0}, {-1, 0, 0}}, 0, kInf, {true, 1.5f, {-1, 0, 0}}},
      {"just off the face plane", box, {{-3, 1.0000001f, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"on a face, leaving", box, {{1, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 0, {1, 0, 0}}},
      {"on a face, entering", box, {{1, 0, 0}, {-1, 0, 0}}, 0, kInf, {true, 0, {1, 0, 0}}},
      {"on a face, entering, d.y = -0", box, {{1, 0.5f, 0}, {-1, -0.0f, 0}}, 0, kInf, {true, 0, {1, 0, 0}}},
      {"corner: x wins the tie", box, {{-2, -2, -2}, {1, 1, 1}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"edge: x wins the tie", box, {{-2, -2, 0}, {1, 1, 0}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"edge y-z: y wins the tie", box, {{0, 3, 3}, {0, -1, -1}}, 0, kInf, {true, 2, {0, 1, 0}}},
      {"corner from inside: x wins the exit tie", box, {{0, 0, 0}, {-1, 1, -1}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"a point box", {{0, 0, 0}, {0, 0, 0}}, {{-1, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 1, {-1, 0, 0}}},
      {"a point box, missed", {{0, 0, 0}, {0, 0, 0}}, {{-1, 1e-30f, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"a flat box, in its plane", {{0, 0, 0}, {1, 1, 0}}, {{-3, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}},
      {"a flat box, through it", {{0, 0, 0}, {1, 1, 0}}, {{0, 0, -3}, {0, 0, 1}}, 0, kInf, {true, 3, {0, 0, -1}}},
      // A plate of zero thickness is entered and left at the same t: the entry face counts.
      {"a flat box, from inside it", {{0, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {0, 0, 1}}, 0, kInf, {true, 0, {0, 0, -1}}},
      {"tmin past the entry", box, {{-3, 0, 0}, {1, 0, 0}}, 2.5f, kInf, {true, 4, {1, 0, 0}}},
      {"tmax before the entry", box, {{-3, 0, 0}, {1, 0, 0}}, 0, 1.5f, {false, 0, {}}},
      {"tmax at the entry", box, {{-3, 0, 0}, {1, 0, 0}}, 0, 2, {true, 2, {-1, 0, 0}}},
      {"unnormalised d", box, {{-3, 0, 0}, {4, 0, 0}}, 0, kInf, {true, 0.5f, {-1, 0, 0}}},
      {"zero direction, inside", box, {{0, 0, 0}, {0, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"subnormal |d|^2", box, {{-3, 0, 0}, {1e-25f, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"overflowing |d|^2", box, {{-3, 0, 0}, {1e20f, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"parallel, outside the slab", box, {{-3, 2, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"parallel, outside the slab, -0", box, {{-3, 2, 0}, {1, -0.0f, 0}}, 0, kInf, {false, 0, {}}},
      {"pointing away", box, {{-3, 0, 0}, {-1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"far from the origin", {{1e6f, 0, 0}, {1, 1, 1}}, {{1e6f - 10, 0.5f, 0.5f}, {1, 0, 0}}, 0, kInf,
       {true, 9, {-1, 0, 0}}},
      {"a small box far away, on its face plane", {{1e4f, 0, 0}, {0.25f, 0.25f, 0.25f}},
       {{1e4f - 1, 0.25f, 0}, {1, 0, 0}}, 0, kInf, {true, 0.75f, {-1, 0, 0}}},
  };
  for (const C& c : cases) expect_cast(raycast(c.b, c.r, c.tmin, c.tmax), c.e, c.what);
}

TEST(RaycastObb, HardCases) {
  const float s = 0.70710677f;
  OBB rot;  // 45 degrees about z
  rot.orientation = mat3{{{s, s, 0}, {-s, s, 0}, {0, 0, 1}}};
  OBB perm;  // a permutation: local x is world z, local y is world x, local z is world y
  perm.orientation = mat3{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};
  perm.half_extents = {1, 2, 3};  // extent 1 along z, 2 along x, 3 along y
  struct C {
    const char* what;
    OBB b;
    Ray r;
    float tmin, tmax;
    Expect e;
    float tol;
  } cases[] = {
      {"identity = AABB", OBB{}, {{-3, 0, 0}, {1, 0, 0}}, 0, kInf, {true, 2, {-1, 0, 0}}, 0},
      {"rotated: through the top face", rot, {{0, 0, 5}, {0, 0, -1}}, 0, kInf, {true, 4, {0, 0, 1}}, 0},
      {"rotated: along an axis", rot, {{-5 * s, -5 * s, 0}, {s, s, 0}}, 0, kInf, {true, 4, {-s, -s, 0}}, 2e-6f},
      {"rotated: from inside", rot, {{0, 0, 0}, {-s, s, 0}}, 0, kInf, {true, 1, {-s, s, 0}}, 2e-6f},
      {"rotated: misses the corner", rot, {{-5, 1.5f, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}, 0},
      {"permuted: face along world y", perm, {{0, -5, 0}, {0, 1, 0}}, 0, kInf, {true, 2, {0, -1, 0}}, 0},
      {"permuted: on a face plane, d = 0 across it", perm, {{-5, 3, 0.5f}, {1, 0, 0}}, 0, kInf,
       {true, 3, {-1, 0, 0}}, 0},
      {"permuted: on a face plane, d = -0 across it", perm, {{-5, -3, 1}, {1, -0.0f, -0.0f}}, 0, kInf,
       {true, 3, {-1, 0, 0}}, 0},
      {"permuted: just off the face", perm, {{-5, 3.0000002f, 0.5f}, {1, 0, 0}}, 0, kInf, {false, 0, {}}, 0},
      {"permuted: corner tie, local x (world z) wins", perm, {{-3, -4, -2}, {1, 1, 1}}, 0, kInf,
       {true, 1, {0, 0, -1}}, 0},
      {"degenerate: a flat OBB", OBB{{0, 0, 0}, {1, 1, 0}, rot.orientation}, {{0, 0, -2}, {0, 0, 1}}, 0, kInf,
       {true, 2, {0, 0, -1}}, 0},
      {"zero direction", rot, {{0, 0, 0}, {0, 0, 0}}, 0, kInf, {false, 0, {}}, 0},
      {"far from the origin", OBB{{-1e5f, 0, 0}, {1, 1, 1}, rot.orientation}, {{-1e5f, 0, 10}, {0, 0, -2}}, 0,
       kInf, {true, 4.5f, {0, 0, 1}}, 0},
  };
  for (const C& c : cases) expect_cast(raycast(c.b, c.r, c.tmin, c.tmax), c.e, c.what, c.tol);
}

TEST(RaycastPlane, HardCases) {
  const Plane p{{0, 1, 0}, 2};
  struct C {
    const char* what;
    Plane pl;
    Ray r;
    float tmin, tmax;
    Expect e;
  } cases[] = {
      {"from the front", p, {{0, 5, 0}, {0, -1, 0}}, 0, kInf, {true, 3, {0, 1, 0}}},
      {"from the back: the normal faces the origin", p, {{0, -1, 0}, {0, 1, 0}}, 0, kInf, {true, 3, {0, -1, 0}}},
      {"oblique, unnormalised", p, {{1, 6, 1}, {3, -2, 0}}, 0, kInf, {true, 2, {0, 1, 0}}},
      {"in the plane, moving along it", p, {{0, 2, 0}, {1, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"parallel, off the plane", p, {{0, 3, 0}, {1, 0, -1}}, 0, kInf, {false, 0, {}}},
      {"parallel with -0", p, {{0, 3, 0}, {1, -0.0f, 0}}, 0, kInf, {false, 0, {}}},
      {"starting in the plane, leaving +n", p, {{0, 2, 0}, {0, 1, 0}}, 0, kInf, {true, 0, {0, -1, 0}}},
      {"starting in the plane, leaving -n", p, {{0, 2, 0}, {1, -1, 0}}, 0, kInf, {true, 0, {0, 1, 0}}},
      {"pointing away", p, {{0, 5, 0}, {0, 1, 0}}, 0, kInf, {false, 0, {}}},
      {"tmax before", p, {{0, 5, 0}, {0, -1, 0}}, 0, 2.5f, {false, 0, {}}},
      {"tmin after", p, {{0, 5, 0}, {0, -1, 0}}, 3.5f, kInf, {false, 0, {}}},
      {"zero direction", p, {{0, 2, 0}, {0, 0, 0}}, 0, kInf, {false, 0, {}}},
      {"far from the origin", {{1, 0, 0}, 1e6f}, {{1e6f - 4, 1e6f, 0}, {0.5f, 0, 0}}, 0, kInf, {true, 8, {-1, 0, 0}}},
  };
  for (const C& c : cases) expect_cast(raycast(c.pl, c.r, c.tmin, c.tmax), c.e, c.what);
}

TEST(Linetest, HardCases) {
  const Sphere sph{{0, 0, 0}, 1};
  const AABB box{{0, 0, 0}, {1, 1, 1}};
  OBB obb;
  const float s = 0.70710677f;
  obb.orientation = mat3{{{s, s, 0}, {-s, s, 0}, {0, 0, 1}}};
  OBB perm;
  perm.orientation = mat3{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};
  const Plane pl{{0, 1, 0}, 2};
  // Sphere.
  EXPECT_TRUE(linetest(sph, {{-3, 0, 0}, {3, 0, 0}}));          // through
  EXPECT_TRUE(linetest(sph, {{-0.5f, 0, 0}, {0.5f, 0, 0}}));    // inside
  EXPECT_TRUE(linetest(sph, {{-3, 0, 0}, {-1, 0, 0}}));         // ends on the surface
  EXPECT_FALSE(linetest(sph, {{-3, 0, 0}, {-1.0001f, 0, 0}}));  // ends just short
  EXPECT_TRUE(linetest(sph, {{-3, 1, 0}, {3, 1, 0}}));          // tangent
  EXPECT_FALSE(linetest(sph, {{-3, 1.0001f, 0}, {3, 1.0001f, 0}}));
  EXPECT_TRUE(linetest(sph, {{0.5f, 0, 0}, {0.5f, 0, 0}}));     // zero length, inside
  EXPECT_TRUE(linetest(sph, {{0, 1, 0}, {0, 1, 0}}));           // zero length, on the surface
  EXPECT_FALSE(linetest(sph, {{0, 1.0001f, 0}, {0, 1.0001f, 0}}));
  EXPECT_TRUE(linetest(Sphere{{2, 0, 0}, 0}, {{0, 0, 0}, {4, 0, 0}}));  // a point sphere on the segment
  // AABB.
  EXPECT_TRUE(linetest(box, {{-3, 0, 0}, {3, 0, 0}}));
  EXPECT_TRUE(linetest(box, {{-0.5f, 0, 0}, {0.5f, 0.5f, 0}}));  // inside
  EXPECT_TRUE(linetest(box, {{-3, 0, 0}, {-1, 0, 0}}));          // ends on a face
  EXPECT_FALSE(linetest(box, {{-3, 0, 0}, {-1.0001f, 0, 0}}));
  EXPECT_TRUE(linetest(box, {{-3, 1, 0}, {3, 1, 0}}));           // lies in a face plane (d.y = 0, NaN slab)
  EXPECT_TRUE(linetest(box, {{3, 1, 1}, {-3, 1, 1}}));           // along an edge, reversed
  EXPECT_FALSE(linetest(box, {{-3, 1.0001f, 0}, {3, 1.0001f, 0}}));
  EXPECT_FALSE(linetest(box, {{2, 1, 0}, {3, 1, 0}}));           // in a face plane, beside the face
  EXPECT_TRUE(linetest(box, {{0, 0, 0}, {0, 0, 0}}));            // zero length, inside
  EXPECT_TRUE(linetest(box, {{1, 1, 1}, {1, 1, 1}}));            // zero length, on a corner (NaN in every slab)
  EXPECT_FALSE(linetest(box, {{1, 1, 1.5f}, {1, 1, 1.5f}}));
  EXPECT_TRUE(linetest(box, {{-2, -2, -2}, {-1, -1, -1}}));      // ends on a corner
  EXPECT_TRUE(linetest(AABB{{0, 0, 0}, {0, 0, 0}}, {{-1, 0, 0}, {1, 0, 0}}));  // a point box
  // OBB.
  EXPECT_TRUE(linetest(obb, {{-5, 0, 0}, {5, 0, 0}}));
  EXPECT_FALSE(linetest(obb, {{-5, 1.5f, 0}, {5, 1.5f, 0}}));    // past the rotated corner
  EXPECT_TRUE(linetest(obb, {{-5, 1.4f, 0}, {5, 1.4f, 0}}));
  EXPECT_TRUE(linetest(obb, {{0.1f, 0.1f, 0.1f}, {0.1f, 0.1f, 0.1f}}));  // zero length, inside
  EXPECT_TRUE(linetest(perm, {{-5, 1, 0.5f}, {5, 1, 0.5f}}));   // in a face plane (world y = 1), d = 0 across
  EXPECT_FALSE(linetest(perm, {{-5, 1, 1.5f}, {5, 1, 1.5f}}));
  // Plane.
  EXPECT_TRUE(linetest(pl, {{0, 0, 0}, {0, 5, 0}}));
  EXPECT_TRUE(linetest(pl, {{0, 0, 0}, {0, 2, 0}}));  // ends on it
  EXPECT_FALSE(linetest(pl, {{0, 0, 0}, {0, 1.9999f, 0}}));
  EXPECT_FALSE(linetest(pl, {{0, 3, 0}, {5, 4, 0}}));
  EXPECT_TRUE(linetest(pl, {{-1, 2, 0}, {5, 2, 3}}));  // lies in it
  EXPECT_TRUE(linetest(pl, {{1, 2, 1}, {1, 2, 1}}));   // zero length, in it
  EXPECT_FALSE(linetest(pl, {{1, 3, 1}, {1, 3, 1}}));
}

TEST(Raycast, NanInputsDoNotCrash) {
  const float nan = NAN;
  const Ray bad_rays[] = {{{nan, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {nan, 0, 0}}, {{0, 0, -5}, {0, 0, kInf}}};
  for (const Ray& r : bad_rays) {
    // Any defined answer: a miss is all zeros, a hit has a unit-or-NaN normal; nothing traps.
    const RaycastResult h[] = {raycast(Sphere{}, r), raycast(AABB{}, r), raycast(OBB{}, r), raycast(Plane{}, r)};
    for (const RaycastResult& x : h) {
      if (!x.hit) {
        EXPECT_EQ(x.t, 0.0f);
      }
    }
    (void)linetest(Sphere{}, Line{r.origin, r.direction});
    (void)linetest(AABB{}, Line{r.origin, r.direction});
    (void)linetest(OBB{}, Line{r.origin, r.direction});
    (void)linetest(Plane{}, Line{r.origin, r.direction});
  }
  EXPECT_FALSE(raycast(Sphere{{nan, 0, 0}, 1}, Ray{{-3, 0, 0}, {1, 0, 0}}).hit);
  EXPECT_FALSE(raycast(AABB{{0, 0, 0}, {nan, 1, 1}}, Ray{{-3, 0, 0}, {1, 0, 0}}).hit);
}

// ---------------------------------------------------------------- random against binary64

TEST(RaycastSphere, RandomAgainstBinary64) { run_random_rays(kSphere, 101); }
TEST(RaycastAabb, RandomAgainstBinary64) { run_random_rays(kAabb, 102); }
TEST(RaycastObb, RandomAgainstBinary64) { run_random_rays(kObb, 103); }
TEST(RaycastPlane, RandomAgainstBinary64) { run_random_rays(kPlane, 104); }

Line segment_of(const RayCase& rc) { return {rc.ray.origin, rc.ray.origin + rc.ray.direction}; }

bool float_linetest(Kind k, const Shapes& s, const Line& l) {
  switch (k) {
    case kSphere: return linetest(s.sphere, l);
    case kAabb: return linetest(s.aabb, l);
    case kObb: return linetest(s.obb, l);
    default: return linetest(s.plane, l);
  }
}
bool ref_linetest(Kind k, const Shapes& s, const Line& l) {
  switch (k) {
    case kSphere: return ref_line_sphere(s.sphere, l);
    case kAabb: return ref_line_aabb(s.aabb, l);
    case kObb: return ref_line_obb(s.obb, l);
    default: return ref_line_plane(s.plane, l);
  }
}
double ref_depth(Kind k, const Shapes& s, const Line& l) {
  switch (k) {
    case kSphere: return depth_sphere(s.sphere, l);
    case kAabb: return depth_aabb(s.aabb, l);
    case kObb: return depth_obb(s.obb, l);
    default: return depth_plane(s.plane, l);
  }
}
double line_scale(Kind k, const Shapes& s, const Line& l) {
  if (k == kPlane) return (norm(d3(l.start)) + norm(d3(l.end))) + std::abs(double(s.plane.distance));
  const D3 c = shape_center(k, s);
  return std::max(norm(d3(l.start) - c), norm(d3(l.end) - c)) + shape_size(k, s);
}

// Random segments: the random rays' o -> o + d (|d| from 1e-3 to 1e3 sizes), some of zero
// length, some ending on the surface.
Line random_segment(Kind k, const Shapes& s, SplitMix64& g) {
  const RayCase rc = random_ray(k, s, g);
  Line l = segment_of(rc);
  const int how = pick(g, 10);
  if (how == 0) l.end = l.start;                                          // zero length
  if (how == 1) l.end = f3(sample_surface(k, s, g).q);                    // ends on the surface
  if (how == 2) l.start = l.end = f3(sample_surface(k, s, g).q);          // a point on the surface
  if (how == 3) l.end = f3(d3(l.start) + (d3(rc.ray.direction) * 1e-6));  // very short
  return l;
}

void run_random_linetests(Kind k, uint64_t seed) {
  SplitMix64 g(seed);
  std::size_t touches = 0, ref_touches = 0, band = 0, outside = 0, rev_band = 0, rev_outside = 0, zero = 0;
  std::size_t cast_implies = 0, cast_band = 0, cast_outside = 0;
  double max_depth_disagree = 0;  // over disagreements, in ulps of M
  for (int i = 0; i < kRandomCases; ++i) {
    const Shapes s = random_shapes(g);
    const Line l = random_segment(k, s, g);
    zero += l.start == l.end;
    const double tol = kLineBandUlps * kEps * line_scale(k, s, l);
    const bool got = float_linetest(k, s, l), want = ref_linetest(k, s, l);
    const double depth = ref_depth(k, s, l);
    touches += got, ref_touches += want;
    const bool borderline = std::abs(depth) <= tol;
    max_depth_disagree = got != want ? std::max(max_depth_disagree, std::abs(depth) / (kEps * line_scale(k, s, l))) : max_depth_disagree;
    if (got != want) {
      (borderline ? band : outside)++;
      if (!borderline && outside <= 5)
        ADD_FAILURE() << kKindName[k] << " linetest " << got << " reference " << want << " start " << l.start.x << ","
                      << l.start.y << "," << l.start.z << " end " << l.end.x << "," << l.end.y << "," << l.end.z
                      << " depth " << depth / (kEps * line_scale(k, s, l)) << " ulps of M"
                      << dump(s, {ray_from_points(l.start, l.end), 0.0f, 1.0f});
    }
    // Property: the reversed segment touches iff this one does.
    if (float_linetest(k, s, {l.end, l.start}) != got) (borderline ? rev_band : rev_outside)++;
    // Property: a raycast hit with t in [0, 1] along the segment is a linetest hit.
    const RaycastResult h = cast(k, s, {ray_from_points(l.start, l.end), 0.0f, 1.0f});
    if (h.hit) {
      ++cast_implies;
      if (!got) (borderline ? cast_band : cast_outside)++;
    }
  }
  std::printf("  linetest %-8s %d cases (%zu zero-length), %zu touch (reference %zu); disagreements: %zu inside the "
              "band, %zu outside (the largest |depth| of a disagreement: %.3g ulps of M)\n"
              "  %-17s reversed segment differs: %zu inside the band, %zu outside; raycast hit in [0, 1] but no "
              "linetest: %zu inside, %zu outside (of %zu)\n",
              kKindName[k], kRandomCases, zero, touches, ref_touches, band, outside, max_depth_disagree, "", rev_band, rev_outside,
              cast_band, cast_outside, cast_implies);
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(rev_outside, 0u);
  EXPECT_EQ(cast_outside, 0u);
  EXPECT_GT(touches, std::size_t(kRandomCases) / 4);
  EXPECT_LT(touches, std::size_t(kRandomCases) * 95 / 100);
  EXPECT_GT(zero, std::size_t(kRandomCases) / 20);
}

TEST(LinetestSphere, RandomAgainstBinary64) { run_random_linetests(kSphere, 201); }
TEST(LinetestAabb, RandomAgainstBinary64) { run_random_linetests(kAabb, 202); }
TEST(LinetestObb, RandomAgainstBinary64) { run_random_linetests(kObb, 203); }
TEST(LinetestPlane, RandomAgainstBinary64) { run_random_linetests(kPlane, 204); }

// ---------------------------------------------------------------- properties

// Scaling d by 2^k scales every quotient of the computation by an exact power of two, so
// t scales by 2^-k and the normal stays, bit for bit (away from overflow and underflow).
TEST(Raycast, ScalingTheDirectionByTwoScalesTExactly) {
  SplitMix64 g(301);
  std::size_t hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Kind k = Kind(i % 4);
    const Shapes s = random_shapes(g);
    RayCase rc = random_ray(k, s, g);
    rc.tmin = 0, rc.tmax = kInf;
    const RaycastResult h = cast(k, s, rc);
    hits += h.hit;
    for (int e : {-3, -1, 1, 4}) {
      RayCase sc = rc;
      sc.ray.direction = rc.ray.direction * std::ldexp(1.0f, e);
      const RaycastResult hs = cast(k, s, sc);
      ASSERT_EQ(hs.hit, h.hit) << kKindName[k] << " 2^" << e;
      if (!h.hit) continue;
      ASSERT_EQ(hs.t, std::ldexp(h.t, -e)) << kKindName[k] << " 2^" << e;
      ASSERT_EQ(hs.normal, h.normal) << kKindName[k] << " 2^" << e;
    }
  }
  EXPECT_GT(hits, 5000u);
}

// Containment implies a hit: a ray from deep inside a solid (farther than the band from
// its surface) always hits, where it leaves (the normal along d), and every segment from
// inside touches.
TEST(Raycast, FromInsideAlwaysHitsWhereItLeaves) {
  SplitMix64 g(305);
  std::size_t inside = 0;
  for (int i = 0; i < 30000; ++i) {
    const Kind k = Kind(i % 3);
    const Shapes s = random_shapes(g);
    const RayCase rc{{f3(sample_inside(k, s, g)), f3(rand_unit(g) * std::exp2(pick(g, 7) - 3))}, 0.0f, kInf};
    const Line seg = segment_of({{rc.ray.origin, f3(rand_unit(g) * uni(g, 0, 3 * s.S))}, 0.0f, kInf});
    // Depth of the origin in the shape, in binary64.
    const double depth = ref_depth(k, s, {rc.ray.origin, rc.ray.origin});
    if (!(depth > 1e-4 * s.S)) continue;
    ++inside;
    const RaycastResult h = cast(k, s, rc);
    ASSERT_TRUE(h.hit) << kKindName[k] << dump(s, rc);
    EXPECT_GT(h.t, 0.0f) << kKindName[k];
    EXPECT_GT(dot(h.normal, rc.ray.direction), 0.0f) << kKindName[k] << ": the exit's outward normal";
    EXPECT_TRUE(float_linetest(k, s, seg)) << kKindName[k];
  }
  EXPECT_GT(inside, 10000u);
}

// A sphere hit point o + t d lies on the sphere within a few ulps of M, grazing hits
// included (their t moves along the surface), and the normal points out.
TEST(RaycastSphere, HitPointsLieOnTheSurface) {
  SplitMix64 g(302);
  double worst = 0;
  std::size_t n = 0;
  for (int i = 0; i < 20000; ++i) {
    const Shapes s = random_shapes(g);
    const RayCase rc = random_ray(kSphere, s, g);
    const RaycastResult h = raycast(s.sphere, rc.ray, rc.tmin, rc.tmax);
    if (!h.hit) continue;
    ++n;
    // The point o + t d in binary64 from the float t: its distance to the centre is r
    // within the error of t (grazing hits move t by up to sqrt(eps) r, but along the surface).
    const D3 p = d3(rc.ray.origin) + d3(rc.ray.direction) * double(h.t);
    const double M = scale_of(kSphere, s, rc.ray);
    if (!(M > 0) || s.sphere.radius == 0) continue;
    worst = std::max(worst, std::abs(norm(p - d3(s.sphere.center)) - s.sphere.radius) / M);
    EXPECT_GT(dot(d3(h.normal), p - d3(s.sphere.center)), -1e-3 * M) << "outward";
  }
  std::printf("  sphere hit points: %zu, max | |p - c| - r | / M = %.3g\n", n, worst);
  EXPECT_LT(worst, 1e-6);
}

// The per-pair computation of the ray-sphere kernel gyro had before the lane templates
// (ray_sphere_kernels.cpp, commit 3bbacec), verbatim in scalar form: the golden hashes of
// the determinism scenes were pinned with it.
float legacy_ray_sphere_t(const Ray& ray, const Sphere& sp, float tmin, float tmax) {
  const float ox = ray.origin.x, oy = ray.origin.y, oz = ray.origin.z;
  const float dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  const float dd = (dx * dx + dy * dy) + dz * dz;
  const bool ray_ok = (dd >= FLT_MIN) && (dd <= FLT_MAX);
  const float inv_dd = 1.0f / dd;
  const float ocx = ox - sp.center.x, ocy = oy - sp.center.y, ocz = oz - sp.center.z;
  const float b = -((ocx * dx + ocy * dy) + ocz * dz);
  const float s = b * inv_dd;
  const float fx = ocx + s * dx, fy = ocy + s * dy, fz = ocz + s * dz;
  const float r2 = sp.radius * sp.radius;
  const float h = r2 - ((fx * fx + fy * fy) + fz * fz);
  if (!(h >= 0.0f)) return kInf;
  const float c = ((ocx * ocx + ocy * ocy) + ocz * ocz) - r2;
  const float q = b + std::copysign(std::sqrt(dd * h), b);
  const float t0 = c / q, t1 = q / dd;
  const float tn = t0 < t1 ? t0 : t1, tf = t0 > t1 ? t0 : t1;
  const float t = tn >= tmin ? tn : tf;
  return (ray_ok && t >= tmin && t <= tmax && t < kInf) ? t + 0.0f : kInf;
}

// ray_sphere_t gives the legacy kernel's t bits (so the pinned hashes keep their t and
// primitive words) except where its c/q root is repaired: rays leaving (or grazing) the
// sphere along its surface, where the legacy hit can lie far off the sphere. Every
// repaired answer is inside the band; the legacy answers are counted.
TEST(RaycastSphere, TemplateGivesTheLegacyKernelsBitsExceptItsWildRoots) {
  // The R1S pairs of the determinism scene r1s_2k (its first 500 rays).
  const testing::SphereSet spheres = testing::r1_spheres();
  const testing::RaySet rays = testing::r1_rays(500);
  std::size_t pairs = 0, hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray r{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
    for (std::size_t j = 0; j < spheres.size(); ++j, ++pairs) {
      const Sphere sp{{spheres.cx[j], spheres.cy[j], spheres.cz[j]}, spheres.r[j]};
      const RaycastResult h = raycast(sp, r);
      const float legacy = legacy_ray_sphere_t(r, sp, 0.0f, kInf);
      hits += h.hit;
      ASSERT_EQ(std::bit_cast<uint32_t>(h.hit ? h.t : kInf), std::bit_cast<uint32_t>(legacy)) << i << " " << j;
    }
  }
  // Random rays with every hard case: differences only where the legacy answer is wrong.
  SplitMix64 g(303);
  std::size_t same = 0, repaired = 0, wild = 0, random_hits = 0;
  for (int i = 0; i < kRandomCases; ++i) {
    const Shapes s = random_shapes(g);
    const RayCase rc = random_ray(kSphere, s, g);
    const RaycastResult h = raycast(s.sphere, rc.ray, rc.tmin, rc.tmax);
    const float legacy = legacy_ray_sphere_t(rc.ray, s.sphere, rc.tmin, rc.tmax);
    random_hits += h.hit;
    if (std::bit_cast<uint32_t>(h.hit ? h.t : kInf) == std::bit_cast<uint32_t>(legacy)) {
      ++same;
      continue;
    }
    ++repaired;
    const double dlen = norm(d3(rc.ray.direction)), M = scale_of(kSphere, s, rc.ray);
    auto fn = [&](const Perturb& p) { return ref_sphere(s.sphere, rc.ray, rc.tmin, rc.tmax, p); };
    wild += !explain(legacy < kInf, legacy, dlen, M, fn).explained;
    EXPECT_TRUE(explain(h.hit, h.t, dlen, M, fn).explained) << dump(s, rc);
  }
  std::printf("  R1S: %zu pairs (%zu hits) bit-identical to the legacy kernel; random: %zu identical, %zu "
              "repaired (the legacy answer outside the band in %zu of them; of %d rays, %zu hits)\n",
              pairs, hits, same, repaired, wild, kRandomCases, random_hits);
  EXPECT_GT(hits, 100u);
  EXPECT_GT(wild, 0u) << "the random rays should include rays leaving a sphere along its surface";
  EXPECT_LT(repaired, std::size_t(kRandomCases) / 100);
}

// The batch call (the same templates, per SIMD level) gives the scalar raycast()'s bits:
// t, primitive and normal, for every kind.
ShapeArray one_shape(Kind k, const Shapes& s) {
  switch (k) {
    case kSphere: return shape_array(SpheresView{&s.sphere.center.x, &s.sphere.center.y, &s.sphere.center.z,
                                                 &s.sphere.radius});
    case kAabb: {
      const AABB& b = s.aabb;
      return shape_array(AabbsView{&b.center.x, &b.center.y, &b.center.z, &b.half_extents.x, &b.half_extents.y,
                                   &b.half_extents.z});
    }
    case kObb: {
      const OBB& b = s.obb;
      const auto& m = b.orientation.m;
      return shape_array(ObbsView{&b.center.x, &b.center.y, &b.center.z, &b.half_extents.x, &b.half_extents.y,
                                  &b.half_extents.z, &m[0][0], &m[0][1], &m[0][2], &m[1][0], &m[1][1], &m[1][2],
                                  &m[2][0], &m[2][1], &m[2][2]});
    }
    default: return shape_array(PlanesView{&s.plane.normal.x, &s.plane.normal.y, &s.plane.normal.z, &s.plane.distance});
  }
}

TEST(Raycast, BatchCallGivesTheScalarBits) {
  SplitMix64 g(304);
  constexpr int kShapes = 100, kRaysEach = 67;  // 67: not a multiple of any lane count
  std::size_t hits = 0, levels = 0;
  for (int k = 0; k < 4; ++k) {
    std::vector<Shapes> shapes;
    std::vector<RayCase> rays;
    for (int j = 0; j < kShapes; ++j) {
      shapes.push_back(random_shapes(g));
      for (int i = 0; i < kRaysEach; ++i) rays.push_back(random_ray(Kind(k), shapes.back(), g));
    }
    for (uint32_t v = 1; v <= 5; ++v) {
      const SimdLevel level = SimdLevel(v);
      if (!simd_level_available(level)) continue;
      set_simd_level(level);
      levels += k == 0;
      for (int j = 0; j < kShapes; ++j) {
        std::vector<float> in[8], t(kRaysEach), nx(kRaysEach), ny(kRaysEach), nz(kRaysEach);
        std::vector<int32_t> prim(kRaysEach);
        for (int i = 0; i < kRaysEach; ++i) {
          const RayCase& rc = rays[std::size_t(j) * kRaysEach + i];
          const float x[8] = {rc.ray.origin.x,    rc.ray.origin.y,    rc.ray.origin.z, rc.ray.direction.x,
                              rc.ray.direction.y, rc.ray.direction.z, rc.tmin,         rc.tmax};
          for (int c = 0; c < 8; ++c) in[c].push_back(x[c]);
        }
        const RaysView rv{in[0].data(), in[1].data(), in[2].data(), in[3].data(),
                          in[4].data(), in[5].data(), in[6].data(), in[7].data()};
        HitsOut out;
        out.t = t.data(), out.primitive = prim.data(), out.nx = nx.data(), out.ny = ny.data(), out.nz = nz.data();
        ASSERT_EQ(raycast_closest(rv, kRaysEach, one_shape(Kind(k), shapes[j]), 1, out), Status::ok);
        for (int i = 0; i < kRaysEach; ++i) {
          const RayCase& rc = rays[std::size_t(j) * kRaysEach + i];
          const RaycastResult h = cast(Kind(k), shapes[j], rc);
          ASSERT_EQ(h.hit, prim[i] == 0) << kKindName[k] << " " << simd_level_name(level) << " ray " << i;
          if (!h.hit) continue;
          hits += v == 1;
          ASSERT_EQ(std::bit_cast<uint32_t>(h.t), std::bit_cast<uint32_t>(t[i])) << kKindName[k];
          ASSERT_EQ(h.normal, (vec3{nx[i], ny[i], nz[i]})) << kKindName[k] << " " << simd_level_name(level);
        }
      }
    }
  }
  set_simd_level(SimdLevel::automatic);
  EXPECT_GE(levels, 2u);
  EXPECT_GT(hits, std::size_t(4 * kShapes * kRaysEach) / 4);
}

// ---------------------------------------------------------------- per-level probe

TEST(Raycast, EveryTemplateGivesTheScalarBitsAtEveryLevel) {
  SplitMix64 g(401);
  std::vector<float> in[8];  // ox oy oz dx dy dz tmin tmax
  std::vector<float> sph[4], box[6], obb[15], pl[4];
  auto push_case = [&](const Shapes& s, const RayCase& rc) {
    const float r[8] = {rc.ray.origin.x, rc.ray.origin.y, rc.ray.origin.z, rc.ray.direction.x,
                        rc.ray.direction.y, rc.ray.direction.z, rc.tmin, rc.tmax};
    for (int i = 0; i < 8; ++i) in[i].push_back(r[i]);
    const float a[4] = {s.sphere.center.x, s.sphere.center.y, s.sphere.center.z, s.sphere.radius};
    for (int i = 0; i < 4; ++i) sph[i].push_back(a[i]);
    for (int i = 0; i < 3; ++i) box[i].push_back(s.aabb.center[i]), box[3 + i].push_back(s.aabb.half_extents[i]);
    for (int i = 0; i < 3; ++i) obb[i].push_back(s.obb.center[i]), obb[3 + i].push_back(s.obb.half_extents[i]);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) obb[6 + 3 * k + c].push_back(s.obb.orientation.m[k][c]);
    for (int i = 0; i < 3; ++i) pl[i].push_back(s.plane.normal[i]);
    pl[3].push_back(s.plane.distance);
  };
  // Random cases aimed at each kind in turn (the other shapes are hit now and then).
  for (int i = 0; i < 16000; ++i) {
    const Shapes s = random_shapes(g);
    push_case(s, random_ray(Kind(i % 4), s, g));
  }
  // Special values in every input: +-0, +-inf, NaN, subnormals, huge.
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-30f, 1e-40f, 1e30f, INFINITY, -INFINITY, NAN, 3.0f};
  const std::size_t special_begin = in[0].size();
  for (int i = 0; i < 4000; ++i) {
    Shapes s = random_shapes(g);
    RayCase rc = random_ray(Kind(i % 4), s, g);
    auto sp = [&] { return specials[pick(g, 12)]; };
    for (int m = 0; m < 1 + pick(g, 3); ++m) {
      switch (pick(g, 8)) {
        case 0: rc.ray.origin[pick(g, 3)] = sp(); break;
        case 1: rc.ray.direction[pick(g, 3)] = sp(); break;
        case 2: rc.tmax = std::abs(sp()); break;
        case 3: s.sphere.radius = sp(); break;
        case 4: s.aabb.half_extents[pick(g, 3)] = sp(); break;
        case 5: s.obb.orientation.m[pick(g, 3)][pick(g, 3)] = sp(); break;
        case 6: s.plane.normal[pick(g, 3)] = sp(); break;
        default: s.aabb.center[pick(g, 3)] = sp(), s.sphere.center[pick(g, 3)] = sp(); break;
      }
    }
    push_case(s, rc);
  }
  const std::size_t n = in[0].size() - 3;  // not a multiple of any lane count
  RaycastProbeArgs args{in[0].data(), in[1].data(), in[2].data(), in[3].data(), in[4].data(), in[5].data(),
                        in[6].data(), in[7].data(),
                        {sph[0].data(), sph[1].data(), sph[2].data(), sph[3].data()},
                        {box[0].data(), box[1].data(), box[2].data(), box[3].data(), box[4].data(), box[5].data()},
                        {obb[0].data(), obb[1].data(), obb[2].data(), obb[3].data(), obb[4].data(), obb[5].data(),
                         obb[6].data(), obb[7].data(), obb[8].data(), obb[9].data(), obb[10].data(), obb[11].data(),
                         obb[12].data(), obb[13].data(), obb[14].data()},
                        {pl[0].data(), pl[1].data(), pl[2].data(), pl[3].data()},
                        {}};
  auto run = [&](SimdLevel level) {
    std::vector<std::vector<float>> out(kRaycastProbeOutputs, std::vector<float>(n, -7.0f));
    RaycastProbeArgs a = args;
    for (int k = 0; k < kRaycastProbeOutputs; ++k) a.out[k] = out[k].data();
    detail::raycast_probe_for(level)(a, 0, n);
    return out;
  };
  const auto ref = run(SimdLevel::scalar);
  // The scalar probe is the public API: spot-check it against raycast() on the random part.
  std::size_t hits[4] = {};
  for (std::size_t i = 0; i < special_begin; ++i) {
    const Ray r{{in[0][i], in[1][i], in[2][i]}, {in[3][i], in[4][i], in[5][i]}};
    const RaycastResult h = raycast(Sphere{{sph[0][i], sph[1][i], sph[2][i]}, sph[3][i]}, r, in[6][i], in[7][i]);
    ASSERT_EQ(h.hit ? h.t : kInf, ref[4 * kRaycastProbeSphere][i]);
    for (int k = 0; k < 4; ++k) hits[k] += ref[4 * k][i] < kInf;
  }
  std::printf("  probe: %zu cases (%zu with special values); hits sphere %zu, AABB %zu, OBB %zu, plane %zu\n", n,
              n - special_begin, hits[0], hits[1], hits[2], hits[3]);
  for (int k = 0; k < 4; ++k) EXPECT_GT(hits[k], special_begin / 16) << kKindName[k];
  int levels = 0;
  for (uint32_t v = 2; v <= 5; ++v) {
    const SimdLevel level = SimdLevel(v);
    if (!simd_level_available(level)) continue;
    ++levels;
    const auto got = run(level);
    for (int k = 0; k < kRaycastProbeOutputs; ++k)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(detail::canonical_float_bits(got[k][i]), detail::canonical_float_bits(ref[k][i]))
            << "output " << k << " at " << simd_level_name(level) << " case " << i;
  }
  EXPECT_GE(levels, 1) << "no SIMD level available to compare";
}

}  // namespace
}  // namespace gyro
