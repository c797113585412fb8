/* gyro batch raycast: a fan of rays through a scene in one call, through the C ABI.
 *
 *   cc batch_raycast.c $(pkg-config --cflags --libs gyro) -lm -o batch_raycast
 *
 * The scene holds a ground plane, a ring of spheres, a ring of rotated boxes and a torus
 * mesh (with its own BVH), under the scene's BVH. A sensor casts a fan of rays (16 rows of
 * 4,096 columns, all around) with gyro_scene_raycast_closest: rays in, structure-of-arrays
 * hits out (t, model, triangle, normal). The example prints what was hit, a few sample rays
 * and the rays per second, then checks one ray against its known answer and that the
 * occlusion query (gyro_scene_raycast_any) agrees on which rays hit something, and that
 * rays of another layer pass through the boxes (gyro_scene_set_layers). */
#define _POSIX_C_SOURCE 199309L
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define ROWS 16
#define COLUMNS 4096
#define RAYS (ROWS * COLUMNS)
#define RANGE 50.0f
#define RING 12
#define REPS 9
#define PI 3.14159265358979

#define CHECK(call)                                                                                        \
  do {                                                                                                     \
    gyro_status status_ = (call);                                                                          \
    if (status_ != GYRO_OK) {                                                                              \
      fprintf(stderr, "%s failed: %s (%s)\n", #call, gyro_status_name(status_), gyro_last_error());       \
      exit(1);                                                                                             \
    }                                                                                                      \
  } while (0)

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void* a, const void* b) {
  const double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* A torus around the y axis: major radius R, minor radius r, nu x nv quads, two triangles each. */
static gyro_mesh* make_torus(float R, float r, int nu, int nv) {
  const int nvert = nu * nv, ntri = 2 * nu * nv;
  float *x = malloc(nvert * sizeof(float)), *y = malloc(nvert * sizeof(float)), *z = malloc(nvert * sizeof(float));
  uint32_t* idx = malloc(3 * (size_t)ntri * sizeof(uint32_t));
  gyro_mesh_def def = gyro_mesh_def_default();
  gyro_mesh* mesh = NULL;
  int i, j, k = 0;
  if (!x || !y || !z || !idx) exit(1);
  for (i = 0; i < nu; ++i)
    for (j = 0; j < nv; ++j) {
      const double u = 2 * PI * i / nu, v = 2 * PI * j / nv;
      x[i * nv + j] = (float)((R + r * cos(v)) * cos(u));
      y[i * nv + j] = (float)(r * sin(v));
      z[i * nv + j] = (float)((R + r * cos(v)) * sin(u));
    }
  for (i = 0; i < nu; ++i)
    for (j = 0; j < nv; ++j) {
      const uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j);
      const uint32_t c = (uint32_t)(i * nv + (j + 1) % nv), d = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv);
      idx[k++] = a, idx[k++] = b, idx[k++] = c;
      idx[k++] = c, idx[k++] = b, idx[k++] = d;
    }
  def.vertex_count = nvert, def.x = x, def.y = y, def.z = z, def.indices = idx, def.triangle_count = ntri;
  CHECK(gyro_mesh_create(&def, &mesh));
  free(x), free(y), free(z), free(idx);
  return mesh;
}

static int same_model(gyro_model_id a, gyro_model_id b) { return a.index == b.index && a.generation == b.generation; }

int main(void) {
  static float ox[RAYS], oy[RAYS], oz[RAYS], dx[RAYS], dy[RAYS], dz[RAYS], tmax[RAYS];
  static float t[RAYS], nx[RAYS], ny[RAYS], nz[RAYS], any_t[RAYS];
  static gyro_model_id model[RAYS], any_model[RAYS];
  static int32_t primitive[RAYS], any_primitive[RAYS];
  static uint32_t masks[RAYS];
  gyro_scene* scene = NULL;
  gyro_mesh* torus;
  gyro_model_def def;
  gyro_model_id ground, spheres[RING], boxes[RING], torus_model;
  gyro_ray_soa rays;
  gyro_scene_hit_soa hits, any_hits;
  gyro_mesh_info info;
  double times[REPS], ms;
  int i, j, k, n_ground = 0, n_sphere = 0, n_box = 0, n_torus = 0, n_miss = 0, disagree = 0;

  if (gyro_abi_version() >> 16 != GYRO_ABI_VERSION >> 16 || gyro_abi_version() < GYRO_ABI_VERSION) {
    fprintf(stderr, "gyro library ABI %#x does not match the header's %#x\n", (unsigned)gyro_abi_version(),
            (unsigned)GYRO_ABI_VERSION);
    return 1;
  }
  if (!(gyro_features() & GYRO_FEATURE_SPATIAL)) {
    printf("this gyro build has no spatial module (scenes)\n");
    return 0;
  }

  /* ---- the scene */
  CHECK(gyro_scene_create(GYRO_SCENE_BVH, &scene));
  def = gyro_model_def_default();
  def.shape = GYRO_MODEL_PLANE; /* y = 0, normal +y */
  def.plane[0] = 0.0f, def.plane[1] = 1.0f, def.plane[2] = 0.0f, def.plane[3] = 0.0f;
  CHECK(gyro_scene_add_model(scene, &def, &ground));
  for (i = 0; i < RING; ++i) {
    /* spheres 8 m out, boxes 14 m out between them, turned about y by their azimuth */
    const double a = 2 * PI * i / RING, b = a + PI / RING;
    def = gyro_model_def_default();
    def.shape = GYRO_MODEL_SPHERE;
    def.radius = 0.5f + 0.1f * (float)(i % 4);
    def.transform.position[0] = (float)(8 * cos(a)), def.transform.position[1] = def.radius;
    def.transform.position[2] = (float)(8 * sin(a));
    CHECK(gyro_scene_add_model(scene, &def, &spheres[i]));
    def = gyro_model_def_default();
    def.shape = GYRO_MODEL_BOX;
    def.half_extents[0] = 1.0f, def.half_extents[1] = 1.5f, def.half_extents[2] = 0.4f;
    def.transform.position[0] = (float)(14 * cos(b)), def.transform.position[1] = 1.5f;
    def.transform.position[2] = (float)(14 * sin(b));
    def.transform.rotation[1] = (float)sin(-0.5 * b), def.transform.rotation[3] = (float)cos(-0.5 * b);
    CHECK(gyro_scene_add_model(scene, &def, &boxes[i]));
  }
  torus = make_torus(1.5f, 0.5f, 64, 32);
  CHECK(gyro_mesh_get_info(torus, &info));
  def = gyro_model_def_default();
  def.shape = GYRO_MODEL_MESH;
  def.mesh = torus;
  def.transform.position[1] = 4.0f; /* above the sensor, tilted 30 degrees about x */
  def.transform.rotation[0] = (float)sin(PI / 12), def.transform.rotation[3] = (float)cos(PI / 12);
  CHECK(gyro_scene_add_model(scene, &def, &torus_model));
  gyro_mesh_destroy(torus); /* the scene keeps its own reference */

  /* ---- the fan: 16 rows from -20 to +60 degrees elevation, 4,096 columns all around */
  for (j = 0; j < ROWS; ++j) {
    const double el = (-20.0 + 80.0 * j / (ROWS - 1)) * PI / 180.0;
    for (i = 0; i < COLUMNS; ++i) {
      const double az = 2 * PI * (i + 0.5) / COLUMNS;
      k = j * COLUMNS + i;
      ox[k] = 0.0f, oy[k] = 1.2f, oz[k] = 0.0f;
      dx[k] = (float)(cos(el) * cos(az)), dy[k] = (float)sin(el), dz[k] = (float)(cos(el) * sin(az));
      tmax[k] = RANGE;
    }
  }
  rays.ox = ox, rays.oy = oy, rays.oz = oz, rays.dx = dx, rays.dy = dy, rays.dz = dz;
  rays.tmin = NULL, rays.tmax = tmax;
  memset(&hits, 0, sizeof hits);
  hits.t = t, hits.model = model, hits.primitive = primitive, hits.nx = nx, hits.ny = ny, hits.nz = nz;

  CHECK(gyro_scene_raycast_closest(scene, &rays, RAYS, &hits)); /* warm-up */
  for (k = 0; k < REPS; ++k) {
    const double start = now_ms();
    CHECK(gyro_scene_raycast_closest(scene, &rays, RAYS, &hits));
    times[k] = now_ms() - start;
  }
  qsort(times, REPS, sizeof times[0], cmp_double);
  ms = times[REPS / 2];

  for (k = 0; k < RAYS; ++k) {
    if (primitive[k] < 0) {
      ++n_miss;
    } else if (same_model(model[k], ground)) {
      ++n_ground;
    } else if (same_model(model[k], torus_model)) {
      ++n_torus;
    } else {
      for (i = 0; i < RING; ++i) {
        n_sphere += same_model(model[k], spheres[i]);
        n_box += same_model(model[k], boxes[i]);
      }
    }
  }
  printf("gyro %s batch raycast: %d rays (%d rows x %d columns, %.0f m) against %d models (a plane, %d spheres, %d "
         "boxes, a %d-triangle torus mesh)\n",
         gyro_version_string(), RAYS, ROWS, COLUMNS, RANGE, gyro_scene_model_count(scene), RING, RING,
         info.triangle_count);
  printf("hits: ground %d, spheres %d, boxes %d, torus %d, missed %d\n", n_ground, n_sphere, n_box, n_torus, n_miss);
  printf("sample rays of the row at %+.0f degrees:\n", -20.0 + 80.0 * 4 / (ROWS - 1));
  printf("  %8s %8s  %-8s %9s  %s\n", "azimuth", "t (m)", "model", "triangle", "normal");
  for (i = 0; i < COLUMNS; i += COLUMNS / 8) {
    k = 4 * COLUMNS + i;
    printf("  %8.1f %8.3f  %-8u %9d  (%+.3f, %+.3f, %+.3f)\n", 360.0 * (i + 0.5) / COLUMNS, t[k],
           (unsigned)model[k].index, (int)primitive[k], nx[k], ny[k], nz[k]);
  }
  printf("time: %.3f ms per call (median of %d), %.2f Mrays/s on %u thread(s), SIMD %s\n", ms, REPS,
         RAYS / ms / 1e3, gyro_get_thread_count(), gyro_simd_level_name(gyro_get_simd_level()));

  /* Checks. The row at +60 degrees looks up through the torus's hole or hits it. */
  if (n_ground == 0 || n_sphere == 0 || n_box == 0 || n_torus == 0) {
    fprintf(stderr, "expected every kind of model to be hit\n");
    return 1;
  }
  /* A ray from the sensor straight at sphere 0 (centre (8, r, 0)) along its height: the
   * surface is 8 - r away. */
  {
    float o[3] = {0.0f, 0.0f, 0.0f}, d[3] = {1.0f, 0.0f, 0.0f}, one_t;
    const float r = 0.5f;
    gyro_model_id one_model;
    int32_t one_prim;
    gyro_ray_soa one;
    gyro_scene_hit_soa one_hit;
    o[1] = r; /* the sphere's centre height */
    one.ox = &o[0], one.oy = &o[1], one.oz = &o[2], one.dx = &d[0], one.dy = &d[1], one.dz = &d[2];
    one.tmin = NULL, one.tmax = NULL;
    memset(&one_hit, 0, sizeof one_hit);
    one_hit.t = &one_t, one_hit.model = &one_model, one_hit.primitive = &one_prim;
    CHECK(gyro_scene_raycast_closest(scene, &one, 1, &one_hit));
    printf("known answer: a ray at sphere 0 hits model %u at t = %.6f (expected %.6f)\n", (unsigned)one_model.index,
           one_t, 8.0f - r);
    if (!same_model(one_model, spheres[0]) || fabsf(one_t - (8.0f - r)) > 1e-5f) return 1;
  }
  /* The occlusion query must find a hit exactly where the closest-hit query did. */
  memset(&any_hits, 0, sizeof any_hits);
  any_hits.t = any_t, any_hits.model = any_model, any_hits.primitive = any_primitive;
  CHECK(gyro_scene_raycast_any(scene, &rays, RAYS, &any_hits));
  for (k = 0; k < RAYS; ++k) disagree += (any_primitive[k] >= 0) != (primitive[k] >= 0);
  printf("occlusion query agrees on which rays hit: %s (%d differ)\n", disagree == 0 ? "yes" : "NO", disagree);
  /* Layers (ABI 1.9): the boxes alone in layer 2, the sensor's rays in layer 1. The rays
   * pass through the boxes to whatever lies behind them; no ray hits a box. */
  for (i = 0; i < RING; ++i) CHECK(gyro_scene_set_layers(scene, boxes[i], 2u));
  for (k = 0; k < RAYS; ++k) masks[k] = 1u;
  CHECK(gyro_scene_raycast_closest_masked(scene, &rays, masks, RAYS, &hits));
  n_box = 0;
  for (k = 0; k < RAYS; ++k)
    for (i = 0; i < RING; ++i) n_box += same_model(model[k], boxes[i]);
  printf("rays of layer 1 with the boxes in layer 2: %d box hits (expected 0)\n", n_box);
  gyro_scene_destroy(scene);
  return disagree == 0 && n_box == 0 ? 0 : 1;
}
