// SoftBody: particles and springs in structure-of-arrays columns, the cloth, cube and mesh
// builders, the sub-step loop of both models and the swept collisions. Conventions:
// include/gyro/soft_body.hpp; the spring passes are in soft_solver_kernels.cpp.
//
// Determinism: the solve order is a function of the springs' creation order (soft_plan.hpp);
// a colour's runs share no particle and the per-particle passes read and write only their own
// particle, so every pass runs in fixed chunks on any number of threads with the same bits.
#include "gyro/soft_body.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/state_hash.hpp"
#include "core/validate.hpp"
#include "dynamics/particle_colliders.hpp"
#include "dynamics/soft_body_internal.hpp"
#include "dynamics/soft_plan.hpp"
#include "dynamics/soft_solver.hpp"
#include "gyro/raycast.hpp"
#include "gyro/triangle.hpp"
#include "gyro/triangle_mesh.hpp"

#include <algorithm>
#include <initializer_list>
#include <utility>
#include <cmath>
#include <span>
#include <vector>

namespace gyro {
namespace {

using detail::Collider;
using detail::ColliderKind;
using detail::fail;
using detail::is_finite;
using detail::MeshCollider;

// Parallel chunks (fixed: results do not depend on threads). A step is a chain of dependent
// stages with a barrier each, so it only goes parallel when its widest stage has
// kMinParallelChunks chunks (a 128 x 128 cloth does, a 64 x 64 one runs on one thread).
constexpr std::size_t kParticleChunk = 4096;  // particles per chunk of the predict and velocity passes
constexpr std::size_t kCollideChunk = 512;    // particles per chunk of the collision pass (costlier per particle)
constexpr std::size_t kSpringChunk = 2048;    // springs per chunk of a colour (rounded to whole runs)
constexpr std::size_t kMinParallelChunks = 4;
constexpr uint32_t kMaxSubsteps = 256, kMaxIterations = 64;
constexpr int kMaxSweeps = 3;                 // swept collisions per particle and sub-step

Status check_constants(const SpringConstants& c, const char* name) {
  if (std::isnan(c.stiffness)) return fail(Status::non_finite, "%s stiffness is NaN", name);
  if (!(c.stiffness > 0.0f)) return fail(Status::invalid_argument, "%s stiffness %g is not > 0", name, double(c.stiffness));
  if (!is_finite(c.damping)) return fail(Status::non_finite, "%s damping is not finite", name);
  if (c.damping < 0.0f) return fail(Status::invalid_argument, "%s damping %g is negative", name, double(c.damping));
  return Status::ok;
}

Status check_mass(float mass, const char* name) {
  if (!is_finite(mass)) return fail(Status::non_finite, "%s is not finite", name);
  if (!(mass > 0.0f)) return fail(Status::invalid_argument, "%s %g is not > 0", name, double(mass));
  return Status::ok;
}

const char* family_name(uint32_t f) {
  static const char* const names[kSpringFamilyCount] = {"structural", "shear", "bend", "radial", "joint"};
  return f < kSpringFamilyCount ? names[f] : "unknown";
}

/// A collider of the body: a primitive, or a mesh (kind none and mesh set). Free slots have
/// neither.
struct SoftCollider {
  Collider shape;
  MeshCollider mesh;
  bool used() const { return shape.kind != ColliderKind::none || mesh.mesh != nullptr; }
};

/// What a builder makes: particles, springs and triangles in creation order.
struct Network {
  std::vector<vec3> positions;
  std::vector<float> masses;
  std::vector<uint32_t> a, b;
  std::vector<uint8_t> family;
  std::vector<uint32_t> triangles;
  void spring(uint32_t pa, uint32_t pb, SpringFamily f) {
    a.push_back(pa), b.push_back(pb), family.push_back(static_cast<uint8_t>(f));
  }
};

}  // namespace

struct SoftBody::Impl {
  SoftSettings settings;
  SpringConstants families[kSpringFamilyCount] = {{1.0e6f, 0.0f}, {1.0e6f, 0.0f}, {1.0e4f, 0.0f}, {1.0e3f, 0.0f}, {1.0e6f, 0.0f}};

  // particles
  std::vector<float> px, py, pz, vx, vy, vz, qx, qy, qz, w;
  std::vector<float> mass;       // kept while pinned, so unpin restores it
  std::vector<uint8_t> pinned;
  // springs, creation order
  std::vector<uint32_t> sa, sb;
  std::vector<float> rest;
  std::vector<uint8_t> family;
  uint32_t joints = 0;
  std::vector<uint32_t> triangles;
  uint32_t grid_nx = 0, grid_nz = 0;  // a cloth's grid (0: not a cloth)

  // the solve order (derived: rebuilt when springs change, never hashed)
  bool plan_dirty = true;
  detail::SoftPlan plan;
  std::vector<uint32_t> oa, ob;
  std::vector<float> orest, ostiff, ocompl, odamp, olambda;
  std::vector<std::size_t> color_chunk;  // runs per parallel chunk, per colour
  bool any_infinite = false, any_damped = false;  // over the springs (set with the constants)

  std::vector<SoftCollider> colliders;
  std::size_t live_colliders = 0;
  // the world's colliders during step_with
  std::span<const Collider> world_shapes;
  std::span<const MeshCollider> world_meshes;
  std::vector<Collider> shapes;  // this step's shapes (own and the world's), inflated by the thickness

  std::size_t count() const { return px.size(); }
  vec3 position(std::size_t i) const { return {px[i], py[i], pz[i]}; }

  Status check_index(uint32_t i) const {
    if (i >= count()) return fail(Status::invalid_argument, "particle index %u is out of range (%zu particles)", i, count());
    return Status::ok;
  }

  void load(const Network& net) {
    const std::size_t n = net.positions.size();
    for (auto* col : {&px, &py, &pz, &vx, &vy, &vz, &qx, &qy, &qz, &w, &mass}) col->assign(n, 0.0f);
    pinned.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      px[i] = qx[i] = net.positions[i].x;
      py[i] = qy[i] = net.positions[i].y;
      pz[i] = qz[i] = net.positions[i].z;
      mass[i] = net.masses[i];
      w[i] = 1.0f / net.masses[i];
    }
    sa = net.a, sb = net.b, family = net.family;
    rest.resize(sa.size());
    for (std::size_t k = 0; k < sa.size(); ++k) rest[k] = length(position(sb[k]) - position(sa[k]));
    triangles = net.triangles;
    joints = 0;
    grid_nx = grid_nz = 0;
    plan_dirty = true;
  }

  /// Per-spring constants in solve order from the families (k = +inf: compliance 0).
  void refresh_constants() {
    const std::size_t m = plan.order.size();
    ostiff.resize(m), ocompl.resize(m), odamp.resize(m);
    any_infinite = any_damped = false;
    for (std::size_t k = 0; k < m; ++k) {
      const SpringConstants& c = families[family[plan.order[k]]];
      ostiff[k] = c.stiffness;
      ocompl[k] = std::isinf(c.stiffness) ? 0.0f : 1.0f / c.stiffness;
      odamp[k] = c.damping;
      any_infinite = any_infinite || std::isinf(c.stiffness);
      any_damped = any_damped || c.damping > 0.0f;
    }
  }

  void rebuild_plan() {
    plan = detail::build_soft_plan(sa, sb, count());
    const std::size_t m = plan.order.size();
    oa.resize(m), ob.resize(m), orest.resize(m), olambda.assign(m, 0.0f);
    for (std::size_t k = 0; k < m; ++k) oa[k] = sa[plan.order[k]], ob[k] = sb[plan.order[k]], orest[k] = rest[plan.order[k]];
    refresh_constants();
    color_chunk.assign(plan.colors(), 1);
    for (std::size_t c = 0; c < plan.colors(); ++c) {
      const std::size_t r0 = plan.color_runs[c], r1 = plan.color_runs[c + 1];
      std::size_t springs = 0;
      for (std::size_t r = r0; r < r1; ++r) springs += plan.runs[r].count;
      // Whole runs per chunk, about kSpringChunk springs each: a function of the plan alone.
      if (springs) color_chunk[c] = std::max<std::size_t>(1, (r1 - r0) * kSpringChunk / springs);
    }
    plan_dirty = false;
  }


  Status add_spring(uint32_t a, uint32_t b, float rest_length, SpringFamily f) {
    sa.push_back(a), sb.push_back(b), family.push_back(static_cast<uint8_t>(f));
    rest.push_back(rest_length);
    plan_dirty = true;
    return Status::ok;
  }

  Status add_collider(const SoftCollider& c, uint32_t* index) {
    GYRO_TRY(detail::require_not_null(index, "index"));
    uint32_t at = 0;
    while (at < colliders.size() && colliders[at].used()) ++at;
    if (at == colliders.size()) colliders.push_back(c);
    else colliders[at] = c;
    ++live_colliders;
    *index = at;
    return Status::ok;
  }

  Status step(float dt);
  void collide(std::size_t i, float h);
};

// ---------------------------------------------------------------- collisions

namespace {

/// The first entering crossing of s -> s + d with a placed mesh (either side: a mesh is a
/// surface), with the normal facing s.
/// The first crossing of s -> s + d with a placed mesh (either side: a mesh is a surface)
/// within `reach` beyond the segment's end (a particle coming within the thickness of the
/// surface touches it), with the normal facing s; t in units of |d| may exceed 1.
bool first_hit_mesh(const MeshCollider& m, const vec3& s, const vec3& d, float reach, float* t, vec3* point, vec3* normal) {
  const float len = length(d);
  if (!(len > 0.0f)) return false;
  const quat inv = conjugate(m.orientation);
  const Ray local{rotate(inv, s - m.position), rotate(inv, d / len)};
  const MeshHit hit = raycast(*m.mesh, local, 0.0f, len + reach);
  if (!hit.hit.hit) return false;
  vec3 n = rotate(m.orientation, hit.hit.normal);
  if (dot(n, d) > 0.0f) n = -n;
  *t = hit.hit.t / len, *point = s + d * (hit.hit.t / len), *normal = n;
  return true;
}

bool segment_meets(const vec3& lo, const vec3& hi, const vec3& s, const vec3& e, float pad) {
  for (int k = 0; k < 3; ++k) {
    const float a = s[k] < e[k] ? s[k] : e[k], b = s[k] < e[k] ? e[k] : s[k];
    if (a > hi[k] + pad || b < lo[k] - pad) return false;
  }
  return true;
}

}  // namespace

// Colliders are inflated by the thickness (detail::inflated: spheres, capsules and boxes
// grow, planes and hull faces move out), so a particle resting on one is `thickness` from its
// true surface. Meshes are surfaces and keep the thickness at the stop point instead.
using detail::inflated;

// Sweeps the particle from its sub-step start q to its solved position x through every
// collider: at the first surface crossed it stops just outside and sweeps on with the
// tangential rest of its motion (kMaxSweeps times; then it stays). A particle that starts
// inside a solid is pushed out first, one that ends inside is pushed out last. Then
// position-based Coulomb friction: the tangential motion of the sub-step is cancelled while
// it is under friction times the normal correction, else shortened by that much. The start
// position is moved so the velocity the sub-step ends with has no normal part: a contact
// stops a particle, it never throws it (no energy from the correction). Penalty response
// instead pulls a particle inside a solid out by a spring.
void SoftBody::Impl::collide(std::size_t i, float h) {
  if (!(w[i] > 0.0f)) return;
  const float thk = settings.thickness;
  const float mu = settings.friction;
  const vec3 q{qx[i], qy[i], qz[i]};
  vec3 s = q;
  vec3 e = position(i);
  const vec3 e0 = e;
  auto near = [&](const Collider& c, const vec3& a, const vec3& b) {
    vec3 lo, hi;
    return !detail::collider_bounds(c, &lo, &hi) || segment_meets(lo, hi, a, b, detail::skin_at(a) + 2.0f * detail::kSkin);
  };
  auto each_mesh = [&](auto&& fn) {
    for (const SoftCollider& c : colliders)
      if (c.mesh.mesh) fn(c.mesh);
    for (const MeshCollider& m : world_meshes) fn(m);
  };

  if (settings.response == CollisionResponse::penalty) {
    vec3 push{};
    for (const Collider& c : shapes) {
      if (!near(c, e, e)) continue;
      push = push + (detail::push_out(c, e) - e);
    }
    if (push == vec3{}) return;
    if (settings.model == SoftModel::xpbd) {
      const float f = settings.penalty_stiffness * h * h * w[i];
      e = e + push * (f < 1.0f ? f : 1.0f);
      px[i] = e.x, py[i] = e.y, pz[i] = e.z;
    } else {
      const vec3 dv = push * (settings.penalty_stiffness * h * w[i]);
      vx[i] += dv.x, vy[i] += dv.y, vz[i] += dv.z;
    }
    return;
  }

  vec3 normal_sum{};
  bool touched = false;
  for (const Collider& c : shapes) {
    if (!near(c, s, s)) continue;
    vec3 n;
    const vec3 out = detail::push_out(c, s, 0.0f, &n);
    if (!(out == s)) e = e + (out - s), s = out, touched = true, normal_sum = normal_sum + n;
  }
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    const vec3 d = e - s;
    float best_t = 2.0f, gap = 0.0f;
    vec3 point, normal;
    for (const Collider& c : shapes) {
      if (!near(c, s, e)) continue;
      float t;
      vec3 p, n;
      if (detail::first_hit(c, s, d, &t, &p, &n) && t < best_t) best_t = t, point = p, normal = n, gap = 0.0f;
    }
    each_mesh([&](const MeshCollider& m) {
      float t;
      vec3 p, n;
      if (first_hit_mesh(m, s, d, thk + detail::skin_at(s), &t, &p, &n) && t < best_t) best_t = t, point = p, normal = n, gap = thk;
    });
    if (best_t == 2.0f) break;
    touched = true, normal_sum = normal_sum + normal;
    const vec3 stop = point + normal * (gap + detail::skin_at(point));
    const vec3 rest_motion = e - point;
    s = stop;
    e = sweep + 1 < kMaxSweeps ? stop + (rest_motion - normal * dot(rest_motion, normal)) : stop;
  }
  // A particle that ends within two skins of a surface rests on it: it is held one skin
  // out, inside that band, with its normal motion stopped, so the next sub-step finds it in
  // the band again; otherwise it would fall through the band for a few sub-steps and be
  // stopped with a jolt (velocity noise at rest).
  for (const Collider& c : shapes) {
    if (!near(c, e, e)) continue;
    vec3 n;
    const vec3 out = detail::push_out(inflated(c, 2.0f * detail::kSkin), e, -detail::kSkin, &n);
    if (!(out == e)) e = out, touched = true, normal_sum = normal_sum + n;
  }
  // Meshes have no inside to push out of: a particle within the thickness of a triangle is
  // moved out along the line from the closest point, on the side it is on.
  each_mesh([&](const MeshCollider& m) {
    const quat inv = conjugate(m.orientation);
    const vec3 local = rotate(inv, e - m.position);
    const float reach = thk + 2.0f * detail::skin_at(e);
    uint32_t near_tris[16];
    const std::size_t found = m.mesh->triangles_overlapping(AABB{local, vec3{reach, reach, reach}}, near_tris, 16);
    float best = reach;
    vec3 away{};
    for (std::size_t k = 0; k < (found < 16 ? found : 16); ++k) {
      const vec3 cp = closest_point(m.mesh->triangle(near_tris[k]), local);
      const vec3 off = local - cp;
      const float dist = length(off);
      if (dist < best && dist > 0.0f) best = dist, away = off / dist;
    }
    if (best < reach) {
      const vec3 n = rotate(m.orientation, away);
      e = e + n * (thk + detail::skin_at(e) - best);
      touched = true, normal_sum = normal_sum + n;
    }
  });
  if (!touched) return;
  const float nlen = length(normal_sum);
  const vec3 n = nlen > 0.0f ? normal_sum / nlen : vec3{0.0f, 1.0f, 0.0f};
  const float correction = dot(e - e0, n);  // how far the contacts pushed, along n
  const vec3 d = e - q;
  const vec3 dt = d - n * dot(d, n);
  const float lt = length(dt);
  const float limit = mu * (correction > 0.0f ? correction : 0.0f);
  const vec3 removed = lt <= limit ? dt : dt * (limit / lt);
  e = e - removed;
  px[i] = e.x, py[i] = e.y, pz[i] = e.z;
  const vec3 slide = dt - removed;  // the tangential motion the sub-step keeps
  if (settings.model == SoftModel::xpbd) {
    const vec3 start = e - slide;  // so (x - q) / h is the slide alone
    qx[i] = start.x, qy[i] = start.y, qz[i] = start.z;
  } else {
    const vec3 v{vx[i], vy[i], vz[i]};
    const float vn = dot(v, n);
    const vec3 vt = v - n * vn;
    const float lv = length(vt), lim = limit / h;
    const vec3 v_out = (lv <= lim ? vec3{} : vt * (1.0f - lim / lv)) + n * (vn > 0.0f ? vn : 0.0f);
    vx[i] = v_out.x, vy[i] = v_out.y, vz[i] = v_out.z;
  }
}

// ---------------------------------------------------------------- step

Status SoftBody::Impl::step(float dt) {
  if (!is_finite(dt)) return fail(Status::non_finite, "soft body step dt is not finite");
  if (!(dt > 0.0f)) return fail(Status::invalid_argument, "soft body step dt %g is not > 0", double(dt));
  const std::size_t n = count();
  if (n == 0) return Status::ok;
  if (plan_dirty) rebuild_plan();  // derived state only: a failing step below still changes nothing
  if (settings.model == SoftModel::springs && any_infinite)
    return fail(Status::invalid_argument, "the springs model needs finite stiffness (a family is +infinity)");

  const uint32_t substeps = settings.substeps;
  const float h = dt / static_cast<float>(substeps);
  detail::SoftKernelArgs g{};
  g.px = px.data(), g.py = py.data(), g.pz = pz.data();
  g.vx = vx.data(), g.vy = vy.data(), g.vz = vz.data();
  g.qx = qx.data(), g.qy = qy.data(), g.qz = qz.data();
  g.w = w.data();
  g.a = oa.data(), g.b = ob.data();
  g.rest = orest.data(), g.stiffness = ostiff.data(), g.compliance = ocompl.data(), g.damping = odamp.data();
  g.lambda = olambda.data();
  g.h = h, g.inv_h = 1.0f / h, g.inv_h2 = g.inv_h * g.inv_h;
  g.gx = settings.gravity.x * h, g.gy = settings.gravity.y * h, g.gz = settings.gravity.z * h;
  g.damp = 1.0f / (1.0f + h * settings.damping);
  const bool xpbd = settings.model == SoftModel::xpbd;
  const uint32_t iterations = xpbd ? settings.iterations : 1;
  g.accumulate = iterations > 1 ? 1u : 0u;
  g.damped = any_damped ? 1u : 0u;

  auto* predict = GYRO_DISPATCH(soft_predict);
  auto* update_velocity = GYRO_DISPATCH(soft_update_velocity);
  auto* spring_pass = xpbd ? GYRO_DISPATCH(soft_xpbd_runs) : GYRO_DISPATCH(soft_spring_runs);
  shapes.clear();
  for (const SoftCollider& c : colliders)
    if (c.shape.kind != ColliderKind::none) shapes.push_back(inflated(c.shape, settings.thickness));
  for (const Collider& c : world_shapes) shapes.push_back(inflated(c, settings.thickness));
  const bool collide_any = !shapes.empty() || !world_meshes.empty() ||
                           std::any_of(colliders.begin(), colliders.end(), [](const SoftCollider& c) { return c.mesh.mesh != nullptr; });
  const detail::SpringRun* runs = plan.runs.data();

  // One parallel region for the whole step: per sub-step the stages below, a barrier
  // between stages (colours depend on each other, the passes on the colours).
  const std::size_t colors = plan.colors();
  enum Stage : uint32_t { predict_stage, reset_stage, color_stage, collide_stage, velocity_stage };
  const std::size_t per_sub = 1 + (g.accumulate ? 1 : 0) + iterations * colors + (collide_any ? 1 : 0) + (xpbd ? 1 : 0);
  auto decode = [&](std::size_t stage, std::size_t* color) -> Stage {
    std::size_t r = stage % per_sub;
    if (r == 0) return predict_stage;
    r -= 1;
    if (g.accumulate) {
      if (r == 0) return reset_stage;
      r -= 1;
    }
    if (r < iterations * colors) {
      *color = r % colors;
      return color_stage;
    }
    r -= iterations * colors;
    if (collide_any && r == 0) return collide_stage;
    return velocity_stage;
  };
  detail::parallel_stages(
      substeps * per_sub, kMinParallelChunks,
      [&](std::size_t stage, std::size_t* count, std::size_t* chunk) {
        std::size_t c = 0;
        switch (decode(stage, &c)) {
          case predict_stage:
          case velocity_stage: *count = n, *chunk = kParticleChunk; break;
          case reset_stage: *count = olambda.size(), *chunk = kSpringChunk; break;
          case color_stage: *count = plan.color_runs[c + 1] - plan.color_runs[c], *chunk = color_chunk[c]; break;
          case collide_stage: *count = n, *chunk = kCollideChunk; break;
        }
      },
      [&](std::size_t stage, std::size_t b, std::size_t e) {
        std::size_t c = 0;
        switch (decode(stage, &c)) {
          case predict_stage: predict(g, b, e); break;
          case reset_stage: std::fill(olambda.begin() + b, olambda.begin() + e, 0.0f); break;
          case color_stage: spring_pass(g, runs, plan.color_runs[c] + b, plan.color_runs[c] + e); break;
          case collide_stage:
            for (std::size_t i = b; i < e; ++i) collide(i, h);
            break;
          case velocity_stage: update_velocity(g, b, e); break;
        }
      });
  return Status::ok;
}

// ---------------------------------------------------------------- builders

namespace {

/// Position of column i in its row: the row holds columns i % 4 == 0, 1, 2, 3 as four blocks,
/// so springs between columns i and i + 1 or i + 2 join two blocks element by element.
struct GridLayout {
  uint32_t nx = 0, offset[4] = {0, 0, 0, 0};
  explicit GridLayout(uint32_t nx_) : nx(nx_) {
    uint32_t at = 0;
    for (uint32_t m = 0; m < 4; ++m) {
      offset[m] = at;
      at += nx > m ? (nx - 1 - m) / 4 + 1 : 0;
    }
  }
  uint32_t index(uint32_t i, uint32_t j) const { return j * nx + offset[i % 4] + i / 4; }
};

/// Springs (i, j) - (i + di, j + dj) for every column block in turn, so each (row, block)
/// is a contiguous stretch; dl mirrors the x offset ((i + di, j) - (i, j + dj): the other
/// diagonal). keep(i, j) selects cells (the alternating diagonals).
template <class Keep>
void grid_springs(Network& net, const GridLayout& g, uint32_t nz, uint32_t di, uint32_t dj, bool mirrored, SpringFamily f, Keep keep) {
  for (uint32_t j = 0; j + dj < nz; ++j)
    for (uint32_t m = 0; m < 4; ++m)
      for (uint32_t i = m; i + di < g.nx; i += 4) {
        if (!keep(i, j)) continue;
        if (mirrored) net.spring(g.index(i + di, j), g.index(i, j + dj), f);
        else net.spring(g.index(i, j), g.index(i + di, j + dj), f);
      }
}

/// Orders triangle (a, b, c) so its normal points away from `inside`.
void outward(Network& net, uint32_t a, uint32_t b, uint32_t c, const vec3& inside) {
  const vec3 pa = net.positions[a], pb = net.positions[b], pc = net.positions[c];
  const vec3 n = cross(pb - pa, pc - pa);
  const vec3 centre = (pa + pb + pc) * (1.0f / 3.0f);
  if (dot(n, centre - inside) < 0.0f) std::swap(b, c);
  net.triangles.insert(net.triangles.end(), {a, b, c});
}

/// Loads a built network into a body and sets the constants of the families the builder
/// defines (the others keep theirs).
void assign(SoftBody::Impl& impl, const Network& net, std::initializer_list<std::pair<SpringFamily, SpringConstants>> families) {
  impl.load(net);
  for (const auto& [f, c] : families) impl.families[static_cast<uint32_t>(f)] = c;
}

}  // namespace

Status SoftBody::make(const SoftBodyDef& def, SoftBody* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  GYRO_TRY(detail::require_not_null(def.positions, "positions"));
  if (def.particle_count < 1 || def.particle_count > (1u << 26))
    return fail(Status::invalid_count, "soft body particle_count %u is outside 1..2^26", def.particle_count);
  if (def.spring_count && !def.springs) return fail(Status::null_argument, "springs is null");
  if (def.triangle_count && !def.triangles) return fail(Status::null_argument, "triangles is null");
  const uint32_t n = def.particle_count;
  Network net;
  net.positions.assign(def.positions, def.positions + n);
  net.masses.assign(n, 1.0f);
  for (uint32_t i = 0; i < n; ++i) {
    if (!gyro::is_finite(net.positions[i])) return fail(Status::non_finite, "particle %u position is not finite", i);
    if (def.masses) {
      GYRO_TRY(check_mass(def.masses[i], "particle mass"));
      net.masses[i] = def.masses[i];
    }
  }
  std::vector<float> rest(def.spring_count);
  for (uint32_t k = 0; k < def.spring_count; ++k) {
    const SoftSpringDef& sp = def.springs[k];
    if (sp.a >= n || sp.b >= n) return fail(Status::invalid_argument, "spring %u names a particle past %u", k, n);
    if (sp.a == sp.b) return fail(Status::invalid_argument, "spring %u joins particle %u to itself", k, sp.a);
    if (static_cast<uint32_t>(sp.family) >= kSpringFamilyCount) return fail(Status::invalid_argument, "spring %u has an unknown family", k);
    if (std::isnan(sp.rest_length) || std::isinf(sp.rest_length)) return fail(Status::non_finite, "spring %u rest_length is not finite", k);
    net.spring(sp.a, sp.b, sp.family);
    rest[k] = sp.rest_length;
  }
  for (uint32_t t = 0; t < def.triangle_count * 3u; ++t)
    if (def.triangles[t] >= n) return fail(Status::invalid_argument, "triangle %u names a particle past %u", t / 3, n);
  net.triangles.assign(def.triangles, def.triangles + std::size_t{def.triangle_count} * 3);
  Impl& m = *out->impl_;
  m.load(net);
  for (uint32_t k = 0; k < def.spring_count; ++k)
    if (rest[k] >= 0.0f) m.rest[k] = rest[k];
  if (def.pinned)
    for (uint32_t i = 0; i < n; ++i)
      if (def.pinned[i]) m.pinned[i] = 1, m.w[i] = 0.0f;
  return Status::ok;
}

Status SoftBody::make_cloth(const ClothDef& def, SoftBody* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  if (def.nx < 2 || def.nz < 2) return fail(Status::invalid_count, "cloth grid %u x %u is smaller than 2 x 2", def.nx, def.nz);
  if (uint64_t{def.nx} * def.nz > (uint64_t{1} << 26)) return fail(Status::invalid_count, "cloth grid %u x %u is too large", def.nx, def.nz);
  if (!is_finite(def.size_x) || !is_finite(def.size_z) || !gyro::is_finite(def.center))
    return fail(Status::non_finite, "cloth size or centre is not finite");
  if (!(def.size_x > 0.0f) || !(def.size_z > 0.0f))
    return fail(Status::invalid_argument, "cloth size %g x %g is not > 0", double(def.size_x), double(def.size_z));
  GYRO_TRY(check_mass(def.particle_mass, "cloth particle_mass"));
  GYRO_TRY(check_constants(def.structural, "cloth structural"));
  GYRO_TRY(check_constants(def.shear, "cloth shear"));
  GYRO_TRY(check_constants(def.bend_constants, "cloth bend"));

  const uint32_t nx = def.nx, nz = def.nz;
  const GridLayout g(nx);
  Network net;
  const std::size_t n = std::size_t{nx} * nz;
  net.positions.resize(n), net.masses.assign(n, def.particle_mass);
  for (uint32_t j = 0; j < nz; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      // Binary64 like BENCHMARKS.md's C1 patch: lerp from the -x/-z corner by i / (nx - 1).
      const double tx = double(i) / double(nx - 1), tz = double(j) / double(nz - 1);
      net.positions[g.index(i, j)] = {float(double(def.center.x) - 0.5 * def.size_x + tx * def.size_x), def.center.y,
                                      float(double(def.center.z) - 0.5 * def.size_z + tz * def.size_z)};
    }
  auto all = [](uint32_t, uint32_t) { return true; };
  grid_springs(net, g, nz, 1, 0, false, SpringFamily::structural, all);
  grid_springs(net, g, nz, 0, 1, false, SpringFamily::structural, all);
  // Bullet's gendiags: cell (i, j) gets (i, j) - (i+1, j+1) when i + j is odd, the other diagonal when even.
  auto odd = [](uint32_t i, uint32_t j) { return ((i + j) & 1u) == 1u; };
  auto even = [](uint32_t i, uint32_t j) { return ((i + j) & 1u) == 0u; };
  if (def.both_diagonals) {
    grid_springs(net, g, nz, 1, 1, false, SpringFamily::shear, all);
    grid_springs(net, g, nz, 1, 1, true, SpringFamily::shear, all);
  } else {
    grid_springs(net, g, nz, 1, 1, false, SpringFamily::shear, odd);
    grid_springs(net, g, nz, 1, 1, true, SpringFamily::shear, even);
  }
  if (def.bend) {
    grid_springs(net, g, nz, 2, 0, false, SpringFamily::bend, all);
    grid_springs(net, g, nz, 0, 2, false, SpringFamily::bend, all);
  }
  // Two triangles a cell, split along the cell's diagonal spring (the (i,j)-(i+1,j+1) one
  // when both exist), counter-clockwise seen from +y.
  net.triangles.reserve(std::size_t{nx - 1} * (nz - 1) * 6);
  for (uint32_t j = 0; j + 1 < nz; ++j)
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t p00 = g.index(i, j), p10 = g.index(i + 1, j), p01 = g.index(i, j + 1), p11 = g.index(i + 1, j + 1);
      if (def.both_diagonals || odd(i, j)) net.triangles.insert(net.triangles.end(), {p00, p11, p10, p00, p01, p11});
      else net.triangles.insert(net.triangles.end(), {p00, p01, p10, p10, p01, p11});
    }
  assign(*out->impl_, net,
         {{SpringFamily::structural, def.structural}, {SpringFamily::shear, def.shear}, {SpringFamily::bend, def.bend_constants}});
  out->impl_->grid_nx = nx, out->impl_->grid_nz = nz;
  return Status::ok;
}

Status SoftBody::make_cube(const SoftCubeDef& def, SoftBody* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  if (!gyro::is_finite(def.center) || !is_finite(def.half_extent)) return fail(Status::non_finite, "soft cube is not finite");
  if (!(def.half_extent > 0.0f)) return fail(Status::invalid_argument, "soft cube half_extent %g is not > 0", double(def.half_extent));
  GYRO_TRY(check_mass(def.particle_mass, "soft cube particle_mass"));
  GYRO_TRY(check_constants(def.structural, "soft cube structural"));
  GYRO_TRY(check_constants(def.shear, "soft cube shear"));
  GYRO_TRY(check_constants(def.bend, "soft cube bend"));
  Network net;
  const float e = def.half_extent;
  for (uint32_t c = 0; c < 8; ++c)
    net.positions.push_back(def.center + vec3{(c & 1u) ? e : -e, (c & 2u) ? e : -e, (c & 4u) ? e : -e});
  net.masses.assign(8, def.particle_mass);
  // All 28 pairs of corners: differing in one coordinate (edges), two (face diagonals) or three.
  for (uint32_t a = 0; a < 8; ++a)
    for (uint32_t b = a + 1; b < 8; ++b) {
      const int bits = __builtin_popcount(a ^ b);
      net.spring(a, b, bits == 1 ? SpringFamily::structural : bits == 2 ? SpringFamily::shear : SpringFamily::bend);
    }
  for (uint32_t axis = 0; axis < 3; ++axis)
    for (uint32_t side = 0; side < 2; ++side) {
      uint32_t q[4], k = 0;
      for (uint32_t c = 0; c < 8; ++c)
        if (((c >> axis) & 1u) == side) q[k++] = c;
      // q: the face's corners in bit order, so q[0]-q[3] is a diagonal.
      outward(net, q[0], q[1], q[3], def.center);
      outward(net, q[0], q[3], q[2], def.center);
    }
  assign(*out->impl_, net, {{SpringFamily::structural, def.structural}, {SpringFamily::shear, def.shear}, {SpringFamily::bend, def.bend}});
  return Status::ok;
}

Status SoftBody::make_from_mesh(const SoftMeshDef& def, SoftBody* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  GYRO_TRY(detail::require_not_null(def.vertices, "vertices"));
  GYRO_TRY(detail::require_not_null(def.indices, "indices"));
  if (def.vertex_count < 4) return fail(Status::invalid_count, "soft mesh has %u vertices (at least 4)", def.vertex_count);
  if (def.triangle_count < 4) return fail(Status::invalid_count, "soft mesh has %u triangles (at least 4)", def.triangle_count);
  if (def.vertex_count > (1u << 24) || def.triangle_count > (1u << 25)) return fail(Status::invalid_count, "soft mesh is too large");
  GYRO_TRY(check_mass(def.particle_mass, "soft mesh particle_mass"));
  GYRO_TRY(check_constants(def.structural, "soft mesh structural"));
  GYRO_TRY(check_constants(def.bend, "soft mesh bend"));
  GYRO_TRY(check_constants(def.radial, "soft mesh radial"));
  const uint32_t nv = def.vertex_count;
  for (std::size_t k = 0; k < std::size_t{nv} * 3; ++k)
    if (!is_finite(def.vertices[k])) return fail(Status::non_finite, "soft mesh vertex %zu is not finite", k / 3);
  for (uint32_t t = 0; t < def.triangle_count; ++t) {
    const uint32_t* tri = def.indices + std::size_t{t} * 3;
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) return fail(Status::invalid_argument, "soft mesh triangle %u indexes past the vertices", t);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return fail(Status::invalid_argument, "soft mesh triangle %u repeats a vertex", t);
  }
  // Edges with the vertex opposite them in each triangle, sorted: a closed mesh has every edge twice.
  struct Edge {
    uint32_t lo, hi, opposite;
    bool operator<(const Edge& o) const { return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : opposite < o.opposite; }
  };
  std::vector<Edge> edges;
  edges.reserve(std::size_t{def.triangle_count} * 3);
  for (uint32_t t = 0; t < def.triangle_count; ++t) {
    const uint32_t* tri = def.indices + std::size_t{t} * 3;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3], o = tri[(k + 2) % 3];
      edges.push_back({a < b ? a : b, a < b ? b : a, o});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k < edges.size(); k += 2)
    if (k + 1 >= edges.size() || edges[k].lo != edges[k + 1].lo || edges[k].hi != edges[k + 1].hi ||
        (k + 2 < edges.size() && edges[k + 2].lo == edges[k].lo && edges[k + 2].hi == edges[k].hi))
      return fail(Status::invalid_argument, "soft mesh is not closed: edge (%u, %u) is not shared by exactly two triangles",
                  edges[k].lo, edges[k].hi);

  Network net;
  net.positions.resize(nv + 1);
  vec3 centroid{};
  for (uint32_t v = 0; v < nv; ++v) {
    net.positions[v] = {def.vertices[3 * v], def.vertices[3 * v + 1], def.vertices[3 * v + 2]};
    centroid = centroid + net.positions[v];
  }
  net.positions[nv] = centroid * (1.0f / static_cast<float>(nv));
  net.masses.assign(nv + 1, def.particle_mass);
  for (std::size_t k = 0; k < edges.size(); k += 2) net.spring(edges[k].lo, edges[k].hi, SpringFamily::structural);
  for (std::size_t k = 0; k < edges.size(); k += 2) {
    const uint32_t a = edges[k].opposite, b = edges[k + 1].opposite;
    if (a != b) net.spring(a < b ? a : b, a < b ? b : a, SpringFamily::bend);
  }
  for (uint32_t v = 0; v < nv; ++v) net.spring(v, nv, SpringFamily::radial);
  net.triangles.assign(def.indices, def.indices + std::size_t{def.triangle_count} * 3);
  assign(*out->impl_, net, {{SpringFamily::structural, def.structural}, {SpringFamily::bend, def.bend}, {SpringFamily::radial, def.radial}});
  return Status::ok;
}

// ---------------------------------------------------------------- lifetime, settings, families

SoftBody::SoftBody() : impl_(std::make_unique<Impl>()) {}
SoftBody::~SoftBody() = default;
SoftBody::SoftBody(const SoftBody& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
SoftBody& SoftBody::operator=(const SoftBody& other) {
  if (this != &other) *impl_ = *other.impl_;
  return *this;
}
SoftBody::SoftBody(SoftBody&& other) noexcept : impl_(std::make_unique<Impl>()) { impl_.swap(other.impl_); }
SoftBody& SoftBody::operator=(SoftBody&& other) noexcept {
  impl_.swap(other.impl_);
  return *this;
}

Status SoftBody::set_settings(const SoftSettings& s) {
  if (static_cast<uint32_t>(s.model) > 1u) return fail(Status::invalid_argument, "unknown soft model %u", static_cast<uint32_t>(s.model));
  if (s.substeps < 1 || s.substeps > kMaxSubsteps) return fail(Status::invalid_argument, "soft substeps %u is outside 1..%u", s.substeps, kMaxSubsteps);
  if (s.iterations < 1 || s.iterations > kMaxIterations)
    return fail(Status::invalid_argument, "soft iterations %u is outside 1..%u", s.iterations, kMaxIterations);
  if (!gyro::is_finite(s.gravity)) return fail(Status::non_finite, "soft gravity is not finite");
  for (float v : {s.damping, s.thickness, s.friction, s.penalty_stiffness})
    if (!is_finite(v)) return fail(Status::non_finite, "a soft setting is not finite");
  if (s.damping < 0.0f) return fail(Status::invalid_argument, "soft damping %g is negative", double(s.damping));
  if (s.thickness < 0.0f) return fail(Status::invalid_argument, "soft thickness %g is negative", double(s.thickness));
  if (s.friction < 0.0f || s.friction > 1.0f) return fail(Status::invalid_argument, "soft friction %g is outside [0, 1]", double(s.friction));
  if (static_cast<uint32_t>(s.response) > 1u) return fail(Status::invalid_argument, "unknown collision response %u", static_cast<uint32_t>(s.response));
  if (!(s.penalty_stiffness > 0.0f)) return fail(Status::invalid_argument, "penalty_stiffness %g is not > 0", double(s.penalty_stiffness));
  impl_->settings = s;
  return Status::ok;
}

const SoftSettings& SoftBody::settings() const { return impl_->settings; }

Status SoftBody::set_family(SpringFamily f, const SpringConstants& c) {
  const uint32_t index = static_cast<uint32_t>(f);
  if (index >= kSpringFamilyCount) return fail(Status::invalid_argument, "unknown spring family %u", index);
  GYRO_TRY(check_constants(c, family_name(index)));
  impl_->families[index] = c;
  if (!impl_->plan_dirty) impl_->refresh_constants();
  return Status::ok;
}

SpringConstants SoftBody::family(SpringFamily f) const {
  const uint32_t index = static_cast<uint32_t>(f);
  return index < kSpringFamilyCount ? impl_->families[index] : SpringConstants{};
}

std::size_t SoftBody::particle_count() const { return impl_->count(); }
std::size_t SoftBody::spring_count() const { return impl_->sa.size(); }

Status SoftBody::cloth_index(uint32_t ix, uint32_t iz, uint32_t* index) const {
  GYRO_TRY(detail::require_not_null(index, "index"));
  const Impl& m = *impl_;
  if (m.grid_nx == 0) return fail(Status::invalid_argument, "this soft body is not a cloth grid");
  if (ix >= m.grid_nx || iz >= m.grid_nz)
    return fail(Status::invalid_argument, "cloth cell (%u, %u) is outside the %u x %u grid", ix, iz, m.grid_nx, m.grid_nz);
  *index = GridLayout(m.grid_nx).index(ix, iz);
  return Status::ok;
}

// ---------------------------------------------------------------- particles

Status SoftBody::set_particle_mass(uint32_t i, float mass) {
  GYRO_TRY(impl_->check_index(i));
  GYRO_TRY(check_mass(mass, "particle mass"));
  impl_->mass[i] = mass;
  if (!impl_->pinned[i]) impl_->w[i] = 1.0f / mass;
  return Status::ok;
}

Status SoftBody::set_mass(float mass) {
  GYRO_TRY(check_mass(mass, "particle mass"));
  Impl& m = *impl_;
  for (std::size_t i = 0; i < m.count(); ++i) {
    m.mass[i] = mass;
    if (!m.pinned[i]) m.w[i] = 1.0f / mass;
  }
  return Status::ok;
}

Status SoftBody::pin(uint32_t i) {
  GYRO_TRY(impl_->check_index(i));
  impl_->pinned[i] = 1, impl_->w[i] = 0.0f;
  impl_->vx[i] = impl_->vy[i] = impl_->vz[i] = 0.0f;
  return Status::ok;
}

Status SoftBody::unpin(uint32_t i) {
  GYRO_TRY(impl_->check_index(i));
  impl_->pinned[i] = 0, impl_->w[i] = 1.0f / impl_->mass[i];
  return Status::ok;
}

Status SoftBody::is_pinned(uint32_t i, bool* pinned) const {
  GYRO_TRY(detail::require_not_null(pinned, "pinned"));
  GYRO_TRY(impl_->check_index(i));
  *pinned = impl_->pinned[i] != 0;
  return Status::ok;
}

Status SoftBody::get_position(uint32_t i, vec3* p) const {
  GYRO_TRY(detail::require_not_null(p, "position"));
  GYRO_TRY(impl_->check_index(i));
  *p = impl_->position(i);
  return Status::ok;
}

Status SoftBody::get_velocity(uint32_t i, vec3* v) const {
  GYRO_TRY(detail::require_not_null(v, "velocity"));
  GYRO_TRY(impl_->check_index(i));
  *v = {impl_->vx[i], impl_->vy[i], impl_->vz[i]};
  return Status::ok;
}

Status SoftBody::set_position(uint32_t i, const vec3& p) {
  GYRO_TRY(impl_->check_index(i));
  if (!gyro::is_finite(p)) return fail(Status::non_finite, "particle position is not finite");
  Impl& m = *impl_;
  m.px[i] = m.qx[i] = p.x, m.py[i] = m.qy[i] = p.y, m.pz[i] = m.qz[i] = p.z;
  return Status::ok;
}

Status SoftBody::set_velocity(uint32_t i, const vec3& v) {
  GYRO_TRY(impl_->check_index(i));
  if (!gyro::is_finite(v)) return fail(Status::non_finite, "particle velocity is not finite");
  if (impl_->pinned[i]) return Status::ok;  // a pinned particle moves only by set_position
  impl_->vx[i] = v.x, impl_->vy[i] = v.y, impl_->vz[i] = v.z;
  return Status::ok;
}

// ---------------------------------------------------------------- joints

Status SoftBody::add_joint(const ParticleJointDef& def, uint32_t* index) {
  Impl& m = *impl_;
  GYRO_TRY(m.check_index(def.a));
  GYRO_TRY(m.check_index(def.b));
  if (def.a == def.b) return fail(Status::invalid_argument, "a joint needs two different particles (both are %u)", def.a);
  if (std::isnan(def.rest_length) || std::isinf(def.rest_length)) return fail(Status::non_finite, "joint rest_length is not finite");
  const float rest = def.rest_length < 0.0f ? length(m.position(def.b) - m.position(def.a)) : def.rest_length;
  if (index) *index = m.joints;
  ++m.joints;
  return m.add_spring(def.a, def.b, rest, SpringFamily::joint);
}

Status SoftBody::add_ball_joint(uint32_t a, uint32_t b) { return add_joint({a, b, 0.0f}); }

Status SoftBody::add_hinge_joint(uint32_t a0, uint32_t b0, uint32_t a1, uint32_t b1) {
  Impl& m = *impl_;
  for (uint32_t i : {a0, b0, a1, b1}) GYRO_TRY(m.check_index(i));
  if (a0 == b0 || a1 == b1) return fail(Status::invalid_argument, "a hinge joins two different particles at each end");
  if (a0 == a1 || b0 == b1) return fail(Status::invalid_argument, "a hinge needs two different points on its axis");
  GYRO_TRY(add_ball_joint(a0, b0));
  return add_ball_joint(a1, b1);
}

// ---------------------------------------------------------------- colliders

Status SoftBody::add_collider(const Sphere& sphere, uint32_t* index) {
  SoftCollider c;
  GYRO_TRY(detail::to_collider(sphere, &c.shape));
  return impl_->add_collider(c, index);
}

Status SoftBody::add_collider(const AABB& box, uint32_t* index) {
  SoftCollider c;
  GYRO_TRY(detail::to_collider(box, &c.shape));
  return impl_->add_collider(c, index);
}

Status SoftBody::add_collider(const OBB& box, uint32_t* index) {
  SoftCollider c;
  GYRO_TRY(detail::to_collider(box, &c.shape));
  return impl_->add_collider(c, index);
}

Status SoftBody::add_collider(const Plane& plane, uint32_t* index) {
  SoftCollider c;
  GYRO_TRY(detail::to_collider(plane, &c.shape));
  return impl_->add_collider(c, index);
}

Status SoftBody::add_collider(const TriangleMesh& mesh, uint32_t* index) {
  if (mesh.empty()) return fail(Status::invalid_argument, "mesh collider is empty");
  SoftCollider c;
  c.mesh.mesh = &mesh;
  return impl_->add_collider(c, index);
}

Status SoftBody::remove_collider(uint32_t index) {
  Impl& m = *impl_;
  if (index >= m.colliders.size() || !m.colliders[index].used())
    return fail(Status::invalid_argument, "no collider %u", index);
  m.colliders[index] = SoftCollider{};
  --m.live_colliders;
  while (!m.colliders.empty() && !m.colliders.back().used()) m.colliders.pop_back();
  return Status::ok;
}

void SoftBody::clear_colliders() {
  impl_->colliders.clear();
  impl_->live_colliders = 0;
}

std::size_t SoftBody::collider_count() const { return impl_->live_colliders; }

// ---------------------------------------------------------------- step, views, figures

Status SoftBody::step(float dt) { return impl_->step(dt); }

Status detail::SoftAccess::step_with(SoftBody& body, float dt, std::span<const Collider> colliders, std::span<const MeshCollider> meshes) {
  SoftBody::Impl& m = *body.impl_;
  m.world_shapes = colliders, m.world_meshes = meshes;
  const Status s = m.step(dt);
  m.world_shapes = {}, m.world_meshes = {};
  return s;
}

bool detail::SoftAccess::step_bounds(const SoftBody& body, float dt, vec3* lo, vec3* hi) {
  const SoftBody::Impl& m = *body.impl_;
  if (m.count() == 0) return false;
  vec3 a = m.position(0), b = a;
  float speed2 = 0.0f;
  for (std::size_t i = 0; i < m.count(); ++i) {
    a = min(a, m.position(i)), b = max(b, m.position(i));
    const float q = m.vx[i] * m.vx[i] + m.vy[i] * m.vy[i] + m.vz[i] * m.vz[i];
    speed2 = q > speed2 ? q : speed2;
  }
  const float reach = (std::sqrt(speed2) + length(m.settings.gravity) * dt) * dt + m.settings.thickness + 0.01f;
  const vec3 pad{reach, reach, reach};
  *lo = a - pad, *hi = b + pad;
  return true;
}

SoftView SoftBody::view() const {
  const Impl& m = *impl_;
  return {m.count(), m.px.data(), m.py.data(), m.pz.data(), m.vx.data(), m.vy.data(), m.vz.data(), m.w.data(),
          m.triangles.size() / 3, m.triangles.data()};
}

SoftStats SoftBody::stats() const {
  const Impl& m = *impl_;
  SoftStats s;
  s.particles = m.count(), s.springs = m.sa.size();
  s.colors = m.plan_dirty ? detail::build_soft_plan(m.sa, m.sb, m.count()).colors() : m.plan.colors();
  std::size_t structural = 0;
  for (std::size_t k = 0; k < m.sa.size(); ++k) {
    const vec3 d = m.position(m.sb[k]) - m.position(m.sa[k]);
    const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    const double c = len - double(m.rest[k]);
    const SpringConstants& fc = m.families[m.family[k]];
    if (!std::isinf(fc.stiffness)) s.elastic_energy += 0.5 * double(fc.stiffness) * c * c;
    if (m.family[k] == static_cast<uint8_t>(SpringFamily::structural) && m.rest[k] > 0.0f) {
      const double strain = std::abs(c) / double(m.rest[k]);
      s.max_strain = strain > s.max_strain ? strain : s.max_strain;
      s.mean_strain += strain;
      ++structural;
    }
  }
  if (structural) s.mean_strain /= double(structural);
  const vec3 gv = m.settings.gravity;
  s.min_y = m.count() ? double(m.py[0]) : 0.0;
  for (std::size_t i = 0; i < m.count(); ++i) {
    s.min_y = double(m.py[i]) < s.min_y ? double(m.py[i]) : s.min_y;
    if (m.pinned[i]) continue;
    const double mass = m.mass[i];
    s.kinetic_energy += 0.5 * mass * (double(m.vx[i]) * m.vx[i] + double(m.vy[i]) * m.vy[i] + double(m.vz[i]) * m.vz[i]);
    s.potential_energy -= mass * (double(gv.x) * m.px[i] + double(gv.y) * m.py[i] + double(gv.z) * m.pz[i]);
  }
  return s;
}

uint64_t SoftBody::hash() const {
  detail::StateHasher h;
  detail::SoftAccess::hash_into(*this, h);
  return h.digest();
}

void detail::SoftAccess::hash_into(const SoftBody& body, StateHasher& h) {
  const SoftBody::Impl& m = *body.impl_;
  const SoftSettings& s = m.settings;
  h.add_u32(static_cast<uint32_t>(s.model)), h.add_u32(s.substeps), h.add_u32(s.iterations);
  const float settings[] = {s.gravity.x, s.gravity.y, s.gravity.z, s.damping, s.thickness, s.friction, s.penalty_stiffness};
  h.add_floats(settings);
  h.add_u32(static_cast<uint32_t>(s.response));
  for (const SpringConstants& c : m.families) h.add_float(c.stiffness), h.add_float(c.damping);
  const std::size_t n = m.count();
  for (const std::vector<float>* col : {&m.px, &m.py, &m.pz, &m.vx, &m.vy, &m.vz, &m.qx, &m.qy, &m.qz, &m.w, &m.mass})
    h.add_floats({col->data(), n});
  h.add_u64(n);
  for (uint8_t p : m.pinned) h.add_u32(p);
  h.add_u32s(m.sa), h.add_u32s(m.sb), h.add_floats(m.rest);
  h.add_u64(m.family.size());
  for (uint8_t f : m.family) h.add_u32(f);
  h.add_u32(m.joints), h.add_u32(m.grid_nx), h.add_u32(m.grid_nz);
  h.add_u32s(m.triangles);
  h.add_u64(m.colliders.size());
  for (const SoftCollider& c : m.colliders) {
    hash_collider(c.shape, h);
    // A mesh is named by its being there and its size, never by its address.
    h.add_u64(c.mesh.mesh ? c.mesh.mesh->triangle_count() + 1 : 0);
  }
}

// ---------------------------------------------------------------- snapshot

void detail::SoftAccess::add_meshes(const SoftBody& body, SnapshotMeshes& meshes) {
  for (const SoftCollider& c : body.impl_->colliders) meshes.add(c.mesh.mesh);
}

namespace {
// Particles, springs, triangles and colliders, in one description for both directions (the
// settings and families go through the validating setters on reading).
template <class Io, class M> void io_soft_state(Io& io, M& m, const detail::SnapshotMeshes& meshes) {
  for (auto* col : {&m.px, &m.py, &m.pz, &m.vx, &m.vy, &m.vz, &m.qx, &m.qy, &m.qz, &m.w, &m.mass}) io.array(*col);
  io.array(m.pinned);
  io.array(m.sa), io.array(m.sb), io.array(m.rest), io.array(m.family);
  io.u32(m.joints), io.u32(m.grid_nx), io.u32(m.grid_nz);
  io.array(m.triangles);
  std::size_t colliders = m.colliders.size();
  io.count(colliders, io.remaining() / 16);
  if constexpr (Io::reading) {
    if (!io.ok()) return;
    m.colliders.assign(colliders, SoftCollider{});
  }
  for (auto& c : m.colliders) {
    detail::io_collider(io, c.shape);
    uint32_t mesh = meshes.index_of(c.mesh.mesh);
    io.u32(mesh);
    io.v3(c.mesh.position), io.q4(c.mesh.orientation);
    if constexpr (Io::reading) c.mesh.mesh = meshes.at(mesh, io);
  }
}
}  // namespace

void detail::SoftAccess::write(const SoftBody& body, ByteWriter& w, const SnapshotMeshes& meshes) {
  const SoftBody::Impl& m = *body.impl_;
  const SoftSettings& s = m.settings;
  w.enumeration(s.model, 0xFFFFFFFFu), w.u32(s.substeps), w.u32(s.iterations), w.v3(s.gravity);
  w.f32(s.damping), w.f32(s.thickness), w.f32(s.friction), w.enumeration(s.response, 0xFFFFFFFFu);
  w.f32(s.penalty_stiffness);
  for (const SpringConstants& c : m.families) w.f32(c.stiffness), w.f32(c.damping);
  io_soft_state(w, m, meshes);
}

void detail::SoftAccess::read(ByteReader& r, SoftBody& body, const SnapshotMeshes& meshes) {
  SoftBody::Impl& m = *body.impl_;
  SoftSettings s;
  r.enumeration(s.model, 0xFFFFFFFFu), r.u32(s.substeps), r.u32(s.iterations), r.v3(s.gravity);
  r.f32(s.damping), r.f32(s.thickness), r.f32(s.friction), r.enumeration(s.response, 0xFFFFFFFFu);
  r.f32(s.penalty_stiffness);
  if (!r.ok() || body.set_settings(s) != Status::ok) return r.fail();
  for (uint32_t f = 0; f < kSpringFamilyCount; ++f) {
    SpringConstants c;
    r.f32(c.stiffness), r.f32(c.damping);
    if (!r.ok() || body.set_family(static_cast<SpringFamily>(f), c) != Status::ok) return r.fail();
  }
  io_soft_state(r, m, meshes);
  if (!r.ok()) return;
  // Everything the solver indexes with must be in range.
  const std::size_t n = m.px.size();
  for (const std::vector<float>* col : {&m.py, &m.pz, &m.vx, &m.vy, &m.vz, &m.qx, &m.qy, &m.qz, &m.w, &m.mass})
    r.require(col->size() == n);
  r.require(m.pinned.size() == n && n < 0xFFFFFFFFu);
  const std::size_t springs = m.sa.size();
  r.require(m.sb.size() == springs && m.rest.size() == springs && m.family.size() == springs);
  for (std::size_t k = 0; r.ok() && k < springs; ++k)
    r.require(m.sa[k] < n && m.sb[k] < n && m.family[k] < kSpringFamilyCount);
  r.require(m.triangles.size() % 3 == 0);
  for (std::size_t k = 0; r.ok() && k < m.triangles.size(); ++k) r.require(m.triangles[k] < n);
  for (std::size_t i = 0; r.ok() && i < n; ++i) r.require(m.pinned[i] <= 1);
  r.require(m.grid_nx == 0 ? m.grid_nz == 0 : uint64_t(m.grid_nx) * m.grid_nz <= n);
  if (!r.ok()) return;
  m.live_colliders = 0;
  for (const SoftCollider& c : m.colliders) m.live_colliders += c.used();
  m.plan_dirty = true;
}

}  // namespace gyro
