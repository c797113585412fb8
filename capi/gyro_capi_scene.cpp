// The C ABI of scenes: models, transforms and parents, batch raycasts, queries, picking.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_handles.hpp"
#include "capi_support.hpp"
#include "core/validate.hpp"
#include "gyro/scene.hpp"

#include <algorithm>
#include <cstring>
#include <memory>

struct gyro_scene {
  gyro::Scene scene;
};

namespace {

using gyro::Status;
using gyro::capi::check_count;
using gyro::capi::guarded;
using gyro::capi::require;
using gyro::capi::view_of;
using gyro::detail::fail;

static_assert(sizeof(gyro_model_id) == sizeof(gyro::ModelId) && alignof(gyro_model_id) == alignof(gyro::ModelId));
static_assert(sizeof(gyro_transform) == 32 && sizeof(gyro_model_def) == 88 && sizeof(gyro_scene_hit) == 52 &&
              sizeof(gyro_scene_hit_soa) == 8 * sizeof(void*));

gyro::ModelId id_of(gyro_model_id id) { return {id.index, id.generation}; }
gyro_model_id c_id(gyro::ModelId id) { return {id.index, id.generation}; }

gyro::ModelTransform transform_of(const gyro_transform& t) {
  gyro::ModelTransform m;
  m.position = {t.position[0], t.position[1], t.position[2]};
  m.rotation = {t.rotation[0], t.rotation[1], t.rotation[2], t.rotation[3]};
  m.scale = t.scale;
  return m;
}

Status model_def_of(const gyro_model_def& d, gyro::ModelDef& out) {
  if (d.struct_size != sizeof(gyro_model_def))
    return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_model_def_default()", d.struct_size);
  gyro::ModelDef m;
  switch (d.shape) {
    case GYRO_MODEL_SPHERE: m.shape = gyro::ModelShape::sphere; break;
    case GYRO_MODEL_BOX: m.shape = gyro::ModelShape::box; break;
    case GYRO_MODEL_MESH: m.shape = gyro::ModelShape::mesh; break;
    case GYRO_MODEL_PLANE: m.shape = gyro::ModelShape::plane; break;
    default: return fail(Status::invalid_argument, "def->shape = %u is unknown", d.shape);
  }
  m.radius = d.radius;
  m.half_extents = {d.half_extents[0], d.half_extents[1], d.half_extents[2]};
  m.plane = {{d.plane[0], d.plane[1], d.plane[2]}, d.plane[3]};
  if (d.shape == GYRO_MODEL_MESH) {
    GYRO_TRY(require(d.mesh, "def->mesh"));
    m.mesh = d.mesh->mesh;
  }
  m.transform = transform_of(d.transform);
  m.parent = id_of(d.parent);
  out = std::move(m);
  return Status::ok;
}

Status scene_raycast(const gyro_scene* scene, const gyro_ray_soa* rays, const uint32_t* masks, int32_t n,
                     const gyro_scene_hit_soa* hits, bool any) {
  GYRO_TRY(require(scene, "scene"));
  GYRO_TRY(require(rays, "rays"));
  GYRO_TRY(require(hits, "hits"));
  GYRO_TRY(check_count(n, "ray_count"));
  gyro::SceneHitsOut h;
  h.t = hits->t, h.model = reinterpret_cast<gyro::ModelId*>(hits->model), h.primitive = hits->primitive;
  h.nx = hits->nx, h.ny = hits->ny, h.nz = hits->nz, h.u = hits->u, h.v = hits->v;
  gyro::RaysView r = view_of<gyro::RaysView>(*rays);
  r.mask = masks;
  return any ? gyro::raycast_any(scene->scene, r, std::size_t(n), h)
             : gyro::raycast_closest(scene->scene, r, std::size_t(n), h);
}

Status write_ids(const std::vector<gyro::ModelId>& ids, gyro_model_id* out, int32_t capacity, int32_t* count) {
  const std::size_t n = std::min(ids.size(), std::size_t(capacity));
  for (std::size_t i = 0; i < n; ++i) out[i] = c_id(ids[i]);
  *count = int32_t(ids.size());
  return Status::ok;
}

Status check_query_out(const gyro_model_id* out, int32_t capacity, int32_t* count) {
  GYRO_TRY(require(count, "count"));
  GYRO_TRY(check_count(capacity, "capacity"));
  if (capacity > 0) GYRO_TRY(require(out, "out"));
  return Status::ok;
}

}  // namespace

extern "C" {

GYRO_API gyro_model_def gyro_model_def_default(void) {
  gyro_model_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_model_def);
  d.shape = GYRO_MODEL_SPHERE;
  d.radius = 1.0f;
  d.half_extents[0] = d.half_extents[1] = d.half_extents[2] = 1.0f;
  d.plane[1] = 1.0f;
  d.transform.rotation[3] = 1.0f;
  d.transform.scale = 1.0f;
  return d;
}

GYRO_API gyro_status gyro_scene_create(gyro_scene_accel accel, gyro_scene** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    if (accel > GYRO_SCENE_OCTREE) return fail(Status::invalid_argument, "accel = %u is unknown", accel);
    auto s = std::make_unique<gyro_scene>();
    gyro::SceneSettings settings;
    settings.accel = accel == GYRO_SCENE_BVH ? gyro::SceneAccel::bvh : gyro::SceneAccel::octree;
    GYRO_TRY(s->scene.configure(settings));
    *out = s.release();
    return Status::ok;
  });
}

GYRO_API void gyro_scene_destroy(gyro_scene* scene) { delete scene; }

GYRO_API gyro_status gyro_scene_set_ray_prefetch(gyro_scene* scene, gyro_ray_prefetch mode) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    if (mode > GYRO_RAY_PREFETCH_NEVER) return fail(Status::invalid_argument, "mode = %u is unknown", mode);
    gyro::SceneSettings settings = scene->scene.settings();
    settings.ray_prefetch = mode == GYRO_RAY_PREFETCH_ALWAYS  ? gyro::RayPrefetch::always
                            : mode == GYRO_RAY_PREFETCH_NEVER ? gyro::RayPrefetch::never
                                                              : gyro::RayPrefetch::automatic;
    return scene->scene.configure(settings);
  });
}

GYRO_API gyro_status gyro_scene_set_refit(gyro_scene* scene, uint32_t enabled) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    if (enabled > 1) return fail(Status::invalid_argument, "enabled = %u is neither 0 nor 1", enabled);
    gyro::SceneSettings settings = scene->scene.settings();
    settings.refit = enabled == 1;
    return scene->scene.configure(settings);
  });
}

GYRO_API gyro_status gyro_scene_add_model(gyro_scene* scene, const gyro_model_def* def, gyro_model_id* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    gyro::ModelDef m;
    GYRO_TRY(model_def_of(*def, m));
    gyro::ModelId id;
    GYRO_TRY(scene->scene.add_model(m, &id));
    *out = c_id(id);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_scene_remove_model(gyro_scene* scene, gyro_model_id id) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    return scene->scene.remove_model(id_of(id));
  });
}

GYRO_API gyro_status gyro_scene_set_transform(gyro_scene* scene, gyro_model_id id, const gyro_transform* local) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    GYRO_TRY(require(local, "local"));
    return scene->scene.set_transform(id_of(id), transform_of(*local));
  });
}

GYRO_API gyro_status gyro_scene_set_parent(gyro_scene* scene, gyro_model_id id, gyro_model_id parent) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    return scene->scene.set_parent(id_of(id), id_of(parent));
  });
}

GYRO_API gyro_status gyro_scene_set_layers(gyro_scene* scene, gyro_model_id id, uint32_t layers) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    return scene->scene.set_layers(id_of(id), layers);
  });
}

GYRO_API int32_t gyro_scene_model_count(const gyro_scene* scene) {
  return scene ? int32_t(scene->scene.model_count()) : 0;
}

GYRO_API gyro_status gyro_scene_raycast_closest(const gyro_scene* scene, const gyro_ray_soa* rays, int32_t ray_count,
                                                const gyro_scene_hit_soa* hits) {
  return guarded([&] { return scene_raycast(scene, rays, nullptr, ray_count, hits, false); });
}

GYRO_API gyro_status gyro_scene_raycast_any(const gyro_scene* scene, const gyro_ray_soa* rays, int32_t ray_count,
                                            const gyro_scene_hit_soa* hits) {
  return guarded([&] { return scene_raycast(scene, rays, nullptr, ray_count, hits, true); });
}

GYRO_API gyro_status gyro_scene_raycast_closest_masked(const gyro_scene* scene, const gyro_ray_soa* rays,
                                                       const uint32_t* masks, int32_t ray_count,
                                                       const gyro_scene_hit_soa* hits) {
  return guarded([&] { return scene_raycast(scene, rays, masks, ray_count, hits, false); });
}

GYRO_API gyro_status gyro_scene_raycast_any_masked(const gyro_scene* scene, const gyro_ray_soa* rays,
                                                   const uint32_t* masks, int32_t ray_count,
                                                   const gyro_scene_hit_soa* hits) {
  return guarded([&] { return scene_raycast(scene, rays, masks, ray_count, hits, true); });
}

GYRO_API gyro_status gyro_scene_query_masked(const gyro_scene* scene, const gyro_shape_soa* shape, uint32_t mask,
                                             gyro_model_id* out, int32_t capacity, int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    GYRO_TRY(require(shape, "shape"));
    GYRO_TRY(check_query_out(out, capacity, count));
    std::vector<gyro::ModelId> ids;
    auto f3 = [](const float* x, const float* y, const float* z) { return gyro::vec3{x[0], y[0], z[0]}; };
    switch (shape->type) {
      case GYRO_SHAPE_SPHERE: {
        const gyro_sphere_soa& s = shape->as.sphere;
        if (!s.cx || !s.cy || !s.cz || !s.r) return fail(Status::null_argument, "shape->as.sphere has a null array");
        GYRO_TRY(gyro::query(scene->scene, gyro::Sphere{f3(s.cx, s.cy, s.cz), s.r[0]}, ids, mask));
        break;
      }
      case GYRO_SHAPE_AABB: {
        const gyro_aabb_soa& b = shape->as.aabb;
        if (!b.cx || !b.cy || !b.cz || !b.ex || !b.ey || !b.ez)
          return fail(Status::null_argument, "shape->as.aabb has a null array");
        GYRO_TRY(gyro::query(scene->scene, gyro::AABB{f3(b.cx, b.cy, b.cz), f3(b.ex, b.ey, b.ez)}, ids, mask));
        break;
      }
      case GYRO_SHAPE_OBB: {
        const gyro_obb_soa& b = shape->as.obb;
        const float* p[] = {b.cx, b.cy, b.cz, b.ex, b.ey, b.ez, b.u0x, b.u0y, b.u0z, b.u1x, b.u1y, b.u1z, b.u2x, b.u2y, b.u2z};
        for (const float* q : p)
          if (!q) return fail(Status::null_argument, "shape->as.obb has a null array");
        gyro::OBB obb{f3(b.cx, b.cy, b.cz), f3(b.ex, b.ey, b.ez), {}};
        const gyro::vec3 axes[3] = {f3(b.u0x, b.u0y, b.u0z), f3(b.u1x, b.u1y, b.u1z), f3(b.u2x, b.u2y, b.u2z)};
        for (int r = 0; r < 3; ++r) obb.orientation.m[r][0] = axes[r].x, obb.orientation.m[r][1] = axes[r].y, obb.orientation.m[r][2] = axes[r].z;
        GYRO_TRY(gyro::query(scene->scene, obb, ids, mask));
        break;
      }
      default: return fail(Status::invalid_argument, "shape->type = %u: queries take a sphere, AABB or OBB", shape->type);
    }
    return write_ids(ids, out, capacity, count);
  });
}

GYRO_API gyro_status gyro_scene_query(const gyro_scene* scene, const gyro_shape_soa* shape, gyro_model_id* out,
                                      int32_t capacity, int32_t* count) {
  return gyro_scene_query_masked(scene, shape, 0xFFFFFFFFu, out, capacity, count);
}

GYRO_API gyro_status gyro_scene_query_frustum_masked(const gyro_scene* scene, const gyro_frustum* frustum, uint32_t mask,
                                                     gyro_model_id* out, int32_t capacity, int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    GYRO_TRY(require(frustum, "frustum"));
    GYRO_TRY(check_query_out(out, capacity, count));
    const gyro::Frustum f = gyro::capi::frustum_of(*frustum);
    std::vector<gyro::ModelId> ids;
    GYRO_TRY(gyro::query(scene->scene, f, ids, mask));
    return write_ids(ids, out, capacity, count);
  });
}

GYRO_API gyro_status gyro_scene_query_frustum(const gyro_scene* scene, const gyro_frustum* frustum, gyro_model_id* out,
                                              int32_t capacity, int32_t* count) {
  return gyro_scene_query_frustum_masked(scene, frustum, 0xFFFFFFFFu, out, capacity, count);
}

GYRO_API gyro_status gyro_scene_pick_masked(const gyro_scene* scene, const gyro_camera* camera, float screen_x,
                                            float screen_y, float viewport_width, float viewport_height, uint32_t mask,
                                            gyro_scene_hit* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(scene, "scene"));
    GYRO_TRY(require(out, "out"));
    gyro::Camera cam;
    GYRO_TRY(gyro::capi::camera_of(camera, cam));
    gyro::SceneHit h;
    GYRO_TRY(gyro::pick(scene->scene, cam, {screen_x, screen_y}, {viewport_width, viewport_height}, &h, mask));
    gyro_scene_hit c;
    std::memset(&c, 0, sizeof c);
    if (h.hit.hit) {
      c.hit = 1, c.t = h.hit.t;
      c.point[0] = h.hit.point.x, c.point[1] = h.hit.point.y, c.point[2] = h.hit.point.z;
      c.normal[0] = h.hit.normal.x, c.normal[1] = h.hit.normal.y, c.normal[2] = h.hit.normal.z;
      c.model = c_id(h.model), c.primitive = int32_t(h.primitive), c.u = h.u, c.v = h.v;
    }
    *out = c;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_scene_pick(const gyro_scene* scene, const gyro_camera* camera, float screen_x, float screen_y,
                                     float viewport_width, float viewport_height, gyro_scene_hit* out) {
  return gyro_scene_pick_masked(scene, camera, screen_x, screen_y, viewport_width, viewport_height, 0xFFFFFFFFu, out);
}

}  // extern "C"
