// Watertightness of the ray-triangle test (Woop, Benthin, Wald 2013): on closed meshes
// with shared vertices, rays aimed exactly at the float corners (shared vertices), at edge
// midpoints computed in float and at other float points of shared edges, from outside and
// from inside, must all hit the mesh (any-hit over the triangles around the target, and
// closest hit over the whole mesh by brute force for a sample). Also: a ray through a
// shared edge gets the same t from both triangles up to the rounding of the position along
// the edge (beyond the difference the exact planes themselves have there: the float ray
// passes within rounding of the edge, not through it), and rays along an axis through an
// edge (edge functions exactly 0) hit both triangles at bit-identical t.
#include "gyro/triangle.hpp"

#include "geometry/ray_triangle_lanes.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

namespace gyro {
namespace {

namespace lanes = GYRO_ARCH_NS;

struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 normalized(D3 a) { return a * (1 / std::sqrt(dot(a, a))); }
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
vec3 f3(D3 v) { return {float(v.x), float(v.y), float(v.z)}; }

// A closed triangle mesh with vertices shared by index, rounded to float once, faces wound
// consistently (outward), plus what the test needs: each vertex's fan and each edge's
// two faces.
struct Mesh {
  std::vector<vec3> v;
  std::vector<std::array<uint32_t, 3>> f;
  std::vector<std::vector<uint32_t>> fan;                         // faces around a vertex
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;  // (lo, hi) -> faces
  D3 centre;
  double inner_radius = 0;  // a ball of this radius about centre is inside

  Triangle tri(uint32_t face) const { return {v[f[face][0]], v[f[face][1]], v[f[face][2]]}; }
  void finish() {
    fan.assign(v.size(), {});
    edges.clear();
    for (uint32_t k = 0; k < f.size(); ++k)
      for (int j = 0; j < 3; ++j) {
        fan[f[k][j]].push_back(k);
        const uint32_t a = f[k][j], b = f[k][(j + 1) % 3];
        edges[{std::min(a, b), std::max(a, b)}].push_back(k);
      }
  }
};

// Subdivided icosahedron on a sphere of radius r about c (binary64, then rounded once).
Mesh icosphere(int levels, D3 c, double r) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  std::vector<D3> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                       {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  for (D3& x : v) x = normalized(x);
  std::vector<std::array<uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalized((v[a] + v[b]) * 0.5));
      return mid[key] = uint32_t(v.size() - 1);
    };
    std::vector<std::array<uint32_t, 3>> g;
    for (const auto& t : f) {
      const uint32_t a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c2 = midpoint(t[2], t[0]);
      g.push_back({t[0], a, c2}), g.push_back({t[1], b, a}), g.push_back({t[2], c2, b}), g.push_back({a, b, c2});
    }
    f.swap(g);
  }
  Mesh m;
  for (const D3& x : v) m.v.push_back(f3(c + x * r));
  m.f = f;
  m.centre = c;
  m.inner_radius = 0.9 * r;
  m.finish();
  return m;
}

// A cube of half size h about c, each face an n x n grid split into triangles (diagonals
// alternating), rotated by the rows of R; grid corners are shared along the cube's edges.
Mesh cube(int n, D3 c, double h, const D3 R[3]) {
  Mesh m;
  std::map<std::array<int, 3>, uint32_t> index;
  auto vertex = [&](int i, int j, int k) {
    const std::array<int, 3> key{i, j, k};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const D3 local = D3{2.0 * i / n - 1, 2.0 * j / n - 1, 2.0 * k / n - 1} * h;
    m.v.push_back(f3(c + R[0] * local.x + R[1] * local.y + R[2] * local.z));
    return index[key] = uint32_t(m.v.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side <= 1; ++side)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          auto at = [&](int u, int w) {
            std::array<int, 3> g{};
            g[axis] = side * n, g[(axis + 1) % 3] = u, g[(axis + 2) % 3] = w;
            return vertex(g[0], g[1], g[2]);
          };
          uint32_t q[4] = {at(a, b), at(a + 1, b), at(a + 1, b + 1), at(a, b + 1)};
          if (side == 0) std::swap(q[1], q[3]);  // outward winding on the low side
          if ((a + b) % 2 == 0) {
            m.f.push_back({q[0], q[1], q[2]}), m.f.push_back({q[0], q[2], q[3]});
          } else {
            m.f.push_back({q[0], q[1], q[3]}), m.f.push_back({q[1], q[2], q[3]});
          }
        }
  m.centre = c;
  m.inner_radius = 0.9 * h;
  m.finish();
  return m;
}

// Closed and consistently wound: every edge has two faces that walk it in opposite
// directions; and the signed volume is positive (outward).
void check_closed(const Mesh& m) {
  std::size_t open = 0;
  for (const auto& [e, faces] : m.edges) {
    if (faces.size() != 2) {
      ++open;
      continue;
    }
    auto walks = [&](uint32_t face, uint32_t a, uint32_t b) {
      for (int j = 0; j < 3; ++j)
        if (m.f[face][j] == a && m.f[face][(j + 1) % 3] == b) return true;
      return false;
    };
    if (walks(faces[0], e.first, e.second) == walks(faces[1], e.first, e.second)) ++open;
  }
  double volume = 0;
  for (uint32_t k = 0; k < m.f.size(); ++k) {
    const Triangle t = m.tri(k);
    volume += dot(d3(t.a) - m.centre, cross(d3(t.b) - m.centre, d3(t.c) - m.centre)) / 6;
  }
  ASSERT_EQ(open, 0u) << "the mesh is not closed and consistently wound";
  ASSERT_GT(volume, 0.0);
}

D3 random_rotation_row(gyro::testing::SplitMix64& rng, int row, double q[4]) {
  if (row == 0) {
    const double u0 = rng.u(), u1 = rng.u(), u2 = rng.u();
    const double s1 = std::sqrt(1 - u0), s2 = std::sqrt(u0);
    q[0] = s1 * std::sin(6.283185307179586 * u1), q[1] = s1 * std::cos(6.283185307179586 * u1);
    q[2] = s2 * std::sin(6.283185307179586 * u2), q[3] = s2 * std::cos(6.283185307179586 * u2);
  }
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const D3 rows[3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  return rows[row];
}

struct Tally {
  std::size_t rays = 0, leaks = 0, far_hits = 0, double_hits = 0;
  std::size_t edge_pairs = 0, same_t_bits = 0, within_1ulp = 0, beyond_bound = 0;
  int64_t worst_ulps = 0;
  double worst_excess = 0;  // (|t1 - t2| - exact difference) / (eps (|t| + depth extent of the edge))
};

// The exact t at which the float ray meets the plane of a triangle (binary64 from the
// float inputs): the two triangles at an edge differ here already, because the ray only
// passes within rounding of the edge and the planes meet at an angle.
double plane_t(const Triangle& t, D3 o, D3 d) {
  const D3 n = cross(d3(t.b) - d3(t.a), d3(t.c) - d3(t.a));
  return dot(n, d3(t.a) - o) / dot(n, d);
}

int64_t ulps_apart(float a, float b) {
  auto key = [](float x) {
    const int32_t i = std::bit_cast<int32_t>(x);
    return i < 0 ? int64_t(int32_t(0x80000000u)) - i : int64_t(i);
  };
  return std::abs(key(a) - key(b));
}

// Casts rays at every shared vertex and at float points of every shared edge, from
// outside (beyond the target, away from a random interior point) and from inside (from
// that interior point), against the triangles around the target: the fan of a vertex, the
// fans of an edge's two ends. A leak is a ray none of them hits.
void cast_at_mesh(const Mesh& m, uint64_t seed, int rays_per_vertex, int rays_per_edge_point, Tally& out) {
  gyro::testing::SplitMix64 rng(seed);
  auto interior = [&]() {
    for (;;) {
      const D3 u{2 * rng.u() - 1, 2 * rng.u() - 1, 2 * rng.u() - 1};
      if (dot(u, u) <= 1) return m.centre + u * m.inner_radius;
    }
  };
  std::vector<uint32_t> local;
  auto cast = [&](const vec3& target, bool is_edge, uint32_t e0, uint32_t e1) {
    const D3 q = interior();
    const bool inside = rng.next() & 1;
    const D3 o = inside ? q : d3(target) + (d3(target) - q) * (0.05 + 3 * rng.u());
    const vec3 of = f3(o);
    const vec3 d = target - of;
    const lanes::WatertightRay<float> wr = lanes::watertight_ray(lanes::RayL<float>{{of.x, of.y, of.z}, {d.x, d.y, d.z}});
    float best = __builtin_inff();
    int hits = 0;
    for (uint32_t face : local) {
      const Triangle t = m.tri(face);
      float u, v;
      const float th = lanes::ray_triangle_t(wr, lanes::TriangleL<float>{{t.a.x, t.a.y, t.a.z}, {t.b.x, t.b.y, t.b.z},
                                                                          {t.c.x, t.c.y, t.c.z}},
                                             0.0f, __builtin_inff(), u, v);
      if (th < __builtin_inff()) ++hits, best = std::min(best, th);
    }
    ++out.rays;
    // It must hit at the target (t = 1), up to the rounding of the coordinates over |d|.
    const double mag = std::max({std::abs(target.x), std::abs(target.y), std::abs(target.z), std::abs(of.x),
                                 std::abs(of.y), std::abs(of.z)});
    const double t_tol = 1e-5 + 64 * 0x1p-24 * mag / std::sqrt(dot(d3(d), d3(d)));
    if (hits == 0) ++out.leaks;
    else if (!(std::abs(best - 1.0) <= t_tol)) ++out.far_hits;
    if (hits > 1) ++out.double_hits;
    if (is_edge) {
      // Both triangles of the edge, hit or not: t = T / det from each.
      const auto& faces = m.edges.at({std::min(e0, e1), std::max(e0, e1)});
      float ts[2];
      for (int k = 0; k < 2; ++k) {
        const Triangle t = m.tri(faces[k]);
        const auto terms = lanes::detail_rt::ray_triangle_terms(
            wr, lanes::TriangleL<float>{{t.a.x, t.a.y, t.a.z}, {t.b.x, t.b.y, t.b.z}, {t.c.x, t.c.y, t.c.z}});
        ts[k] = terms.T / terms.det;
      }
      const int64_t ulps = ulps_apart(ts[0], ts[1]);
      ++out.edge_pairs;
      out.same_t_bits += ulps == 0;
      out.within_1ulp += ulps <= 1;
      out.worst_ulps = std::max(out.worst_ulps, ulps);
      // Beyond the exact planes' own difference, the float t may differ by the rounding of
      // the position along the edge: a few eps of t and of the edge's extent in t.
      const D3 od = d3(of), dd = d3(d);
      const double exact = std::abs(plane_t(m.tri(faces[0]), od, dd) - plane_t(m.tri(faces[1]), od, dd));
      const double depth = std::abs(dot(d3(m.v[e0]) - d3(m.v[e1]), dd)) / dot(dd, dd);
      const double excess = (std::abs(double(ts[0]) - ts[1]) - exact) / (0x1p-24 * (std::abs(double(ts[0])) + depth));
      out.worst_excess = std::max(out.worst_excess, excess);
      out.beyond_bound += !(excess <= 16);
    }
  };
  auto gather = [&](std::initializer_list<uint32_t> vertices) {
    local.clear();
    for (uint32_t vtx : vertices) local.insert(local.end(), m.fan[vtx].begin(), m.fan[vtx].end());
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
  };
  for (uint32_t vtx = 0; vtx < m.v.size(); ++vtx) {
    gather({vtx});
    for (int r = 0; r < rays_per_vertex; ++r) cast(m.v[vtx], false, 0, 0);
  }
  for (const auto& [e, faces] : m.edges) {
    gather({e.first, e.second});
    const vec3 a = m.v[e.first], b = m.v[e.second];
    const vec3 midpoint = (a + b) * 0.5f;  // in float
    for (int r = 0; r < rays_per_edge_point; ++r) cast(midpoint, true, e.first, e.second);
    for (int r = 0; r < rays_per_edge_point; ++r) {
      const vec3 p = a + (b - a) * float(0.02 + 0.96 * rng.u());  // a float point of the edge
      cast(p, true, e.first, e.second);
    }
  }
}

void print_tally(const char* name, const Tally& t) {
  std::printf("  %-34s %8zu rays: %zu leaks, %zu hits not at the target, %zu rays hit 2+ triangles\n"
              "  %-34s t from both triangles of %zu edges: %.1f%% bit-identical, %.1f%% within 1 ulp, worst %lld ulp;\n"
              "  %-34s beyond the exact planes' difference at most %.1f eps (|t| + edge depth), %zu over 16\n",
              name, t.rays, t.leaks, t.far_hits, t.double_hits, "", t.edge_pairs, 100.0 * t.same_t_bits / t.edge_pairs,
              100.0 * t.within_1ulp / t.edge_pairs, static_cast<long long>(t.worst_ulps), "", t.worst_excess,
              t.beyond_bound);
}

TEST(Watertight, RaysAtSharedEdgesAndVerticesNeverLeak) {
  const auto start = std::chrono::steady_clock::now();
  gyro::testing::SplitMix64 rng(7);
  double q[4];
  const D3 rot[3] = {random_rotation_row(rng, 0, q), random_rotation_row(rng, 1, q), random_rotation_row(rng, 2, q)};
  const D3 identity[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  struct Case {
    const char* name;
    Mesh mesh;
    int per_vertex, per_edge_point;
  };
  Case cases[] = {
      {"icosphere (5120 tris) at origin", icosphere(4, {0, 0, 0}, 1.0), 24, 18},
      {"icosphere (5120 tris) at 1e3", icosphere(4, {1000.5, -700.25, 300.75}, 3.0), 24, 18},
      {"rotated cube (3072 tris) at 1e4", cube(16, {-9000.5, 4000.25, 7000.75}, 20.0, rot), 24, 18},
      {"axis-aligned cube (3072 tris)", cube(16, {0.5, -0.25, 0.125}, 1.3, identity), 24, 18},
  };
  Tally total;
  uint64_t seed = 100;
  for (Case& c : cases) {
    check_closed(c.mesh);
    Tally t;
    cast_at_mesh(c.mesh, seed++, c.per_vertex, c.per_edge_point, t);
    print_tally(c.name, t);
    total.rays += t.rays, total.leaks += t.leaks, total.far_hits += t.far_hits;
    EXPECT_EQ(t.leaks, 0u) << c.name;
    EXPECT_EQ(t.far_hits, 0u) << c.name;
    EXPECT_EQ(t.beyond_bound, 0u) << c.name;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("  total: %zu rays, %zu leaks, %.0f ms (mesh building included)\n", total.rays, total.leaks, ms);
  EXPECT_GE(total.rays, 1000000u);
  EXPECT_EQ(total.leaks, 0u);
}

// Brute force over the whole mesh for a sample of rays: the closest hit over all
// triangles is at the target (outside origins hit there first; inside ones leave there),
// through the public raycast().
TEST(Watertight, ClosestHitOverTheWholeMeshIsAtTheTarget) {
  const Mesh m = icosphere(3, {10.25, -3.5, 7.75}, 2.0);  // 1280 triangles
  check_closed(m);
  gyro::testing::SplitMix64 rng(8);
  std::size_t misses = 0, wrong = 0, n = 0;
  for (int r = 0; r < 3000; ++r) {
    const bool at_vertex = r % 2 == 0;
    vec3 target;
    if (at_vertex) {
      target = m.v[rng.next() % m.v.size()];
    } else {
      const auto& t = m.f[rng.next() % m.f.size()];
      target = (m.v[t[0]] + m.v[t[1]]) * 0.5f;
    }
    D3 qd;
    for (;;) {
      qd = {2 * rng.u() - 1, 2 * rng.u() - 1, 2 * rng.u() - 1};
      if (dot(qd, qd) <= 1) break;
    }
    const D3 q = m.centre + qd * m.inner_radius;
    const vec3 o = (r % 4 < 2) ? f3(q) : f3(d3(target) + (d3(target) - q) * (0.05 + 3 * rng.u()));
    const Ray ray{o, target - o};
    float best = __builtin_inff();
    for (uint32_t k = 0; k < m.f.size(); ++k) {
      const RaycastResult h = raycast(m.tri(k), ray);
      if (h.hit) best = std::min(best, h.t);
    }
    ++n;
    if (!(best < __builtin_inff())) ++misses;
    else if (!(std::abs(best - 1.0f) <= 1e-3f)) ++wrong;
  }
  std::printf("  %zu rays x %zu triangles by brute force: %zu miss the mesh, %zu closest hits not at the target\n", n,
              m.f.size(), misses, wrong);
  EXPECT_EQ(misses, 0u);
  EXPECT_EQ(wrong, 0u);
}

// Rays along an axis through points of an edge of the axis-aligned cube: the sheared
// coordinates are exact, the shared edge's function is exactly 0 in both triangles, and
// both must report the hit (0 counts as inside), at bit-identical t when the edge lies in
// a face perpendicular to the ray.
TEST(Watertight, AxisRaysThroughEdgesHitBothTriangles) {
  const D3 identity[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Mesh m = cube(8, {0, 0, 0}, 1.0, identity);
  std::size_t pairs = 0, both = 0, same_t = 0;
  for (const auto& [e, faces] : m.edges) {
    const vec3 a = m.v[e.first], b = m.v[e.second];
    for (int axis = 0; axis < 3; ++axis) {
      // Only edges in a face perpendicular to this axis (both ends on the same face).
      const float ca = axis == 0 ? a.x : (axis == 1 ? a.y : a.z), cb = axis == 0 ? b.x : (axis == 1 ? b.y : b.z);
      if (ca != cb || std::abs(ca) != 1.0f) continue;
      bool flat = true;  // both faces in that plane (not a fold of the cube)
      for (uint32_t face : faces)
        for (uint32_t vi : m.f[face]) flat = flat && (axis == 0 ? m.v[vi].x : (axis == 1 ? m.v[vi].y : m.v[vi].z)) == ca;
      if (!flat) continue;
      for (float s : {0.25f, 0.5f, 0.75f}) {
        const vec3 p = a + (b - a) * s;
        vec3 d{};
        (axis == 0 ? d.x : (axis == 1 ? d.y : d.z)) = ca > 0 ? -1.0f : 1.0f;
        const Ray ray{p - d * 3.0f, d};
        const RaycastResult h0 = raycast(m.tri(faces[0]), ray), h1 = raycast(m.tri(faces[1]), ray);
        ++pairs;
        both += h0.hit && h1.hit;
        same_t += h0.hit && h1.hit && h0.t == h1.t;
      }
    }
  }
  std::printf("  %zu axis rays through edges of face-perpendicular edges: both triangles hit %zu, same t %zu\n", pairs,
              both, same_t);
  EXPECT_GT(pairs, 500u);
  EXPECT_EQ(both, pairs);
  EXPECT_EQ(same_t, pairs);
}

}  // namespace
}  // namespace gyro
