// The C ABI of springs, cloth and soft bodies in a world: definitions, settings, family
// constants, masses, pins, particle state, joints, zero-copy views, stats and hashes, over
// gyro/soft_body.hpp and the world's soft-body calls (gyro/world.hpp).
//
// Every entry point checks everything it can before touching the world (NULL, struct_size,
// enum values, booleans, NaN/Inf, ranges, particle indices, stale ids), so a bad call
// changes nothing whatever the C++ layer would do with it, and the status does not depend
// on the order in which the C++ layer checks.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_support.hpp"
#include "capi_recorder.hpp"
#include "capi_world.hpp"
#include "core/validate.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/world.hpp"

#include <climits>
#include <cstddef>
#include <cstring>
#include <utility>
#include <type_traits>
#include <vector>

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
using gyro::detail::is_nan;

// Plain-data layouts every binding relies on.
static_assert(sizeof(gyro_soft_body_id) == 8 && sizeof(gyro_soft_body_id) == sizeof(gyro::SoftBodyId));
static_assert(sizeof(gyro_spring_constants) == 8 && sizeof(gyro_soft_settings) == 48 &&
              sizeof(gyro_cloth_def) == 68 && sizeof(gyro_soft_cube_def) == 48 &&
              sizeof(gyro_soft_body_stats) == 64);
static_assert(sizeof(void*) != 8 || (sizeof(gyro_soft_mesh_def) == 72 && sizeof(gyro_soft_body_view) == 72));
static_assert(sizeof(gyro_soft_model) == 4 && sizeof(gyro_spring_family) == 4 &&
              sizeof(gyro_collision_response) == 4 && sizeof(gyro_step_stage) == 4);
static_assert(uint32_t(gyro::SoftModel::xpbd) == GYRO_SOFT_MODEL_XPBD &&
              uint32_t(gyro::SoftModel::springs) == GYRO_SOFT_MODEL_SPRINGS);
static_assert(uint32_t(gyro::SpringFamily::structural) == GYRO_SPRING_STRUCTURAL &&
              uint32_t(gyro::SpringFamily::shear) == GYRO_SPRING_SHEAR &&
              uint32_t(gyro::SpringFamily::bend) == GYRO_SPRING_BEND &&
              uint32_t(gyro::SpringFamily::radial) == GYRO_SPRING_RADIAL &&
              uint32_t(gyro::SpringFamily::joint) == GYRO_SPRING_JOINT &&
              gyro::kSpringFamilyCount == GYRO_SPRING_JOINT + 1);
static_assert(uint32_t(gyro::CollisionResponse::projection) == GYRO_COLLISION_PROJECTION &&
              uint32_t(gyro::CollisionResponse::penalty) == GYRO_COLLISION_PENALTY);

/// The largest grid or mesh the C layer accepts: 2^24 particles (counts, indices and the
/// view's int32_t counts stay far from overflow).
constexpr int64_t kMaxParticles = int64_t(1) << 24;

gyro::SoftBodyId id_of(gyro_soft_body_id id) { return {id.index, id.generation}; }
gyro_soft_body_id c_id(gyro::SoftBodyId id) { return {id.index, id.generation}; }
gyro::SpringConstants constants_of(gyro_spring_constants c) { return {c.stiffness, c.damping}; }
gyro_spring_constants c_constants(const gyro::SpringConstants& c) { return {c.stiffness, c.damping}; }

/// Finite and > 0 (sizes, masses).
Status check_positive(float v, const char* name) {
  GYRO_TRY(check_finite(v, name));
  return v > 0.0f ? Status::ok : fail(Status::invalid_argument, "%s = %g must be > 0", name, double(v));
}
/// Finite and >= 0.
Status check_non_negative(float v, const char* name) {
  GYRO_TRY(check_finite(v, name));
  return v >= 0.0f ? Status::ok : fail(Status::invalid_argument, "%s = %g must be >= 0", name, double(v));
}

/// Stiffness > 0 or +infinity (NaN: non_finite; zero, negative or -infinity: invalid);
/// damping finite and >= 0.
Status check_constants(const gyro_spring_constants& c, const char* name) {
  if (is_nan(c.stiffness)) return fail(Status::non_finite, "%s.stiffness is NaN", name);
  if (!(c.stiffness > 0.0f))
    return fail(Status::invalid_argument, "%s.stiffness = %g must be > 0", name, double(c.stiffness));
  if (!is_finite(c.damping)) return fail(Status::non_finite, "%s.damping = %g is not finite", name, double(c.damping));
  if (!(c.damping >= 0.0f))
    return fail(Status::invalid_argument, "%s.damping = %g must be >= 0", name, double(c.damping));
  return Status::ok;
}

Status require_world(const gyro_world* w) { return require(w, "world"); }

// The world and a live soft body: every per-body call starts here, so a stale id never
// reaches the C++ layer.
Status stale(gyro_soft_body_id id) {
  return fail(Status::stale_id, "soft body {%u, %u} is not a live soft body of this world", id.index, id.generation);
}
Status require_soft(gyro_world* w, gyro_soft_body_id id, gyro::SoftBody** out) {
  GYRO_TRY(require_world(w));
  gyro::SoftBody* body = w->world->is_valid(id_of(id)) ? w->world->soft_body(id_of(id)) : nullptr;
  if (!body) return stale(id);
  *out = body;
  return Status::ok;
}
Status require_soft(const gyro_world* w, gyro_soft_body_id id, const gyro::SoftBody** out) {
  GYRO_TRY(require_world(w));
  const gyro::World& world = *w->world;
  const gyro::SoftBody* body = world.is_valid(id_of(id)) ? world.soft_body(id_of(id)) : nullptr;
  if (!body) return stale(id);
  *out = body;
  return Status::ok;
}

Status check_particle(const gyro::SoftBody& b, uint32_t index, const char* name) {
  const std::size_t n = b.particle_count();
  if (index < n) return Status::ok;
  return fail(Status::invalid_argument, "%s = %u is out of range (the body has %zu particles)", name, index, n);
}

/// A per-particle call: the soft body and the particle checked (stale id, index range), then
/// fn(body). A const world gives fn a const body.
template <class W, class F> gyro_status on_particle(W* world, gyro_soft_body_id id, uint32_t particle, F&& fn) {
  return guarded([&]() -> Status {
    std::conditional_t<std::is_const_v<W>, const gyro::SoftBody, gyro::SoftBody>* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(check_particle(*b, particle, "particle"));
    return fn(*b);
  });
}

Status check_family(gyro_spring_family family) {
  return family <= GYRO_SPRING_JOINT ? Status::ok
                                     : fail(Status::invalid_argument, "family = %u is unknown", family);
}

Status check_count_fits(std::size_t n, const char* name) {
  return n <= std::size_t(INT32_MAX) ? Status::ok
                                     : fail(Status::invalid_count, "%s = %zu does not fit an int32_t", name, n);
}

Status settings_of(const gyro_soft_settings& s, gyro::SoftSettings& out) {
  if (s.struct_size != sizeof(gyro_soft_settings))
    return fail(Status::invalid_argument, "settings->struct_size = %u: start from gyro_soft_settings_default()",
                s.struct_size);
  if (s.model > GYRO_SOFT_MODEL_SPRINGS) return fail(Status::invalid_argument, "settings->model = %u is unknown", s.model);
  if (s.response > GYRO_COLLISION_PENALTY)
    return fail(Status::invalid_argument, "settings->response = %u is unknown", s.response);
  if (s.substeps < 1 || s.substeps > 256)
    return fail(Status::invalid_argument, "settings->substeps = %u is outside 1..256", s.substeps);
  if (s.iterations < 1 || s.iterations > 64)
    return fail(Status::invalid_argument, "settings->iterations = %u is outside 1..64", s.iterations);
  GYRO_TRY(check_finite(s.gravity, "settings->gravity"));
  GYRO_TRY(check_non_negative(s.damping, "settings->damping"));
  GYRO_TRY(check_non_negative(s.thickness, "settings->thickness"));
  GYRO_TRY(check_non_negative(s.friction, "settings->friction"));
  if (s.friction > 1.0f)
    return fail(Status::invalid_argument, "settings->friction = %g is outside [0, 1]", double(s.friction));
  GYRO_TRY(check_positive(s.penalty_stiffness, "settings->penalty_stiffness"));
  gyro::SoftSettings g;
  g.model = static_cast<gyro::SoftModel>(s.model);
  g.substeps = s.substeps, g.iterations = s.iterations;
  g.gravity = v3(s.gravity);
  g.damping = s.damping, g.thickness = s.thickness, g.friction = s.friction;
  g.response = static_cast<gyro::CollisionResponse>(s.response);
  g.penalty_stiffness = s.penalty_stiffness;
  out = g;
  return Status::ok;
}

gyro_soft_settings c_settings(const gyro::SoftSettings& g) {
  gyro_soft_settings s;
  std::memset(&s, 0, sizeof s);
  s.struct_size = sizeof(gyro_soft_settings);
  s.model = static_cast<gyro_soft_model>(g.model);
  s.substeps = g.substeps, s.iterations = g.iterations;
  s.gravity = c_v3(g.gravity);
  s.damping = g.damping, s.thickness = g.thickness, s.friction = g.friction;
  s.response = static_cast<gyro_collision_response>(g.response);
  s.penalty_stiffness = g.penalty_stiffness;
  return s;
}

/// The springs model is explicit: an infinitely stiff family cannot run in it.
Status check_model_constants(gyro::SoftModel model, const gyro::SoftBody& b, int skip_family,
                             const gyro::SpringConstants* extra) {
  if (model != gyro::SoftModel::springs) return Status::ok;
  if (extra && !is_finite(extra->stiffness))
    return fail(Status::invalid_argument, "an infinite stiffness needs the XPBD model (the springs model is explicit)");
  for (uint32_t f = 0; f < gyro::kSpringFamilyCount; ++f) {
    if (int(f) == skip_family) continue;
    if (!is_finite(b.family(static_cast<gyro::SpringFamily>(f)).stiffness))
      return fail(Status::invalid_argument,
                  "family %u has an infinite stiffness: the springs model needs finite ones (set them first)", f);
  }
  return Status::ok;
}

Status cloth_def_of(const gyro_cloth_def& d, gyro::ClothDef& out) {
  if (d.struct_size != sizeof(gyro_cloth_def))
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_cloth_def_default()", d.struct_size);
  if (d.nx < 2 || d.nz < 2)
    return fail(Status::invalid_count, "def->nx = %d, def->nz = %d: a cloth needs at least 2 x 2 particles", d.nx,
                d.nz);
  if (int64_t(d.nx) * int64_t(d.nz) > kMaxParticles)
    return fail(Status::invalid_count, "def->nx * def->nz = %lld is over the limit of %lld particles",
                static_cast<long long>(int64_t(d.nx) * d.nz), static_cast<long long>(kMaxParticles));
  GYRO_TRY(check_positive(d.size_x, "def->size_x"));
  GYRO_TRY(check_positive(d.size_z, "def->size_z"));
  GYRO_TRY(check_finite(d.center, "def->center"));
  GYRO_TRY(check_positive(d.particle_mass, "def->particle_mass"));
  GYRO_TRY(check_bool(d.both_diagonals, "def->both_diagonals"));
  GYRO_TRY(check_bool(d.bend, "def->bend"));
  GYRO_TRY(check_constants(d.structural, "def->structural"));
  GYRO_TRY(check_constants(d.shear, "def->shear"));
  GYRO_TRY(check_constants(d.bend_constants, "def->bend_constants"));
  gyro::ClothDef c;
  c.nx = uint32_t(d.nx), c.nz = uint32_t(d.nz);
  c.size_x = d.size_x, c.size_z = d.size_z;
  c.center = v3(d.center);
  c.particle_mass = d.particle_mass;
  c.both_diagonals = d.both_diagonals != 0, c.bend = d.bend != 0;
  c.structural = constants_of(d.structural), c.shear = constants_of(d.shear);
  c.bend_constants = constants_of(d.bend_constants);
  out = c;
  return Status::ok;
}

Status cube_def_of(const gyro_soft_cube_def& d, gyro::SoftCubeDef& out) {
  if (d.struct_size != sizeof(gyro_soft_cube_def))
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_soft_cube_def_default()",
                d.struct_size);
  GYRO_TRY(check_finite(d.center, "def->center"));
  GYRO_TRY(check_positive(d.half_extent, "def->half_extent"));
  GYRO_TRY(check_positive(d.particle_mass, "def->particle_mass"));
  GYRO_TRY(check_constants(d.structural, "def->structural"));
  GYRO_TRY(check_constants(d.shear, "def->shear"));
  GYRO_TRY(check_constants(d.bend, "def->bend"));
  gyro::SoftCubeDef c;
  c.center = v3(d.center);
  c.half_extent = d.half_extent, c.particle_mass = d.particle_mass;
  c.structural = constants_of(d.structural), c.shear = constants_of(d.shear), c.bend = constants_of(d.bend);
  out = c;
  return Status::ok;
}

/// The C++ definition over `vertices` (x, y, z per vertex, filled here).
Status mesh_def_of(const gyro_soft_mesh_def& d, gyro::SoftMeshDef& out, std::vector<float>& vertices) {
  if (d.struct_size != sizeof(gyro_soft_mesh_def))
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_soft_mesh_def_default()",
                d.struct_size);
  GYRO_TRY(gyro::capi::check_count(d.vertex_count, "def->vertex_count"));
  GYRO_TRY(gyro::capi::check_count(d.triangle_count, "def->triangle_count"));
  if (d.vertex_count < 4 || d.triangle_count < 4)
    return fail(Status::invalid_count,
                "def->vertex_count = %d, def->triangle_count = %d: a closed mesh needs at least 4 of each",
                d.vertex_count, d.triangle_count);
  if (int64_t(d.vertex_count) + 1 > kMaxParticles || int64_t(d.triangle_count) > kMaxParticles)
    return fail(Status::invalid_count, "def->vertex_count = %d, def->triangle_count = %d: over the limit of %lld",
                d.vertex_count, d.triangle_count, static_cast<long long>(kMaxParticles));
  GYRO_TRY(require(d.x, "def->x"));
  GYRO_TRY(require(d.y, "def->y"));
  GYRO_TRY(require(d.z, "def->z"));
  GYRO_TRY(require(d.indices, "def->indices"));
  const std::size_t nv = std::size_t(d.vertex_count), nt = std::size_t(d.triangle_count);
  GYRO_TRY(gyro::detail::require_finite(d.x, nv, "def->x"));
  GYRO_TRY(gyro::detail::require_finite(d.y, nv, "def->y"));
  GYRO_TRY(gyro::detail::require_finite(d.z, nv, "def->z"));
  for (std::size_t t = 0; t < nt; ++t) {
    const uint32_t* tri = d.indices + 3 * t;
    for (int k = 0; k < 3; ++k)
      if (tri[k] >= nv)
        return fail(Status::invalid_argument, "def->indices[%zu] = %u is out of range (%d vertices)", 3 * t + k,
                    tri[k], d.vertex_count);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      return fail(Status::invalid_argument, "triangle %zu repeats a vertex (%u, %u, %u)", t, tri[0], tri[1], tri[2]);
  }
  GYRO_TRY(check_positive(d.particle_mass, "def->particle_mass"));
  GYRO_TRY(check_constants(d.structural, "def->structural"));
  GYRO_TRY(check_constants(d.bend, "def->bend"));
  GYRO_TRY(check_constants(d.radial, "def->radial"));
  vertices.resize(3 * nv);
  for (std::size_t i = 0; i < nv; ++i)
    vertices[3 * i] = d.x[i], vertices[3 * i + 1] = d.y[i], vertices[3 * i + 2] = d.z[i];
  gyro::SoftMeshDef m;
  m.vertices = vertices.data();
  m.vertex_count = uint32_t(nv);
  m.indices = d.indices;
  m.triangle_count = uint32_t(nt);
  m.particle_mass = d.particle_mass;
  m.structural = constants_of(d.structural), m.bend = constants_of(d.bend), m.radial = constants_of(d.radial);
  out = m;
  return Status::ok;
}

/// Adds a built body to the world; *out is written only on success.
Status add_to_world(gyro_world* world, const gyro::SoftBody& body, gyro_soft_body_id* out) {
  gyro::SoftBodyId id;
  GYRO_TRY(world->world->add_soft_body(body, &id));
  if (id.is_null()) return fail(Status::internal, "World::add_soft_body returned ok and a null id");
  *out = c_id(id);
  return Status::ok;
}

}  // namespace

extern "C" {

GYRO_API gyro_soft_settings gyro_soft_settings_default(void) { return c_settings(gyro::SoftSettings{}); }

GYRO_API gyro_cloth_def gyro_cloth_def_default(void) {
  const gyro::ClothDef c;
  gyro_cloth_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_cloth_def);
  d.nx = int32_t(c.nx), d.nz = int32_t(c.nz);
  d.size_x = c.size_x, d.size_z = c.size_z;
  d.center = c_v3(c.center);
  d.particle_mass = c.particle_mass;
  d.both_diagonals = c.both_diagonals, d.bend = c.bend;
  d.structural = c_constants(c.structural), d.shear = c_constants(c.shear);
  d.bend_constants = c_constants(c.bend_constants);
  return d;
}

GYRO_API gyro_soft_cube_def gyro_soft_cube_def_default(void) {
  const gyro::SoftCubeDef c;
  gyro_soft_cube_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_soft_cube_def);
  d.center = c_v3(c.center);
  d.half_extent = c.half_extent, d.particle_mass = c.particle_mass;
  d.structural = c_constants(c.structural), d.shear = c_constants(c.shear), d.bend = c_constants(c.bend);
  return d;
}

GYRO_API gyro_soft_mesh_def gyro_soft_mesh_def_default(void) {
  const gyro::SoftMeshDef c;
  gyro_soft_mesh_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_soft_mesh_def);
  d.particle_mass = c.particle_mass;
  d.structural = c_constants(c.structural), d.bend = c_constants(c.bend), d.radial = c_constants(c.radial);
  return d;
}

GYRO_API gyro_status gyro_world_create_cloth(gyro_world* world, const gyro_cloth_def* def, gyro_soft_body_id* out) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro::ClothDef c;
    GYRO_TRY(cloth_def_of(*def, c));
    gyro::SoftBody body;
    GYRO_TRY(gyro::SoftBody::make_cloth(c, &body));
    return add_to_world(world, body, out);
  });
  return gyro::capi::rec::recorded<&gyro_world_create_cloth>(st, world, def, out);
}

GYRO_API gyro_status gyro_world_create_soft_cube(gyro_world* world, const gyro_soft_cube_def* def,
                                                 gyro_soft_body_id* out) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro::SoftCubeDef c;
    GYRO_TRY(cube_def_of(*def, c));
    gyro::SoftBody body;
    GYRO_TRY(gyro::SoftBody::make_cube(c, &body));
    return add_to_world(world, body, out);
  });
  return gyro::capi::rec::recorded<&gyro_world_create_soft_cube>(st, world, def, out);
}

GYRO_API gyro_status gyro_world_create_soft_mesh(gyro_world* world, const gyro_soft_mesh_def* def,
                                                 gyro_soft_body_id* out) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro::SoftMeshDef m;
    std::vector<float> vertices;
    GYRO_TRY(mesh_def_of(*def, m, vertices));
    gyro::SoftBody body;
    GYRO_TRY(gyro::SoftBody::make_from_mesh(m, &body));
    return add_to_world(world, body, out);
  });
  return gyro::capi::rec::recorded<&gyro_world_create_soft_mesh>(st, world, def, out);
}

GYRO_API gyro_status gyro_world_destroy_soft_body(gyro_world* world, gyro_soft_body_id id) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    return world->world->destroy_soft_body(id_of(id));
  });
  return gyro::capi::rec::recorded<&gyro_world_destroy_soft_body>(st, world, id);
}

GYRO_API uint32_t gyro_soft_body_is_valid(const gyro_world* world, gyro_soft_body_id id) {
  return world && world->world->is_valid(id_of(id)) ? 1u : 0u;
}

GYRO_API gyro_status gyro_world_soft_body_count(const gyro_world* world, int32_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out, "out"));
    const std::size_t n = world->world->soft_body_count();
    GYRO_TRY(check_count_fits(n, "soft_body_count"));
    *out = int32_t(n);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_set_settings(gyro_world* world, gyro_soft_body_id id,
                                                 const gyro_soft_settings* settings) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(settings, "settings"));
    gyro::SoftSettings s;
    GYRO_TRY(settings_of(*settings, s));
    GYRO_TRY(check_model_constants(s.model, *b, -1, nullptr));
    return b->set_settings(s);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_settings>(st, world, id, settings);
}

GYRO_API gyro_status gyro_soft_body_get_settings(const gyro_world* world, gyro_soft_body_id id,
                                                 gyro_soft_settings* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(out, "out"));
    if (out->struct_size != sizeof(gyro_soft_settings))
      return fail(Status::invalid_argument, "out->struct_size = %u: start from gyro_soft_settings_default()",
                  out->struct_size);
    *out = c_settings(b->settings());
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_set_family(gyro_world* world, gyro_soft_body_id id, gyro_spring_family family,
                                               const gyro_spring_constants* constants) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(check_family(family));
    GYRO_TRY(require(constants, "constants"));
    GYRO_TRY(check_constants(*constants, "constants"));
    const gyro::SpringConstants c = constants_of(*constants);
    GYRO_TRY(check_model_constants(b->settings().model, *b, int(family), &c));
    return b->set_family(static_cast<gyro::SpringFamily>(family), c);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_family>(st, world, id, family, constants);
}

GYRO_API gyro_status gyro_soft_body_get_family(const gyro_world* world, gyro_soft_body_id id,
                                               gyro_spring_family family, gyro_spring_constants* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(check_family(family));
    GYRO_TRY(require(out, "out"));
    *out = c_constants(b->family(static_cast<gyro::SpringFamily>(family)));
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_set_mass(gyro_world* world, gyro_soft_body_id id, float mass) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(check_positive(mass, "mass"));
    return b->set_mass(mass);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_mass>(st, world, id, mass);
}

GYRO_API gyro_status gyro_soft_body_set_particle_mass(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                      float mass) {
  const gyro_status st = on_particle(world, id, particle, [&](gyro::SoftBody& b) -> Status {
    GYRO_TRY(check_positive(mass, "mass"));
    return b.set_particle_mass(particle, mass);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_particle_mass>(st, world, id, particle, mass);
}

GYRO_API gyro_status gyro_soft_body_pin(gyro_world* world, gyro_soft_body_id id, uint32_t particle) {
  const gyro_status st = on_particle(world, id, particle, [&](gyro::SoftBody& b) { return b.pin(particle); });
  return gyro::capi::rec::recorded<&gyro_soft_body_pin>(st, world, id, particle);
}

GYRO_API gyro_status gyro_soft_body_unpin(gyro_world* world, gyro_soft_body_id id, uint32_t particle) {
  const gyro_status st = on_particle(world, id, particle, [&](gyro::SoftBody& b) { return b.unpin(particle); });
  return gyro::capi::rec::recorded<&gyro_soft_body_unpin>(st, world, id, particle);
}

GYRO_API gyro_status gyro_soft_body_is_pinned(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                              uint32_t* out) {
  return on_particle(world, id, particle, [&](const gyro::SoftBody& b) -> Status {
    GYRO_TRY(require(out, "out"));
    bool pinned = false;
    GYRO_TRY(b.is_pinned(particle, &pinned));
    *out = pinned ? 1u : 0u;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_get_position(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3* out) {
  return on_particle(world, id, particle, [&](const gyro::SoftBody& b) -> Status {
    GYRO_TRY(require(out, "out"));
    gyro::vec3 p;
    GYRO_TRY(b.get_position(particle, &p));
    *out = c_v3(p);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_set_position(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3 position) {
  const gyro_status st = on_particle(world, id, particle, [&](gyro::SoftBody& b) -> Status {
    GYRO_TRY(check_finite(position, "position"));
    return b.set_position(particle, v3(position));
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_position>(st, world, id, particle, position);
}

GYRO_API gyro_status gyro_soft_body_get_velocity(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3* out) {
  return on_particle(world, id, particle, [&](const gyro::SoftBody& b) -> Status {
    GYRO_TRY(require(out, "out"));
    gyro::vec3 v;
    GYRO_TRY(b.get_velocity(particle, &v));
    *out = c_v3(v);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_set_velocity(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3 velocity) {
  const gyro_status st = on_particle(world, id, particle, [&](gyro::SoftBody& b) -> Status {
    GYRO_TRY(check_finite(velocity, "velocity"));
    return b.set_velocity(particle, v3(velocity));
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_set_velocity>(st, world, id, particle, velocity);
}

GYRO_API gyro_status gyro_soft_body_cloth_index(const gyro_world* world, gyro_soft_body_id id, uint32_t ix,
                                                uint32_t iz, uint32_t* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(out, "out"));
    uint32_t index = 0;
    GYRO_TRY(b->cloth_index(ix, iz, &index));
    if (index >= b->particle_count())
      return fail(Status::internal, "cloth_index(%u, %u) = %u is not a particle", ix, iz, index);
    *out = index;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_add_distance_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a,
                                                       uint32_t b, float rest_length, uint32_t* out_joint) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* body = nullptr;
    GYRO_TRY(require_soft(world, id, &body));
    GYRO_TRY(check_particle(*body, a, "a"));
    GYRO_TRY(check_particle(*body, b, "b"));
    if (a == b) return fail(Status::invalid_argument, "a joint joins two different particles (a = b = %u)", a);
    GYRO_TRY(check_finite(rest_length, "rest_length"));
    gyro::ParticleJointDef def;
    def.a = a, def.b = b;
    def.rest_length = rest_length < 0.0f ? -1.0f : rest_length;
    uint32_t joint = 0;
    GYRO_TRY(body->add_joint(def, &joint));
    if (out_joint) *out_joint = joint;
    return Status::ok;
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_add_distance_joint>(st, world, id, a, b, rest_length, out_joint);
}

GYRO_API gyro_status gyro_soft_body_add_ball_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a, uint32_t b) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* body = nullptr;
    GYRO_TRY(require_soft(world, id, &body));
    GYRO_TRY(check_particle(*body, a, "a"));
    GYRO_TRY(check_particle(*body, b, "b"));
    if (a == b) return fail(Status::invalid_argument, "a joint joins two different particles (a = b = %u)", a);
    return body->add_ball_joint(a, b);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_add_ball_joint>(st, world, id, a, b);
}

GYRO_API gyro_status gyro_soft_body_add_hinge_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a0,
                                                    uint32_t b0, uint32_t a1, uint32_t b1) {
  const gyro_status st = guarded([&]() -> Status {
    gyro::SoftBody* body = nullptr;
    GYRO_TRY(require_soft(world, id, &body));
    GYRO_TRY(check_particle(*body, a0, "a0"));
    GYRO_TRY(check_particle(*body, b0, "b0"));
    GYRO_TRY(check_particle(*body, a1, "a1"));
    GYRO_TRY(check_particle(*body, b1, "b1"));
    if (a0 == b0 || a1 == b1)
      return fail(Status::invalid_argument, "a hinge joins two different particles at each end (%u-%u, %u-%u)", a0, b0,
                  a1, b1);
    if (a0 == a1 || b0 == b1)
      return fail(Status::invalid_argument, "a hinge's axis needs two different particles on each side (%u-%u, %u-%u)",
                  a0, a1, b0, b1);
    return body->add_hinge_joint(a0, b0, a1, b1);
  });
  return gyro::capi::rec::recorded<&gyro_soft_body_add_hinge_joint>(st, world, id, a0, b0, a1, b1);
}

GYRO_API gyro_status gyro_soft_body_get_view(const gyro_world* world, gyro_soft_body_id id, gyro_soft_body_view* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(out, "out"));
    const gyro::SoftView v = b->view();
    GYRO_TRY(check_count_fits(v.count, "particle count"));
    GYRO_TRY(check_count_fits(v.triangle_count, "triangle count"));
    gyro_soft_body_view c;
    std::memset(&c, 0, sizeof c);
    c.count = int32_t(v.count);
    c.triangle_count = int32_t(v.triangle_count);
    c.px = v.px, c.py = v.py, c.pz = v.pz;
    c.vx = v.vx, c.vy = v.vy, c.vz = v.vz;
    c.inverse_mass = v.inverse_mass;
    c.triangles = v.triangle_count ? v.triangles : nullptr;
    *out = c;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_get_stats(const gyro_world* world, gyro_soft_body_id id,
                                              gyro_soft_body_stats* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(out, "out"));
    const gyro::SoftStats s = b->stats();
    GYRO_TRY(check_count_fits(s.particles, "particles"));
    GYRO_TRY(check_count_fits(s.springs, "springs"));
    GYRO_TRY(check_count_fits(s.colors, "colors"));
    gyro_soft_body_stats c;
    std::memset(&c, 0, sizeof c);
    c.particles = int32_t(s.particles), c.springs = int32_t(s.springs), c.colors = int32_t(s.colors);
    c.max_strain = s.max_strain, c.mean_strain = s.mean_strain;
    c.kinetic_energy = s.kinetic_energy, c.potential_energy = s.potential_energy;
    c.elastic_energy = s.elastic_energy, c.min_y = s.min_y;
    *out = c;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_soft_body_hash(const gyro_world* world, gyro_soft_body_id id, uint64_t* out) {
  return guarded([&]() -> Status {
    const gyro::SoftBody* b = nullptr;
    GYRO_TRY(require_soft(world, id, &b));
    GYRO_TRY(require(out, "out"));
    *out = b->hash();
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_get_stage_time(const gyro_world* world, gyro_step_stage stage, double* out_ms) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_world(world));
    GYRO_TRY(require(out_ms, "out_ms"));
    const gyro::StepTimings& t = world->world->timings();
    double ms = 0.0;
    switch (stage) {
      case GYRO_STAGE_FORCES: ms = t.forces; break;
      case GYRO_STAGE_BROADPHASE: ms = t.broadphase; break;
      case GYRO_STAGE_NARROWPHASE: ms = t.narrowphase; break;
      case GYRO_STAGE_ISLANDS: ms = t.islands; break;
      case GYRO_STAGE_SOLVER: ms = t.solver; break;
      case GYRO_STAGE_PARTICLES: ms = t.particles; break;
      case GYRO_STAGE_TOTAL: ms = t.total; break;
      case GYRO_STAGE_SOFT_BODIES: ms = t.soft_bodies; break;
      default: return fail(Status::invalid_argument, "stage = %u is unknown", stage);
    }
    *out_ms = ms;
    return Status::ok;
  });
}

}  // extern "C"
