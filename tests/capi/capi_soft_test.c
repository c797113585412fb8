/* Springs, cloth and soft bodies through the C ABI, from a C99 program: a 16 x 16 cloth
 * pinned at two corners falls onto a static sphere body and no particle ends inside it; the
 * cloth sags; its stats are finite; two worlds fed the same calls hash the same (and a
 * third on the scalar level and 2 threads too); a soft cube dropped on a ground box comes
 * to rest on it; a soft mesh (an octahedron) steps; settings, family constants, masses,
 * pins, particle state and joints round-trip; and every bad input (NULL, wrong struct_size,
 * NaN/Inf, negative stiffness, out-of-range particles, stale ids, ...) returns its
 * documented status and leaves the world's hash unchanged. */
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

STATIC_ASSERT(sizeof(gyro_soft_body_id) == 8, soft_body_id);
STATIC_ASSERT(sizeof(gyro_soft_model) == 4 && sizeof(gyro_spring_family) == 4 &&
                  sizeof(gyro_collision_response) == 4 && sizeof(gyro_step_stage) == 4,
              enums);
STATIC_ASSERT(sizeof(gyro_spring_constants) == 8, spring_constants);
STATIC_ASSERT(sizeof(gyro_soft_settings) == 48, soft_settings);
STATIC_ASSERT(sizeof(gyro_cloth_def) == 68, cloth_def);
STATIC_ASSERT(sizeof(gyro_soft_cube_def) == 48, soft_cube_def);
STATIC_ASSERT(sizeof(gyro_soft_body_stats) == 64, soft_body_stats);
STATIC_ASSERT(sizeof(void*) != 8 || sizeof(gyro_soft_mesh_def) == 72, soft_mesh_def_64);
STATIC_ASSERT(sizeof(void*) != 8 || sizeof(gyro_soft_body_view) == 72, soft_body_view_64);
STATIC_ASSERT(sizeof(gyro_step_timings) == 56, step_timings_unchanged);

static const float kDt = 1.0f / 60.0f;

/* The drape scene: a 2 x 2 m cloth of 16 x 16 particles at y = 0.8 pinned at its two
 * corners on the z = -1 edge, over a static sphere of radius 0.5 whose top is at y = 0.6. */
#define CLOTH_N 16
#define CLOTH_Y 0.8f
#define SPHERE_R 0.5f
static const float kSphere[3] = {0.0f, 0.1f, 0.2f};

static gyro_vec3 vec3(float x, float y, float z) {
  gyro_vec3 v;
  v.x = x, v.y = y, v.z = z;
  return v;
}

static uint64_t hash_of(const gyro_world* w) {
  uint64_t h = 0;
  CHECK(gyro_world_hash(w, &h) == GYRO_OK);
  return h;
}

static uint64_t soft_hash_of(const gyro_world* w, gyro_soft_body_id id) {
  uint64_t h = 0;
  CHECK(gyro_soft_body_hash(w, id, &h) == GYRO_OK);
  return h;
}

static int finite_d(double v) { return v == v && v - v == 0.0; }

static gyro_world* drape_scene(gyro_soft_body_id* cloth, gyro_body_id* sphere, uint32_t pins[2]) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd = gyro_body_def_default();
  gyro_cloth_def cd = gyro_cloth_def_default();
  gyro_world* w = NULL;
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK && w != NULL);
  if (!w) return NULL;
  bd.type = GYRO_BODY_STATIC;
  bd.shape = GYRO_BODY_SHAPE_SPHERE;
  bd.radius = SPHERE_R;
  bd.position = vec3(kSphere[0], kSphere[1], kSphere[2]);
  CHECK(gyro_body_create(w, &bd, sphere) == GYRO_OK);
  cd.nx = cd.nz = CLOTH_N;
  cd.size_x = cd.size_z = 2.0f;
  cd.center = vec3(0.0f, CLOTH_Y, 0.0f);
  cd.particle_mass = 0.02f;
  CHECK(gyro_world_create_cloth(w, &cd, cloth) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, *cloth, 0, 0, &pins[0]) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, *cloth, CLOTH_N - 1, 0, &pins[1]) == GYRO_OK);
  CHECK(gyro_soft_body_pin(w, *cloth, pins[0]) == GYRO_OK);
  CHECK(gyro_soft_body_pin(w, *cloth, pins[1]) == GYRO_OK);
  return w;
}

static void test_versions(void) {
  CHECK(gyro_abi_version() >> 16 == GYRO_ABI_VERSION >> 16);
  CHECK((gyro_abi_version() & 0xFFFFu) >= 3u); /* soft bodies arrived in ABI 1.3 */
  CHECK(GYRO_ABI_VERSION >= ((1u << 16) | 3u)); /* this header is at least 1.3 */
  CHECK(gyro_features() & GYRO_FEATURE_DYNAMICS);
  CHECK(gyro_features() & GYRO_FEATURE_SOFT_BODIES);
}

static void test_defaults(void) {
  gyro_cloth_def cd = gyro_cloth_def_default();
  gyro_soft_cube_def kd = gyro_soft_cube_def_default();
  gyro_soft_mesh_def md = gyro_soft_mesh_def_default();
  gyro_soft_settings s = gyro_soft_settings_default();
  CHECK(cd.struct_size == sizeof cd && cd.nx == 32 && cd.nz == 32 && cd.size_x == 10.0f && cd.particle_mass == 1.0f);
  CHECK(cd.both_diagonals == 1 && cd.bend == 1 && cd.structural.stiffness > 0.0f && cd.shear.damping == 0.0f);
  CHECK(kd.struct_size == sizeof kd && kd.half_extent == 0.5f && kd.particle_mass == 1.0f);
  CHECK(md.struct_size == sizeof md && md.x == NULL && md.indices == NULL && md.vertex_count == 0);
  CHECK(md.particle_mass == 1.0f && md.radial.stiffness > 0.0f);
  CHECK(s.struct_size == sizeof s && s.model == GYRO_SOFT_MODEL_XPBD && s.substeps == 16 && s.iterations == 1);
  CHECK(s.gravity.y < -9.0f && s.response == GYRO_COLLISION_PROJECTION && s.penalty_stiffness > 0.0f);
}

/* Runs the drape scene for 120 steps; checks the result against the sphere; returns the
 * world hash (and the cloth's own hash). */
static uint64_t drape(int check, uint64_t* soft_hash) {
  gyro_soft_body_id cloth;
  gyro_body_id sphere;
  uint32_t pins[2];
  gyro_world* w = drape_scene(&cloth, &sphere, pins);
  gyro_soft_body_view view;
  gyro_soft_body_stats stats;
  gyro_vec3 pin_start[2], p;
  double min_d = 1e30, min_y = 1e30, soft_ms = -1.0, total_ms = -1.0;
  uint64_t h;
  int step, k;
  int32_t i, inside = 0, tri_ok = 1, ccw = 1;
  if (!w) return 0;
  for (k = 0; k < 2; ++k) CHECK(gyro_soft_body_get_position(w, cloth, pins[k], &pin_start[k]) == GYRO_OK);
  if (check) { /* the flat cloth's triangles: in range, counter-clockwise seen from +y */
    CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK);
    CHECK(view.count == CLOTH_N * CLOTH_N && view.triangle_count == 2 * (CLOTH_N - 1) * (CLOTH_N - 1));
    CHECK(view.px && view.py && view.pz && view.vx && view.vy && view.vz && view.inverse_mass && view.triangles);
    for (i = 0; i < view.triangle_count; ++i) {
      const uint32_t a = view.triangles[3 * i], b = view.triangles[3 * i + 1], c = view.triangles[3 * i + 2];
      if (a >= (uint32_t)view.count || b >= (uint32_t)view.count || c >= (uint32_t)view.count) {
        tri_ok = 0;
        continue;
      }
      /* y of (b - a) x (c - a) = dz1 dx2 - dx1 dz2 */
      if ((view.pz[b] - view.pz[a]) * (view.px[c] - view.px[a]) - (view.px[b] - view.px[a]) * (view.pz[c] - view.pz[a]) <=
          0.0f)
        ccw = 0;
    }
    CHECK(tri_ok);
    CHECK(ccw);
    CHECK(view.inverse_mass[pins[0]] == 0.0f && view.inverse_mass[pins[1]] == 0.0f);
    for (i = 0; i < view.count; ++i)
      if ((uint32_t)i != pins[0] && (uint32_t)i != pins[1] && !(fabsf(view.inverse_mass[i] - 50.0f) < 1e-3f))
        tri_ok = 0; /* 1 / 0.02 kg */
    CHECK(tri_ok);
  }
  /* After every step (the view is re-read: a step invalidates it), no particle is inside the
   * sphere. The cloth falls onto it, drapes over it, then slides off towards its pins. */
  for (step = 0; step < 120; ++step) {
    CHECK(gyro_world_step(w, kDt) == GYRO_OK);
    if (!check && step + 1 < 120) continue;
    CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK);
    CHECK(view.count == CLOTH_N * CLOTH_N);
    for (i = 0; i < view.count; ++i) {
      const double dx = (double)view.px[i] - kSphere[0], dy = (double)view.py[i] - kSphere[1],
                   dz = (double)view.pz[i] - kSphere[2];
      const double d = sqrt(dx * dx + dy * dy + dz * dz);
      if (!(d >= SPHERE_R)) ++inside;
      if (d < min_d) min_d = d;
      if (step + 1 == 120 && view.py[i] < min_y) min_y = view.py[i];
    }
  }
  CHECK(gyro_world_get_stage_time(w, GYRO_STAGE_SOFT_BODIES, &soft_ms) == GYRO_OK);
  CHECK(gyro_world_get_stage_time(w, GYRO_STAGE_TOTAL, &total_ms) == GYRO_OK);
  if (check) {
    CHECK(inside == 0);             /* no particle was ever inside the sphere */
    CHECK(min_d < SPHERE_R + 0.05); /* and the cloth did lie on it */
    CHECK(min_y < CLOTH_Y - 0.1);   /* it sags */
    CHECK(soft_ms > 0.0 && total_ms >= soft_ms);
    /* pinned particles do not move */
    for (k = 0; k < 2; ++k) {
      CHECK(gyro_soft_body_get_position(w, cloth, pins[k], &p) == GYRO_OK);
      CHECK(p.x == pin_start[k].x && p.y == pin_start[k].y && p.z == pin_start[k].z);
    }
    CHECK(gyro_soft_body_get_stats(w, cloth, &stats) == GYRO_OK);
    CHECK(stats.particles == CLOTH_N * CLOTH_N && stats.springs > 0 && stats.colors > 0 && stats.reserved == 0);
    CHECK(finite_d(stats.max_strain) && finite_d(stats.mean_strain) && finite_d(stats.kinetic_energy));
    CHECK(finite_d(stats.potential_energy) && finite_d(stats.elastic_energy) && finite_d(stats.min_y));
    CHECK(stats.max_strain >= stats.mean_strain && stats.mean_strain >= 0.0 && stats.max_strain < 0.1);
    CHECK(fabs(stats.min_y - min_y) < 1e-6);
    printf("drape: closest approach to the sphere centre %.4f m (radius %.2f), lowest particle %.3f m, max strain "
           "%.2e, soft-body stage %.3f ms of %.3f ms\n",
           min_d, (double)SPHERE_R, min_y, stats.max_strain, soft_ms, total_ms);
  }
  h = hash_of(w);
  *soft_hash = soft_hash_of(w, cloth);
  gyro_world_destroy(w);
  return h;
}

static void test_drape_and_determinism(void) {
  uint64_t s1 = 0, s2 = 0, s3 = 0;
  const uint64_t h1 = drape(1, &s1);
  const uint64_t h2 = drape(0, &s2);
  uint64_t h3;
  CHECK(h1 == h2 && s1 == s2);
  /* the same bits on the scalar reference level and on 2 threads */
  CHECK(gyro_set_simd_level(GYRO_SIMD_SCALAR) == GYRO_OK);
  CHECK(gyro_set_thread_count(2) == GYRO_OK);
  h3 = drape(0, &s3);
  CHECK(h3 == h1 && s3 == s1);
  CHECK(gyro_set_simd_level(GYRO_SIMD_AUTO) == GYRO_OK);
  CHECK(gyro_set_thread_count(0) == GYRO_OK);
}

/* The appendix's soft cube (8 particles, 28 springs, damped springs) dropped from 1.5 m onto
 * a ground box: after 4 s it rests on the box. */
static void test_cube_on_ground(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def gd = gyro_body_def_default();
  gyro_soft_cube_def kd = gyro_soft_cube_def_default();
  gyro_world* w = NULL;
  gyro_body_id ground;
  gyro_soft_body_id cube;
  gyro_soft_body_view view;
  gyro_soft_body_stats stats;
  int step;
  int32_t i;
  double min_y = 1e30, max_speed = 0.0;
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK);
  if (!w) return;
  gd.type = GYRO_BODY_STATIC;
  gd.half_extents = vec3(5.0f, 0.5f, 5.0f);
  gd.position = vec3(0.0f, -0.5f, 0.0f); /* top face at y = 0 */
  CHECK(gyro_body_create(w, &gd, &ground) == GYRO_OK);
  kd.center = vec3(0.0f, 2.0f, 0.0f);
  kd.structural.damping = kd.shear.damping = kd.bend.damping = 10.0f; /* N s/m; k = 1e4 N/m, 1 kg corners */
  CHECK(gyro_world_create_soft_cube(w, &kd, &cube) == GYRO_OK);
  for (step = 0; step < 240; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_soft_body_get_view(w, cube, &view) == GYRO_OK);
  CHECK(view.count == 8 && view.triangle_count >= 0);
  for (i = 0; i < view.count; ++i) {
    const double s = sqrt((double)view.vx[i] * view.vx[i] + (double)view.vy[i] * view.vy[i] +
                          (double)view.vz[i] * view.vz[i]);
    if (view.py[i] < min_y) min_y = view.py[i];
    if (!(s <= max_speed)) max_speed = s;
  }
  CHECK(min_y >= -1e-3);  /* above the ground */
  CHECK(min_y < 0.05);    /* resting on it, not floating */
  CHECK(max_speed < 0.05); /* at rest */
  CHECK(gyro_soft_body_get_stats(w, cube, &stats) == GYRO_OK);
  CHECK(stats.particles == 8 && stats.springs == 28);
  CHECK(finite_d(stats.kinetic_energy) && stats.kinetic_energy < 1e-2 && stats.max_strain < 0.2);
  printf("cube: lowest corner %.4f m, fastest corner %.2e m/s, max strain %.2e after 4 s\n", min_y, max_speed,
         stats.max_strain);
  gyro_world_destroy(w);
}

/* An octahedron (6 vertices, 8 triangles, outward counter-clockwise) as a soft mesh. */
static const float kOctX[6] = {1, -1, 0, 0, 0, 0}, kOctY[6] = {0, 0, 1, -1, 0, 0}, kOctZ[6] = {0, 0, 0, 0, 1, -1};
static const uint32_t kOctTris[24] = {0, 2, 4, 4, 2, 1, 1, 2, 5, 5, 2, 0, 0, 4, 3, 4, 1, 3, 1, 5, 3, 5, 0, 3};

static gyro_soft_mesh_def octahedron(void) {
  gyro_soft_mesh_def md = gyro_soft_mesh_def_default();
  md.x = kOctX, md.y = kOctY, md.z = kOctZ, md.vertex_count = 6;
  md.indices = kOctTris, md.triangle_count = 8;
  return md;
}

static void test_soft_mesh(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_soft_mesh_def md = octahedron();
  gyro_soft_body_id id;
  gyro_soft_body_view view;
  gyro_soft_body_stats stats;
  int step;
  int32_t count = -1;
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK);
  if (!w) return;
  CHECK(gyro_world_create_soft_mesh(w, &md, &id) == GYRO_OK);
  CHECK(gyro_world_soft_body_count(w, &count) == GYRO_OK && count == 1);
  CHECK(gyro_soft_body_get_view(w, id, &view) == GYRO_OK);
  CHECK(view.count == 7); /* the vertices and the centre particle */
  CHECK(view.py[6] == 0.0f);
  for (step = 0; step < 30; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_soft_body_get_stats(w, id, &stats) == GYRO_OK);
  CHECK(stats.particles == 7 && stats.springs > 12 && finite_d(stats.min_y) && stats.min_y < -1.0);
  CHECK(gyro_world_destroy_soft_body(w, id) == GYRO_OK);
  CHECK(!gyro_soft_body_is_valid(w, id));
  CHECK(gyro_world_soft_body_count(w, &count) == GYRO_OK && count == 0);
  gyro_world_destroy(w);
}

/* Settings, family constants, masses, pins, particle state and joints round-trip. */
static void test_state(void) {
  gyro_soft_body_id cloth;
  gyro_body_id sphere;
  uint32_t pins[2], idx, joint = 99, pinned = 7, a, b, c, d;
  gyro_world* w = drape_scene(&cloth, &sphere, pins);
  gyro_soft_settings s = gyro_soft_settings_default(), got = gyro_soft_settings_default();
  gyro_spring_constants k = {2.0e5f, 0.5f}, kg = {0.0f, 0.0f};
  gyro_vec3 p, v;
  gyro_soft_body_view view;
  uint64_t h;
  if (!w) return;
  CHECK(gyro_soft_body_is_valid(w, cloth));
  CHECK(gyro_soft_body_get_settings(w, cloth, &got) == GYRO_OK && memcmp(&got, &s, sizeof s) == 0);
  s.substeps = 8, s.iterations = 2, s.damping = 0.1f, s.friction = 0.5f, s.thickness = 0.02f;
  s.gravity = vec3(0.0f, -5.0f, 0.0f);
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_OK);
  CHECK(gyro_soft_body_get_settings(w, cloth, &got) == GYRO_OK && memcmp(&got, &s, sizeof s) == 0);

  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_SHEAR, &k) == GYRO_OK);
  CHECK(gyro_soft_body_get_family(w, cloth, GYRO_SPRING_SHEAR, &kg) == GYRO_OK);
  CHECK(kg.stiffness == k.stiffness && kg.damping == k.damping);
  k.stiffness = INFINITY, k.damping = 0.0f; /* inextensible: XPBD only */
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_STRUCTURAL, &k) == GYRO_OK);
  CHECK(gyro_soft_body_get_family(w, cloth, GYRO_SPRING_STRUCTURAL, &kg) == GYRO_OK && kg.stiffness == INFINITY);
  h = hash_of(w);
  s.model = GYRO_SOFT_MODEL_SPRINGS; /* explicit springs cannot take an infinite stiffness */
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(hash_of(w) == h);
  k.stiffness = 1.0e4f;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_STRUCTURAL, &k) == GYRO_OK);
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_OK);
  k.stiffness = INFINITY;
  h = hash_of(w);
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_BEND, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(hash_of(w) == h);
  s.model = GYRO_SOFT_MODEL_XPBD;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_OK);

  /* masses and pins */
  CHECK(gyro_soft_body_cloth_index(w, cloth, 3, 5, &idx) == GYRO_OK && idx < CLOTH_N * CLOTH_N);
  h = hash_of(w);
  CHECK(gyro_soft_body_set_particle_mass(w, cloth, idx, 0.5f) == GYRO_OK);
  CHECK(hash_of(w) != h); /* the world hash covers its soft bodies */
  CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK && view.inverse_mass[idx] == 2.0f);
  CHECK(gyro_soft_body_set_mass(w, cloth, 0.25f) == GYRO_OK);
  CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK && view.inverse_mass[idx] == 4.0f);
  CHECK(view.inverse_mass[pins[0]] == 0.0f); /* pinned particles stay pinned */
  CHECK(gyro_soft_body_is_pinned(w, cloth, pins[0], &pinned) == GYRO_OK && pinned == 1);
  CHECK(gyro_soft_body_is_pinned(w, cloth, idx, &pinned) == GYRO_OK && pinned == 0);
  CHECK(gyro_soft_body_pin(w, cloth, idx) == GYRO_OK);
  CHECK(gyro_soft_body_is_pinned(w, cloth, idx, &pinned) == GYRO_OK && pinned == 1);
  CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK && view.inverse_mass[idx] == 0.0f);
  CHECK(gyro_soft_body_unpin(w, cloth, idx) == GYRO_OK);
  CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK && view.inverse_mass[idx] == 4.0f);

  /* particle state: a pinned particle is moved by set_position (a kinematic pin) */
  CHECK(gyro_soft_body_set_position(w, cloth, pins[0], vec3(-1.0f, 1.0f, -1.0f)) == GYRO_OK);
  CHECK(gyro_soft_body_get_position(w, cloth, pins[0], &p) == GYRO_OK && p.y == 1.0f && p.x == -1.0f);
  CHECK(gyro_soft_body_set_velocity(w, cloth, idx, vec3(0.0f, 1.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_soft_body_get_velocity(w, cloth, idx, &v) == GYRO_OK && v.y == 1.0f && v.x == 0.0f);
  CHECK(gyro_soft_body_get_view(w, cloth, &view) == GYRO_OK && view.vy[idx] == 1.0f && view.py[pins[0]] == 1.0f);

  /* joints between particles of the cloth */
  CHECK(gyro_soft_body_cloth_index(w, cloth, 0, CLOTH_N - 1, &a) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, cloth, CLOTH_N - 1, CLOTH_N - 1, &b) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, cloth, 1, CLOTH_N - 1, &c) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, cloth, CLOTH_N - 2, CLOTH_N - 1, &d) == GYRO_OK);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, a, b, 1.0f, &joint) == GYRO_OK && joint == 0);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, a, d, -1.0f, &joint) == GYRO_OK && joint == 1);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, c, b, -1.0f, NULL) == GYRO_OK);
  CHECK(gyro_soft_body_add_ball_joint(w, cloth, c, d) == GYRO_OK);
  CHECK(gyro_soft_body_add_hinge_joint(w, cloth, a, c, b, d) == GYRO_OK);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, a, b, 1.0f, &joint) == GYRO_OK && joint >= 3);
  {
    int step;
    gyro_soft_body_stats st;
    for (step = 0; step < 30; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
    CHECK(gyro_soft_body_get_stats(w, cloth, &st) == GYRO_OK && finite_d(st.kinetic_energy) && finite_d(st.min_y));
  }
  gyro_world_destroy(w);
}

/* Every bad call returns its status and changes nothing: the hashes and counts stay. */
static void test_bad_input(void) {
  gyro_soft_body_id cloth, gone, out, null_id = {0, 0}, far_id, ids[3];
  gyro_body_id sphere;
  uint32_t pins[2], u = 77, big = CLOTH_N * CLOTH_N;
  gyro_world* w = drape_scene(&cloth, &sphere, pins);
  gyro_cloth_def cd = gyro_cloth_def_default();
  gyro_soft_cube_def kd = gyro_soft_cube_def_default();
  gyro_soft_mesh_def md = octahedron();
  gyro_soft_settings s = gyro_soft_settings_default();
  gyro_spring_constants k = {1.0e4f, 0.0f};
  gyro_vec3 p, nan3 = {NAN, 0.0f, 0.0f}, inf3 = {0.0f, INFINITY, 0.0f}, zero3 = {0.0f, 0.0f, 0.0f};
  gyro_soft_body_view view;
  gyro_soft_body_stats stats;
  float bad_x[6];
  uint32_t bad_tris[24];
  double ms;
  uint64_t h, hs, v64;
  int32_t count;
  int step, n;
  if (!w) return;
  cd.nx = cd.nz = 4;
  for (step = 0; step < 5; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_world_create_cloth(w, &cd, &gone) == GYRO_OK);
  CHECK(gyro_world_destroy_soft_body(w, gone) == GYRO_OK);
  CHECK(!gyro_soft_body_is_valid(w, gone));
  h = hash_of(w);
  hs = soft_hash_of(w, cloth);
  out = null_id;

  /* creation: *out untouched, nothing added */
  CHECK(gyro_world_create_cloth(NULL, &cd, &out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_create_cloth(w, NULL, &out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_create_cloth(w, &cd, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  cd.struct_size = sizeof cd - 4;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(gyro_last_error(), "struct_size") != NULL);
  cd = gyro_cloth_def_default(), cd.nx = -3;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_COUNT);
  cd = gyro_cloth_def_default(), cd.nz = -1;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_COUNT);
  cd = gyro_cloth_def_default(), cd.nx = 0;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_COUNT);
  cd = gyro_cloth_def_default(), cd.nz = 1;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_COUNT);
  cd = gyro_cloth_def_default(), cd.nx = 1 << 16, cd.nz = 1 << 16; /* 2^32 particles */
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_COUNT);
  cd = gyro_cloth_def_default(), cd.size_x = 0.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.size_z = -2.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.size_x = NAN;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_NON_FINITE);
  cd = gyro_cloth_def_default(), cd.center = inf3;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_NON_FINITE);
  cd = gyro_cloth_def_default(), cd.particle_mass = 0.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.particle_mass = -1.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.particle_mass = INFINITY;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_NON_FINITE);
  cd = gyro_cloth_def_default(), cd.both_diagonals = 2;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.bend = 0xFFFFFFFFu;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.structural.stiffness = -1.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.shear.stiffness = 0.0f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.bend_constants.stiffness = -INFINITY;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.structural.stiffness = NAN;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_NON_FINITE);
  cd = gyro_cloth_def_default(), cd.shear.damping = -0.5f;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  cd = gyro_cloth_def_default(), cd.bend_constants.damping = INFINITY;
  CHECK(gyro_world_create_cloth(w, &cd, &out) == GYRO_STATUS_NON_FINITE);

  CHECK(gyro_world_create_soft_cube(w, NULL, &out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_create_soft_cube(w, &kd, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  kd.struct_size = 0;
  CHECK(gyro_world_create_soft_cube(w, &kd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  kd = gyro_soft_cube_def_default(), kd.half_extent = 0.0f;
  CHECK(gyro_world_create_soft_cube(w, &kd, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  kd = gyro_soft_cube_def_default(), kd.center = nan3;
  CHECK(gyro_world_create_soft_cube(w, &kd, &out) == GYRO_STATUS_NON_FINITE);
  kd = gyro_soft_cube_def_default(), kd.particle_mass = NAN;
  CHECK(gyro_world_create_soft_cube(w, &kd, &out) == GYRO_STATUS_NON_FINITE);
  kd = gyro_soft_cube_def_default(), kd.shear.stiffness = -5.0f;
  CHECK(gyro_world_create_soft_cube(w, &kd, &out) == GYRO_STATUS_INVALID_ARGUMENT);

  CHECK(gyro_world_create_soft_mesh(w, NULL, &out) == GYRO_STATUS_NULL_ARGUMENT);
  md.x = NULL;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_NULL_ARGUMENT);
  md = octahedron(), md.indices = NULL;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_NULL_ARGUMENT);
  md = octahedron(), md.struct_size = 1;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  md = octahedron(), md.vertex_count = -6;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_COUNT);
  md = octahedron(), md.triangle_count = -1;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_COUNT);
  md = octahedron(), md.triangle_count = 3;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_COUNT);
  md = octahedron(), md.triangle_count = 7; /* no longer closed */
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  md = octahedron(), md.vertex_count = 5; /* index 5 is now out of range */
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  memcpy(bad_tris, kOctTris, sizeof bad_tris);
  bad_tris[7] = bad_tris[6]; /* a triangle repeating a vertex */
  md = octahedron(), md.indices = bad_tris;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  memcpy(bad_x, kOctX, sizeof bad_x);
  bad_x[4] = NAN;
  md = octahedron(), md.x = bad_x;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_NON_FINITE);
  md = octahedron(), md.particle_mass = -1.0f;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  md = octahedron(), md.radial.stiffness = NAN;
  CHECK(gyro_world_create_soft_mesh(w, &md, &out) == GYRO_STATUS_NON_FINITE);
  CHECK(out.index == 0 && out.generation == 0);
  CHECK(gyro_world_soft_body_count(w, &count) == GYRO_OK && count == 1);
  CHECK(hash_of(w) == h);

  /* settings */
  CHECK(gyro_soft_body_set_settings(w, cloth, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  s.struct_size = 0;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.model = 2;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.response = 2;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.substeps = 0;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.substeps = 257;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.iterations = 0;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.iterations = 65;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.gravity = nan3;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_NON_FINITE);
  s = gyro_soft_settings_default(), s.damping = -1.0f;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.thickness = -0.01f;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.thickness = INFINITY;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_NON_FINITE);
  s = gyro_soft_settings_default(), s.friction = 1.5f;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.penalty_stiffness = 0.0f;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT);
  s = gyro_soft_settings_default(), s.penalty_stiffness = NAN;
  CHECK(gyro_soft_body_set_settings(w, cloth, &s) == GYRO_STATUS_NON_FINITE);
  s = gyro_soft_settings_default(), s.struct_size = 0;
  CHECK(gyro_soft_body_get_settings(w, cloth, &s) == GYRO_STATUS_INVALID_ARGUMENT && s.substeps == 16);
  CHECK(gyro_soft_body_get_settings(w, cloth, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(hash_of(w) == h);

  /* family constants */
  CHECK(gyro_soft_body_set_family(w, cloth, 5, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_get_family(w, cloth, 5, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_SHEAR, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_get_family(w, cloth, GYRO_SPRING_SHEAR, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  k.stiffness = -1.0f;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_SHEAR, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  k.stiffness = 0.0f;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_STRUCTURAL, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  k.stiffness = NAN;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_BEND, &k) == GYRO_STATUS_NON_FINITE);
  k.stiffness = 1.0e4f, k.damping = -1.0f;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_BEND, &k) == GYRO_STATUS_INVALID_ARGUMENT);
  k.damping = NAN;
  CHECK(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_JOINT, &k) == GYRO_STATUS_NON_FINITE);
  CHECK(hash_of(w) == h);

  /* masses, pins and particle state: bad values, out-of-range particles */
  CHECK(gyro_soft_body_set_mass(w, cloth, 0.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_mass(w, cloth, -1.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_mass(w, cloth, NAN) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_set_mass(w, cloth, INFINITY) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_set_particle_mass(w, cloth, 3, -2.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_particle_mass(w, cloth, 3, NAN) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_set_particle_mass(w, cloth, big, 1.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(gyro_last_error(), "out of range") != NULL);
  CHECK(gyro_soft_body_set_particle_mass(w, cloth, 0xFFFFFFFFu, 1.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_pin(w, cloth, big) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_unpin(w, cloth, big + 5) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_is_pinned(w, cloth, big, &u) == GYRO_STATUS_INVALID_ARGUMENT && u == 77);
  CHECK(gyro_soft_body_is_pinned(w, cloth, 0, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_get_position(w, cloth, big, &p) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_get_position(w, cloth, 0, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_get_velocity(w, cloth, big, &p) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_get_velocity(w, cloth, 0, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_set_position(w, cloth, big, zero3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_position(w, cloth, 0, nan3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_set_position(w, cloth, 0, inf3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_set_velocity(w, cloth, big, zero3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_set_velocity(w, cloth, 0, inf3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_cloth_index(w, cloth, CLOTH_N, 0, &u) == GYRO_STATUS_INVALID_ARGUMENT && u == 77);
  CHECK(gyro_soft_body_cloth_index(w, cloth, 0, CLOTH_N, &u) == GYRO_STATUS_INVALID_ARGUMENT && u == 77);
  CHECK(gyro_soft_body_cloth_index(w, cloth, 0, 0, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(hash_of(w) == h);

  /* joints */
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, 0, 0, 1.0f, &u) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, 0, big, 1.0f, &u) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, 0, 1, NAN, &u) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_soft_body_add_distance_joint(w, cloth, 0, 1, INFINITY, &u) == GYRO_STATUS_NON_FINITE && u == 77);
  CHECK(gyro_soft_body_add_ball_joint(w, cloth, 3, 3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_ball_joint(w, cloth, big, 3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_hinge_joint(w, cloth, 0, 1, 2, big) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_hinge_joint(w, cloth, 0, 0, 2, 3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_add_hinge_joint(w, cloth, 0, 1, 0, 3) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(hash_of(w) == h);

  /* outputs and stage times */
  CHECK(gyro_soft_body_get_view(w, cloth, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_get_stats(w, cloth, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_soft_body_hash(w, cloth, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_soft_body_count(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_soft_body_count(NULL, &count) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_stage_time(w, GYRO_STAGE_SOFT_BODIES + 1, &ms) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_get_stage_time(w, GYRO_STAGE_SOFT_BODIES, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_stage_time(NULL, GYRO_STAGE_SOFT_BODIES, &ms) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(!gyro_soft_body_is_valid(NULL, cloth));
  CHECK(hash_of(w) == h);

  /* stale ids: a destroyed body, the null id and one never created, through every call */
  far_id.index = cloth.index + 1000, far_id.generation = cloth.generation;
  ids[0] = gone, ids[1] = null_id, ids[2] = far_id;
  for (n = 0; n < 3; ++n) {
    const gyro_soft_body_id id = ids[n];
    s = gyro_soft_settings_default();
    k.stiffness = 1.0e3f, k.damping = 0.0f;
    CHECK(!gyro_soft_body_is_valid(w, id));
    CHECK(gyro_world_destroy_soft_body(w, id) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_world_destroy_soft_body(NULL, id) == GYRO_STATUS_NULL_ARGUMENT);
    CHECK(gyro_soft_body_set_settings(w, id, &s) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_settings(w, id, &s) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_set_family(w, id, GYRO_SPRING_SHEAR, &k) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_family(w, id, GYRO_SPRING_SHEAR, &k) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_set_mass(w, id, 1.0f) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_set_particle_mass(w, id, 0, 1.0f) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_pin(w, id, 0) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_unpin(w, id, 0) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_is_pinned(w, id, 0, &u) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_position(w, id, 0, &p) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_set_position(w, id, 0, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_velocity(w, id, 0, &p) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_set_velocity(w, id, 0, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_cloth_index(w, id, 0, 0, &u) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_add_distance_joint(w, id, 0, 1, -1.0f, &u) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_add_ball_joint(w, id, 0, 1) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_add_hinge_joint(w, id, 0, 1, 2, 3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_view(w, id, &view) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_get_stats(w, id, &stats) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_soft_body_hash(w, id, &v64) == GYRO_STATUS_STALE_ID);
  }
  CHECK(u == 77);
  CHECK(gyro_world_soft_body_count(w, &count) == GYRO_OK && count == 1);
  CHECK(hash_of(w) == h);
  CHECK(soft_hash_of(w, cloth) == hs);

  /* and the world still steps */
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(hash_of(w) != h);
  CHECK(soft_hash_of(w, cloth) != hs);
  gyro_world_destroy(w);
}

int main(void) {
  test_versions();
  test_defaults();
  test_drape_and_determinism();
  test_cube_on_ground();
  test_soft_mesh();
  test_state();
  test_bad_input();
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("capi soft: all checks passed\n");
  return 0;
}
