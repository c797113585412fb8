/* The dynamics world's C ABI from a C99 program: a box falls onto a ground box and comes to
 * rest at the right height; two worlds fed the same calls hash the same; the zero-copy view
 * agrees with gyro_body_get_transform; the landing is one begin event; forces, impulses,
 * velocities, sleep and user data round-trip; a mesh body outlives its handle; and every
 * bad input (NULL, NaN/Inf, stale ids, wrong struct_size, dt <= 0 or NaN, ...) returns its
 * documented status and leaves the world's hash unchanged. */
#include "gyro.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

STATIC_ASSERT(sizeof(gyro_vec3) == 12, vec3);
STATIC_ASSERT(sizeof(gyro_quat) == 16, quat);
STATIC_ASSERT(sizeof(gyro_body_id) == 8, body_id);
STATIC_ASSERT(sizeof(gyro_body_type) == 4 && sizeof(gyro_body_shape) == 4 && sizeof(gyro_contact_model) == 4, enums);
STATIC_ASSERT(sizeof(gyro_world_def) == 92, world_def);
STATIC_ASSERT(sizeof(gyro_step_timings) == 56, step_timings);
STATIC_ASSERT(sizeof(gyro_step_stats) == 32, step_stats);
STATIC_ASSERT(sizeof(gyro_contact_event) == 16, contact_event);
STATIC_ASSERT(sizeof(void*) != 8 || sizeof(gyro_body_def) == 160, body_def_64);
STATIC_ASSERT(sizeof(void*) != 8 || sizeof(gyro_body_view) == 120, body_view_64);
STATIC_ASSERT(sizeof(void*) != 8 || sizeof(gyro_contact_events) == 24, contact_events_64);

static const float kDt = 1.0f / 60.0f;

static gyro_vec3 vec3(float x, float y, float z) {
  gyro_vec3 v;
  v.x = x, v.y = y, v.z = z;
  return v;
}

static gyro_quat identity(void) {
  gyro_quat q;
  q.x = q.y = q.z = 0.0f, q.w = 1.0f;
  return q;
}

static int same_id(gyro_body_id a, gyro_body_id b) { return a.index == b.index && a.generation == b.generation; }

static uint64_t hash_of(const gyro_world* w) {
  uint64_t h = 0;
  CHECK(gyro_world_hash(w, &h) == GYRO_OK);
  return h;
}

/* A world with sleep off (so every step does the full work), a static ground box with its
 * top face at y = 0 and a dynamic unit box (1 kg) whose bottom face starts at y = drop. */
static gyro_world* drop_scene(float drop, gyro_body_id* ground, gyro_body_id* box) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def gd = gyro_body_def_default(), bd = gyro_body_def_default();
  gyro_world* w = NULL;
  wd.enable_sleep = 0;
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK && w != NULL);
  if (!w) return NULL;
  gd.type = GYRO_BODY_STATIC;
  gd.half_extents = vec3(10.0f, 0.5f, 10.0f);
  gd.position = vec3(0.0f, -0.5f, 0.0f);
  gd.user_data = 1;
  CHECK(gyro_body_create(w, &gd, ground) == GYRO_OK);
  bd.position = vec3(0.0f, 0.5f + drop, 0.0f);
  bd.user_data = 0xB0C5u;
  CHECK(gyro_body_create(w, &bd, box) == GYRO_OK);
  return w;
}

/* Counts the events naming the pair (a, b) in either order. */
static int count_pair(const gyro_contact_event* e, int32_t n, gyro_body_id a, gyro_body_id b) {
  int32_t i;
  int c = 0;
  for (i = 0; i < n; ++i)
    c += (same_id(e[i].a, a) && same_id(e[i].b, b)) || (same_id(e[i].a, b) && same_id(e[i].b, a));
  return c;
}

static void test_versions(void) {
  CHECK(gyro_abi_version() >> 16 == GYRO_ABI_VERSION >> 16);
  CHECK((gyro_abi_version() & 0xFFFFu) >= 2u); /* the world arrived in ABI 1.2 */
  CHECK(gyro_features() & GYRO_FEATURE_DYNAMICS);
}

static void test_fall_and_rest(void) {
  gyro_body_id ground, box, ground2, box2;
  gyro_world* w = drop_scene(2.0f, &ground, &box);
  gyro_world* twin = drop_scene(2.0f, &ground2, &box2);
  gyro_world* other = drop_scene(2.001f, &ground2, &box2);
  gyro_vec3 p, v, wv;
  gyro_quat q;
  gyro_body_view view;
  gyro_contact_events ev;
  gyro_step_stats stats;
  gyro_step_timings timings;
  int step, begins = 0, ends = 0, hashes_equal = 1;
  int32_t i, count = 0;
  if (!w || !twin || !other) return;
  CHECK(gyro_world_body_count(w, &count) == GYRO_OK && count == 2);
  CHECK(hash_of(w) == hash_of(twin));
  CHECK(hash_of(w) != hash_of(other)); /* the hash sees a 1 mm difference */
  for (step = 0; step < 120; ++step) { /* 2 s */
    CHECK(gyro_world_step(w, kDt) == GYRO_OK);
    CHECK(gyro_world_step(twin, kDt) == GYRO_OK);
    CHECK(gyro_world_step(other, kDt) == GYRO_OK);
    hashes_equal &= hash_of(w) == hash_of(twin);
    if (step == 10) CHECK(hash_of(w) != hash_of(other)); /* still falling: a different state */
    CHECK(gyro_world_get_contact_events(w, &ev) == GYRO_OK);
    CHECK(ev.begin_count >= 0 && ev.end_count >= 0);
    CHECK((ev.begin_count == 0) == (ev.begin == NULL) && (ev.end_count == 0) == (ev.end == NULL));
    begins += count_pair(ev.begin, ev.begin_count, ground, box);
    ends += count_pair(ev.end, ev.end_count, ground, box);
  }
  CHECK(hashes_equal);
  CHECK(begins == 1 && ends == 0);

  /* at rest on the ground: centre 0.5 m above its top face, within 1 cm; upright, still */
  CHECK(gyro_body_get_transform(w, box, &p, &q) == GYRO_OK);
  CHECK(fabsf(p.y - 0.5f) < 0.01f && fabsf(p.x) < 0.01f && fabsf(p.z) < 0.01f);
  CHECK(fabsf(q.w) > 0.9999f);
  CHECK(gyro_body_get_velocity(w, box, &v, &wv) == GYRO_OK);
  CHECK(fabsf(v.x) + fabsf(v.y) + fabsf(v.z) < 0.01f && fabsf(wv.x) + fabsf(wv.y) + fabsf(wv.z) < 0.01f);
  CHECK(gyro_body_get_transform(w, ground, &p, &q) == GYRO_OK && p.y == -0.5f && q.w == 1.0f);

  /* the zero-copy view agrees bit for bit with the per-body getters */
  CHECK(gyro_world_get_body_view(w, &view) == GYRO_OK);
  CHECK(view.count == 2 && view.ids != NULL && view.px != NULL && view.wz != NULL);
  for (i = 0; i < view.count; ++i) {
    CHECK(gyro_body_get_transform(w, view.ids[i], &p, &q) == GYRO_OK);
    CHECK(gyro_body_get_velocity(w, view.ids[i], &v, &wv) == GYRO_OK);
    CHECK(p.x == view.px[i] && p.y == view.py[i] && p.z == view.pz[i]);
    CHECK(q.x == view.qx[i] && q.y == view.qy[i] && q.z == view.qz[i] && q.w == view.qw[i]);
    CHECK(v.x == view.vx[i] && v.y == view.vy[i] && v.z == view.vz[i]);
    CHECK(wv.x == view.wx[i] && wv.y == view.wy[i] && wv.z == view.wz[i]);
  }
  CHECK((same_id(view.ids[0], ground) && same_id(view.ids[1], box)) ||
        (same_id(view.ids[0], box) && same_id(view.ids[1], ground)));

  CHECK(gyro_world_get_stats(w, &stats) == GYRO_OK);
  CHECK(stats.bodies == 2 && stats.manifolds >= 1 && stats.contacts >= 1 && stats.reserved == 0);
  CHECK(gyro_world_get_timings(w, &timings) == GYRO_OK);
  CHECK(timings.total >= 0.0 && timings.solver >= 0.0 && timings.total >= timings.solver);

  gyro_world_destroy(w);
  gyro_world_destroy(twin);
  gyro_world_destroy(other);
  gyro_world_destroy(NULL);
}

static void test_body_state(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd = gyro_body_def_default();
  gyro_world* w = NULL;
  gyro_body_id a, b;
  gyro_vec3 v, wv, p;
  gyro_quat q;
  float mass = 0.0f;
  gyro_body_type type = 99;
  uint64_t user = 0;
  uint32_t awake = 7;
  wd.gravity = vec3(0.0f, 0.0f, 0.0f);
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK);
  if (!w) return;
  bd.user_data = 0x1234567890ABCDEFull;
  CHECK(gyro_body_create(w, &bd, &a) == GYRO_OK);
  bd.position = vec3(5.0f, 0.0f, 0.0f);
  bd.user_data = 2;
  CHECK(gyro_body_create(w, &bd, &b) == GYRO_OK);
  CHECK(!same_id(a, b) && gyro_body_is_valid(w, a) && gyro_body_is_valid(w, b));

  CHECK(gyro_body_get_mass(w, a, &mass) == GYRO_OK && fabsf(mass - 1.0f) < 1e-6f); /* 1 m^3 at density 1 */
  CHECK(gyro_body_get_type(w, a, &type) == GYRO_OK && type == GYRO_BODY_DYNAMIC);
  CHECK(gyro_body_get_user_data(w, a, &user) == GYRO_OK && user == 0x1234567890ABCDEFull);

  /* an impulse at the centre changes the velocity at once: dv = J / m */
  CHECK(gyro_body_apply_linear_impulse(w, a, vec3(2.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, a, &v, &wv) == GYRO_OK && fabsf(v.x - 2.0f) < 1e-6f && v.y == 0.0f);
  CHECK(gyro_body_apply_angular_impulse(w, a, vec3(0.0f, 1.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, a, &v, &wv) == GYRO_OK && wv.y > 0.0f);
  CHECK(gyro_body_set_velocity(w, a, vec3(0.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, a, &v, &wv) == GYRO_OK && v.x == 0.0f && wv.y == 0.0f);

  /* a force at the centre for one step: dv = F dt / m; a torque spins; both last one step */
  CHECK(gyro_body_apply_force_at_center(w, b, vec3(60.0f, 0.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_body_apply_torque(w, a, vec3(0.0f, 0.0f, 6.0f)) == GYRO_OK);
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, b, &v, &wv) == GYRO_OK && fabsf(v.x - 1.0f) < 1e-4f);
  CHECK(gyro_body_get_velocity(w, a, &v, &wv) == GYRO_OK && wv.z > 0.0f);
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, b, &v, &wv) == GYRO_OK && fabsf(v.x - 1.0f) < 1e-4f); /* the force is gone */
  /* an off-centre force also spins the body */
  CHECK(gyro_body_apply_force(w, b, vec3(0.0f, 60.0f, 0.0f), vec3(5.5f, 0.0f, 0.0f)) == GYRO_OK);
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, b, &v, &wv) == GYRO_OK && v.y > 0.5f && wv.z > 0.0f);

  /* teleport */
  q = identity();
  q.y = 1.0f, q.w = 0.0f; /* half a turn about y */
  CHECK(gyro_body_set_transform(w, a, vec3(0.0f, 3.0f, 0.0f), q) == GYRO_OK);
  CHECK(gyro_body_get_transform(w, a, &p, &q) == GYRO_OK && p.y == 3.0f && fabsf(q.y) == 1.0f);

  CHECK(gyro_body_set_awake(w, a, 0) == GYRO_OK);
  CHECK(gyro_body_is_awake(w, a, &awake) == GYRO_OK && awake == 0);
  CHECK(gyro_body_set_awake(w, a, 1) == GYRO_OK);
  CHECK(gyro_body_is_awake(w, a, &awake) == GYRO_OK && awake == 1);

  CHECK(gyro_body_destroy(w, b) == GYRO_OK);
  CHECK(!gyro_body_is_valid(w, b) && gyro_body_is_valid(w, a));
  gyro_world_destroy(w);
}

/* A 40 x 40 m quad at y = 0 as a static mesh body; the caller's handle is released at once. */
static void test_mesh_body(void) {
  static const float mx[4] = {-20, 20, -20, 20}, my[4] = {0, 0, 0, 0}, mz[4] = {-20, -20, 20, 20};
  static const uint32_t tris[6] = {0, 2, 1, 1, 2, 3};
  gyro_mesh_def md = gyro_mesh_def_default();
  gyro_mesh* mesh = NULL;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def gd = gyro_body_def_default(), sd = gyro_body_def_default();
  gyro_world* w = NULL;
  gyro_body_id ground, ball;
  gyro_vec3 p;
  gyro_quat q;
  int step;
  md.x = mx, md.y = my, md.z = mz, md.vertex_count = 4, md.indices = tris, md.triangle_count = 2;
  CHECK(gyro_mesh_create(&md, &mesh) == GYRO_OK);
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK);
  if (!mesh || !w) return;
  gd.type = GYRO_BODY_STATIC;
  gd.shape = GYRO_BODY_SHAPE_MESH;
  gd.mesh = mesh;
  CHECK(gyro_body_create(w, &gd, &ground) == GYRO_OK);
  gyro_mesh_destroy(mesh); /* the world keeps its own reference */
  sd.shape = GYRO_BODY_SHAPE_SPHERE;
  sd.radius = 0.5f;
  sd.position = vec3(1.0f, 2.0f, 1.0f);
  CHECK(gyro_body_create(w, &sd, &ball) == GYRO_OK);
  for (step = 0; step < 120; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_body_get_transform(w, ball, &p, &q) == GYRO_OK && fabsf(p.y - 0.5f) < 0.01f);
  CHECK(gyro_body_destroy(w, ground) == GYRO_OK);
  gyro_world_destroy(w);
}

/* Every bad call returns its status and changes nothing: the hash and the body count stay. */
static void test_bad_input(void) {
  gyro_body_id ground, box, gone, out_id, null_id = {0, 0};
  gyro_world* w = drop_scene(1.0f, &ground, &box);
  gyro_world* untouched = (gyro_world*)&ground;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def bd = gyro_body_def_default();
  gyro_vec3 p, v, nan3 = {NAN, 0.0f, 0.0f}, inf3 = {0.0f, INFINITY, 0.0f}, zero3 = {0.0f, 0.0f, 0.0f};
  gyro_quat q = identity(), zero_q = {0.0f, 0.0f, 0.0f, 0.0f}, nan_q = {0.0f, 0.0f, 0.0f, NAN};
  gyro_body_view view;
  gyro_contact_events ev;
  gyro_step_stats stats;
  gyro_step_timings timings;
  uint64_t h, u;
  float mass;
  gyro_body_type type;
  uint32_t awake;
  int32_t count;
  int step;
  const gyro_body_id* stale[2];
  int k;
  if (!w) return;
  for (step = 0; step < 10; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  /* a body created and destroyed: its id is stale from now on */
  CHECK(gyro_body_create(w, &bd, &gone) == GYRO_OK);
  CHECK(gyro_body_destroy(w, gone) == GYRO_OK);
  h = hash_of(w);

  /* world creation: *out untouched */
  CHECK(gyro_world_create(NULL, &untouched) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_create(&wd, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  wd.struct_size = sizeof wd - 8; /* neither 1.4 nor 1.3 (sizeof wd - 4) */
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(strstr(gyro_last_error(), "struct_size") != NULL);
  wd = gyro_world_def_default();
  wd.gravity.y = NAN;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_NON_FINITE);
  wd = gyro_world_def_default();
  wd.contact_hertz = INFINITY;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_NON_FINITE);
  wd = gyro_world_def_default();
  wd.contact_model = 3;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  wd = gyro_world_def_default();
  wd.enable_sleep = 2;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  wd = gyro_world_def_default();
  wd.substeps = 0;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  wd = gyro_world_def_default();
  wd.velocity_iterations = 0;
  CHECK(gyro_world_create(&wd, &untouched) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(untouched == (gyro_world*)&ground);

  /* body creation: *out untouched, no body added */
  out_id = null_id;
  CHECK(gyro_body_create(NULL, &bd, &out_id) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_create(w, NULL, &out_id) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_create(w, &bd, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  bd.struct_size = 8;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.position = nan3;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_NON_FINITE);
  bd = gyro_body_def_default();
  bd.linear_velocity = inf3;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_NON_FINITE);
  bd = gyro_body_def_default();
  bd.orientation = nan_q;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_NON_FINITE);
  bd = gyro_body_def_default();
  bd.mass = NAN;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_NON_FINITE);
  bd = gyro_body_def_default();
  bd.mass = -1.0f;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.density = -1.0f;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.half_extents.y = 0.0f;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.shape = GYRO_BODY_SHAPE_SPHERE;
  bd.radius = -0.5f;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.orientation = zero_q;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.shape = GYRO_BODY_SHAPE_PLANE; /* planes are static only */
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.type = GYRO_BODY_STATIC;
  bd.shape = GYRO_BODY_SHAPE_MESH; /* with no mesh */
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_NULL_ARGUMENT);
  bd = gyro_body_def_default();
  bd.type = 3;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.shape = 9;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.awake = 5;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  bd = gyro_body_def_default();
  bd.reserved = 1;
  CHECK(gyro_body_create(w, &bd, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(same_id(out_id, null_id));
  CHECK(gyro_world_body_count(w, &count) == GYRO_OK && count == 2);
  CHECK(hash_of(w) == h);

  /* NaN and infinite arguments of the per-body calls */
  CHECK(gyro_body_set_transform(w, box, nan3, q) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_set_transform(w, box, zero3, nan_q) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_set_transform(w, box, zero3, zero_q) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_body_set_velocity(w, box, inf3, zero3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_set_velocity(w, box, zero3, nan3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_force(w, box, nan3, zero3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_force(w, box, zero3, inf3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_force_at_center(w, box, inf3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_torque(w, box, nan3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_linear_impulse(w, box, nan3, zero3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_apply_angular_impulse(w, box, inf3) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_body_set_awake(w, box, 2) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(hash_of(w) == h);

  /* NULL world or outputs */
  CHECK(gyro_body_set_transform(NULL, box, zero3, q) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_transform(w, box, NULL, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_velocity(w, box, NULL, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_transform(w, box, NULL, &q) == GYRO_OK); /* one output is enough */
  CHECK(gyro_body_get_transform(w, box, &p, NULL) == GYRO_OK);
  CHECK(gyro_body_get_velocity(w, box, NULL, &v) == GYRO_OK);
  CHECK(gyro_body_get_mass(w, box, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_type(w, box, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_user_data(w, box, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_is_awake(w, box, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_apply_force_at_center(NULL, box, zero3) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_destroy(NULL, box) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_hash(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_hash(NULL, &u) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_body_count(NULL, &count) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_body_view(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_body_view(NULL, &view) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_contact_events(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_contact_events(NULL, &ev) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_stats(NULL, &stats) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_timings(w, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_get_timings(NULL, &timings) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(!gyro_body_is_valid(NULL, box));
  CHECK(hash_of(w) == h);

  /* stale ids: the destroyed body and the null id, through every per-body call */
  stale[0] = &gone, stale[1] = &null_id;
  for (k = 0; k < 2; ++k) {
    const gyro_body_id id = *stale[k];
    CHECK(!gyro_body_is_valid(w, id));
    CHECK(gyro_body_destroy(w, id) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_get_transform(w, id, &p, &q) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_set_transform(w, id, zero3, q) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_get_velocity(w, id, &p, &v) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_set_velocity(w, id, zero3, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_get_mass(w, id, &mass) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_get_type(w, id, &type) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_get_user_data(w, id, &u) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_apply_force(w, id, zero3, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_apply_force_at_center(w, id, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_apply_torque(w, id, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_apply_linear_impulse(w, id, zero3, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_apply_angular_impulse(w, id, zero3) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_set_awake(w, id, 1) == GYRO_STATUS_STALE_ID);
    CHECK(gyro_body_is_awake(w, id, &awake) == GYRO_STATUS_STALE_ID);
  }
  CHECK(hash_of(w) == h);

  /* steps that cannot run */
  CHECK(gyro_world_step(w, 0.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_step(w, -1.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_step(w, -0.0f) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(gyro_world_step(w, NAN) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_world_step(w, INFINITY) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_world_step(NULL, kDt) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(strlen(gyro_last_error()) > 0);
  CHECK(hash_of(w) == h);
  CHECK(gyro_world_body_count(w, &count) == GYRO_OK && count == 2);

  /* and the world still steps */
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(hash_of(w) != h);
  gyro_world_destroy(w);
}

/* Snapshots: a restored world (in place, after changes) and one built from the bytes retrace
 * the original's hashes; the mesh the C layer holds for the ground stays alive across it;
 * damaged bytes are refused and change nothing. */
static void test_snapshot(void) {
  static const float mx[4] = {-20, 20, -20, 20}, my[4] = {0, 0, 0, 0}, mz[4] = {-20, -20, 20, 20};
  static const uint32_t tris[6] = {0, 2, 1, 1, 2, 3};
  gyro_mesh_def md = gyro_mesh_def_default();
  gyro_mesh* mesh = NULL;
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def gd = gyro_body_def_default(), bd = gyro_body_def_default();
  gyro_world *w = NULL, *copy = NULL;
  gyro_body_id ground, ids[6];
  uint64_t size = 0, written = 0, ahead[30], h = 0, h2 = 0, before = 0;
  unsigned char* buf;
  int i;
  CHECK((gyro_features() & GYRO_FEATURE_SNAPSHOT) != 0);
  md.x = mx, md.y = my, md.z = mz, md.vertex_count = 4, md.indices = tris, md.triangle_count = 2;
  CHECK(gyro_mesh_create(&md, &mesh) == GYRO_OK);
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK);
  if (!mesh || !w) return;
  gd.type = GYRO_BODY_STATIC;
  gd.shape = GYRO_BODY_SHAPE_MESH;
  gd.mesh = mesh;
  CHECK(gyro_body_create(w, &gd, &ground) == GYRO_OK);
  gyro_mesh_destroy(mesh);
  for (i = 0; i < 6; ++i) {
    bd.shape = i % 2 ? GYRO_BODY_SHAPE_BOX : GYRO_BODY_SHAPE_SPHERE;
    bd.position = vec3(0.3f * (float)i, 1.0f + 1.2f * (float)i, 0.0f);
    CHECK(gyro_body_create(w, &bd, &ids[i]) == GYRO_OK);
  }
  for (i = 0; i < 30; ++i) CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  CHECK(gyro_world_snapshot_size(w, &size) == GYRO_OK && size > 32);
  buf = (unsigned char*)malloc((size_t)size);
  if (!buf) return;
  CHECK(gyro_world_snapshot(w, buf, size - 1, &written) == GYRO_STATUS_INVALID_COUNT && written == 0);
  CHECK(gyro_world_snapshot(w, buf, size, &written) == GYRO_OK && written == size);
  for (i = 0; i < 30; ++i) {
    CHECK(gyro_world_step(w, kDt) == GYRO_OK);
    CHECK(gyro_world_hash(w, &ahead[i]) == GYRO_OK);
  }
  CHECK(gyro_body_destroy(w, ids[2]) == GYRO_OK);
  CHECK(gyro_world_restore(w, buf, size) == GYRO_OK);
  CHECK(gyro_world_create_from_snapshot(buf, size, &copy) == GYRO_OK);
  for (i = 0; i < 30 && copy; ++i) {
    CHECK(gyro_world_step(w, kDt) == GYRO_OK && gyro_world_step(copy, kDt) == GYRO_OK);
    CHECK(gyro_world_hash(w, &h) == GYRO_OK && h == ahead[i]);
    CHECK(gyro_world_hash(copy, &h2) == GYRO_OK && h2 == ahead[i]);
  }
  CHECK(gyro_body_is_valid(w, ids[2]) == 1);
  /* Damaged bytes: refused, nothing changed. */
  CHECK(gyro_world_hash(w, &before) == GYRO_OK);
  buf[size / 2] ^= 0x10;
  CHECK(gyro_world_restore(w, buf, size) == GYRO_STATUS_CORRUPT_DATA);
  CHECK(gyro_world_restore(w, buf, 7) == GYRO_STATUS_CORRUPT_DATA);
  CHECK(gyro_world_restore(w, NULL, size) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_world_hash(w, &h) == GYRO_OK && h == before);
  CHECK(strcmp(gyro_status_name(GYRO_STATUS_CORRUPT_DATA), "corrupt_data") == 0);
  /* The ground's mesh outlives the restore: destroying the body then stepping is fine. */
  CHECK(gyro_body_destroy(w, ground) == GYRO_OK);
  CHECK(gyro_world_step(w, kDt) == GYRO_OK);
  free(buf);
  gyro_world_destroy(copy);
  gyro_world_destroy(w);
}

int main(void) {
  test_versions();
  test_fall_and_rest();
  test_body_state();
  test_mesh_body();
  test_snapshot();
  test_bad_input();
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("capi world: all checks passed\n");
  return 0;
}
