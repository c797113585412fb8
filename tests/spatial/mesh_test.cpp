// Mesh utilities (gyro/mesh.hpp): validate_mesh on every bad case with the index it names;
// mesh_bounds against a binary64 brute force with exact containment; is_closed on the
// generators, after breaking them, and against a brute-force edge count on seeded random
// meshes; weld_vertices against a brute-force greedy reference, with its stated invariants
// checked pairwise; the generators' counts, positions, orientation (every face normal
// outward), area and volume against the analytic values.
#include "gyro/mesh.hpp"

#include "core/error.hpp"
#include "gyro/math_scalar.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr double kPiD = 3.14159265358979323846;

struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 d3(const vec3& v) { return {v.x, v.y, v.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dotd(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 crossd(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

std::string last() { return last_error(); }
bool has(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }

// Sum of the signed tetrahedron volumes (origin, a, b, c): the enclosed volume of a closed
// mesh, positive when its faces are counter-clockwise seen from outside.
double signed_volume(const MeshData& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Triangle tr = m.triangle(t);
    v += dotd(d3(tr.a), crossd(d3(tr.b), d3(tr.c))) / 6.0;
  }
  return v;
}

double total_area(const MeshData& m) {
  double a = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Triangle tr = m.triangle(t);
    const D3 n = crossd(d3(tr.b) - d3(tr.a), d3(tr.c) - d3(tr.a));
    a += 0.5 * std::sqrt(dotd(n, n));
  }
  return a;
}

// Brute-force closedness: count directed edges in an ordered map.
bool closed_reference(const MeshData& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = m.indices[3 * t + e], b = m.indices[3 * t + (e + 1) % 3];
      if (a == b) return false;
      ++directed[{a, b}];
    }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto back = directed.find({edge.second, edge.first});
    if (back == directed.end() || back->second != 1) return false;
  }
  return !directed.empty();
}

MeshData flipped(MeshData m, std::size_t t) {
  std::swap(m.indices[3 * t + 1], m.indices[3 * t + 2]);
  return m;
}

MeshData without(MeshData m, std::size_t t) {
  m.indices.erase(m.indices.begin() + std::ptrdiff_t(3 * t), m.indices.begin() + std::ptrdiff_t(3 * t + 3));
  return m;
}

// Every triangle gets its own three vertices (what an STL file or a naive export gives).
MeshData exploded(const MeshData& m) {
  MeshData e;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Triangle tr = m.triangle(t);
    const uint32_t base = uint32_t(e.vertex_count());
    e.add_vertex(tr.a), e.add_vertex(tr.b), e.add_vertex(tr.c);
    e.add_triangle(base, base + 1, base + 2);
  }
  return e;
}

bool same_bits(const MeshData& a, const MeshData& b) {
  const auto bits = [](const std::vector<float>& v) {
    std::vector<uint32_t> r;
    for (float f : v) r.push_back(std::bit_cast<uint32_t>(f));
    return r;
  };
  return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z) && a.indices == b.indices;
}

// ------------------------------------------------------------------ validate_mesh

TEST(MeshValidate, AcceptsGoodMeshesAndDegenerateTriangles) {
  EXPECT_EQ(validate_mesh(make_box_mesh({1, 2, 3})), Status::ok);
  EXPECT_EQ(validate_mesh(make_sphere_mesh(1, 8, 12)), Status::ok);
  MeshData m;
  m.add_vertex({0, 0, 0}), m.add_vertex({1, 0, 0});
  m.add_triangle(0, 0, 1);  // zero area, still valid
  m.add_triangle(1, 1, 1);
  EXPECT_EQ(validate_mesh(m), Status::ok);
}

TEST(MeshValidate, RejectsEachBadCaseNamingTheFirstOffender) {
  const MeshData good = make_box_mesh({1, 1, 1});
  {
    MeshData m;
    EXPECT_EQ(validate_mesh(m), Status::invalid_count);
    EXPECT_TRUE(has(last(), "no triangles")) << last();
  }
  {
    MeshData m = good;
    m.indices.clear();
    EXPECT_EQ(validate_mesh(m), Status::invalid_count);
    EXPECT_TRUE(has(last(), "no triangles (8 vertices)")) << last();
  }
  {
    MeshData m = good;
    m.indices.push_back(0);
    EXPECT_EQ(validate_mesh(m), Status::invalid_count);
    EXPECT_TRUE(has(last(), "37 indices")) << last();
  }
  for (int column = 0; column < 3; ++column) {
    MeshData m = good;
    (column == 0 ? m.x : column == 1 ? m.y : m.z).pop_back();
    EXPECT_EQ(validate_mesh(m), Status::invalid_count) << column;
    EXPECT_TRUE(has(last(), "differ in size")) << last();
  }
  {
    MeshData m = good;
    m.indices[3 * 5 + 2] = 8;  // triangle 5
    m.indices[3 * 9 + 0] = 100;
    EXPECT_EQ(validate_mesh(m), Status::invalid_argument);
    EXPECT_TRUE(has(last(), "triangle 5 has index 8")) << last();
  }
  {
    MeshData m = good;
    m.indices[3 * 11 + 1] = std::numeric_limits<uint32_t>::max();
    EXPECT_EQ(validate_mesh(m), Status::invalid_argument);
    EXPECT_TRUE(has(last(), "triangle 11 has index 4294967295")) << last();
  }
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  {
    MeshData m = good;
    m.z[6] = inf, m.y[3] = nan, m.x[7] = -inf;
    EXPECT_EQ(validate_mesh(m), Status::non_finite);
    EXPECT_TRUE(has(last(), "vertex 3 ")) << last();
  }
  {
    MeshData m = good;
    m.add_vertex({0, 0, inf});  // unreferenced, still checked
    EXPECT_EQ(validate_mesh(m), Status::non_finite);
    EXPECT_TRUE(has(last(), "vertex 8 ")) << last();
  }
  {
    // Structure is checked before coordinates.
    MeshData m = good;
    m.x[0] = nan;
    m.indices[0] = 50;
    EXPECT_EQ(validate_mesh(m), Status::invalid_argument);
  }
}

// ------------------------------------------------------------------ mesh_bounds

TEST(MeshBounds, BoxAndSphereAreExact) {
  const AABB b = mesh_bounds(make_box_mesh({1.5f, 0.25f, 3}));
  EXPECT_EQ(b.center, (vec3{0, 0, 0}));
  EXPECT_EQ(b.half_extents, (vec3{1.5f, 0.25f, 3}));
  const AABB s = mesh_bounds(make_sphere_mesh(2, 2, 4));  // an octahedron: poles and a square ring
  EXPECT_EQ(aabb_max(s).y, 2.0f);
  EXPECT_EQ(aabb_min(s).y, -2.0f);
  EXPECT_EQ(mesh_bounds(MeshData{}).half_extents, (vec3{0, 0, 0}));
}

TEST(MeshBounds, ContainsReferencedVerticesExactlyAndIsTight) {
  SplitMix64 rng(0xB0B5);
  for (int trial = 0; trial < 400; ++trial) {
    MeshData m;
    const int nv = 3 + int(rng.next() % 40);
    // Magnitudes from 1e-6 to 1e37 (1e34 and an offset up to 1e3 times that), centred anywhere: rounding of the
    // midpoint matters.
    const double scale = std::pow(10.0, -6.0 + 40.0 * rng.u());
    const double offset = (rng.u() - 0.5) * scale * (rng.next() % 2 ? 1e3 : 0.0);
    for (int v = 0; v < nv; ++v) {
      vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = float(offset + (rng.u() - 0.5) * scale);
      m.add_vertex(p);
    }
    for (int t = 0; t < 1 + int(rng.next() % 10); ++t)
      m.add_triangle(uint32_t(rng.next() % uint64_t(nv - 1)), uint32_t(rng.next() % uint64_t(nv - 1)),
                     uint32_t(rng.next() % uint64_t(nv - 1)));
    m.add_vertex({1e30f, -1e30f, 1e30f});  // the last vertex is never referenced
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (uint32_t i : m.indices)
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], double(m.vertex(i)[k])), hi[k] = std::max(hi[k], double(m.vertex(i)[k]));
    const AABB b = mesh_bounds(m);
    const vec3 bmin = aabb_min(b), bmax = aabb_max(b);
    for (int k = 0; k < 3; ++k) {
      // Exact containment in float, as documented.
      for (uint32_t i : m.indices) {
        ASSERT_LE(bmin[k], m.vertex(i)[k]) << trial;
        ASSERT_GE(bmax[k], m.vertex(i)[k]) << trial;
      }
      // Tight: within 4 ulp of the extreme coordinates.
      const double ulp = std::max(std::abs(lo[k]), std::abs(hi[k])) * 0x1p-23;
      EXPECT_LE(double(b.half_extents[k]), (hi[k] - lo[k]) / 2 + 4 * ulp) << trial;
      EXPECT_GE(double(bmin[k]), lo[k] - 4 * ulp) << trial;
      EXPECT_LE(double(bmax[k]), hi[k] + 4 * ulp) << trial;
    }
  }
}

TEST(MeshBounds, ExtremeCoordinatesStayFinite) {
  const float big = std::numeric_limits<float>::max();
  MeshData m;
  m.add_vertex({-big, big, 0}), m.add_vertex({big, big, -big}), m.add_vertex({0, big, big});
  m.add_triangle(0, 1, 2);
  const AABB b = mesh_bounds(m);
  EXPECT_TRUE(std::isfinite(b.half_extents.x) && std::isfinite(b.center.x));
  EXPECT_EQ(b.half_extents.x, big);
  EXPECT_EQ(b.center.y, big);
  EXPECT_EQ(b.half_extents.y, 0.0f);
}

// ------------------------------------------------------------------ is_closed

TEST(MeshClosed, GeneratorsAreClosedAndBreakingOneTriangleOpensThem) {
  std::vector<MeshData> solids = {make_box_mesh({1, 2, 3}),  make_box_mesh({0, 0, 0}),       make_sphere_mesh(1, 2, 3),
                                  make_sphere_mesh(1, 3, 4), make_sphere_mesh(2.5f, 16, 24), make_sphere_mesh(0, 5, 7)};
  for (std::size_t s = 0; s < solids.size(); ++s) {
    const MeshData& m = solids[s];
    ASSERT_TRUE(is_closed(m)) << s;
    for (std::size_t t = 0; t < m.triangle_count(); t += 1 + t / 8) {
      EXPECT_FALSE(is_closed(without(m, t))) << s << " " << t;
      EXPECT_FALSE(is_closed(flipped(m, t))) << s << " " << t;
    }
    // A third triangle on an edge, and every triangle flipped (still closed, inside out).
    MeshData extra = m;
    extra.add_triangle(m.indices[0], m.indices[1], m.indices[2]);
    EXPECT_FALSE(is_closed(extra)) << s;
    MeshData all_flipped = m;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) all_flipped = flipped(all_flipped, t);
    EXPECT_TRUE(is_closed(all_flipped)) << s;
  }
}

TEST(MeshClosed, OpenDegenerateAndInvalidMeshes) {
  EXPECT_FALSE(is_closed(make_grid_mesh(3, 2, 1.0f)));
  EXPECT_FALSE(is_closed(MeshData{}));
  MeshData pillow;  // two triangles back to back: every edge used once each way
  pillow.add_vertex({0, 0, 0}), pillow.add_vertex({1, 0, 0}), pillow.add_vertex({0, 1, 0});
  pillow.add_triangle(0, 1, 2), pillow.add_triangle(0, 2, 1);
  EXPECT_TRUE(is_closed(pillow));
  MeshData repeated = pillow;
  repeated.add_triangle(0, 0, 1), repeated.add_triangle(0, 1, 0);
  EXPECT_FALSE(is_closed(repeated));
  MeshData bad = pillow;
  bad.indices[0] = 3;
  EXPECT_FALSE(is_closed(bad));
  // Two disjoint boxes in one mesh.
  MeshData two = make_box_mesh({1, 1, 1});
  const MeshData other = make_box_mesh({2, 1, 1});
  for (std::size_t v = 0; v < other.vertex_count(); ++v) two.add_vertex(other.vertex(v) + vec3{10, 0, 0});
  for (uint32_t i : other.indices) two.indices.push_back(i + 8);
  EXPECT_TRUE(is_closed(two));
}

TEST(MeshClosed, MatchesBruteForceOnRandomMeshes) {
  SplitMix64 rng(77);
  const MeshData base = make_sphere_mesh(1, 4, 5);
  int closed = 0, open = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    MeshData m;
    switch (trial % 3) {
      case 0: {  // random triangles over few vertices
        const uint32_t nv = 3 + uint32_t(rng.next() % 5);
        for (uint32_t v = 0; v < nv; ++v) m.add_vertex({float(v), 0, 0});
        const int nt = 1 + int(rng.next() % 8);
        for (int t = 0; t < nt; ++t) {
          const uint32_t a = uint32_t(rng.next() % nv), b = uint32_t(rng.next() % nv), c = uint32_t(rng.next() % nv);
          m.add_triangle(a, b, c);
          if (rng.next() % 2) m.add_triangle(a, c, b);
        }
        break;
      }
      default: {  // a closed mesh with a few random edits
        m = base;
        const int edits = int(rng.next() % 3);
        for (int e = 0; e < edits; ++e) {
          const std::size_t t = rng.next() % m.triangle_count();
          switch (rng.next() % 4) {
            case 0:
              m = flipped(m, t);
              break;
            case 1:
              if (m.triangle_count() > 1) m = without(m, t);
              break;
            case 2:
              m.add_triangle(m.indices[3 * t], m.indices[3 * t + 2], m.indices[3 * t + 1]);
              break;
            default:
              m.indices[3 * t + rng.next() % 3] = uint32_t(rng.next() % m.vertex_count());
              break;
          }
        }
        // Rotating a triangle's corners changes nothing.
        const std::size_t t = rng.next() % m.triangle_count();
        std::rotate(m.indices.begin() + std::ptrdiff_t(3 * t), m.indices.begin() + std::ptrdiff_t(3 * t + 1),
                    m.indices.begin() + std::ptrdiff_t(3 * t + 3));
      }
    }
    const bool want = closed_reference(m);
    ASSERT_EQ(is_closed(m), want) << trial;
    (want ? closed : open)++;
  }
  std::printf("  is_closed vs brute force: %d closed, %d open, 0 mismatches\n", closed, open);
  EXPECT_GT(closed, 300);
  EXPECT_GT(open, 300);
}

// ------------------------------------------------------------------ generators

TEST(MeshGenerators, BoxHasOutwardFacesAreaAndVolume) {
  const vec3 h{0.5f, 2.0f, 1.25f};
  const MeshData m = make_box_mesh(h);
  ASSERT_EQ(m.vertex_count(), 8u);
  ASSERT_EQ(m.triangle_count(), 12u);
  for (std::size_t v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::abs(m.vertex(v)[k]), h[k]);
  int per_axis[3][2] = {};
  for (std::size_t t = 0; t < 12; ++t) {
    const Triangle tr = m.triangle(t);
    const D3 n = crossd(d3(tr.b) - d3(tr.a), d3(tr.c) - d3(tr.a));
    const D3 centroid = d3(tr.a) + d3(tr.b) + d3(tr.c);
    EXPECT_GT(dotd(n, centroid), 0.0) << t;  // outward
    // The normal is along one axis, on the side its corners are.
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if ((k == 0 ? n.x : k == 1 ? n.y : n.z) != 0) axis = axis == -1 ? k : 3;
    ASSERT_TRUE(axis >= 0 && axis < 3) << t;
    per_axis[axis][(axis == 0 ? n.x : axis == 1 ? n.y : n.z) > 0]++;
  }
  for (auto& a : per_axis) EXPECT_TRUE(a[0] == 2 && a[1] == 2);
  const double hx = h.x, hy = h.y, hz = h.z;
  EXPECT_DOUBLE_EQ(signed_volume(m), 8 * hx * hy * hz);
  EXPECT_DOUBLE_EQ(total_area(m), 8 * (hx * hy + hy * hz + hz * hx));
  EXPECT_TRUE(is_closed(m));
}

TEST(MeshGenerators, SphereCountsPositionsOrientationAndVolume) {
  for (auto [stacks, slices] : {std::pair{2, 3}, {3, 4}, {8, 12}, {32, 64}, {100, 7}}) {
    const float r = 1.75f;
    const MeshData m = make_sphere_mesh(r, stacks, slices);
    ASSERT_EQ(validate_mesh(m), Status::ok);
    ASSERT_EQ(m.vertex_count(), std::size_t(slices) * std::size_t(stacks - 1) + 2);
    ASSERT_EQ(m.triangle_count(), 2 * std::size_t(slices) * std::size_t(stacks - 1));
    EXPECT_EQ(m.vertex(0), (vec3{0, r, 0}));
    EXPECT_EQ(m.vertex(m.vertex_count() - 1), (vec3{0, -r, 0}));
    double worst_radius = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      const D3 p = d3(m.vertex(v));
      worst_radius = std::max(worst_radius, std::abs(std::sqrt(dotd(p, p)) - r) / r);
    }
    EXPECT_LT(worst_radius, 1e-6) << stacks << "x" << slices;
    // Every face turns outward (the origin is inside a convex polytope).
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const Triangle tr = m.triangle(t);
      const D3 n = crossd(d3(tr.b) - d3(tr.a), d3(tr.c) - d3(tr.a));
      ASSERT_GT(dotd(n, d3(tr.a) + d3(tr.b) + d3(tr.c)), 0.0) << stacks << "x" << slices << " t" << t;
    }
    // Against the same polytope built in binary64 from the documented formula: every
    // vertex within a few float roundings, and the volume to 1e-6.
    std::vector<D3> exact = {{0, r, 0}};
    for (int i = 1; i < stacks; ++i)
      for (int j = 0; j < slices; ++j) {
        const double t = kPiD * i / stacks, p = 2 * kPiD * j / slices;
        exact.push_back({r * std::sin(t) * std::cos(p), r * std::cos(t), r * std::sin(t) * std::sin(p)});
      }
    exact.push_back({0, -r, 0});
    double worst_position = 0, exact_volume = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      const D3 d = d3(m.vertex(v)) - exact[v];
      worst_position = std::max(worst_position, std::sqrt(dotd(d, d)) / r);
    }
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const uint32_t* c = &m.indices[3 * t];
      exact_volume += dotd(exact[c[0]], crossd(exact[c[1]], exact[c[2]])) / 6.0;
    }
    EXPECT_LT(worst_position, 1e-6) << stacks << "x" << slices;
    const double ball = 4.0 / 3.0 * kPiD * r * r * r, vol = signed_volume(m);
    EXPECT_NEAR(vol, exact_volume, 1e-6 * ball) << stacks << "x" << slices;
    // An inscribed polytope: below the ball, by O(1/stacks^2 + 1/slices^2) (the ring
    // polygons alone lose 1 - sin(2 pi / n) n / (2 pi) ~ (2/3) pi^2 / n^2).
    EXPECT_GT(vol, 0.0);
    EXPECT_LT(vol, ball);
    const double bound = (1.0 / (stacks * stacks) + 1.0 / (slices * slices)) * kPiD * kPiD;
    EXPECT_LT((ball - vol) / ball, bound) << stacks << "x" << slices;
    EXPECT_TRUE(is_closed(m));
  }
  // 32 x 64: the relative volume deficit printed for the record.
  const MeshData fine = make_sphere_mesh(1, 32, 64);
  std::printf("  sphere 32x64: volume %.6f vs 4pi/3 = %.6f (deficit %.3g)\n", signed_volume(fine), 4.0 / 3.0 * kPiD,
              1 - signed_volume(fine) / (4.0 / 3.0 * kPiD));
}

TEST(MeshGenerators, SphereOctahedronIsExactAndCallsAreBitIdentical) {
  // stacks 2, slices 4: the octahedron, every vertex on an axis up to sin/cos rounding.
  const MeshData m = make_sphere_mesh(1, 2, 4);
  EXPECT_NEAR(m.vertex(1).x, 1.0f, 1e-7f);
  EXPECT_NEAR(m.vertex(2).z, 1.0f, 1e-7f);
  EXPECT_NEAR(signed_volume(m), 4.0 / 3.0, 1e-6);
  EXPECT_TRUE(same_bits(make_sphere_mesh(3, 17, 23), make_sphere_mesh(3, 17, 23)));
}

TEST(MeshGenerators, BadArgumentsGiveAnEmptyMeshAndAReason) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (vec3 h : {vec3{-1, 1, 1}, vec3{1, nan, 1}, vec3{1, 1, inf}}) {
    detail::clear_error();
    EXPECT_EQ(make_box_mesh(h).vertex_count(), 0u);
    EXPECT_TRUE(has(last(), "make_box_mesh")) << last();
  }
  for (auto [r, st, sl] :
       {std::tuple{-1.0f, 4, 4}, {nan, 4, 4}, {1.0f, 1, 4}, {1.0f, 4, 2}, {1.0f, 4097, 4}, {1.0f, 4, 5000}}) {
    detail::clear_error();
    EXPECT_TRUE(make_sphere_mesh(r, st, sl).indices.empty());
    EXPECT_TRUE(has(last(), "make_sphere_mesh")) << last();
  }
  for (auto [cx, cz, size] :
       {std::tuple{0, 1, 1.0f}, {1, 0, 1.0f}, {16385, 1, 1.0f}, {1, 1, 0.0f}, {1, 1, -2.0f}, {1, 1, inf}}) {
    detail::clear_error();
    EXPECT_TRUE(make_grid_mesh(cx, cz, size).indices.empty());
    EXPECT_TRUE(has(last(), "make_grid_mesh")) << last();
  }
  detail::clear_error();
  const auto bad_height = [](float x, float, void*) { return x > 0 ? std::numeric_limits<float>::quiet_NaN() : 0.0f; };
  EXPECT_TRUE(make_grid_mesh(2, 2, 1, bad_height).indices.empty());
  EXPECT_TRUE(has(last(), "not finite")) << last();
}

TEST(MeshGenerators, GridLayoutSymmetryNormalsAndHeights) {
  const int cx = 5, cz = 3;
  const float size = 0.1f;
  const MeshData flat = make_grid_mesh(cx, cz, size);
  ASSERT_EQ(validate_mesh(flat), Status::ok);
  ASSERT_EQ(flat.vertex_count(), std::size_t((cx + 1) * (cz + 1)));
  ASSERT_EQ(flat.triangle_count(), std::size_t(2 * cx * cz));
  for (int j = 0; j <= cz; ++j)
    for (int i = 0; i <= cx; ++i) {
      const vec3 p = flat.vertex(std::size_t(j * (cx + 1) + i));
      EXPECT_EQ(p.x, (float(i) - 2.5f) * size);
      EXPECT_EQ(p.z, (float(j) - 1.5f) * size);
      EXPECT_EQ(p.y, 0.0f);
      // Mirror images are exact negatives.
      EXPECT_EQ(p.x, -flat.vertex(std::size_t(j * (cx + 1) + (cx - i))).x);
    }
  double area = 0;
  for (std::size_t t = 0; t < flat.triangle_count(); ++t) {
    const Triangle tr = flat.triangle(t);
    const D3 n = crossd(d3(tr.b) - d3(tr.a), d3(tr.c) - d3(tr.a));
    EXPECT_EQ(n.x, 0.0);
    EXPECT_EQ(n.z, 0.0);
    EXPECT_GT(n.y, 0.0) << t;  // up
    area += 0.5 * n.y;
  }
  EXPECT_NEAR(area, cx * cz * double(size) * double(size), 1e-6 * area);  // positions are rounded
  // Boundary edges (used once) are exactly the rim: 2 (cx + cz).
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (std::size_t t = 0; t < flat.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = flat.indices[3 * t + e], b = flat.indices[3 * t + (e + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  int rim = 0;
  for (const auto& [edge, n] : uses) {
    EXPECT_LE(n, 2);
    rim += n == 1;
  }
  EXPECT_EQ(rim, 2 * (cx + cz));

  struct Wave {
    float amplitude;
    int calls = 0;
  } wave{0.5f};
  const auto height = [](float x, float z, void* context) {
    auto* w = static_cast<Wave*>(context);
    ++w->calls;
    return w->amplitude * (x * x - z);
  };
  const MeshData hills = make_grid_mesh(cx, cz, size, height, &wave);
  EXPECT_EQ(wave.calls, (cx + 1) * (cz + 1));
  for (std::size_t v = 0; v < hills.vertex_count(); ++v) {
    EXPECT_EQ(hills.x[v], flat.x[v]);
    EXPECT_EQ(hills.y[v], 0.5f * (hills.x[v] * hills.x[v] - hills.z[v]));
  }
  EXPECT_EQ(hills.indices, flat.indices);
}

// ------------------------------------------------------------------ weld_vertices

TEST(MeshWeld, ExplodedMeshesWeldBackToTheOriginal) {
  for (const MeshData& m : {make_box_mesh({1, 2, 3}), make_sphere_mesh(1, 9, 13), make_grid_mesh(4, 6, 0.5f)}) {
    const MeshData e = exploded(m);
    ASSERT_FALSE(is_closed(e));
    const MeshData w = weld_vertices(e);
    ASSERT_EQ(validate_mesh(w), Status::ok);
    EXPECT_EQ(w.vertex_count(), m.vertex_count());
    ASSERT_EQ(w.triangle_count(), m.triangle_count());
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const Triangle a = w.triangle(t), b = m.triangle(t);
      ASSERT_TRUE(a.a == b.a && a.b == b.b && a.c == b.c) << t;
    }
    EXPECT_EQ(is_closed(w), is_closed(m));
    // Welding a welded mesh changes nothing.
    EXPECT_TRUE(same_bits(weld_vertices(w), w));
  }
}

TEST(MeshWeld, OrderSignedZeroAndUnreferencedVertices) {
  MeshData m;
  m.add_vertex({9, 9, 9});      // 0: unreferenced
  m.add_vertex({1, 0, 0});      // 1
  m.add_vertex({0, 0, 0});      // 2
  m.add_vertex({1, 0, 0});      // 3 = 1
  m.add_vertex({-0.0f, 0, 0});  // 4: bit-different from 2
  m.add_vertex({0, 1, 0});      // 5
  m.add_vertex({0, 0, 0});      // 6 = 2
  m.add_triangle(5, 3, 6);
  m.add_triangle(1, 2, 4);
  const MeshData w = weld_vertices(m);
  // Representatives in original order: 1, 2, 4, 5 -> 0, 1, 2, 3.
  ASSERT_EQ(w.vertex_count(), 4u);
  EXPECT_EQ(w.vertex(0), (vec3{1, 0, 0}));
  EXPECT_TRUE(std::signbit(w.x[2]));
  EXPECT_FALSE(std::signbit(w.x[1]));
  EXPECT_EQ(w.indices, (std::vector<uint32_t>{3, 0, 1, 0, 1, 2}));
  // A tolerance merges the zeros: 4 joins 2.
  const MeshData t = weld_vertices(m, 1e-6f);
  ASSERT_EQ(t.vertex_count(), 3u);
  EXPECT_EQ(t.indices, (std::vector<uint32_t>{2, 0, 1, 0, 1, 1}));
}

TEST(MeshWeld, BadInputGivesAnEmptyMesh) {
  const MeshData box = make_box_mesh({1, 1, 1});
  for (float tol : {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    detail::clear_error();
    EXPECT_EQ(weld_vertices(box, tol).vertex_count(), 0u);
    EXPECT_TRUE(has(last(), "tolerance")) << last();
  }
  MeshData bad = box;
  bad.indices[4] = 99;
  detail::clear_error();
  EXPECT_EQ(weld_vertices(bad).vertex_count(), 0u);
  EXPECT_TRUE(has(last(), "triangle 1")) << last();
}

// The documented greedy rule, by brute force: vertex v joins the lowest-index earlier
// representative within tolerance on every axis.
MeshData weld_reference(const MeshData& m, float tol) {
  std::vector<uint8_t> used(m.vertex_count(), 0);
  for (uint32_t i : m.indices) used[i] = 1;
  std::vector<uint32_t> reps, rep(m.vertex_count(), 0), out_index(m.vertex_count(), 0);
  MeshData out;
  for (uint32_t v = 0; v < m.vertex_count(); ++v) {
    if (!used[v]) continue;
    bool found = false;
    for (uint32_t r : reps)
      if (std::abs(m.x[v] - m.x[r]) <= tol && std::abs(m.y[v] - m.y[r]) <= tol && std::abs(m.z[v] - m.z[r]) <= tol) {
        rep[v] = r, found = true;
        break;
      }
    if (!found) {
      rep[v] = v, reps.push_back(v);
      out_index[v] = uint32_t(out.vertex_count());
      out.add_vertex(m.vertex(v));
    }
  }
  for (uint32_t i : m.indices) out.indices.push_back(out_index[rep[i]]);
  return out;
}

TEST(MeshWeld, ToleranceMatchesBruteForceGreedyReference) {
  SplitMix64 rng(2024);
  std::size_t merged = 0, total = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Points on a lattice of step tol / 4 (so |d| == tol ties happen), some far from the
    // origin, plus an exploded copy of each triangle's corners jittered along the lattice.
    const float tol = float(std::ldexp(1.0, int(rng.next() % 40) - 20));
    const float step = tol * 0.25f;
    const double far = (trial % 4 == 0) ? double(step) * double(1 << 20) : 0.0;
    MeshData m;
    const int nv = 30 + int(rng.next() % 200);
    for (int v = 0; v < nv; ++v) {
      vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = float(far + double(step) * double(int(rng.next() % 24) - 12));
      if (trial % 4 == 1 && v % 3 == 0) p.x = float(rng.u() * 4096.0);  // a tolerance far below the extent
      m.add_vertex(p);
    }
    for (int t = 0; t < nv; ++t)
      m.add_triangle(uint32_t(rng.next() % uint64_t(nv)), uint32_t(rng.next() % uint64_t(nv)),
                     uint32_t(rng.next() % uint64_t(nv)));
    const MeshData w = weld_vertices(m, tol);
    const MeshData ref = weld_reference(m, tol);
    ASSERT_EQ(validate_mesh(w), Status::ok) << trial;
    ASSERT_TRUE(same_bits(w, ref)) << trial << " tol " << tol << ": " << w.vertex_count() << " vs "
                                   << ref.vertex_count();
    // Stated invariants: each corner moved by at most tol per axis; outputs pairwise apart.
    for (std::size_t i = 0; i < m.indices.size(); ++i) {
      const vec3 d = abs(m.vertex(m.indices[i]) - w.vertex(w.indices[i]));
      ASSERT_TRUE(d.x <= tol && d.y <= tol && d.z <= tol) << trial;
    }
    for (std::size_t a = 0; a < w.vertex_count(); ++a)
      for (std::size_t b = a + 1; b < w.vertex_count(); ++b) {
        const vec3 d = abs(w.vertex(a) - w.vertex(b));
        ASSERT_FALSE(d.x <= tol && d.y <= tol && d.z <= tol) << trial << " " << a << " " << b;
      }
    merged += m.vertex_count() - w.vertex_count();
    total += m.vertex_count();
  }
  std::printf("  tolerance weld: %zu of %zu vertices merged or dropped, identical to brute force\n", merged, total);
  EXPECT_GT(merged, total / 4);
  // A tolerance above the extent merges every referenced vertex into the first one.
  const MeshData all = weld_vertices(make_sphere_mesh(1, 6, 7), 2.0f);
  EXPECT_EQ(all.vertex_count(), 1u);
  EXPECT_EQ(all.vertex(0), (vec3{0, 1, 0}));
  EXPECT_EQ(all.indices, std::vector<uint32_t>(all.indices.size(), 0u));
}

}  // namespace
}  // namespace gyro
