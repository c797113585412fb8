#include "determinism.hpp"

#include "core/state_hash.hpp"
#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"
#include "gyro/math.hpp"
#include "math/trig_batch.hpp"
#include "random_shapes.hpp"
#if defined(GYRO_HAS_SPATIAL)
#include "gyro/camera.hpp"
#include "gyro/frustum.hpp"
#include "gyro/mesh.hpp"
#include "gyro/scene.hpp"
#include "gyro/triangle.hpp"
#include "gyro/triangle_mesh.hpp"
#include "spatial/bvh.hpp"
#endif
#include "workloads.hpp"
#if defined(GYRO_HAS_DYNAMICS)
#include "gyro/convex.hpp"
#include "gyro/particles.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/world.hpp"
#include "mixed_world.hpp"
#endif

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace gyro::testing {
namespace {

// Every trig function over arguments that cover reduction boundaries, the polynomial
// ranges, special values and large inputs.
uint64_t scene_trig() {
  std::vector<float> x, y;
  for (int i = -20000; i <= 20000; ++i) x.push_back(static_cast<float>(i) * 0.000314159f);  // [-6.3, 6.3]
  for (int i = -4000; i <= 4000; ++i) x.push_back(static_cast<float>(i) * 1.37f);          // large angles
  for (int i = -2000; i <= 2000; ++i) x.push_back(static_cast<float>(i) / 2000.0f);        // asin/acos domain
  const float specials[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1e-45f, 3.0e38f, -3.0e38f, __builtin_inff(),
                            -__builtin_inff(), __builtin_nanf(""), 0.5f, -0.5f, 1.0f, -1.0f, 1.0000001f,
                            0.41421356f, 2.4142137f, 1.5707964f, 3.1415927f, 12582912.0f};
  for (float s : specials) x.push_back(s);
  SplitMix64 rng(7);
  for (int i = 0; i < 20000; ++i) x.push_back(static_cast<float>((rng.u() - 0.5) * 200.0));
  y.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[(i * 7919) % x.size()];
  std::vector<float> out(x.size());
  detail::StateHasher h;
  for (uint32_t op = 0; op <= static_cast<uint32_t>(TrigOp::atan2); ++op) {
    const TrigBatchArgs args{static_cast<TrigOp>(op), x.data(), y.data(), out.data()};
    GYRO_DISPATCH(trig_batch)(args, 0, x.size());
    h.add_floats(out);
  }
  return h.digest();
}

// The first 2,000 rays of R1 against the 10,000 R1 spheres (closest hit and normals).
uint64_t scene_r1s_2k() {
  static const SphereSet spheres = r1_spheres();
  static const RaySet rays = r1_rays(2000);
  HitSet hits(rays.size());
  if (raycast_spheres_closest(rays.view(), rays.size(), spheres.view(), spheres.size(), hits.out()) != Status::ok)
    return 0;
  detail::StateHasher h;
  h.add_floats(hits.t);
  h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz);
  for (int32_t p : hits.primitive) h.add_u32(static_cast<uint32_t>(p));
  return h.digest();
}

// Rays that start on, inside and tangent to spheres, parallel and degenerate directions.
uint64_t scene_rays_edge_cases() {
  SphereSet s;
  const float sph[][4] = {{0, 0, 0, 1}, {3, 0, 0, 0.5f}, {0, 5, 0, 0}, {1e4f, 1e4f, 1e4f, 2}, {-2, -2, -2, 1e-3f}};
  for (auto& v : sph) s.cx.push_back(v[0]), s.cy.push_back(v[1]), s.cz.push_back(v[2]), s.r.push_back(v[3]);
  RaySet r;
  const float rays[][6] = {{-5, 0, 0, 1, 0, 0},  {0, 0, 0, 1, 0, 0},   {1, 0, 0, 1, 0, 0},  {-5, 1, 0, 1, 0, 0},
                           {0, 5, -3, 0, 0, 1}, {0, 0, 0, 0, 0, 0},   {0, 0, 0, 1e-20f, 0, 0},
                           {-5, 0, 0, 1e3f, 0, 0}, {0, 0, 0, 0.577f, 0.577f, 0.577f}, {-2, -2, -3, 0, 0, 1}};
  for (auto& v : rays) r.push(v[0], v[1], v[2], v[3], v[4], v[5]);
  HitSet hits(r.size());
  if (raycast_spheres_closest(r.view(), r.size(), s.view(), s.size(), hits.out()) != Status::ok) return 0;
  detail::StateHasher h;
  h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz);
  for (int32_t p : hits.primitive) h.add_u32(static_cast<uint32_t>(p));
  return h.digest();
}

// The public math library (include/gyro/math*.hpp, Cookbook chapters 1-3) over seeded
// inputs: inverses, products, determinants, adjugates, quaternion products, slerp, to_mat3,
// integration, transforms, view and projection matrices, angles. Header-only inline code
// is compiled into each caller, so this pins what every compiler makes of it.
uint64_t scene_math_library() {
  SplitMix64 rng(0x6d617468);  // "math"
  const auto f = [&rng](double lo, double hi) { return static_cast<float>(lo + (hi - lo) * rng.u()); };
  const auto v3 = [&f](double r) { return vec3{f(-r, r), f(-r, r), f(-r, r)}; };
  detail::StateHasher h;
  const auto add = [&h](const auto& m) {
    h.add_floats(std::span<const float>(reinterpret_cast<const float*>(&m), sizeof(m) / sizeof(float)));
  };
  for (int i = 0; i < 256; ++i) {
    const vec3 s{f(0.1, 10), f(0.1, 10), f(0.1, 10)}, euler = v3(4), t = v3(1000), axis = v3(1);
    const float a = f(-7, 7);
    const mat4 trs = transform(s, euler, t);
    mat4 inv = mat4::zero();
    h.add_u32(inverse(trs, &inv));
    add(inv), add(trs * inv), h.add_float(determinant(trs));
    const mat4 rigid = rotation_axis_angle(axis, a) * translation(t);
    add(inverse_rigid(rigid)), add(transform(s, axis, a, t));
    mat4 g;
    for (int k = 0; k < 16; ++k) g.data()[k] = f(-2, 2);
    if (i % 8 == 0)
      for (int k = 0; k < 4; ++k) g.m[3][k] = g.m[0][k] * 0.5f + g.m[1][k] * 1.5f;  // nearly singular
    mat4 ginv = mat4::zero();
    h.add_u32(inverse(g, &ginv));
    add(ginv), h.add_float(determinant(g)), add(adjugate(g)), add(g * trs);
    mat3 g3 = to_mat3(g), g3inv;
    h.add_u32(inverse(g3, &g3inv));
    add(g3inv), add(minors(g3)), h.add_float(determinant(mat2{{{g3.m[0][0], g3.m[0][1]}, {g3.m[1][0], g3.m[1][1]}}}));
    const quat qa = from_axis_angle(axis, a), qb = from_euler(euler.x, euler.y, euler.z);
    const float t0 = f(0, 1), t1 = f(0, 1);
    add(qa * qb), add(slerp(qa, qb, t0)), add(nlerp(qa, qb, t1)), add(to_mat3(qa * qb));
    add(slerp(qa, from_axis_angle(axis, a + 0.01f), 0.25f)), add(inverse(qb * 3.0f));
    const vec3 omega = v3(10);
    add(integrate(qa, omega, 1.0f / 60.0f)), add(rotate(qb, t)), add(transform(s, qb, t));
    add(rotation_euler(euler.x, euler.y, euler.z)), add(rotation3_axis_angle(axis, a));
    const vec3 eye = v3(100), target = v3(100), up = v3(1);
    add(look_at(eye, target, up)), add(look_at_rh(eye, target, up));
    // One draw per declarator: the order of arguments in a call is unspecified in C++.
    const float n = f(0.01, 1), fa = n * f(10, 1e4), fov = f(0.3, 2.5), aspect = f(0.5, 2.5);
    const float l = -f(1, 50), r = f(1, 50), b = -f(1, 50), tp = f(1, 50);
    const mat4 proj = perspective(fov, aspect, n, fa), proj_rh = perspective_rh(1.0f, 1.5f, n, fa);
    add(proj), add(proj_rh), add(vec4{t.x, t.y, t.z, 1.0f} * proj);
    add(orthographic(l, r, b, tp, n, fa)), add(orthographic_rh(-8, 8, -4.5f, 4.5f, n, fa));
    add(multiply_point(eye, look_at(eye, target, up) * proj)), add(multiply_vector(axis, trs));
    const vec3 p = v3(50), d = v3(50);
    h.add_float(angle(p, d)), h.add_float(angle(p, cross(p, d))), add(normalized(d * 1e-30f)), add(normalized(p));
    add(project(p, d)), add(perpendicular(p, d)), add(reflect(p, normalized(d))), h.add_float(distance(p, d));
  }
  return h.digest();
}

// The first 30,000 N1 box pairs: verdicts, separations, and one against many, with a few
// invalid inputs flagged.
uint64_t scene_n1_overlap() {
  static const BoxPairs clean = n1_pairs(30000);
  BoxPairs p = clean;
  p.a.cx[5] = __builtin_nanf(""), p.b.hz[9] = -1.0f, p.a.r[2][77] = __builtin_inff();
  const std::size_t n = p.a.size();
  std::vector<uint32_t> out(n), one(n);
  std::vector<float> sep(n);
  if (overlap_pairwise(shape_array(p.a.view()), shape_array(p.b.view()), n, out.data()) != Status::ok) return 0;
  if (overlap_one_against_many(shape_array(clean.b.view()), shape_array(clean.a.view()), n, one.data()) != Status::ok) return 0;
  if (obb_separation_pairwise(clean.a.view(), clean.b.view(), n, sep.data()) != Status::ok) return 0;
  detail::StateHasher h;
  h.add_u32s(out), h.add_u32s(one), h.add_floats(sep);
  return h.digest();
}

// Random shapes of every type (tests/support/random_shapes: only sqrt, so the inputs are
// the same bits on every libm), all 15 overlap pair types, and raycasts (closest and any
// hit, normals and barycentrics) against every primitive type.
uint64_t scene_geometry_batch() {
  const std::size_t n = 2003, rays_n = 997, prims_n = 211;
  static const auto shapes = [](std::size_t count, uint64_t seed) {
    std::vector<RandomShapes> all;
    SplitMix64 rng(seed);
    for (uint32_t t = 1; t <= 5; ++t) all.push_back(random_shapes(ShapeType(t), count, rng, 8.0f));
    return all;
  };
  static const std::vector<RandomShapes> a = shapes(n, 11), b = shapes(n, 12), p = shapes(prims_n, 13);
  static const RaySet rays = [] {
    RaySet r;
    SplitMix64 rng(14);
    for (std::size_t i = 0; i < rays_n; ++i) {
      const float o[3] = {float(10 * rng.u() - 1), float(10 * rng.u() - 1), float(10 * rng.u() - 1)};
      const float d[3] = {float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
      r.push(o[0], o[1], o[2], d[0], d[1], d[2]);
    }
    return r;
  }();
  detail::StateHasher h;
  std::vector<uint32_t> out(n);
  for (uint32_t ta = 1; ta <= 5; ++ta)
    for (uint32_t tb = ta; tb <= 5; ++tb) {
      if (overlap_pairwise(a[ta - 1].view(), b[tb - 1].view(), n, out.data()) != Status::ok) return 0;
      h.add_u32s(out);
    }
  HitSet hits(rays_n);
  std::vector<float> u(rays_n), v(rays_n);
  for (uint32_t t = 1; t <= 5; ++t) {
    HitsOut o = hits.out();
    o.u = u.data(), o.v = v.data();
    if (raycast_closest(rays.view(), rays_n, p[t - 1].view(), prims_n, o) != Status::ok) return 0;
    h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz), h.add_floats(u),
        h.add_floats(v);
    for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));
    if (raycast_any(rays.view(), rays_n, p[t - 1].view(), prims_n, hits.out(false)) != Status::ok) return 0;
    h.add_floats(hits.t);
    for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));
  }
  return h.digest();
}


#if defined(GYRO_HAS_SPATIAL)
// A terrain with seeded heights (no libm: inputs must be the same bits on every CPU) plus
// a soup of random triangles above it: the BVH's bytes (the build must be deterministic
// too) and closest and any hits of rays of every kind, with normals and barycentrics.
// A 96 x 96 height field with 3000 floating triangles above it (mesh_bvh, rays_one_origin).
const MeshData& det_terrain() {
  static const MeshData mesh = [] {
    MeshData m;
    SplitMix64 rng(31);
    const int n = 96;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.add_vertex({float(i) * 0.5f, float(2.0 * rng.u()), float(j) * 0.5f});
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
        m.add_triangle(a, c, b), m.add_triangle(b, c, d);
      }
    for (int t = 0; t < 3000; ++t) {
      const vec3 c{float(48 * rng.u()), float(3 + 10 * rng.u()), float(48 * rng.u())};
      const uint32_t v = uint32_t(m.vertex_count());
      for (int k = 0; k < 3; ++k) m.add_vertex(c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)});
      m.add_triangle(v, v + 1, v + 2);
    }
    return m;
  }();
  return mesh;
}

uint64_t scene_mesh_bvh() {
  const MeshData& mesh = det_terrain();
  static const RaySet rays = [] {
    RaySet r;
    SplitMix64 rng(32);
    for (int i = 0; i < 4000; ++i) {
      const float o[3] = {float(60 * rng.u() - 6), float(20 * rng.u()), float(60 * rng.u() - 6)};
      float d[3] = {float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
      if (i % 7 == 0) d[0] = 0.0f, d[2] = 0.0f;  // straight down: zero components
      r.push(o[0], o[1], o[2], d[0], d[1], d[2]);
    }
    return r;
  }();
  detail::StateHasher h;
  const detail::Bvh8 bvh = detail::build_bvh8(mesh);
  for (const auto& node : bvh.nodes) {
    for (const auto& row : node.bounds) h.add_floats(std::span<const float>(row, 8));
    h.add_u32s(std::span<const uint32_t>(node.child, 8));
  }
  for (const auto& leaf : bvh.leaves) h.add_u32s(std::span<const uint32_t>(leaf.triangle, 4));
  TriangleMesh tm;
  if (TriangleMesh::create(mesh, tm) != Status::ok) return 0;
  HitSet hits(rays.size());
  std::vector<float> u(rays.size()), v(rays.size());
  HitsOut o = hits.out();
  o.u = u.data(), o.v = v.data();
  if (raycast_closest(tm, rays.view(), rays.size(), o) != Status::ok) return 0;
  h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz), h.add_floats(u),
      h.add_floats(v);
  for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));
  if (raycast_any(tm, rays.view(), rays.size(), hits.out(false)) != Status::ok) return 0;
  h.add_floats(hits.t);
  for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));
  return h.digest();
}

// `count` rays with origins scale * u + offset on each axis and directions u - 0.5, drawn
// in that order (into an array: a call's arguments are evaluated in no fixed order, and
// g++ and clang++ differ).
RaySet random_rays(uint64_t seed, int count, double scale, double offset) {
  RaySet r;
  SplitMix64 rng(seed);
  for (int i = 0; i < count; ++i) {
    float v[6];
    for (int k = 0; k < 6; ++k) v[k] = k < 3 ? float(scale * rng.u() + offset) : float(rng.u() - 0.5);
    r.push(v[0], v[1], v[2], v[3], v[4], v[5]);
  }
  return r;
}

// Model i of a random scene: a sphere, a box or an instance of `meshes` (in turn), of random
// size, position in a 60-unit cube and rotation, unscaled and without a parent.
ModelDef random_model(SplitMix64& rng, int i, const std::vector<std::shared_ptr<const TriangleMesh>>& meshes) {
  ModelDef d;
  d.shape = ModelShape(i % 3);
  d.radius = float(0.2 + 2 * rng.u());
  d.half_extents = {float(0.1 + rng.u()), float(0.1 + 2 * rng.u()), float(0.1 + rng.u())};
  if (d.shape == ModelShape::mesh) d.mesh = meshes[std::size_t(i) % meshes.size()];
  d.transform.position = {float(60 * rng.u() - 30), float(60 * rng.u() - 30), float(60 * rng.u() - 30)};
  // Named first: a function's arguments are evaluated in no fixed order (g++ on x86-64 takes
  // them right to left, clang and aarch64 g++ left to right), so draws inside one call would
  // give each compiler another scene.
  const vec3 axis{float(rng.u() - 0.5), float(rng.u()), float(rng.u() - 0.5)};
  const float angle = float(6 * rng.u());
  d.transform.rotation = from_axis_angle(axis, angle);
  return d;
}

// A scene under `accel` of `count` spheres, boxes and instances of `meshes` (in turn),
// scaled, rotated, every seventh the child of an earlier one, in a 60-unit cube; their ids
// in ids.
bool random_scene(SceneAccel accel, SplitMix64& rng, int count,
                  const std::vector<std::shared_ptr<const TriangleMesh>>& meshes, Scene& scene,
                  std::vector<ModelId>& ids) {
  SceneSettings settings;
  settings.accel = accel;
  scene = Scene(settings);
  ids.clear();
  for (int i = 0; i < count; ++i) {
    ModelDef d = random_model(rng, i, meshes);
    d.transform.scale = float(0.5 + rng.u());
    if (i % 7 == 6) d.parent = ids[std::size_t(rng.next() % ids.size())], d.transform.position = d.transform.position * 0.1f;
    ModelId id;
    if (scene.add_model(d, &id) != Status::ok) return false;
    ids.push_back(id);
  }
  return true;
}

// A scene of spheres, boxes, instanced meshes (scaled, rotated, some parented) and two
// planes, in both acceleration modes: batch closest and any hits with model ids, normals
// and barycentrics, and sphere, AABB and frustum queries; then after removes and moves
// (a rebuild), then after moves alone (a refit under the BVH).
// A box and a sphere mesh, made once (empty if either fails).
const std::vector<std::shared_ptr<const TriangleMesh>>& scene_meshes() {
  static const std::vector<std::shared_ptr<const TriangleMesh>> meshes = [] {
    std::vector<std::shared_ptr<const TriangleMesh>> out;
    for (const MeshData& m : {make_box_mesh({1.0f, 0.5f, 2.0f}), make_sphere_mesh(1.5f, 8, 12)}) {
      auto t = std::make_shared<TriangleMesh>();
      if (TriangleMesh::create(m, *t) != Status::ok) return out;
      out.push_back(t);
    }
    return out;
  }();
  return meshes;
}

uint64_t scene_models() {
  const std::vector<std::shared_ptr<const TriangleMesh>>& meshes = scene_meshes();
  if (meshes.size() != 2) return 0;
  static const RaySet rays = random_rays(41, 3000, 80.0, -40.0);
  detail::StateHasher h;
  for (SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
    Scene scene;
    SplitMix64 rng(42);
    std::vector<ModelId> ids;
    if (!random_scene(accel, rng, 400, meshes, scene, ids)) return 0;
    ModelDef plane;
    plane.shape = ModelShape::plane;
    plane.plane = {{0.0f, 1.0f, 0.0f}, -35.0f};
    ModelId pid;
    if (scene.add_model(plane, &pid) != Status::ok) return 0;
    for (int round = 0; round < 3; ++round) {
      std::vector<float> t(rays.size()), nx(rays.size()), ny(rays.size()), nz(rays.size()), u(rays.size()), v(rays.size());
      std::vector<ModelId> model(rays.size());
      std::vector<int32_t> prim(rays.size());
      const SceneHitsOut out{t.data(), model.data(), prim.data(), nx.data(), ny.data(), nz.data(), u.data(), v.data()};
      if (raycast_closest(scene, rays.view(), rays.size(), out) != Status::ok) return 0;
      h.add_floats(t), h.add_floats(nx), h.add_floats(ny), h.add_floats(nz), h.add_floats(u), h.add_floats(v);
      for (std::size_t i = 0; i < rays.size(); ++i) h.add_u32(model[i].index), h.add_u32(uint32_t(prim[i]));
      if (raycast_any(scene, rays.view(), rays.size(), SceneHitsOut{t.data(), model.data(), prim.data()}) != Status::ok)
        return 0;
      for (std::size_t i = 0; i < rays.size(); ++i) h.add_u32(prim[i] >= -1 ? uint32_t(prim[i] >= 0) : 2u);
      if (round == 2) {
        // After moves alone the BVH was refit (SceneSettings::refit), not rebuilt: which model
        // an any hit names follows the tree, so it is pinned here, with the refit's cost.
        for (std::size_t i = 0; i < rays.size(); ++i) h.add_u32(model[i].index);
        const SceneStats st = scene.stats();
        h.add_u32(uint32_t(st.builds)), h.add_u32(uint32_t(st.refits));
        h.add_u64(std::bit_cast<uint64_t>(st.sah_cost));
      }
      std::vector<ModelId> found;
      if (query(scene, Sphere{{1.0f, 2.0f, 3.0f}, 12.0f}, found) != Status::ok) return 0;
      for (ModelId id : found) h.add_u32(id.index);
      if (query(scene, AABB{{-5.0f, 0.0f, 5.0f}, {9.0f, 4.0f, 7.0f}}, found) != Status::ok) return 0;
      for (ModelId id : found) h.add_u32(id.index);
      Camera cam = perspective_camera(1.0f, 1.3f, 0.5f, 60.0f);
      set_look_at(cam, {0.0f, 5.0f, -45.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
      if (query(scene, frustum(cam), found) != Status::ok) return 0;
      for (ModelId id : found) h.add_u32(id.index);
      // Round 3: every fourth model moved (a refit under the BVH: 2 builds, 1 refit).
      for (std::size_t i = 0; i < ids.size() && round == 1; i += 4) {
        if (!scene.contains(ids[i])) continue;
        ModelInfo info;
        if (scene.model(ids[i], &info) != Status::ok) return 0;
        ModelTransform tr = info.def.transform;
        tr.position = tr.position + vec3{-0.75f, 0.5f, 1.0f};
        if (scene.set_transform(ids[i], tr) != Status::ok) return 0;
      }
      // Round 2: every fifth model removed, every third moved.
      for (std::size_t i = 0; i < ids.size() && round == 0; ++i) {
        if (i % 5 == 0) {
          if (scene.remove_model(ids[i]) != Status::ok) return 0;
        } else if (i % 3 == 0) {
          ModelInfo info;
          if (scene.model(ids[i], &info) != Status::ok) return 0;
          ModelTransform tr = info.def.transform;
          tr.position = tr.position + vec3{1.5f, -0.5f, 0.25f};
          if (scene.set_transform(ids[i], tr) != Status::ok) return 0;
        }
      }
    }
  }
  return h.digest();
}

// Spawning and despawning under the BVH: 3,000 root models (no parents: adds and removes
// keep the tree, detaching and attaching leaves, BvhRefit) through frames of removes, adds
// and moves, one of them moving every model (placed in parallel chunks, refit in parallel
// subtrees), one adding a model that is unplaced and a plane. Closest hits, the model an
// any hit names (it follows the tree), and the tree's counts and cost after every frame.
uint64_t scene_spawn() {
  const std::vector<std::shared_ptr<const TriangleMesh>>& meshes = scene_meshes();
  if (meshes.size() != 2) return 0;
  static const RaySet rays = random_rays(51, 2000, 80.0, -40.0);
  detail::StateHasher h;
  Scene scene;
  SplitMix64 rng(52);
  std::vector<ModelId> ids;
  const auto add = [&](int i) {
    const ModelDef d = random_model(rng, i, meshes);
    ModelId id;
    if (scene.add_model(d, &id) != Status::ok) return false;
    ids.push_back(id);
    return true;
  };
  int made = 0;
  for (; made < 3000; ++made)
    if (!add(made)) return 0;
  const auto remove = [&](std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t at = std::size_t(rng.next() % ids.size());
      if (scene.remove_model(ids[at]) != Status::ok) return false;
      ids[at] = ids.back();
      ids.pop_back();
    }
    return true;
  };
  const auto move = [&](std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      const ModelId id = count >= ids.size() ? ids[k % ids.size()] : ids[std::size_t(rng.next() % ids.size())];
      ModelInfo info;
      if (scene.model(id, &info) != Status::ok) return false;
      ModelTransform t = info.def.transform;
      t.position = t.position + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
      if (scene.set_transform(id, t) != Status::ok) return false;
    }
    return true;
  };
  for (int frame = 0; frame < 5; ++frame) {
    if (frame > 0 && !remove(frame == 2 ? 400 : 40)) return 0;
    for (int k = 0; k < (frame == 2 ? 300 : 50); ++k)
      if (!add(made++)) return 0;
    if (frame == 2) {
      ModelDef far;
      far.transform.position = {std::numeric_limits<float>::max(), 0.0f, 0.0f};  // unplaced
      ModelDef plane;
      plane.shape = ModelShape::plane;
      plane.plane = {{0.0f, 1.0f, 0.0f}, -35.0f};
      ModelId a, b;
      if (scene.add_model(far, &a) != Status::ok || scene.add_model(plane, &b) != Status::ok) return 0;
      ids.push_back(a), ids.push_back(b);
    }
    if (frame == 3) {
      // Every model moved: the transforms read first (a model() between the moves would place
      // them one by one), then set.
      std::vector<std::pair<ModelId, ModelTransform>> to;
      for (ModelId id : ids) {
        ModelInfo info;
        if (scene.model(id, &info) != Status::ok) return 0;
        ModelTransform t = info.def.transform;
        t.position = t.position + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
        to.push_back({id, t});
      }
      for (const auto& [id, t] : to)
        if (scene.set_transform(id, t) != Status::ok) return 0;
    } else if (!move(30)) {
      return 0;
    }
    std::vector<float> t(rays.size());
    std::vector<ModelId> model(rays.size());
    std::vector<int32_t> prim(rays.size());
    if (raycast_closest(scene, rays.view(), rays.size(), SceneHitsOut{t.data(), model.data(), prim.data()}) != Status::ok)
      return 0;
    h.add_floats(t);
    for (std::size_t i = 0; i < rays.size(); ++i) h.add_u32(model[i].index), h.add_u32(uint32_t(prim[i]));
    if (raycast_any(scene, rays.view(), rays.size(), SceneHitsOut{t.data(), model.data(), prim.data()}) != Status::ok)
      return 0;
    for (std::size_t i = 0; i < rays.size(); ++i) h.add_u32(model[i].index);
    const SceneStats st = scene.stats();
    for (std::size_t v : {st.models, st.tree_models, st.planes, st.builds, st.refits, st.nodes, st.leaves, st.max_depth})
      h.add_u32(uint32_t(v));
    h.add_u64(std::bit_cast<uint64_t>(st.sah_cost));
  }
  return h.digest();
}

// Layers: 300 models of random_scene() (some parented) and a plane, each model in
// one of four layers, in none or in all (set_layers before the first build, and the plane's
// ModelDef::layers), under both structures; rays of random masks (one layer, two, none,
// all), closest and any hits, single rays too, and sphere queries of every mask; then after
// a tenth of the layers changed (set_layers on a built tree: only the leaves' masks
// rewritten).
uint64_t scene_layers() {
  static const std::vector<std::shared_ptr<const TriangleMesh>> meshes = [] {
    auto t = std::make_shared<TriangleMesh>();
    return TriangleMesh::create(make_sphere_mesh(1.2f, 6, 10), *t) == Status::ok
               ? std::vector<std::shared_ptr<const TriangleMesh>>{t}
               : std::vector<std::shared_ptr<const TriangleMesh>>{};
  }();
  if (meshes.empty()) return 0;
  static const uint32_t kLayers[7] = {1u, 2u, 4u, 8u, 3u, 0u, kAllLayers};
  static const std::vector<uint32_t> ray_masks = [] {
    std::vector<uint32_t> m;
    SplitMix64 rng(52);
    for (int i = 0; i < 2000; ++i) m.push_back(kLayers[rng.next() % 7]);
    return m;
  }();
  static const RaySet rays = random_rays(51, 2000, 70.0, -35.0);
  detail::StateHasher h;
  for (SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
    Scene scene;
    SplitMix64 rng(53);
    std::vector<ModelId> ids;
    if (!random_scene(accel, rng, 300, meshes, scene, ids)) return 0;
    for (std::size_t i = 0; i < ids.size(); ++i)
      if (scene.set_layers(ids[i], i % 11 == 0 ? 0u : i % 13 == 0 ? kAllLayers : 1u << (rng.next() % 4)) !=
          Status::ok)
        return 0;
    ModelDef plane;
    plane.shape = ModelShape::plane;
    plane.plane = {{0.0f, 1.0f, 0.0f}, -30.0f};
    plane.layers = 2u;
    ModelId pid;
    if (scene.add_model(plane, &pid) != Status::ok) return 0;
    for (int round = 0; round < 2; ++round) {
      const std::size_t n = rays.size();
      std::vector<float> t(n);
      std::vector<ModelId> model(n);
      std::vector<int32_t> prim(n);
      RaysView view = rays.view();
      view.mask = ray_masks.data();
      if (raycast_closest(scene, view, n, SceneHitsOut{t.data(), model.data(), prim.data()}) != Status::ok) return 0;
      h.add_floats(t);
      for (std::size_t i = 0; i < n; ++i) h.add_u32(model[i].index), h.add_u32(uint32_t(prim[i]));
      if (raycast_any(scene, view, n, SceneHitsOut{t.data(), model.data(), prim.data()}) != Status::ok) return 0;
      for (std::size_t i = 0; i < n; ++i) h.add_u32(model[i].index);
      for (std::size_t i = 0; i < n; i += 7) {
        const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
        const SceneHit one = raycast(scene, ray, 0.0f, __builtin_inff(), ray_masks[i]);
        h.add_u32(std::bit_cast<uint32_t>(one.hit.t)), h.add_u32(one.model.index);
      }
      std::vector<ModelId> found;
      for (const uint32_t mask : kLayers) {
        if (query(scene, Sphere{{2.0f, -1.0f, 3.0f}, 14.0f}, found, mask) != Status::ok) return 0;
        for (ModelId id : found) h.add_u32(id.index);
        h.add_u32(uint32_t(found.size()));
      }
      for (std::size_t i = 0; i < ids.size(); i += 10)
        if (scene.set_layers(ids[i], kLayers[(i / 10) % 7]) != Status::ok) return 0;
    }
  }
  return h.digest();
}

// Rays from one origin, which the batch raycasts walk in packets of eight: a lidar fan
// (32 channels x 128 columns, some with a [tmin, tmax] window) over det_terrain(), and a
// camera's fan into a scene of spheres, boxes, mesh instances and a plane; closest hits
// with normals (and the scene's model ids and barycentrics).
RaySet fan(const vec3& o, float az0, float az1, int columns, float el0, float el1, int channels) {
  RaySet r;
  for (int c = 0; c < columns; ++c) {
    const double a = az0 + (az1 - az0) * (c + 0.5) / columns;
    for (int k = 0; k < channels; ++k) {
      const double e = el0 + (el1 - el0) * (k + 0.5) / channels;
      r.push(o.x, o.y, o.z, float(std::cos(e) * std::cos(a)), float(std::sin(e)), float(std::cos(e) * std::sin(a)));
    }
  }
  return r;
}

// Slivers (a third corner 1e-4 to 1e-3 of the length off the line of the other two): most
// hits take the watertight test's double path (ray_triangle_lanes.hpp), whose doubles must
// round alike everywhere. Random rays and a fan from one origin (the packet walk), closest
// hits with normals and barycentrics, and the scalar raycast's t and weights.
uint64_t scene_mesh_slivers() {
  static const MeshData mesh = [] {
    SplitMix64 rng(45);
    return sliver_mesh(2000, rng, 20.0f, 4.0f);
  }();
  static const RaySet rays = random_rays(46, 3000, 24.0, -2.0);
  static const RaySet fan_rays = fan({10.0f, 10.0f, 10.0f}, 0.0f, 6.2831853f, 96, -1.2f, 1.2f, 24);
  TriangleMesh tm;
  if (TriangleMesh::create(mesh, tm) != Status::ok) return 0;
  detail::StateHasher h;
  for (const RaySet* set : {&rays, &fan_rays}) {
    HitSet hits(set->size());
    std::vector<float> u(set->size()), v(set->size());
    HitsOut o = hits.out();
    o.u = u.data(), o.v = v.data();
    if (raycast_closest(tm, set->view(), set->size(), o) != Status::ok) return 0;
    h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz), h.add_floats(u),
        h.add_floats(v);
    for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));
  }
  for (std::size_t i = 0; i < rays.size(); i += 3) {
    const uint32_t k = uint32_t(i % mesh.triangle_count());
    const auto corner = [&](int c) {
      const uint32_t q = mesh.indices[3 * k + uint32_t(c)];
      return vec3{mesh.x[q], mesh.y[q], mesh.z[q]};
    };
    const Triangle t{corner(0), corner(1), corner(2)};
    const vec3 target = (t.a + t.b) * 0.5f;
    const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, target - vec3{rays.ox[i], rays.oy[i], rays.oz[i]}};
    vec3 bary;
    const RaycastResult r = raycast(t, ray, &bary);
    h.add_u32(r.hit ? 1u : 0u), h.add_float(r.t), h.add_float(bary.x), h.add_float(bary.y), h.add_float(bary.z);
  }
  return h.digest();
}

uint64_t scene_rays_one_origin() {
  detail::StateHasher h;
  static const RaySet lidar = fan({24.0f, 6.0f, 24.0f}, 0.0f, 6.2831853f, 128, -0.7f, 0.45f, 32);
  std::vector<float> tmin(lidar.size(), 0.0f), tmax(lidar.size(), 60.0f);
  for (std::size_t i = 0; i < lidar.size(); i += 11) tmin[i] = 0.5f, tmax[i] = 9.0f;
  TriangleMesh tm;
  if (TriangleMesh::create(det_terrain(), tm) != Status::ok) return 0;
  RaysView lv = lidar.view();
  lv.tmin = tmin.data(), lv.tmax = tmax.data();
  HitSet hits(lidar.size());
  if (raycast_closest(tm, lv, lidar.size(), hits.out()) != Status::ok) return 0;
  h.add_floats(hits.t), h.add_floats(hits.nx), h.add_floats(hits.ny), h.add_floats(hits.nz);
  for (int32_t k : hits.primitive) h.add_u32(uint32_t(k));

  auto sphere_mesh = std::make_shared<TriangleMesh>();
  if (TriangleMesh::create(make_sphere_mesh(1.5f, 8, 12), *sphere_mesh) != Status::ok) return 0;
  Scene scene;
  SplitMix64 rng(71);
  for (int i = 0; i < 300; ++i) {
    ModelDef d;
    d.shape = ModelShape(i % 3);
    d.radius = float(0.2 + 2 * rng.u());
    d.half_extents = {float(0.1 + rng.u()), float(0.1 + 2 * rng.u()), float(0.1 + rng.u())};
    if (d.shape == ModelShape::mesh) d.mesh = sphere_mesh;
    d.transform.position = {float(60 * rng.u() - 30), float(60 * rng.u() - 30), float(60 * rng.u() - 30)};
    const vec3 axis{float(rng.u() - 0.5), float(rng.u()), float(rng.u() - 0.5)};
    const float angle = float(6 * rng.u());
    d.transform.rotation = from_axis_angle(axis, angle);
    ModelId id;
    if (scene.add_model(d, &id) != Status::ok) return 0;
  }
  ModelDef plane;
  plane.shape = ModelShape::plane;
  plane.plane = {{0.0f, 1.0f, 0.0f}, -35.0f};
  ModelId pid;
  if (scene.add_model(plane, &pid) != Status::ok) return 0;
  static const RaySet cam = fan({0.0f, 4.0f, -45.0f}, 0.9f, 2.25f, 96, -0.5f, 0.4f, 40);
  const std::size_t n = cam.size();
  std::vector<float> t(n), nx(n), ny(n), nz(n), u(n), v(n);
  std::vector<ModelId> model(n);
  std::vector<int32_t> prim(n);
  const SceneHitsOut out{t.data(), model.data(), prim.data(), nx.data(), ny.data(), nz.data(), u.data(), v.data()};
  if (raycast_closest(scene, cam.view(), n, out) != Status::ok) return 0;
  h.add_floats(t), h.add_floats(nx), h.add_floats(ny), h.add_floats(nz), h.add_floats(u), h.add_floats(v);
  for (std::size_t i = 0; i < n; ++i) h.add_u32(model[i].index), h.add_u32(uint32_t(prim[i]));
  return h.digest();
}

// A camera's matrices, picking rays and frustum, and batch culling of random spheres,
// AABBs and OBBs around it.
uint64_t scene_camera_frustum() {
  detail::StateHasher h;
  Camera cam = perspective_camera(1.1f, 1.5f, 0.25f, 80.0f);
  set_look_at(cam, {3.0f, 4.0f, -12.0f}, {1.0f, 0.5f, 2.0f}, {0.0f, 1.0f, 0.0f});
  const mat4 vp = view_projection_matrix(cam);
  h.add_floats(std::span<const float>(&vp.m[0][0], 16));
  for (int y = 0; y <= 8; ++y)
    for (int x = 0; x <= 8; ++x) {
      const Ray r = picking_ray(cam, {float(x) * 160.0f, float(y) * 90.0f}, {1280.0f, 720.0f});
      const float f[6] = {r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z};
      h.add_floats(std::span<const float>(f, 6));
    }
  const Frustum fr = frustum(cam);
  for (const Plane& p : fr.planes) {
    const float f[4] = {p.normal.x, p.normal.y, p.normal.z, p.distance};
    h.add_floats(std::span<const float>(f, 4));
  }
  static const std::vector<RandomShapes> shapes = [] {
    std::vector<RandomShapes> all;
    SplitMix64 rng(33);
    for (ShapeType t : {ShapeType::sphere, ShapeType::aabb, ShapeType::obb}) all.push_back(random_shapes(t, 5003, rng, 60.0f));
    return all;
  }();
  std::vector<uint32_t> visible(5003);
  if (frustum_cull(fr, shapes[0].view().spheres, visible.size(), visible.data()) != Status::ok) return 0;
  h.add_u32s(visible);
  if (frustum_cull(fr, shapes[1].view().aabbs, visible.size(), visible.data()) != Status::ok) return 0;
  h.add_u32s(visible);
  if (frustum_cull(fr, shapes[2].view().obbs, visible.size(), visible.data()) != Status::ok) return 0;
  h.add_u32s(visible);
  return h.digest();
}
#endif


#if defined(GYRO_HAS_DYNAMICS)
// Rigid bodies in every configuration a step handles: a plane, a static box, a static
// triangle-mesh ramp, a small pyramid, spheres that bounce, a spinning kinematic paddle, a
// body destroyed mid-run, sleeping, and each contact model. Hashes the world every 10 steps.
// A ground plane and a static mesh ramp beside the origin: the floor of the world scenes.
bool add_ground_and_ramp(World& w, const TriangleMesh& ramp) {
  BodyId id;
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::plane;
  if (w.create_body(d, &id) != Status::ok) return false;
  d.shape.type = BodyShape::mesh;
  d.shape.mesh = &ramp;
  d.position = {4.0f, 0.01f, -3.0f};
  return w.create_body(d, &id) == Status::ok;
}

uint64_t scene_world_pile() {
  detail::StateHasher h;
  static const TriangleMesh ramp = [] {
    TriangleMesh m;
    MeshData grid = make_grid_mesh(6, 6, 1.0f, [](float x, float z, void*) { return 0.15f * x + 0.05f * z; });
    TriangleMesh::create(grid, m);
    return m;
  }();
  for (ContactModel model : {ContactModel::soft_step, ContactModel::baumgarte, ContactModel::linear_projection}) {
    WorldDef def;
    def.contact_model = model;
    if (model != ContactModel::soft_step) def.velocity_iterations = 8;
    std::unique_ptr<World> w;
    if (World::create(def, &w) != Status::ok) return 0;
    if (!add_ground_and_ramp(*w, ramp)) return 0;
    BodyId id;
    BodyDef d;
    d.type = BodyType::kinematic;
    d.shape.half_extents = {2.0f, 0.1f, 0.3f};
    d.position = {-4.0f, 0.6f, 0.0f};
    d.angular_velocity = {0.0f, 1.5f, 0.0f};
    if (w->create_body(d, &id) != Status::ok) return 0;
    std::vector<BodyId> bodies;
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4 - row; ++k) {
        BodyDef b;
        b.shape.half_extents = {0.4f, 0.4f, 0.4f};
        b.position = {(float(k) - float(3 - row) * 0.5f) * 0.85f, 0.4f + 0.8f * float(row), 0.0f};
        b.density = 2.0f;
        if (w->create_body(b, &id) != Status::ok) return 0;
        bodies.push_back(id);
      }
    SplitMix64 rng(77);
    for (int k = 0; k < 12; ++k) {
      const float r[5] = {float(rng.u()), float(rng.u()), float(rng.u()), float(rng.u()),
                          float(rng.u())};
      BodyDef b;
      b.shape.type = k % 3 == 0 ? BodyShape::box : BodyShape::sphere;
      b.shape.radius = 0.2f + 0.2f * r[0];
      b.shape.half_extents = {0.2f + 0.2f * r[0], 0.3f, 0.25f};
      b.position = {8.0f * r[1] - 4.0f, 3.0f + 4.0f * r[2], 6.0f * r[3] - 3.0f};
      b.orientation = from_axis_angle({r[1], 1.0f, r[3]}, 3.0f * r[4]);
      b.restitution = 0.4f * r[4];
      b.friction = 0.3f + 0.5f * r[0];
      b.angular_velocity = {r[2] - 0.5f, 0.0f, r[3] - 0.5f};
      if (w->create_body(b, &id) != Status::ok) return 0;
      bodies.push_back(id);
    }
    for (int step = 1; step <= 240; ++step) {
      if (step == 40 && w->destroy_body(bodies[3]) != Status::ok) return 0;
      if (step == 80 && w->apply_linear_impulse(bodies[12], {2.0f, 3.0f, 0.0f}, {0.0f, 5.0f, 0.0f}) != Status::ok)
        return 0;
      if (w->step(1.0f / 60.0f) != Status::ok) return 0;
      if (step % 10 == 0) h.add_u64(w->hash());
    }
  }
  return h.digest();
}

// Particles in a world, with every integrator: a fountain against a sphere, a box, a rotated
// box and a plane, some pinned, some fast enough to cross a collider in one step.
uint64_t scene_world_particles() {
  detail::StateHasher h;
  for (ParticleIntegrator integrator :
       {ParticleIntegrator::explicit_euler, ParticleIntegrator::semi_implicit_euler, ParticleIntegrator::verlet}) {
    std::unique_ptr<World> w;
    if (World::create(WorldDef{}, &w) != Status::ok) return 0;
    ParticleSystem& ps = w->particles();
    ParticleSettings settings = ps.settings();
    settings.integrator = integrator;
    settings.damping = 0.05f;
    if (ps.set_settings(settings) != Status::ok) return 0;
    uint32_t index;
    if (ps.add_collider(Plane{{0.0f, 1.0f, 0.0f}, 0.0f}, &index) != Status::ok) return 0;
    if (ps.add_collider(Sphere{{1.0f, 1.0f, 0.0f}, 0.7f}, &index) != Status::ok) return 0;
    if (ps.add_collider(AABB{{-1.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}}, &index) != Status::ok) return 0;
    if (ps.add_collider(OBB{{0.0f, 2.0f, -1.5f}, {1.0f, 0.02f, 1.0f}, to_mat3(from_axis_angle({1.0f, 0.0f, 0.3f}, 0.4f))},
                        &index) != Status::ok)
      return 0;
    SplitMix64 rng(91);
    for (int k = 0; k < 300; ++k) {
      const float r[6] = {float(rng.u()), float(rng.u()), float(rng.u()), float(rng.u()), float(rng.u()), float(rng.u())};
      ParticleDef d;
      d.position = {4.0f * r[0] - 2.0f, 3.0f + 2.0f * r[1], 4.0f * r[2] - 2.0f};
      d.velocity = {10.0f * r[3] - 5.0f, (k % 7 == 0 ? -200.0f : 8.0f * r[4]), 10.0f * r[5] - 5.0f};
      d.bounce = 0.3f + 0.6f * r[1];
      d.friction = 0.2f * r[2];
      d.pinned = k % 37 == 0;
      ParticleId id;
      if (ps.create(d, &id) != Status::ok) return 0;
    }
    for (int step = 1; step <= 180; ++step) {
      if (w->step(1.0f / 60.0f) != Status::ok) return 0;
      if (step % 20 == 0) h.add_u64(w->hash());
    }
  }
  return h.digest();
}

// Springs, cloth and soft bodies: a 24 x 24 cloth (xpbd, two corners pinned, a joint) draped
// over a sphere collider, and a soft cube (the springs model, damped) dropped on a plane and
// the sphere. Hashes both bodies every 10 of 60 steps.
uint64_t scene_soft_cloth() {
  detail::StateHasher h;
  ClothDef def;
  def.nx = def.nz = 24;
  def.size_x = def.size_z = 2.4f;
  def.center = {0.05f, 1.0f, -0.03f};
  def.particle_mass = 0.05f;
  def.bend_constants = {2.0e3f, 0.5f};
  SoftBody cloth;
  if (SoftBody::make_cloth(def, &cloth) != Status::ok) return 0;
  uint32_t index;
  if (cloth.cloth_index(0, 0, &index) != Status::ok || cloth.pin(index) != Status::ok) return 0;
  if (cloth.cloth_index(23, 0, &index) != Status::ok || cloth.pin(index) != Status::ok) return 0;
  uint32_t far_a, far_b;
  if (cloth.cloth_index(0, 23, &far_a) != Status::ok || cloth.cloth_index(23, 23, &far_b) != Status::ok) return 0;
  if (cloth.add_joint({far_a, far_b, 1.8f}) != Status::ok) return 0;
  if (cloth.add_collider(Sphere{{0.0f, 0.0f, 0.0f}, 0.7f}, &index) != Status::ok) return 0;
  SoftBody cube;
  SoftSettings s;
  s.model = SoftModel::springs;
  s.damping = 0.2f;
  if (cube.set_settings(s) != Status::ok) return 0;
  SoftCubeDef cd;
  cd.center = {0.4f, 1.5f, 0.1f};
  cd.half_extent = 0.2f;
  cd.structural = {1.0e4f, 2.0f};
  if (SoftBody::make_cube(cd, &cube) != Status::ok) return 0;
  if (cube.set_velocity(0, {1.0f, 0.0f, -0.5f}) != Status::ok) return 0;
  if (cube.add_collider(Plane{{0.0f, 1.0f, 0.0f}, 0.0f}, &index) != Status::ok) return 0;
  if (cube.add_collider(Sphere{{0.0f, 0.0f, 0.0f}, 0.7f}, &index) != Status::ok) return 0;
  for (int step = 1; step <= 60; ++step) {
    if (cloth.step(1.0f / 60.0f) != Status::ok || cube.step(1.0f / 60.0f) != Status::ok) return 0;
    if (step % 10 == 0) h.add_u64(cloth.hash()), h.add_u64(cube.hash());
  }
  return h.digest();
}

// Six box pyramids of base 12 (468 boxes) on a ground box, with spheres dropped among them:
// large enough that the narrowphase runs many chunks of box pairs through the lane
// separating axis test and that the solver cuts its colours (~200 constraints each) into
// several chunks at 2, 3 and 8 threads. Hashes the world every 10 of 20 steps.
uint64_t scene_world_pyramids() {
  detail::StateHasher h;
  WorldDef def;
  def.enable_sleep = false;
  std::unique_ptr<World> w;
  if (World::create(def, &w) != Status::ok) return 0;
  BodyId id;
  BodyDef ground;
  ground.type = BodyType::static_body;
  ground.shape.half_extents = {40.0f, 0.5f, 40.0f};
  ground.position = {0.0f, -0.5f, 0.0f};
  if (w->create_body(ground, &id) != Status::ok) return 0;
  for (int p = 0; p < 6; ++p) {
    const float cx = -15.0f + 15.0f * float(p % 3), cz = p < 3 ? -6.0f : 6.0f;
    for (int row = 0; row < 12; ++row)
      for (int k = 0; k < 12 - row; ++k) {
        BodyDef b;
        b.shape.half_extents = {0.5f, 0.5f, 0.5f};
        b.position = {cx + (float(k) - float(11 - row) * 0.5f) * 1.05f, 0.5f + float(row), cz + 0.01f * float(p)};
        if (w->create_body(b, &id) != Status::ok) return 0;
      }
  }
  SplitMix64 rng(4242);
  for (int k = 0; k < 12; ++k) {
    BodyDef b;
    b.shape.type = BodyShape::sphere;
    b.shape.radius = 0.3f + 0.2f * float(rng.u());
    b.position = {30.0f * float(rng.u()) - 15.0f, 13.0f + 2.0f * float(rng.u()), 12.0f * float(rng.u()) - 6.0f};
    b.linear_velocity = {0.0f, -4.0f, 0.0f};
    if (w->create_body(b, &id) != Status::ok) return 0;
  }
  for (int step = 1; step <= 20; ++step) {
    if (w->step(1.0f / 60.0f) != Status::ok) return 0;
    if (step % 10 == 0) h.add_u64(w->hash());
  }
  return h.digest();
}

void add_result(detail::StateHasher& h, const ConvexResult& r) {
  h.add_u32(uint32_t(r.status)), h.add_float(r.distance), h.add_u32(r.iterations);
  for (const vec3* v : {&r.normal, &r.point_a, &r.point_b}) h.add_float(v->x), h.add_float(v->y), h.add_float(v->z);
}

// The convex pair queries: N1 box pairs through the batches (GJK over lanes, EPA, the
// scalar fallback for the invalid and out-of-range pairs below), and every shape type
// against every other through GJK and EPA one by one.
uint64_t scene_convex_pairs() {
  detail::StateHasher h;
  static const BoxPairs boxes = [] {
    BoxPairs p = n1_pairs(3000 + 13);
    p.a.hx[0] = -1.0f, p.b.cy[1] = __builtin_nanf(""), p.a.cx[2] = p.b.cx[2] = 3e37f, p.b.r[0][3] = 5.0f;
    for (std::size_t i : {4, 5}) {  // faces touching exactly, and one box inside the other
      for (BoxSet* s : {&p.a, &p.b}) {
        s->cx[i] = s->cy[i] = s->cz[i] = 0.0f, s->hx[i] = s->hy[i] = s->hz[i] = 1.0f;
        for (int e = 0; e < 9; ++e) s->r[e][i] = e % 4 == 0 ? 1.0f : 0.0f;
      }
    }
    p.b.cx[4] = 2.0f, p.b.hx[5] = p.b.hy[5] = p.b.hz[5] = 0.5f;
    return p;
  }();
  const std::size_t n = boxes.a.size();
  ConvexBoxPairs pairs;
  const auto fill = [](const BoxSet& s, const float* (&c)[3], const float* (&hf)[3], const float* (&r)[9]) {
    c[0] = s.cx.data(), c[1] = s.cy.data(), c[2] = s.cz.data();
    hf[0] = s.hx.data(), hf[1] = s.hy.data(), hf[2] = s.hz.data();
    for (int k = 0; k < 3; ++k)
      for (int col = 0; col < 3; ++col) r[3 * k + col] = s.r[3 * col + k].data();
  };
  fill(boxes.a, pairs.a_center, pairs.a_half, pairs.a_rot), fill(boxes.b, pairs.b_center, pairs.b_half, pairs.b_rot);
  std::vector<ConvexStatus> verdict(n);
  std::vector<ConvexResult> res(n);
  convex_intersect_batch(pairs, n, verdict.data());
  for (ConvexStatus st : verdict) h.add_u32(uint32_t(st));
  ConvexQueryOptions no_gap;
  no_gap.separated_distance = false;
  for (int q = 0; q < 4; ++q) {
    if (q == 0) convex_intersect_batch(pairs, n, res.data());
    else if (q == 1) convex_distance_batch(pairs, n, res.data());
    else convex_penetration_batch(pairs, n, res.data(), q == 2 ? ConvexQueryOptions{} : no_gap);
    for (const ConvexResult& r : res) add_result(h, r);
  }
  // Every pair of the six shape types, 40 random poses each, half of them overlapping.
  static const std::vector<vec3> cloud = [] {
    SplitMix64 r(404);
    std::vector<vec3> v;
    for (int i = 0; i < 14; ++i) v.push_back({float(r.u()) - 0.5f, 0.6f * float(r.u()) - 0.3f, float(r.u()) - 0.5f});
    return v;
  }();
  ConvexShape shape[6];
  if (make_sphere(0.4f, shape[0]) != Status::ok || make_box({0.5f, 0.02f, 0.3f}, shape[1]) != Status::ok ||
      make_capsule(0.2f, 0.4f, shape[2]) != Status::ok || make_cylinder(0.3f, 0.25f, shape[3]) != Status::ok ||
      make_triangle({-0.5f, 0.0f, -0.3f}, {0.5f, 0.0f, -0.3f}, {0.0f, 0.0f, 0.6f}, shape[4]) != Status::ok ||
      make_convex_points(cloud.data(), cloud.size(), shape[5]) != Status::ok)
    return 0;
  SplitMix64 rng(405);
  for (int ta = 0; ta < 6; ++ta)
    for (int tb = 0; tb < 6; ++tb)
      for (int k = 0; k < 40; ++k) {
        ConvexPose pa, pb;
        pa.rotation = random_rotation(rng), pb.rotation = random_rotation(rng);
        const float x = float(rng.u()), y = float(rng.u()), z = float(rng.u());
        pa.position = {x - 0.5f, y - 0.5f, z - 0.5f};
        const float spread = k < 20 ? 0.5f : 2.0f;
        const float u = float(rng.u()), v = float(rng.u()), w = float(rng.u());
        pb.position = pa.position + vec3{spread * (u - 0.5f), spread * (v - 0.5f), spread * (w - 0.5f)};
        add_result(h, convex_distance(shape[ta], pa, shape[tb], pb));
        add_result(h, convex_penetration(shape[ta], pa, shape[tb], pb));
      }
  return h.digest();
}

// Capsules and hulls (cubes, prisms, random point clouds) with spheres and boxes on a plane,
// a mesh ramp and each other, under both convex manifold models; a hull destroyed midway.
uint64_t scene_convex_bodies() {
  detail::StateHasher h;
  static const TriangleMesh ramp = [] {
    TriangleMesh m;
    MeshData grid = make_grid_mesh(6, 6, 1.0f, [](float x, float z, void*) { return 0.2f * x - 0.05f * z; });
    TriangleMesh::create(grid, m);
    return m;
  }();
  SplitMix64 rng(2026);
  std::vector<ConvexHull> hulls(4);
  {
    std::vector<vec3> pts;
    for (int i = 0; i < 8; ++i) pts.push_back({(i & 1) ? 0.3f : -0.3f, (i & 2) ? 0.2f : -0.2f, (i & 4) ? 0.4f : -0.4f});
    if (build_convex_hull(pts.data(), pts.size(), hulls[0]) != Status::ok) return 0;
    pts.clear();
    for (int i = 0; i < 5; ++i) {
      float sn, cs;
      gyro::sincos(1.2566371f * float(i), &sn, &cs);
      pts.push_back({0.35f * cs, -0.15f, 0.35f * sn}), pts.push_back({0.35f * cs, 0.15f, 0.35f * sn});
    }
    if (build_convex_hull(pts.data(), pts.size(), hulls[1]) != Status::ok) return 0;
    for (int k = 2; k < 4; ++k) {
      pts.clear();
      for (int i = 0; i < 24; ++i) {
        const float x = float(rng.u()), y = float(rng.u()), z = float(rng.u());
        pts.push_back({0.6f * x - 0.3f + 0.1f, 0.5f * y - 0.25f, 0.6f * z - 0.3f});
      }
      if (build_convex_hull(pts.data(), pts.size(), hulls[std::size_t(k)]) != Status::ok) return 0;
    }
  }
  for (ConvexManifold model : {ConvexManifold::clipping, ConvexManifold::incremental}) {
    WorldDef def;
    def.convex_manifold = model;
    std::unique_ptr<World> w;
    if (World::create(def, &w) != Status::ok) return 0;
    if (!add_ground_and_ramp(*w, ramp)) return 0;
    BodyId id;
    std::vector<BodyId> bodies;
    SplitMix64 r(99);
    for (int k = 0; k < 24; ++k) {
      const float u[5] = {float(r.u()), float(r.u()), float(r.u()), float(r.u()), float(r.u())};
      BodyDef b;
      const int kind = k % 6;
      b.shape.type = kind == 0 ? BodyShape::capsule : kind == 1 ? BodyShape::sphere : kind == 2 ? BodyShape::box
                                                                                    : BodyShape::hull;
      b.shape.radius = 0.15f + 0.1f * u[0];
      b.shape.half_height = 0.2f + 0.2f * u[1];
      b.shape.half_extents = {0.25f, 0.2f + 0.1f * u[0], 0.3f};
      b.shape.hull = &hulls[std::size_t(k % 4)];
      b.position = {5.0f * u[1] - 2.5f, 1.0f + 0.5f * float(k), 4.0f * u[2] - 2.0f};
      b.orientation = from_axis_angle({u[3], 1.0f, u[1]}, 3.0f * u[4]);
      b.friction = 0.3f + 0.5f * u[0];
      b.angular_velocity = {u[2] - 0.5f, 0.0f, u[3] - 0.5f};
      if (w->create_body(b, &id) != Status::ok) return 0;
      bodies.push_back(id);
    }
    for (int step = 1; step <= 240; ++step) {
      if (step == 60 && w->destroy_body(bodies[3]) != Status::ok) return 0;
      if (w->step(1.0f / 60.0f) != Status::ok) return 0;
      if (step % 10 == 0) h.add_u64(w->hash());
    }
  }
  return h.digest();
}

// Snapshot and restore: the mixed world (every shape, particles, cloth, soft cube) is stepped,
// snapshotted, stepped on; then restored in place and rebuilt from the bytes in a new world,
// and both must retrace the same hashes step by step. The snapshot bytes themselves are
// hashed, so the format and everything in it is pinned across platforms too.
uint64_t scene_snapshot_restore() {
  detail::StateHasher h;
  static const TriangleMesh ramp = test::make_mixed_world_ramp();
  std::unique_ptr<World> w;
  if (World::create(WorldDef{}, &w) != Status::ok || !test::build_mixed_world(*w, ramp)) return 0;
  for (int step = 0; step < 45; ++step)
    if (w->step(1.0f / 60.0f) != Status::ok) return 0;
  std::vector<uint8_t> snap(w->snapshot_size());
  std::size_t size = 0;
  if (w->snapshot(snap.data(), snap.size(), &size) != Status::ok || size != snap.size()) return 0;
  h.add_u64(size);
  h.add_u64(detail::fnv1a64(snap.data(), snap.size()));
  const uint64_t at_snapshot = w->hash();
  std::vector<uint64_t> ahead;
  for (int step = 0; step < 60; ++step) {
    if (w->step(1.0f / 60.0f) != Status::ok) return 0;
    ahead.push_back(w->hash());
  }
  std::unique_ptr<World> copy;
  if (World::create_from_snapshot(snap.data(), snap.size(), &copy) != Status::ok) return 0;
  if (w->restore(snap.data(), snap.size()) != Status::ok) return 0;
  if (w->hash() != at_snapshot || copy->hash() != at_snapshot) return 0;
  for (int step = 0; step < 60; ++step) {
    if (w->step(1.0f / 60.0f) != Status::ok || copy->step(1.0f / 60.0f) != Status::ok) return 0;
    if (w->hash() != ahead[std::size_t(step)] || copy->hash() != ahead[std::size_t(step)]) return 0;
    h.add_u64(ahead[std::size_t(step)]);
  }
  return h.digest();
}
#endif

const DetScene kScenes[] = {
    {"trig", scene_trig, 0x69125c38406c536bull},
    {"r1s_2k", scene_r1s_2k, 0x8ef0b58be8aab651ull},
    {"rays_edge_cases", scene_rays_edge_cases, 0x2155c274b0cbd76bull},
    {"math_library", scene_math_library, 0x3de9709813336bbcull},
    {"n1_overlap", scene_n1_overlap, 0xad908dedd18ef994ull},
    {"geometry_batch", scene_geometry_batch, 0x1d2f55ce85f87c4full},
#if defined(GYRO_HAS_SPATIAL)
    {"mesh_bvh", scene_mesh_bvh, 0xde9c8060e85afecaull},
    {"camera_frustum", scene_camera_frustum, 0x246ff5bf8a6a766cull},
    {"scene_models", scene_models, 0xdba9aabb65c16b46ull},
    {"scene_layers", scene_layers, 0xd8ccdb8e79b20c3dull},
    {"scene_spawn", scene_spawn, 0xfd8ed5fb3da35e8full},
    {"rays_one_origin", scene_rays_one_origin, 0x4ee4f0393c05adbaull},
    {"mesh_slivers", scene_mesh_slivers, 0xa80aeab449555782ull},
#endif
#if defined(GYRO_HAS_DYNAMICS)
    {"world_pile", scene_world_pile, 0x754cdfcd63378e65ull},
    {"world_particles", scene_world_particles, 0x8e3766db8d8855a1ull},
    {"soft_cloth", scene_soft_cloth, 0x4b131c88424dd139ull},
    {"convex_bodies", scene_convex_bodies, 0x45809748c4eecc2eull},
    {"convex_pairs", scene_convex_pairs, 0xefaa1b2ba499c7bcull},
    {"world_pyramids", scene_world_pyramids, 0x9f3aafe4c55bf10dull},
    {"snapshot_restore", scene_snapshot_restore, 0x5a7ce78bef94a882ull},
#endif
};

}  // namespace

std::span<const DetScene> determinism_scenes() { return kScenes; }

std::vector<SimdLevel> available_levels() {
  std::vector<SimdLevel> out;
  for (uint32_t v = 1; v <= 5; ++v)
    if (simd_level_available(static_cast<SimdLevel>(v))) out.push_back(static_cast<SimdLevel>(v));
  return out;
}

std::vector<DetRun> run_matrix(const DetScene& scene, std::span<const uint32_t> threads) {
  const SimdLevel saved_level = simd_level();
  const uint32_t saved_threads = thread_count();
  std::vector<DetRun> runs;
  for (SimdLevel level : available_levels()) {
    set_simd_level(level);
    for (uint32_t t : threads) {
      set_thread_count(t);
      runs.push_back({level, t, scene.run()});
    }
  }
  set_simd_level(saved_level);
  set_thread_count(saved_threads);
  return runs;
}

}  // namespace gyro::testing
