// ParticleSystem (Cookbook chapter 14): SoA particle state, the three integrators and the
// swept collision against static colliders. Conventions: include/gyro/particles.hpp.
//
// Determinism: a particle's step reads only its own columns, the settings and the
// colliders, and writes only its own columns, so particles run in fixed chunks on any number
// of threads with the same bits. Colliders are tried in index order and a tie in t keeps
// the lower index. Arithmetic is + - * / and sqrt only (no FMA: -ffp-contract=off), through
// gyro's raycasts, which are themselves deterministic.
#include "gyro/particles.hpp"

#include "core/columns.hpp"
#include "core/error.hpp"
#include "core/id_pool.hpp"
#include "core/parallel.hpp"
#include "core/state_hash.hpp"
#include "core/validate.hpp"
#include "dynamics/particle_colliders.hpp"
#include "dynamics/particles_internal.hpp"
#include "dynamics/snapshot_io.hpp"
#include "gyro/raycast.hpp"

#include <cmath>
#include <vector>

namespace gyro {
namespace {

using detail::Column;
using detail::fail;
using detail::is_finite;
using detail::Collider;
using detail::ColliderKind;
using detail::first_hit;
using detail::push_out;
using detail::skin_at;

constexpr int kMaxBounces = 4;            // reflected sweeps per step; the next surface stops the particle
constexpr std::size_t kChunk = 512;       // particles per parallel chunk (fixed: results do not depend on threads)

/// Moves a particle from s towards e through the colliders: pushes s out of solids, then
/// sweeps, stopping at the first surface, reflecting velocity v and the rest of the
/// displacement (normal part * -bounce, tangential * (1 - friction)), up to kMaxBounces times.
/// Returns whether anything changed the straight path; e and v receive the result.
bool collide(const std::vector<Collider>& colliders, vec3 s, vec3& e, vec3& v, float bounce, float friction) {
  bool touched = false;
  for (const Collider& c : colliders) {
    const vec3 out = push_out(c, s);
    if (!(out == s)) e = e + (out - s), s = out, touched = true;
  }
  const float keep = 1.0f - friction;
  for (int k = 0;; ++k) {
    const vec3 d = e - s;
    float best_t = 2.0f;
    vec3 point, normal;
    for (const Collider& c : colliders) {
      float t;
      vec3 p, n;
      if (first_hit(c, s, d, &t, &p, &n) && t < best_t) best_t = t, point = p, normal = n;
    }
    if (best_t > 1.0f) return touched;
    touched = true;
    s = point + normal * skin_at(point);
    const float vn = dot(v, normal);
    if (vn < 0.0f) {
      const vec3 v_n = normal * vn;
      v = (v - v_n) * keep - v_n * bounce;
    }
    if (k == kMaxBounces) {
      e = s;
      return true;
    }
    const vec3 rest = e - point;
    const vec3 r_n = normal * dot(rest, normal);
    e = s + (rest - r_n) * keep - r_n * bounce;
  }
}

Status check_unit_interval(float v, const char* name) {
  if (!is_finite(v)) return fail(Status::non_finite, "%s is not finite", name);
  if (v < 0.0f || v > 1.0f) return fail(Status::invalid_argument, "%s %g is outside [0, 1]", name, double(v));
  return Status::ok;
}

}  // namespace

struct ParticleSystem::Impl {
  ParticleSettings settings;
  detail::IdPool pool;
  std::vector<ParticleId> ids;  // dense, ids[slot]
  Column<float> px, py, pz, vx, vy, vz;
  Column<float> qx, qy, qz;  // Verlet: the previous position
  Column<float> fx, fy, fz;  // forces for the next step
  Column<float> inv_mass, bounce, friction, gravity_scale;
  Column<uint32_t> reseed;   // 1: derive Verlet's previous position from the velocity next step
  float last_dt = 0.0f;      // the dt the previous positions belong to
  std::vector<Collider> colliders;
  std::size_t live_colliders = 0;

  uint32_t slot(ParticleId id) const { return pool.slot(detail::Id{id.index, id.generation}); }
  vec3 position(uint32_t i) const { return {px[i], py[i], pz[i]}; }
  vec3 velocity(uint32_t i) const { return {vx[i], vy[i], vz[i]}; }

  Status find(ParticleId id, uint32_t* out) const {
    *out = slot(id);
    if (*out == detail::IdPool::kNoSlot)
      return fail(Status::stale_id, "particle id {%u, %u} is stale or null", id.index, id.generation);
    return Status::ok;
  }

  Status add_collider(const Collider& c, uint32_t* index) {
    GYRO_TRY(detail::require_not_null(index, "index"));
    uint32_t at = 0;
    while (at < colliders.size() && colliders[at].kind != ColliderKind::none) ++at;
    if (at == colliders.size()) colliders.push_back(c);
    else colliders[at] = c;
    ++live_colliders;
    *index = at;
    return Status::ok;
  }

  void step_one(uint32_t i, float dt, float damp, bool reseed_all);
};

namespace {
/// Every float column, in the order create() fills and hash_into() hashes them.
constexpr Column<float> ParticleSystem::Impl::*kFloatColumns[] = {
    &ParticleSystem::Impl::px, &ParticleSystem::Impl::py, &ParticleSystem::Impl::pz,
    &ParticleSystem::Impl::vx, &ParticleSystem::Impl::vy, &ParticleSystem::Impl::vz,
    &ParticleSystem::Impl::qx, &ParticleSystem::Impl::qy, &ParticleSystem::Impl::qz,
    &ParticleSystem::Impl::fx, &ParticleSystem::Impl::fy, &ParticleSystem::Impl::fz,
    &ParticleSystem::Impl::inv_mass, &ParticleSystem::Impl::bounce, &ParticleSystem::Impl::friction,
    &ParticleSystem::Impl::gravity_scale};
}  // namespace

// ---------------------------------------------------------------- lifetime and settings

ParticleSystem::ParticleSystem() : impl_(std::make_unique<Impl>()) {}
ParticleSystem::~ParticleSystem() = default;
ParticleSystem::ParticleSystem(const ParticleSystem& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
ParticleSystem& ParticleSystem::operator=(const ParticleSystem& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}

Status ParticleSystem::set_settings(const ParticleSettings& s) {
  if (!gyro::is_finite(s.gravity)) return fail(Status::non_finite, "particle gravity is not finite");
  if (!is_finite(s.damping)) return fail(Status::non_finite, "particle damping is not finite");
  if (s.damping < 0.0f) return fail(Status::invalid_argument, "particle damping %g is negative", double(s.damping));
  if (static_cast<uint32_t>(s.integrator) > static_cast<uint32_t>(ParticleIntegrator::verlet))
    return fail(Status::invalid_argument, "unknown particle integrator %u", static_cast<uint32_t>(s.integrator));
  if (s.integrator != impl_->settings.integrator) {
    // Verlet's previous positions are only kept up to date while it runs.
    for (std::size_t i = 0; i < impl_->reseed.size(); ++i) impl_->reseed[i] = 1;
  }
  impl_->settings = s;
  return Status::ok;
}

const ParticleSettings& ParticleSystem::settings() const { return impl_->settings; }

// ---------------------------------------------------------------- particles

Status ParticleSystem::create(const ParticleDef& def, ParticleId* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  if (!gyro::is_finite(def.position)) return fail(Status::non_finite, "particle position is not finite");
  if (!gyro::is_finite(def.velocity)) return fail(Status::non_finite, "particle velocity is not finite");
  if (!def.pinned) {
    if (!is_finite(def.mass)) return fail(Status::non_finite, "particle mass is not finite");
    if (!(def.mass > 0.0f)) return fail(Status::invalid_argument, "particle mass %g is not > 0 (pin it instead)", double(def.mass));
  }
  GYRO_TRY(check_unit_interval(def.bounce, "particle bounce"));
  GYRO_TRY(check_unit_interval(def.friction, "particle friction"));
  if (!is_finite(def.gravity_scale)) return fail(Status::non_finite, "particle gravity_scale is not finite");

  Impl& m = *impl_;
  const std::size_t n = m.ids.size();
  bool room = m.reseed.reserve(n + 1);
  for (auto col : kFloatColumns) room = room && (m.*col).reserve(n + 1);
  if (!room) return fail(Status::out_of_memory, "no memory for particle %zu", n);
  m.ids.reserve(n + 1);

  const detail::Id id = m.pool.create();
  const vec3 p = def.position, v = def.velocity;
  const float values[] = {p.x, p.y, p.z, v.x, v.y, v.z, p.x, p.y, p.z, 0.0f, 0.0f, 0.0f,
                          def.pinned ? 0.0f : 1.0f / def.mass, def.bounce, def.friction, def.gravity_scale};
  for (std::size_t k = 0; k < std::size(kFloatColumns); ++k) (m.*kFloatColumns[k]).push_back(values[k]);
  m.reseed.push_back(1);
  m.ids.push_back({id.index, id.generation});
  *out = {id.index, id.generation};
  return Status::ok;
}

Status ParticleSystem::destroy(ParticleId id) {
  Impl& m = *impl_;
  uint32_t slot;
  GYRO_TRY(m.find(id, &slot));
  const detail::IdPool::Removal r = m.pool.destroy(detail::Id{id.index, id.generation});
  for (auto col : kFloatColumns) (m.*col).swap_remove(r.slot);
  m.reseed.swap_remove(r.slot);
  m.ids[r.slot] = m.ids.back();
  m.ids.pop_back();
  return Status::ok;
}

bool ParticleSystem::is_valid(ParticleId id) const { return impl_->slot(id) != detail::IdPool::kNoSlot; }
std::size_t ParticleSystem::count() const { return impl_->ids.size(); }

Status ParticleSystem::get_position(ParticleId id, vec3* position) const {
  GYRO_TRY(detail::require_not_null(position, "position"));
  uint32_t i;
  GYRO_TRY(impl_->find(id, &i));
  *position = impl_->position(i);
  return Status::ok;
}

Status ParticleSystem::get_velocity(ParticleId id, vec3* velocity) const {
  GYRO_TRY(detail::require_not_null(velocity, "velocity"));
  uint32_t i;
  GYRO_TRY(impl_->find(id, &i));
  *velocity = impl_->velocity(i);
  return Status::ok;
}

Status ParticleSystem::set_position(ParticleId id, const vec3& position) {
  uint32_t i;
  GYRO_TRY(impl_->find(id, &i));
  if (!gyro::is_finite(position)) return fail(Status::non_finite, "particle position is not finite");
  Impl& m = *impl_;
  m.px[i] = position.x, m.py[i] = position.y, m.pz[i] = position.z;
  m.reseed[i] = 1;
  return Status::ok;
}

Status ParticleSystem::set_velocity(ParticleId id, const vec3& velocity) {
  uint32_t i;
  GYRO_TRY(impl_->find(id, &i));
  if (!gyro::is_finite(velocity)) return fail(Status::non_finite, "particle velocity is not finite");
  Impl& m = *impl_;
  m.vx[i] = velocity.x, m.vy[i] = velocity.y, m.vz[i] = velocity.z;
  m.reseed[i] = 1;
  return Status::ok;
}

Status ParticleSystem::add_force(ParticleId id, const vec3& force) {
  uint32_t i;
  GYRO_TRY(impl_->find(id, &i));
  if (!gyro::is_finite(force)) return fail(Status::non_finite, "particle force is not finite");
  Impl& m = *impl_;
  m.fx[i] = m.fx[i] + force.x, m.fy[i] = m.fy[i] + force.y, m.fz[i] = m.fz[i] + force.z;
  return Status::ok;
}

// ---------------------------------------------------------------- colliders

Status ParticleSystem::add_collider(const Sphere& sphere, uint32_t* index) {
  Collider c;
  GYRO_TRY(detail::to_collider(sphere, &c));
  return impl_->add_collider(c, index);
}

Status ParticleSystem::add_collider(const AABB& box, uint32_t* index) {
  Collider c;
  GYRO_TRY(detail::to_collider(box, &c));
  return impl_->add_collider(c, index);
}

Status ParticleSystem::add_collider(const OBB& box, uint32_t* index) {
  Collider c;
  GYRO_TRY(detail::to_collider(box, &c));
  return impl_->add_collider(c, index);
}

Status ParticleSystem::add_collider(const Plane& plane, uint32_t* index) {
  Collider c;
  GYRO_TRY(detail::to_collider(plane, &c));
  return impl_->add_collider(c, index);
}

Status ParticleSystem::remove_collider(uint32_t index) {
  Impl& m = *impl_;
  if (index >= m.colliders.size() || m.colliders[index].kind == ColliderKind::none)
    return fail(Status::invalid_argument, "no particle collider %u", index);
  m.colliders[index] = Collider{};
  --m.live_colliders;
  while (!m.colliders.empty() && m.colliders.back().kind == ColliderKind::none) m.colliders.pop_back();
  return Status::ok;
}

void ParticleSystem::clear_colliders() {
  impl_->colliders.clear();
  impl_->live_colliders = 0;
}

std::size_t ParticleSystem::collider_count() const { return impl_->live_colliders; }

// ---------------------------------------------------------------- step

void ParticleSystem::Impl::step_one(uint32_t i, float dt, float damp, bool reseed_all) {
  const vec3 x = position(i), v = velocity(i);
  const float im = inv_mass[i];
  vec3 xn, vn;
  if (im == 0.0f) {  // pinned: kinematic
    xn = x + v * dt;
    qx[i] = x.x, qy[i] = x.y, qz[i] = x.z;
    px[i] = xn.x, py[i] = xn.y, pz[i] = xn.z;
    fx[i] = fy[i] = fz[i] = 0.0f;
    reseed[i] = 0;
    return;
  }
  const vec3 a = settings.gravity * gravity_scale[i] + vec3{fx[i], fy[i], fz[i]} * im;
  const ParticleIntegrator integrator = settings.integrator;
  switch (integrator) {
    case ParticleIntegrator::explicit_euler:
      xn = x + v * dt;
      vn = (v + a * dt) * damp;
      break;
    case ParticleIntegrator::semi_implicit_euler:
      vn = (v + a * dt) * damp;
      xn = x + vn * dt;
      break;
    case ParticleIntegrator::verlet: {
      // The previous position that makes the step x + v dt + a dt^2 / 2 (exact for constant a).
      const vec3 prev = (reseed_all || reseed[i]) ? x - v * dt + a * (0.5f * dt * dt) : vec3{qx[i], qy[i], qz[i]};
      // The small terms first: one rounding at the position's magnitude per step.
      xn = x + ((x - prev) * damp + a * (dt * dt));
      vn = (xn - x) / dt + a * (0.5f * dt);
      break;
    }
  }
  const bool hit = !colliders.empty() && collide(colliders, x, xn, vn, bounce[i], friction[i]);
  if (integrator == ParticleIntegrator::verlet) {
    // After a bounce, the previous position whose implied velocity is the reflected one.
    const vec3 q = hit ? xn - vn * dt + a * (0.5f * dt * dt) : x;
    qx[i] = q.x, qy[i] = q.y, qz[i] = q.z;
  } else {
    qx[i] = x.x, qy[i] = x.y, qz[i] = x.z;
  }
  px[i] = xn.x, py[i] = xn.y, pz[i] = xn.z;
  vx[i] = vn.x, vy[i] = vn.y, vz[i] = vn.z;
  fx[i] = fy[i] = fz[i] = 0.0f;
  reseed[i] = 0;
}

Status ParticleSystem::step(float dt) {
  if (!is_finite(dt)) return fail(Status::non_finite, "particle step dt is not finite");
  if (!(dt > 0.0f)) return fail(Status::invalid_argument, "particle step dt %g is not > 0", double(dt));
  Impl& m = *impl_;
  const float damp = 1.0f / (1.0f + dt * m.settings.damping);
  const bool reseed_all = dt != m.last_dt;  // Verlet's previous positions were for another dt
  detail::parallel_for(m.ids.size(), kChunk, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) m.step_one(static_cast<uint32_t>(i), dt, damp, reseed_all);
  });
  m.last_dt = dt;
  return Status::ok;
}

// ---------------------------------------------------------------- views and hashing

ParticleView ParticleSystem::view() const {
  const Impl& m = *impl_;
  return {m.ids.size(), m.ids.data(), m.px.data(), m.py.data(), m.pz.data(), m.vx.data(), m.vy.data(), m.vz.data()};
}

uint64_t ParticleSystem::hash() const {
  detail::StateHasher h;
  detail::ParticleAccess::hash_into(*this, h);
  return h.digest();
}

void detail::ParticleAccess::hash_into(const ParticleSystem& ps, StateHasher& h) {
  const ParticleSystem::Impl& m = *ps.impl_;
  const ParticleSettings& s = m.settings;
  h.add_float(s.gravity.x), h.add_float(s.gravity.y), h.add_float(s.gravity.z);
  h.add_u32(static_cast<uint32_t>(s.integrator));
  h.add_float(s.damping);
  h.add_float(m.last_dt);
  m.pool.hash_into(h);
  const std::size_t n = m.ids.size();
  for (auto col : kFloatColumns) h.add_floats({(m.*col).data(), n});
  h.add_u32s({m.reseed.data(), n});
  for (const ParticleId& id : m.ids) h.add_u64((uint64_t{id.index} << 32) | id.generation);
  h.add_u64(m.colliders.size());
  for (const Collider& c : m.colliders) detail::hash_collider(c, h);
}

// ---------------------------------------------------------------- snapshot

namespace {
// The columns and colliders, in one description for both directions.
template <class Io, class M> void io_particle_state(Io& io, M& m, std::size_t n) {
  io.f32(m.last_dt);
  for (auto col : kFloatColumns) io.column(m.*col, n);
  io.column(m.reseed, n);
  std::size_t colliders = m.colliders.size();
  io.count(colliders, io.remaining() / 16);
  if constexpr (Io::reading) {
    if (!io.ok()) return;
    m.colliders.assign(colliders, Collider{});
  }
  for (auto& c : m.colliders) detail::io_collider(io, c);
}
}  // namespace

void detail::ParticleAccess::write(const ParticleSystem& ps, ByteWriter& w) {
  const ParticleSystem::Impl& m = *ps.impl_;
  w.v3(m.settings.gravity), w.enumeration(m.settings.integrator, 2), w.f32(m.settings.damping);
  m.pool.write(w);
  io_particle_state(w, m, m.ids.size());
}

void detail::ParticleAccess::read(ByteReader& r, ParticleSystem& ps) {
  ParticleSystem::Impl& m = *ps.impl_;
  ParticleSettings settings;
  r.v3(settings.gravity), r.enumeration(settings.integrator, 2), r.f32(settings.damping);
  if (!r.ok() || ps.set_settings(settings) != Status::ok) return r.fail();
  m.pool.read(r);
  if (!r.ok()) return;
  const std::size_t n = m.pool.size();
  try {
    m.ids.resize(n);
  } catch (const std::bad_alloc&) {
    return r.fail();
  }
  for (std::size_t i = 0; i < n; ++i) {
    const detail::Id id = m.pool.id_at(static_cast<uint32_t>(i));
    m.ids[i] = {id.index, id.generation};
  }
  io_particle_state(r, m, n);
  if (!r.ok()) return;
  m.live_colliders = 0;
  for (const Collider& c : m.colliders) m.live_colliders += c.kind != ColliderKind::none;
  for (std::size_t i = 0; i < n; ++i) r.require(m.reseed[i] <= 1);
}

}  // namespace gyro
