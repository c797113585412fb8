/* gyro demo: the embedded default scene through the C ABI.
 *
 * A 32-channel lidar (1,024 columns per turn, 120 m range) sits in a field of 1,024
 * spheres. Every ray is cast against every sphere (the brute-force batch kernel) at each
 * SIMD level this CPU has, then with more threads. The report gives rays/s, the speed-up
 * over the scalar level, the error against a double-precision reference, and a hash of
 * the results, which is the same at every level and thread count: gyro is deterministic. */
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
  return same && disagree == 0 ? 0 : 1;
}
