// TriangleMesh queries against brute force: the BVH raycast must give exactly the answer of
// the brute-force batch kernel over the same triangles (same t bits, same triangle), at every
// SIMD level and thread count; overlaps and linetests must agree with looping over every
// triangle with gyro/triangle.hpp's tests.
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"
#include "gyro/triangle.hpp"
#include "gyro/triangle_mesh.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace gyro {
namespace {

using testing::HitSet;
using testing::RaySet;
using testing::SplitMix64;

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

// Triangles of a mesh expanded to SoA, for the brute-force kernel.
struct Soup {
  std::vector<float> c[9];
  explicit Soup(const MeshData& m) {
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const Triangle tri = m.triangle(t);
      const vec3 p[3] = {tri.a, tri.b, tri.c};
      for (int k = 0; k < 3; ++k) c[3 * k].push_back(p[k].x), c[3 * k + 1].push_back(p[k].y), c[3 * k + 2].push_back(p[k].z);
    }
  }
  ShapeArray view() const {
    return shape_array(TrianglesView{c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(), c[5].data(),
                                     c[6].data(), c[7].data(), c[8].data()});
  }
};

// A height field on a grid (shared edges and vertices, as R2), scaled and moved.
MeshData grid_mesh(int n, float scale, vec3 offset, SplitMix64& rng) {
  MeshData m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.add_vertex(vec3{float(i), float(0.3 * rng.u()), float(j)} * scale + offset);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      m.add_triangle(a, c, b);
      m.add_triangle(b, c, d);
    }
  return m;
}

// Random triangles of mixed sizes (some degenerate, some huge) in a cube.
MeshData soup_mesh(std::size_t n, SplitMix64& rng) {
  MeshData m;
  for (std::size_t t = 0; t < n; ++t) {
    const vec3 c{float(10 * rng.u()), float(10 * rng.u()), float(10 * rng.u())};
    const float s = t % 50 == 0 ? 5.0f : float(0.02 + 0.5 * rng.u());
    const uint32_t v = uint32_t(m.vertex_count());
    for (int k = 0; k < 3; ++k) m.add_vertex(c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * s);
    if (t % 97 == 0) m.x[v + 2] = m.x[v], m.y[v + 2] = m.y[v], m.z[v + 2] = m.z[v];  // degenerate: a segment
    m.add_triangle(v, v + 1, v + 2);
  }
  return m;
}

// Rays of every kind: random, axis-parallel (zero direction components), aimed at vertices
// and edge midpoints, starting on the surface, and with finite [tmin, tmax] windows. With
// `origin`, every ray starts there (a lidar's or a camera's rays, which the batch walks in
// packets), sorted by the signs of their directions so that most groups of eight share
// them (the groups that do not walk ray by ray: both paths are tested).
RaySet rays_for(const MeshData& m, std::size_t n, SplitMix64& rng, std::vector<float>& tmin, std::vector<float>& tmax,
                const vec3* origin = nullptr) {
  RaySet r;
  const AABB box = aabb_from_min_max({*std::min_element(m.x.begin(), m.x.end()), *std::min_element(m.y.begin(), m.y.end()),
                                      *std::min_element(m.z.begin(), m.z.end())},
                                     {*std::max_element(m.x.begin(), m.x.end()), *std::max_element(m.y.begin(), m.y.end()),
                                      *std::max_element(m.z.begin(), m.z.end())});
  const vec3 lo = aabb_min(box) - box.half_extents * 0.5f, size = box.half_extents * 3.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const vec3 o = lo + vec3{float(rng.u()) * size.x, float(rng.u()) * size.y, float(rng.u()) * size.z};
    vec3 d{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
    const std::size_t kind = i % 6;
    if (kind == 1) {  // at a vertex
      const std::size_t v = std::size_t(rng.next() % m.vertex_count());
      d = m.vertex(v) - o;
    } else if (kind == 2) {  // at an edge midpoint
      const Triangle t = m.triangle(std::size_t(rng.next() % m.triangle_count()));
      d = (t.a + t.b) * 0.5f - o;
    } else if (kind == 3) {  // axis-parallel
      const int axis = int(rng.next() % 3);
      d = vec3{0.0f, 0.0f, 0.0f};
      (axis == 0 ? d.x : axis == 1 ? d.y : d.z) = rng.u() < 0.5 ? -1.0f : 1.0f;
    }
    vec3 start = o;
    if (kind == 4) start = m.vertex(std::size_t(rng.next() % m.vertex_count()));  // on the surface
    if (origin) {
      if (kind == 1 || kind == 2) d = d + (o - *origin);  // still aimed at the vertex or edge
      start = *origin;
    }
    r.push(start.x, start.y, start.z, d.x, d.y, d.z);
    const bool window = i % 5 == 0;
    tmin.push_back(window ? float(0.3 * rng.u()) : 0.0f);
    tmax.push_back(window ? float(0.5 + rng.u()) : INFINITY);
  }
  if (origin) {
    const auto signs = [&](std::size_t i) { return (r.dx[i] < 0) | (r.dy[i] < 0) << 1 | (r.dz[i] < 0) << 2; };
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return signs(x) < signs(y); });
    RaySet sorted;
    std::vector<float> t0, t1;
    for (std::size_t i : order)
      sorted.push(r.ox[i], r.oy[i], r.oz[i], r.dx[i], r.dy[i], r.dz[i]), t0.push_back(tmin[i]), t1.push_back(tmax[i]);
    r = sorted, tmin = t0, tmax = t1;
  }
  return r;
}

void expect_matches_brute_force(const MeshData& m, std::size_t nrays, uint64_t seed, double min_hit_fraction = 0.1,
                                const vec3* origin = nullptr) {
  SplitMix64 rng(seed);
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(m, mesh), Status::ok);
  const Soup soup(m);
  std::vector<float> tmin, tmax;
  RaySet rays = rays_for(m, nrays, rng, tmin, tmax, origin);
  RaysView view = rays.view();
  view.tmin = tmin.data(), view.tmax = tmax.data();
  HitSet want(nrays);
  set_simd_level(SimdLevel::automatic);
  ASSERT_EQ(raycast_closest(view, nrays, soup.view(), m.triangle_count(), want.out()), Status::ok);
  // A zero direction (a ray aimed at its own origin) misses for brute force and is flagged
  // invalid by the mesh query.
  for (std::size_t i = 0; i < nrays; ++i)
    if (rays.dx[i] == 0.0f && rays.dy[i] == 0.0f && rays.dz[i] == 0.0f) want.primitive[i] = kRayInvalid;
  std::size_t hits = 0;
  for (int32_t p : want.primitive) hits += p >= 0;
  EXPECT_GE(double(hits), min_hit_fraction * double(nrays)) << "too few hits to be a test";
  for (uint32_t v = 1; v <= 5; ++v) {
    if (!simd_level_available(SimdLevel(v))) continue;
    set_simd_level(SimdLevel(v));
    for (uint32_t threads : {1u, 3u}) {
      set_thread_count(threads);
      HitSet got(nrays);
      ASSERT_EQ(raycast_closest(mesh, view, nrays, got.out()), Status::ok);
      std::size_t bad = 0;
      for (std::size_t i = 0; i < nrays; ++i) {
        if (got.primitive[i] == want.primitive[i] && bits(got.t[i]) == bits(want.t[i]) &&
            bits(got.nx[i]) == bits(want.nx[i]) && bits(got.ny[i]) == bits(want.ny[i]) && bits(got.nz[i]) == bits(want.nz[i]))
          continue;
        if (++bad <= 5)
          ADD_FAILURE() << simd_level_name(SimdLevel(v)) << " ray " << i << ": bvh " << got.primitive[i] << " t "
                        << got.t[i] << ", brute force " << want.primitive[i] << " t " << want.t[i];
      }
      EXPECT_EQ(bad, 0u) << "of " << nrays << " rays, " << simd_level_name(SimdLevel(v)) << ", threads " << threads;
      // Any hit: hit exactly when brute force hits, and the triangle reported is hit at t.
      ASSERT_EQ(raycast_any(mesh, view, nrays, got.out(false)), Status::ok);
      for (std::size_t i = 0; i < nrays; ++i) {
        ASSERT_EQ(got.primitive[i] >= 0, want.primitive[i] >= 0) << "any-hit ray " << i;
        if (want.primitive[i] == kRayInvalid) {
          ASSERT_EQ(got.primitive[i], kRayInvalid);
        }
        if (got.primitive[i] < 0) continue;
        const Triangle tri = m.triangle(std::size_t(got.primitive[i]));
        const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
        const RaycastResult r = raycast(tri, ray);
        ASSERT_TRUE(r.hit && bits(r.t) == bits(got.t[i])) << "any-hit ray " << i;
      }
    }
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);
}

TEST(TriangleMesh, GridRaycastsEqualBruteForceAtEveryLevel) {
  SplitMix64 rng(11);
  expect_matches_brute_force(grid_mesh(40, 0.25f, {1.0f, -2.0f, 3.0f}, rng), 6000, 12);
}

TEST(TriangleMesh, SoupRaycastsEqualBruteForceAtEveryLevel) {
  SplitMix64 rng(21);
  expect_matches_brute_force(soup_mesh(3000, rng), 6000, 22);
}

// Rays from one origin (above the grid, inside the soup) walk in packets of eight.
TEST(TriangleMesh, SliverRaycastsEqualBruteForceAtEveryLevel) {
  SplitMix64 rng(25);
  const MeshData m = sliver_mesh(3000, rng, 10.0f, 2.0f);
  expect_matches_brute_force(m, 6000, 26, 0.01);
  const vec3 inside{5.0f, 5.0f, 5.0f};
  expect_matches_brute_force(m, 6000, 27, 0.01, &inside);
}

TEST(TriangleMesh, OneOriginRaysEqualBruteForceAtEveryLevel) {
  SplitMix64 rng(13);
  const vec3 above{6.0f, 1.5f, 8.0f}, inside{5.0f, 5.0f, 5.0f};
  expect_matches_brute_force(grid_mesh(40, 0.25f, {1.0f, -2.0f, 3.0f}, rng), 6000, 14, 0.1, &above);
  expect_matches_brute_force(soup_mesh(3000, rng), 6000, 15, 0.1, &inside);
}

TEST(TriangleMesh, TinyAndHugeAndFarScalesEqualBruteForce) {
  for (float scale : {1e-4f, 1e3f}) {
    SplitMix64 rng(31);
    expect_matches_brute_force(grid_mesh(20, scale, {1e4f, 5e3f, -2e4f}, rng), 3000, 32);
  }
}

TEST(TriangleMesh, SingleTriangleAndFewTriangles) {
  // Triangle 0 of a soup is a degenerate segment, which few rays hit.
  for (std::size_t n : {1u, 2u, 4u, 5u, 17u}) {
    SplitMix64 rng(40 + n);
    expect_matches_brute_force(soup_mesh(n, rng), 3000, 41, n == 1 ? 0.0 : 0.01);
  }
}

TEST(TriangleMesh, ScalarRaycastEqualsBatch) {
  SplitMix64 rng(51);
  const MeshData m = grid_mesh(16, 1.0f, {0.0f, 0.0f, 0.0f}, rng);
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(m, mesh), Status::ok);
  std::vector<float> tmin, tmax;
  const RaySet rays = rays_for(m, 2000, rng, tmin, tmax);
  HitSet got(rays.size());
  std::vector<float> u(rays.size()), v(rays.size());
  HitsOut out = got.out();
  out.u = u.data(), out.v = v.data();
  ASSERT_EQ(raycast_closest(mesh, rays.view(), rays.size(), out), Status::ok);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
    const MeshHit h = raycast(mesh, ray);
    ASSERT_EQ(h.hit.hit, got.primitive[i] >= 0) << i;
    EXPECT_EQ(raycast_any(mesh, ray), h.hit.hit) << i;
    if (!h.hit.hit) continue;
    EXPECT_EQ(h.triangle, uint32_t(got.primitive[i]));
    EXPECT_EQ(bits(h.hit.t), bits(got.t[i]));
    EXPECT_EQ(bits(h.hit.normal.y), bits(got.ny[i]));
    EXPECT_EQ(bits(h.u), bits(u[i]));
    EXPECT_EQ(bits(h.v), bits(v[i]));
    // The barycentric weights reproduce the hit point.
    const Triangle t = m.triangle(h.triangle);
    const vec3 p = t.a * (1.0f - h.u - h.v) + t.b * h.u + t.c * h.v;
    EXPECT_NEAR(p.x, h.hit.point.x, 1e-4f);
    EXPECT_NEAR(p.z, h.hit.point.z, 1e-4f);
  }
}

// A closed mesh (the surface of a cube, each face an n x n grid sharing its border vertices
// with the next face): rays from inside towards vertices and edge midpoints must all hit.
TEST(TriangleMesh, ClosedMeshIsWatertightForRaysThroughVerticesAndEdges) {
  const int n = 12;
  MeshData m;
  auto vertex_id = [&](vec3 p) {
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
      if (m.vertex(v) == p) return uint32_t(v);
    m.add_vertex(p);
    return uint32_t(m.vertex_count() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f})
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          auto at = [&](int a, int b) {
            float c[3];
            c[axis] = side;
            c[(axis + 1) % 3] = -1.0f + 2.0f * float(a) / n;
            c[(axis + 2) % 3] = -1.0f + 2.0f * float(b) / n;
            return vertex_id({c[0], c[1], c[2]});
          };
          const uint32_t p = at(i, j), q = at(i + 1, j), r = at(i, j + 1), s = at(i + 1, j + 1);
          m.add_triangle(p, q, s);
          m.add_triangle(p, s, r);
        }
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(m, mesh), Status::ok);
  RaySet rays;
  SplitMix64 rng(61);
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    for (int k = 0; k < 20; ++k) {
      const vec3 o{float(0.9 * (2 * rng.u() - 1)), float(0.9 * (2 * rng.u() - 1)), float(0.9 * (2 * rng.u() - 1))};
      const vec3 target = k % 2 ? m.vertex(v) : (m.vertex(v) + m.vertex(m.indices[(3 * (v % m.triangle_count())) + 1])) * 0.5f;
      const vec3 d = target - o;
      rays.push(o.x, o.y, o.z, d.x, d.y, d.z);
    }
  HitSet got(rays.size());
  ASSERT_EQ(raycast_closest(mesh, rays.view(), rays.size(), got.out(false)), Status::ok);
  std::size_t missed = 0;
  for (int32_t p : got.primitive) missed += p < 0;
  EXPECT_EQ(missed, 0u) << "of " << rays.size() << " rays from inside a closed mesh";
}

TEST(TriangleMesh, OverlapsAndLinetestsEqualBruteForce) {
  SplitMix64 rng(71);
  const MeshData m = soup_mesh(600, rng);
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(m, mesh), Status::ok);
  std::size_t positives[5] = {}, negatives[5] = {};
  for (int q = 0; q < 1200; ++q) {
    const vec3 c{float(12 * rng.u() - 1), float(12 * rng.u() - 1), float(12 * rng.u() - 1)};
    const float s = float(0.05 + 0.6 * rng.u());
    const Sphere sphere{c, s};
    const AABB box{c, {s, float(0.5 * s), float(0.8 * s)}};
    const OBB obb{c, {s, float(0.3 * s), float(0.6 * s)}, mat3{{{0.6f, 0.8f, 0.0f}, {-0.8f, 0.6f, 0.0f}, {0.0f, 0.0f, 1.0f}}}};
    const Triangle tri{c, c + vec3{3 * s, 0.0f, 0.0f}, c + vec3{0.0f, 3 * s, 1.5f * s}};
    const Line line{c, c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * 3.0f};
    bool want[5] = {false, false, false, false, false};
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const Triangle mt = m.triangle(t);
      want[0] = want[0] || overlaps(mt, sphere);
      want[1] = want[1] || overlaps(mt, box);
      want[2] = want[2] || overlaps(mt, obb);
      want[3] = want[3] || overlaps(mt, tri);
      want[4] = want[4] || linetest(mt, line);
    }
    const bool got[5] = {overlaps(mesh, sphere), overlaps(mesh, box), overlaps(mesh, obb), overlaps(mesh, tri),
                         linetest(mesh, line)};
    for (int k = 0; k < 5; ++k) {
      ASSERT_EQ(got[k], want[k]) << "query kind " << k << ", case " << q;
      (want[k] ? positives : negatives)[k]++;
    }
  }
  for (int k = 0; k < 5; ++k) EXPECT_GT(positives[k], 15u) << "kind " << k;
  for (int k = 0; k < 5; ++k) EXPECT_GT(negatives[k], 100u) << "kind " << k;
  // A zero-length segment is its point.
  const Triangle t0 = m.triangle(0);
  const vec3 p = (t0.a + t0.b + t0.c) * (1.0f / 3.0f);
  EXPECT_TRUE(linetest(mesh, Line{p, p}));
}

TEST(TriangleMesh, BadMeshesAreRejectedAndLeaveTheOutputUnchanged) {
  SplitMix64 rng(81);
  const MeshData good = soup_mesh(10, rng);
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(good, mesh), Status::ok);
  const std::size_t before = mesh.triangle_count();
  MeshData nan = good;
  nan.y[3] = NAN;
  EXPECT_EQ(TriangleMesh::create(nan, mesh), Status::non_finite);
  MeshData inf = good;
  inf.z[0] = -INFINITY;
  EXPECT_EQ(TriangleMesh::create(inf, mesh), Status::non_finite);
  MeshData range = good;
  range.indices[7] = uint32_t(range.vertex_count());
  EXPECT_EQ(TriangleMesh::create(range, mesh), Status::invalid_argument);
  EXPECT_NE(std::strstr(last_error(), "triangle 2"), nullptr) << last_error();
  MeshData ragged = good;
  ragged.indices.pop_back();
  EXPECT_EQ(TriangleMesh::create(ragged, mesh), Status::invalid_count);
  MeshData sizes = good;
  sizes.z.pop_back();
  EXPECT_EQ(TriangleMesh::create(sizes, mesh), Status::invalid_count);
  EXPECT_EQ(TriangleMesh::create(MeshData{}, mesh), Status::invalid_count);
  EXPECT_EQ(mesh.triangle_count(), before);

  // Batch calls: an empty mesh and bad rays get a status and write nothing.
  TriangleMesh none;
  RaySet rays;
  rays.push(0, 0, 0, 0, 1, 0);
  rays.push(0, 0, 0, NAN, 1, 0);
  HitSet h(2);
  h.t.assign(2, 42.0f);
  EXPECT_EQ(raycast_closest(none, rays.view(), 1, h.out()), Status::invalid_argument);
  EXPECT_EQ(raycast_any(mesh, rays.view(), std::size_t(1) << 31, h.out()), Status::invalid_count);
  RaysView no_dz = rays.view();
  no_dz.dz = nullptr;
  EXPECT_EQ(raycast_closest(mesh, no_dz, 2, h.out()), Status::null_argument);
  EXPECT_EQ(h.t[0], 42.0f);
  EXPECT_EQ(h.t[1], 42.0f);
  // Bad ray values are flagged per ray; the good rays are answered.
  RaySet mixed;
  const float fnan = NAN, finf = INFINITY;
  const float bad[][6] = {{fnan, 0, 0, 0, 1, 0}, {0, 0, finf, 0, 1, 0}, {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, -finf, 0},
                          {0, 0, 0, fnan, 1, 0}};
  for (const auto& r : bad) mixed.push(r[0], r[1], r[2], r[3], r[4], r[5]);
  const Triangle t0 = good.triangle(1);
  const vec3 target = (t0.a + t0.b + t0.c) * (1.0f / 3.0f);
  mixed.push(target.x, target.y + 5.0f, target.z, 0.0f, -1.0f, 0.0f);
  std::vector<float> tmin(mixed.size(), 0.0f), tmax(mixed.size(), finf);
  RaysView mv = mixed.view();
  mv.tmin = tmin.data(), mv.tmax = tmax.data();
  for (int window = 0; window < 3; ++window) {
    tmin[5] = window == 1 ? fnan : 0.0f;
    tmax[5] = window == 2 ? -1.0f : finf;
    HitSet hm(mixed.size());
    ASSERT_EQ(raycast_closest(mesh, mv, mixed.size(), hm.out()), Status::ok);
    for (std::size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(hm.primitive[i], kRayInvalid) << i;
      EXPECT_EQ(hm.t[i], finf);
      EXPECT_EQ(hm.ny[i], 0.0f);
    }
    if (window == 0) EXPECT_GE(hm.primitive[5], 0);
    else EXPECT_EQ(hm.primitive[5], kRayInvalid);
  }
  EXPECT_FALSE(raycast(none, Ray{}).hit.hit);
  EXPECT_FALSE(overlaps(none, Sphere{}));
}

TEST(TriangleMesh, BuildIsDeterministicAndBoundsTheMesh) {
  SplitMix64 rng(91);
  const MeshData m = soup_mesh(5000, rng);
  TriangleMesh a, b;
  ASSERT_EQ(TriangleMesh::create(m, a), Status::ok);
  ASSERT_EQ(TriangleMesh::create(m, b), Status::ok);
  const BvhStats sa = a.stats(), sb = b.stats();
  EXPECT_EQ(sa.nodes, sb.nodes);
  EXPECT_EQ(sa.leaves, sb.leaves);
  EXPECT_EQ(sa.sah_cost, sb.sah_cost);
  EXPECT_GE(sa.leaves * 4, m.triangle_count());
  EXPECT_LE(sa.max_depth, 40u);
  EXPECT_GT(sa.sah_cost, 1.0);
  const AABB box = a.bounds();
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const vec3 p = m.vertex(v);
    ASSERT_TRUE(std::abs(p.x - box.center.x) <= box.half_extents.x * 1.000001f + 1e-6f);
  }
}

}  // namespace
}  // namespace gyro
