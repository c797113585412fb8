// The World API: validation at the boundary (bad input changes nothing), body creation and
// destruction, state access, and the hash. The step's stages are in step.cpp.
#include "core/error.hpp"
#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "dynamics/mass.hpp"
#include "dynamics/particles_internal.hpp"
#include "gyro/triangle_mesh.hpp"
#include "world/world_impl.hpp"

#include <new>

namespace gyro {
namespace {

using detail::fail;
using detail::is_finite;


Status check_vec(const vec3& v, const char* name) {
  return gyro::is_finite(v) ? Status::ok : fail(Status::non_finite, "%s is not finite", name);
}

// A unit quaternion from the input, or an error for NaN, infinite or (near) zero ones.
Status unit_quat(const quat& q, quat* out, const char* name) {
  if (!gyro::is_finite(q)) return fail(Status::non_finite, "%s is not finite", name);
  const float n = dot(q, q);
  if (!(n > 1e-12f) || !is_finite(n)) return fail(Status::invalid_argument, "%s is zero or too large", name);
  *out = normalized(q);
  return Status::ok;
}

}  // namespace

World::World() : impl_(std::make_unique<Impl>()) {}
World::~World() = default;

Status World::create(const WorldDef& def, std::unique_ptr<World>* out) {
  if (!out) return fail(Status::null_argument, "out is null");
  GYRO_TRY(check_vec(def.gravity, "gravity"));
  if (uint32_t(def.contact_model) > uint32_t(ContactModel::linear_projection))
    return fail(Status::invalid_argument, "unknown contact model %u", unsigned(def.contact_model));
  auto in_range = [](uint32_t v) { return v >= 1 && v <= 64; };
  if (!in_range(def.substeps) || !in_range(def.velocity_iterations) || !in_range(def.position_iterations) ||
      def.relax_iterations > 64)
    return fail(Status::invalid_argument, "substeps and iterations must be in 1..64 (relax 0..64)");
  const float nonneg[] = {def.linear_slop, def.baumgarte, def.contact_hertz, def.contact_damping_ratio,
                          def.max_push_velocity, def.restitution_threshold, def.sleep_time,
                          def.sleep_linear_velocity, def.sleep_angular_velocity};
  for (float v : nonneg)
    if (!is_finite(v) || v < 0.0f) return fail(Status::invalid_argument, "world settings must be finite and >= 0");
  if (uint32_t(def.convex_manifold) > uint32_t(ConvexManifold::incremental))
    return fail(Status::invalid_argument, "unknown convex manifold %u", unsigned(def.convex_manifold));
  if (def.baumgarte > 1.0f) return fail(Status::invalid_argument, "baumgarte must be in [0, 1]");
  if (def.threads > 1024) return fail(Status::invalid_count, "threads must be <= 1024");
  std::unique_ptr<World> w(new (std::nothrow) World());
  if (!w || !w->impl_) return fail(Status::out_of_memory, "world");
  w->impl_->def = def;
  *out = std::move(w);
  return Status::ok;
}

Status World::create_body(const BodyDef& def, BodyId* out) {
  if (!out) return fail(Status::null_argument, "out is null");
  if (uint32_t(def.type) > uint32_t(BodyType::dynamic))
    return fail(Status::invalid_argument, "unknown body type %u", unsigned(def.type));
  GYRO_TRY(check_vec(def.position, "position"));
  GYRO_TRY(check_vec(def.linear_velocity, "linear_velocity"));
  GYRO_TRY(check_vec(def.angular_velocity, "angular_velocity"));
  quat q;
  GYRO_TRY(unit_quat(def.orientation, &q, "orientation"));
  const float materials[] = {def.friction, def.restitution, def.linear_damping, def.angular_damping};
  for (float v : materials)
    if (!is_finite(v) || v < 0.0f) return fail(Status::invalid_argument, "friction, restitution and damping must be finite and >= 0");
  if (!is_finite(def.gravity_scale)) return fail(Status::non_finite, "gravity_scale is not finite");
  GYRO_TRY(detail::check_shape(def));
  std::unique_ptr<detail::BodyHull> hull;
  vec3 position = def.position;
  if (def.shape.type == BodyShape::hull) {
    hull.reset(new (std::nothrow) detail::BodyHull);
    if (!hull) return fail(Status::out_of_memory, "hull");
    GYRO_TRY(detail::make_body_hull(*def.shape.hull, hull.get()));
    // The body frame is the mass frame: where the caller's frame puts the centroid, turned
    // by the principal axes.
    position = def.position - rotate(q * conjugate(hull->shape_rotation), hull->shape_offset);
    q = normalized(q * conjugate(hull->shape_rotation));
    if (!gyro::is_finite(position)) return fail(Status::non_finite, "hull position overflows");
  }
  detail::MassProperties mp;
  GYRO_TRY(detail::compute_mass(def, hull.get(), &mp));

  detail::BodyStore& s = impl_->bodies;
  if (!s.reserve(s.size() + 1)) return fail(Status::out_of_memory, "bodies");
  auto& hulls = impl_->hulls;
  if (hull && hulls.size() <= s.ids.next_index()) {  // room before the id is taken: nothing to undo
    try {
      hulls.resize(std::size_t(s.ids.next_index()) + 1);
    } catch (const std::bad_alloc&) {
      return fail(Status::out_of_memory, "hulls");
    }
  }
  const detail::Id id = s.ids.create();
  const BodyId bid{id.index, id.generation};
  if (hull) hulls[id.index] = std::move(hull);
  const detail::BodyHull* body_hull = def.shape.type == BodyShape::hull ? hulls[id.index].get() : nullptr;
  const bool moves = def.type != BodyType::static_body;
  s.id.push_back(bid);
  s.px.push_back(position.x), s.py.push_back(position.y), s.pz.push_back(position.z);
  s.qx.push_back(q.x), s.qy.push_back(q.y), s.qz.push_back(q.z), s.qw.push_back(q.w);
  const vec3 v = moves ? def.linear_velocity : vec3{}, w = moves ? def.angular_velocity : vec3{};
  s.vx.push_back(v.x), s.vy.push_back(v.y), s.vz.push_back(v.z);
  s.wx.push_back(w.x), s.wy.push_back(w.y), s.wz.push_back(w.z);
  for (auto* c : {&s.fx, &s.fy, &s.fz, &s.tx, &s.ty, &s.tz}) c->push_back(0.0f);
  s.mass.push_back(mp.mass), s.inv_mass.push_back(mp.inv_mass);
  s.inv_ix.push_back(mp.inv_inertia.x), s.inv_iy.push_back(mp.inv_inertia.y), s.inv_iz.push_back(mp.inv_inertia.z);
  s.linear_damping.push_back(def.linear_damping), s.angular_damping.push_back(def.angular_damping);
  s.gravity_scale.push_back(def.gravity_scale);
  s.sleep_time.push_back(0.0f);
  s.type.push_back(uint32_t(def.type));
  s.shape.push_back(uint32_t(def.shape.type));
  s.radius.push_back(def.shape.type == BodyShape::sphere ? def.shape.radius
                                                         : detail::bounding_radius(def.shape, body_hull));
  const bool box = def.shape.type == BodyShape::box, capsule = def.shape.type == BodyShape::capsule;
  s.hx.push_back(box ? def.shape.half_extents.x : capsule ? def.shape.radius : 0.0f);
  s.hy.push_back(box ? def.shape.half_extents.y : capsule ? def.shape.half_height : 0.0f);
  s.hz.push_back(box ? def.shape.half_extents.z : 0.0f);
  s.mesh.push_back(def.shape.type == BodyShape::mesh ? def.shape.mesh : nullptr);
  s.hull.push_back(body_hull);
  s.friction.push_back(def.friction), s.restitution.push_back(def.restitution);
  s.category.push_back(def.category), s.mask.push_back(def.mask);
  uint32_t flags = def.allow_sleep ? detail::kBodyAllowSleep : 0u;
  if (def.awake || def.type != BodyType::dynamic) flags |= detail::kBodyAwake;
  s.flags.push_back(flags);
  s.user_data.push_back(def.user_data);
  *out = bid;
  return Status::ok;
}

namespace {
// The dense slot of a live id, or a stale_id failure.
Status slot_of(const detail::BodyStore& s, BodyId id, uint32_t* slot) {
  const uint32_t k = s.ids.slot(detail::Id{id.index, id.generation});
  if (k == detail::IdPool::kNoSlot)
    return fail(Status::stale_id, "body {%u, %u} does not exist", unsigned(id.index), unsigned(id.generation));
  *slot = k;
  return Status::ok;
}
}  // namespace

Status World::destroy_body(BodyId id) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(slot_of(s, id, &k));
  // Bodies resting on this one must notice it is gone.
  for (const detail::ContactRecord& r : impl_->contacts.records())
    if (r.index_a() == id.index || r.index_b() == id.index) impl_->wake(r.index_a() == id.index ? r.slot_b : r.slot_a);
  impl_->contacts.remove_body(id.index);
  const detail::IdPool::Removal rm = s.ids.destroy(detail::Id{id.index, id.generation});
  s.for_each_column([&](auto& c) { c.swap_remove(rm.slot); });
  if (id.index < impl_->hulls.size()) impl_->hulls[id.index].reset();
  if (rm.moved_from != rm.slot) impl_->contacts.remap_slot(rm.moved_from, rm.slot);
  return Status::ok;
}

bool World::is_valid(BodyId id) const { return impl_->bodies.ids.valid(detail::Id{id.index, id.generation}); }
std::size_t World::body_count() const { return impl_->bodies.size(); }

Status World::get_transform(BodyId id, vec3* position, quat* orientation) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (position) *position = impl_->bodies.position(k);
  if (orientation) *orientation = impl_->bodies.orientation(k);
  return Status::ok;
}

Status World::set_transform(BodyId id, const vec3& position, const quat& orientation) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(slot_of(s, id, &k));
  GYRO_TRY(check_vec(position, "position"));
  quat q;
  GYRO_TRY(unit_quat(orientation, &q, "orientation"));
  s.set_position(k, position);
  s.set_orientation(k, q);
  impl_->wake(k);
  for (const detail::ContactRecord& r : impl_->contacts.records())
    if (r.slot_a == k || r.slot_b == k) impl_->wake(r.slot_a == k ? r.slot_b : r.slot_a);
  return Status::ok;
}

Status World::get_shape_frame(BodyId id, vec3* offset, quat* rotation) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!offset && !rotation) return fail(Status::null_argument, "offset and rotation are both null");
  const detail::BodyHull* h = impl_->bodies.hull[k];
  if (offset) *offset = h ? h->shape_offset : vec3{};
  if (rotation) *rotation = h ? h->shape_rotation : quat{};
  return Status::ok;
}

Status World::get_mesh(BodyId id, const TriangleMesh** mesh) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!mesh) return fail(Status::null_argument, "mesh is null");
  *mesh = impl_->bodies.mesh[k];
  return Status::ok;
}

Status World::get_velocity(BodyId id, vec3* linear, vec3* angular) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (linear) *linear = impl_->bodies.linear_velocity(k);
  if (angular) *angular = impl_->bodies.angular_velocity(k);
  return Status::ok;
}

Status World::set_velocity(BodyId id, const vec3& linear, const vec3& angular) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(slot_of(s, id, &k));
  GYRO_TRY(check_vec(linear, "linear"));
  GYRO_TRY(check_vec(angular, "angular"));
  if (s.is_static(k)) return fail(Status::invalid_argument, "a static body has no velocity");
  s.set_linear_velocity(k, linear);
  s.set_angular_velocity(k, angular);
  impl_->wake(k);
  return Status::ok;
}

Status World::get_mass(BodyId id, float* mass) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!mass) return fail(Status::null_argument, "mass is null");
  *mass = impl_->bodies.mass[k];
  return Status::ok;
}

Status World::get_type(BodyId id, BodyType* type) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!type) return fail(Status::null_argument, "type is null");
  *type = BodyType(impl_->bodies.type[k]);
  return Status::ok;
}

Status World::get_user_data(BodyId id, uint64_t* user_data) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!user_data) return fail(Status::null_argument, "user_data is null");
  *user_data = impl_->bodies.user_data[k];
  return Status::ok;
}

namespace {
// Forces and impulses act on dynamic bodies only (a no-op with status ok on others would hide
// mistakes: they get invalid_argument).
Status dynamic_slot(const detail::BodyStore& s, BodyId id, uint32_t* k) {
  GYRO_TRY(slot_of(s, id, k));
  if (!s.is_dynamic(*k)) return fail(Status::invalid_argument, "body {%u, %u} is not dynamic", id.index, id.generation);
  return Status::ok;
}
}  // namespace

Status World::apply_force(BodyId id, const vec3& force, const vec3& point) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(check_vec(force, "force"));
  GYRO_TRY(check_vec(point, "point"));
  GYRO_TRY(dynamic_slot(s, id, &k));
  const vec3 t = cross(point - s.position(k), force);
  s.fx[k] += force.x, s.fy[k] += force.y, s.fz[k] += force.z;
  s.tx[k] += t.x, s.ty[k] += t.y, s.tz[k] += t.z;
  impl_->wake(k);
  return Status::ok;
}

Status World::apply_force_at_center(BodyId id, const vec3& force) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(check_vec(force, "force"));
  GYRO_TRY(dynamic_slot(s, id, &k));
  s.fx[k] += force.x, s.fy[k] += force.y, s.fz[k] += force.z;
  impl_->wake(k);
  return Status::ok;
}

Status World::apply_torque(BodyId id, const vec3& torque) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(check_vec(torque, "torque"));
  GYRO_TRY(dynamic_slot(s, id, &k));
  s.tx[k] += torque.x, s.ty[k] += torque.y, s.tz[k] += torque.z;
  impl_->wake(k);
  return Status::ok;
}

namespace {
vec3 inv_inertia_times(const detail::BodyStore& s, uint32_t k, const vec3& x) {
  const quat q = s.orientation(k);
  const vec3 b = rotate(conjugate(q), x);
  return rotate(q, vec3{b.x * s.inv_ix[k], b.y * s.inv_iy[k], b.z * s.inv_iz[k]});
}
}  // namespace

Status World::apply_linear_impulse(BodyId id, const vec3& impulse, const vec3& point) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(check_vec(impulse, "impulse"));
  GYRO_TRY(check_vec(point, "point"));
  GYRO_TRY(dynamic_slot(s, id, &k));
  s.set_linear_velocity(k, s.linear_velocity(k) + impulse * s.inv_mass[k]);
  s.set_angular_velocity(k, s.angular_velocity(k) + inv_inertia_times(s, k, cross(point - s.position(k), impulse)));
  impl_->wake(k);
  return Status::ok;
}

Status World::apply_angular_impulse(BodyId id, const vec3& impulse) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(check_vec(impulse, "impulse"));
  GYRO_TRY(dynamic_slot(s, id, &k));
  s.set_angular_velocity(k, s.angular_velocity(k) + inv_inertia_times(s, k, impulse));
  impl_->wake(k);
  return Status::ok;
}

Status World::set_awake(BodyId id, bool awake) {
  detail::BodyStore& s = impl_->bodies;
  uint32_t k = 0;
  GYRO_TRY(slot_of(s, id, &k));
  if (!s.is_dynamic(k)) return Status::ok;
  if (awake) {
    impl_->wake(k);
  } else {
    s.flags[k] &= ~detail::kBodyAwake;
    s.set_linear_velocity(k, {});
    s.set_angular_velocity(k, {});
  }
  return Status::ok;
}

Status World::is_awake(BodyId id, bool* awake) const {
  uint32_t k = 0;
  GYRO_TRY(slot_of(impl_->bodies, id, &k));
  if (!awake) return fail(Status::null_argument, "awake is null");
  *awake = impl_->bodies.is_awake(k);
  return Status::ok;
}

Status World::step(float dt) {
  if (!is_finite(dt) || !(dt > 0.0f)) return fail(Status::invalid_argument, "dt must be finite and > 0");
  detail::FloatEnvGuard env;
  detail::ScopedThreadCount threads(impl_->def.threads);
  impl_->step(dt);
  return Status::ok;
}

uint64_t World::hash() const {
  detail::StateHasher h;
  h.add_u64(impl_->steps);
  impl_->bodies.ids.hash_into(h);
  impl_->bodies.hash_into(h);
  impl_->contacts.hash_into(h);
  if (impl_->particles) detail::hash_into(*impl_->particles, h);
  if (!impl_->soft_bodies.empty()) {
    impl_->soft_pool.hash_into(h);
    for (const auto& body : impl_->soft_bodies) detail::SoftAccess::hash_into(*body, h);
  }
  return h.digest();
}

BodyView World::bodies() const {
  const detail::BodyStore& s = impl_->bodies;
  BodyView v;
  v.count = s.size();
  v.ids = s.id.data();
  v.px = s.px.data(), v.py = s.py.data(), v.pz = s.pz.data();
  v.qx = s.qx.data(), v.qy = s.qy.data(), v.qz = s.qz.data(), v.qw = s.qw.data();
  v.vx = s.vx.data(), v.vy = s.vy.data(), v.vz = s.vz.data();
  v.wx = s.wx.data(), v.wy = s.wy.data(), v.wz = s.wz.data();
  return v;
}

const StepTimings& World::timings() const { return impl_->timings; }
const StepStats& World::stats() const { return impl_->stats; }

std::size_t World::begin_events(const ContactEvent** events) const {
  const auto& e = impl_->contacts.begin_events();
  if (events) *events = e.data();
  return e.size();
}
std::size_t World::end_events(const ContactEvent** events) const {
  const auto& e = impl_->contacts.end_events();
  if (events) *events = e.data();
  return e.size();
}

const WorldDef& World::def() const { return impl_->def; }

ParticleSystem& World::particles() {
  if (!impl_->particles) {
    impl_->particles = std::make_unique<ParticleSystem>();
    ParticleSettings settings;
    settings.gravity = impl_->def.gravity;  // particles fall like the bodies unless told otherwise
    impl_->particles->set_settings(settings);
  }
  return *impl_->particles;
}

}  // namespace gyro

namespace gyro::detail {

void BodyStore::hash_into(StateHasher& h) const {
  const std::size_t n = size();
  h.add_u64(n);
  auto floats = [&](const Column<float>& c) { h.add_floats({c.data(), n}); };
  auto words = [&](const Column<uint32_t>& c) { h.add_u32s({c.data(), n}); };
  for (std::size_t i = 0; i < n; ++i) h.add_u64((uint64_t{id[i].index} << 32) | id[i].generation);
  for (const Column<float>* c : {&px, &py, &pz, &qx, &qy, &qz, &qw, &vx, &vy, &vz, &wx, &wy, &wz, &fx, &fy, &fz, &tx, &ty,
                                 &tz, &mass, &inv_mass, &inv_ix, &inv_iy, &inv_iz, &linear_damping, &angular_damping,
                                 &gravity_scale, &sleep_time, &radius, &hx, &hy, &hz, &friction, &restitution})
    floats(*c);
  for (const Column<uint32_t>* c : {&type, &shape, &category, &mask, &flags}) words(*c);
  for (std::size_t i = 0; i < n; ++i) {
    h.add_u64(user_data[i]);
    h.add_u64(mesh[i] ? mesh[i]->triangle_count() : 0);
    if (hull[i]) {
      h.add_u64((uint64_t{hull[i]->hull.vertices.size()} << 32) | hull[i]->hull.face_count());
      for (const vec3& v : hull[i]->hull.vertices) h.add_float(v.x), h.add_float(v.y), h.add_float(v.z);
    }
  }
}

}  // namespace gyro::detail
