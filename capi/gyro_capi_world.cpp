// The C ABI of the dynamics world: world and body definitions (ABI 1.3 and 1.4 layouts),
// body state and shape frames, forces and impulses, zero-copy views, timings, stats and
// contact events, over gyro/world.hpp.
//
// Every entry point checks what it can before touching the world (NULL, struct_size, enum
// values, booleans, reserved fields, NaN/Inf, stale ids, dt), so a bad call changes nothing
// whatever the C++ layer would do with it; range checks (negative mass, zero-size shapes,
// zero quaternions, ...) are the C++ layer's and keep its detail text.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_convex.hpp"
#include "capi_handles.hpp"
#include "capi_support.hpp"
#include "capi_recorder.hpp"
#include "capi_world.hpp"
#include "core/validate.hpp"
#include "gyro/world.hpp"

#include <climits>
#include <cstddef>
#include <cstring>
#include <map>
#include <memory>
#include <utility>

namespace {

using gyro::Status;
using gyro::capi::guarded;
using gyro::capi::c_v3;
using gyro::capi::check_bool;
using gyro::capi::check_finite;
using gyro::capi::require;
using gyro::capi::v3;
using gyro::detail::fail;
using gyro::detail::is_finite;

// The C structs mirror the C++ ones where the views and events are handed out without a copy.
static_assert(sizeof(gyro_body_id) == sizeof(gyro::BodyId) && alignof(gyro_body_id) == alignof(gyro::BodyId));
static_assert(sizeof(gyro_contact_event) == sizeof(gyro::ContactEvent) &&
              offsetof(gyro::ContactEvent, b) == offsetof(gyro_contact_event, b));
static_assert(sizeof(gyro_vec3) == 12 && sizeof(gyro_quat) == 16 && sizeof(gyro_world_def) == 92 &&
              sizeof(gyro_step_timings) == 56 && sizeof(gyro_step_stats) == 32 && sizeof(gyro_contact_event) == 16);
static_assert(sizeof(void*) != 8 || (sizeof(gyro_body_def) == 160 && sizeof(gyro_body_view) == 120 &&
                                     sizeof(gyro_contact_events) == 24));
// ABI 1.3's gyro_body_def ended with mesh: its size is the offset of half_height rounded up to
// the struct's alignment (the fields appended in 1.4 need no more alignment than uint64_t
// and pointers, so the alignment is unchanged).
constexpr std::size_t kBodyDefSize13 = (offsetof(gyro_body_def, half_height) + alignof(gyro_body_def) - 1) /
                                       alignof(gyro_body_def) * alignof(gyro_body_def);
static_assert(sizeof(void*) != 8 || (offsetof(gyro_body_def, half_height) == 144 && kBodyDefSize13 == 144 &&
                                     offsetof(gyro_body_def, hull) == 152));
static_assert(kBodyDefSize13 < sizeof(gyro_body_def));
static_assert(uint32_t(gyro::BodyType::dynamic) == GYRO_BODY_DYNAMIC &&
              uint32_t(gyro::BodyType::kinematic) == GYRO_BODY_KINEMATIC &&
              uint32_t(gyro::BodyType::static_body) == GYRO_BODY_STATIC);
static_assert(uint32_t(gyro::BodyShape::sphere) == GYRO_BODY_SHAPE_SPHERE &&
              uint32_t(gyro::BodyShape::box) == GYRO_BODY_SHAPE_BOX &&
              uint32_t(gyro::BodyShape::plane) == GYRO_BODY_SHAPE_PLANE &&
              uint32_t(gyro::BodyShape::mesh) == GYRO_BODY_SHAPE_MESH &&
              uint32_t(gyro::BodyShape::capsule) == GYRO_BODY_SHAPE_CAPSULE &&
              uint32_t(gyro::BodyShape::hull) == GYRO_BODY_SHAPE_HULL);
static_assert(uint32_t(gyro::ConvexManifold::clipping) == GYRO_CONVEX_MANIFOLD_CLIPPING &&
              uint32_t(gyro::ConvexManifold::incremental) == GYRO_CONVEX_MANIFOLD_INCREMENTAL);
static_assert(uint32_t(gyro::ContactModel::soft_step) == GYRO_CONTACT_SOFT_STEP &&
              uint32_t(gyro::ContactModel::baumgarte) == GYRO_CONTACT_BAUMGARTE &&
              uint32_t(gyro::ContactModel::linear_projection) == GYRO_CONTACT_LINEAR_PROJECTION);

gyro::BodyId id_of(gyro_body_id id) { return {id.index, id.generation}; }
gyro_body_id c_id(gyro::BodyId id) { return {id.index, id.generation}; }
gyro::quat q4(gyro_quat q) { return {q.x, q.y, q.z, q.w}; }
gyro_quat c_q4(const gyro::quat& q) { return {q.x, q.y, q.z, q.w}; }

Status check_finite(gyro_quat q, const char* name) {
  if (is_finite(q.x) && is_finite(q.y) && is_finite(q.z) && is_finite(q.w)) return Status::ok;
  return fail(Status::non_finite, "%s has a NaN or infinite component", name);
}

Status require_world(const gyro_world* w) { return require(w, "world"); }

// The world and a live body: every per-body call starts here, so a stale id never reaches
// the C++ layer and the status does not depend on how it reports one.
Status require_body(const gyro_world* w, gyro_body_id id) {
  GYRO_TRY(require_world(w));
  if (!w->world->is_valid(id_of(id)))
    return fail(Status::stale_id, "body {%u, %u} is not a live body of this world", id.index, id.generation);
  return Status::ok;
}

// ABI 1.3's gyro_world_def ended before convex_manifold.
constexpr std::size_t kWorldDefSize13 = offsetof(gyro_world_def, convex_manifold);

Status world_def_of(const gyro_world_def& given, gyro::WorldDef& out) {
  gyro_world_def d;
  if (given.struct_size == sizeof(gyro_world_def)) {
    d = given;
  } else if (given.struct_size == kWorldDefSize13) {
    d = gyro_world_def_default();  // the fields 1.3 lacks keep their defaults
    std::memcpy(&d, &given, kWorldDefSize13);
  } else {
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_world_def_default()", given.struct_size);
  }
  if (d.convex_manifold > GYRO_CONVEX_MANIFOLD_INCREMENTAL)
    return fail(Status::invalid_argument, "def->convex_manifold = %u is unknown", d.convex_manifold);
  if (d.contact_model > GYRO_CONTACT_LINEAR_PROJECTION)
    return fail(Status::invalid_argument, "def->contact_model = %u is unknown", d.contact_model);
  GYRO_TRY(check_bool(d.enable_warm_starting, "def->enable_warm_starting"));
  GYRO_TRY(check_bool(d.enable_sleep, "def->enable_sleep"));
  GYRO_TRY(check_bool(d.enable_continuous, "def->enable_continuous"));
  GYRO_TRY(check_finite(d.gravity, "def->gravity"));
  const std::pair<float, const char*> floats[] = {
      {d.linear_slop, "def->linear_slop"}, {d.baumgarte, "def->baumgarte"},
      {d.contact_hertz, "def->contact_hertz"}, {d.contact_damping_ratio, "def->contact_damping_ratio"},
      {d.max_push_velocity, "def->max_push_velocity"}, {d.restitution_threshold, "def->restitution_threshold"},
      {d.sleep_time, "def->sleep_time"}, {d.sleep_linear_velocity, "def->sleep_linear_velocity"},
      {d.sleep_angular_velocity, "def->sleep_angular_velocity"}};
  for (const auto& [v, name] : floats) GYRO_TRY(check_finite(v, name));
  gyro::WorldDef w;
  w.gravity = v3(d.gravity);
  w.contact_model = static_cast<gyro::ContactModel>(d.contact_model);
  w.substeps = d.substeps, w.velocity_iterations = d.velocity_iterations;
  w.relax_iterations = d.relax_iterations, w.position_iterations = d.position_iterations;
  w.linear_slop = d.linear_slop, w.baumgarte = d.baumgarte;
  w.contact_hertz = d.contact_hertz, w.contact_damping_ratio = d.contact_damping_ratio;
  w.max_push_velocity = d.max_push_velocity, w.restitution_threshold = d.restitution_threshold;
  w.enable_warm_starting = d.enable_warm_starting != 0, w.enable_sleep = d.enable_sleep != 0;
  w.sleep_time = d.sleep_time, w.sleep_linear_velocity = d.sleep_linear_velocity;
  w.sleep_angular_velocity = d.sleep_angular_velocity;
  w.enable_continuous = d.enable_continuous != 0, w.threads = d.threads;
  w.convex_manifold = static_cast<gyro::ConvexManifold>(d.convex_manifold);
  out = w;
  return Status::ok;
}

gyro_body_def default_body_def() {
  const gyro::BodyDef b;
  gyro_body_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_body_def);
  d.type = static_cast<gyro_body_type>(b.type);
  d.shape = static_cast<gyro_body_shape>(b.shape.type);
  d.radius = b.shape.radius;
  d.half_extents = c_v3(b.shape.half_extents);
  d.position = c_v3(b.position);
  d.orientation = c_q4(b.orientation);
  d.linear_velocity = c_v3(b.linear_velocity);
  d.angular_velocity = c_v3(b.angular_velocity);
  d.density = b.density, d.mass = b.mass, d.friction = b.friction, d.restitution = b.restitution;
  d.linear_damping = b.linear_damping, d.angular_damping = b.angular_damping, d.gravity_scale = b.gravity_scale;
  d.category = b.category, d.mask = b.mask;
  d.allow_sleep = b.allow_sleep, d.awake = b.awake;
  d.user_data = b.user_data;
  d.mesh = nullptr;
  d.half_height = b.shape.half_height;
  d.hull = nullptr;
  return d;
}

// The caller's definition as this header's struct: an ABI 1.3 one (struct_size
// kBodyDefSize13) is read only up to its end, the fields it lacks keep their defaults.
Status read_body_def(const gyro_body_def* def, gyro_body_def& out) {
  uint32_t size = 0;
  std::memcpy(&size, def, sizeof size);
  if (size == sizeof(gyro_body_def)) {
    out = *def;
    return Status::ok;
  }
  if (size != kBodyDefSize13)
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_body_def_default()", size);
  gyro_body_def d = default_body_def();
  std::memcpy(&d, def, offsetof(gyro_body_def, half_height));
  out = d;
  return Status::ok;
}

// The C++ BodyDef, with the mesh reference to keep (null for other shapes). d comes from
// read_body_def (struct_size is this header's or ABI 1.3's).
Status body_def_of(const gyro_body_def& d, gyro::BodyDef& out, std::shared_ptr<const gyro::TriangleMesh>& mesh) {
  const bool abi13 = d.struct_size != sizeof(gyro_body_def);
  if (d.type > GYRO_BODY_DYNAMIC) return fail(Status::invalid_argument, "def->type = %u is unknown", d.type);
  if (d.shape > GYRO_BODY_SHAPE_HULL) return fail(Status::invalid_argument, "def->shape = %u is unknown", d.shape);
  if (abi13 && d.shape > GYRO_BODY_SHAPE_MESH)
    return fail(Status::invalid_argument,
                "def->shape = %u needs the ABI 1.4 gyro_body_def (struct_size %zu, not %u): start from "
                "gyro_body_def_default()",
                d.shape, sizeof(gyro_body_def), d.struct_size);
  if (d.reserved != 0) return fail(Status::invalid_argument, "def->reserved must be 0");
  if (d.reserved2 != 0) return fail(Status::invalid_argument, "def->reserved2 must be 0");
  GYRO_TRY(check_bool(d.allow_sleep, "def->allow_sleep"));
  GYRO_TRY(check_bool(d.awake, "def->awake"));
  if (d.shape == GYRO_BODY_SHAPE_MESH) {
    GYRO_TRY(require(d.mesh, "def->mesh"));
  } else if (d.mesh) {
    return fail(Status::invalid_argument, "def->mesh is set but def->shape = %u is not GYRO_BODY_SHAPE_MESH", d.shape);
  }
  if (d.shape == GYRO_BODY_SHAPE_HULL) {
    GYRO_TRY(require(d.hull, "def->hull"));
  } else if (d.hull) {
    return fail(Status::invalid_argument, "def->hull is set but def->shape = %u is not GYRO_BODY_SHAPE_HULL", d.shape);
  }
  GYRO_TRY(check_finite(d.half_height, "def->half_height"));
  GYRO_TRY(check_finite(d.half_extents, "def->half_extents"));
  GYRO_TRY(check_finite(d.position, "def->position"));
  GYRO_TRY(check_finite(d.orientation, "def->orientation"));
  GYRO_TRY(check_finite(d.linear_velocity, "def->linear_velocity"));
  GYRO_TRY(check_finite(d.angular_velocity, "def->angular_velocity"));
  const std::pair<float, const char*> floats[] = {
      {d.radius, "def->radius"}, {d.density, "def->density"}, {d.mass, "def->mass"},
      {d.friction, "def->friction"}, {d.restitution, "def->restitution"},
      {d.linear_damping, "def->linear_damping"}, {d.angular_damping, "def->angular_damping"},
      {d.gravity_scale, "def->gravity_scale"}};
  for (const auto& [v, name] : floats) GYRO_TRY(check_finite(v, name));
  gyro::BodyDef b;
  b.type = static_cast<gyro::BodyType>(d.type);
  b.shape.type = static_cast<gyro::BodyShape>(d.shape);
  b.shape.radius = d.radius;
  b.shape.half_extents = v3(d.half_extents);
  b.shape.mesh = d.mesh ? d.mesh->mesh.get() : nullptr;
  b.shape.half_height = d.half_height;
  b.shape.hull = d.hull ? &d.hull->hull : nullptr;  // copied by the world
  b.position = v3(d.position);
  b.orientation = q4(d.orientation);
  b.linear_velocity = v3(d.linear_velocity);
  b.angular_velocity = v3(d.angular_velocity);
  b.density = d.density, b.mass = d.mass, b.friction = d.friction, b.restitution = d.restitution;
  b.linear_damping = d.linear_damping, b.angular_damping = d.angular_damping, b.gravity_scale = d.gravity_scale;
  b.category = d.category, b.mask = d.mask;
  b.allow_sleep = d.allow_sleep != 0, b.awake = d.awake != 0;
  b.user_data = d.user_data;
  out = b;
  mesh = d.mesh ? d.mesh->mesh : nullptr;
  return Status::ok;
}

Status check_count_fits(std::size_t n, const char* name) {
  return n <= std::size_t(INT32_MAX) ? Status::ok
                                     : fail(Status::invalid_count, "%s = %zu does not fit an int32_t", name, n);
}

}  // namespace

extern "C" {

GYRO_API gyro_world_def gyro_world_def_default(void) {
  const gyro::WorldDef w;
  gyro_world_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_world_def);
  d.contact_model = static_cast<gyro_contact_model>(w.contact_model);
  d.gravity = c_v3(w.gravity);
  d.substeps = w.substeps, d.velocity_iterations = w.velocity_iterations;
  d.relax_iterations = w.relax_iterations, d.position_iterations = w.position_iterations;
  d.linear_slop = w.linear_slop, d.baumgarte = w.baumgarte;
  d.contact_hertz = w.contact_hertz, d.contact_damping_ratio = w.contact_damping_ratio;
  d.max_push_velocity = w.max_push_velocity, d.restitution_threshold = w.restitution_threshold;
  d.enable_warm_starting = w.enable_warm_starting, d.enable_sleep = w.enable_sleep;
  d.sleep_time = w.sleep_time, d.sleep_linear_velocity = w.sleep_linear_velocity;
  d.sleep_angular_velocity = w.sleep_angular_velocity;
  d.enable_continuous = w.enable_continuous, d.threads = w.threads;
  d.convex_manifold = static_cast<gyro_convex_manifold>(w.convex_manifold);
  return d;
}

GYRO_API gyro_status gyro_world_create(const gyro_world_def* def, gyro_world** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro::WorldDef w;
    GYRO_TRY(world_def_of(*def, w));
    auto c = std::make_unique<gyro_world>();
    GYRO_TRY(gyro::World::create(w, &c->world));
    if (!c->world) return fail(Status::internal, "World::create returned ok and no world");
    *out = c.release();
    return Status::ok;
  });
}

GYRO_API void gyro_world_destroy(gyro_world* world) {
  // The bodies go first (with the world), then the meshes they pointed at.
  if (world) world->world.reset();
  delete world;
}

GYRO_API gyro_status gyro_world_step(gyro_world* world, float dt) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(check_finite(dt, "dt"));
    if (!(dt > 0.0f)) return fail(Status::invalid_argument, "dt = %g must be > 0", double(dt));
    return world->world->step(dt);
  });
  return gyro::capi::rec::recorded<&gyro_world_step>(st, world, dt);
}

GYRO_API gyro_status gyro_world_hash(const gyro_world* world, uint64_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    *out = world->world->hash();
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_body_count(const gyro_world* world, int32_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const std::size_t n = world->world->body_count();
    GYRO_TRY(check_count_fits(n, "body_count"));
    *out = int32_t(n);
    return Status::ok;
  });
}

GYRO_API gyro_body_def gyro_body_def_default(void) { return default_body_def(); }

GYRO_API gyro_status gyro_body_create(gyro_world* world, const gyro_body_def* def, gyro_body_id* out) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro_body_def d = default_body_def();
    GYRO_TRY(read_body_def(def, d));
    gyro::BodyDef b;
    std::shared_ptr<const gyro::TriangleMesh> mesh;
    GYRO_TRY(body_def_of(d, b, mesh));
    // The mesh reference's map node is allocated before the body exists, so nothing can
    // fail once it does (re-keying and inserting a node allocate nothing).
    decltype(world->meshes) staged;
    if (mesh) staged.emplace(std::pair<uint32_t, uint32_t>{0, 0}, std::move(mesh));
    gyro::BodyId id;
    const Status s = world->world->create_body(b, &id);
    if (s == Status::ok && !staged.empty()) {
      auto node = staged.extract(staged.begin());
      node.key() = {id.index, id.generation};
      world->meshes.insert(std::move(node));
    }
    if (s != Status::ok) return s;
    *out = c_id(id);
    return Status::ok;
  });
  return gyro::capi::rec::recorded<&gyro_body_create>(st, world, def, out);
}

GYRO_API gyro_status gyro_body_destroy(gyro_world* world, gyro_body_id id) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(world->world->destroy_body(id_of(id)));
    world->meshes.erase({id.index, id.generation});  // no-op for other shapes; never throws
    return Status::ok;
  });
  return gyro::capi::rec::recorded<&gyro_body_destroy>(st, world, id);
}

GYRO_API uint32_t gyro_body_is_valid(const gyro_world* world, gyro_body_id id) {
  return world && world->world->is_valid(id_of(id)) ? 1u : 0u;
}

GYRO_API gyro_status gyro_body_get_transform(const gyro_world* world, gyro_body_id id, gyro_vec3* position,
                                             gyro_quat* orientation) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    if (!position && !orientation) return fail(Status::null_argument, "position and orientation are both null");
    gyro::vec3 p;
    gyro::quat q;
    GYRO_TRY(world->world->get_transform(id_of(id), &p, &q));
    if (position) *position = c_v3(p);
    if (orientation) *orientation = c_q4(q);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_get_shape_frame(const gyro_world* world, gyro_body_id id, gyro_vec3* offset,
                                               gyro_quat* rotation) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    if (!offset && !rotation) return fail(Status::null_argument, "offset and rotation are both null");
    gyro::vec3 o;
    gyro::quat q;
    GYRO_TRY(world->world->get_shape_frame(id_of(id), &o, &q));
    if (offset) *offset = c_v3(o);
    if (rotation) *rotation = c_q4(q);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_set_transform(gyro_world* world, gyro_body_id id, gyro_vec3 position,
                                             gyro_quat orientation) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(position, "position"));
    GYRO_TRY(check_finite(orientation, "orientation"));
    return world->world->set_transform(id_of(id), v3(position), q4(orientation));
  });
  return gyro::capi::rec::recorded<&gyro_body_set_transform>(st, world, id, position, orientation);
}

GYRO_API gyro_status gyro_body_get_velocity(const gyro_world* world, gyro_body_id id, gyro_vec3* linear,
                                            gyro_vec3* angular) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    if (!linear && !angular) return fail(Status::null_argument, "linear and angular are both null");
    gyro::vec3 v, w;
    GYRO_TRY(world->world->get_velocity(id_of(id), &v, &w));
    if (linear) *linear = c_v3(v);
    if (angular) *angular = c_v3(w);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_set_velocity(gyro_world* world, gyro_body_id id, gyro_vec3 linear, gyro_vec3 angular) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(linear, "linear"));
    GYRO_TRY(check_finite(angular, "angular"));
    return world->world->set_velocity(id_of(id), v3(linear), v3(angular));
  });
  return gyro::capi::rec::recorded<&gyro_body_set_velocity>(st, world, id, linear, angular);
}

GYRO_API gyro_status gyro_body_get_mass(const gyro_world* world, gyro_body_id id, float* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(require(out, "out"));
    float m = 0.0f;
    GYRO_TRY(world->world->get_mass(id_of(id), &m));
    *out = m;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_get_type(const gyro_world* world, gyro_body_id id, gyro_body_type* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(require(out, "out"));
    gyro::BodyType t{};
    GYRO_TRY(world->world->get_type(id_of(id), &t));
    *out = static_cast<gyro_body_type>(t);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_get_user_data(const gyro_world* world, gyro_body_id id, uint64_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(require(out, "out"));
    uint64_t u = 0;
    GYRO_TRY(world->world->get_user_data(id_of(id), &u));
    *out = u;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_body_apply_force(gyro_world* world, gyro_body_id id, gyro_vec3 force, gyro_vec3 world_point) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(force, "force"));
    GYRO_TRY(check_finite(world_point, "world_point"));
    return world->world->apply_force(id_of(id), v3(force), v3(world_point));
  });
  return gyro::capi::rec::recorded<&gyro_body_apply_force>(st, world, id, force, world_point);
}

GYRO_API gyro_status gyro_body_apply_force_at_center(gyro_world* world, gyro_body_id id, gyro_vec3 force) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(force, "force"));
    return world->world->apply_force_at_center(id_of(id), v3(force));
  });
  return gyro::capi::rec::recorded<&gyro_body_apply_force_at_center>(st, world, id, force);
}

GYRO_API gyro_status gyro_body_apply_torque(gyro_world* world, gyro_body_id id, gyro_vec3 torque) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(torque, "torque"));
    return world->world->apply_torque(id_of(id), v3(torque));
  });
  return gyro::capi::rec::recorded<&gyro_body_apply_torque>(st, world, id, torque);
}

GYRO_API gyro_status gyro_body_apply_linear_impulse(gyro_world* world, gyro_body_id id, gyro_vec3 impulse,
                                                    gyro_vec3 world_point) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(impulse, "impulse"));
    GYRO_TRY(check_finite(world_point, "world_point"));
    return world->world->apply_linear_impulse(id_of(id), v3(impulse), v3(world_point));
  });
  return gyro::capi::rec::recorded<&gyro_body_apply_linear_impulse>(st, world, id, impulse, world_point);
}

GYRO_API gyro_status gyro_body_apply_angular_impulse(gyro_world* world, gyro_body_id id, gyro_vec3 impulse) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_finite(impulse, "impulse"));
    return world->world->apply_angular_impulse(id_of(id), v3(impulse));
  });
  return gyro::capi::rec::recorded<&gyro_body_apply_angular_impulse>(st, world, id, impulse);
}

GYRO_API gyro_status gyro_body_set_awake(gyro_world* world, gyro_body_id id, uint32_t awake) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(check_bool(awake, "awake"));
    return world->world->set_awake(id_of(id), awake != 0);
  });
  return gyro::capi::rec::recorded<&gyro_body_set_awake>(st, world, id, awake);
}

GYRO_API gyro_status gyro_body_is_awake(const gyro_world* world, gyro_body_id id, uint32_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_body(world, id));
    GYRO_TRY(require(out, "out"));
    bool awake = false;
    GYRO_TRY(world->world->is_awake(id_of(id), &awake));
    *out = awake ? 1u : 0u;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_get_body_view(const gyro_world* world, gyro_body_view* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const gyro::BodyView v = world->world->bodies();
    GYRO_TRY(check_count_fits(v.count, "body count"));
    gyro_body_view c;
    std::memset(&c, 0, sizeof c);
    c.count = int32_t(v.count);
    c.ids = reinterpret_cast<const gyro_body_id*>(v.ids);
    c.px = v.px, c.py = v.py, c.pz = v.pz;
    c.qx = v.qx, c.qy = v.qy, c.qz = v.qz, c.qw = v.qw;
    c.vx = v.vx, c.vy = v.vy, c.vz = v.vz;
    c.wx = v.wx, c.wy = v.wy, c.wz = v.wz;
    *out = c;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_get_timings(const gyro_world* world, gyro_step_timings* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const gyro::StepTimings& t = world->world->timings();
    *out = gyro_step_timings{t.forces, t.broadphase, t.narrowphase, t.islands, t.solver, t.particles, t.total};
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_get_stats(const gyro_world* world, gyro_step_stats* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const gyro::StepStats& s = world->world->stats();
    *out = gyro_step_stats{s.bodies, s.awake_bodies, s.pairs, s.manifolds, s.contacts, s.colors, s.islands, 0};
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_get_contact_events(const gyro_world* world, gyro_contact_events* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const gyro::ContactEvent *begin = nullptr, *end = nullptr;
    const std::size_t nb = world->world->begin_events(&begin), ne = world->world->end_events(&end);
    GYRO_TRY(check_count_fits(nb, "begin event count"));
    GYRO_TRY(check_count_fits(ne, "end event count"));
    gyro_contact_events c;
    c.begin = nb ? reinterpret_cast<const gyro_contact_event*>(begin) : nullptr;
    c.end = ne ? reinterpret_cast<const gyro_contact_event*>(end) : nullptr;
    c.begin_count = int32_t(nb), c.end_count = int32_t(ne);
    *out = c;
    return Status::ok;
  });
}

}  // extern "C"
