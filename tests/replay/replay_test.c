/* Record and replay (ABI 1.5) from a C99 program.
 *
 *   gyro_replay_test                 the tests (ctest replay.c99): a session mixing rigid
 *                                    bodies (spheres, boxes, a capsule, hulls, mesh bodies)
 *                                    with forces, impulses, teleports, sleep and a destroy,
 *                                    and one with a cloth, a soft cube and a soft mesh, are
 *                                    recorded and replayed with no divergence to the live
 *                                    world's hash; a flipped byte or a truncation is
 *                                    CORRUPT_DATA; a tampered step hash is a divergence at
 *                                    that step; failed calls are not recorded; geometry is
 *                                    stored once; mutated recordings never crash.
 *   gyro_replay_test --golden DIR    (ctest replay.golden) replays every golden recording in
 *                                    DIR at every SIMD level this CPU has and on 1 and 3
 *                                    threads, and requires no divergence: a change that
 *                                    alters simulation results (or the snapshot format)
 *                                    fails here.
 *   gyro_replay_test --restore       (ctest replay.restore) a gyro_world_restore made while
 *                                    recording is recorded and replayed.
 *   gyro_replay_test --regenerate DIR  writes the golden recordings into DIR.
 *
 * When a change alters results on purpose, regenerate the goldens and commit them with it:
 *   cmake --build build --target gyro_replay_test
 *   build/tests/replay/gyro_replay_test --regenerate tests/replay/golden
 * and say in the commit why the results changed. The sessions below are the goldens' content:
 * changing them changes the goldens too. */
#include "gyro.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

STATIC_ASSERT(sizeof(gyro_replay_report) == 56, replay_report);

static const float kDt = 1.0f / 60.0f;

/* The golden recordings, in DIR. */
static const char* const kGoldens[] = {"rigid.gyrorec", "soft.gyrorec"};
#define GOLDEN_COUNT 2

/* ------------------------------------------------------------------ the format, for tampering
 * (capi/capi_recorder.hpp): a 24-byte header, u64 snapshot size and the snapshot, then
 * records (u32 opcode, u32 payload size, payload) up to the end record (opcode 0), then the
 * FNV-1a 64 of everything before it. */
enum { HEADER = 24, OP_END = 0, OP_MESH = 1, OP_HULL = 2, OP_STEP = 16, OP_BODY_CREATE = 32 };

static uint32_t le32(const unsigned char* p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static uint64_t le64(const unsigned char* p) { return (uint64_t)le32(p) | (uint64_t)le32(p + 4) << 32; }
static void put32(unsigned char* p, uint32_t v) {
  int k;
  for (k = 0; k < 4; ++k) p[k] = (unsigned char)(v >> (8 * k));
}
static void put64(unsigned char* p, uint64_t v) {
  put32(p, (uint32_t)v);
  put32(p + 4, (uint32_t)(v >> 32));
}

static void fix_checksum(unsigned char* b, uint64_t size) {
  uint64_t h = 0xcbf29ce484222325ull, i;
  for (i = 0; i + 8 < size; ++i) {
    h ^= b[i];
    h *= 0x100000001b3ull;
  }
  put64(b + size - 8, h);
}

/* The offset of the k-th record (0-based) with the opcode (any opcode: op < 0), or 0. */
static uint64_t find_record(const unsigned char* b, uint64_t size, long op, int k) {
  uint64_t at;
  if (size < HEADER + 8) return 0;
  at = HEADER + 8 + le64(b + HEADER);
  while (at + 8 <= size - 8) {
    const uint32_t o = le32(b + at), n = le32(b + at + 4);
    if ((op < 0 || o == (uint32_t)op) && k-- == 0) return at;
    if (o == OP_END) return 0;
    at += 8 + (uint64_t)n;
  }
  return 0;
}

/* ------------------------------------------------------------------ helpers */

static int64_t g_calls; /* successful mutating calls since recording began */

#define DO(call)                      \
  do {                                \
    const gyro_status do_s_ = (call); \
    CHECK(do_s_ == GYRO_OK);          \
    if (do_s_ == GYRO_OK) ++g_calls;  \
  } while (0)

static gyro_vec3 vec3(float x, float y, float z) {
  gyro_vec3 v;
  v.x = x, v.y = y, v.z = z;
  return v;
}
static gyro_quat quat(float x, float y, float z, float w) {
  gyro_quat q;
  q.x = x, q.y = y, q.z = z, q.w = w;
  return q;
}
static uint64_t hash_of(const gyro_world* w) {
  uint64_t h = 0;
  CHECK(gyro_world_hash(w, &h) == GYRO_OK);
  return h;
}
static uint64_t record_size(const gyro_world* w) {
  uint64_t n = 0;
  CHECK(gyro_world_record_size(w, &n) == GYRO_OK);
  return n;
}
/* The recording so far (malloc'd). */
static unsigned char* recording_of(const gyro_world* w, uint64_t* size) {
  uint64_t n = record_size(w), got = 0;
  unsigned char* b = (unsigned char*)malloc(n ? n : 1);
  CHECK(b != NULL);
  if (!b) return NULL;
  CHECK(gyro_world_record_copy(w, b, n, &got) == GYRO_OK && got == n);
  *size = got;
  return b;
}
static gyro_replay_report report_init(void) {
  gyro_replay_report r;
  memset(&r, 0xAB, sizeof r);
  r.struct_size = sizeof r;
  return r;
}
static void step(gyro_world* w, int n) {
  int i;
  for (i = 0; i < n; ++i) DO(gyro_world_step(w, kDt));
}

/* A static mesh: an nx x nz grid of quads, cell metres apart, centred at the origin, with
 * small fixed bumps. */
static gyro_mesh* grid_mesh(int nx, int nz, float cell) {
  enum { MAXV = 256, MAXI = 6 * 225 };
  float x[MAXV], y[MAXV], z[MAXV];
  uint32_t idx[MAXI];
  int i, j, t = 0;
  gyro_mesh_def d = gyro_mesh_def_default();
  gyro_mesh* m = NULL;
  if ((nx + 1) * (nz + 1) > MAXV || 6 * nx * nz > MAXI) return NULL;
  for (j = 0; j <= nz; ++j)
    for (i = 0; i <= nx; ++i) {
      const int v = j * (nx + 1) + i;
      x[v] = (i - 0.5f * nx) * cell;
      z[v] = (j - 0.5f * nz) * cell;
      y[v] = (float)((i * 7 + j * 3) % 5) * 0.04f - 0.08f;
    }
  for (j = 0; j < nz; ++j)
    for (i = 0; i < nx; ++i) {
      const uint32_t a = (uint32_t)(j * (nx + 1) + i), b = a + 1, c = a + (uint32_t)(nx + 1), e = c + 1;
      idx[t++] = a, idx[t++] = c, idx[t++] = b;
      idx[t++] = b, idx[t++] = c, idx[t++] = e;
    }
  d.vertex_count = (nx + 1) * (nz + 1);
  d.x = x, d.y = y, d.z = z;
  d.indices = idx;
  d.triangle_count = 2 * nx * nz;
  CHECK(gyro_mesh_create(&d, &m) == GYRO_OK);
  return m;
}

/* An irregular convex hull (a box with a roof), about 1 m across. */
static gyro_convex_hull* roof_hull(void) {
  static const float p[9][3] = {{-0.5f, -0.4f, -0.3f}, {0.5f, -0.4f, -0.3f},  {0.5f, -0.4f, 0.3f},
                                {-0.5f, -0.4f, 0.3f},  {-0.45f, 0.2f, -0.3f}, {0.5f, 0.2f, -0.25f},
                                {0.45f, 0.2f, 0.3f},   {-0.5f, 0.2f, 0.3f},   {0.05f, 0.6f, 0.0f}};
  gyro_vec3 pts[9];
  gyro_convex_hull* h = NULL;
  int i;
  for (i = 0; i < 9; ++i) pts[i] = vec3(p[i][0], p[i][1], p[i][2]);
  CHECK(gyro_convex_hull_create(pts, 9, &h) == GYRO_OK);
  return h;
}

static gyro_body_id add_body(gyro_world* w, gyro_body_def* d) {
  gyro_body_id id;
  memset(&id, 0, sizeof id);
  DO(gyro_body_create(w, d, &id));
  return id;
}

/* ------------------------------------------------------------------ the sessions
 * Each returns a world that is recording (the caller ends it), with g_calls counting the
 * recorded calls and *steps the recorded steps. */

/* Rigid bodies on a mesh ground: spheres, boxes, a capsule, hull bodies, a kinematic box,
 * forces, torques, impulses, a velocity change, a teleport, sleep, a destroy, bodies and a
 * mesh body created while recording. Recording begins after a few steps, so the start
 * snapshot holds live contacts. */
static gyro_world* rigid_session(int64_t* steps) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_mesh *ground_mesh = grid_mesh(6, 6, 4.0f), *ramp_mesh = grid_mesh(2, 2, 1.5f);
  gyro_convex_hull* hull = roof_hull();
  gyro_body_def d;
  gyro_body_id s1, s3, b1, b2, b3, cap, h1, extra;
  int i;
  if (!ground_mesh || !ramp_mesh || !hull || gyro_world_create(&wd, &w) != GYRO_OK) {
    CHECK(0);
    return NULL;
  }
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_MESH, d.mesh = ground_mesh;
  add_body(w, &d);
  d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_SPHERE, d.radius = 0.5f;
  d.position = vec3(-2.0f, 2.0f, 0.0f), s1 = add_body(w, &d);
  d.position = vec3(-2.0f, 3.2f, 0.1f), add_body(w, &d);
  d.position = vec3(3.0f, 1.5f, -2.0f), d.restitution = 0.4f, s3 = add_body(w, &d);
  d = gyro_body_def_default();
  d.position = vec3(0.0f, 0.6f, 0.0f), b1 = add_body(w, &d);
  d.position = vec3(0.1f, 1.7f, 0.0f), b2 = add_body(w, &d);
  d.half_extents = vec3(1.0f, 0.25f, 0.5f), d.position = vec3(2.0f, 3.0f, 1.0f);
  d.orientation = quat(0.0f, 0.29552f, 0.0f, 0.95534f), b3 = add_body(w, &d);
  d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_CAPSULE, d.radius = 0.3f, d.half_height = 0.5f;
  d.position = vec3(-1.0f, 4.0f, 2.0f), d.orientation = quat(0.0f, 0.0f, 0.38268f, 0.92388f), cap = add_body(w, &d);
  d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_HULL, d.hull = hull, d.density = 2.0f;
  d.position = vec3(1.0f, 5.0f, -1.0f), h1 = add_body(w, &d);
  d = gyro_body_def_default(), d.type = GYRO_BODY_KINEMATIC, d.half_extents = vec3(0.5f, 0.3f, 0.5f);
  d.position = vec3(-6.0f, 0.5f, 4.0f), d.linear_velocity = vec3(1.5f, 0.0f, 0.0f);
  add_body(w, &d);
  step(w, 5);

  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  g_calls = 0, *steps = 0;
  /* A mesh body and a second one on the same mesh (stored once), while recording. */
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_MESH, d.mesh = ramp_mesh;
  d.position = vec3(6.0f, 0.2f, 6.0f), d.orientation = quat(0.1305f, 0.0f, 0.0f, 0.99144f);
  add_body(w, &d);
  d.position = vec3(-6.0f, 0.2f, -6.0f);
  add_body(w, &d);
  for (i = 0; i < 120; ++i) {
    if (i == 0) {
      DO(gyro_body_apply_force(w, s1, vec3(120.0f, 0.0f, 10.0f), vec3(-2.0f, 2.3f, 0.0f)));
      DO(gyro_body_apply_force_at_center(w, b1, vec3(0.0f, 0.0f, -40.0f)));
      DO(gyro_body_apply_torque(w, cap, vec3(0.0f, 3.0f, 1.0f)));
    }
    if (i == 10) {
      DO(gyro_body_apply_linear_impulse(w, h1, vec3(1.5f, 2.0f, 0.0f), vec3(1.2f, 4.0f, -1.0f)));
      DO(gyro_body_apply_angular_impulse(w, b3, vec3(0.0f, 0.8f, 0.0f)));
    }
    if (i == 20) DO(gyro_body_set_velocity(w, s3, vec3(0.0f, 5.0f, 0.5f), vec3(0.0f, 1.0f, 0.0f)));
    if (i == 30) DO(gyro_body_set_transform(w, b3, vec3(0.0f, 6.0f, 0.5f), quat(0.0f, 0.0f, 0.0f, 1.0f)));
    if (i == 40) DO(gyro_body_destroy(w, b2));
    if (i == 50) {
      d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_SPHERE, d.radius = 0.35f;
      d.position = vec3(0.0f, 4.0f, 0.0f), extra = add_body(w, &d);
      (void)extra;
      d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_HULL, d.hull = hull;
      d.position = vec3(-3.0f, 6.0f, -2.0f), add_body(w, &d);
    }
    if (i == 60) DO(gyro_body_set_awake(w, s1, 0));
    if (i == 70) DO(gyro_body_set_awake(w, s1, 1));
    DO(gyro_world_step(w, kDt));
    ++*steps;
  }
  gyro_mesh_destroy(ground_mesh);
  gyro_mesh_destroy(ramp_mesh);
  gyro_convex_hull_destroy(hull);
  return w;
}

/* A cloth pinned at two corners over a sphere, a soft cube with joints and a soft
 * octahedron, with every soft-body call; recording begins on a world with only colliders. */
static gyro_world* soft_session(int64_t* steps) {
  static const float ox[6] = {1.0f, -1.0f, 0.0f, 0.0f, 0.0f, 0.0f}, oy[6] = {0.0f, 0.0f, 1.0f, -1.0f, 0.0f, 0.0f},
                     oz[6] = {0.0f, 0.0f, 0.0f, 0.0f, 1.0f, -1.0f};
  static const uint32_t ot[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_body_def d;
  gyro_cloth_def cd = gyro_cloth_def_default();
  gyro_soft_cube_def kd = gyro_soft_cube_def_default();
  gyro_soft_mesh_def md = gyro_soft_mesh_def_default();
  gyro_soft_settings ss = gyro_soft_settings_default();
  gyro_spring_constants sc;
  gyro_soft_body_id cloth, cube, octa;
  uint32_t c00 = 0, c90 = 0, joint = 0;
  float mx[6], my[6], mz[6];
  int i;
  if (gyro_world_create(&wd, &w) != GYRO_OK) {
    CHECK(0);
    return NULL;
  }
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_PLANE;
  add_body(w, &d);
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_SPHERE, d.radius = 1.0f;
  d.position = vec3(0.0f, 1.0f, 0.0f), add_body(w, &d);

  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  g_calls = 0, *steps = 0;
  d = gyro_body_def_default(), d.position = vec3(3.0f, 1.0f, 0.0f);
  add_body(w, &d);
  cd.nx = 10, cd.nz = 10, cd.size_x = 4.0f, cd.size_z = 4.0f, cd.center = vec3(0.0f, 2.6f, 0.0f);
  cd.particle_mass = 0.05f;
  DO(gyro_world_create_cloth(w, &cd, &cloth));
  CHECK(gyro_soft_body_cloth_index(w, cloth, 0, 0, &c00) == GYRO_OK);
  CHECK(gyro_soft_body_cloth_index(w, cloth, 9, 0, &c90) == GYRO_OK);
  DO(gyro_soft_body_pin(w, cloth, c00));
  DO(gyro_soft_body_pin(w, cloth, c90));
  ss.substeps = 8, ss.friction = 0.4f;
  DO(gyro_soft_body_set_settings(w, cloth, &ss));
  sc.stiffness = 5000.0f, sc.damping = 0.5f;
  DO(gyro_soft_body_set_family(w, cloth, GYRO_SPRING_SHEAR, &sc));
  DO(gyro_soft_body_set_mass(w, cloth, 0.04f));
  DO(gyro_soft_body_set_particle_mass(w, cloth, 55, 0.2f));
  kd.center = vec3(3.0f, 3.0f, 0.0f), kd.half_extent = 0.4f;
  DO(gyro_world_create_soft_cube(w, &kd, &cube));
  DO(gyro_soft_body_add_distance_joint(w, cube, 0, 7, -1.0f, &joint));
  DO(gyro_soft_body_add_distance_joint(w, cube, 1, 6, 1.0f, NULL));
  DO(gyro_soft_body_add_ball_joint(w, cube, 2, 3));
  DO(gyro_soft_body_add_hinge_joint(w, cube, 0, 1, 4, 5));
  for (i = 0; i < 6; ++i) mx[i] = ox[i] * 0.5f - 3.0f, my[i] = oy[i] * 0.5f + 3.0f, mz[i] = oz[i] * 0.5f;
  md.vertex_count = 6, md.x = mx, md.y = my, md.z = mz, md.indices = ot, md.triangle_count = 8;
  md.particle_mass = 0.1f;
  DO(gyro_world_create_soft_mesh(w, &md, &octa));
  DO(gyro_soft_body_set_velocity(w, octa, 6, vec3(0.0f, 0.0f, 1.0f)));
  for (i = 0; i < 80; ++i) {
    if (i == 15) DO(gyro_soft_body_set_position(w, cloth, c90, vec3(2.2f, 2.8f, -2.0f)));
    if (i == 20) DO(gyro_soft_body_set_velocity(w, cloth, 40, vec3(0.0f, 2.0f, 0.0f)));
    if (i == 30) {
      ss.iterations = 2;
      DO(gyro_soft_body_set_settings(w, cloth, &ss));
    }
    if (i == 40) DO(gyro_soft_body_unpin(w, cloth, c00));
    if (i == 60) DO(gyro_world_destroy_soft_body(w, cube));
    DO(gyro_world_step(w, kDt));
    ++*steps;
  }
  return w;
}

/* ------------------------------------------------------------------ tests */

/* Replays a session's recording in memory and from a file: no divergence, the live hash. */
static void check_roundtrip(gyro_world* w, int64_t steps, const char* file) {
  uint64_t size = 0;
  unsigned char* b = recording_of(w, &size);
  gyro_replay_report r = report_init();
  const uint64_t live = hash_of(w);
  if (!b) return;
  CHECK(gyro_replay(b, size, &r) == GYRO_OK);
  if (r.diverged || r.calls != g_calls || r.steps != steps)
    fprintf(stderr, "%s: diverged %u at step %lld, %lld calls (%lld made), %lld steps (%lld made)\n", file, r.diverged,
            (long long)r.first_divergent_step, (long long)r.calls, (long long)g_calls, (long long)r.steps,
            (long long)steps);
  CHECK(r.struct_size == sizeof r && r.diverged == 0 && r.first_divergent_step == -1);
  CHECK(r.expected_hash == 0 && r.actual_hash == 0);
  CHECK(r.steps == steps && r.calls == g_calls);
  CHECK(r.final_hash == live);
  CHECK(gyro_world_record_save(w, file) == GYRO_OK);
  r = report_init();
  CHECK(gyro_replay_file(file, &r) == GYRO_OK);
  CHECK(r.diverged == 0 && r.steps == steps && r.calls == g_calls && r.final_hash == live);
  remove(file);
  free(b);
}

static void test_rigid(void) {
  int64_t steps = 0;
  gyro_world* w = rigid_session(&steps);
  if (!w) return;
  CHECK(steps == 120);
  check_roundtrip(w, steps, "replay_test_rigid.gyrorec");
  CHECK(gyro_world_record_end(w) == GYRO_OK);
  gyro_world_destroy(w);
}

static void test_soft(void) {
  int64_t steps = 0;
  gyro_world* w = soft_session(&steps);
  if (!w) return;
  check_roundtrip(w, steps, "replay_test_soft.gyrorec");
  CHECK(gyro_world_record_end(w) == GYRO_OK);
  gyro_world_destroy(w);
}

/* Flipped bytes, truncations, an extra byte, and (checksum fixed) an unknown opcode, a bad
 * payload size, another format version, wrong end counts: all CORRUPT_DATA. */
static void test_corrupt(void) {
  int64_t steps = 0;
  gyro_world* w = rigid_session(&steps);
  uint64_t size = 0, i, at;
  unsigned char *b, *m;
  gyro_replay_report r;
  if (!w) return;
  b = recording_of(w, &size);
  m = (unsigned char*)malloc(size + 1);
  if (!b || !m) return;
  for (i = 0; i < size; i += 1 + size / 97) {
    memcpy(m, b, size);
    m[i] ^= (unsigned char)(1u << (i % 8));
    r = report_init();
    CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
    CHECK(r.diverged == 0xABABABABu); /* nothing written on error */
  }
  {
    const uint64_t cuts[] = {0, 1, 7, 24, 31, 40, size / 2, size - 33, size - 9, size - 8, size - 1};
    for (i = 0; i < sizeof cuts / sizeof cuts[0]; ++i) {
      r = report_init();
      CHECK(gyro_replay(b, cuts[i], &r) == GYRO_STATUS_CORRUPT_DATA);
    }
  }
  memcpy(m, b, size), m[size] = 0;
  r = report_init();
  CHECK(gyro_replay(m, size + 1, &r) == GYRO_STATUS_CORRUPT_DATA);

  at = find_record(b, size, OP_STEP, 3);
  CHECK(at != 0);
  memcpy(m, b, size), put32(m + at, 999), fix_checksum(m, size);
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), put32(m + at + 4, 0x7FFFFFF0u), fix_checksum(m, size);
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), put32(m + at + 4, 8), fix_checksum(m, size); /* a short step record */
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), put32(m + 8, 2), fix_checksum(m, size); /* format version 2 */
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), m[0] = 'X', fix_checksum(m, size);
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), put64(m + size - 24, le64(b + size - 24) + 1), fix_checksum(m, size); /* end: calls */
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), put64(m + HEADER, le64(b + HEADER) + 5), fix_checksum(m, size); /* snapshot size */
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  memcpy(m, b, size), m[HEADER + 8 + 20] ^= 0x40, fix_checksum(m, size); /* inside the snapshot */
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  at = find_record(b, size, OP_BODY_CREATE, 0); /* a mesh reference past the meshes read */
  CHECK(at != 0);
  {
    const uint32_t n = le32(b + at + 4);
    memcpy(m, b, size), put32(m + at + 8 + n - 16, 7), fix_checksum(m, size);
    CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  }
  at = find_record(b, size, OP_MESH, 0); /* a mesh index out of range */
  CHECK(at != 0);
  memcpy(m, b, size), put32(m + at + 8 + 8 + 12 * le32(b + at + 8), 100000), fix_checksum(m, size);
  CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  at = find_record(b, size, OP_HULL, 0); /* a hull face vertex out of range */
  CHECK(at != 0);
  {
    const uint32_t nv = le32(b + at + 8), nf = le32(b + at + 8 + 4 + 12 * nv);
    memcpy(m, b, size), put32(m + at + 8 + 4 + 12 * nv + 4 + 4 * (nf + 1) + 4, 5000), fix_checksum(m, size);
    CHECK(gyro_replay(m, size, &r) == GYRO_STATUS_CORRUPT_DATA);
  }
  free(m);
  free(b);
  gyro_world_destroy(w); /* destroyed while recording: the recording goes with it */
}

/* A tampered step hash is a divergence at that step (the rest replays to the live hash). */
static void test_tampered_hash(void) {
  int64_t steps = 0;
  gyro_world* w = rigid_session(&steps);
  uint64_t size = 0, at, recorded;
  unsigned char* b;
  gyro_replay_report r = report_init();
  if (!w) return;
  b = recording_of(w, &size);
  if (!b) return;
  at = find_record(b, size, OP_STEP, 7);
  CHECK(at != 0 && le32(b + at + 4) == 12);
  recorded = le64(b + at + 12);
  put64(b + at + 12, recorded ^ 0x100);
  fix_checksum(b, size);
  CHECK(gyro_replay(b, size, &r) == GYRO_OK);
  CHECK(r.diverged == 1 && r.first_divergent_step == 7);
  CHECK(r.expected_hash == (recorded ^ 0x100) && r.actual_hash == recorded);
  CHECK(r.steps == steps && r.calls == g_calls && r.final_hash == hash_of(w));
  free(b);
  gyro_world_destroy(w);
}

/* Failed calls change nothing and are not recorded; successful ones are. */
static void test_only_successes(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_body_def d = gyro_body_def_default();
  gyro_body_id id, stale;
  gyro_soft_body_id cloth;
  gyro_cloth_def cd = gyro_cloth_def_default();
  uint64_t n;
  const float nan = strtof("nan", NULL);
  if (gyro_world_create(&wd, &w) != GYRO_OK) return;
  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  g_calls = 0;
  DO(gyro_body_create(w, &d, &id));
  cd.nx = 4, cd.nz = 4;
  DO(gyro_world_create_cloth(w, &cd, &cloth));
  stale = id, stale.generation += 7;
  n = record_size(w);
  CHECK(gyro_body_set_velocity(w, id, vec3(nan, 0.0f, 0.0f), vec3(0.0f, 0.0f, 0.0f)) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_torque(w, stale, vec3(1.0f, 0.0f, 0.0f)) == GYRO_STATUS_STALE_ID);
  CHECK(gyro_world_step(w, -1.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_body_set_awake(w, id, 2) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_soft_body_pin(w, cloth, 1000) == GYRO_STATUS_INVALID_ARGUMENT);
  d.radius = -1.0f, d.shape = GYRO_BODY_SHAPE_SPHERE;
  CHECK(gyro_body_create(w, &d, &id) != GYRO_OK);
  CHECK(record_size(w) == n);
  DO(gyro_body_apply_torque(w, id, vec3(1.0f, 0.0f, 0.0f)));
  CHECK(record_size(w) > n);
  step(w, 3);
  check_roundtrip(w, 3, "replay_test_small.gyrorec");
  gyro_world_destroy(w);
}

/* A mesh or hull is stored the first time a call names it, then named by index: also when
 * another handle holds the same geometry. */
static void test_geometry_once(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_mesh *m1 = grid_mesh(4, 4, 1.0f), *m2 = grid_mesh(4, 4, 1.0f);
  gyro_convex_hull *h1 = roof_hull(), *h2 = roof_hull();
  gyro_body_def d;
  uint64_t n0, n1, n2, n3;
  if (!m1 || !m2 || !h1 || !h2 || gyro_world_create(&wd, &w) != GYRO_OK) return;
  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  g_calls = 0;
  d = gyro_body_def_default(), d.type = GYRO_BODY_STATIC, d.shape = GYRO_BODY_SHAPE_MESH, d.mesh = m1;
  n0 = record_size(w), add_body(w, &d), n1 = record_size(w);
  add_body(w, &d), n2 = record_size(w);
  d.mesh = m2, add_body(w, &d), n3 = record_size(w);
  CHECK(n1 - n0 > 4 * 25 * 3 && n2 - n1 == n3 - n2 && n2 - n1 < 200);
  d = gyro_body_def_default(), d.shape = GYRO_BODY_SHAPE_HULL, d.hull = h1, d.position.y = 3.0f;
  n0 = record_size(w), add_body(w, &d), n1 = record_size(w);
  d.position.x = 2.0f, add_body(w, &d), n2 = record_size(w);
  d.hull = h2, d.position.x = -2.0f, add_body(w, &d), n3 = record_size(w);
  CHECK(n1 - n0 > n2 - n1 && n2 - n1 == n3 - n2);
  gyro_mesh_destroy(m1), gyro_mesh_destroy(m2);
  gyro_convex_hull_destroy(h1), gyro_convex_hull_destroy(h2);
  step(w, 30);
  check_roundtrip(w, 30, "replay_test_geometry.gyrorec");
  gyro_world_destroy(w);
}

/* An ABI 1.3 body definition is recorded as the equivalent current one. */
static void test_abi13_def(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  gyro_body_def d = gyro_body_def_default();
  if (sizeof(void*) != 8 || gyro_world_create(&wd, &w) != GYRO_OK) return;
  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  g_calls = 0;
  d.struct_size = 144, d.position.y = 2.0f;
  add_body(w, &d);
  step(w, 10);
  check_roundtrip(w, 10, "replay_test_abi13.gyrorec");
  gyro_world_destroy(w);
}

/* A restore while recording is recorded: replay restores the same state and follows it. */
static void test_restore(void) {
  int64_t steps = 0;
  gyro_world* w = rigid_session(&steps);
  uint64_t n = 0, got = 0;
  unsigned char* snap;
  if (!w) return;
  CHECK(gyro_world_snapshot_size(w, &n) == GYRO_OK);
  snap = (unsigned char*)malloc(n ? n : 1);
  if (!snap) return;
  CHECK(gyro_world_snapshot(w, snap, n, &got) == GYRO_OK);
  step(w, 20);
  DO(gyro_world_restore(w, snap, got));
  step(w, 10);
  check_roundtrip(w, steps + 30, "replay_test_restore.gyrorec");
  free(snap);
  gyro_world_destroy(w);
}

/* The record calls' errors. */
static void test_api_errors(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_world* w = NULL;
  uint64_t n = 0, got = 0;
  unsigned char buf[64];
  gyro_replay_report r = report_init();
  if (gyro_world_create(&wd, &w) != GYRO_OK) return;
  CHECK(gyro_world_record_begin(NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_size(w, &n) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_copy(w, buf, sizeof buf, &got) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_save(w, "replay_test_never.gyrorec") == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_end(w) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_end(NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_begin(w) == GYRO_OK);
  CHECK(gyro_world_record_begin(w) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_size(NULL, &n) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_size(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_size(w, &n) == GYRO_OK && n > 56);
  got = 12345;
  memset(buf, 0x5A, sizeof buf);
  CHECK(gyro_world_record_copy(w, buf, n - 1, &got) == GYRO_STATUS_INVALID_COUNT);
  CHECK(got == 12345 && buf[0] == 0x5A);
  CHECK(gyro_world_record_copy(w, NULL, n, &got) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_save(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_record_save(w, "/nonexistent-dir/x/y.gyrorec") == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_record_end(w) == GYRO_OK);
  CHECK(gyro_world_record_end(w) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_replay(NULL, 10, &r) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_replay(buf, sizeof buf, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  r.struct_size = 12;
  CHECK(gyro_replay(buf, sizeof buf, &r) == GYRO_STATUS_INVALID_ARGUMENT);
  r = report_init();
  CHECK(gyro_replay(buf, 0, &r) == GYRO_STATUS_CORRUPT_DATA);
  CHECK(gyro_replay(buf, sizeof buf, &r) == GYRO_STATUS_CORRUPT_DATA);
  CHECK(gyro_replay_file(NULL, &r) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_replay_file("/nonexistent-dir/none.gyrorec", &r) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_replay_file(".", &r) != GYRO_OK); /* a directory */
  CHECK((gyro_features() & GYRO_FEATURE_REPLAY) != 0);
  gyro_world_destroy(w);
}

/* Mutated recordings with the checksum fixed (so the parser itself is reached): replay
 * answers OK or CORRUPT_DATA, never crashes. Bytes of the records are mutated (the snapshot
 * is its own format's), except a cloth's definition, which a mutation may turn into a
 * legitimate million-particle cloth that takes minutes to step. */
static void mutate(const unsigned char* b, uint64_t size, uint32_t* seed, int runs) {
  const uint64_t start = HEADER + 8 + le64(b + HEADER);
  uint64_t skip_at = find_record(b, size, 64, 0), skip_end = 0, i;
  unsigned char* m = (unsigned char*)malloc(size);
  int k, ok = 0, corrupt = 0;
  if (!m) return;
  if (skip_at) skip_end = skip_at + 8 + le32(b + skip_at + 4);
  for (k = 0; k < runs; ++k) {
    int flips = 1 + k % 3, f;
    gyro_replay_report r = report_init();
    gyro_status s;
    memcpy(m, b, size);
    for (f = 0; f < flips; ++f) {
      do {
        *seed = *seed * 1664525u + 1013904223u;
        i = start + (*seed >> 8) % (size - 8 - start);
      } while (i >= skip_at && i < skip_end);
      *seed = *seed * 1664525u + 1013904223u;
      m[i] ^= (unsigned char)(1u + (*seed >> 24) % 255u);
    }
    fix_checksum(m, size);
    s = gyro_replay(m, size, &r);
    CHECK(s == GYRO_OK || s == GYRO_STATUS_CORRUPT_DATA);
    ok += s == GYRO_OK, corrupt += s == GYRO_STATUS_CORRUPT_DATA;
  }
  CHECK(ok > 0 && corrupt > 0);
  /* Random bytes of many lengths. */
  for (k = 0; k < 50; ++k) {
    gyro_replay_report r = report_init();
    for (i = 0; i < size; ++i) *seed = *seed * 1664525u + 1013904223u, m[i] = (unsigned char)(*seed >> 24);
    CHECK(gyro_replay(m, 1 + (uint64_t)k * (size / 50), &r) == GYRO_STATUS_CORRUPT_DATA);
  }
  free(m);
}

/* GYRO_TEST_QUICK (make sanitize sets it): the instrumented build replays 30 mutations of
 * each recording, not 200 (the fuzz target mutates recordings too, under the same sanitizers). */
static void test_mutations(void) {
  uint32_t seed = 12345u;
  int64_t steps = 0;
  const int runs = getenv("GYRO_TEST_QUICK") ? 30 : 200;
  int s;
  for (s = 0; s < 2; ++s) {
    gyro_world* w = s == 0 ? rigid_session(&steps) : soft_session(&steps);
    uint64_t size = 0;
    unsigned char* b;
    if (!w) return;
    b = recording_of(w, &size);
    if (b) mutate(b, size, &seed, runs);
    free(b);
    gyro_world_destroy(w);
  }
}

/* ------------------------------------------------------------------ goldens */

static int regenerate(const char* dir) {
  char path[4096];
  int64_t steps = 0;
  gyro_world* w;
  int g;
  for (g = 0; g < GOLDEN_COUNT; ++g) {
    w = g == 0 ? rigid_session(&steps) : soft_session(&steps);
    if (!w) return 1;
    snprintf(path, sizeof path, "%s/%s", dir, kGoldens[g]);
    CHECK(gyro_world_record_save(w, path) == GYRO_OK);
    printf("wrote %s (%llu bytes, %lld steps)\n", path, (unsigned long long)record_size(w), (long long)steps);
    gyro_world_destroy(w);
  }
  return failures ? 1 : 0;
}

static int golden(const char* dir) {
  static const gyro_simd_level levels[] = {GYRO_SIMD_SCALAR, GYRO_SIMD_SSE2, GYRO_SIMD_AVX2, GYRO_SIMD_AVX512,
                                           GYRO_SIMD_NEON};
  static const uint32_t threads[] = {1, 3};
  char path[4096];
  int g, l, t;
  for (g = 0; g < GOLDEN_COUNT; ++g) {
    uint64_t first_final = 0;
    snprintf(path, sizeof path, "%s/%s", dir, kGoldens[g]);
    for (l = 0; l < 5; ++l) {
      if (!gyro_simd_level_available(levels[l])) continue;
      CHECK(gyro_set_simd_level(levels[l]) == GYRO_OK);
      for (t = 0; t < 2; ++t) {
        gyro_replay_report r = report_init();
        gyro_status s;
        CHECK(gyro_set_thread_count(threads[t]) == GYRO_OK);
        s = gyro_replay_file(path, &r);
        CHECK(s == GYRO_OK);
        if (s != GYRO_OK) {
          fprintf(stderr, "%s: %s (%s)\n", path, gyro_status_name(s), gyro_last_error());
          return 1;
        }
        if (r.diverged)
          fprintf(stderr,
                  "%s at %s, %u threads: diverged at step %lld (recorded hash %016llx, replayed %016llx).\n"
                  "If this change alters results on purpose, regenerate the goldens (see the top of "
                  "tests/replay/replay_test.c).\n",
                  path, gyro_simd_level_name(levels[l]), threads[t], (long long)r.first_divergent_step,
                  (unsigned long long)r.expected_hash, (unsigned long long)r.actual_hash);
        CHECK(r.diverged == 0 && r.steps > 0);
        if (!first_final) first_final = r.final_hash;
        CHECK(r.final_hash == first_final);
        printf("%s %s/%u threads: %lld steps, %lld calls, final hash %016llx%s\n", kGoldens[g],
               gyro_simd_level_name(levels[l]), threads[t], (long long)r.steps, (long long)r.calls,
               (unsigned long long)r.final_hash, r.diverged ? " DIVERGED" : "");
      }
    }
  }
  gyro_set_simd_level(GYRO_SIMD_AUTO);
  gyro_set_thread_count(0);
  return failures ? 1 : 0;
}

int main(int argc, char** argv) {
  if (argc == 3 && strcmp(argv[1], "--regenerate") == 0) return regenerate(argv[2]);
  if (argc == 3 && strcmp(argv[1], "--golden") == 0) return golden(argv[2]);
  if (argc == 2 && strcmp(argv[1], "--restore") == 0) {
    test_restore();
    return failures ? 1 : 0;
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s [--golden DIR | --regenerate DIR | --restore]\n", argv[0]);
    return 2;
  }
  test_rigid();
  test_soft();
  test_corrupt();
  test_tampered_hash();
  test_only_successes();
  test_geometry_once();
  test_abi13_def();
  test_api_errors();
  test_mutations();
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("replay: all checks passed\n");
  return 0;
}
