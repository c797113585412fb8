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
 * run at every SIMD level and on 2 threads, and their world hashes must agree. */
#define _POSIX_C_SOURCE 199309L
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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


/* Rigid bodies: a pyramid of 55 boxes hit by a heavy ball, 240 steps at 60 Hz, at every SIMD
 * level (1 thread) and on 2 threads; the world hash after the run must be the same bits. */
#define PYR_BASE 10
#define PYR_STEPS 240
static double pyramid_run(uint64_t* hash, double* drift, gyro_step_timings* timings, gyro_step_stats* stats) {
  gyro_world* world;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd;
  gyro_body_id ids[PYR_BASE * (PYR_BASE + 1) / 2], id;
  float start[PYR_BASE * (PYR_BASE + 1) / 2][3];
  int row, k, n = 0, s;
  double t0, ms;
  check(gyro_world_create(&wd, &world), "world");
  bd = gyro_body_def_default();
  bd.type = GYRO_BODY_STATIC, bd.half_extents.x = 30, bd.half_extents.y = 0.5f, bd.half_extents.z = 30;
  bd.position.y = -0.5f;
  check(gyro_body_create(world, &bd, &id), "ground");
  for (row = 0; row < PYR_BASE; ++row)
    for (k = 0; k < PYR_BASE - row; ++k) {
      bd = gyro_body_def_default();
      bd.position.x = (float)((k - (PYR_BASE - row - 1) * 0.5) * 1.1), bd.position.y = 0.5f + (float)row;
      check(gyro_body_create(world, &bd, &ids[n]), "box");
      start[n][0] = bd.position.x, start[n][1] = bd.position.y, start[n][2] = 0.0f;
      ++n;
    }
  bd = gyro_body_def_default();
  bd.shape = GYRO_BODY_SHAPE_SPHERE, bd.radius = 0.6f, bd.density = 20.0f;
  bd.position.x = -12.0f, bd.position.y = 2.0f, bd.linear_velocity.x = 14.0f, bd.linear_velocity.y = 2.0f;
  check(gyro_body_create(world, &bd, &id), "ball");
  t0 = now_ms();
  for (s = 0; s < PYR_STEPS; ++s) check(gyro_world_step(world, 1.0f / 60.0f), "step");
  ms = (now_ms() - t0) / PYR_STEPS;
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
    ms = pyramid_run(&h, &drift, &tm, &st);
    if (level == GYRO_SIMD_SCALAR) first = h;
    if (ms < best_ms) best_ms = ms, best = level;
    same = same && h == first;
    printf("  %-8s %7u %10.3f  0x%016llx\n", gyro_simd_level_name(level), 1u, ms, (unsigned long long)h);
  }
  check(gyro_set_simd_level(best), "set level");
  check(gyro_set_thread_count(2), "set threads");
  ms = pyramid_run(&h, &drift, &tm, &st);
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

static double cloth_run(uint64_t* hash, double* soft_ms, double* max_strain, double* min_gap) {
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
    ms = cloth_run(&h, &soft_ms, &strain, &gap);
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

int main(void) {
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
  return (gyro_features() & GYRO_FEATURE_SOFT_BODIES) ? cloth_demo() : 0;
}
