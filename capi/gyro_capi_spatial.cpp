// The C ABI of the spatial module: meshes with their BVH, camera, frustum culling.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_handles.hpp"
#include "capi_support.hpp"
#include "core/validate.hpp"
#include "gyro/camera.hpp"
#include "gyro/frustum.hpp"
#include "gyro/obj.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cstring>
#include <memory>

namespace {

using gyro::Status;
using gyro::capi::camera_of;
using gyro::capi::check_count;
using gyro::capi::guarded;
using gyro::capi::require;
using gyro::capi::view_of;
using gyro::detail::fail;

static_assert(sizeof(gyro_mesh_def) == 48 && sizeof(gyro_mesh_info) == 48 && sizeof(gyro_frustum) == 96 &&
              sizeof(gyro_camera) == 76);
static_assert(GYRO_RAY_INVALID == gyro::kRayInvalid);

Status make_mesh(const gyro::MeshData& data, gyro_mesh** out) {
  auto mesh = std::make_shared<gyro::TriangleMesh>();
  GYRO_TRY(gyro::TriangleMesh::create(data, *mesh));
  *out = new gyro_mesh{std::move(mesh)};
  return Status::ok;
}

gyro_camera c_camera(const gyro::Camera& cam) {
  gyro_camera c;
  c.position[0] = cam.position.x, c.position[1] = cam.position.y, c.position[2] = cam.position.z;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c.orientation[3 * r + k] = cam.orientation.m[r][k];
  c.mode = cam.mode == gyro::ProjectionMode::perspective ? GYRO_PROJECTION_PERSPECTIVE : GYRO_PROJECTION_ORTHOGRAPHIC;
  c.fov_y = cam.fov_y, c.aspect = cam.aspect, c.width = cam.width, c.height = cam.height;
  c.z_near = cam.z_near, c.z_far = cam.z_far;
  return c;
}

void c_frustum(const gyro::Frustum& f, gyro_frustum* out) {
  for (int p = 0; p < 6; ++p) {
    out->planes[p][0] = f.planes[p].normal.x, out->planes[p][1] = f.planes[p].normal.y;
    out->planes[p][2] = f.planes[p].normal.z, out->planes[p][3] = f.planes[p].distance;
  }
}

Status mesh_raycast(const gyro_mesh* mesh, const gyro_ray_soa* rays, int32_t ray_count, const gyro_hit_soa* hits,
                    bool any) {
  GYRO_TRY(require(mesh, "mesh"));
  GYRO_TRY(require(rays, "rays"));
  GYRO_TRY(require(hits, "hits"));
  GYRO_TRY(check_count(ray_count, "ray_count"));
  const auto r = view_of<gyro::RaysView>(*rays);
  const auto h = view_of<gyro::HitsOut>(*hits);
  const auto n = static_cast<std::size_t>(ray_count);
  return any ? gyro::raycast_any(*mesh->mesh, r, n, h) : gyro::raycast_closest(*mesh->mesh, r, n, h);
}

}  // namespace

namespace gyro::capi {
Status camera_of(const gyro_camera* c, Camera& out) {
  GYRO_TRY(require(c, "camera"));
  gyro::Camera cam;
  cam.position = {c->position[0], c->position[1], c->position[2]};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) cam.orientation.m[r][k] = c->orientation[3 * r + k];
  if (c->mode > GYRO_PROJECTION_ORTHOGRAPHIC) return detail::fail(Status::invalid_argument, "camera->mode = %u is unknown", c->mode);
  cam.mode = c->mode == GYRO_PROJECTION_PERSPECTIVE ? gyro::ProjectionMode::perspective : gyro::ProjectionMode::orthographic;
  cam.fov_y = c->fov_y, cam.aspect = c->aspect, cam.width = c->width, cam.height = c->height;
  cam.z_near = c->z_near, cam.z_far = c->z_far;
  GYRO_TRY(gyro::check_camera(cam));
  out = cam;
  return Status::ok;
}

}  // namespace gyro::capi

extern "C" {

GYRO_API gyro_mesh_def gyro_mesh_def_default(void) {
  gyro_mesh_def d;
  std::memset(&d, 0, sizeof d);
  d.struct_size = sizeof(gyro_mesh_def);
  return d;
}

GYRO_API gyro_status gyro_mesh_create(const gyro_mesh_def* def, gyro_mesh** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(def, "def"));
    GYRO_TRY(require(out, "out"));
    if (def->struct_size != sizeof(gyro_mesh_def))
      return fail(Status::invalid_argument, "def->struct_size = %u: start from gyro_mesh_def_default()", def->struct_size);
    if (def->reserved != 0) return fail(Status::invalid_argument, "def->reserved must be 0");
    GYRO_TRY(check_count(def->vertex_count, "def->vertex_count"));
    GYRO_TRY(check_count(def->triangle_count, "def->triangle_count"));
    const auto nv = std::size_t(def->vertex_count), nt = std::size_t(def->triangle_count);
    if (nv > 0) {
      GYRO_TRY(require(def->x, "def->x"));
      GYRO_TRY(require(def->y, "def->y"));
      GYRO_TRY(require(def->z, "def->z"));
    }
    if (nt > 0) GYRO_TRY(require(def->indices, "def->indices"));
    gyro::MeshData data;
    if (nv > 0) {
      data.x.assign(def->x, def->x + nv);
      data.y.assign(def->y, def->y + nv);
      data.z.assign(def->z, def->z + nv);
    }
    if (nt > 0) data.indices.assign(def->indices, def->indices + 3 * nt);
    return make_mesh(data, out);
  });
}

GYRO_API gyro_status gyro_mesh_load_obj(const char* path, gyro_mesh** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    gyro::MeshData data;
    GYRO_TRY(gyro::load_obj(path, data));
    return make_mesh(data, out);
  });
}

GYRO_API void gyro_mesh_destroy(gyro_mesh* mesh) { delete mesh; }

GYRO_API gyro_status gyro_mesh_get_info(const gyro_mesh* mesh, gyro_mesh_info* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(mesh, "mesh"));
    GYRO_TRY(require(out, "out"));
    const gyro::BvhStats s = mesh->mesh->stats();
    const gyro::AABB b = mesh->mesh->bounds();
    const gyro::vec3 lo = gyro::aabb_min(b), hi = gyro::aabb_max(b);
    gyro_mesh_info info;
    info.triangle_count = int32_t(mesh->mesh->triangle_count());
    info.bvh_nodes = int32_t(s.nodes), info.bvh_leaves = int32_t(s.leaves), info.bvh_depth = int32_t(s.max_depth);
    info.bytes = s.bytes;
    info.bounds_min[0] = lo.x, info.bounds_min[1] = lo.y, info.bounds_min[2] = lo.z;
    info.bounds_max[0] = hi.x, info.bounds_max[1] = hi.y, info.bounds_max[2] = hi.z;
    *out = info;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_mesh_raycast_closest(const gyro_mesh* mesh, const gyro_ray_soa* rays, int32_t ray_count,
                                               const gyro_hit_soa* hits) {
  return guarded([&] { return mesh_raycast(mesh, rays, ray_count, hits, false); });
}

GYRO_API gyro_status gyro_mesh_raycast_any(const gyro_mesh* mesh, const gyro_ray_soa* rays, int32_t ray_count,
                                           const gyro_hit_soa* hits) {
  return guarded([&] { return mesh_raycast(mesh, rays, ray_count, hits, true); });
}

GYRO_API gyro_camera gyro_camera_perspective(float fov_y, float aspect, float z_near, float z_far) {
  return c_camera(gyro::perspective_camera(fov_y, aspect, z_near, z_far));
}

GYRO_API gyro_status gyro_camera_look_at(gyro_camera* camera, const float eye[3], const float target[3],
                                         const float up[3]) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(eye, "eye"));
    GYRO_TRY(require(target, "target"));
    GYRO_TRY(require(up, "up"));
    gyro::Camera cam;
    GYRO_TRY(camera_of(camera, cam));
    const float v[9] = {eye[0], eye[1], eye[2], target[0], target[1], target[2], up[0], up[1], up[2]};
    GYRO_TRY(gyro::detail::require_finite(v, 9, "eye, target, up"));
    gyro::set_look_at(cam, {eye[0], eye[1], eye[2]}, {target[0], target[1], target[2]}, {up[0], up[1], up[2]});
    GYRO_TRY(gyro::check_camera(cam));  // eye == target or up along the view: no orientation
    *camera = c_camera(cam);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_camera_view_projection(const gyro_camera* camera, float out[16]) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    gyro::Camera cam;
    GYRO_TRY(camera_of(camera, cam));
    const gyro::mat4 m = gyro::view_projection_matrix(cam);
    std::memcpy(out, m.m, sizeof m.m);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_camera_picking_ray(const gyro_camera* camera, float screen_x, float screen_y,
                                             float viewport_width, float viewport_height, float origin[3],
                                             float direction[3]) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(origin, "origin"));
    GYRO_TRY(require(direction, "direction"));
    gyro::Camera cam;
    GYRO_TRY(camera_of(camera, cam));
    const float v[4] = {screen_x, screen_y, viewport_width, viewport_height};
    GYRO_TRY(gyro::detail::require_finite(v, 4, "screen point and viewport size"));
    if (!(viewport_width > 0.0f) || !(viewport_height > 0.0f))
      return fail(Status::invalid_argument, "viewport size %g x %g must be positive", double(viewport_width),
                  double(viewport_height));
    const gyro::Ray ray = gyro::picking_ray(cam, {screen_x, screen_y}, {viewport_width, viewport_height});
    origin[0] = ray.origin.x, origin[1] = ray.origin.y, origin[2] = ray.origin.z;
    direction[0] = ray.direction.x, direction[1] = ray.direction.y, direction[2] = ray.direction.z;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_frustum_from_matrix(const float view_projection[16], gyro_frustum* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(view_projection, "view_projection"));
    GYRO_TRY(require(out, "out"));
    GYRO_TRY(gyro::detail::require_finite(view_projection, 16, "view_projection"));
    gyro::mat4 m;
    std::memcpy(m.m, view_projection, sizeof m.m);
    c_frustum(gyro::frustum(m), out);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_camera_frustum(const gyro_camera* camera, gyro_frustum* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    gyro::Camera cam;
    GYRO_TRY(camera_of(camera, cam));
    c_frustum(gyro::frustum(cam), out);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_frustum_cull(const gyro_frustum* frustum, const gyro_shape_soa* shapes, int32_t count,
                                       uint32_t* visible) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(frustum, "frustum"));
    GYRO_TRY(require(shapes, "shapes"));
    GYRO_TRY(check_count(count, "count"));
    const gyro::Frustum f = gyro::capi::frustum_of(*frustum);
    const auto n = static_cast<std::size_t>(count);
    switch (shapes->type) {
      case GYRO_SHAPE_SPHERE: return gyro::frustum_cull(f, view_of<gyro::SpheresView>(shapes->as.sphere), n, visible);
      case GYRO_SHAPE_AABB: return gyro::frustum_cull(f, view_of<gyro::AabbsView>(shapes->as.aabb), n, visible);
      case GYRO_SHAPE_OBB: return gyro::frustum_cull(f, view_of<gyro::ObbsView>(shapes->as.obb), n, visible);
      default: return fail(Status::invalid_argument, "shapes->type = %u: culling takes spheres, AABBs or OBBs", shapes->type);
    }
  });
}

}  // extern "C"
