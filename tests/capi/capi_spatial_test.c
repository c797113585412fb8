/* The spatial module's C ABI from a C99 program: a mesh and its BVH raycasts (with bad rays
 * flagged per ray), the OBJ reader's line-numbered errors, camera picking and frustum
 * culling, and bad input that must get a clear status and change nothing. */
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

/* The cube [-1, 1]^3: 8 corners, 12 outward triangles. */
static const float vx[8] = {-1, 1, -1, 1, -1, 1, -1, 1};
static const float vy[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
static const float vz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
static const uint32_t cube[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                  2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};

static void test_mesh(void) {
  gyro_mesh_def def = gyro_mesh_def_default();
  gyro_mesh* mesh = NULL;
  gyro_mesh* untouched = (gyro_mesh*)&def;
  gyro_mesh_info info;
  uint32_t bad_indices[36];
  float ox[4] = {0, 0, 0, 0}, oy[4] = {0, 0.5f, 0, 0}, oz[4] = {-5, 5, 0, 0};
  float dx[4] = {0, 0, 0, 0}, dy[4] = {0, 0, 0, 1}, dz[4] = {1, -2, 0, 0};
  float t[4], nz[4], nxv[4], nyv[4];
  int32_t prim[4];
  gyro_ray_soa rays;
  gyro_hit_soa hits;
  CHECK(gyro_features() & GYRO_FEATURE_SPATIAL);
  CHECK(sizeof(gyro_mesh_def) == 48 && sizeof(gyro_mesh_info) == 48);
  def.x = vx, def.y = vy, def.z = vz, def.vertex_count = 8, def.indices = cube, def.triangle_count = 12;
  CHECK(gyro_mesh_create(&def, &mesh) == GYRO_OK && mesh != NULL);
  CHECK(gyro_mesh_get_info(mesh, &info) == GYRO_OK);
  CHECK(info.triangle_count == 12 && info.bvh_nodes >= 1 && info.bounds_min[0] == -1.0f && info.bounds_max[2] == 1.0f);

  /* bad definitions: a clear status, *out untouched */
  memcpy(bad_indices, cube, sizeof cube);
  bad_indices[7] = 8;
  def.indices = bad_indices;
  CHECK(gyro_mesh_create(&def, &untouched) == GYRO_STATUS_INVALID_ARGUMENT && untouched == (gyro_mesh*)&def);
  CHECK(strstr(gyro_last_error(), "triangle 2") != NULL);
  def.indices = cube;
  def.triangle_count = -1;
  CHECK(gyro_mesh_create(&def, &untouched) == GYRO_STATUS_INVALID_COUNT);
  def.triangle_count = 0;
  CHECK(gyro_mesh_create(&def, &untouched) == GYRO_STATUS_INVALID_COUNT);
  def.triangle_count = 12;
  def.struct_size = 12;
  CHECK(gyro_mesh_create(&def, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  def.struct_size = sizeof def;
  def.y = NULL;
  CHECK(gyro_mesh_create(&def, &untouched) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(untouched == (gyro_mesh*)&def);

  /* rays: into the front face, from above inside the box, a zero direction, a NaN origin */
  ox[3] = NAN;
  rays.ox = ox, rays.oy = oy, rays.oz = oz, rays.dx = dx, rays.dy = dy, rays.dz = dz, rays.tmin = NULL, rays.tmax = NULL;
  hits.t = t, hits.primitive = prim, hits.nx = nxv, hits.ny = nyv, hits.nz = nz, hits.u = NULL, hits.v = NULL;
  CHECK(gyro_mesh_raycast_closest(mesh, &rays, 4, &hits) == GYRO_OK);
  CHECK(prim[0] >= 0 && prim[0] < 2 && t[0] == 4.0f && nz[0] == -1.0f);
  CHECK(prim[1] >= 0 && t[1] == 2.0f); /* from (0, 0.5, 5) along -2z: the z = 1 face at t = 2 */
  CHECK(prim[2] == GYRO_RAY_INVALID && prim[3] == GYRO_RAY_INVALID && t[3] == INFINITY);
  CHECK(gyro_mesh_raycast_any(mesh, &rays, 4, &hits) == GYRO_OK);
  CHECK(prim[0] >= 0 && prim[2] == GYRO_RAY_INVALID);
  CHECK(gyro_mesh_raycast_closest(NULL, &rays, 4, &hits) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_mesh_raycast_closest(mesh, &rays, -4, &hits) == GYRO_STATUS_INVALID_COUNT);
  gyro_mesh_destroy(mesh);
  gyro_mesh_destroy(NULL);
}

static void test_obj(void) {
  const char* path = "gyro_capi_spatial_test.obj";
  gyro_mesh* mesh = NULL;
  gyro_mesh_info info;
  FILE* f = fopen(path, "w");
  CHECK(f != NULL);
  if (!f) return;
  fputs("# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", f);
  fclose(f);
  CHECK(gyro_mesh_load_obj(path, &mesh) == GYRO_OK && mesh != NULL);
  CHECK(gyro_mesh_get_info(mesh, &info) == GYRO_OK && info.triangle_count == 2);
  gyro_mesh_destroy(mesh);
  f = fopen(path, "w");
  if (!f) return;
  fputs("v 0 0 0\nv 1 0 0\nv 1 1 zero\nf 1 2 3\n", f);
  fclose(f);
  mesh = NULL;
  CHECK(gyro_mesh_load_obj(path, &mesh) == GYRO_STATUS_INVALID_ARGUMENT && mesh == NULL);
  CHECK(strstr(gyro_last_error(), "line 3") != NULL);
  remove(path);
  CHECK(gyro_mesh_load_obj("/nonexistent/gyro.obj", &mesh) == GYRO_STATUS_INVALID_ARGUMENT && mesh == NULL);
  CHECK(gyro_mesh_load_obj(NULL, &mesh) == GYRO_STATUS_NULL_ARGUMENT);
}

static void test_camera_and_frustum(void) {
  gyro_camera cam = gyro_camera_perspective(1.0f, 16.0f / 9.0f, 0.1f, 100.0f);
  const float eye[3] = {0, 5, -10}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  float o[3], d[3], vp[16], len;
  gyro_frustum fr, from_matrix;
  float cx[3] = {0, 0, 0}, cy[3] = {0, 5, 0}, cz[3] = {0, -30, 300}, r[3] = {1, 1, 1};
  uint32_t visible[3] = {7, 7, 7};
  gyro_shape_soa spheres;
  int i, k;
  CHECK(sizeof(gyro_camera) == 76 && sizeof(gyro_frustum) == 96);
  CHECK(gyro_camera_look_at(&cam, eye, target, up) == GYRO_OK);
  /* the centre of the screen looks at the target */
  CHECK(gyro_camera_picking_ray(&cam, 960.0f, 540.0f, 1920.0f, 1080.0f, o, d) == GYRO_OK);
  len = sqrtf(125.0f);
  CHECK(fabsf(d[0]) < 1e-5f && fabsf(d[1] + 5.0f / len) < 1e-5f && fabsf(d[2] - 10.0f / len) < 1e-5f);
  CHECK(gyro_camera_picking_ray(&cam, 0, 0, 0.0f, 1080.0f, o, d) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_camera_frustum(&cam, &fr) == GYRO_OK);
  CHECK(gyro_camera_view_projection(&cam, vp) == GYRO_OK);
  CHECK(gyro_frustum_from_matrix(vp, &from_matrix) == GYRO_OK);
  for (i = 0; i < 6; ++i)
    for (k = 0; k < 4; ++k) CHECK(fabsf(fr.planes[i][k] - from_matrix.planes[i][k]) < 1e-4f * (1.0f + fabsf(fr.planes[i][k])));
  spheres.type = GYRO_SHAPE_SPHERE, spheres.reserved = 0;
  spheres.as.sphere.cx = cx, spheres.as.sphere.cy = cy, spheres.as.sphere.cz = cz, spheres.as.sphere.r = r;
  CHECK(gyro_frustum_cull(&fr, &spheres, 3, visible) == GYRO_OK);
  CHECK(visible[0] == 1 && visible[1] == 0 && visible[2] == 0); /* target; behind the eye; past the far plane */
  spheres.type = GYRO_SHAPE_PLANE;
  visible[0] = 7;
  CHECK(gyro_frustum_cull(&fr, &spheres, 3, visible) == GYRO_STATUS_INVALID_ARGUMENT && visible[0] == 7);
  cam.z_near = -1.0f;
  CHECK(gyro_camera_frustum(&cam, &fr) == GYRO_STATUS_INVALID_ARGUMENT);
  vp[3] = NAN;
  CHECK(gyro_frustum_from_matrix(vp, &fr) == GYRO_STATUS_NON_FINITE);
}


static void test_scene(gyro_scene_accel accel) {
  gyro_mesh_def mdef = gyro_mesh_def_default();
  gyro_mesh* cube_mesh = NULL;
  gyro_scene* scene = NULL;
  gyro_model_def def = gyro_model_def_default();
  gyro_model_id sphere, box, inst, plane, stale, ids[8];
  gyro_transform tr;
  float ox[5] = {0, 3, -3, 0, 0}, oy[5] = {0, 0, 0, 0, NAN}, oz[5] = {0, 0, 0, 0, 0};
  float dx[5] = {0, 0, 0, 0, 0}, dy[5] = {0, 0, 0, -1, 0}, dz[5] = {1, 1, 1, 0, 1};
  float t[5], u[5], v[5];
  gyro_model_id model[5];
  int32_t prim[5], count = -1;
  gyro_ray_soa rays;
  gyro_scene_hit_soa hits;
  float cx = 0, cy = 0, cz = 5, r = 1.5f;
  gyro_shape_soa query;
  gyro_camera cam = gyro_camera_perspective(1.0f, 1.0f, 0.1f, 100.0f);
  gyro_scene_hit picked;
  gyro_frustum fr;
  mdef.x = vx, mdef.y = vy, mdef.z = vz, mdef.vertex_count = 8, mdef.indices = cube, mdef.triangle_count = 12;
  CHECK(gyro_mesh_create(&mdef, &cube_mesh) == GYRO_OK);
  CHECK(gyro_scene_create(accel, &scene) == GYRO_OK);
  CHECK(gyro_scene_create(7, &scene) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(sizeof(gyro_model_def) == 88 && sizeof(gyro_transform) == 32 && sizeof(gyro_scene_hit) == 52);

  def.transform.position[2] = 5; /* unit sphere at (0, 0, 5) */
  CHECK(gyro_scene_add_model(scene, &def, &sphere) == GYRO_OK && sphere.generation != 0);
  def.shape = GYRO_MODEL_BOX, def.transform.position[0] = 3; /* unit box at (3, 0, 5) */
  CHECK(gyro_scene_add_model(scene, &def, &box) == GYRO_OK);
  def.shape = GYRO_MODEL_MESH, def.mesh = cube_mesh, def.transform.position[0] = -3, def.transform.scale = 0.5f;
  CHECK(gyro_scene_add_model(scene, &def, &inst) == GYRO_OK);
  gyro_mesh_destroy(cube_mesh); /* the scene keeps its own reference */
  def = gyro_model_def_default();
  def.shape = GYRO_MODEL_PLANE, def.plane[3] = -2; /* y = -2 */
  CHECK(gyro_scene_add_model(scene, &def, &plane) == GYRO_OK);
  CHECK(gyro_scene_model_count(scene) == 4);

  /* bad models change nothing */
  def = gyro_model_def_default();
  def.radius = -1;
  CHECK(gyro_scene_add_model(scene, &def, &stale) == GYRO_STATUS_INVALID_ARGUMENT);
  def.radius = 1, def.transform.scale = 0;
  CHECK(gyro_scene_add_model(scene, &def, &stale) == GYRO_STATUS_INVALID_ARGUMENT);
  def.transform.scale = 1, def.transform.position[1] = NAN;
  CHECK(gyro_scene_add_model(scene, &def, &stale) == GYRO_STATUS_NON_FINITE);
  def.transform.position[1] = 0, def.shape = GYRO_MODEL_MESH, def.mesh = NULL;
  CHECK(gyro_scene_add_model(scene, &def, &stale) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_scene_model_count(scene) == 4);
  CHECK(gyro_scene_set_parent(scene, sphere, sphere) == GYRO_STATUS_INVALID_ARGUMENT);

  rays.ox = ox, rays.oy = oy, rays.oz = oz, rays.dx = dx, rays.dy = dy, rays.dz = dz, rays.tmin = NULL, rays.tmax = NULL;
  hits.t = t, hits.model = model, hits.primitive = prim, hits.nx = hits.ny = hits.nz = NULL, hits.u = u, hits.v = v;
  CHECK(gyro_scene_raycast_closest(scene, &rays, 5, &hits) == GYRO_OK);
  CHECK(t[0] == 4.0f && model[0].index == sphere.index && prim[0] == 0);
  CHECK(t[1] == 4.0f && model[1].index == box.index);
  CHECK(t[2] == 4.5f && model[2].index == inst.index && prim[2] >= 0 && prim[2] < 12);
  CHECK(t[3] == 2.0f && model[3].index == plane.index);
  CHECK(prim[4] == GYRO_RAY_INVALID && model[4].index == 0 && model[4].generation == 0);
  CHECK(gyro_scene_raycast_any(scene, &rays, 5, &hits) == GYRO_OK);
  CHECK(prim[0] >= 0 && prim[4] == GYRO_RAY_INVALID);
  /* prefetching changes speed only (ABI 1.7); bad calls change nothing */
  CHECK(gyro_scene_set_ray_prefetch(NULL, GYRO_RAY_PREFETCH_ALWAYS) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_scene_set_ray_prefetch(scene, 3) == GYRO_STATUS_INVALID_ARGUMENT);
  for (gyro_ray_prefetch mode = GYRO_RAY_PREFETCH_AUTO; mode <= GYRO_RAY_PREFETCH_NEVER; ++mode) {
    CHECK(gyro_scene_set_ray_prefetch(scene, mode) == GYRO_OK);
    CHECK(gyro_scene_raycast_closest(scene, &rays, 5, &hits) == GYRO_OK);
    CHECK(t[0] == 4.0f && model[0].index == sphere.index && t[2] == 4.5f && model[2].index == inst.index);
    CHECK(t[3] == 2.0f && model[3].index == plane.index && prim[4] == GYRO_RAY_INVALID);
  }
  /* refit (ABI 1.8): the box moved away and back refits the tree or rebuilds it, the same
     hits either way; bad calls change nothing */
  CHECK(gyro_scene_set_refit(NULL, 1) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_scene_set_refit(scene, 2) == GYRO_STATUS_INVALID_ARGUMENT);
  for (uint32_t on = 0; on <= 1; ++on) {
    gyro_transform moved = gyro_model_def_default().transform;
    CHECK(gyro_scene_set_refit(scene, on) == GYRO_OK);
    moved.position[0] = 3, moved.position[1] = 40, moved.position[2] = 5;
    CHECK(gyro_scene_set_transform(scene, box, &moved) == GYRO_OK);
    CHECK(gyro_scene_raycast_closest(scene, &rays, 5, &hits) == GYRO_OK);
    CHECK(t[0] == 4.0f && model[0].index == sphere.index && model[1].index == 0 && t[2] == 4.5f);
    moved.position[1] = 0;
    CHECK(gyro_scene_set_transform(scene, box, &moved) == GYRO_OK);
    CHECK(gyro_scene_raycast_closest(scene, &rays, 5, &hits) == GYRO_OK);
    CHECK(t[1] == 4.0f && model[1].index == box.index && t[3] == 2.0f && model[3].index == plane.index);
  }

  /* layers (ABI 1.9): each model in its own layer; a ray sees a model only through a
     shared bit, whatever its shape (the plane and the mesh's exact test included) */
  {
    const uint32_t seen[5] = {1, 2, 4, 8, 0xFFFFFFFFu}, unseen[5] = {2, 4, 8, 1, 0};
    CHECK(gyro_scene_set_layers(NULL, sphere, 1) == GYRO_STATUS_NULL_ARGUMENT);
    CHECK(gyro_scene_set_layers(scene, sphere, 1) == GYRO_OK && gyro_scene_set_layers(scene, box, 2) == GYRO_OK);
    CHECK(gyro_scene_set_layers(scene, inst, 4) == GYRO_OK && gyro_scene_set_layers(scene, plane, 8) == GYRO_OK);
    CHECK(gyro_scene_raycast_closest_masked(scene, &rays, seen, 5, &hits) == GYRO_OK);
    CHECK(t[0] == 4.0f && model[0].index == sphere.index && t[1] == 4.0f && model[1].index == box.index);
    CHECK(t[2] == 4.5f && model[2].index == inst.index && t[3] == 2.0f && model[3].index == plane.index);
    CHECK(prim[4] == GYRO_RAY_INVALID);
    CHECK(gyro_scene_raycast_closest_masked(scene, &rays, unseen, 5, &hits) == GYRO_OK);
    for (int k = 0; k < 4; ++k) CHECK(t[k] == INFINITY && model[k].generation == 0 && prim[k] == -1);
    CHECK(gyro_scene_raycast_any_masked(scene, &rays, unseen, 5, &hits) == GYRO_OK);
    for (int k = 0; k < 4; ++k) CHECK(model[k].generation == 0);
    CHECK(gyro_scene_raycast_any_masked(scene, &rays, seen, 5, &hits) == GYRO_OK && model[3].index == plane.index);
    /* the unmasked calls see every layer */
    CHECK(gyro_scene_raycast_closest(scene, &rays, 5, &hits) == GYRO_OK && model[0].index == sphere.index);
    CHECK(gyro_scene_raycast_closest_masked(scene, &rays, NULL, 5, &hits) == GYRO_OK && model[2].index == inst.index);
    CHECK(gyro_scene_raycast_closest_masked(NULL, &rays, seen, 5, &hits) == GYRO_STATUS_NULL_ARGUMENT);
    /* queries and picks of a mask see the models of its layers only */
    query.type = GYRO_SHAPE_SPHERE, query.reserved = 0;
    query.as.sphere.cx = &cx, query.as.sphere.cy = &cy, query.as.sphere.cz = &cz, query.as.sphere.r = &r;
    cx = 0.5f, r = 1.6f; /* the sphere and the box */
    CHECK(gyro_scene_query_masked(scene, &query, 2, ids, 8, &count) == GYRO_OK && count == 1 && ids[0].index == box.index);
    CHECK(gyro_scene_query_masked(scene, &query, 4 | 8, ids, 8, &count) == GYRO_OK && count == 0);
    CHECK(gyro_scene_query_masked(scene, &query, 3, ids, 8, &count) == GYRO_OK && count == 2);
    CHECK(gyro_scene_query_masked(NULL, &query, 3, ids, 8, &count) == GYRO_STATUS_NULL_ARGUMENT);
    CHECK(gyro_camera_frustum(&cam, &fr) == GYRO_OK);
    CHECK(gyro_scene_query_frustum_masked(scene, &fr, 8, ids, 8, &count) == GYRO_OK && count == 1 &&
          ids[0].index == plane.index);
    CHECK(gyro_scene_pick_masked(scene, &cam, 320, 240, 640, 480, 2 | 4 | 8, &picked) == GYRO_OK &&
          (picked.hit == 0 || picked.model.index != sphere.index));
    CHECK(gyro_scene_pick_masked(scene, &cam, 320, 240, 640, 480, 1, &picked) == GYRO_OK && picked.hit == 1 &&
          picked.model.index == sphere.index);
    cx = 0.0f, r = 1.5f;
    for (gyro_model_id m4[4] = {sphere, box, inst, plane}, *p = m4; p < m4 + 4; ++p)
      CHECK(gyro_scene_set_layers(scene, *p, 0xFFFFFFFFu) == GYRO_OK);
  }

  /* queries */
  query.type = GYRO_SHAPE_SPHERE, query.reserved = 0;
  query.as.sphere.cx = &cx, query.as.sphere.cy = &cy, query.as.sphere.cz = &cz, query.as.sphere.r = &r;
  CHECK(gyro_scene_query(scene, &query, ids, 8, &count) == GYRO_OK && count == 1 && ids[0].index == sphere.index);
  cx = 0.5f, r = 1.6f; /* reaches the box (x >= 2), not the mesh (x <= -2.5) nor the plane (y = -2) */
  CHECK(gyro_scene_query(scene, &query, ids, 1, &count) == GYRO_OK && count == 2 && ids[0].index == sphere.index);
  CHECK(gyro_scene_query(scene, &query, NULL, 0, &count) == GYRO_OK && count == 2);

  /* the camera at the origin looks down +z: the sphere is in the middle of the screen */
  CHECK(gyro_scene_pick(scene, &cam, 320, 240, 640, 480, &picked) == GYRO_OK);
  CHECK(picked.hit == 1 && picked.model.index == sphere.index && fabsf(picked.t - 3.9f) < 1e-3f);
  CHECK(gyro_camera_frustum(&cam, &fr) == GYRO_OK);
  CHECK(gyro_scene_query_frustum(scene, &fr, ids, 8, &count) == GYRO_OK && count == 4); /* plane crosses it */

  /* transforms, removal, stale ids */
  memset(&tr, 0, sizeof tr);
  tr.position[2] = 10, tr.rotation[3] = 1, tr.scale = 1;
  CHECK(gyro_scene_set_transform(scene, sphere, &tr) == GYRO_OK);
  CHECK(gyro_scene_raycast_closest(scene, &rays, 1, &hits) == GYRO_OK && t[0] == 9.0f);
  CHECK(gyro_scene_remove_model(scene, sphere) == GYRO_OK);
  CHECK(gyro_scene_remove_model(scene, sphere) == GYRO_STATUS_STALE_ID);
  CHECK(gyro_scene_set_transform(scene, sphere, &tr) == GYRO_STATUS_STALE_ID);
  CHECK(gyro_scene_set_layers(scene, sphere, 1) == GYRO_STATUS_STALE_ID);
  CHECK(gyro_scene_raycast_closest(scene, &rays, 1, &hits) == GYRO_OK && prim[0] == -1 && t[0] == INFINITY);
  CHECK(gyro_scene_model_count(scene) == 3);
  gyro_scene_destroy(scene);
  gyro_scene_destroy(NULL);
}

int main(void) {
  test_mesh();
  test_obj();
  test_camera_and_frustum();
  test_scene(GYRO_SCENE_BVH);
  test_scene(GYRO_SCENE_OCTREE);
  if (failures) {
    fprintf(stderr, "%d checks failed\n", failures);
    return 1;
  }
  printf("capi spatial: all checks passed\n");
  return 0;
}
