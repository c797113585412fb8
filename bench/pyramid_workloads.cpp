// P1, P2, P3 (BENCHMARKS.md): box pyramids on a static ground box, stepped at 1/60 s with
// sleeping disabled, in gyro (through gyro/world.hpp; its default soft step and the book's
// Baumgarte model with 10 iterations) and in Bullet. Every rep rebuilds the scene and times
// the steps alone; time_ms is the median per step. Accuracy figures come from the final
// state of each engine, computed the same way for both (pyramid_figures): the largest drift
// of a box from its start, the deepest overlap between neighbouring boxes or a box and the
// ground (gyro's 15-axis SAT), and the change of energy per box.
#include "pyramid_workloads.hpp"

#include "gyro/convex.hpp"

#include "gyro/batch_overlap.hpp"
#include "gyro/world.hpp"
#include "scenario.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <string>

namespace gyro::bench {
namespace {

// ------------------------------------------------------------------ scenes

// Rows i = 0..base-1 (0 = bottom) of n = base - i boxes at x = (k - (n-1)/2) * 1.1 + ox,
// y = 0.5 + i, z = oz: a 0.1 gap between neighbours, each row resting on the one below.
// binary64, rounded once to binary32 (BENCHMARKS.md's arithmetic rule).
void add_pyramid(PyramidScene& s, int base, double ox, double oz) {
  for (int i = 0; i < base; ++i) {
    const int n = base - i;
    for (int k = 0; k < n; ++k) {
      s.x.push_back(float((k - (n - 1) / 2.0) * 1.1 + ox));
      s.y.push_back(float(0.5 + i));
      s.z.push_back(float(oz));
    }
  }
}

PyramidScene single_pyramid(const char* name, int base, float ground_half_xz, int steps) {
  PyramidScene s;
  s.name = name;
  add_pyramid(s, base, 0.0, 0.0);
  s.ground_half[0] = s.ground_half[2] = ground_half_xz;
  s.steps = steps;
  return s;
}

// P3: 16 pyramids of base 10 on a 4 x 4 grid 15 m apart (centres at -22.5, -7.5, 7.5, 22.5
// in x and z), 880 boxes on one ground box.
PyramidScene many_pyramids() {
  PyramidScene s;
  s.name = "P3";
  for (int gz = 0; gz < 4; ++gz)
    for (int gx = 0; gx < 4; ++gx) add_pyramid(s, 10, (gx - 1.5) * 15.0, (gz - 1.5) * 15.0);
  s.ground_half[0] = s.ground_half[2] = 100.0f;
  s.steps = 300;
  return s;
}

// ------------------------------------------------------------------ figures

struct Figures {
  double max_displacement = 0;  // m
  double max_penetration = 0;   // m, >= 0
  double energy = 0;            // J per box: (kinetic + potential) at the end minus at the start
};

// One OBB per box (and the ground) in the SoA columns obb_separation_pairwise reads.
struct ObbColumns {
  std::vector<float> c[15];
  void push(const double centre[3], const double half[3], const double axes[3][3]) {
    for (int k = 0; k < 3; ++k) c[k].push_back(float(centre[k])), c[3 + k].push_back(float(half[k]));
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k) c[6 + 3 * a + k].push_back(float(axes[a][k]));
  }
  ObbsView view() const {
    return {c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(), c[5].data(), c[6].data(), c[7].data(),
            c[8].data(), c[9].data(), c[10].data(), c[11].data(), c[12].data(), c[13].data(), c[14].data()};
  }
};

// The world directions of the box's local axes (columns of the rotation of the normalised q).
void box_axes(const BodyStates& st, std::size_t i, double axes[3][3]) {
  double x = st.qx[i], y = st.qy[i], z = st.qz[i], w = st.qw[i];
  const double len = std::sqrt(x * x + y * y + z * z + w * w);
  x /= len, y /= len, z /= len, w /= len;
  const double u[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                          {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                          {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k) axes[a][k] = u[a][k];
}

// Deepest overlap among the pairs that can touch: boxes whose centres lie within 1.5 m
// (neighbours in a row and the boxes a box rests on), and every box with the ground.
double max_penetration(const PyramidScene& s, const BodyStates& st) {
  const std::size_t n = s.size();
  const double half[3] = {s.half, s.half, s.half};
  ObbColumns a, b;
  auto push_box = [&](ObbColumns& cols, std::size_t i) {
    double axes[3][3];
    box_axes(st, i, axes);
    const double centre[3] = {st.px[i], st.py[i], st.pz[i]};
    cols.push(centre, half, axes);
  };
  const double ground_c[3] = {s.ground_centre[0], s.ground_centre[1], s.ground_centre[2]};
  const double ground_h[3] = {s.ground_half[0], s.ground_half[1], s.ground_half[2]};
  const double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (std::size_t i = 0; i < n; ++i) push_box(a, i), b.push(ground_c, ground_h, identity);
  // Sweep along x: only pairs within 1.5 m in x can be within 1.5 m.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return st.px[p] < st.px[q] || (st.px[p] == st.px[q] && p < q); });
  const double reach = 1.5;
  for (std::size_t oi = 0; oi < n; ++oi) {
    const std::size_t i = order[oi];
    for (std::size_t oj = oi + 1; oj < n && double(st.px[order[oj]]) - st.px[i] <= reach; ++oj) {
      const std::size_t j = order[oj];
      const double dx = double(st.px[j]) - st.px[i], dy = double(st.py[j]) - st.py[i], dz = double(st.pz[j]) - st.pz[i];
      if (dx * dx + dy * dy + dz * dz <= reach * reach) push_box(a, i), push_box(b, j);
    }
  }
  std::vector<float> sep(a.c[0].size());
  if (obb_separation_pairwise(a.view(), b.view(), sep.size(), sep.data()) != Status::ok) return NAN;
  double deepest = 0;
  for (float v : sep) deepest = std::max(deepest, -double(v));
  return deepest;
}

Figures pyramid_figures(const PyramidScene& s, const BodyStates& st) {
  Figures f;
  const double g = -double(s.gravity), m = s.mass, side = 2.0 * s.half;
  const double inertia = m * side * side / 6.0;  // a solid cube about any axis through its centre
  double energy = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double dx = double(st.px[i]) - s.x[i], dy = double(st.py[i]) - s.y[i], dz = double(st.pz[i]) - s.z[i];
    f.max_displacement = std::max(f.max_displacement, std::sqrt(dx * dx + dy * dy + dz * dz));
    const double v2 = double(st.vx[i]) * st.vx[i] + double(st.vy[i]) * st.vy[i] + double(st.vz[i]) * st.vz[i];
    const double w2 = double(st.wx[i]) * st.wx[i] + double(st.wy[i]) * st.wy[i] + double(st.wz[i]) * st.wz[i];
    energy += 0.5 * m * v2 + 0.5 * inertia * w2 + m * g * dy;  // at rest at the start
  }
  f.energy = s.size() ? energy / double(s.size()) : 0.0;
  f.max_penetration = max_penetration(s, st);
  return f;
}

// ------------------------------------------------------------------ gyro

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

struct GyroModel {
  const char* method;
  WorldDef def;
};

std::vector<GyroModel> gyro_models(const PyramidScene& s) {
  WorldDef soft;  // the default: soft step, 4 sub-steps
  soft.enable_sleep = false;
  if (s.hull_boxes) {  // the convex manifold models side by side
    WorldDef incremental = soft;
    incremental.convex_manifold = ConvexManifold::incremental;
    return {{"soft_step_clipping", soft}, {"soft_step_incremental", incremental}};
  }
  WorldDef book = soft;  // the appendix's Baumgarte model, as the Cookbook runs it
  book.contact_model = ContactModel::baumgarte;
  book.substeps = 1;
  book.velocity_iterations = 10;
  return {{"soft_step", soft}, {"baumgarte", book}};
}

// Builds and steps the scene in a fresh gyro world; false (with a comment line) on any error.
bool gyro_run_pyramid(const PyramidScene& s, const WorldDef& def, PyramidRun& out, uint64_t* hash) {
  const auto t0 = Clock::now();
  std::unique_ptr<World> world;
  if (World::create(def, &world) != Status::ok) {
    std::printf("# %s: World::create failed: %s\n", s.name, last_error());
    return false;
  }
  BodyDef ground;
  ground.type = BodyType::static_body;
  ground.shape.type = BodyShape::box;
  ground.shape.half_extents = {s.ground_half[0], s.ground_half[1], s.ground_half[2]};
  ground.position = {s.ground_centre[0], s.ground_centre[1], s.ground_centre[2]};
  ground.friction = s.friction, ground.restitution = s.restitution;
  BodyId id;
  if (world->create_body(ground, &id) != Status::ok) {
    std::printf("# %s: ground: %s\n", s.name, last_error());
    return false;
  }
  std::vector<BodyId> ids(s.size());
  BodyDef box;
  box.shape.type = BodyShape::box;
  box.shape.half_extents = {s.half, s.half, s.half};
  ConvexHull hull;
  if (s.hull_boxes) {
    vec3 corners[8];
    for (int k = 0; k < 8; ++k)
      corners[k] = {(k & 1) ? s.half : -s.half, (k & 2) ? s.half : -s.half, (k & 4) ? s.half : -s.half};
    if (build_convex_hull(corners, 8, hull) != Status::ok) {
      std::printf("# %s: hull: %s\n", s.name, last_error());
      return false;
    }
    box.shape.type = BodyShape::hull;
    box.shape.hull = &hull;
  }
  box.mass = s.mass, box.friction = s.friction, box.restitution = s.restitution;
  box.allow_sleep = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    box.position = {s.x[i], s.y[i], s.z[i]};
    if (world->create_body(box, &ids[i]) != Status::ok) {
      std::printf("# %s: box %zu: %s\n", s.name, i, last_error());
      return false;
    }
  }
  const auto t1 = Clock::now();
  for (int k = 0; k < s.steps; ++k)
    if (world->step(s.dt) != Status::ok) {
      std::printf("# %s: step %d: %s\n", s.name, k, last_error());
      return false;
    }
  const auto t2 = Clock::now();
  out.build_ms = ms_between(t0, t1);
  out.step_ms = ms_between(t1, t2);
  BodyStates& st = out.state;
  st.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    vec3 p, v, w;
    quat q;
    world->get_transform(ids[i], &p, &q);
    world->get_velocity(ids[i], &v, &w);
    st.px[i] = p.x, st.py[i] = p.y, st.pz[i] = p.z;
    st.qx[i] = q.x, st.qy[i] = q.y, st.qz[i] = q.z, st.qw[i] = q.w;
    st.vx[i] = v.x, st.vy[i] = v.y, st.vz[i] = v.z;
    st.wx[i] = w.x, st.wy[i] = w.y, st.wz[i] = w.z;
  }
  *hash = world->hash();
  return true;
}

// ------------------------------------------------------------------ runner

// The medians over reps of one engine and settings, and the last rep's state.
struct Measured {
  double build_ms = 0, step_ms = 0;  // step_ms: per step
  PyramidRun last;
  uint64_t hash = 0;
  bool hash_stable = true;  // the same hash in every rep
};

// Every engine and setting of a scene, measured rep by rep in turn (Bullet's rep, then
// each gyro setting's, then Bullet's again, ...), so a slow phase of a noisy machine falls
// on all of them instead of on whichever was measured then. A warm-up run of each first
// (page faults, caches, the thread pool, the CPU's clock), except for P2, whose single run
// takes seconds. An engine that fails is dropped (ok = false).
using RunOnce = std::function<bool(PyramidRun&, uint64_t*)>;
struct Runner {
  RunOnce run;
  Measured m;
  bool ok = true;
  std::vector<double> build, step;
};

void measure_interleaved(const PyramidScene& s, int reps, std::vector<Runner>& runners) {
  if (s.size() * std::size_t(s.steps) <= 1000000)
    for (Runner& r : runners) r.ok = r.run(r.m.last, &r.m.hash);
  for (int rep = 0; rep < std::max(1, reps); ++rep) {
    for (Runner& r : runners) {
      if (!r.ok) continue;
      uint64_t h = 0;
      if (!r.run(r.m.last, &h)) {
        r.ok = false;
        continue;
      }
      if (rep > 0 && h != r.m.hash) r.m.hash_stable = false;
      r.m.hash = h;
      r.build.push_back(r.m.last.build_ms);
      r.step.push_back(r.m.last.step_ms / s.steps);
    }
  }
  for (Runner& r : runners)
    if (r.ok) r.m.build_ms = median(r.build), r.m.step_ms = median(r.step);
}

void emit(const PyramidScene& s, const char* library, const char* method, const char* simd, uint32_t threads,
          uint32_t substeps, uint32_t iterations, const Measured& m, int reps, const uint64_t* hash, double bullet_ms) {
  const Figures f = pyramid_figures(s, m.last.state);
  JsonLine line;
  line.str("workload", s.name).str("library", library).str("method", method).str("simd", simd)
      .integer("threads", threads).integer("substeps", substeps).integer("iterations", iterations)
      .num("build_ms", m.build_ms, 4).num("time_ms", m.step_ms, 5).num("throughput", 1000.0 / m.step_ms, 5)
      .str("unit", "steps/s").integer("hits", int64_t(s.size())).num("checksum", f.max_displacement, 6)
      .num("error", f.max_displacement, 6).str("error_metric", "max displacement of any box from its start (m)")
      .num("max_penetration", f.max_penetration, 5).num("energy", f.energy, 5).integer("steps", s.steps);
  if (hash) line.hex("state_hash", *hash);
  line.integer("reps", reps);
  if (bullet_ms > 0) line.num("ratio_vs_bullet", bullet_ms / m.step_ms, 4);
  line.print();
}

void run_scene(const Options& o, const PyramidScene& s) {
  std::printf("# %s: %zu boxes, %d steps of 1/60 s, sleeping off; ground half extents (%g, %g, %g)\n", s.name,
              s.size(), s.steps, double(s.ground_half[0]), double(s.ground_half[1]), double(s.ground_half[2]));
  std::string summary;
  char buf[160];
  // By default only the level kernels run at now (the best, or GYRO_SIMD's): a physics
  // scene at every level takes minutes. --simd asks for others; the state hash must not
  // change with them.
  const std::vector<SimdLevel> levels = o.levels.empty() ? std::vector<SimdLevel>{simd_level()} : levels_to_run(o);
  struct Config {
    const GyroModel* model;
    SimdLevel level;
    uint32_t threads;
  };
  const std::vector<GyroModel> models = gyro_models(s);
  std::vector<Config> configs;
  for (const GyroModel& model : models)
    for (SimdLevel level : levels)
      for (uint32_t threads : threads_to_run(o)) configs.push_back({&model, level, threads});

  std::vector<Runner> runners;
  const bool with_bullet = o.peers && bullet_dynamics_available();
  if (o.peers && !with_bullet) std::printf("# bullet not installed\n");
  if (with_bullet) runners.push_back({[&](PyramidRun& r, uint64_t*) { return bullet_run_pyramid(s, r); }, {}, true, {}, {}});
  for (const Config& c : configs)
    runners.push_back({[&s, c](PyramidRun& r, uint64_t* h) {
                         set_simd_level(c.level);
                         set_thread_count(c.threads);
                         return gyro_run_pyramid(s, c.model->def, r, h);
                       },
                       {}, true, {}, {}});
  measure_interleaved(s, o.reps, runners);
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);

  double bullet_ms = 0;
  std::size_t next = 0;
  if (with_bullet) {
    const Runner& r = runners[next++];
    if (r.ok) {
      bullet_ms = r.m.step_ms;
      emit(s, "bullet", "btSequentialImpulse", "scalar", 1, 1, 10, r.m, o.reps, nullptr, 0);
      std::snprintf(buf, sizeof buf, "Bullet %d.%02d %.3f", bullet_version() / 100, bullet_version() % 100, r.m.step_ms);
      summary += buf;
    }
  }
  const GyroModel* current = nullptr;
  bool have_hash = false;
  uint64_t first_hash = 0;  // every level and thread count of a model must give this one
  for (const Config& c : configs) {
    const Runner& r = runners[next++];
    if (c.model != current) current = c.model, have_hash = false;
    if (!r.ok) continue;
    const Measured& m = r.m;
    const uint32_t substeps = c.model->def.contact_model == ContactModel::soft_step ? c.model->def.substeps : 1;
    emit(s, "gyro", c.model->method, simd_level_name(c.level), c.threads, substeps, c.model->def.velocity_iterations, m,
         o.reps, &m.hash, bullet_ms);
    if (!m.hash_stable) std::printf("# WARNING: %s %s: state_hash differs between reps\n", s.name, c.model->method);
    if (have_hash && m.hash != first_hash)
      std::printf("# WARNING: %s %s: state_hash differs across SIMD levels / threads\n", s.name, c.model->method);
    if (!have_hash) have_hash = true, first_hash = m.hash;
    std::snprintf(buf, sizeof buf, "%sgyro %s %s %ut %.3f", summary.empty() ? "" : ", ", c.model->method,
                  simd_level_name(c.level), c.threads, m.step_ms);
    summary += buf;
    if (bullet_ms > 0) std::snprintf(buf, sizeof buf, " (%.2fx)", bullet_ms / m.step_ms), summary += buf;
  }
  std::printf("# %s ms/step (gyro speed-up over Bullet; reps interleaved): %s\n", s.name, summary.c_str());
  if (bullet_ms > 0)
    std::printf("# %s: Bullet multiplies the bodies' friction (0.6 * 0.6 = 0.36 per contact), gyro takes "
                "sqrt(0.6 * 0.6) = 0.6\n", s.name);
}

}  // namespace

void run_p1(const Options& o) { run_scene(o, single_pyramid("P1", 20, 50.0f, 600)); }
void run_p1h(const Options& o) {
  PyramidScene s = single_pyramid("P1H", 20, 50.0f, 600);
  s.hull_boxes = true;
  run_scene(o, s);
}
void run_p2(const Options& o) { run_scene(o, single_pyramid("P2", 100, 60.0f, 300)); }
void run_p3(const Options& o) { run_scene(o, many_pyramids()); }

}  // namespace gyro::bench
