// Scenes against brute force: raycasts (single and batch, closest and any) must equal a loop
// over every model's own raycast bit for bit (gyro::raycast on the world sphere, OBB or
// plane; the mesh raycast on the ray moved by to_local), in both acceleration modes, at every
// SIMD level and at 1 and 3 threads, before and after removes, moves and re-parenting.
// Overlap and frustum queries must equal the brute-force loop over the same exact tests.
// World placement is checked against binary64, ids against staleness, and bad input
// against changing anything.
#include "gyro/mesh.hpp"
#include "gyro/overlap.hpp"
#include "gyro/raycast.hpp"
#include "gyro/runtime.hpp"
#include "gyro/scene.hpp"
#include "determinism.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <thread>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr float kInf = __builtin_inff();

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float uni(SplitMix64& rng, double lo, double hi) { return float(lo + (hi - lo) * rng.u()); }

quat random_rotation(SplitMix64& rng) {
  const vec3 axis{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)};
  return from_axis_angle(axis, uni(rng, -3.2, 3.2));
}

float grid_height(float x, float z, void*) { return 0.1f * x - 0.05f * z + ((int(x * 2.0f) + int(z * 2.0f)) & 1) * 0.2f; }

std::vector<std::shared_ptr<const TriangleMesh>> test_meshes() {
  std::vector<std::shared_ptr<const TriangleMesh>> out;
  for (const MeshData& data : {make_box_mesh({1.0f, 0.5f, 2.0f}), make_sphere_mesh(1.5f, 6, 10),
                               make_grid_mesh(6, 6, 0.5f, grid_height, nullptr)}) {
    auto m = std::make_shared<TriangleMesh>();
    EXPECT_EQ(TriangleMesh::create(data, *m), Status::ok);
    out.push_back(std::move(m));
  }
  return out;
}

ModelTransform random_transform(SplitMix64& rng, float spread) {
  ModelTransform t;
  t.position = {uni(rng, -spread, spread), uni(rng, -spread, spread), uni(rng, -spread, spread)};
  t.rotation = random_rotation(rng);
  t.scale = rng.u() < 0.5 ? 1.0f : uni(rng, 0.5, 2.0);
  return t;
}

// A random model: spheres, boxes, instanced meshes, some degenerate, a quarter parented.
ModelDef random_def(SplitMix64& rng, const std::vector<std::shared_ptr<const TriangleMesh>>& meshes,
                    const std::vector<ModelId>& live, float spread = 50.0f) {
  ModelDef d;
  const double kind = rng.u();
  if (kind < 0.4) {
    d.shape = ModelShape::sphere;
    d.radius = rng.u() < 0.05 ? 0.0f : uni(rng, 0.2, 3.0);
  } else if (kind < 0.72) {
    d.shape = ModelShape::box;
    d.half_extents = {uni(rng, 0.2, 3.0), uni(rng, 0.2, 3.0), uni(rng, 0.2, 3.0)};
    if (rng.u() < 0.05) d.half_extents.y = 0.0f;
  } else {
    d.shape = ModelShape::mesh;
    d.mesh = meshes[rng.next() % meshes.size()];
  }
  const bool child = !live.empty() && rng.u() < 0.25;
  d.transform = random_transform(rng, child ? 5.0f : spread);
  if (child) d.parent = live[rng.next() % live.size()];
  return d;
}

// n random models without parents in an 80-unit spread, their ids and transforms; then prepared.
void add_root_models(Scene& scene, SplitMix64& rng, const std::vector<std::shared_ptr<const TriangleMesh>>& meshes,
                     std::size_t n, std::vector<ModelId>& ids, std::vector<ModelTransform>& local) {
  ids.assign(n, ModelId{});
  local.assign(n, ModelTransform{});
  const std::vector<ModelId> no_parents;
  for (std::size_t i = 0; i < n; ++i) {
    const ModelDef d = random_def(rng, meshes, no_parents, 80.0f);
    EXPECT_EQ(scene.add_model(d, &ids[i]), Status::ok);
    local[i] = d.transform;
  }
  scene.prepare();
}

struct TestScene {
  Scene scene;
  std::vector<std::shared_ptr<const TriangleMesh>> meshes = test_meshes();
  std::vector<ModelId> ids;

  explicit TestScene(std::size_t n, uint64_t seed, float spread = 50.0f) {
    SplitMix64 rng(seed);
    for (std::size_t i = 0; i < n; ++i) add(random_def(rng, meshes, ids, spread));
    // Two planes (a tilted ground and a far wall), kept outside the tree.
    ModelDef p;
    p.shape = ModelShape::plane;
    p.plane = {{0.0f, 1.0f, 0.0f}, -60.0f};
    p.transform.rotation = from_axis_angle({1.0f, 0.0f, 0.2f}, 0.1f);
    add(p);
    p.plane = {{0.0f, 0.0f, 1.0f}, 80.0f};
    p.transform = {};
    add(p);
  }
  ModelId add(const ModelDef& d) {
    ModelId id;
    EXPECT_EQ(scene.add_model(d, &id), Status::ok) << last_error();
    ids.push_back(id);
    return id;
  }
};

struct Snapshot {
  ModelId id;
  ModelInfo info;
};

std::vector<Snapshot> snapshot(const Scene& scene) {
  std::vector<Snapshot> out;
  for (ModelId id : scene.model_ids()) {
    Snapshot s{id, {}};
    EXPECT_EQ(scene.model(id, &s.info), Status::ok);
    out.push_back(std::move(s));
  }
  return out;
}

// One model's hit as the header defines it, computed from the public pieces.
SceneHit model_hit(const Snapshot& m, const Ray& ray, float tmin, float tmax) {
  SceneHit h;
  switch (m.info.def.shape) {
    case ModelShape::sphere: h.hit = raycast(m.info.sphere, ray, tmin, tmax); break;
    case ModelShape::box: h.hit = raycast(m.info.box, ray, tmin, tmax); break;
    case ModelShape::plane: h.hit = raycast(m.info.plane, ray, tmin, tmax); break;
    case ModelShape::mesh: {
      const MeshHit mh = raycast(*m.info.def.mesh, to_local(m.info.world, ray), tmin, tmax);
      if (!mh.hit.hit) break;
      h.hit = mh.hit;
      h.hit.point = ray.origin + ray.direction * mh.hit.t;
      h.hit.normal = mh.hit.normal * to_mat3(m.info.world.rotation);
      h.primitive = mh.triangle;
      h.u = mh.u, h.v = mh.v;
      break;
    }
  }
  if (h.hit.hit) h.model = m.id;
  return h;
}

SceneHit brute_closest(const std::vector<Snapshot>& models, const Ray& ray, float tmin, float tmax) {
  SceneHit best;
  for (const Snapshot& m : models) {
    const SceneHit h = model_hit(m, ray, tmin, tmax);
    if (!h.hit.hit) continue;
    if (!best.hit.hit || h.hit.t < best.hit.t || (h.hit.t == best.hit.t && h.model.index < best.model.index)) best = h;
  }
  return best;
}

void expect_same(const SceneHit& a, const SceneHit& b, std::size_t ray) {
  ASSERT_EQ(a.hit.hit, b.hit.hit) << "ray " << ray;
  EXPECT_EQ(a.model, b.model) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.t), bits(b.hit.t)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.point.x), bits(b.hit.point.x)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.point.y), bits(b.hit.point.y)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.point.z), bits(b.hit.point.z)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.normal.x), bits(b.hit.normal.x)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.normal.y), bits(b.hit.normal.y)) << "ray " << ray;
  EXPECT_EQ(bits(a.hit.normal.z), bits(b.hit.normal.z)) << "ray " << ray;
  EXPECT_EQ(a.primitive, b.primitive) << "ray " << ray;
  EXPECT_EQ(bits(a.u), bits(b.u)) << "ray " << ray;
  EXPECT_EQ(bits(a.v), bits(b.v)) << "ray " << ray;
}

struct Rays {
  testing::RaySet set;
  std::vector<float> tmin, tmax;
  RaysView view() const {
    RaysView v = set.view();
    v.tmin = tmin.data(), v.tmax = tmax.data();
    return v;
  }
  Ray ray(std::size_t i) const {
    return {{set.ox[i], set.oy[i], set.oz[i]}, {set.dx[i], set.dy[i], set.dz[i]}};
  }
};

// Random rays, rays aimed at model centres (hits), from inside models, axis-parallel ones,
// zero-length ones, [tmin, tmax] windows, and near misses: rays from far away grazing a
// sphere's silhouette or a box's corner within a few ulps (where a raycast's rounding may
// report a hit that the exact ray would miss, so the tree's margins must keep the model).
Rays make_rays(const std::vector<Snapshot>& models, std::size_t n, uint64_t seed) {
  SplitMix64 rng(seed);
  Rays r;
  for (std::size_t i = 0; i < n; ++i) {
    vec3 o{uni(rng, -65, 65), uni(rng, -65, 65), uni(rng, -65, 65)};
    vec3 d{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)};
    const Snapshot& m = models[rng.next() % models.size()];
    const vec3 c = m.info.def.shape == ModelShape::plane ? vec3{} : m.info.bounds.center;
    switch (i % 10) {
      case 0: case 1: d = c - o; break;                              // aimed at a model
      case 2: o = c; break;                                          // from inside a model
      case 3: d.x = 0.0f, d.z = 0.0f; d.y = d.y == 0.0f ? 1.0f : d.y; break;  // axis-parallel
      case 4: d = (c - o) * uni(rng, 0.01, 100.0); break;            // unnormalised lengths
      case 5: d = d * 1e-3f; break;
      case 6: case 7: {
        // A target on (or a hair off) the silhouette of a sphere or a box corner, seen from
        // 10^2 to 10^4 away.
        const vec3 far_dir = normalized(vec3{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)});
        vec3 target = c;
        const float hair = 1.0f + float(int(rng.next() % 7) - 3) * 1e-7f;
        if (m.info.def.shape == ModelShape::sphere) {
          vec3 side = cross(far_dir, vec3{0.3f, 1.0f, -0.2f});
          side = normalized(side);
          target = m.info.sphere.center + side * (m.info.sphere.radius * hair);
        } else if (m.info.def.shape == ModelShape::box) {
          const OBB& b = m.info.box;
          const float sx = rng.u() < 0.5 ? -1.0f : 1.0f, sy = rng.u() < 0.5 ? -1.0f : 1.0f, sz = rng.u() < 0.5 ? -1.0f : 1.0f;
          const vec3 local{sx * b.half_extents.x * hair, sy * b.half_extents.y * hair, sz * b.half_extents.z * hair};
          target = b.center + local * b.orientation;
        }
        o = target + far_dir * float(std::pow(10.0, 2.0 + 2.0 * rng.u()));
        d = target - o;
        if (i % 10 == 7) d = normalized(d);
        break;
      }
      default: break;
    }
    if (i % 97 == 0) d = {0.0f, 0.0f, 0.0f};
    r.set.push(o.x, o.y, o.z, d.x, d.y, d.z);
    const bool window = i % 5 == 0;
    r.tmin.push_back(window ? uni(rng, 0.0, 0.5) : 0.0f);
    r.tmax.push_back(window ? uni(rng, 0.5, 1.5) : kInf);
  }
  return r;
}

// make_rays' rays moved to one origin (a camera, a lidar: the batch walks such rays in
// packets of eight), each aimed at a point of the original ray (a model's centre, a
// silhouette, ...), sorted by the signs of their directions so that most groups of eight
// share them (groups that do not walk ray by ray: both paths are tested). Zero directions
// and [tmin, tmax] windows stay.
Rays make_rays_from(const std::vector<Snapshot>& models, std::size_t n, uint64_t seed, const vec3& origin) {
  const Rays src = make_rays(models, n, seed);
  std::vector<std::size_t> order(n);
  std::vector<vec3> dir(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Ray r = src.ray(i);
    dir[i] = i % 97 == 0 ? vec3{} : (r.origin + r.direction) - origin;
    order[i] = i;
  }
  const auto signs = [&](std::size_t i) { return (dir[i].x < 0) | (dir[i].y < 0) << 1 | (dir[i].z < 0) << 2; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return signs(a) < signs(b); });
  Rays r;
  for (std::size_t i : order) {
    r.set.push(origin.x, origin.y, origin.z, dir[i].x, dir[i].y, dir[i].z);
    r.tmin.push_back(src.tmin[i]), r.tmax.push_back(src.tmax[i]);
  }
  return r;
}

struct Columns {
  std::vector<float> t, nx, ny, nz, u, v;
  std::vector<int32_t> primitive;
  std::vector<ModelId> model;
  explicit Columns(std::size_t n)
      : t(n, -1.0f), nx(n, -1.0f), ny(n, -1.0f), nz(n, -1.0f), u(n, -1.0f), v(n, -1.0f), primitive(n, -7), model(n, {9, 9}) {}
  SceneHitsOut out() {
    return {t.data(), model.data(), primitive.data(), nx.data(), ny.data(), nz.data(), u.data(), v.data()};
  }
  SceneHit at(std::size_t i) const {
    SceneHit h;
    h.model = model[i];
    h.hit.hit = !model[i].is_null();
    h.hit.t = h.hit.hit ? t[i] : 0.0f;
    h.hit.normal = {nx[i], ny[i], nz[i]};
    h.primitive = primitive[i] < 0 ? 0 : uint32_t(primitive[i]);
    h.u = u[i], h.v = v[i];
    return h;
  }
};

// The rays the mesh and scene batches flag (triangle_mesh.hpp's kRayInvalid).
bool ray_valid(const Rays& r, std::size_t i) {
  const float v[6] = {r.set.ox[i], r.set.oy[i], r.set.oz[i], r.set.dx[i], r.set.dy[i], r.set.dz[i]};
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return (v[3] != 0.0f || v[4] != 0.0f || v[5] != 0.0f) && std::isfinite(r.tmin[i]) && r.tmin[i] >= 0.0f &&
         r.tmax[i] >= r.tmin[i];
}

void expect_batch_matches(const Columns& c, const std::vector<SceneHit>& expect, const Rays& rays, std::size_t i) {
  const SceneHit& e = expect[i];
  ASSERT_EQ(c.model[i], e.model) << "ray " << i;
  EXPECT_EQ(bits(c.t[i]), bits(e.hit.hit ? e.hit.t : kInf)) << "ray " << i;
  EXPECT_EQ(c.primitive[i], e.hit.hit ? int32_t(e.primitive) : ray_valid(rays, i) ? -1 : kRayInvalid) << "ray " << i;
  EXPECT_EQ(bits(c.nx[i]), bits(e.hit.normal.x)) << "ray " << i;
  EXPECT_EQ(bits(c.ny[i]), bits(e.hit.normal.y)) << "ray " << i;
  EXPECT_EQ(bits(c.nz[i]), bits(e.hit.normal.z)) << "ray " << i;
  EXPECT_EQ(bits(c.u[i]), bits(e.u)) << "ray " << i;
  EXPECT_EQ(bits(c.v[i]), bits(e.v)) << "ray " << i;
}

// The batch asked for t, model and primitive only (no normals, no barycentrics): the same
// answers as the full one (the scene then skips the winner's details where it can).
void expect_bare_batch_matches(const Scene& scene, const std::vector<SceneHit>& expect, const Rays& rays) {
  const std::size_t n = rays.set.size();
  Columns c(n);
  SceneHitsOut out = c.out();
  out.nx = out.ny = out.nz = out.u = out.v = nullptr;
  ASSERT_EQ(raycast_closest(scene, rays.view(), n, out), Status::ok);
  for (std::size_t i = 0; i < n; ++i) {
    const SceneHit& e = expect[i];
    ASSERT_EQ(c.model[i], e.model) << "ray " << i;
    EXPECT_EQ(bits(c.t[i]), bits(e.hit.hit ? e.hit.t : kInf)) << "ray " << i;
    EXPECT_EQ(c.primitive[i], e.hit.hit ? int32_t(e.primitive) : ray_valid(rays, i) ? -1 : kRayInvalid) << "ray " << i;
    EXPECT_EQ(c.nx[i], -1.0f) << "ray " << i;  // not written
  }
  // Any hit: the bare batch names the same models at the same t as the full one.
  Columns full(n), bare(n);
  SceneHitsOut bare_out = bare.out();
  bare_out.nx = bare_out.ny = bare_out.nz = bare_out.u = bare_out.v = nullptr;
  ASSERT_EQ(raycast_any(scene, rays.view(), n, full.out()), Status::ok);
  ASSERT_EQ(raycast_any(scene, rays.view(), n, bare_out), Status::ok);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(bare.model[i], full.model[i]) << "ray " << i;
    EXPECT_EQ(bits(bare.t[i]), bits(full.t[i])) << "ray " << i;
    EXPECT_EQ(bare.primitive[i], full.primitive[i]) << "ray " << i;
  }
}

class ScopedExecution {
 public:
  ScopedExecution(SimdLevel level, uint32_t threads) {
    EXPECT_EQ(set_simd_level(level), Status::ok);
    EXPECT_EQ(set_thread_count(threads), Status::ok);
  }
  ~ScopedExecution() {
    set_simd_level(SimdLevel::automatic);
    set_thread_count(0);
  }
};

// Every raycast path against the brute force, in both modes; the batch at every level and
// at 1 and 3 threads. *hit_count gets how many rays hit (so a test can insist they do).
// The brute-force answers of the scene's models as they are now.
std::vector<SceneHit> brute_answers(const Scene& scene, const Rays& rays, std::size_t* hits, std::size_t* invalid) {
  const std::vector<Snapshot> models = snapshot(scene);
  std::vector<SceneHit> expect(rays.set.size());
  for (std::size_t i = 0; i < expect.size(); ++i) {
    expect[i] = brute_closest(models, rays.ray(i), rays.tmin[i], rays.tmax[i]);
    *hits += expect[i].hit.hit;
    *invalid += !ray_valid(rays, i);
  }
  return expect;
}

// The scene's single and batch raycasts, in its current structure, against `expect`: at
// every level and on 1 and 3 threads; any hits name a model hit where the closest hit is,
// the same one everywhere.
void expect_raycasts(Scene& scene, const Rays& rays, const std::vector<SceneHit>& expect) {
  const std::vector<Snapshot> models = snapshot(scene);
  const std::size_t n = rays.set.size();
  for (std::size_t i = 0; i < n; ++i) {
    expect_same(raycast(scene, rays.ray(i), rays.tmin[i], rays.tmax[i]), expect[i], i);
    const SceneHit any = raycast_any(scene, rays.ray(i), rays.tmin[i], rays.tmax[i]);
    ASSERT_EQ(any.hit.hit, expect[i].hit.hit) << "ray " << i;
    if (any.hit.hit) {
      // The model it names is hit, and the hit reported is that model's own closest one.
      const auto it = std::find_if(models.begin(), models.end(), [&](const Snapshot& m) { return m.id == any.model; });
      ASSERT_NE(it, models.end());
      expect_same(any, model_hit(*it, rays.ray(i), rays.tmin[i], rays.tmax[i]), i);
    }
  }
  std::vector<ModelId> any_first;
  for (const SimdLevel level : testing::available_levels())
    for (const uint32_t threads : {1u, 3u}) {
      ScopedExecution exec(level, threads);
      Columns c(n);
      ASSERT_EQ(raycast_closest(scene, rays.view(), n, c.out()), Status::ok);
      for (std::size_t i = 0; i < n; ++i) expect_batch_matches(c, expect, rays, i);
      expect_bare_batch_matches(scene, expect, rays);
      Columns a(n);
      ASSERT_EQ(raycast_any(scene, rays.view(), n, a.out()), Status::ok);
      if (any_first.empty()) any_first = a.model;
      EXPECT_EQ(a.model, any_first) << simd_level_name(level) << " x" << threads;
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a.model[i].is_null(), !expect[i].hit.hit) << "ray " << i;
    }
}

void check_raycasts(Scene& scene, const Rays& rays, std::size_t* hit_count) {
  std::size_t hits = 0, invalid = 0;
  const std::vector<SceneHit> expect = brute_answers(scene, rays, &hits, &invalid);
  EXPECT_GT(invalid, 0u);  // the zero directions
  *hit_count = hits;
  // The octree three ways: small leaves; leaves of up to 16 and a root leaf holding every
  // model, whose items go under nodes of their own in its node form (octree_bvh.hpp).
  SceneSettings modes[4];
  modes[1].accel = modes[2].accel = modes[3].accel = SceneAccel::octree;
  modes[1].octree = {5, 4}, modes[2].octree = {3, 16}, modes[3].octree = {0, 1};
  for (const SceneSettings& settings : modes) {
    EXPECT_EQ(scene.configure(settings), Status::ok);
    expect_raycasts(scene, rays, expect);
  }
}

TEST(Scene, RaycastsEqualBruteForceInBothModes) {
  TestScene s(300, 21);
  const Rays rays = make_rays(snapshot(s.scene), 1200, 22);
  std::size_t hits = 0;
  check_raycasts(s.scene, rays, &hits);
  EXPECT_GT(hits, 500u);
  EXPECT_LT(hits, rays.set.size());
}

// Models crowded into a 1-unit cube: the octree cannot separate them (every child holds
// nearly all of them until max_depth), so its leaves hold hundreds of models, nested under
// several levels of nodes of their own in its node form. Still the brute-force answers.
TEST(Scene, CrowdedModelsEqualBruteForceInBothModes) {
  TestScene s(150, 23, 0.5f);
  const Rays rays = make_rays(snapshot(s.scene), 400, 24);
  std::size_t hits = 0;
  check_raycasts(s.scene, rays, &hits);
  EXPECT_GT(hits, 100u);
  SceneSettings octree;
  octree.accel = SceneAccel::octree;
  ASSERT_EQ(s.scene.configure(octree), Status::ok);
  EXPECT_GT(s.scene.stats().references, 3u * 150u);  // stored many times over
}

// A tree larger than a core's L2 cache (about 1 MiB of nodes and leaves): the batch closest
// hits of a scene's BVH equal the octree's single-ray hits (another tree shape), ray for
// ray, at every level and on 1 and 2 threads, with and without prefetching (RayPrefetch: the
// tree here is below the automatic mode's 8 MiB), and the batch any hits name the same
// model in every one of these configurations (prefetching changes no answer), hitting
// exactly where the closest hit does. The first rays' octree hits are checked against the
// brute-force loop too (all of them would take the test seconds).
void expect_batch_equals_octree_walk(TestScene& s, const Rays& rays) {
  const std::size_t n = rays.set.size();
  SceneSettings settings;
  settings.accel = SceneAccel::octree;
  ASSERT_EQ(s.scene.configure(settings), Status::ok);
  std::vector<SceneHit> expect(n);
  std::size_t hits = 0;
  const std::vector<Snapshot> models = snapshot(s.scene);
  for (std::size_t i = 0; i < n; ++i) {
    expect[i] = raycast(s.scene, rays.ray(i), rays.tmin[i], rays.tmax[i]);
    if (i < 300) expect_same(expect[i], brute_closest(models, rays.ray(i), rays.tmin[i], rays.tmax[i]), i);
    hits += expect[i].hit.hit;
  }
  EXPECT_GT(hits, n / 4);
  std::vector<ModelId> any_first;
  for (const RayPrefetch prefetch : {RayPrefetch::automatic, RayPrefetch::always, RayPrefetch::never}) {
    SceneSettings bvh;
    bvh.ray_prefetch = prefetch;
    ASSERT_EQ(s.scene.configure(bvh), Status::ok);
    const SceneStats st = s.scene.stats();
    EXPECT_GT(st.nodes * 256 + st.leaves * 128, std::size_t(1) << 20);  // BvhNode8, SceneLeaf4
    for (const SimdLevel level : testing::available_levels())
      for (const uint32_t threads : {1u, 2u}) {
        ScopedExecution exec(level, threads);
        Columns c(n);
        ASSERT_EQ(raycast_closest(s.scene, rays.view(), n, c.out()), Status::ok);
        for (std::size_t i = 0; i < n; ++i) expect_batch_matches(c, expect, rays, i);
        expect_bare_batch_matches(s.scene, expect, rays);
        Columns any(n);
        ASSERT_EQ(raycast_any(s.scene, rays.view(), n, any.out()), Status::ok);
        if (any_first.empty()) any_first = any.model;
        EXPECT_EQ(any.model, any_first) << simd_level_name(level) << " x" << threads;
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(any.model[i].is_null(), !expect[i].hit.hit) << "ray " << i;
      }
  }
}

TEST(Scene, LargeSceneRaysInTurnsEqualTheOctree) {
  TestScene s(40000, 41, 250.0f);
  expect_batch_equals_octree_walk(s, make_rays(snapshot(s.scene), 3000, 42));
}

// Rays from one origin walk the tree in packets (closest hit): the same answers as brute
// force, from outside the models' cloud and from inside it.
TEST(Scene, OneOriginRaysEqualBruteForce) {
  for (const vec3& origin : {vec3{-90.0f, 20.0f, -70.0f}, vec3{3.0f, -2.0f, 5.0f}}) {
    TestScene s(400, 61);
    const Rays rays = make_rays_from(snapshot(s.scene), 1200, 62, origin);
    std::size_t hits = 0;
    check_raycasts(s.scene, rays, &hits);
    EXPECT_GT(hits, 400u);
  }
}

// The same in a tree beyond the cache, against the octree's hits.
TEST(Scene, LargeSceneOneOriginRaysEqualTheOctree) {
  TestScene s(40000, 41, 250.0f);
  expect_batch_equals_octree_walk(s, make_rays_from(snapshot(s.scene), 3000, 43, {-300.0f, 40.0f, 10.0f}));
}

TEST(Scene, RaycastsStayExactAfterRemovesMovesAndReparenting) {
  TestScene s(260, 31);
  SplitMix64 rng(32);
  for (int k = 0; k < 60; ++k) {
    const std::size_t i = rng.next() % s.ids.size();
    ASSERT_EQ(s.scene.remove_model(s.ids[i]), Status::ok);
    s.ids.erase(s.ids.begin() + std::ptrdiff_t(i));
  }
  for (int k = 0; k < 60; ++k)
    ASSERT_EQ(s.scene.set_transform(s.ids[rng.next() % s.ids.size()], random_transform(rng, 40.0f)), Status::ok);
  for (int k = 0; k < 40; ++k) {
    const ModelId a = s.ids[rng.next() % s.ids.size()], b = s.ids[rng.next() % s.ids.size()];
    const Status st = s.scene.set_parent(a, b);
    EXPECT_TRUE(st == Status::ok || st == Status::invalid_argument);
  }
  for (int k = 0; k < 40; ++k) s.add(random_def(rng, s.meshes, s.ids));  // reuses freed indices
  const Rays rays = make_rays(snapshot(s.scene), 600, 33);
  std::size_t hits = 0;
  check_raycasts(s.scene, rays, &hits);
  EXPECT_GT(hits, 200u);
}

// Ties: models hit at the same t. The lowest id index wins whatever the slot order and
// whatever the traversal meets first.
TEST(Scene, TiesGoToTheLowestIdIndex) {
  Scene scene;
  ModelDef d;
  d.shape = ModelShape::box;
  d.half_extents = {1.0f, 1.0f, 1.0f};
  ModelId ids[4];
  for (ModelId& id : ids) ASSERT_EQ(scene.add_model(d, &id), Status::ok);
  // Remove index 0 and 1 (slots move), then re-add: index 1 comes back first (last freed first).
  ASSERT_EQ(scene.remove_model(ids[0]), Status::ok);
  ASSERT_EQ(scene.remove_model(ids[1]), Status::ok);
  ModelId again;
  ASSERT_EQ(scene.add_model(d, &again), Status::ok);
  EXPECT_EQ(again.index, 1u);
  for (const SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
    ASSERT_EQ(scene.configure({accel, {}}), Status::ok);
    const SceneHit h = raycast(scene, Ray{{0.0f, 0.0f, -5.0f}, {0.0f, 0.0f, 1.0f}});
    ASSERT_TRUE(h.hit.hit);
    EXPECT_EQ(h.hit.t, 4.0f);
    EXPECT_EQ(h.model, again);
  }

  // Two boxes sharing the edge x = 0 that the ray runs into at t = 9: `low` has the lower
  // index, `high` sits in the subtree the traversal enters first (the same entry t, an
  // earlier child slot), with fillers that split the trees between them. Layout 0 separates
  // them along x (the octree's first octant), layout 1 along y (the BVH's first child).
  const Ray ray{{0.0f, 0.0f, -10.0f}, {0.0f, 0.0f, 1.0f}};
  for (int layout = 0; layout < 2; ++layout) {
    Scene two;
    ModelId low, high, filler;
    d.half_extents = layout == 0 ? vec3{2.0f, 1.0f, 1.0f} : vec3{2.0f, 41.0f, 1.0f};
    d.transform.position = layout == 0 ? vec3{2.0f, 0.0f, 0.0f} : vec3{2.0f, 40.0f, 0.0f};
    ASSERT_EQ(two.add_model(d, &low), Status::ok);
    d.transform.position = layout == 0 ? vec3{-2.0f, 0.0f, 0.0f} : vec3{-2.0f, -40.0f, 0.0f};
    ASSERT_EQ(two.add_model(d, &high), Status::ok);
    ModelDef f;
    f.radius = 1.0f;
    // Layout 0: fillers far out on both sides along x. Layout 1: three fillers along each
    // long box, so the BVH makes one leaf of each group.
    const std::vector<vec3> fillers =
        layout == 0 ? std::vector<vec3>{{-100, 0, 0}, {-98, 0, 0}, {-96, 0, 0}, {-94, 0, 0}, {92, 0, 0}, {94, 0, 0}, {96, 0, 0}, {98, 0, 0}}
                    : std::vector<vec3>{{-2, -45, 0}, {-2, -43, 0}, {-2, -41, 0}, {2, 41, 0}, {2, 43, 0}, {2, 45, 0}};
    for (const vec3& p : fillers) {
      f.transform.position = p;
      ASSERT_EQ(two.add_model(f, &filler), Status::ok);
    }
    for (const SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
      ASSERT_EQ(two.configure({accel, {4, 1}}), Status::ok);
      const SceneHit h = raycast(two, ray);
      ASSERT_TRUE(h.hit.hit);
      EXPECT_EQ(h.hit.t, 9.0f);
      EXPECT_EQ(h.model, low) << "layout " << layout << (accel == SceneAccel::bvh ? " bvh" : " octree");
      EXPECT_TRUE(raycast_any(two, ray).hit.hit);
    }
    // Both are hit there: each alone gives the same t.
    for (const ModelId id : {low, high}) {
      ModelInfo info;
      ASSERT_EQ(two.model(id, &info), Status::ok);
      EXPECT_EQ(raycast(info.box, ray).t, 9.0f);
    }
  }
}

TEST(Scene, InstancedMeshRaycastInLocalFrame) {
  // A unit-cube mesh scaled by 2, turned 90 degrees about y, at x = 10: the ray along +x from
  // the origin meets its face x = 8 at t = 8 with the normal facing back (-x).
  auto mesh = std::make_shared<TriangleMesh>();
  ASSERT_EQ(TriangleMesh::create(make_box_mesh({1.0f, 1.0f, 1.0f}), *mesh), Status::ok);
  Scene scene;
  ModelDef d;
  d.shape = ModelShape::mesh;
  d.mesh = mesh;
  d.transform = {{10.0f, 0.0f, 0.0f}, from_axis_angle({0.0f, 1.0f, 0.0f}, kPi / 2.0f), 2.0f};
  ModelId id;
  ASSERT_EQ(scene.add_model(d, &id), Status::ok);
  const SceneHit h = raycast(scene, Ray{{0.0f, 0.25f, 0.0f}, {2.0f, 0.0f, 0.0f}});
  ASSERT_TRUE(h.hit.hit);
  EXPECT_NEAR(h.hit.t, 4.0f, 1e-5f);  // t in units of |d| = 2
  EXPECT_NEAR(h.hit.point.x, 8.0f, 1e-5f);
  EXPECT_NEAR(h.hit.normal.x, -1.0f, 1e-5f);
  EXPECT_NEAR(h.hit.normal.y, 0.0f, 1e-5f);
  EXPECT_LT(h.primitive, 12u);
  EXPECT_EQ(h.model, id);
}

// World transforms and shapes against binary64 composition of the parent chains; bounds
// contain the shapes' exact extents.
TEST(Scene, WorldPlacementMatchesBinary64) {
  TestScene s(200, 41);
  const auto models = snapshot(s.scene);
  struct D3 {
    double x, y, z;
  };
  struct Dq {
    double x, y, z, w;
  };
  auto qmul = [](Dq a, Dq b) {
    return Dq{a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
              a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
  };
  auto rot = [](Dq q, D3 v) {  // q v q*
    const Dq p = {v.x, v.y, v.z, 0.0};
    const Dq c = {-q.x, -q.y, -q.z, q.w};
    auto m = [](Dq a, Dq b) {
      return Dq{a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
    };
    const Dq r = m(m(q, p), c);
    return D3{r.x, r.y, r.z};
  };
  std::size_t chained = 0;
  for (const Snapshot& m : models) {
    // Compose from the root down in binary64.
    std::vector<ModelTransform> chain;
    for (ModelInfo info = m.info;;) {
      chain.push_back(info.def.transform);
      if (info.def.parent.is_null()) break;
      ASSERT_EQ(s.scene.model(info.def.parent, &info), Status::ok);
    }
    chained += chain.size() > 2;
    D3 p{0, 0, 0};
    Dq q{0, 0, 0, 1};
    double sc = 1.0;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const D3 lp = rot(q, D3{it->position.x * sc, it->position.y * sc, it->position.z * sc});
      p = {p.x + lp.x, p.y + lp.y, p.z + lp.z};
      const Dq r{it->rotation.x, it->rotation.y, it->rotation.z, it->rotation.w};
      q = qmul(q, r);
      sc *= it->scale;
    }
    const double mag = 100.0;
    EXPECT_NEAR(m.info.world.position.x, p.x, 1e-5 * mag);
    EXPECT_NEAR(m.info.world.position.y, p.y, 1e-5 * mag);
    EXPECT_NEAR(m.info.world.position.z, p.z, 1e-5 * mag);
    EXPECT_NEAR(m.info.world.scale, sc, 1e-6 * sc);
    const double same = std::abs(q.x * m.info.world.rotation.x + q.y * m.info.world.rotation.y +
                                 q.z * m.info.world.rotation.z + q.w * m.info.world.rotation.w);
    EXPECT_NEAR(same, 1.0, 1e-5);
    // The world transform is compose() of the local and the parent's world, bit for bit.
    if (!m.info.def.parent.is_null()) {
      ModelInfo parent;
      ASSERT_EQ(s.scene.model(m.info.def.parent, &parent), Status::ok);
      const ModelTransform w = compose(m.info.def.transform, parent.world);
      EXPECT_EQ(w.position, m.info.world.position);
      EXPECT_EQ(w.rotation, m.info.world.rotation);
      EXPECT_EQ(w.scale, m.info.world.scale);
    }
    // The shape's extreme points (in binary64) lie inside the bounds.
    const vec3 lo = aabb_min(m.info.bounds), hi = aabb_max(m.info.bounds);
    auto inside = [&](D3 v) {
      EXPECT_TRUE(lo.x <= v.x && v.x <= hi.x && lo.y <= v.y && v.y <= hi.y && lo.z <= v.z && v.z <= hi.z)
          << "model " << m.id.index;
    };
    const D3 wp{m.info.world.position.x, m.info.world.position.y, m.info.world.position.z};
    const Dq wq{m.info.world.rotation.x, m.info.world.rotation.y, m.info.world.rotation.z, m.info.world.rotation.w};
    const double ws = m.info.world.scale;
    auto place = [&](D3 l) {
      const D3 r = rot(wq, D3{l.x * ws, l.y * ws, l.z * ws});
      return D3{r.x + wp.x, r.y + wp.y, r.z + wp.z};
    };
    switch (m.info.def.shape) {
      case ModelShape::sphere: {
        const double r = double(m.info.def.radius) * ws;
        for (int a = 0; a < 3; ++a)
          for (double sg : {-1.0, 1.0}) {
            D3 v = wp;
            (a == 0 ? v.x : a == 1 ? v.y : v.z) += sg * r;
            inside(v);
          }
        break;
      }
      case ModelShape::box:
        for (int k = 0; k < 8; ++k) {
          const vec3 e = m.info.def.half_extents;
          inside(place(D3{(k & 1 ? 1.0 : -1.0) * e.x, (k & 2 ? 1.0 : -1.0) * e.y, (k & 4 ? 1.0 : -1.0) * e.z}));
        }
        break;
      case ModelShape::mesh:
        for (std::size_t t = 0; t < m.info.def.mesh->triangle_count(); ++t) {
          const Triangle tri = m.info.def.mesh->triangle(t);
          for (const vec3& v : {tri.a, tri.b, tri.c}) inside(place(D3{v.x, v.y, v.z}));
        }
        break;
      case ModelShape::plane:
        break;
    }
  }
  EXPECT_GT(chained, 3u);  // some chains of three or more
}

TEST(Scene, TransformHelpersAgreeWithBinary64) {
  SplitMix64 rng(51);
  for (int k = 0; k < 200; ++k) {
    const ModelTransform t = random_transform(rng, 50.0f);
    const ModelTransform tn{t.position, normalized(t.rotation), t.scale};
    const vec3 p{uni(rng, -10, 10), uni(rng, -10, 10), uni(rng, -10, 10)};
    const vec3 w = transform_point(tn, p);
    // to_local inverts transform_point (the ray's origin), and keeps t: the point at t of the
    // local ray maps back to the point at t of the world ray.
    const Ray world{w, {uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)}};
    const Ray local = to_local(tn, world);
    EXPECT_NEAR(local.origin.x, p.x, 1e-4f);
    EXPECT_NEAR(local.origin.y, p.y, 1e-4f);
    EXPECT_NEAR(local.origin.z, p.z, 1e-4f);
    const float tt = uni(rng, 0, 5);
    const vec3 back = transform_point(tn, local.origin + local.direction * tt);
    const vec3 fwd = world.origin + world.direction * tt;
    EXPECT_NEAR(back.x, fwd.x, 1e-4f);
    EXPECT_NEAR(back.y, fwd.y, 1e-4f);
    EXPECT_NEAR(back.z, fwd.z, 1e-4f);
    const Sphere ls = to_local(tn, Sphere{w, 3.0f});
    EXPECT_NEAR(ls.radius, 3.0f / tn.scale, 1e-6f);
    const OBB lb = to_local(tn, AABB{w, {1.0f, 2.0f, 3.0f}});
    // The local box's axes are the world axes seen from the model: orthonormal.
    for (int i = 0; i < 3; ++i) {
      const vec3 u{lb.orientation.m[i][0], lb.orientation.m[i][1], lb.orientation.m[i][2]};
      EXPECT_NEAR(dot(u, u), 1.0f, 1e-5f);
    }
  }
}

// Brute force for the overlap and frustum queries over the same exact tests.
template <class Test> std::vector<ModelId> brute_query(const std::vector<Snapshot>& models, Test&& test) {
  std::vector<ModelId> out;
  for (const Snapshot& m : models)
    if (m.info.placed && test(m)) out.push_back(m.id);
  std::sort(out.begin(), out.end());
  return out;
}

bool plane_in_frustum(const Frustum& f, const Plane& p) {
  vec3 c[8];
  frustum_corners(f, c);
  float mag = std::abs(p.distance);
  for (const vec3& v : c) mag = std::max({mag, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  const float tol = 1e-5f * mag + 1e-30f;
  int above = 0, below = 0;
  for (const vec3& v : c) above += dot(p.normal, v) - p.distance > tol, below += dot(p.normal, v) - p.distance < -tol;
  return above != 8 && below != 8;
}

// Whether a model overlaps the query shape (a sphere, AABB or OBB), by gyro's own tests
// on its world shape.
template <class Query> bool touches(const Snapshot& m, const Query& q) {
  switch (m.info.def.shape) {
    case ModelShape::sphere: return overlaps(q, m.info.sphere);
    case ModelShape::box: return overlaps(q, m.info.box);
    case ModelShape::plane: return overlaps(q, m.info.plane);
    case ModelShape::mesh: return overlaps(*m.info.def.mesh, to_local(m.info.world, q));
  }
  return false;
}

TEST(Scene, QueriesEqualBruteForceInBothModes) {
  TestScene s(300, 61);
  SplitMix64 rng(62);
  const auto models = snapshot(s.scene);
  std::size_t found = 0;
  for (const SceneAccel accel : {SceneAccel::bvh, SceneAccel::octree}) {
    ASSERT_EQ(s.scene.configure({accel, {5, 4}}), Status::ok);
    std::vector<ModelId> got;
    for (int q = 0; q < 60; ++q) {
      const vec3 c{uni(rng, -60, 60), uni(rng, -60, 60), uni(rng, -60, 60)};
      const Sphere sphere{c, uni(rng, 0, 15)};
      ASSERT_EQ(query(s.scene, sphere, got), Status::ok);
      EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return touches(m, sphere); }));
      found += got.size();
      const AABB box{c, {uni(rng, 0, 12), uni(rng, 0, 12), uni(rng, 0, 12)}};
      ASSERT_EQ(query(s.scene, box, got), Status::ok);
      EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return touches(m, box); }));
      found += got.size();
      const OBB obb{c, box.half_extents, to_mat3(random_rotation(rng))};
      ASSERT_EQ(query(s.scene, obb, got), Status::ok);
      EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return touches(m, obb); }));
      found += got.size();
      Camera cam = perspective_camera(uni(rng, 0.3, 1.5), uni(rng, 0.5, 2.0), uni(rng, 0.1, 1.0), uni(rng, 20, 120));
      set_look_at(cam, {uni(rng, -70, 70), uni(rng, -70, 70), uni(rng, -70, 70)}, c, {0.0f, 1.0f, 0.0f});
      const Frustum f = frustum(cam);
      ASSERT_EQ(query(s.scene, f, got), Status::ok);
      EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) {
                  switch (m.info.def.shape) {
                    case ModelShape::sphere: return intersects(f, m.info.sphere);
                    case ModelShape::box:
                    case ModelShape::mesh: return intersects(f, m.info.box);
                    case ModelShape::plane: return plane_in_frustum(f, m.info.plane);
                  }
                  return false;
                }));
      found += got.size();
    }
  }
  EXPECT_GT(found, 1000u);
}

// Layers (ModelDef::layers, RaysView::mask, the queries' and pick's masks): every path's answer is the brute force
// over the models sharing a bit with the ray's mask. Masks set at add and by set_layers
// (with moves, so a refit and a rebuild rewrite the leaves too), both structures, every
// level, 1 and 3 threads, single rays and batches, closest and any hits.
std::vector<SceneHit> brute_masked(const Scene& scene, const Rays& rays, const std::vector<uint32_t>& masks,
                                   std::size_t* hits, std::size_t* hidden) {
  const std::vector<Snapshot> models = snapshot(scene);
  std::vector<SceneHit> expect(rays.set.size());
  for (std::size_t i = 0; i < expect.size(); ++i) {
    std::vector<Snapshot> seen;
    for (const Snapshot& m : models)
      if ((m.info.def.layers & masks[i]) != 0) seen.push_back(m);
    expect[i] = brute_closest(seen, rays.ray(i), rays.tmin[i], rays.tmax[i]);
    *hits += expect[i].hit.hit;
    // A ray the masks changed: what it would hit seeing every layer is hidden from it.
    *hidden += brute_closest(models, rays.ray(i), rays.tmin[i], rays.tmax[i]).model != expect[i].model;
  }
  return expect;
}

void expect_masked_raycasts(Scene& scene, const Rays& rays, const std::vector<uint32_t>& masks,
                            const std::vector<SceneHit>& expect) {
  const std::vector<Snapshot> models = snapshot(scene);
  const std::size_t n = rays.set.size();
  RaysView view = rays.view();
  view.mask = masks.data();
  for (std::size_t i = 0; i < n; i += 3) {
    expect_same(raycast(scene, rays.ray(i), rays.tmin[i], rays.tmax[i], masks[i]), expect[i], i);
    const SceneHit any = raycast_any(scene, rays.ray(i), rays.tmin[i], rays.tmax[i], masks[i]);
    ASSERT_EQ(any.hit.hit, expect[i].hit.hit) << "ray " << i;
  }
  for (const SimdLevel level : testing::available_levels())
    for (const uint32_t threads : {1u, 3u}) {
      ScopedExecution exec(level, threads);
      Columns c(n);
      ASSERT_EQ(raycast_closest(scene, view, n, c.out()), Status::ok);
      for (std::size_t i = 0; i < n; ++i) expect_batch_matches(c, expect, rays, i);
      Columns a(n);
      ASSERT_EQ(raycast_any(scene, view, n, a.out()), Status::ok);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(a.model[i].is_null(), !expect[i].hit.hit) << "ray " << i;
        if (a.model[i].is_null()) continue;
        // The model an any hit names is one the ray sees.
        const auto it = std::find_if(models.begin(), models.end(), [&](const Snapshot& m) { return m.id == a.model[i]; });
        ASSERT_NE(it, models.end());
        EXPECT_NE(it->info.def.layers & masks[i], 0u) << "ray " << i;
      }
    }
}

TEST(Scene, LayersHideModelsFromRaysQueriesAndPicksOfOtherLayers) {
  TestScene s(0, 81);
  SplitMix64 rng(82);
  const uint32_t layers[7] = {1u, 2u, 4u, 8u, 6u, 0u, kAllLayers};
  for (int i = 0; i < 300; ++i) {
    ModelDef d = random_def(rng, s.meshes, s.ids);
    d.layers = layers[rng.next() % 7];
    s.add(d);
  }
  // The two planes of TestScene in layers 1 and 4.
  ASSERT_EQ(s.scene.set_layers(s.ids[0], 1u), Status::ok);
  ASSERT_EQ(s.scene.set_layers(s.ids[1], 4u), Status::ok);
  const Rays rays = make_rays(snapshot(s.scene), 900, 83);
  std::vector<uint32_t> masks(rays.set.size());
  for (uint32_t& m : masks) m = layers[rng.next() % 7];
  const auto check = [&](const char* what) {
    SCOPED_TRACE(what);
    std::size_t hits = 0, hidden = 0;
    const std::vector<SceneHit> expect = brute_masked(s.scene, rays, masks, &hits, &hidden);
    EXPECT_GT(hits, 150u);
    EXPECT_GT(hidden, 100u);  // the masks changed that many answers
    SceneSettings modes[2];
    modes[1].accel = SceneAccel::octree;
    const std::vector<Snapshot> models = snapshot(s.scene);
    for (const SceneSettings& settings : modes) {
      ASSERT_EQ(s.scene.configure(settings), Status::ok);
      expect_masked_raycasts(s.scene, rays, masks, expect);
      // Queries of a mask: the brute-force answers over the models of its layers.
      std::vector<ModelId> got;
      for (int q = 0; q < 40; ++q) {
        const uint32_t mask = layers[q % 7];
        const auto seen = [&](const Snapshot& m) { return (m.info.def.layers & mask) != 0; };
        const Sphere sphere{{uni(rng, -60, 60), uni(rng, -60, 60), uni(rng, -60, 60)}, uni(rng, 0, 20)};
        ASSERT_EQ(query(s.scene, sphere, got, mask), Status::ok);
        EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return seen(m) && touches(m, sphere); }));
        const AABB box{{uni(rng, -60, 60), uni(rng, -60, 60), uni(rng, -60, 60)}, {uni(rng, 0, 15), uni(rng, 0, 15), uni(rng, 0, 15)}};
        ASSERT_EQ(query(s.scene, box, got, mask), Status::ok);
        EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return seen(m) && touches(m, box); }));
      }
    }
  };
  check("masks at add");
  // New masks on the built tree: set_layers neither rebuilds nor refits.
  s.scene.prepare();
  const SceneStats before = s.scene.stats();
  for (std::size_t i = 0; i < s.ids.size(); i += 4) ASSERT_EQ(s.scene.set_layers(s.ids[i], layers[i % 7]), Status::ok);
  s.scene.prepare();
  EXPECT_EQ(s.scene.stats().builds, before.builds);
  EXPECT_EQ(s.scene.stats().refits, before.refits);
  check("masks set");
  // Masks and moves in one frame (a refit writes the moved spheres' leaves alone).
  for (std::size_t i = 2; i < s.ids.size(); i += 6) {
    ModelInfo info;
    ASSERT_EQ(s.scene.model(s.ids[i], &info), Status::ok);
    ModelTransform t = info.def.transform;
    t.position = t.position + vec3{0.5f, -0.25f, 0.75f};
    ASSERT_EQ(s.scene.set_transform(s.ids[i], t), Status::ok);
    ASSERT_EQ(s.scene.set_layers(s.ids[i], layers[(i + 3) % 7]), Status::ok);
  }
  check("masks and moves");
  // Every ray of every layer: the unmasked answers.
  std::vector<uint32_t> all(rays.set.size(), kAllLayers);
  std::size_t hits = 0, invalid = 0;
  const std::vector<SceneHit> unmasked = brute_answers(s.scene, rays, &hits, &invalid);
  std::vector<ModelId> visible;
  for (ModelId id : s.ids) {
    ModelInfo info;
    ASSERT_EQ(s.scene.model(id, &info), Status::ok);
    if (info.def.layers == kAllLayers) visible.push_back(id);
  }
  for (ModelId id : s.ids) ASSERT_EQ(s.scene.set_layers(id, kAllLayers), Status::ok);
  expect_masked_raycasts(s.scene, rays, all, unmasked);
  Columns c(rays.set.size());
  ASSERT_EQ(raycast_closest(s.scene, rays.view(), rays.set.size(), c.out()), Status::ok);  // null masks
  for (std::size_t i = 0; i < rays.set.size(); ++i) expect_batch_matches(c, unmasked, rays, i);
  // A pick of a mask: the masked ray through the cursor.
  Camera cam = perspective_camera(1.0f, 1.3f, 0.5f, 200.0f);
  set_look_at(cam, {0.0f, 5.0f, -70.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  ASSERT_EQ(s.scene.set_layers(s.ids[7], 2u), Status::ok);
  const Ray through = picking_ray(cam, {320.0f, 240.0f}, {640.0f, 480.0f});
  std::size_t picks_hit = 0;
  for (const uint32_t mask : {1u, 2u, 6u, 0u, kAllLayers}) {
    SceneHit picked;
    ASSERT_EQ(pick(s.scene, cam, {320.0f, 240.0f}, {640.0f, 480.0f}, &picked, mask), Status::ok);
    std::vector<Snapshot> seen;
    for (const Snapshot& m : snapshot(s.scene))
      if ((m.info.def.layers & mask) != 0) seen.push_back(m);
    expect_same(picked, brute_closest(seen, through, 0.0f, kInf), mask);
    picks_hit += picked.hit.hit;
  }
  EXPECT_GT(picks_hit, 0u);
  // A stale id changes nothing.
  ASSERT_EQ(s.scene.remove_model(s.ids[5]), Status::ok);
  EXPECT_EQ(s.scene.set_layers(s.ids[5], 1u), Status::stale_id);
}

// Moves alone refit the BVH (SceneSettings::refit): the same answers as brute force over
// the moved models, rays and queries, with the tree's topology kept; moves that spoil the
// tree (its expected cost beyond kSceneRefitCost times the build's) rebuild it, and so do
// adds, and every move when refit is off.
TEST(Scene, MovesRefitTheTreeAndStayExact) {
  TestScene s(300, 71);
  SplitMix64 rng(72);
  const auto moved = [&](ModelId id, float by) {
    ModelInfo info;
    EXPECT_EQ(s.scene.model(id, &info), Status::ok);
    ModelTransform t = info.def.transform;
    t.position = t.position + vec3{uni(rng, -by, by), uni(rng, -by, by), uni(rng, -by, by)};
    t.rotation = random_rotation(rng);
    return t;
  };
  const auto check = [&](uint64_t seed) {
    const Rays rays = make_rays(snapshot(s.scene), 500, seed);
    std::size_t hits = 0, invalid = 0;
    const std::vector<SceneHit> expect = brute_answers(s.scene, rays, &hits, &invalid);
    EXPECT_GT(hits, 150u);
    expect_raycasts(s.scene, rays, expect);
    const auto models = snapshot(s.scene);
    std::vector<ModelId> got;
    for (int q = 0; q < 30; ++q) {
      const Sphere sphere{{uni(rng, -60, 60), uni(rng, -60, 60), uni(rng, -60, 60)}, uni(rng, 0, 15)};
      ASSERT_EQ(query(s.scene, sphere, got), Status::ok);
      EXPECT_EQ(got, brute_query(models, [&](const Snapshot& m) { return touches(m, sphere); }));
    }
  };
  check(73);
  SceneStats st = s.scene.stats();
  EXPECT_EQ(st.builds, 1u);
  EXPECT_EQ(st.refits, 0u);
  const double built_cost = st.sah_cost;
  EXPECT_GT(built_cost, 1.0);
  // A move to where the model already is: a refit of an unchanged tree costs what the build
  // said, to the bit (the same formula over the same boxes).
  {
    ModelInfo info;
    ASSERT_EQ(s.scene.model(s.ids[0], &info), Status::ok);
    ASSERT_EQ(s.scene.set_transform(s.ids[0], info.def.transform), Status::ok);
    s.scene.prepare();
    st = s.scene.stats();
    EXPECT_EQ(st.refits, 1u);
    EXPECT_EQ(st.sah_cost, built_cost);
  }
  // A fifth of the models (some parents, so their children move too) a few units each.
  for (std::size_t i = 0; i < s.ids.size(); i += 5) ASSERT_EQ(s.scene.set_transform(s.ids[i], moved(s.ids[i], 3.0f)), Status::ok);
  check(74);
  st = s.scene.stats();
  EXPECT_EQ(st.builds, 1u);
  EXPECT_EQ(st.refits, 2u);
  EXPECT_NE(st.sah_cost, built_cost);
  EXPECT_LE(st.sah_cost, kSceneRefitCost * built_cost);
  // Every model far across the scene: the old topology no longer fits, so a rebuild.
  for (ModelId id : s.ids) ASSERT_EQ(s.scene.set_transform(id, moved(id, 60.0f)), Status::ok);
  check(75);
  st = s.scene.stats();
  EXPECT_EQ(st.builds, 2u);
  EXPECT_EQ(st.refits, 2u);
  // An add rebuilds.
  s.add(random_def(rng, s.meshes, s.ids));
  check(76);
  EXPECT_EQ(s.scene.stats().builds, 3u);
  // Without refit, a move rebuilds too.
  SceneSettings no_refit;
  no_refit.refit = false;
  ASSERT_EQ(s.scene.configure(no_refit), Status::ok);
  check(77);
  ASSERT_EQ(s.scene.set_transform(s.ids[3], moved(s.ids[3], 1.0f)), Status::ok);
  check(78);
  st = s.scene.stats();
  EXPECT_EQ(st.builds, 5u);
  EXPECT_EQ(st.refits, 2u);
}

// A frame that moves a few models places only them and their descendants again and refits
// only the tree above them (bvh_refit.hpp). Scene `part` gets those moves alone; scene `full`
// gets every model's transform set again each frame (past a quarter of the models, so it
// places every model and refits every node). Both must agree to the bit every frame: the
// placements, the tree's cost and counts, closest and any hits, and queries. Moves include
// parents (their children follow), a model pushed past the float range (unplaced, so the
// tree's items change: its item is detached from the tree, then attached again, each a
// refit, not a build) and back, and frames with no move.
TEST(Scene, PartialUpdatesEqualFullOnes) {
  TestScene part(400, 91), full(400, 91);
  ASSERT_EQ(part.ids, full.ids);
  const std::size_t n = part.ids.size();
  std::vector<ModelTransform> local(n);
  std::size_t far = n;  // a root model (no parent, not a plane) to push past the float range
  for (std::size_t i = 0; i < n; ++i) {
    ModelInfo info;
    ASSERT_EQ(part.scene.model(part.ids[i], &info), Status::ok);
    local[i] = info.def.transform;
    if (far == n && info.def.parent.is_null() && info.def.shape != ModelShape::plane) far = i;
  }
  ASSERT_LT(far, n);
  // Both scenes store normalized(local[i]) from here on (the adds stored normalized inputs,
  // which normalising again may move by an ulp).
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(part.scene.set_transform(part.ids[i], local[i]), Status::ok);
    ASSERT_EQ(full.scene.set_transform(full.ids[i], local[i]), Status::ok);
  }
  part.scene.prepare();
  full.scene.prepare();
  SplitMix64 rng(92);
  const Rays rays = make_rays(snapshot(part.scene), 400, 93);
  const auto same_bits = [](const ModelTransform& a, const ModelTransform& b) {
    const float x[8] = {a.position.x, a.position.y, a.position.z, a.rotation.x, a.rotation.y, a.rotation.z, a.rotation.w, a.scale};
    const float y[8] = {b.position.x, b.position.y, b.position.z, b.rotation.x, b.rotation.y, b.rotation.z, b.rotation.w, b.scale};
    return std::equal(x, x + 8, y, [](float p, float q) { return bits(p) == bits(q); });
  };
  std::size_t unplaced_frames = 0, idle = 0, builds_before = 0;
  for (int frame = 0; frame < 24; ++frame) {
    const std::size_t moves = frame % 6 == 5 ? 0 : 1 + rng.next() % 12;
    for (std::size_t k = 0; k < moves; ++k) {
      const std::size_t i = rng.next() % n;
      ModelInfo info;
      ASSERT_EQ(part.scene.model(part.ids[i], &info), Status::ok);
      if (info.def.shape == ModelShape::plane) continue;
      local[i].position = local[i].position + vec3{uni(rng, -2, 2), uni(rng, -2, 2), uni(rng, -2, 2)};
      local[i].rotation = random_rotation(rng);
      ASSERT_EQ(part.scene.set_transform(part.ids[i], local[i]), Status::ok);
    }
    // Its padded box overflows (gyro::Scene leaves it unplaced), then it comes back.
    if (frame == 7 || frame == 9) {
      local[far].position.x = frame == 7 ? std::numeric_limits<float>::max() : 1.0f;
      ASSERT_EQ(part.scene.set_transform(part.ids[far], local[far]), Status::ok);
    }
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(full.scene.set_transform(full.ids[i], local[i]), Status::ok);
    const SceneStats a = part.scene.stats(), b = full.scene.stats();
    EXPECT_EQ(a.builds, b.builds) << "frame " << frame;
    if (frame == 7) {
      EXPECT_EQ(a.builds, builds_before);  // the item detached, the tree kept
    }
    builds_before = a.builds;
    idle += moves == 0;
    EXPECT_EQ(a.refits + idle, b.refits) << "frame " << frame;  // a frame without moves leaves `part` as it was
    EXPECT_EQ(std::bit_cast<uint64_t>(a.sah_cost), std::bit_cast<uint64_t>(b.sah_cost)) << "frame " << frame;
    EXPECT_EQ(a.tree_models, b.tree_models) << "frame " << frame;
    unplaced_frames += a.tree_models < n - 2;
    for (std::size_t i = 0; i < n; ++i) {
      ModelInfo x, y;
      ASSERT_EQ(part.scene.model(part.ids[i], &x), Status::ok);
      ASSERT_EQ(full.scene.model(full.ids[i], &y), Status::ok);
      ASSERT_EQ(x.placed, y.placed) << "model " << i << " frame " << frame;
      ASSERT_TRUE(same_bits(x.world, y.world)) << "model " << i << " frame " << frame;
    }
    Columns ca(rays.set.size()), cb(rays.set.size()), aa(rays.set.size()), ab(rays.set.size());
    ASSERT_EQ(raycast_closest(part.scene, rays.view(), rays.set.size(), ca.out()), Status::ok);
    ASSERT_EQ(raycast_closest(full.scene, rays.view(), rays.set.size(), cb.out()), Status::ok);
    ASSERT_EQ(raycast_any(part.scene, rays.view(), rays.set.size(), aa.out()), Status::ok);
    ASSERT_EQ(raycast_any(full.scene, rays.view(), rays.set.size(), ab.out()), Status::ok);
    for (std::size_t r = 0; r < rays.set.size(); ++r) {
      ASSERT_EQ(ca.model[r], cb.model[r]) << "ray " << r << " frame " << frame;
      ASSERT_EQ(bits(ca.t[r]), bits(cb.t[r])) << "ray " << r << " frame " << frame;
      // The any hit depends on the tree: equal models say the trees are the same.
      ASSERT_EQ(aa.model[r], ab.model[r]) << "ray " << r << " frame " << frame;
    }
    std::vector<ModelId> ga, gb;
    const AABB box{{uni(rng, -40, 40), uni(rng, -40, 40), uni(rng, -40, 40)}, {10.0f, 10.0f, 10.0f}};
    ASSERT_EQ(query(part.scene, box, ga), Status::ok);
    ASSERT_EQ(query(full.scene, box, gb), Status::ok);
    EXPECT_EQ(ga, gb) << "frame " << frame;
  }
  EXPECT_EQ(unplaced_frames, 2u);  // frames 7 and 8
  // Every frame with a move was a refit or a rebuild (a refit whose cost outgrows
  // kSceneRefitCost, or an attach with no room on its path, rebuilds).
  const SceneStats st = part.scene.stats();
  EXPECT_EQ(idle, 4u);
  EXPECT_EQ(st.refits + (st.builds - 1) + idle, 24u);
  EXPECT_GE(st.refits, 17u);
  // And the partial path against brute force.
  std::size_t hits = 0, invalid = 0;
  const std::vector<SceneHit> expect = brute_answers(part.scene, rays, &hits, &invalid);
  EXPECT_GT(hits, 100u);
  expect_raycasts(part.scene, rays, expect);
}

// Adds and removes of root models in a scene without parents keep the tree: a removed
// model's leaf is detached, a new model attached where its box grows the tree least, and the
// tree refit (BvhRefit::detach, attach). Frame after frame of removes, adds and moves (the
// last slot's model removed too, a world query between them, a plane added and removed, a
// model added unplaced), the rays and queries must equal a scene that rebuilds at every
// change, and brute force; the tree must refit, not rebuild; and emptied, then filled again.
TEST(Scene, AddsAndRemovesPatchTheTreeAndStayExact) {
  const std::vector<std::shared_ptr<const TriangleMesh>> meshes = test_meshes();
  SceneSettings rebuild_settings;
  rebuild_settings.refit = false;
  Scene scene, fresh(rebuild_settings);
  std::vector<std::pair<ModelId, ModelId>> live;  // (scene's, fresh's): both get the same calls
  const std::vector<ModelId> no_parents;
  SplitMix64 rng(511);
  const auto add = [&](const ModelDef& d) {
    ModelId a, b;
    ASSERT_EQ(scene.add_model(d, &a), Status::ok);
    ASSERT_EQ(fresh.add_model(d, &b), Status::ok);
    live.push_back({a, b});
  };
  const auto remove_at = [&](std::size_t k) {
    ASSERT_EQ(scene.remove_model(live[k].first), Status::ok);
    ASSERT_EQ(fresh.remove_model(live[k].second), Status::ok);
    live.erase(live.begin() + std::ptrdiff_t(k));
  };
  for (int i = 0; i < 600; ++i) add(random_def(rng, meshes, no_parents, 40.0f));
  scene.prepare();
  const Rays base_rays = make_rays(snapshot(scene), 300, 512);
  ModelDef plane;
  plane.shape = ModelShape::plane;
  plane.plane = {{0.0f, 1.0f, 0.0f}, -30.0f};
  // The trees answer alike: closest hits to the bit, and the queries' ids.
  const auto expect_alike = [&](int frame) {
    // The fixed rays, and one from afar at each of the newest models (the ones last attached).
    Rays rays = base_rays;
    for (std::size_t k = live.size() >= 40 ? live.size() - 40 : 0; k < live.size(); ++k) {
      ModelInfo info;
      ASSERT_EQ(scene.model(live[k].first, &info), Status::ok);
      const vec3 c = info.bounds.center, o = c + vec3{70.0f, 50.0f, -60.0f};
      rays.set.push(o.x, o.y, o.z, c.x - o.x, c.y - o.y, c.z - o.z);
      rays.tmin.push_back(0.0f), rays.tmax.push_back(kInf);
    }
    Columns a(rays.set.size()), b(rays.set.size());
    ASSERT_EQ(raycast_closest(scene, rays.view(), rays.set.size(), a.out()), Status::ok);
    ASSERT_EQ(raycast_closest(fresh, rays.view(), rays.set.size(), b.out()), Status::ok);
    std::vector<ModelId> to_fresh;  // the scene's ids mapped to fresh's
    for (std::size_t r = 0; r < rays.set.size(); ++r) {
      ModelId mapped;
      for (const auto& [x, y] : live)
        if (x == a.model[r]) mapped = y;
      ASSERT_EQ(mapped, b.model[r]) << "ray " << r << " frame " << frame;
      ASSERT_EQ(bits(a.t[r]), bits(b.t[r])) << "ray " << r << " frame " << frame;
    }
    for (int q = 0; q < 3; ++q) {
      const AABB box{{uni(rng, -40, 40), uni(rng, -40, 40), uni(rng, -40, 40)}, {12.0f, 12.0f, 12.0f}};
      std::vector<ModelId> ga, gb, mapped;
      ASSERT_EQ(query(scene, box, ga), Status::ok);
      ASSERT_EQ(query(fresh, box, gb), Status::ok);
      for (ModelId id : ga)
        for (const auto& [x, y] : live)
          if (x == id) mapped.push_back(y);
      std::sort(mapped.begin(), mapped.end());
      ASSERT_EQ(mapped, gb) << "frame " << frame;
    }
    const SceneStats st = scene.stats();
    std::size_t in_tree = 0;
    for (const auto& [x, y] : live) {
      ModelInfo info;
      ASSERT_EQ(scene.model(x, &info), Status::ok);
      in_tree += info.placed && info.def.shape != ModelShape::plane;
    }
    EXPECT_EQ(st.models, live.size());
    EXPECT_EQ(st.tree_models, in_tree) << "frame " << frame;
    EXPECT_EQ(st.references, in_tree) << "frame " << frame;
  };
  const std::size_t builds0 = scene.stats().builds;
  for (int frame = 0; frame < 14; ++frame) {
    const std::size_t removes = 1 + rng.next() % 25;
    for (std::size_t k = 0; k < removes && !live.empty(); ++k) remove_at(frame % 3 == 0 ? live.size() - 1 : rng.next() % live.size());
    if (frame == 3) {
      ModelInfo info;  // the world placed between the removes and the adds
      ASSERT_EQ(scene.model(live[0].first, &info), Status::ok);
    }
    const std::size_t adds = 1 + rng.next() % 25;
    for (std::size_t k = 0; k < adds; ++k) add(random_def(rng, meshes, no_parents, 40.0f));
    if (frame == 4) add(plane);
    if (frame == 6) remove_at(live.size() - 1 - adds);  // the plane (added before frame 6's adds... and 5's)
    if (frame == 8) {
      ModelDef d = random_def(rng, meshes, no_parents, 40.0f);
      d.transform.position.x = std::numeric_limits<float>::max();  // unplaced: not in the tree
      add(d);
    }
    // Frame 10 moves every model (placed in chunks that stage the spheres as they go) after
    // the adds, whose new leaves the refit must stage too.
    // (The transforms are read first: a model() between the moves would place them one by one.)
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < (frame == 10 ? live.size() : 10); ++k) which.push_back(frame == 10 ? k : rng.next() % live.size());
    std::vector<ModelTransform> to(which.size());
    for (std::size_t k = 0; k < which.size(); ++k) {
      ModelInfo info;
      ASSERT_EQ(scene.model(live[which[k]].first, &info), Status::ok);
      to[k] = info.def.transform;
      to[k].position = to[k].position + vec3{uni(rng, -3, 3), uni(rng, -3, 3), uni(rng, -3, 3)};
    }
    if (frame == 10) {
      for (std::size_t k = 0; k < 5; ++k) {
        ModelDef d = random_def(rng, meshes, no_parents, 40.0f);
        d.shape = ModelShape::sphere, d.radius = 1.5f;  // the shape whose leaves the placing stages
        add(d);
      }
    }
    for (std::size_t k = 0; k < which.size(); ++k) {
      ASSERT_EQ(scene.set_transform(live[which[k]].first, to[k]), Status::ok);
      ASSERT_EQ(fresh.set_transform(live[which[k]].second, to[k]), Status::ok);
    }
    expect_alike(frame);
    EXPECT_EQ(scene.stats().builds, builds0) << "frame " << frame << ": the tree was rebuilt";
  }
  EXPECT_EQ(scene.stats().refits, 14u);
  std::size_t hits = 0, invalid = 0;
  const std::vector<SceneHit> expect = brute_answers(scene, base_rays, &hits, &invalid);
  EXPECT_GT(hits, 50u);
  expect_raycasts(scene, base_rays, expect);
  // Emptied one by one (a refit each, and a build, compacting, whenever half the items are
  // holes), then filled again into the empty tree.
  while (!live.empty()) {
    remove_at(rng.next() % live.size());
    if (live.size() % 97 == 0) expect_alike(100);
  }
  for (int i = 0; i < 40; ++i) add(random_def(rng, meshes, no_parents, 40.0f));
  expect_alike(101);
}

// Frames that move every model of a scene without parents place them in fixed chunks of
// slots on the worker threads, then refit every node. At 1, 2 and 3 threads (and every SIMD
// level the machine has) the frames must give the same bits: placements, the tree's cost and
// counts, closest and any hits; and the same closest hits and placements as a scene that
// rebuilds its tree every frame. Enough models for several chunks; one of them is pushed past
// the float range (unplaced: the tree's items change, a rebuild) and back.
TEST(Scene, EveryModelMovedGivesTheSameBitsAtAnyThreadCount) {
  constexpr std::size_t kModels = 4500;
  constexpr int kFrames = 6;
  const std::vector<std::shared_ptr<const TriangleMesh>> meshes = test_meshes();
  struct Run {
    std::vector<ModelInfo> info;      // every model after every frame
    std::vector<float> closest_t, any_t;
    std::vector<ModelId> closest, any;
    std::vector<uint64_t> stats;      // builds, refits, sah_cost bits, tree models per frame
  };
  const auto run = [&](SimdLevel level, uint32_t threads, bool refit) {
    ScopedExecution exec(level, threads);
    SceneSettings settings;
    settings.refit = refit;
    Scene scene(settings);
    SplitMix64 rng(301);
    std::vector<ModelId> ids;
    std::vector<ModelTransform> local;
    add_root_models(scene, rng, meshes, kModels, ids, local);
    const Rays rays = make_rays(snapshot(scene), 300, 302);
    Run r;
    for (int frame = 0; frame < kFrames; ++frame) {
      for (std::size_t i = 0; i < kModels; ++i) {
        local[i].position = local[i].position + vec3{uni(rng, -0.3, 0.3), uni(rng, -0.3, 0.3), uni(rng, -0.3, 0.3)};
        if (i % 7 == 0) local[i].rotation = random_rotation(rng);
        ModelTransform t = local[i];
        if (i == 11 && frame == 2) t.position.x = std::numeric_limits<float>::max();
        EXPECT_EQ(scene.set_transform(ids[i], t), Status::ok);
      }
      const SceneStats st = scene.stats();
      r.stats.insert(r.stats.end(), {uint64_t(st.builds), uint64_t(st.refits), std::bit_cast<uint64_t>(st.sah_cost),
                                     uint64_t(st.tree_models)});
      for (std::size_t i = 0; i < kModels; ++i) {
        ModelInfo info;
        EXPECT_EQ(scene.model(ids[i], &info), Status::ok);
        r.info.push_back(info);
      }
      Columns c(rays.set.size()), a(rays.set.size());
      EXPECT_EQ(raycast_closest(scene, rays.view(), rays.set.size(), c.out()), Status::ok);
      EXPECT_EQ(raycast_any(scene, rays.view(), rays.set.size(), a.out()), Status::ok);
      r.closest_t.insert(r.closest_t.end(), c.t.begin(), c.t.end());
      r.closest.insert(r.closest.end(), c.model.begin(), c.model.end());
      r.any_t.insert(r.any_t.end(), a.t.begin(), a.t.end());
      r.any.insert(r.any.end(), a.model.begin(), a.model.end());
    }
    return r;
  };
  const auto same_info = [](const ModelInfo& x, const ModelInfo& y) {
    const float p[14] = {x.world.position.x, x.world.position.y, x.world.position.z, x.world.rotation.x, x.world.rotation.y,
                         x.world.rotation.z, x.world.rotation.w, x.world.scale,      x.bounds.center.x,  x.bounds.center.y,
                         x.bounds.center.z,  x.bounds.half_extents.x, x.bounds.half_extents.y, x.bounds.half_extents.z};
    const float q[14] = {y.world.position.x, y.world.position.y, y.world.position.z, y.world.rotation.x, y.world.rotation.y,
                         y.world.rotation.z, y.world.rotation.w, y.world.scale,      y.bounds.center.x,  y.bounds.center.y,
                         y.bounds.center.z,  y.bounds.half_extents.x, y.bounds.half_extents.y, y.bounds.half_extents.z};
    return x.placed == y.placed && std::equal(p, p + 14, q, [](float a, float b) { return bits(a) == bits(b); });
  };
  const Run base = run(SimdLevel::automatic, 1, true);
  // Frame 2's unplaced model is detached from the tree, frame 3's return attached: every
  // frame refits.
  ASSERT_EQ(base.stats.size(), std::size_t(4 * kFrames));
  EXPECT_EQ(base.stats[4 * (kFrames - 1)], 1u);      // builds: the first
  EXPECT_EQ(base.stats[4 * (kFrames - 1) + 1], 6u);  // refits: every frame
  EXPECT_EQ(base.stats[4 * 2 + 3], kModels - 1);
  const Run fresh = run(SimdLevel::automatic, 1, false);
  for (std::size_t k = 0; k < base.info.size(); ++k) ASSERT_TRUE(same_info(base.info[k], fresh.info[k])) << "model " << k;
  for (std::size_t r = 0; r < base.closest.size(); ++r) {
    ASSERT_EQ(base.closest[r], fresh.closest[r]) << "ray " << r;
    ASSERT_EQ(bits(base.closest_t[r]), bits(fresh.closest_t[r])) << "ray " << r;
  }
  for (SimdLevel level : {SimdLevel::scalar, SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    for (uint32_t threads : {1u, 2u, 3u}) {
      const Run other = run(level, threads, true);
      ASSERT_EQ(other.stats, base.stats) << simd_level_name(level) << " threads " << threads;
      for (std::size_t k = 0; k < base.info.size(); ++k)
        ASSERT_TRUE(same_info(base.info[k], other.info[k])) << simd_level_name(level) << " threads " << threads << " model " << k;
      for (std::size_t r = 0; r < base.closest.size(); ++r) {
        ASSERT_EQ(base.closest[r], other.closest[r]) << "ray " << r;
        ASSERT_EQ(bits(base.closest_t[r]), bits(other.closest_t[r])) << "ray " << r;
        ASSERT_EQ(base.any[r], other.any[r]) << "ray " << r;
        ASSERT_EQ(bits(base.any_t[r]), bits(other.any_t[r])) << "ray " << r;
      }
    }
  }
}

// Moving every model stages the spheres for the refit as they are placed; a world query
// (model()) places them at once, and moves after it, before the tree is used, must still
// reach the tree: they place those models again and the refit stages every model afresh.
// The rays must equal a scene that rebuilds, frame after frame.
TEST(Scene, MovesAfterAWorldQueryStillReachTheRefitTree) {
  constexpr std::size_t kModels = 3000;
  const std::vector<std::shared_ptr<const TriangleMesh>> meshes = test_meshes();
  const auto run = [&](bool refit, std::size_t* refits) {
    SceneSettings settings;
    settings.refit = refit;
    Scene scene(settings);
    SplitMix64 rng(411);
    std::vector<ModelId> ids;
    std::vector<ModelTransform> local;
    add_root_models(scene, rng, meshes, kModels, ids, local);
    const Rays rays = make_rays(snapshot(scene), 400, 412);
    std::vector<float> t;
    std::vector<ModelId> hit;
    for (int frame = 0; frame < 4; ++frame) {
      for (std::size_t i = 0; i < kModels; ++i) {
        local[i].position = local[i].position + vec3{uni(rng, -0.4, 0.4), uni(rng, -0.4, 0.4), uni(rng, -0.4, 0.4)};
        EXPECT_EQ(scene.set_transform(ids[i], local[i]), Status::ok);
      }
      ModelInfo info;
      EXPECT_EQ(scene.model(ids[frame], &info), Status::ok);  // the world placed, the tree not yet
      // A few models carried far (beyond the next frame's reach of the others), so a refit
      // that missed them would answer the rays from their old places.
      for (std::size_t i = std::size_t(frame); i < kModels; i += 37) {
        local[i].position = local[i].position + vec3{uni(rng, -20.0, 20.0), uni(rng, -20.0, 20.0), uni(rng, -20.0, 20.0)};
        EXPECT_EQ(scene.set_transform(ids[i], local[i]), Status::ok);
      }
      Columns c(rays.set.size());
      EXPECT_EQ(raycast_closest(scene, rays.view(), rays.set.size(), c.out()), Status::ok);
      t.insert(t.end(), c.t.begin(), c.t.end());
      hit.insert(hit.end(), c.model.begin(), c.model.end());
    }
    *refits = scene.stats().refits;
    return std::make_pair(t, hit);
  };
  std::size_t refits = 0, none = 0;
  const auto refit = run(true, &refits);
  const auto fresh = run(false, &none);
  EXPECT_GE(refits, 3u);  // the frames refit (a move that spoils the tree may rebuild one)
  EXPECT_EQ(none, 0u);
  std::size_t hits = 0;
  for (std::size_t r = 0; r < refit.first.size(); ++r) {
    ASSERT_EQ(refit.second[r], fresh.second[r]) << "ray " << r;
    ASSERT_EQ(bits(refit.first[r]), bits(fresh.first[r])) << "ray " << r;
    hits += !refit.second[r].is_null();
  }
  EXPECT_GT(hits, refit.first.size() / 4);
}

TEST(Scene, PickHitsTheModelUnderTheCursor) {
  Scene scene;
  ModelDef d;
  d.radius = 2.0f;
  d.transform.position = {0.0f, 0.0f, 20.0f};
  ModelId near_id, far_id;
  ASSERT_EQ(scene.add_model(d, &near_id), Status::ok);
  d.transform.position = {0.0f, 0.0f, 40.0f};
  ASSERT_EQ(scene.add_model(d, &far_id), Status::ok);
  const Camera cam = perspective_camera(1.0f, 1.5f, 0.5f, 100.0f);
  SceneHit h;
  ASSERT_EQ(pick(scene, cam, {300.0f, 200.0f}, {600.0f, 400.0f}, &h), Status::ok);
  ASSERT_TRUE(h.hit.hit);
  EXPECT_EQ(h.model, near_id);
  expect_same(h, raycast(scene, picking_ray(cam, {300.0f, 200.0f}, {600.0f, 400.0f})), 0);
  ASSERT_EQ(pick(scene, cam, {5.0f, 5.0f}, {600.0f, 400.0f}, &h), Status::ok);
  EXPECT_FALSE(h.hit.hit);
  Camera bad = cam;
  bad.z_far = 0.1f;
  EXPECT_EQ(pick(scene, bad, {300.0f, 200.0f}, {600.0f, 400.0f}, &h), Status::invalid_argument);
  EXPECT_EQ(pick(scene, cam, {300.0f, 200.0f}, {0.0f, 400.0f}, &h), Status::invalid_argument);
  EXPECT_EQ(pick(scene, cam, {std::nanf(""), 200.0f}, {600.0f, 400.0f}, &h), Status::non_finite);
  EXPECT_EQ(pick(scene, cam, {300.0f, 200.0f}, {600.0f, 400.0f}, nullptr), Status::null_argument);
}

TEST(Scene, StaleIdsAreRejectedAndChangeNothing) {
  TestScene s(20, 71);
  const ModelId gone = s.ids[5];
  ASSERT_EQ(s.scene.remove_model(gone), Status::ok);
  EXPECT_FALSE(s.scene.contains(gone));
  const auto before = snapshot(s.scene);
  ModelInfo info;
  EXPECT_EQ(s.scene.model(gone, &info), Status::stale_id);
  EXPECT_EQ(s.scene.remove_model(gone), Status::stale_id);
  EXPECT_EQ(s.scene.set_transform(gone, {}), Status::stale_id);
  EXPECT_EQ(s.scene.set_parent(gone, ModelId{}), Status::stale_id);
  EXPECT_EQ(s.scene.set_parent(s.ids[0], gone), Status::stale_id);
  std::vector<ModelId> kids{gone};
  EXPECT_EQ(s.scene.children(gone, kids), Status::stale_id);
  EXPECT_TRUE(kids.empty());
  ModelDef d;
  d.parent = gone;
  ModelId id{};
  EXPECT_EQ(s.scene.add_model(d, &id), Status::stale_id);
  EXPECT_TRUE(id.is_null());
  EXPECT_EQ(s.scene.set_transform(ModelId{}, {}), Status::stale_id);
  // The index comes back with a new generation; the old id stays stale.
  ASSERT_EQ(s.scene.add_model(ModelDef{}, &id), Status::ok);
  EXPECT_EQ(id.index, gone.index);
  EXPECT_NE(id.generation, gone.generation);
  EXPECT_EQ(s.scene.model(gone, &info), Status::stale_id);
  ASSERT_EQ(s.scene.remove_model(id), Status::ok);
  const auto after = snapshot(s.scene);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].id, before[i].id);
    EXPECT_EQ(after[i].info.world.position, before[i].info.world.position);
  }
}

TEST(Scene, RemovingAParentLeavesItsChildrenInPlace) {
  Scene scene;
  ModelDef d;
  d.transform = {{5.0f, 0.0f, 0.0f}, from_axis_angle({0.0f, 0.0f, 1.0f}, 0.7f), 2.0f};
  ModelId root, child, grandchild;
  ASSERT_EQ(scene.add_model(d, &root), Status::ok);
  d.transform = {{1.0f, 2.0f, 0.0f}, from_axis_angle({1.0f, 0.0f, 0.0f}, 0.3f), 1.0f};
  d.parent = root;
  ASSERT_EQ(scene.add_model(d, &child), Status::ok);
  d.parent = child;
  ASSERT_EQ(scene.add_model(d, &grandchild), Status::ok);
  std::vector<ModelId> kids;
  ASSERT_EQ(scene.children(root, kids), Status::ok);
  EXPECT_EQ(kids, std::vector<ModelId>{child});
  ModelInfo c0, g0, c1, g1;
  ASSERT_EQ(scene.model(child, &c0), Status::ok);
  ASSERT_EQ(scene.model(grandchild, &g0), Status::ok);
  // Moving the root moves the descendants.
  ASSERT_EQ(scene.set_transform(root, {{6.0f, 0.0f, 0.0f}, from_axis_angle({0.0f, 0.0f, 1.0f}, 0.7f), 2.0f}), Status::ok);
  ASSERT_EQ(scene.model(grandchild, &g1), Status::ok);
  EXPECT_NEAR(g1.world.position.x - g0.world.position.x, 1.0f, 1e-5f);
  ASSERT_EQ(scene.set_transform(root, {{5.0f, 0.0f, 0.0f}, from_axis_angle({0.0f, 0.0f, 1.0f}, 0.7f), 2.0f}), Status::ok);
  ASSERT_EQ(scene.remove_model(root), Status::ok);
  ASSERT_EQ(scene.model(child, &c1), Status::ok);
  ASSERT_EQ(scene.model(grandchild, &g1), Status::ok);
  EXPECT_TRUE(c1.def.parent.is_null());
  EXPECT_EQ(g1.def.parent, child);
  EXPECT_EQ(c1.world.position, c0.world.position);
  EXPECT_EQ(c1.world.rotation, c0.world.rotation);
  EXPECT_EQ(c1.world.scale, c0.world.scale);
  EXPECT_EQ(g1.world.position, g0.world.position);
}

TEST(Scene, BadInputGetsAStatusAndChangesNothing) {
  TestScene s(30, 81);
  const auto before = snapshot(s.scene);
  auto unchanged = [&] {
    const auto now = snapshot(s.scene);
    ASSERT_EQ(now.size(), before.size());
    for (std::size_t i = 0; i < now.size(); ++i) {
      EXPECT_EQ(now[i].id, before[i].id);
      EXPECT_EQ(now[i].info.def.parent, before[i].info.def.parent);
      EXPECT_EQ(now[i].info.world.position, before[i].info.world.position);
      EXPECT_EQ(now[i].info.world.rotation, before[i].info.world.rotation);
    }
  };
  const float nan = std::nanf("");
  ModelId id{};
  ModelDef d;
  d.transform.position.y = nan;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::non_finite);
  EXPECT_NE(std::string(last_error()).find("position"), std::string::npos);
  d = {};
  d.transform.rotation = {0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d = {};
  d.transform.rotation.x = kInf;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::non_finite);
  d = {};
  d.transform.scale = 0.0f;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d.transform.scale = nan;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::non_finite);
  d = {};
  d.radius = -1.0f;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d = {};
  d.shape = ModelShape::box;
  d.half_extents.z = -0.5f;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d = {};
  d.shape = ModelShape::mesh;
  EXPECT_EQ(s.scene.add_model(d, &id), Status::null_argument);
  d.mesh = std::make_shared<TriangleMesh>();
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d = {};
  d.shape = ModelShape::plane;
  d.plane.normal = {0.0f, 2.0f, 0.0f};
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  d = {};
  d.shape = static_cast<ModelShape>(9);
  EXPECT_EQ(s.scene.add_model(d, &id), Status::invalid_argument);
  EXPECT_EQ(s.scene.add_model(ModelDef{}, nullptr), Status::null_argument);
  EXPECT_TRUE(id.is_null());
  ModelTransform t;
  t.position.x = nan;
  EXPECT_EQ(s.scene.set_transform(s.ids[3], t), Status::non_finite);
  t = {};
  t.scale = -2.0f;
  EXPECT_EQ(s.scene.set_transform(s.ids[3], t), Status::invalid_argument);
  // A cycle of parents: 0 <- 1 <- 2, then 0's parent = 2 (and a model as its own parent).
  ASSERT_EQ(s.scene.set_parent(s.ids[1], s.ids[0]), Status::ok);
  ASSERT_EQ(s.scene.set_parent(s.ids[2], s.ids[1]), Status::ok);
  const auto chained = snapshot(s.scene);
  EXPECT_EQ(s.scene.set_parent(s.ids[0], s.ids[2]), Status::invalid_argument);
  EXPECT_NE(std::string(last_error()).find("cycle"), std::string::npos);
  EXPECT_EQ(s.scene.set_parent(s.ids[4], s.ids[4]), Status::invalid_argument);
  EXPECT_EQ(snapshot(s.scene).size(), chained.size());
  ModelInfo info;
  ASSERT_EQ(s.scene.model(s.ids[0], &info), Status::ok);
  EXPECT_TRUE(info.def.parent.is_null());
  ASSERT_EQ(s.scene.set_parent(s.ids[2], ModelId{}), Status::ok);
  ASSERT_EQ(s.scene.set_parent(s.ids[1], ModelId{}), Status::ok);
  unchanged();
  EXPECT_EQ(s.scene.model(s.ids[0], nullptr), Status::null_argument);
  SceneSettings bad;
  bad.octree.max_depth = 99;
  EXPECT_EQ(s.scene.configure(bad), Status::invalid_argument);
  bad = {};
  bad.accel = static_cast<SceneAccel>(5);
  EXPECT_EQ(s.scene.configure(bad), Status::invalid_argument);
  EXPECT_EQ(s.scene.settings().accel, SceneAccel::bvh);
  bad = {};
  bad.ray_prefetch = static_cast<RayPrefetch>(3);
  EXPECT_EQ(s.scene.configure(bad), Status::invalid_argument);
  EXPECT_EQ(s.scene.settings().ray_prefetch, RayPrefetch::automatic);

  // Batch calls: bad views and counts write nothing.
  Rays rays = make_rays(before, 8, 82);
  Columns c(8);
  auto untouched = [&] {
    for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(c.model[i], (ModelId{9, 9}));
    for (float v : c.t) EXPECT_EQ(v, -1.0f);
  };
  RaysView v = rays.view();
  v.oy = nullptr;
  EXPECT_EQ(raycast_closest(s.scene, v, 8, c.out()), Status::null_argument);
  SceneHitsOut out = c.out();
  out.model = nullptr;
  EXPECT_EQ(raycast_closest(s.scene, rays.view(), 8, out), Status::null_argument);
  out = c.out();
  out.ny = nullptr;
  EXPECT_EQ(raycast_any(s.scene, rays.view(), 8, out), Status::null_argument);
  out = c.out();
  out.t = nullptr;
  EXPECT_EQ(raycast_any(s.scene, rays.view(), 8, out), Status::null_argument);
  EXPECT_EQ(raycast_closest(s.scene, rays.view(), std::size_t(1) << 31, c.out()), Status::invalid_count);
  untouched();
  EXPECT_EQ(raycast_closest(s.scene, v, 0, c.out()), Status::ok);  // nothing read
  untouched();
  // Bad ray values are flagged per ray; the other rays are answered as alone.
  Columns alone(8);
  ASSERT_EQ(raycast_closest(s.scene, rays.view(), 8, alone.out()), Status::ok);
  rays.set.dx[5] = nan;
  rays.tmin[2] = -1.0f;
  rays.tmax[6] = std::nanf("");
  ASSERT_EQ(raycast_closest(s.scene, rays.view(), 8, c.out()), Status::ok);
  for (std::size_t i = 0; i < 8; ++i) {
    if (i == 2 || i == 5 || i == 6) {
      EXPECT_EQ(c.primitive[i], kRayInvalid);
      EXPECT_TRUE(c.model[i].is_null());
      EXPECT_EQ(c.t[i], kInf);
      EXPECT_EQ(c.nx[i], 0.0f);
    } else {
      EXPECT_EQ(c.model[i], alone.model[i]);
      EXPECT_EQ(bits(c.t[i]), bits(alone.t[i]));
      EXPECT_EQ(c.primitive[i], alone.primitive[i]);
    }
  }
  // Single rays with NaN, a zero direction or a bad window: a miss, no crash (the same ray
  // with good values hits).
  const vec3 target = before[3].info.bounds.center;
  const Ray good{{0.0f, 0.0f, 0.0f}, target};
  ASSERT_TRUE(raycast(s.scene, good).hit.hit);
  EXPECT_FALSE(raycast(s.scene, Ray{{nan, 0.0f, 0.0f}, target}).hit.hit);
  EXPECT_FALSE(raycast(s.scene, Ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}}).hit.hit);
  EXPECT_FALSE(raycast(s.scene, good, -1.0f, 5.0f).hit.hit);
  EXPECT_FALSE(raycast(s.scene, good, 2.0f, 1.0f).hit.hit);
  EXPECT_FALSE(raycast_any(s.scene, good, nan, 5.0f).hit.hit);
  // Queries with bad shapes: a status and an empty result.
  std::vector<ModelId> got{ModelId{1, 1}};
  EXPECT_EQ(query(s.scene, Sphere{{0.0f, nan, 0.0f}, 1.0f}, got), Status::non_finite);
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(query(s.scene, Sphere{{0.0f, 0.0f, 0.0f}, -1.0f}, got), Status::invalid_argument);
  EXPECT_EQ(query(s.scene, AABB{{0.0f, 0.0f, 0.0f}, {1.0f, -1.0f, 1.0f}}, got), Status::invalid_argument);
  OBB obb;
  obb.orientation.m[1][1] = nan;
  EXPECT_EQ(query(s.scene, obb, got), Status::non_finite);
  Frustum f = frustum(perspective_camera(1.0f, 1.0f, 0.1f, 10.0f));
  f.planes[3].normal.x = nan;
  EXPECT_EQ(query(s.scene, f, got), Status::non_finite);
  unchanged();
}

TEST(Scene, HugeScalesLeaveModelsUnplacedNotBroken) {
  Scene scene;
  ModelDef d;
  d.transform.scale = 1e15f;
  ModelId a, b;
  ASSERT_EQ(scene.add_model(d, &a), Status::ok);
  d.parent = a;
  d.transform.scale = 1e30f;
  d.transform.position = {1e10f, 0.0f, 0.0f};
  ASSERT_EQ(scene.add_model(d, &b), Status::ok);  // world scale 1e45 overflows
  ModelInfo info;
  ASSERT_EQ(scene.model(b, &info), Status::ok);
  EXPECT_FALSE(info.placed);
  ASSERT_EQ(scene.model(a, &info), Status::ok);
  EXPECT_TRUE(info.placed);
  const SceneHit h = raycast(scene, Ray{{0.0f, 0.0f, -2e15f}, {0.0f, 0.0f, 1.0f}});
  ASSERT_TRUE(h.hit.hit);
  EXPECT_EQ(h.model, a);
  std::vector<ModelId> got;
  ASSERT_EQ(query(scene, Sphere{{0.0f, 0.0f, 0.0f}, 1.0f}, got), Status::ok);
  EXPECT_EQ(got, std::vector<ModelId>{a});
  EXPECT_EQ(scene.stats().tree_models, 1u);
}

// Const queries from several threads on a scene just changed: the first ones rebuild
// under the lock, and every thread gets the single-threaded answer.
TEST(Scene, ConcurrentQueriesAfterAChange) {
  TestScene s(200, 101);
  const Rays rays = make_rays(snapshot(s.scene), 300, 102);
  const std::size_t n = rays.set.size();
  Columns expect(n);
  ASSERT_EQ(raycast_closest(s.scene, rays.view(), n, expect.out()), Status::ok);
  std::vector<ModelId> expect_q;
  ASSERT_EQ(query(s.scene, Sphere{{0.0f, 0.0f, 0.0f}, 30.0f}, expect_q), Status::ok);
  for (const SceneAccel accel : {SceneAccel::octree, SceneAccel::bvh}) {
    ASSERT_EQ(s.scene.configure({accel, {}}), Status::ok);  // dirty: the next query rebuilds
    std::vector<Columns> got(4, Columns(n));
    std::vector<std::vector<ModelId>> got_q(4);
    std::vector<Status> st(4, Status::internal);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
      threads.emplace_back([&, k] {
        st[k] = raycast_closest(s.scene, rays.view(), n, got[k].out());
        if (st[k] == Status::ok) st[k] = query(s.scene, Sphere{{0.0f, 0.0f, 0.0f}, 30.0f}, got_q[k]);
      });
    for (std::thread& t : threads) t.join();
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(st[k], Status::ok);
      EXPECT_EQ(got[k].model, expect.model);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(bits(got[k].t[i]), bits(expect.t[i]));
      EXPECT_EQ(got_q[k], expect_q);
    }
  }
}

TEST(Scene, EmptyScene) {
  Scene scene;
  EXPECT_FALSE(raycast(scene, Ray{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}).hit.hit);
  std::vector<ModelId> got;
  EXPECT_EQ(query(scene, Sphere{{0.0f, 0.0f, 0.0f}, 100.0f}, got), Status::ok);
  EXPECT_TRUE(got.empty());
  ASSERT_EQ(scene.configure({SceneAccel::octree, {}}), Status::ok);
  EXPECT_FALSE(raycast_any(scene, Ray{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}).hit.hit);
  EXPECT_EQ(scene.stats().models, 0u);
}

// Timings of the two structures on scenes of a few thousand models (not run by default:
// gyro_tests --gtest_also_run_disabled_tests --gtest_filter='SceneBench*'). "dense" keeps
// the models in the 100-unit cube of the tests; "sparse" grows the cube with the count so
// the density stays that of 300 models.
TEST(SceneBench, DISABLED_OctreeVersusBvh) {
  using clock = std::chrono::steady_clock;
  auto ms = [](clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  for (const std::size_t n : {1000u, 4000u})
    for (const bool sparse : {false, true}) {
      const float spread = sparse ? 50.0f * std::cbrt(float(n) / 300.0f) : 50.0f;
      TestScene s(n, 91, spread);
      Rays rays = make_rays(snapshot(s.scene), 100000, 92);
      std::vector<Frustum> frusta;
      std::vector<Sphere> spheres;
      SplitMix64 rng(93);
      for (int q = 0; q < 2000; ++q) {
        Camera cam = perspective_camera(1.0f, 1.5f, 0.5f, spread);
        set_look_at(cam, {uni(rng, -1.4 * spread, 1.4 * spread), uni(rng, -1.4 * spread, 1.4 * spread), uni(rng, -1.4 * spread, 1.4 * spread)},
                    {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
        frusta.push_back(frustum(cam));
        spheres.push_back({{uni(rng, -spread, spread), uni(rng, -spread, spread), uni(rng, -spread, spread)}, uni(rng, 1, 10)});
      }
      const SceneSettings modes[] = {{SceneAccel::bvh, {}}, {SceneAccel::octree, {5, 16}}, {SceneAccel::octree, {6, 8}},
                                     {SceneAccel::octree, {4, 8}}};
      for (const SceneSettings& mode : modes) {
        ASSERT_EQ(s.scene.configure(mode), Status::ok);
        double build = 1e30;
        for (int rep = 0; rep < 5; ++rep) {
          ASSERT_EQ(s.scene.set_transform(s.ids[0], {}), Status::ok);  // dirty
          const auto t0 = clock::now();
          s.scene.prepare();
          build = std::min(build, ms(clock::now() - t0));
        }
        Columns c(rays.set.size());
        auto t0 = clock::now();
        ASSERT_EQ(raycast_closest(s.scene, rays.view(), rays.set.size(), c.out()), Status::ok);
        const double closest = ms(clock::now() - t0);
        std::size_t hits = 0;
        for (const ModelId& id : c.model) hits += !id.is_null();
        t0 = clock::now();
        ASSERT_EQ(raycast_any(s.scene, rays.view(), rays.set.size(), c.out()), Status::ok);
        const double any = ms(clock::now() - t0);
        std::vector<ModelId> got;
        std::size_t found_s = 0, found_f = 0;
        t0 = clock::now();
        for (const Sphere& q : spheres) {
          ASSERT_EQ(query(s.scene, q, got), Status::ok);
          found_s += got.size();
        }
        const double sq = ms(clock::now() - t0);
        t0 = clock::now();
        for (const Frustum& f : frusta) {
          ASSERT_EQ(query(s.scene, f, got), Status::ok);
          found_f += got.size();
        }
        const double fq = ms(clock::now() - t0);
        const SceneStats st = s.scene.stats();
        char name[32];
        std::snprintf(name, sizeof name, mode.accel == SceneAccel::bvh ? "bvh" : "octree(%d,%d)", int(mode.octree.max_depth),
                      int(mode.octree.leaf_capacity));
        std::printf("%5zu %-6s %-12s build %6.2f ms | 100k rays: closest %7.1f ms, any %6.1f ms (%zu hits) | 2000 spheres"
                    " %6.1f ms (%zu) | 2000 frusta %7.1f ms (%zu) | nodes %zu refs %zu\n",
                    n, sparse ? "sparse" : "dense", name, build, closest, any, hits, sq, found_s, fq, found_f, st.nodes,
                    st.references);
      }
    }
}

}  // namespace
}  // namespace gyro
