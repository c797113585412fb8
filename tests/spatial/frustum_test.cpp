// Frustums and culling (gyro/frustum.hpp) against binary64 references:
//  - plane extraction against planes worked out by hand, and the planes against the eight
//    corners of the camera's frustum computed analytically in double;
//  - the NEVER-DROP property on 10^5 seeded random spheres, AABBs and OBBs per type around
//    four cameras (near and far from the origin, wide, narrow, orthographic), a third of
//    them hugging a face, edge or corner: every shape with a sample point strictly inside
//    the frustum of the float matrices (binary64 clip test) must pass, every culled shape
//    must be separated from that frustum by an exact separating-axis test in binary64, and
//    shapes placed touching a plane must pass; the false positives (kept but separated)
//    are counted and printed;
//  - classify: outside exactly when culled, inside only when certainly inside;
//  - frustum_cull bit for bit equal to the scalar intersects() at every SIMD level and
//    thread counts 1 and 3; bad input gets its status and writes nothing.
#include "gyro/frustum.hpp"

#include "core/error.hpp"
#include "gyro/camera.hpp"
#include "gyro/math_transform.hpp"
#include "gyro/runtime.hpp"
#include "random_shapes.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---------------------------------------------------------------- binary64 helpers
struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
vec3 f3(const D3& v) { return {float(v.x), float(v.y), float(v.z)}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(const D3& a) { return std::sqrt(dot(a, a)); }
D3 unit(const D3& a) { return a * (1.0 / norm(a)); }
D3 row(const mat3& m, int r) { return {m.m[r][0], m.m[r][1], m.m[r][2]}; }

using M4 = double[4][4];

// The four corners of face f (in gyro's plane order left, right, bottom, top, near, far),
// ascending; corner bits: 0 right, 1 top, 2 far. So ids[1] and ids[2] are the neighbours
// of ids[0] along the face and ids[3] is opposite it.
void face_corners(int f, int ids[4]) {
  const int bit = 1 << (f / 2), val = (f % 2) ? bit : 0;
  int n = 0;
  for (int k = 0; k < 8; ++k)
    if ((k & bit) == val) ids[n++] = k;
}

// Gauss-Jordan with partial pivoting.
bool invert(const M4 a, M4 out) {
  double m[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) m[i][j] = j < 4 ? a[i][j] : (j - 4 == i);
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (m[p][c] == 0) return false;
    for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[p][j]);
    const double inv = 1.0 / m[c][c];
    for (int j = 0; j < 8; ++j) m[c][j] *= inv;
    for (int r = 0; r < 4; ++r)
      if (r != c) {
        const double f = m[r][c];
        for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
      }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m[i][j + 4];
  return true;
}

// The exact frustum of a camera's float view and projection matrices, in binary64.
struct RefFrustum {
  M4 vp;
  D3 corner[8];  // bit 0 right, bit 1 top, bit 2 far (gyro's frustum_corners order)
  D3 normal[6];  // unit, inward, in gyro's plane order
  double offset[6];
  D3 centroid;

  explicit RefFrustum(const Camera& cam) {
    const mat4 v = view_matrix(cam), p = projection_matrix(cam);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        vp[i][j] = 0;
        for (int k = 0; k < 4; ++k) vp[i][j] += double(v.m[i][k]) * double(p.m[k][j]);
      }
    M4 inv;
    EXPECT_TRUE(invert(vp, inv));
    for (int k = 0; k < 8; ++k) {
      const double ndc[4] = {(k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : 0.0, 1.0};
      double w[4] = {0, 0, 0, 0};
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) w[j] += ndc[i] * inv[i][j];
      corner[k] = {w[0] / w[3], w[1] / w[3], w[2] / w[3]};
      centroid = centroid + corner[k] * 0.125;
    }
    for (int f = 0; f < 6; ++f) {
      int ids[4];
      face_corners(f, ids);
      D3 nrm = unit(cross(corner[ids[1]] - corner[ids[0]], corner[ids[2]] - corner[ids[0]]));
      if (dot(nrm, centroid - corner[ids[0]]) < 0) nrm = nrm * -1.0;
      normal[f] = nrm;
      offset[f] = dot(nrm, corner[ids[0]]);
    }
  }

  // -w < x < w, -w < y < w, 0 < z < w in binary64: the point is drawn.
  bool strictly_inside(const D3& p) const {
    const double in[4] = {p.x, p.y, p.z, 1.0};
    double c[4] = {0, 0, 0, 0};
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) c[j] += in[i] * vp[i][j];
    return -c[3] < c[0] && c[0] < c[3] && -c[3] < c[1] && c[1] < c[3] && 0 < c[2] && c[2] < c[3];
  }
  double plane_distance(int f, const D3& p) const { return dot(normal[f], p) - offset[f]; }

  // Projection of the frustum on an axis.
  void interval(const D3& a, double& lo, double& hi) const {
    lo = hi = dot(corner[0], a);
    for (int k = 1; k < 8; ++k) lo = std::min(lo, dot(corner[k], a)), hi = std::max(hi, dot(corner[k], a));
  }
  bool separates(const D3& a, double shape_lo, double shape_hi) const {
    double lo, hi;
    interval(a, lo, hi);
    return shape_hi < lo || shape_lo > hi;
  }
  template <class F> void for_each_edge(F&& f) const {
    for (int k = 0; k < 8; ++k)
      for (int b : {1, 2, 4})
        if (!(k & b)) f(corner[k], corner[k | b]);
  }
};

// A box as centre, unit axes and half extents (an AABB has the world axes): the points
// c + sum t_i e_i u_i with |t_i| <= 1, whose extent along a is radius(a).
struct BoxD {
  D3 c, u[3];
  double e[3];
  double radius(const D3& a) const {
    return e[0] * std::abs(dot(u[0], a)) + e[1] * std::abs(dot(u[1], a)) + e[2] * std::abs(dot(u[2], a));
  }
};

// Exact separating-axis tests in binary64 (up to its rounding, 1e-16 relative): convex
// polyhedra are disjoint iff a face normal of either or a cross product of an edge of
// each separates them; a sphere and a polyhedron iff a face normal, or the direction from
// the centre to the nearest point of an edge or corner, does.
bool separated(const RefFrustum& f, const BoxD& b) {
  auto test = [&](const D3& a) {
    const double m = dot(b.c, a), r = b.radius(a);
    return f.separates(a, m - r, m + r);
  };
  for (const D3& n : f.normal)
    if (test(n)) return true;
  // The box's face normals: its float axes are only nearly orthogonal, so the box is the
  // parallelepiped they span, whose faces are normal to the cross products of two axes.
  for (int a = 0; a < 3; ++a)
    if (test(cross(b.u[(a + 1) % 3], b.u[(a + 2) % 3]))) return true;
  bool sep = false;
  f.for_each_edge([&](const D3& p, const D3& q) {
    const D3 d = q - p;
    for (const D3& u : b.u) {
      const D3 a = cross(u, d);
      if (!sep && norm(a) > 1e-12 * norm(d)) sep = test(a);
    }
  });
  return sep;
}

bool separated(const RefFrustum& f, const D3& c, double r) {
  auto test = [&](const D3& a) {
    const double m = dot(c, a), s = r * norm(a);
    return f.separates(a, m - s, m + s);
  };
  for (const D3& n : f.normal)
    if (test(n)) return true;
  bool sep = false;
  f.for_each_edge([&](const D3& p, const D3& q) {
    const D3 d = q - p;
    const double t = std::clamp(dot(c - p, d) / dot(d, d), 0.0, 1.0);
    const D3 a = c - (p + d * t);
    if (!sep && norm(a) > 0) sep = test(a);
  });
  return sep;
}

// Sample points of the shapes: certainly visible when one is strictly inside.
bool certainly_visible(const RefFrustum& f, const BoxD& b) {
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (f.strictly_inside(b.c + b.u[0] * (i * b.e[0]) + b.u[1] * (j * b.e[1]) + b.u[2] * (k * b.e[2]))) return true;
  // The box's point nearest the frustum's centroid.
  D3 p = b.c;
  for (int a = 0; a < 3; ++a) p = p + b.u[a] * std::clamp(dot(f.centroid - b.c, b.u[a]), -b.e[a], b.e[a]);
  return f.strictly_inside(p);
}

bool certainly_visible(const RefFrustum& f, const D3& c, double r) {
  if (f.strictly_inside(c)) return true;
  for (const D3& n : f.normal)  // the sphere's deepest point into each half-space
    if (f.strictly_inside(c + n * r)) return true;
  const D3 to = f.centroid - c;
  if (norm(to) > 0 && f.strictly_inside(c + unit(to) * r)) return true;
  const D3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const D3& a : axes)
    if (f.strictly_inside(c + a * r) || f.strictly_inside(c - a * r)) return true;
  return false;
}

bool certainly_inside(const RefFrustum& f, const BoxD& b) {
  for (int k = 0; k < 6; ++k)
    if (f.plane_distance(k, b.c) - b.radius(f.normal[k]) < 0) return false;
  return true;
}
bool certainly_inside(const RefFrustum& f, const D3& c, double r) {
  for (int k = 0; k < 6; ++k)
    if (f.plane_distance(k, c) < r) return false;
  return true;
}

// ---------------------------------------------------------------- scenes
struct Scene {
  const char* name;
  Camera cam;
};

std::vector<Scene> scenes() {
  SplitMix64 rng(31337);
  std::vector<Scene> s;
  s.push_back({"perspective at the origin", perspective_camera(deg_to_rad(60.0f), 16.0f / 9.0f, 0.5f, 100.0f)});
  Camera far = perspective_camera(kHalfPi, 1.0f, 0.1f, 50.0f);
  set_look_at(far, {1000.0f, 200.0f, -3000.0f}, {1010.0f, 190.0f, -2950.0f}, {0.0f, 1.0f, 0.0f});
  s.push_back({"perspective far from the origin", far});
  Camera ortho = orthographic_camera(40.0f, 30.0f, -10.0f, 60.0f);
  ortho.orientation = testing::random_rotation(rng);
  ortho.position = {5.0f, -3.0f, 2.0f};
  s.push_back({"orthographic, rotated", ortho});
  Camera narrow = perspective_camera(deg_to_rad(10.0f), 1.3f, 1.0f, 1e4f);
  narrow.orientation = testing::random_rotation(rng);
  narrow.position = {-2e4f, 0.0f, 5e3f};
  s.push_back({"narrow perspective, deep and far", narrow});
  return s;
}

enum class Kind { sphere, aabb, obb };

struct GenShape {
  BoxD box;  // sphere: centre c, radius e[0]
  bool touching = false;
};

// Shapes around the frustum: 2/3 with centres anywhere in an enlarged view volume (behind
// the camera and past the far plane too), 1/3 near a face, edge or corner, a sixth of
// those placed touching a plane from outside. Sizes up to 40% of the frustum's half height
// at their depth; a tenth have size 0 (points, flat boxes).
std::vector<GenShape> generate(const Camera& cam, const RefFrustum& ref, Kind kind, std::size_t n, SplitMix64& rng) {
  const mat4 w = world_matrix(cam);
  const bool persp = cam.mode == ProjectionMode::perspective;
  const double th = persp ? std::tan(double(cam.fov_y) / 2) : 0.0, tw = th * cam.aspect;
  const double depth = double(cam.z_far) - double(cam.z_near);
  std::vector<GenShape> out(n);
  for (GenShape& g : out) {
    const double zv = cam.z_near + depth * (1.3 * rng.u() - 0.15);
    const double az = std::max(std::abs(zv), double(cam.z_near));
    const double hh = persp ? th * az : cam.height * 0.5, hw = persp ? tw * az : cam.width * 0.5;
    const double size = rng.u() < 0.1 ? 0.0 : 0.4 * hh * rng.u();
    BoxD& b = g.box;
    for (double& e : b.e) e = size * (kind == Kind::sphere ? 1.0 : (rng.u() < 0.1 ? 0.0 : 0.1 + 0.9 * rng.u()));
    if (kind == Kind::obb) {
      const mat3 r = testing::random_rotation(rng);
      for (int a = 0; a < 3; ++a) b.u[a] = row(r, a);
    } else {
      b.u[0] = {1, 0, 0}, b.u[1] = {0, 1, 0}, b.u[2] = {0, 0, 1};
    }
    const double mode = rng.u();
    if (mode < 2.0 / 3.0) {
      const D3 v{hw * (3 * rng.u() - 1.5), hh * (3 * rng.u() - 1.5), zv};
      b.c = d3(multiply_point(f3(v), w));
    } else {
      // A point on a face (or a little past its edges), then out or in along its normal.
      const int f = int(rng.u() * 6) % 6;
      int ids[4];
      face_corners(f, ids);
      const double s = 1.2 * rng.u() - 0.1, t = 1.2 * rng.u() - 0.1;
      const D3 p = ref.corner[ids[0]] * ((1 - s) * (1 - t)) + ref.corner[ids[1]] * (s * (1 - t)) +
                   ref.corner[ids[2]] * ((1 - s) * t) + ref.corner[ids[3]] * (s * t);
      const D3 out_n = ref.normal[f] * -1.0;
      const double r = kind == Kind::sphere ? b.e[0] : b.radius(out_n);
      g.touching = rng.u() < 1.0 / 6.0 && s >= 0 && s <= 1 && t >= 0 && t <= 1;
      if (!g.touching) {
        b.c = p + out_n * (r * (2.4 * rng.u() - 1.2));
      } else if (kind == Kind::sphere) {
        b.c = p + out_n * r;
      } else {
        // The box's deepest point into the frustum, its support point along the inward
        // normal, is p: the box touches the face at p from outside.
        b.c = p;
        for (int a = 0; a < 3; ++a) b.c = b.c - b.u[a] * (dot(b.u[a], out_n) <= 0 ? b.e[a] : -b.e[a]);
      }
    }
    b.c = d3(f3(b.c));  // the shape is what float holds
    for (double& e : b.e) e = double(float(e));
    for (D3& u : b.u) u = d3(f3(u));
  }
  return out;
}

Sphere sphere_of(const BoxD& b) { return {f3(b.c), float(b.e[0])}; }
AABB aabb_of(const BoxD& b) { return {f3(b.c), {float(b.e[0]), float(b.e[1]), float(b.e[2])}}; }
OBB obb_of(const BoxD& b) { return {f3(b.c), {float(b.e[0]), float(b.e[1]), float(b.e[2])}, from_rows(f3(b.u[0]), f3(b.u[1]), f3(b.u[2]))}; }

// ---------------------------------------------------------------- plane extraction
void expect_plane(const Plane& p, const D3& n, double d, const char* what) {
  EXPECT_NEAR(p.normal.x, n.x, 1e-6) << what;
  EXPECT_NEAR(p.normal.y, n.y, 1e-6) << what;
  EXPECT_NEAR(p.normal.z, n.z, 1e-6) << what;
  EXPECT_NEAR(p.distance, d, 1e-6 * (1 + std::abs(d))) << what;
}

TEST(Frustum, PerspectivePlanesMatchHandComputedValues) {
  // fov 90 degrees, square: the side planes are at 45 degrees through the eye.
  const Frustum f = frustum(perspective_camera(kHalfPi, 1.0f, 1.0f, 10.0f));
  const double s = std::sqrt(0.5);
  expect_plane(f.planes[frustum_plane::left], {s, 0, s}, 0, "left");
  expect_plane(f.planes[frustum_plane::right], {-s, 0, s}, 0, "right");
  expect_plane(f.planes[frustum_plane::bottom], {0, s, s}, 0, "bottom");
  expect_plane(f.planes[frustum_plane::top], {0, -s, s}, 0, "top");
  expect_plane(f.planes[frustum_plane::near], {0, 0, 1}, 1, "near");
  expect_plane(f.planes[frustum_plane::far], {0, 0, -1}, -10, "far");
  // Moved and turned: the camera at (0, 0, 5) looking down -x (its right is +z).
  Camera c = perspective_camera(kHalfPi, 1.0f, 1.0f, 10.0f);
  set_look_at(c, {0, 0, 5}, {-1, 0, 5}, {0, 1, 0});
  const Frustum g = frustum(c);
  expect_plane(g.planes[frustum_plane::near], {-1, 0, 0}, 1, "turned near");
  expect_plane(g.planes[frustum_plane::far], {1, 0, 0}, -10, "turned far");
  expect_plane(g.planes[frustum_plane::left], {-s, 0, s}, 5 * s, "turned left");
}

TEST(Frustum, OrthographicPlanesMatchHandComputedValues) {
  const Frustum f = frustum(orthographic_camera(4.0f, 2.0f, 1.0f, 5.0f));
  expect_plane(f.planes[frustum_plane::left], {1, 0, 0}, -2, "left");
  expect_plane(f.planes[frustum_plane::right], {-1, 0, 0}, -2, "right");
  expect_plane(f.planes[frustum_plane::bottom], {0, 1, 0}, -1, "bottom");
  expect_plane(f.planes[frustum_plane::top], {0, -1, 0}, -1, "top");
  expect_plane(f.planes[frustum_plane::near], {0, 0, 1}, 1, "near");
  expect_plane(f.planes[frustum_plane::far], {0, 0, -1}, -5, "far");
  // From one float matrix, or from the two multiplied in double: the same planes to rounding.
  const Camera c = scenes()[2].cam;
  const Frustum a = frustum(view_projection_matrix(c)), b = frustum(c);
  for (int k = 0; k < 6; ++k) {
    EXPECT_LT(norm(d3(a.planes[k].normal) - d3(b.planes[k].normal)), 1e-6);
    EXPECT_NEAR(a.planes[k].distance, b.planes[k].distance, 1e-5 * (1 + std::abs(b.planes[k].distance)));
  }
}

TEST(Frustum, PlanesContainTheEightCornersOfTheCamerasFrustum) {
  double worst_on = 0, worst_corner = 0, worst_analytic = 0;
  for (const Scene& s : scenes()) {
    const Camera& c = s.cam;
    const Frustum f = frustum(c);
    const RefFrustum ref(c);  // the exact frustum of the float matrices
    const mat3 r = orthonormalized(c.orientation);
    const bool persp = c.mode == ProjectionMode::perspective;
    const double th = std::tan(double(c.fov_y) / 2), n = c.z_near, fa = c.z_far;
    const double scale = norm(d3(c.position)) + fa;
    vec3 got[8];
    frustum_corners(f, got);
    for (int k = 0; k < 8; ++k) {
      const D3& p = ref.corner[k];
      const int on[3] = {(k & 1) ? frustum_plane::right : frustum_plane::left,
                         (k & 2) ? frustum_plane::top : frustum_plane::bottom,
                         (k & 4) ? frustum_plane::far : frustum_plane::near};
      for (int i = 0; i < 6; ++i) {
        const double dist = dot(d3(f.planes[i].normal), p) - f.planes[i].distance;
        if (i == on[0] || i == on[1] || i == on[2]) {
          worst_on = std::max(worst_on, std::abs(dist) / scale);
        } else {
          EXPECT_GT(dist, -2e-6 * scale) << s.name << " corner " << k << " plane " << i;
        }
      }
      EXPECT_TRUE(contains(f, f3(p))) << s.name << " corner " << k;  // closed, with its tolerance
      worst_corner = std::max(worst_corner, norm(d3(got[k]) - p) / scale);
      // The ideal corner, from the camera's parameters in double. The float perspective
      // matrix holds the far plane only to about 2^-24 (far - near)^2 / near (its depth
      // row is far / (far - near) rounded), so far corners get that much slack.
      const double z = (k & 4) ? fa : n;
      const double hy = persp ? th * z : c.height * 0.5, hx = persp ? hy * c.aspect : c.width * 0.5;
      const D3 ideal = d3(c.position) + row(r, 0) * ((k & 1) ? hx : -hx) + row(r, 1) * ((k & 2) ? hy : -hy) + row(r, 2) * z;
      const double slack = persp && (k & 4) ? 4 * 0x1p-24 * (fa - n) * (fa - n) / n : 0.0;
      worst_analytic = std::max(worst_analytic, norm(ideal - p) / (2e-6 * scale + slack));
    }
  }
  std::printf("corners: max distance to their own planes %.2e, frustum_corners error %.2e (relative to scale); "
              "ideal corners within %.2f of their bound\n",
              worst_on, worst_corner, worst_analytic);
  EXPECT_LT(worst_on, 1e-6);
  EXPECT_LT(worst_corner, 2e-6);
  EXPECT_LT(worst_analytic, 1.0);
}

TEST(Frustum, ContainsPoints) {
  const Frustum f = frustum(perspective_camera(kHalfPi, 1.0f, 1.0f, 10.0f));
  EXPECT_TRUE(contains(f, {0, 0, 5}));
  EXPECT_TRUE(contains(f, {0, 0, 1}));     // on the near plane
  EXPECT_TRUE(contains(f, {10, 10, 10}));  // a far corner
  EXPECT_TRUE(contains(f, {-1, 1, 1}));    // a near corner
  EXPECT_FALSE(contains(f, {0, 0, 0.99f}));
  EXPECT_FALSE(contains(f, {0, 0, 10.01f}));
  EXPECT_FALSE(contains(f, {0, 0, -5}));
  EXPECT_FALSE(contains(f, {5.1f, 0, 5}));
  EXPECT_FALSE(contains(f, {0, -5.1f, 5}));
  EXPECT_TRUE(contains(f, {5, 0, 5}));
  // NaN is never culled (a shape with NaN is kept, never called inside).
  EXPECT_TRUE(contains(f, {kNaN, 0, 5}));
  EXPECT_EQ(classify(f, Sphere{{kNaN, 0, 5}, 1}), Containment::intersecting);
}

TEST(Frustum, ShapesTouchingAPlaneAreNeverCulled) {
  const Frustum f = frustum(perspective_camera(kHalfPi, 1.0f, 1.0f, 10.0f));
  // A unit sphere tangent to the near plane from the eye's side, to the far plane from
  // beyond, to the left plane from outside.
  EXPECT_TRUE(intersects(f, Sphere{{0, 0, 0}, 1}));
  EXPECT_TRUE(intersects(f, Sphere{{0, 0, 11}, 1}));
  EXPECT_FALSE(intersects(f, Sphere{{0, 0, 11.01f}, 1}));
  const float s = std::sqrt(0.5f);
  EXPECT_TRUE(intersects(f, Sphere{{-5 - 2 * s, 0, 5}, 1}));  // distance (-5 - 2s + 5) s = -1
  EXPECT_FALSE(intersects(f, Sphere{{-5.01f - 2 * s, 0, 5}, 1}));
  // Boxes: a corner touching the near plane, a face touching the far plane.
  EXPECT_TRUE(intersects(f, AABB{{0, 0, 0.5f}, {0.5f, 0.5f, 0.5f}}));
  EXPECT_FALSE(intersects(f, AABB{{0, 0, 0.49f}, {0.5f, 0.5f, 0.49f}}));
  EXPECT_TRUE(intersects(f, AABB{{3, 3, 12}, {1, 1, 2}}));
  OBB o{{0, 0, 0}, {1, 1, 1}, rotation3_axis_angle({0, 1, 0}, kPi / 4)};
  o.center.z = 1.0f - std::sqrt(2.0f);  // an edge touching the near plane
  EXPECT_TRUE(intersects(f, o));
  o.center.z -= 0.01f;
  EXPECT_FALSE(intersects(f, o));
  EXPECT_EQ(classify(f, Sphere{{0, 0, 5}, 0.5f}), Containment::inside);
  EXPECT_EQ(classify(f, Sphere{{0, 0, 5}, 4}), Containment::intersecting);
  EXPECT_EQ(classify(f, AABB{{0, 0, 5}, {1, 1, 1}}), Containment::inside);
  EXPECT_EQ(classify(f, AABB{{0, 0, -5}, {1, 1, 1}}), Containment::outside);
  EXPECT_EQ(classify(f, OBB{{0, 0, 5}, {1, 1, 1}, rotation3_axis_angle({1, 1, 0}, 0.3f)}), Containment::inside);
  // The Cookbook's false positive: a sphere off a corner, outside two planes' crossing but
  // not entirely outside either.
  EXPECT_TRUE(intersects(f, Sphere{{-11.1f, 0, 11.1f}, 1.2f}));
}

// ---------------------------------------------------------------- the never-drop property
struct Tally {
  std::size_t shapes = 0, visible = 0, culled = 0, false_positive = 0, touching = 0, inside = 0;
  std::size_t dropped = 0, culled_not_separated = 0, touching_culled = 0, wrong_inside = 0, classify_mismatch = 0;
};

template <class Shape>
void check_one(const Frustum& f, const RefFrustum& ref, const GenShape& g, const Shape& shape, bool sphere, Tally& t) {
  const bool kept = intersects(f, shape);
  const Containment cls = classify(f, shape);
  ++t.shapes;
  t.culled += !kept;
  t.classify_mismatch += (cls == Containment::outside) == kept;
  const bool vis = sphere ? certainly_visible(ref, g.box.c, g.box.e[0]) : certainly_visible(ref, g.box);
  t.visible += vis;
  t.dropped += vis && !kept;
  if (!vis) {
    const bool sep = sphere ? separated(ref, g.box.c, g.box.e[0]) : separated(ref, g.box);
    t.culled_not_separated += !kept && !sep;
    t.false_positive += kept && sep;
  }
  if (g.touching) ++t.touching, t.touching_culled += !kept;
  if (cls == Containment::inside) {
    ++t.inside;
    t.wrong_inside += !(sphere ? certainly_inside(ref, g.box.c, g.box.e[0]) : certainly_inside(ref, g.box));
  }
}

TEST(Frustum, NeverDropsAVisibleShape) {
  constexpr std::size_t kPerType = 100000;
  const std::vector<Scene> ss = scenes();
  SplitMix64 rng(20240613);
  const char* names[3] = {"spheres", "AABBs", "OBBs"};
  for (int kind = 0; kind < 3; ++kind) {
    Tally all;
    for (const Scene& s : ss) {
      const RefFrustum ref(s.cam);
      const Frustum f = frustum(s.cam);
      Tally t;
      for (const GenShape& g : generate(s.cam, ref, Kind(kind), kPerType / ss.size(), rng)) {
        if (kind == 0) check_one(f, ref, g, sphere_of(g.box), true, t);
        if (kind == 1) check_one(f, ref, g, aabb_of(g.box), false, t);
        if (kind == 2) check_one(f, ref, g, obb_of(g.box), false, t);
      }
      std::printf("%-7s %-33s: %6zu shapes, %6zu certainly visible, %6zu culled, %5zu false positives (kept, "
                  "separated), %5zu inside\n",
                  names[kind], s.name, t.shapes, t.visible, t.culled, t.false_positive, t.inside);
      EXPECT_EQ(t.dropped, 0u) << names[kind] << ", " << s.name << ": certainly visible shapes culled";
      EXPECT_EQ(t.culled_not_separated, 0u) << names[kind] << ", " << s.name << ": culled shapes not separated";
      EXPECT_EQ(t.touching_culled, 0u) << names[kind] << ", " << s.name << ": touching shapes culled";
      EXPECT_EQ(t.wrong_inside, 0u) << names[kind] << ", " << s.name << ": inside but not certainly inside";
      EXPECT_EQ(t.classify_mismatch, 0u) << names[kind] << ", " << s.name;
      // Enough of every case for the test to mean something.
      EXPECT_GT(t.visible, t.shapes / 4) << s.name;
      EXPECT_GT(t.culled, t.shapes / 5) << s.name;
      EXPECT_GT(t.touching, t.shapes / 40) << s.name;
      EXPECT_GT(t.inside, t.shapes / 20) << s.name;
      all.shapes += t.shapes, all.culled += t.culled, all.false_positive += t.false_positive;
    }
    // False positives are the plane test's known price near edges and corners: a few
    // percent of these deliberately boundary-heavy sets.
    EXPECT_LT(all.false_positive, all.shapes / 10) << names[kind];
  }
}

// ---------------------------------------------------------------- batch culling
struct Columns {
  std::vector<float> col[15];
  void push(std::initializer_list<float> v) {
    int k = 0;
    for (float x : v) col[k++].push_back(x);
  }
  const float* p(int k) const { return col[k].data(); }
};

TEST(Frustum, BatchCullEqualsScalarAtEveryLevelAndThreadCount) {
  const std::vector<Scene> ss = scenes();
  SplitMix64 rng(77);
  const std::size_t n = 10007;  // several chunks and a ragged tail at every width
  int levels = 0;
  for (const Scene& s : {ss[1], ss[2]}) {
    const RefFrustum ref(s.cam);
    const Frustum f = frustum(s.cam);
    for (int kind = 0; kind < 3; ++kind) {
      const std::vector<GenShape> gs = generate(s.cam, ref, Kind(kind), n, rng);
      Columns c;
      std::vector<uint32_t> want(n);
      for (std::size_t i = 0; i < n; ++i) {
        const BoxD& b = gs[i].box;
        if (kind == 0) {
          c.push({float(b.c.x), float(b.c.y), float(b.c.z), float(b.e[0])});
          want[i] = intersects(f, sphere_of(b));
        } else if (kind == 1) {
          c.push({float(b.c.x), float(b.c.y), float(b.c.z), float(b.e[0]), float(b.e[1]), float(b.e[2])});
          want[i] = intersects(f, aabb_of(b));
        } else {
          const OBB o = obb_of(b);
          const mat3& r = o.orientation;
          c.push({o.center.x, o.center.y, o.center.z, o.half_extents.x, o.half_extents.y, o.half_extents.z, r.m[0][0],
                  r.m[0][1], r.m[0][2], r.m[1][0], r.m[1][1], r.m[1][2], r.m[2][0], r.m[2][1], r.m[2][2]});
          want[i] = intersects(f, o);
        }
      }
      std::size_t kept = 0;
      for (uint32_t w : want) kept += w;
      EXPECT_GT(kept, n / 4);
      EXPECT_LT(kept, n - n / 5);
      levels = 0;
      for (uint32_t v = 1; v <= 5; ++v) {
        if (!simd_level_available(SimdLevel(v))) continue;
        ASSERT_EQ(set_simd_level(SimdLevel(v)), Status::ok);
        ++levels;
        for (uint32_t threads : {1u, 3u}) {
          ASSERT_EQ(set_thread_count(threads), Status::ok);
          std::vector<uint32_t> got(n, 0xDEADBEEFu);
          Status st = Status::internal;
          if (kind == 0) st = frustum_cull(f, SpheresView{c.p(0), c.p(1), c.p(2), c.p(3)}, n, got.data());
          if (kind == 1) st = frustum_cull(f, AabbsView{c.p(0), c.p(1), c.p(2), c.p(3), c.p(4), c.p(5)}, n, got.data());
          if (kind == 2)
            st = frustum_cull(f,
                              ObbsView{c.p(0), c.p(1), c.p(2), c.p(3), c.p(4), c.p(5), c.p(6), c.p(7), c.p(8), c.p(9),
                                       c.p(10), c.p(11), c.p(12), c.p(13), c.p(14)},
                              n, got.data());
          ASSERT_EQ(st, Status::ok) << last_error();
          std::size_t diff = 0;
          for (std::size_t i = 0; i < n; ++i) diff += got[i] != want[i];
          EXPECT_EQ(diff, 0u) << s.name << " kind " << kind << " at " << simd_level_name(SimdLevel(v)) << ", "
                              << threads << " threads";
        }
      }
    }
  }
  EXPECT_GE(levels, 1);
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

TEST(Frustum, BatchCullRejectsBadInputAndWritesNothing) {
  const Frustum f = frustum(perspective_camera(1.0f, 1.0f, 0.1f, 10.0f));
  std::vector<float> cx{0, 1, 2}, cy{0, 0, 0}, cz{5, 5, 5}, r{1, 1, 1}, ex{1, 1, 1};
  const SpheresView good{cx.data(), cy.data(), cz.data(), r.data()};
  std::vector<uint32_t> out(3, 7u);
  auto untouched = [&] { return out == std::vector<uint32_t>(3, 7u); };
  auto expect = [&](Status got, Status want, const char* what) {
    EXPECT_EQ(got, want) << what;
    EXPECT_STRNE(last_error(), "") << what;
    EXPECT_TRUE(untouched()) << what;
    detail::clear_error();
  };
  expect(frustum_cull(f, good, 3, nullptr), Status::null_argument, "null output");
  expect(frustum_cull(f, SpheresView{cx.data(), nullptr, cz.data(), r.data()}, 3, out.data()), Status::null_argument,
         "null column");
  expect(frustum_cull(f, AabbsView{cx.data(), cy.data(), cz.data(), ex.data(), nullptr, ex.data()}, 3, out.data()),
         Status::null_argument, "null box column");
  expect(frustum_cull(f, good, std::size_t(1) << 31, out.data()), Status::invalid_count, "count 2^31");
  cz[2] = kNaN;
  expect(frustum_cull(f, good, 3, out.data()), Status::non_finite, "NaN centre");
  cz[2] = std::numeric_limits<float>::infinity();
  expect(frustum_cull(f, good, 3, out.data()), Status::non_finite, "infinite centre");
  cz[2] = 5;
  r[1] = -1;
  expect(frustum_cull(f, good, 3, out.data()), Status::invalid_argument, "negative radius");
  r[1] = 1;
  ex[0] = -0.5f;
  expect(frustum_cull(f, AabbsView{cx.data(), cy.data(), cz.data(), ex.data(), ex.data(), ex.data()}, 3, out.data()),
         Status::invalid_argument, "negative extent");
  ex[0] = 1;
  Frustum bad = f;
  bad.planes[3].distance = kNaN;
  expect(frustum_cull(bad, good, 3, out.data()), Status::non_finite, "NaN plane");
  bad = f;
  bad.planes[5].normal = bad.planes[5].normal * 2.0f;
  expect(frustum_cull(bad, good, 3, out.data()), Status::invalid_argument, "non-unit normal");
  bad.planes[5].normal = {0, 0, 0};
  expect(frustum_cull(bad, good, 3, out.data()), Status::invalid_argument, "zero normal");
  // Count 0 reads and writes nothing, even through null pointers.
  EXPECT_EQ(frustum_cull(f, SpheresView{}, 0, nullptr), Status::ok);
  // And the good input works.
  ASSERT_EQ(frustum_cull(f, good, 3, out.data()), Status::ok);
  EXPECT_EQ(out, (std::vector<uint32_t>{1, 1, 1}));
}

}  // namespace
}  // namespace gyro
