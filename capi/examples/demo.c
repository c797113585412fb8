/* gyro demo: the embedded default scene through the C ABI.
 *
 * Part 1: a 32-channel lidar (1,024 columns per turn, 120 m range) sits in a field of 1,024
 * spheres. Every ray is cast against every sphere (the brute-force batch kernel) at each
 * SIMD level this CPU has, then with more threads. The report gives rays/s, the speed-up
 * over the scalar level, the error against a double-precision reference, and a hash of
 * the results, which is the same at every level and thread count: gyro is deterministic.
 *
 * Part 2: a 64-channel lidar (2,048 columns) scans a 131,072-triangle terrain through the
 * mesh BVH; the hits are compared with the brute-force kernel over every triangle.
 *
 * Part 3: a pyramid of rigid boxes hit by a ball. Part 4: a cloth draped over a sphere. Both
 * run at every SIMD level and on 2 threads, and their world hashes must agree.
 *
 * Pictures: the 2-thread runs of parts 3 and 4 are drawn by gyro's own batch raycaster (a
 * scene of the world's bodies and the cloth mesh, camera picking rays, shadow rays) into PNG
 * files: pyramid_hit.png, pyramid_after.png and cloth.png in argv[1] (default build/demo). */
#define _POSIX_C_SOURCE 199309L
#include "gyro.h"
#include "png_writer.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define SPHERES 1024
#define CHANNELS 32
#define COLUMNS 1024
#define RAYS (CHANNELS * COLUMNS)
#define RANGE 120.0f
#define REPS 3
#define REF_STRIDE 8 /* the reference checks every 8th ray */

static uint64_t rng_state = 42;
static double rng_u(void) { /* splitmix64, 24-bit uniform in [0, 1) */
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 40) * (1.0 / 16777216.0);
}

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

static uint64_t fnv1a(const void* data, size_t n, uint64_t h) {
  const unsigned char* p = (const unsigned char*)data;
  size_t i;
  for (i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

/* Closest sphere-surface crossing in [0, tmax], in double (the textbook quadratic). */
static int ref_cast(const float* o, const float* d, float tmax, const float* cx, const float* cy, const float* cz,
                    const float* cr, double* t_out) {
  int best = -1, j;
  double best_t = 1e300, a = (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2];
  for (j = 0; j < SPHERES; ++j) {
    double px = (double)o[0] - cx[j], py = (double)o[1] - cy[j], pz = (double)o[2] - cz[j];
    double b = px * d[0] + py * d[1] + pz * d[2], c = px * px + py * py + pz * pz - (double)cr[j] * cr[j];
    double disc = b * b - a * c, sq, t0, t1, t;
    if (disc < 0) continue;
    sq = sqrt(disc), t0 = (-b - sq) / a, t1 = (-b + sq) / a;
    t = t0 >= 0 ? t0 : t1;
    if (t >= 0 && t <= tmax && t < best_t) best_t = t, best = j;
  }
  *t_out = best_t;
  return best;
}

static float *cx, *cy, *cz, *cr, *ox, *oy, *oz, *dx, *dy, *dz, *tmax, *t, *nx, *ny, *nz;
static int32_t* prim;

static void check(gyro_status s, const char* what) {
  if (s != GYRO_OK) {
    fprintf(stderr, "%s failed: %s (%s)\n", what, gyro_status_name(s), gyro_last_error());
    exit(1);
  }
}

/* Casts all rays at the current settings; returns the median time in ms and the hash. */
static double run(uint64_t* hash) {
  gyro_ray_soa rays;
  gyro_sphere_soa spheres;
  gyro_hit_soa hits;
  double times[REPS];
  int r;
  rays.ox = ox, rays.oy = oy, rays.oz = oz, rays.dx = dx, rays.dy = dy, rays.dz = dz, rays.tmin = NULL, rays.tmax = tmax;
  spheres.cx = cx, spheres.cy = cy, spheres.cz = cz, spheres.r = cr;
  hits.t = t, hits.primitive = prim, hits.nx = nx, hits.ny = ny, hits.nz = nz, hits.u = NULL, hits.v = NULL;
  check(gyro_raycast_spheres_closest(&rays, RAYS, &spheres, SPHERES, &hits), "warm-up raycast");
  for (r = 0; r < REPS; ++r) {
    double start = now_ms();
    check(gyro_raycast_spheres_closest(&rays, RAYS, &spheres, SPHERES, &hits), "raycast");
    times[r] = now_ms() - start;
  }
  qsort(times, REPS, sizeof times[0], cmp_double);
  *hash = fnv1a(prim, RAYS * sizeof *prim, fnv1a(t, RAYS * sizeof *t, 0xcbf29ce484222325ull));
  *hash = fnv1a(nx, RAYS * sizeof *nx, fnv1a(ny, RAYS * sizeof *ny, fnv1a(nz, RAYS * sizeof *nz, *hash)));
  return times[REPS / 2];
}


/* ---------------------------------------------------------------- part 2: terrain + BVH */

#define GRID 257 /* vertices per side: 2 x 256 x 256 = 131,072 triangles */
#define T_CHANNELS 64
#define T_COLUMNS 2048
#define T_RAYS (T_CHANNELS * T_COLUMNS)
#define T_REF_STRIDE 97 /* brute force checks every 97th ray */

static int terrain_demo(void) {
  const int nv = GRID * GRID, nt = 2 * (GRID - 1) * (GRID - 1);
  float *vx = malloc(nv * sizeof(float)), *vy = malloc(nv * sizeof(float)), *vz = malloc(nv * sizeof(float));
  uint32_t* idx = malloc(3 * (size_t)nt * sizeof(uint32_t));
  float *rox = malloc(T_RAYS * sizeof(float)), *roy = malloc(T_RAYS * sizeof(float)), *roz = malloc(T_RAYS * sizeof(float));
  float *rdx = malloc(T_RAYS * sizeof(float)), *rdy = malloc(T_RAYS * sizeof(float)), *rdz = malloc(T_RAYS * sizeof(float));
  float *rtmax = malloc(T_RAYS * sizeof(float)), *rt = malloc(T_RAYS * sizeof(float));
  int32_t* rp = malloc(T_RAYS * sizeof(int32_t));
  float *tax, *tay, *taz, *tbx, *tby, *tbz, *tcx, *tcy, *tcz;
  gyro_mesh_def def = gyro_mesh_def_default();
  gyro_mesh* mesh = NULL;
  gyro_mesh_info info;
  gyro_ray_soa rays;
  gyro_hit_soa hits;
  gyro_simd_level level;
  uint64_t first_hash = 0;
  double build_ms, start;
  int i, j, k, hitcount = 0, checked = 0, disagree = 0, same = 1, first = 1;
  if (!vx || !vy || !vz || !idx || !rox || !roy || !roz || !rdx || !rdy || !rdz || !rtmax || !rt || !rp) return 1;

  /* Rolling hills on a 200 x 200 m square centred on the sensor. */
  for (j = 0; j < GRID; ++j)
    for (i = 0; i < GRID; ++i) {
      const double x = -100.0 + 200.0 * i / (GRID - 1), z = -100.0 + 200.0 * j / (GRID - 1);
      k = j * GRID + i;
      vx[k] = (float)x, vz[k] = (float)z;
      vy[k] = (float)(3.0 * sin(0.07 * x) * cos(0.05 * z) + 1.5 * sin(0.23 * x + 0.17 * z) - 2.0);
    }
  for (j = 0, k = 0; j < GRID - 1; ++j)
    for (i = 0; i < GRID - 1; ++i) {
      const uint32_t a = (uint32_t)(j * GRID + i), b = a + 1, c = a + GRID, d = c + 1;
      idx[k++] = a, idx[k++] = c, idx[k++] = b, idx[k++] = b, idx[k++] = c, idx[k++] = d;
    }
  for (j = 0; j < T_CHANNELS; ++j) {
    const double el = (-25.0 + 40.0 * j / (T_CHANNELS - 1)) * 3.14159265358979 / 180.0;
    for (i = 0; i < T_COLUMNS; ++i) {
      const double az = 2 * 3.14159265358979 * i / T_COLUMNS;
      k = j * T_COLUMNS + i;
      rox[k] = 0.3f, roy[k] = 4.0f, roz[k] = -0.7f;
      rdx[k] = (float)(cos(el) * cos(az)), rdy[k] = (float)sin(el), rdz[k] = (float)(cos(el) * sin(az));
      rtmax[k] = RANGE;
    }
  }
  def.x = vx, def.y = vy, def.z = vz, def.vertex_count = nv, def.indices = idx, def.triangle_count = nt;
  start = now_ms();
  check(gyro_mesh_create(&def, &mesh), "mesh create");
  build_ms = now_ms() - start;
  check(gyro_mesh_get_info(mesh, &info), "mesh info");
  printf("\nterrain: %d lidar rays (%d x %d) against %d triangles through the BVH (built in %.0f ms, %d nodes, %.0f "
         "bytes/triangle)\n",
         T_RAYS, T_CHANNELS, T_COLUMNS, nt, build_ms, info.bvh_nodes, (double)info.bytes / nt);
  printf("  %-8s %7s %10s %9s  %s\n", "simd", "threads", "time ms", "Mrays/s", "result hash");
  rays.ox = rox, rays.oy = roy, rays.oz = roz, rays.dx = rdx, rays.dy = rdy, rays.dz = rdz, rays.tmin = NULL;
  rays.tmax = rtmax;
  hits.t = rt, hits.primitive = rp, hits.nx = hits.ny = hits.nz = hits.u = hits.v = NULL;
  for (level = GYRO_SIMD_SCALAR; level <= GYRO_SIMD_NEON + 1; ++level) {
    /* every level on one thread, then the best level on every thread */
    const int all_threads = level == GYRO_SIMD_NEON + 1;
    double times[REPS];
    uint64_t h;
    int r;
    if (!all_threads && !gyro_simd_level_available(level)) continue;
    check(gyro_set_simd_level(all_threads ? GYRO_SIMD_AUTO : level), "set level");
    check(gyro_set_thread_count(all_threads ? 0 : 1), "set threads");
    for (r = 0; r < REPS; ++r) {
      start = now_ms();
      check(gyro_mesh_raycast_closest(mesh, &rays, T_RAYS, &hits), "mesh raycast");
      times[r] = now_ms() - start;
    }
    qsort(times, REPS, sizeof times[0], cmp_double);
    h = fnv1a(rp, T_RAYS * sizeof *rp, fnv1a(rt, T_RAYS * sizeof *rt, 0xcbf29ce484222325ull));
    if (first) first_hash = h, first = 0;
    same = same && h == first_hash;
    printf("  %-8s %7u %10.2f %9.3f  0x%016llx\n", gyro_simd_level_name(gyro_get_simd_level()), gyro_get_thread_count(),
           times[REPS / 2], T_RAYS / times[REPS / 2] / 1e3, (unsigned long long)h);
  }
  for (i = 0; i < T_RAYS; ++i) hitcount += rp[i] >= 0;

  /* Brute force over every triangle for a sample of rays: the BVH must give the same hit. */
  tax = malloc(nt * sizeof(float)), tay = malloc(nt * sizeof(float)), taz = malloc(nt * sizeof(float));
  tbx = malloc(nt * sizeof(float)), tby = malloc(nt * sizeof(float)), tbz = malloc(nt * sizeof(float));
  tcx = malloc(nt * sizeof(float)), tcy = malloc(nt * sizeof(float)), tcz = malloc(nt * sizeof(float));
  if (tax && tay && taz && tbx && tby && tbz && tcx && tcy && tcz) {
    float bt[T_RAYS / T_REF_STRIDE + 1];
    int32_t bp[T_RAYS / T_REF_STRIDE + 1];
    float *col[7];
    gyro_shape_soa tris;
    gyro_ray_soa sub;
    gyro_hit_soa sub_hits;
    int n = 0;
    static float cols[7][T_RAYS / T_REF_STRIDE + 1];
    for (k = 0; k < nt; ++k) {
      const uint32_t a = idx[3 * k], b = idx[3 * k + 1], c = idx[3 * k + 2];
      tax[k] = vx[a], tay[k] = vy[a], taz[k] = vz[a], tbx[k] = vx[b], tby[k] = vy[b], tbz[k] = vz[b];
      tcx[k] = vx[c], tcy[k] = vy[c], tcz[k] = vz[c];
    }
    for (i = 0; i < T_RAYS; i += T_REF_STRIDE, ++n) {
      cols[0][n] = rox[i], cols[1][n] = roy[i], cols[2][n] = roz[i], cols[3][n] = rdx[i], cols[4][n] = rdy[i];
      cols[5][n] = rdz[i], cols[6][n] = rtmax[i];
    }
    for (k = 0; k < 7; ++k) col[k] = cols[k];
    memset(&tris, 0, sizeof tris);
    tris.type = GYRO_SHAPE_TRIANGLE;
    tris.as.triangle.ax = tax, tris.as.triangle.ay = tay, tris.as.triangle.az = taz;
    tris.as.triangle.bx = tbx, tris.as.triangle.by = tby, tris.as.triangle.bz = tbz;
    tris.as.triangle.cx = tcx, tris.as.triangle.cy = tcy, tris.as.triangle.cz = tcz;
    sub.ox = col[0], sub.oy = col[1], sub.oz = col[2], sub.dx = col[3], sub.dy = col[4], sub.dz = col[5];
    sub.tmin = NULL, sub.tmax = col[6];
    sub_hits.t = bt, sub_hits.primitive = bp, sub_hits.nx = sub_hits.ny = sub_hits.nz = sub_hits.u = sub_hits.v = NULL;
    check(gyro_raycast_closest(&sub, n, &tris, nt, &sub_hits), "brute-force raycast");
    for (i = 0, k = 0; k < n; i += T_REF_STRIDE, ++k, ++checked)
      if (bp[k] != rp[i] || memcmp(&bt[k], &rt[i], sizeof(float)) != 0) ++disagree;
  }
  printf("hits: %d of %d rays (%.1f%%)\n", hitcount, T_RAYS, 100.0 * hitcount / T_RAYS);
  printf("error vs brute force over all %d triangles: %d of %d checked rays differ (same triangle, same t bits)\n", nt,
         disagree, checked);
  printf("determinism: %s (hash 0x%016llx)\n",
         same ? "every SIMD level and thread count gave identical bits" : "RESULTS DIFFER (bug)",
         (unsigned long long)first_hash);
  gyro_mesh_destroy(mesh);
  free(vx), free(vy), free(vz), free(idx), free(rox), free(roy), free(roz), free(rdx), free(rdy), free(rdz);
  free(rtmax), free(rt), free(rp), free(tax), free(tay), free(taz), free(tbx), free(tby), free(tbz), free(tcx);
  free(tcy), free(tcz);
  return same && disagree == 0 ? 0 : 1;
}


/* ---------------------------------------------------------------- pictures
 *
 * The rigid-body and cloth scenes are drawn by gyro's own batch raycaster: the world's
 * bodies become models of a gyro scene (boxes and spheres at their transforms, the cloth as
 * a mesh of its particles and triangles), a camera gives one picking ray per pixel, one
 * gyro_scene_raycast_closest call finds every pixel's surface and normal, one
 * gyro_scene_raycast_any call casts the shadow rays towards the light, and png_writer.c
 * writes the picture. */

#define PIC_W 640
#define PIC_H 360
#define PIC_PIXELS (PIC_W * PIC_H)
#define MAX_PICTURES 8
#define MAX_MODELS 1024

typedef enum { PATTERN_PLAIN = 0, PATTERN_GROUND = 1, PATTERN_CLOTH = 2 } pattern;

/* A body the demo created, with what a picture needs to know of it. */
typedef struct demo_body {
  gyro_body_id id;
  gyro_body_shape shape; /* sphere or box */
  float size[3];         /* radius, or half extents */
  float rgb[3];
  pattern pattern;
} demo_body;

/* A cloth to draw: its soft body and, per triangle, which colour of its checks it takes. */
typedef struct demo_cloth {
  gyro_soft_body_id id;
  const unsigned char* check; /* triangle_count entries */
  float rgb[2][3];
} demo_cloth;

typedef struct picture_view {
  float eye[3], target[3];
  float fov_y; /* radians */
  float light[3]; /* towards the light, unit */
  int floor; /* 1: a floor plane at floor_y (a backdrop, not part of the simulation) */
  float floor_y;
} picture_view;

typedef struct picture_report {
  char path[512];
  int models;
  long rays;
  double ms; /* in the two raycast calls */
} picture_report;

static const char* picture_dir = "build/demo";
static picture_report pictures[MAX_PICTURES];
static int picture_count = 0, picture_failed = 0;

/* The material of each model, by model index. */
static struct {
  float rgb[2][3];
  pattern pattern;
  const unsigned char* check;
} materials[MAX_MODELS];

/* Per-pixel buffers: camera rays and hits, shadow rays and hits, the picture. */
static struct {
  float *ox, *oy, *oz, *dx, *dy, *dz, *t, *nx, *ny, *nz;
  float *sox, *soy, *soz, *sdx, *sdy, *sdz, *st, *lit;
  gyro_model_id *model, *shadow_model;
  int32_t *prim, *shadow_prim, *shadow_pixel;
  unsigned char* rgb;
} px;

static int picture_buffers(void) {
  float** columns[] = {&px.ox, &px.oy, &px.oz, &px.dx, &px.dy, &px.dz, &px.t, &px.nx, &px.ny,
                       &px.nz, &px.sox, &px.soy, &px.soz, &px.sdx, &px.sdy, &px.sdz, &px.st, &px.lit};
  size_t i;
  if (px.rgb) return 1;
  for (i = 0; i < sizeof columns / sizeof columns[0]; ++i)
    if (!(*columns[i] = (float*)malloc(PIC_PIXELS * sizeof(float)))) return 0;
  px.model = (gyro_model_id*)malloc(PIC_PIXELS * sizeof *px.model);
  px.shadow_model = (gyro_model_id*)malloc(PIC_PIXELS * sizeof *px.shadow_model);
  px.prim = (int32_t*)malloc(PIC_PIXELS * sizeof *px.prim);
  px.shadow_prim = (int32_t*)malloc(PIC_PIXELS * sizeof *px.shadow_prim);
  px.shadow_pixel = (int32_t*)malloc(PIC_PIXELS * sizeof *px.shadow_pixel);
  px.rgb = (unsigned char*)malloc(3 * (size_t)PIC_PIXELS);
  return px.model && px.shadow_model && px.prim && px.shadow_prim && px.shadow_pixel && px.rgb;
}

static void picture_free(void) {
  float* columns[] = {px.ox, px.oy, px.oz, px.dx, px.dy, px.dz, px.t, px.nx, px.ny,
                      px.nz, px.sox, px.soy, px.soz, px.sdx, px.sdy, px.sdz, px.st, px.lit};
  size_t i;
  for (i = 0; i < sizeof columns / sizeof columns[0]; ++i) free(columns[i]);
  free(px.model), free(px.shadow_model), free(px.prim), free(px.shadow_prim), free(px.shadow_pixel), free(px.rgb);
  memset(&px, 0, sizeof px);
}

/* mkdir -p */
static int make_dirs(const char* path) {
  char buf[512];
  size_t i, n = strlen(path);
  if (n == 0 || n >= sizeof buf) return -1;
  memcpy(buf, path, n + 1);
  for (i = 1; i <= n; ++i)
    if (buf[i] == '/' || buf[i] == '\0') {
      const char c = buf[i];
      buf[i] = '\0';
      if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
      buf[i] = c;
    }
  return 0;
}

static void set_material(gyro_model_id id, const float* rgb, const float* rgb2, pattern p, const unsigned char* check) {
  if (id.index >= MAX_MODELS) return;
  memcpy(materials[id.index].rgb[0], rgb, 3 * sizeof(float));
  memcpy(materials[id.index].rgb[1], rgb2 ? rgb2 : rgb, 3 * sizeof(float));
  materials[id.index].pattern = p, materials[id.index].check = check;
}

static unsigned char to_srgb8(double linear) {
  const double c = linear <= 0 ? 0 : linear >= 1 ? 1 : linear;
  return (unsigned char)(255.0 * (c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055) + 0.5);
}

/* Draws the world's bodies (and a cloth) seen from view into picture_dir/name. */
static void render_picture(const char* name, gyro_world* world, const demo_body* bodies, int body_count,
                           const demo_cloth* cloth, const picture_view* view) {
  static const float ground_rgb[2][3] = {{0.50f, 0.50f, 0.48f}, {0.33f, 0.34f, 0.33f}};
  gyro_scene* scene = NULL;
  gyro_mesh* mesh = NULL;
  gyro_model_def def;
  gyro_model_id id;
  gyro_camera camera;
  gyro_ray_soa rays;
  gyro_scene_hit_soa hits;
  picture_report* report;
  const float up[3] = {0.0f, 1.0f, 0.0f};
  double start, ms;
  int i, shadows = 0;
  if (picture_count >= MAX_PICTURES || !picture_buffers() || make_dirs(picture_dir) != 0) {
    fprintf(stderr, "cannot render %s into %s\n", name, picture_dir);
    picture_failed = 1;
    return;
  }
  report = &pictures[picture_count++];
  snprintf(report->path, sizeof report->path, "%s/%s", picture_dir, name);
  memset(materials, 0, sizeof materials);

  check(gyro_scene_create(GYRO_SCENE_BVH, &scene), "scene");
  for (i = 0; i < body_count; ++i) {
    gyro_vec3 p;
    gyro_quat q;
    check(gyro_body_get_transform(world, bodies[i].id, &p, &q), "body transform");
    def = gyro_model_def_default();
    def.shape = bodies[i].shape == GYRO_BODY_SHAPE_SPHERE ? GYRO_MODEL_SPHERE : GYRO_MODEL_BOX;
    def.radius = bodies[i].size[0];
    def.half_extents[0] = bodies[i].size[0], def.half_extents[1] = bodies[i].size[1];
    def.half_extents[2] = bodies[i].size[2];
    def.transform.position[0] = p.x, def.transform.position[1] = p.y, def.transform.position[2] = p.z;
    def.transform.rotation[0] = q.x, def.transform.rotation[1] = q.y, def.transform.rotation[2] = q.z;
    def.transform.rotation[3] = q.w;
    check(gyro_scene_add_model(scene, &def, &id), "body model");
    set_material(id, bodies[i].rgb, bodies[i].pattern == PATTERN_GROUND ? ground_rgb[1] : NULL, bodies[i].pattern,
                 NULL);
  }
  if (cloth) {
    /* the cloth's current particles and triangles (the view stays valid: no step until we
     * are done) as a mesh; the scene keeps its own reference */
    gyro_soft_body_view sv;
    gyro_mesh_def md = gyro_mesh_def_default();
    check(gyro_soft_body_get_view(world, cloth->id, &sv), "cloth view");
    md.vertex_count = sv.count, md.x = sv.px, md.y = sv.py, md.z = sv.pz;
    md.indices = sv.triangles, md.triangle_count = sv.triangle_count;
    check(gyro_mesh_create(&md, &mesh), "cloth mesh");
    def = gyro_model_def_default();
    def.shape = GYRO_MODEL_MESH, def.mesh = mesh;
    check(gyro_scene_add_model(scene, &def, &id), "cloth model");
    gyro_mesh_destroy(mesh);
    set_material(id, cloth->rgb[0], cloth->rgb[1], PATTERN_CLOTH, cloth->check);
  }
  if (view->floor) {
    def = gyro_model_def_default();
    def.shape = GYRO_MODEL_PLANE;
    def.plane[0] = 0.0f, def.plane[1] = 1.0f, def.plane[2] = 0.0f, def.plane[3] = view->floor_y;
    check(gyro_scene_add_model(scene, &def, &id), "floor model");
    set_material(id, ground_rgb[0], ground_rgb[1], PATTERN_GROUND, NULL);
  }
  report->models = gyro_scene_model_count(scene);

  /* one picking ray through every pixel's centre */
  camera = gyro_camera_perspective(view->fov_y, (float)PIC_W / PIC_H, 0.05f, 500.0f);
  check(gyro_camera_look_at(&camera, view->eye, view->target, up), "look at");
  for (i = 0; i < PIC_PIXELS; ++i) {
    float o[3], d[3];
    check(gyro_camera_picking_ray(&camera, (float)(i % PIC_W) + 0.5f, (float)(i / PIC_W) + 0.5f, (float)PIC_W,
                                  (float)PIC_H, o, d),
          "picking ray");
    px.ox[i] = o[0], px.oy[i] = o[1], px.oz[i] = o[2], px.dx[i] = d[0], px.dy[i] = d[1], px.dz[i] = d[2];
  }
  rays.ox = px.ox, rays.oy = px.oy, rays.oz = px.oz, rays.dx = px.dx, rays.dy = px.dy, rays.dz = px.dz;
  rays.tmin = NULL, rays.tmax = NULL;
  memset(&hits, 0, sizeof hits);
  hits.t = px.t, hits.model = px.model, hits.primitive = px.prim, hits.nx = px.nx, hits.ny = px.ny, hits.nz = px.nz;
  start = now_ms();
  check(gyro_scene_raycast_closest(scene, &rays, PIC_PIXELS, &hits), "camera rays");
  ms = now_ms() - start;

  /* shadow rays from the hit points, lifted 2 mm off the surface, towards the light */
  for (i = 0; i < PIC_PIXELS; ++i) {
    float side;
    px.lit[i] = 0.0f;
    if (px.prim[i] < 0) continue;
    /* the normal of the side the camera sees (cloth triangles have two) */
    side = px.dx[i] * px.nx[i] + px.dy[i] * px.ny[i] + px.dz[i] * px.nz[i] > 0 ? -1.0f : 1.0f;
    px.nx[i] *= side, px.ny[i] *= side, px.nz[i] *= side;
    if (px.nx[i] * view->light[0] + px.ny[i] * view->light[1] + px.nz[i] * view->light[2] <= 0) continue;
    px.sox[shadows] = px.ox[i] + px.t[i] * px.dx[i] + 2e-3f * px.nx[i];
    px.soy[shadows] = px.oy[i] + px.t[i] * px.dy[i] + 2e-3f * px.ny[i];
    px.soz[shadows] = px.oz[i] + px.t[i] * px.dz[i] + 2e-3f * px.nz[i];
    px.sdx[shadows] = view->light[0], px.sdy[shadows] = view->light[1], px.sdz[shadows] = view->light[2];
    px.shadow_pixel[shadows++] = i;
  }
  rays.ox = px.sox, rays.oy = px.soy, rays.oz = px.soz, rays.dx = px.sdx, rays.dy = px.sdy, rays.dz = px.sdz;
  memset(&hits, 0, sizeof hits);
  hits.t = px.st, hits.model = px.shadow_model, hits.primitive = px.shadow_prim;
  start = now_ms();
  check(gyro_scene_raycast_any(scene, &rays, shadows, &hits), "shadow rays");
  ms += now_ms() - start;
  for (i = 0; i < shadows; ++i) px.lit[px.shadow_pixel[i]] = px.shadow_prim[i] < 0 ? 1.0f : 0.0f;
  report->rays = PIC_PIXELS + shadows;
  report->ms = ms;

  /* shade: sky where nothing was hit, else the model's colour lit by the sky and, where the
   * shadow ray got out, the sun (Lambert) */
  for (i = 0; i < PIC_PIXELS; ++i) {
    double c[3];
    int k;
    if (px.prim[i] < 0) {
      const double a = px.dy[i] > 0 ? px.dy[i] : 0;
      c[0] = 0.62 - 0.45 * a, c[1] = 0.72 - 0.40 * a, c[2] = 0.88 - 0.25 * a;
    } else {
      const unsigned m = px.model[i].index < MAX_MODELS ? px.model[i].index : 0;
      const double lambert = px.nx[i] * view->light[0] + px.ny[i] * view->light[1] + px.nz[i] * view->light[2];
      const double sun = (lambert > 0 ? lambert : 0) * px.lit[i], sky = 0.20 + 0.08 * px.ny[i];
      int which = 0;
      if (materials[m].pattern == PATTERN_GROUND) { /* 1 m checks */
        const double hx = px.ox[i] + (double)px.t[i] * px.dx[i], hz = px.oz[i] + (double)px.t[i] * px.dz[i];
        which = (int)(((long)floor(hx) + (long)floor(hz)) & 1);
      } else if (materials[m].pattern == PATTERN_CLOTH && materials[m].check) {
        which = materials[m].check[px.prim[i]];
      }
      for (k = 0; k < 3; ++k) c[k] = materials[m].rgb[which][k] * (sky + 0.9 * sun);
    }
    for (k = 0; k < 3; ++k) px.rgb[3 * i + k] = to_srgb8(c[k]);
  }
  gyro_scene_destroy(scene);
  if (png_write_rgb(report->path, PIC_W, PIC_H, px.rgb) != 0) {
    fprintf(stderr, "cannot write %s\n", report->path);
    picture_failed = 1;
  }
}

/* Rigid bodies: a pyramid of 55 boxes hit by a heavy ball, 240 steps at 60 Hz, at every SIMD
 * level (1 thread) and on 2 threads; the world hash after the run must be the same bits. */
#define PYR_BASE 10
#define PYR_STEPS 240
#define PYR_HIT_STEP 36 /* 0.6 s: the ball is in the pyramid */
static double pyramid_run(uint64_t* hash, double* drift, gyro_step_timings* timings, gyro_step_stats* stats,
                          int draw) {
  gyro_world* world;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd;
  gyro_body_id ids[PYR_BASE * (PYR_BASE + 1) / 2], id;
  float start[PYR_BASE * (PYR_BASE + 1) / 2][3];
  demo_body bodies[PYR_BASE * (PYR_BASE + 1) / 2 + 2];
  /* gyro's frame is the Cookbook's (left-handed): from -z, +x is to the right and the ball
   * comes in from the left */
  const picture_view view = {{6.0f, 6.5f, -20.0f}, {-0.5f, 3.6f, 0.0f}, 0.75f, {-0.48f, 0.78f, -0.40f}, 0, 0.0f};
  int row, k, n = 0, s, nb = 0;
  double t0, ms, step_ms = 0;
  check(gyro_world_create(&wd, &world), "world");
  bd = gyro_body_def_default();
  bd.type = GYRO_BODY_STATIC, bd.half_extents.x = 30, bd.half_extents.y = 0.5f, bd.half_extents.z = 30;
  bd.position.y = -0.5f;
  check(gyro_body_create(world, &bd, &id), "ground");
  bodies[nb].id = id, bodies[nb].shape = GYRO_BODY_SHAPE_BOX, bodies[nb].pattern = PATTERN_GROUND;
  bodies[nb].size[0] = 30.0f, bodies[nb].size[1] = 0.5f, bodies[nb].size[2] = 30.0f;
  bodies[nb].rgb[0] = 0.50f, bodies[nb].rgb[1] = 0.50f, bodies[nb].rgb[2] = 0.48f, ++nb;
  for (row = 0; row < PYR_BASE; ++row)
    for (k = 0; k < PYR_BASE - row; ++k) {
      bd = gyro_body_def_default();
      bd.position.x = (float)((k - (PYR_BASE - row - 1) * 0.5) * 1.1), bd.position.y = 0.5f + (float)row;
      check(gyro_body_create(world, &bd, &ids[n]), "box");
      start[n][0] = bd.position.x, start[n][1] = bd.position.y, start[n][2] = 0.0f;
      /* rows from brick red at the bottom to sand at the top */
      bodies[nb].id = ids[n], bodies[nb].shape = GYRO_BODY_SHAPE_BOX, bodies[nb].pattern = PATTERN_PLAIN;
      bodies[nb].size[0] = bodies[nb].size[1] = bodies[nb].size[2] = 0.5f;
      bodies[nb].rgb[0] = 0.55f + 0.035f * row, bodies[nb].rgb[1] = 0.12f + 0.05f * row;
      bodies[nb].rgb[2] = 0.06f + 0.025f * row + ((row + k) % 2) * 0.04f, ++nb;
      ++n;
    }
  bd = gyro_body_def_default();
  bd.shape = GYRO_BODY_SHAPE_SPHERE, bd.radius = 0.6f, bd.density = 20.0f;
  bd.position.x = -12.0f, bd.position.y = 2.0f, bd.linear_velocity.x = 14.0f, bd.linear_velocity.y = 2.0f;
  check(gyro_body_create(world, &bd, &id), "ball");
  bodies[nb].id = id, bodies[nb].shape = GYRO_BODY_SHAPE_SPHERE, bodies[nb].pattern = PATTERN_PLAIN;
  bodies[nb].size[0] = bd.radius, bodies[nb].size[1] = bodies[nb].size[2] = 0.0f;
  bodies[nb].rgb[0] = 0.08f, bodies[nb].rgb[1] = 0.20f, bodies[nb].rgb[2] = 0.55f, ++nb;
  for (s = 0; s < PYR_STEPS; ++s) {
    t0 = now_ms();
    check(gyro_world_step(world, 1.0f / 60.0f), "step");
    step_ms += now_ms() - t0;
    if (draw && s + 1 == PYR_HIT_STEP) render_picture("pyramid_hit.png", world, bodies, nb, NULL, &view);
  }
  ms = step_ms / PYR_STEPS;
  if (draw) render_picture("pyramid_after.png", world, bodies, nb, NULL, &view);
  *drift = 0;
  for (k = 0; k < n; ++k) {
    gyro_vec3 p;
    double d;
    check(gyro_body_get_transform(world, ids[k], &p, NULL), "transform");
    d = sqrt((p.x - start[k][0]) * (p.x - start[k][0]) + (p.y - start[k][1]) * (p.y - start[k][1]) +
             (p.z - start[k][2]) * (p.z - start[k][2]));
    if (d > *drift) *drift = d;
  }
  check(gyro_world_hash(world, hash), "hash");
  check(gyro_world_get_timings(world, timings), "timings");
  check(gyro_world_get_stats(world, stats), "stats");
  gyro_world_destroy(world);
  return ms;
}

static int pyramid_demo(void) {
  gyro_simd_level level, best = GYRO_SIMD_SCALAR;
  uint64_t first = 0, h;
  double ms, drift, best_ms = 1e300;
  int same = 1;
  gyro_step_timings tm;
  gyro_step_stats st;
  printf("\nrigid bodies: a pyramid of %d boxes hit by a ball, %d steps at 60 Hz (soft step, 8 sub-steps x 2 "
         "iterations)\n", PYR_BASE * (PYR_BASE + 1) / 2, PYR_STEPS);
  printf("  %-8s %7s %10s  %s\n", "simd", "threads", "ms/step", "world hash");
  for (level = GYRO_SIMD_SCALAR; level <= GYRO_SIMD_NEON; ++level) {
    if (!gyro_simd_level_available(level)) continue;
    check(gyro_set_simd_level(level), "set level");
    check(gyro_set_thread_count(1), "set threads");
    ms = pyramid_run(&h, &drift, &tm, &st, 0);
    if (level == GYRO_SIMD_SCALAR) first = h;
    if (ms < best_ms) best_ms = ms, best = level;
    same = same && h == first;
    printf("  %-8s %7u %10.3f  0x%016llx\n", gyro_simd_level_name(level), 1u, ms, (unsigned long long)h);
  }
  check(gyro_set_simd_level(best), "set level");
  check(gyro_set_thread_count(2), "set threads");
  ms = pyramid_run(&h, &drift, &tm, &st, 1); /* this run also draws its pictures */
  same = same && h == first;
  printf("  %-8s %7u %10.3f  0x%016llx\n", gyro_simd_level_name(best), 2u, ms, (unsigned long long)h);
  printf("last step: broadphase %.3f ms, narrowphase %.3f, islands %.3f, solver %.3f, total %.3f; %u bodies, %u "
         "contacts in %u manifolds, %u colours\n",
         tm.broadphase, tm.narrowphase, tm.islands, tm.solver, tm.total, st.bodies, st.contacts, st.manifolds, st.colors);
  printf("largest box displacement after the hit: %.2f m\n", drift);
  printf("determinism: %s (hash 0x%016llx)\n",
         same ? "every SIMD level and thread count gave identical bits" : "RESULTS DIFFER (bug)", (unsigned long long)first);
  return same ? 0 : 1;
}

/* Cloth: a 32 x 32 cloth (2 x 2 m, XPBD, 16 sub-steps) pinned at two corners falls onto a
 * static sphere and drapes over it, 120 steps at 60 Hz, at every SIMD level (1 thread) and on
 * 2 threads; the world hash (which covers the cloth) must be the same bits. */
#define CLOTH_N 32
#define CLOTH_STEPS 120
static const float cloth_sphere[4] = {0.0f, 0.3f, 0.2f, 0.5f}; /* centre, radius */

/* Draws the draped cloth: its triangles checked in 4 x 4 cells of the grid. */
static void draw_cloth(gyro_world* world, gyro_soft_body_id cloth, gyro_body_id sphere, double min_y) {
  static unsigned char check_of[2 * (CLOTH_N - 1) * (CLOTH_N - 1)];
  int cell_of[CLOTH_N * CLOTH_N][2];
  const picture_view view = {{2.3f, 1.75f, 3.1f}, {0.0f, 0.28f, 0.15f}, 0.72f, {-0.46f, 0.80f, 0.38f}, 1, 0.0f};
  demo_body body;
  demo_cloth dc;
  gyro_soft_body_view sv;
  picture_view v = view;
  uint32_t ix, iz, p;
  int32_t tri, k;
  memset(cell_of, 0, sizeof cell_of);
  for (iz = 0; iz < CLOTH_N; ++iz)
    for (ix = 0; ix < CLOTH_N; ++ix) {
      check(gyro_soft_body_cloth_index(world, cloth, ix, iz, &p), "cloth index");
      if (p < CLOTH_N * CLOTH_N) cell_of[p][0] = (int)ix, cell_of[p][1] = (int)iz;
    }
  check(gyro_soft_body_get_view(world, cloth, &sv), "view");
  for (tri = 0; tri < sv.triangle_count && tri < (int32_t)sizeof check_of; ++tri) {
    int lo_x = CLOTH_N, lo_z = CLOTH_N;
    for (k = 0; k < 3; ++k) {
      const uint32_t q = sv.triangles[3 * tri + k];
      if (q < CLOTH_N * CLOTH_N && cell_of[q][0] < lo_x) lo_x = cell_of[q][0];
      if (q < CLOTH_N * CLOTH_N && cell_of[q][1] < lo_z) lo_z = cell_of[q][1];
    }
    check_of[tri] = (unsigned char)((lo_x / 4 + lo_z / 4) & 1);
  }
  body.id = sphere, body.shape = GYRO_BODY_SHAPE_SPHERE, body.pattern = PATTERN_PLAIN;
  body.size[0] = cloth_sphere[3], body.size[1] = body.size[2] = 0.0f;
  body.rgb[0] = 0.10f, body.rgb[1] = 0.30f, body.rgb[2] = 0.62f;
  dc.id = cloth, dc.check = check_of;
  dc.rgb[0][0] = 0.85f, dc.rgb[0][1] = 0.80f, dc.rgb[0][2] = 0.68f;
  dc.rgb[1][0] = 0.70f, dc.rgb[1][1] = 0.16f, dc.rgb[1][2] = 0.12f;
  /* a floor just below the cloth and the sphere, as a backdrop for the shadows (the
   * simulated world has none) */
  v.floor_y = (float)((min_y < cloth_sphere[1] - cloth_sphere[3] ? min_y : cloth_sphere[1] - cloth_sphere[3]) - 0.02);
  render_picture("cloth.png", world, &body, 1, &dc, &v);
}

static double cloth_run(uint64_t* hash, double* soft_ms, double* max_strain, double* min_gap, int draw) {
  gyro_world* world;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd = gyro_body_def_default();
  gyro_cloth_def cd = gyro_cloth_def_default();
  gyro_soft_body_id cloth;
  gyro_body_id sphere;
  gyro_soft_body_view view;
  gyro_soft_body_stats stats;
  uint32_t corner;
  int s;
  int32_t i;
  double t0, ms, stage, run_ms;
  check(gyro_world_create(&wd, &world), "world");
  bd.type = GYRO_BODY_STATIC, bd.shape = GYRO_BODY_SHAPE_SPHERE, bd.radius = cloth_sphere[3];
  bd.position.x = cloth_sphere[0], bd.position.y = cloth_sphere[1], bd.position.z = cloth_sphere[2];
  check(gyro_body_create(world, &bd, &sphere), "sphere");
  cd.nx = cd.nz = CLOTH_N, cd.size_x = cd.size_z = 2.0f, cd.center.y = 1.0f, cd.particle_mass = 0.005f;
  check(gyro_world_create_cloth(world, &cd, &cloth), "cloth");
  check(gyro_soft_body_cloth_index(world, cloth, 0, 0, &corner), "corner");
  check(gyro_soft_body_pin(world, cloth, corner), "pin");
  check(gyro_soft_body_cloth_index(world, cloth, CLOTH_N - 1, 0, &corner), "corner");
  check(gyro_soft_body_pin(world, cloth, corner), "pin");
  *soft_ms = 0;
  t0 = now_ms();
  *min_gap = 1e300;
  run_ms = 0;
  for (s = 0; s < CLOTH_STEPS; ++s) {
    t0 = now_ms();
    check(gyro_world_step(world, 1.0f / 60.0f), "step");
    run_ms += now_ms() - t0;
    check(gyro_world_get_stage_time(world, GYRO_STAGE_SOFT_BODIES, &stage), "stage time");
    *soft_ms += stage;
    /* the closest any particle comes to the sphere's surface over the run (the view is
     * valid until the next step) */
    check(gyro_soft_body_get_view(world, cloth, &view), "view");
    for (i = 0; i < view.count; ++i) {
      const double dx = view.px[i] - cloth_sphere[0], dy = view.py[i] - cloth_sphere[1],
                   dz = view.pz[i] - cloth_sphere[2];
      const double gap = sqrt(dx * dx + dy * dy + dz * dz) - cloth_sphere[3];
      if (gap < *min_gap) *min_gap = gap;
    }
  }
  ms = run_ms / CLOTH_STEPS;
  *soft_ms /= CLOTH_STEPS;
  check(gyro_soft_body_get_stats(world, cloth, &stats), "stats");
  *max_strain = stats.max_strain;
  check(gyro_world_hash(world, hash), "hash");
  if (draw) draw_cloth(world, cloth, sphere, stats.min_y);
  gyro_world_destroy(world);
  return ms;
}

static int cloth_demo(void) {
  gyro_simd_level level, best = GYRO_SIMD_SCALAR;
  uint64_t first = 0, h;
  double ms, soft_ms, strain, gap, best_ms = 1e300, min_gap = 1e300;
  int same = 1;
  printf("\ncloth: %d x %d particles pinned at two corners, draped over a sphere (r %.1f m), %d steps at 60 Hz "
         "(XPBD, 16 sub-steps)\n", CLOTH_N, CLOTH_N, cloth_sphere[3], CLOTH_STEPS);
  printf("  %-8s %7s %10s %10s %11s %13s  %s\n", "simd", "threads", "ms/step", "cloth ms", "max strain", "min gap mm",
         "world hash");
  for (level = GYRO_SIMD_SCALAR; level <= GYRO_SIMD_NEON + 1; ++level) {
    /* every level on one thread, then the fastest on 2 threads */
    const int two = level == GYRO_SIMD_NEON + 1;
    if (!two && !gyro_simd_level_available(level)) continue;
    check(gyro_set_simd_level(two ? best : level), "set level");
    check(gyro_set_thread_count(two ? 2 : 1), "set threads");
    ms = cloth_run(&h, &soft_ms, &strain, &gap, two); /* the 2-thread run draws its picture */
    if (level == GYRO_SIMD_SCALAR) first = h;
    if (!two && ms < best_ms) best_ms = ms, best = level;
    same = same && h == first;
    if (gap < min_gap) min_gap = gap;
    printf("  %-8s %7u %10.3f %10.3f %11.2e %13.3f  0x%016llx\n", gyro_simd_level_name(two ? best : level),
           two ? 2u : 1u, ms, soft_ms, strain, gap * 1e3, (unsigned long long)h);
  }
  printf("cloth stays outside the sphere: %s (closest particle %.3f mm from its surface)\n",
         min_gap >= 0 ? "yes" : "NO (bug)", min_gap * 1e3);
  printf("determinism: %s (hash 0x%016llx)\n",
         same ? "every SIMD level and thread count gave identical bits" : "RESULTS DIFFER (bug)", (unsigned long long)first);
  return same && min_gap >= 0 ? 0 : 1;
}

/* The pictures' report: where they are and how fast gyro drew them. */
static int report_pictures(void) {
  int i;
  long rays = 0;
  double ms = 0;
  if (picture_count == 0) return 0;
  printf("\npictures: %d x %d, drawn by gyro's scene raycaster (camera picking rays, then shadow rays; "
         "%u thread(s))\n", PIC_W, PIC_H, gyro_get_thread_count());
  printf("  %-40s %7s %9s %9s %9s\n", "file", "models", "rays", "ms", "Mrays/s");
  for (i = 0; i < picture_count; ++i) {
    printf("  %-40s %7d %9ld %9.1f %9.2f\n", pictures[i].path, pictures[i].models, pictures[i].rays, pictures[i].ms,
           pictures[i].rays / pictures[i].ms / 1e3);
    rays += pictures[i].rays, ms += pictures[i].ms;
  }
  printf("render: %ld rays in %.1f ms, %.2f Mrays/s%s\n", rays, ms, rays / ms / 1e3,
         picture_failed ? " (SOME PICTURES FAILED)" : "");
  picture_free();
  return picture_failed ? 1 : 0;
}

/* Usage: gyro-demo [DIR]: the pictures go to DIR (default build/demo), created if needed. */
int main(int argc, char** argv) {
  int i, c, hits = 0, disagree = 0, checked = 0, same = 1;
  double max_dt = 0, scalar_ms = 0, best_ms = 1e300;
  uint64_t first_hash = 0;
  gyro_simd_level level, best_level = GYRO_SIMD_SCALAR;
  uint32_t threads, max_threads;

  float** cols[] = {&cx, &cy, &cz, &cr, &ox, &oy, &oz, &dx, &dy, &dz, &tmax, &t, &nx, &ny, &nz};
  for (i = 0; i < (int)(sizeof cols / sizeof cols[0]); ++i) {
    *cols[i] = (float*)malloc(RAYS * sizeof(float));
    if (!*cols[i]) return 1;
  }
  prim = (int32_t*)malloc(RAYS * sizeof *prim);
  if (!prim) return 1;
  if (argc > 1) picture_dir = argv[1];

  /* The scene: spheres in a 200 x 30 x 200 m block around the sensor, 0.3 to 2.3 m. */
  for (i = 0; i < SPHERES; ++i) {
    cx[i] = (float)(rng_u() * 200 - 100), cy[i] = (float)(rng_u() * 30 - 5), cz[i] = (float)(rng_u() * 200 - 100);
    cr[i] = (float)(0.3 + 2.0 * rng_u());
  }
  /* The lidar: 32 channels from -15 to +15 degrees elevation, 1,024 columns per turn. */
  for (c = 0; c < CHANNELS; ++c) {
    double el = (-15.0 + 30.0 * c / (CHANNELS - 1)) * 3.14159265358979 / 180.0;
    for (i = 0; i < COLUMNS; ++i) {
      double az = 2 * 3.14159265358979 * i / COLUMNS;
      int k = c * COLUMNS + i;
      ox[k] = 0, oy[k] = 1.8f, oz[k] = 0;
      dx[k] = (float)(cos(el) * cos(az)), dy[k] = (float)sin(el), dz[k] = (float)(cos(el) * sin(az));
      tmax[k] = RANGE;
    }
  }

  printf("gyro %s demo: %d lidar rays (%d channels x %d columns, %.0f m) against %d spheres, brute force\n",
         gyro_version_string(), RAYS, CHANNELS, COLUMNS, RANGE, SPHERES);
  printf("  %-8s %7s %10s %9s %9s  %s\n", "simd", "threads", "time ms", "Mrays/s", "speed-up", "result hash");
  max_threads = gyro_get_thread_count();
  for (level = GYRO_SIMD_SCALAR; level <= GYRO_SIMD_NEON; ++level) {
    uint64_t h;
    double ms;
    if (!gyro_simd_level_available(level)) continue;
    check(gyro_set_simd_level(level), "set level");
    check(gyro_set_thread_count(1), "set threads");
    ms = run(&h);
    if (level == GYRO_SIMD_SCALAR) scalar_ms = ms, first_hash = h;
    if (ms < best_ms) best_ms = ms, best_level = level;
    same = same && h == first_hash;
    printf("  %-8s %7u %10.2f %9.3f %8.1fx  0x%016llx\n", gyro_simd_level_name(level), 1u, ms, RAYS / ms / 1e3,
           scalar_ms / ms, (unsigned long long)h);
  }
  check(gyro_set_simd_level(best_level), "set level");
  for (threads = 2; threads <= (max_threads > 2 ? max_threads : 2); threads *= 2) {
    uint64_t h;
    double ms;
    check(gyro_set_thread_count(threads), "set threads");
    ms = run(&h);
    same = same && h == first_hash;
    printf("  %-8s %7u %10.2f %9.3f %8.1fx  0x%016llx\n", gyro_simd_level_name(best_level), threads, ms,
           RAYS / ms / 1e3, scalar_ms / ms, (unsigned long long)h);
  }

  for (i = 0; i < RAYS; ++i) hits += prim[i] >= 0;
  for (i = 0; i < RAYS; i += REF_STRIDE) {
    const float o[3] = {ox[i], oy[i], oz[i]}, d[3] = {dx[i], dy[i], dz[i]};
    double rt;
    int rp = ref_cast(o, d, tmax[i], cx, cy, cz, cr, &rt);
    ++checked;
    if (rp != prim[i]) {
      ++disagree;
    } else if (rp >= 0 && fabs(rt - t[i]) > max_dt) {
      max_dt = fabs(rt - t[i]);
    }
  }
  printf("hits: %d of %d rays (%.1f%%)\n", hits, RAYS, 100.0 * hits / RAYS);
  printf("error vs double precision: %d of %d checked rays disagree, max |dt| = %.2e m\n", disagree, checked, max_dt);
  printf("determinism: %s (hash 0x%016llx)\n",
         same ? "every SIMD level and thread count gave identical bits" : "RESULTS DIFFER (bug)",
         (unsigned long long)first_hash);
  for (i = 0; i < (int)(sizeof cols / sizeof cols[0]); ++i) free(*cols[i]);
  free(prim);
  if (!(same && disagree == 0)) return 1;
  if ((gyro_features() & GYRO_FEATURE_SPATIAL) && terrain_demo() != 0) return 1;
  if ((gyro_features() & GYRO_FEATURE_DYNAMICS) && pyramid_demo() != 0) return 1;
  if ((gyro_features() & GYRO_FEATURE_SOFT_BODIES) && cloth_demo() != 0) return 1;
  return report_pictures();
}
