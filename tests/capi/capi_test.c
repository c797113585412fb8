/* The C ABI from a C99 program: versions, settings, a batch raycast, and bad input that
 * must get a clear status and write nothing. */
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

#define N 37
#define POISON_T 12345.0f
#define POISON_P 777

static float ox[N], oy[N], oz[N], dx[N], dy[N], dz[N];
static float cx[3] = {0, 10, 0}, cy[3] = {0, 0, 10}, cz[3] = {0, 0, 0}, cr[3] = {1, 2, 0.5f};
static float t[N], nx[N], ny[N], nz[N];
static int32_t prim[N];

static void poison(void) {
  int i;
  for (i = 0; i < N; ++i) t[i] = POISON_T, prim[i] = POISON_P, nx[i] = ny[i] = nz[i] = POISON_T;
}
static int untouched(void) {
  int i;
  for (i = 0; i < N; ++i)
    if (t[i] != POISON_T || prim[i] != POISON_P || nx[i] != POISON_T) return 0;
  return 1;
}

int main(void) {
  gyro_ray_soa rays;
  gyro_sphere_soa spheres;
  gyro_hit_soa hits;
  int i;
  uint32_t v;

  CHECK(gyro_abi_version() >> 16 == GYRO_ABI_VERSION >> 16);
  CHECK(strlen(gyro_version_string()) > 0);
  CHECK(gyro_features() & GYRO_FEATURE_MATH);
  CHECK(sizeof(gyro_ray_soa) == 8 * sizeof(void*));
  CHECK(sizeof(gyro_status) == 4 && sizeof(gyro_simd_level) == 4);
  CHECK(strcmp(gyro_status_name(GYRO_STATUS_NON_FINITE), "non_finite") == 0);
  CHECK(strcmp(gyro_status_name(-3), "unknown_status") == 0);

  /* Settings */
  CHECK(gyro_simd_level_available(GYRO_SIMD_SCALAR));
  CHECK(gyro_set_simd_level(GYRO_SIMD_SCALAR) == GYRO_OK);
  CHECK(gyro_get_simd_level() == GYRO_SIMD_SCALAR);
  CHECK(strcmp(gyro_simd_level_name(GYRO_SIMD_SCALAR), "scalar") == 0);
  CHECK(gyro_set_simd_level(77) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_get_simd_level() == GYRO_SIMD_SCALAR);
  CHECK(gyro_set_simd_level(GYRO_SIMD_AUTO) == GYRO_OK);
  for (v = GYRO_SIMD_SCALAR; v <= GYRO_SIMD_NEON; ++v)
    if (!gyro_simd_level_available(v)) CHECK(gyro_set_simd_level(v) == GYRO_STATUS_UNSUPPORTED);
  CHECK(gyro_set_thread_count(2) == GYRO_OK);
  CHECK(gyro_set_thread_count(100000) == GYRO_STATUS_INVALID_COUNT);
  CHECK(strstr(gyro_last_error(), "1024") != NULL);
  CHECK(gyro_set_thread_count(0) == GYRO_OK);

  /* A fan of rays from (-5, 0, 0) towards +x: the middle ones hit sphere 0 at t = 4. */
  for (i = 0; i < N; ++i) {
    float a = (float)(i - N / 2) * 0.02f;
    ox[i] = -5, oy[i] = 0, oz[i] = 0;
    dx[i] = cosf(a), dy[i] = sinf(a), dz[i] = 0;
  }
  rays.ox = ox, rays.oy = oy, rays.oz = oz, rays.dx = dx, rays.dy = dy, rays.dz = dz;
  rays.tmin = NULL, rays.tmax = NULL;
  spheres.cx = cx, spheres.cy = cy, spheres.cz = cz, spheres.r = cr;
  hits.t = t, hits.primitive = prim, hits.nx = nx, hits.ny = ny, hits.nz = nz, hits.u = NULL, hits.v = NULL;

  poison();
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_OK);
  CHECK(prim[N / 2] == 0 && fabsf(t[N / 2] - 4.0f) < 1e-6f && fabsf(nx[N / 2] + 1.0f) < 1e-6f);
  for (i = 0; i < N; ++i) CHECK(prim[i] == -1 || prim[i] == 0 || prim[i] == 1);
  for (i = 0; i < N; ++i) CHECK(prim[i] >= 0 ? t[i] > 0 : t[i] == INFINITY);

  /* Bad input: a clear status, a message, nothing written. */
  poison();
  CHECK(gyro_raycast_spheres_closest(NULL, N, &spheres, 3, &hits) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_raycast_spheres_closest(&rays, N, NULL, 3, &hits) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_raycast_spheres_closest(&rays, -1, &spheres, 3, &hits) == GYRO_STATUS_INVALID_COUNT);
  CHECK(strstr(gyro_last_error(), "ray_count") != NULL);
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, -5, &hits) == GYRO_STATUS_INVALID_COUNT);
  rays.dz = NULL;
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(strstr(gyro_last_error(), "rays.dz") != NULL);
  rays.dz = dz;
  dx[5] = NAN;
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_STATUS_NON_FINITE);
  CHECK(strstr(gyro_last_error(), "rays.dx[5]") != NULL);
  dx[5] = 1.0f;
  cr[1] = -2.0f;
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_STATUS_INVALID_ARGUMENT);
  cr[1] = INFINITY;
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_STATUS_NON_FINITE);
  cr[1] = 2.0f;
  hits.ny = NULL;
  CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_STATUS_NULL_ARGUMENT);
  hits.ny = ny;
  CHECK(untouched());

  /* Results do not depend on the SIMD level or threads: compare every available level. */
  {
    float ref_t[N];
    int32_t ref_p[N];
    CHECK(gyro_set_simd_level(GYRO_SIMD_SCALAR) == GYRO_OK);
    CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_OK);
    memcpy(ref_t, t, sizeof t), memcpy(ref_p, prim, sizeof prim);
    for (v = GYRO_SIMD_SSE2; v <= GYRO_SIMD_NEON; ++v) {
      if (!gyro_simd_level_available(v)) continue;
      CHECK(gyro_set_simd_level(v) == GYRO_OK);
      poison();
      CHECK(gyro_raycast_spheres_closest(&rays, N, &spheres, 3, &hits) == GYRO_OK);
      CHECK(memcmp(ref_t, t, sizeof t) == 0 && memcmp(ref_p, prim, sizeof prim) == 0);
    }
    CHECK(gyro_set_simd_level(GYRO_SIMD_AUTO) == GYRO_OK);
  }

  /* Batch overlap: OBB pairs. Unit boxes at x = 0 and x = d, the second turned 45 degrees
   * about z (its half width along x is then sqrt(2)): overlapping while d <= 1 + sqrt(2). */
  {
    enum { M = 6 };
    static float acx[M], acy[M], acz[M], ae[M], bcx[M], u0x[M], u0y[M], u1x[M], u1y[M], zero[M], one[M];
    const float d[M] = {0.0f, 1.0f, 2.4f, 2.42f, 3.0f, 1.0f};
    const uint32_t expect[M] = {GYRO_OVERLAPPING, GYRO_OVERLAPPING, GYRO_OVERLAPPING, GYRO_SEPARATED, GYRO_SEPARATED,
                                GYRO_INVALID_INPUT};
    const float s = 0.70710678f;
    gyro_shape_soa a, b;
    uint32_t out[M];
    float sep[M];
    memset(&a, 0, sizeof a), memset(&b, 0, sizeof b);
    for (i = 0; i < M; ++i) {
      acx[i] = 0, acy[i] = 0, acz[i] = 0, ae[i] = 1, bcx[i] = d[i], zero[i] = 0, one[i] = 1;
      u0x[i] = s, u0y[i] = s, u1x[i] = -s, u1y[i] = s;
    }
    ae[M - 1] = NAN; /* the last pair is invalid */
    a.type = GYRO_SHAPE_OBB, b.type = GYRO_SHAPE_OBB;
    a.as.obb.cx = acx, a.as.obb.cy = acy, a.as.obb.cz = acz, a.as.obb.ex = ae, a.as.obb.ey = one, a.as.obb.ez = one;
    a.as.obb.u0x = one, a.as.obb.u0y = zero, a.as.obb.u0z = zero, a.as.obb.u1x = zero, a.as.obb.u1y = one;
    a.as.obb.u1z = zero, a.as.obb.u2x = zero, a.as.obb.u2y = zero, a.as.obb.u2z = one;
    b.as.obb = a.as.obb;
    b.as.obb.cx = bcx, b.as.obb.ex = one;
    b.as.obb.u0x = u0x, b.as.obb.u0y = u0y, b.as.obb.u1x = u1x, b.as.obb.u1y = u1y;
    CHECK(sizeof(gyro_shape_soa) == 8 + 15 * sizeof(void*));
    CHECK(gyro_overlap_pairwise(&a, &b, M, out, 0) == GYRO_OK);
    for (i = 0; i < M; ++i) CHECK(out[i] == expect[i]);
    CHECK(gyro_overlap_pairwise(&b, &a, M, out, 0) == GYRO_OK); /* symmetric */
    for (i = 0; i < M; ++i) CHECK(out[i] == expect[i]);
    CHECK(gyro_overlap_one_against_many(&a, &b, M - 1, out, 0) == GYRO_OK);
    for (i = 0; i < M - 1; ++i) CHECK(out[i] == expect[i]);
    for (i = 0; i < M; ++i) out[i] = 99;
    CHECK(gyro_overlap_pairwise(&a, &b, M, out, GYRO_BATCH_STRICT) == GYRO_STATUS_NON_FINITE);
    CHECK(strstr(gyro_last_error(), "a.ex[5]") != NULL);
    CHECK(gyro_overlap_pairwise(&a, &b, -1, out, 0) == GYRO_STATUS_INVALID_COUNT);
    CHECK(gyro_overlap_pairwise(NULL, &b, M, out, 0) == GYRO_STATUS_NULL_ARGUMENT);
    CHECK(gyro_overlap_pairwise(&a, &b, M, NULL, 0) == GYRO_STATUS_NULL_ARGUMENT);
    CHECK(gyro_overlap_pairwise(&a, &b, M, out, 0x40) == GYRO_STATUS_INVALID_ARGUMENT);
    b.type = 42;
    CHECK(gyro_overlap_pairwise(&a, &b, M, out, 0) == GYRO_STATUS_INVALID_ARGUMENT);
    b.type = GYRO_SHAPE_OBB;
    for (i = 0; i < M; ++i) CHECK(out[i] == 99); /* nothing written on failure */
    CHECK(gyro_obb_separation_pairwise(&a.as.obb, &b.as.obb, M - 1, sep) == GYRO_OK);
    CHECK(fabsf(sep[0] + 2.0f) < 1e-5f); /* concentric: the least depth is along z, 1 + 1 */
    CHECK(fabsf(sep[4] - (3.0f - 1.0f - 1.41421356f)) < 1e-5f);
  }

  /* Batch raycasts against AABBs and triangles: closest and any hit. A row of unit boxes
   * at x = 2, 4, 6 and a triangle in the plane x = 3; rays along +x from the origin. */
  {
    static float bcx[3] = {6, 2, 4}, bzero[3] = {0, 0, 0}, bone[3] = {1, 1, 1};
    static float tax[1] = {3}, tay[1] = {-5}, taz[1] = {-5}, tbx[1] = {3}, tby[1] = {5}, tbz[1] = {-5};
    static float tcx[1] = {3}, tcy[1] = {0}, tcz[1] = {5};
    static float rox[2] = {0, 0}, roy[2] = {0, 0.5f}, roz[2] = {0, 0}, rdx[2] = {1, 1}, rdy[2] = {0, 0}, rdz[2] = {0, 0};
    float rt[2], rnx[2], rny[2], rnz[2], ru[2], rv[2];
    int32_t rp[2];
    gyro_ray_soa r;
    gyro_shape_soa boxes, tris;
    gyro_hit_soa h;
    memset(&boxes, 0, sizeof boxes), memset(&tris, 0, sizeof tris), memset(&h, 0, sizeof h);
    r.ox = rox, r.oy = roy, r.oz = roz, r.dx = rdx, r.dy = rdy, r.dz = rdz, r.tmin = NULL, r.tmax = NULL;
    boxes.type = GYRO_SHAPE_AABB;
    boxes.as.aabb.cx = bcx, boxes.as.aabb.cy = bzero, boxes.as.aabb.cz = bzero;
    boxes.as.aabb.ex = bone, boxes.as.aabb.ey = bone, boxes.as.aabb.ez = bone;
    h.t = rt, h.primitive = rp, h.nx = rnx, h.ny = rny, h.nz = rnz;
    CHECK(gyro_raycast_closest(&r, 2, &boxes, 3, &h) == GYRO_OK);
    CHECK(rp[0] == 1 && rt[0] == 1.0f && rnx[0] == -1.0f); /* the box at x = 2, entered at x = 1 */
    CHECK(gyro_raycast_any(&r, 2, &boxes, 3, &h) == GYRO_OK);
    CHECK(rp[0] == 0 && rt[0] == 5.0f); /* any hit: the lowest index crossed, box 0 at x = 6 */
    tris.type = GYRO_SHAPE_TRIANGLE;
    tris.as.triangle.ax = tax, tris.as.triangle.ay = tay, tris.as.triangle.az = taz;
    tris.as.triangle.bx = tbx, tris.as.triangle.by = tby, tris.as.triangle.bz = tbz;
    tris.as.triangle.cx = tcx, tris.as.triangle.cy = tcy, tris.as.triangle.cz = tcz;
    h.u = ru, h.v = rv;
    CHECK(gyro_raycast_closest(&r, 2, &tris, 1, &h) == GYRO_OK);
    CHECK(rp[0] == 0 && rt[0] == 3.0f && rnx[0] == -1.0f && rp[1] == 0);
    /* hit point = a + u (b - a) + v (c - a) */
    CHECK(fabsf(-5.0f + ru[1] * 10.0f + rv[1] * 5.0f - 0.5f) < 1e-5f && fabsf(-5.0f + rv[1] * 10.0f) < 1e-5f);
    h.v = NULL; /* u without v */
    CHECK(gyro_raycast_closest(&r, 2, &tris, 1, &h) == GYRO_STATUS_NULL_ARGUMENT);
    h.v = rv;
    tris.reserved = 1;
    CHECK(gyro_raycast_closest(&r, 2, &tris, 1, &h) == GYRO_STATUS_INVALID_ARGUMENT);
    tris.reserved = 0;
    bone[1] = -1.0f;
    CHECK(gyro_raycast_closest(&r, 2, &boxes, 3, &h) == GYRO_STATUS_INVALID_ARGUMENT);
    CHECK(strstr(gyro_last_error(), "prims.ex[1]") != NULL);
    bone[1] = 1.0f;
  }

  if (failures) {
    fprintf(stderr, "%d checks failed\n", failures);
    return 1;
  }
  printf("capi: all checks passed (%s, %u threads)\n", gyro_simd_level_name(gyro_get_simd_level()),
         gyro_get_thread_count());
  return 0;
}
