// A world step, stage by stage in the Cookbook's order. Every stage is written so that its
// result depends only on the state and the inputs: loops over bodies run in slot order or
// in fixed chunks that each write their own outputs; contacts are ordered by ids.
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "dynamics/body_bounds.hpp"
#include "dynamics/body_integrate.hpp"
#include "dynamics/mass.hpp"
#include "gyro/particles.hpp"
#include "gyro/triangle_mesh.hpp"
#include "world/world_impl.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace gyro {
namespace {

using detail::BodyStore;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

constexpr std::size_t kBodyChunk = 2048;  // integration is ~20 ns a body: smaller chunks cost more than they save
constexpr std::size_t kMinIntegrateChunk = 256;  // ~5 us of integration: well above a fork and join

}  // namespace

void World::Impl::wake(uint32_t i) {
  if (!bodies.is_dynamic(i)) return;
  bodies.flags[i] |= detail::kBodyAwake;
  bodies.sleep_time[i] = 0.0f;
}

void World::Impl::find_pairs(float dt) {
  BodyStore& s = bodies;
  const uint32_t n = s.size();
  candidates.clear();
  bool any_active = false;
  for (uint32_t i = 0; i < n; ++i) any_active = any_active || active[i];
  if (!any_active) return;

  // Bounds: the shape's box grown by the speculative margin and, for moving bodies, by the
  // motion of the step, so a fast body finds what it could reach.
  broad_slot.clear(), planes.clear();
  bmin_x.clear(), bmin_y.clear(), bmin_z.clear(), bmax_x.clear(), bmax_y.clear(), bmax_z.clear();
  broad_key.clear(), broad_cat.clear(), broad_mask.clear(), broad_flags.clear();
  const float spec = 4.0f * def.linear_slop;
  for (uint32_t i = 0; i < n; ++i) {
    if (s.shape[i] == uint32_t(BodyShape::plane)) {
      planes.push_back(i);
      continue;
    }
    const AABB box = detail::shape_bounds(s, i);
    vec3 reach = box.half_extents;
    const vec3 c = box.center;
    float grow = spec;
    if (active[i] && def.enable_continuous)
      grow = grow + (length(s.linear_velocity(i)) + length(s.angular_velocity(i)) * s.radius[i]) * dt;
    reach = reach + vec3{grow, grow, grow};
    broad_slot.push_back(i);
    bmin_x.push_back(c.x - reach.x), bmin_y.push_back(c.y - reach.y), bmin_z.push_back(c.z - reach.z);
    bmax_x.push_back(c.x + reach.x), bmax_y.push_back(c.y + reach.y), bmax_z.push_back(c.z + reach.z);
    broad_key.push_back(s.id[i].index);
    broad_cat.push_back(s.category[i]), broad_mask.push_back(s.mask[i]);
    broad_flags.push_back(uint8_t((s.is_dynamic(i) ? detail::kBroadDynamic : 0) | (active[i] ? detail::kBroadActive : 0)));
  }
  detail::BroadphaseInput in;
  in.count = broad_slot.size();
  in.min_x = bmin_x.data(), in.min_y = bmin_y.data(), in.min_z = bmin_z.data();
  in.max_x = bmax_x.data(), in.max_y = bmax_y.data(), in.max_z = bmax_z.data();
  in.category = broad_cat.data(), in.mask = broad_mask.data(), in.flags = broad_flags.data(), in.key = broad_key.data();
  broadphase.find_pairs(in, broad_pairs);
  for (const detail::BroadPair& p : broad_pairs) candidates.push_back({broad_slot[p.a], broad_slot[p.b]});

  // Planes are infinite: tested against every active dynamic body directly.
  if (!planes.empty()) {
    const std::size_t before = candidates.size();
    for (uint32_t k = 0; k < broad_slot.size(); ++k) {
      const uint32_t i = broad_slot[k];
      if (!active[i] || !s.is_dynamic(i)) continue;
      for (uint32_t p : planes) {
        if (!(s.category[i] & s.mask[p]) || !(s.category[p] & s.mask[i])) continue;
        const vec3 nrm = rotate(s.orientation(p), vec3{0.0f, 1.0f, 0.0f});
        const vec3 c{(bmin_x[k] + bmax_x[k]) * 0.5f, (bmin_y[k] + bmax_y[k]) * 0.5f, (bmin_z[k] + bmax_z[k]) * 0.5f};
        const vec3 e{(bmax_x[k] - bmin_x[k]) * 0.5f, (bmax_y[k] - bmin_y[k]) * 0.5f, (bmax_z[k] - bmin_z[k]) * 0.5f};
        const float dist = dot(nrm, c - s.position(p));
        const float r = (std::abs(nrm.x) * e.x + std::abs(nrm.y) * e.y) + std::abs(nrm.z) * e.z;
        if (std::abs(dist) > r) continue;
        const bool plane_first = s.id[p].index < s.id[i].index;
        candidates.push_back(plane_first ? detail::CandidatePair{p, i} : detail::CandidatePair{i, p});
      }
    }
    if (candidates.size() != before) {
      // Keys are unique, so this order is total and the sort deterministic.
      std::sort(candidates.begin(), candidates.end(), [&](const detail::CandidatePair& x, const detail::CandidatePair& y) {
        const uint64_t kx = (uint64_t{s.id[x.a].index} << 32) | s.id[x.b].index;
        const uint64_t ky = (uint64_t{s.id[y.a].index} << 32) | s.id[y.b].index;
        return kx < ky;
      });
    }
  }
}

void World::Impl::wake_islands() {
  BodyStore& s = bodies;
  islands.build(s, contacts.records());
  const uint32_t ni = islands.count();
  island_awake.assign(ni, 0);
  // A kinematic body touching an island keeps it awake (it moves, whatever the island does).
  for (const detail::ContactRecord& r : contacts.records()) {
    const bool ka = s.type[r.slot_a] == uint32_t(BodyType::kinematic), kb = s.type[r.slot_b] == uint32_t(BodyType::kinematic);
    if (ka == kb || !r.touching()) continue;
    const uint32_t kin = ka ? r.slot_a : r.slot_b;
    if (length_squared(s.linear_velocity(kin)) == 0.0f && length_squared(s.angular_velocity(kin)) == 0.0f) continue;
    const uint32_t k = islands.island_of(ka ? r.slot_b : r.slot_a);
    if (k != detail::Islands::kNone) island_awake[k] = 1;
  }
  for (uint32_t i = 0; i < s.size(); ++i) {
    const uint32_t k = islands.island_of(i);
    if (k != detail::Islands::kNone && s.is_awake(i)) island_awake[k] = 1;
  }
  for (uint32_t i = 0; i < s.size(); ++i) {
    const uint32_t k = islands.island_of(i);
    if (k != detail::Islands::kNone && island_awake[k] && !s.is_awake(i)) wake(i);
  }
}

void World::Impl::build_solver_bodies() {
  BodyStore& s = bodies;
  const uint32_t n = s.size();
  index_of_slot.resize(n);
  slot_of_body.clear();
  for (uint32_t i = 0; i < n; ++i) {
    const bool moves = (s.is_dynamic(i) && s.is_awake(i)) || s.type[i] == uint32_t(BodyType::kinematic);
    index_of_slot[i] = moves ? uint32_t(slot_of_body.size()) : 0xFFFFFFFFu;
    if (moves) slot_of_body.push_back(i);
  }
  const uint32_t m = uint32_t(slot_of_body.size());
  for (uint32_t i = 0; i < n; ++i)
    if (index_of_slot[i] == 0xFFFFFFFFu) index_of_slot[i] = m;  // the dummy
  solver_bodies.resize(m + 1);
  inv_inertia.resize(6 * std::size_t(m + 1));
  inv_mass.resize(m + 1);
  writable.resize(m + 1);
  lin_acc.resize(3 * std::size_t(m));
  ang_acc.resize(3 * std::size_t(m));
  const vec3 g = def.gravity;
  detail::parallel_for(m + 1, kBodyChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      detail::SolverBody& sb = solver_bodies[b];
      sb = detail::SolverBody{};
      float* ii = inv_inertia.data() + 6 * b;
      if (b == m) {
        for (int k = 0; k < 6; ++k) ii[k] = 0.0f;
        inv_mass[b] = 0.0f, writable[b] = 0;
        continue;
      }
      const uint32_t i = slot_of_body[b];
      const bool dyn = s.is_dynamic(i);
      sb.v[0] = s.vx[i], sb.v[1] = s.vy[i], sb.v[2] = s.vz[i];
      sb.w[0] = s.wx[i], sb.w[1] = s.wy[i], sb.w[2] = s.wz[i];
      sb.dynamic = dyn ? 1u : 0u;
      writable[b] = dyn ? 1 : 0;
      inv_mass[b] = s.inv_mass[i];
      // World inverse inertia R diag(d) R^T; the rows of to_mat3(q) are the body axes.
      const mat3 r = to_mat3(s.orientation(i));
      const float d[3] = {s.inv_ix[i], s.inv_iy[i], s.inv_iz[i]};
      auto e = [&](int x, int y) {
        return (r.m[0][x] * d[0] * r.m[0][y] + r.m[1][x] * d[1] * r.m[1][y]) + r.m[2][x] * d[2] * r.m[2][y];
      };
      ii[0] = e(0, 0), ii[1] = e(0, 1), ii[2] = e(0, 2), ii[3] = e(1, 1), ii[4] = e(1, 2), ii[5] = e(2, 2);
      const float gs = s.gravity_scale[i], im = s.inv_mass[i];
      vec3 la{}, aa{};
      if (dyn) {
        la = g * gs + vec3{s.fx[i], s.fy[i], s.fz[i]} * im;
        const vec3 t{s.tx[i], s.ty[i], s.tz[i]};
        aa = {(ii[0] * t.x + ii[1] * t.y) + ii[2] * t.z, (ii[1] * t.x + ii[3] * t.y) + ii[4] * t.z,
              (ii[2] * t.x + ii[4] * t.y) + ii[5] * t.z};
      }
      lin_acc[b] = la.x, lin_acc[m + b] = la.y, lin_acc[2 * std::size_t(m) + b] = la.z;
      ang_acc[b] = aa.x, ang_acc[m + b] = aa.y, ang_acc[2 * std::size_t(m) + b] = aa.z;
    }
  });
}

detail::IntegrateArgs World::Impl::integrate_args(float h) {
  BodyStore& s = bodies;
  const std::size_t m = slot_of_body.size();
  if (solver_index.size() < m) {
    const std::size_t from = solver_index.size();
    solver_index.resize(m);
    for (std::size_t b = from; b < m; ++b) solver_index[b] = uint32_t(b);
  }
  detail::IntegrateArgs args;
  args.bodies = solver_bodies.data();
  args.solver_index = solver_index.data();
  args.slot_of_body = slot_of_body.data();
  args.px = s.px.data(), args.py = s.py.data(), args.pz = s.pz.data();
  args.qx = s.qx.data(), args.qy = s.qy.data(), args.qz = s.qz.data(), args.qw = s.qw.data();
  args.h = h;
  for (std::size_t k = 0; k < 3; ++k) args.lin_acc[k] = lin_acc.data() + k * m, args.ang_acc[k] = ang_acc.data() + k * m;
  args.linear_damping = s.linear_damping.data(), args.angular_damping = s.angular_damping.data();
  args.inv_ix = s.inv_ix.data(), args.inv_iy = s.inv_iy.data(), args.inv_iz = s.inv_iz.data();
  return args;
}

// The sub-step's integrations split the solver bodies the way the contact passes split
// their colours: one chunk per thread, statically assigned (thread k always takes chunk k).
// Constraints are ordered by body id, so chunk k of every colour mostly touches the bodies
// of chunk k here, and a body's row stays in one core's cache through the sub-step instead
// of moving to the calling thread for every integration (measured on 16 pyramids, 2
// threads: the solver stage took ~15% longer with integration on one thread).
void World::Impl::integrate_split(integrate_positions_fn* kernel, float h) {
  const detail::IntegrateArgs args = integrate_args(h);
  const std::size_t m = slot_of_body.size();
  const std::size_t chunk = detail::per_thread_chunk(m, kMinIntegrateChunk, 16);  // whole SIMD batches
  detail::parallel_stages(
      1, 2, [&](std::size_t, std::size_t* n, std::size_t* c) { *n = m, *c = chunk; },
      [&](std::size_t, std::size_t begin, std::size_t end) { kernel(args, begin, end); });
}

void World::Impl::integrate_velocities(float h) { integrate_split(GYRO_DISPATCH(integrate_velocities), h); }

void World::Impl::integrate_positions(float h) { integrate_split(GYRO_DISPATCH(integrate_positions), h); }

void World::Impl::write_back() {
  BodyStore& s = bodies;
  const std::size_t m = slot_of_body.size();
  for (std::size_t b = 0; b < m; ++b) {
    const detail::SolverBody& sb = solver_bodies[b];
    if (!sb.dynamic) continue;
    const uint32_t i = slot_of_body[b];
    s.vx[i] = sb.v[0], s.vy[i] = sb.v[1], s.vz[i] = sb.v[2];
    s.wx[i] = sb.w[0], s.wy[i] = sb.w[1], s.wz[i] = sb.w[2];
  }
}

void World::Impl::update_sleep(float dt) {
  BodyStore& s = bodies;
  const uint32_t n = s.size();
  const float lv = def.sleep_linear_velocity, av = def.sleep_angular_velocity;
  for (uint32_t i = 0; i < n; ++i) {
    if (!s.is_dynamic(i) || !s.is_awake(i)) continue;
    const bool still = (s.flags[i] & detail::kBodyAllowSleep) && length_squared(s.linear_velocity(i)) <= lv * lv &&
                       length_squared(s.angular_velocity(i)) <= av * av;
    s.sleep_time[i] = still ? s.sleep_time[i] + dt : 0.0f;
  }
  // A body touching a moving kinematic body must stay awake.
  for (const detail::ContactRecord& r : contacts.records()) {
    if (!r.touching()) continue;
    for (int side = 0; side < 2; ++side) {
      const uint32_t k = side ? r.slot_b : r.slot_a, o = side ? r.slot_a : r.slot_b;
      if (s.type[k] == uint32_t(BodyType::kinematic) &&
          (length_squared(s.linear_velocity(k)) > 0.0f || length_squared(s.angular_velocity(k)) > 0.0f))
        s.sleep_time[o] = 0.0f;
    }
  }
  if (!def.enable_sleep) return;
  const uint32_t ni = islands.count();
  island_rest.assign(ni, 3.0e38f);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t k = islands.island_of(i);
    if (k == detail::Islands::kNone) continue;
    const float t = s.is_awake(i) ? s.sleep_time[i] : 3.0e38f;
    island_rest[k] = t < island_rest[k] ? t : island_rest[k];
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t k = islands.island_of(i);
    if (k == detail::Islands::kNone || !s.is_awake(i) || island_rest[k] < def.sleep_time) continue;
    s.flags[i] &= ~detail::kBodyAwake;
    s.set_linear_velocity(i, {});
    s.set_angular_velocity(i, {});
  }
}

void World::Impl::step(float dt) {
  BodyStore& s = bodies;
  const uint32_t n = s.size();
  timings = StepTimings{};
  stats = StepStats{};
  const auto t_start = Clock::now();

  // Forces: which bodies move this step (the rest are skipped by every later stage).
  auto t0 = Clock::now();
  active.resize(n);
  for (uint32_t i = 0; i < n; ++i)
    active[i] = uint8_t((s.is_dynamic(i) && s.is_awake(i)) || s.type[i] == uint32_t(BodyType::kinematic));
  timings.forces = ms_since(t0);

  t0 = Clock::now();
  find_pairs(dt);
  timings.broadphase = ms_since(t0);

  t0 = Clock::now();
  // Also with nothing to collide: last step's touches must end and its events clear.
  if (!candidates.empty() || !contacts.records().empty() || !contacts.begin_events().empty() ||
      !contacts.end_events().empty()) {
    detail::ContactSettings cs;
    cs.speculative_distance = 4.0f * def.linear_slop;
    cs.continuous = def.enable_continuous;
    cs.incremental_convex = def.convex_manifold == ConvexManifold::incremental;
    cs.dt = dt;
    contacts.update(s, candidates, active.data(), cs);
  }
  timings.narrowphase = ms_since(t0);

  t0 = Clock::now();
  wake_islands();
  timings.islands = ms_since(t0);

  t0 = Clock::now();
  build_solver_bodies();
  if (!slot_of_body.empty()) {
    const bool soft = def.contact_model == ContactModel::soft_step;
    const uint32_t substeps = soft ? def.substeps : 1;
    const float h = dt / float(substeps);
    detail::SolverBodies sbv;
    sbv.bodies = solver_bodies.data();
    sbv.inv_inertia = inv_inertia.data();
    sbv.inv_mass = inv_mass.data();
    sbv.writable = writable.data();
    sbv.index_of_slot = index_of_slot.data();
    sbv.count = slot_of_body.size();
    stats.colors = solver.prepare(s, contacts.records(), sbv, def, dt, h);
    const detail::BiasMode bias = def.contact_model == ContactModel::soft_step   ? detail::BiasMode::soft
                                  : def.contact_model == ContactModel::baumgarte ? detail::BiasMode::baumgarte
                                                                                 : detail::BiasMode::none;
    for (uint32_t sub = 0; sub < substeps; ++sub) {
      integrate_velocities(h);
      solver.warm_start();
      for (uint32_t it = 0; it < def.velocity_iterations; ++it) solver.solve(bias);
      integrate_positions(h);
      if (soft)
        for (uint32_t it = 0; it < def.relax_iterations; ++it) solver.solve(detail::BiasMode::none);
    }
    if (def.contact_model == ContactModel::linear_projection)
      for (uint32_t it = 0; it < def.position_iterations; ++it) solver.project_positions(s, slot_of_body.data());
    solver.restitution();
    solver.store_impulses(contacts.records());
    write_back();
  }
  update_sleep(dt);
  timings.solver = ms_since(t0);

  t0 = Clock::now();
  if (particles && !particles->empty()) particles->step(dt);
  timings.particles = ms_since(t0);

  if (!soft_bodies.empty()) {
    t0 = Clock::now();
    step_soft_bodies(dt);
    timings.soft_bodies = ms_since(t0);
  }

  for (uint32_t i = 0; i < n; ++i) s.fx[i] = s.fy[i] = s.fz[i] = s.tx[i] = s.ty[i] = s.tz[i] = 0.0f;

  stats.bodies = n;
  for (uint32_t i = 0; i < n; ++i) stats.awake_bodies += (s.is_dynamic(i) && s.is_awake(i)) ? 1u : 0u;
  stats.pairs = uint32_t(candidates.size());
  for (const detail::ContactRecord& r : contacts.records()) {
    stats.manifolds += r.manifold.count > 0 ? 1u : 0u;
    stats.contacts += r.manifold.count;
  }
  stats.islands = islands.count();
  ++steps;
  timings.total = ms_since(t_start);
}

}  // namespace gyro
