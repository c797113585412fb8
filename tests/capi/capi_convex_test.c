/* Convex shapes through the C ABI (ABI 1.4), from a C99 program: a hull of a cube's corners
 * (with duplicates and an inside point) has 8 vertices, 6 faces and 12 edges, outward planes
 * and counter-clockwise faces, copied out through caller-sized arrays; degenerate, short and
 * non-finite point sets give their statuses with *out untouched; a box hull's mass
 * properties match the analytic ones; the pair queries agree with known answers (spheres,
 * boxes, capsules, a cylinder, a triangle, a hull); bad pairs are flagged one by one while
 * bad calls fail whole with nothing written; results are the same bits at 1 and 4 threads;
 * and the world's capsule and hull bodies rest at the right height, report their shape
 * frames, reject mismatched hulls, and gyro_body_create still takes the ABI 1.3 body def. */
#include "gyro.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

STATIC_ASSERT(sizeof(gyro_convex_type) == 4 && sizeof(gyro_convex_status) == 4, enums);
STATIC_ASSERT(sizeof(gyro_convex_hull_info) == 16, hull_info);
STATIC_ASSERT(sizeof(gyro_convex_plane) == 16 && offsetof(gyro_convex_plane, d) == 12, plane);
STATIC_ASSERT(sizeof(gyro_convex_edge) == 8, edge);
STATIC_ASSERT(sizeof(gyro_convex_mass) == 100 && offsetof(gyro_convex_mass, principal_axes) == 64, mass);
STATIC_ASSERT(sizeof(gyro_convex_pose) == 48 && offsetof(gyro_convex_pose, rotation) == 12, pose);
STATIC_ASSERT(sizeof(gyro_convex_result) == 48 && offsetof(gyro_convex_result, normal) == 8 &&
                  offsetof(gyro_convex_result, point_b) == 32 && offsetof(gyro_convex_result, iterations) == 44,
              result);
STATIC_ASSERT(offsetof(gyro_convex_shape, half_extents) == 12 && offsetof(gyro_convex_shape, triangle) == 24 &&
                  offsetof(gyro_convex_shape, reserved) == 60,
              shape);
STATIC_ASSERT(sizeof(void*) != 8 || (sizeof(gyro_convex_shape) == 72 && offsetof(gyro_convex_shape, hull) == 64),
              shape_64);
/* gyro_body_def: ABI 1.3's fields keep their offsets; 1.4 appends half_height and hull. */
STATIC_ASSERT(sizeof(void*) != 8 || (offsetof(gyro_body_def, user_data) == 128 &&
                                     offsetof(gyro_body_def, mesh) == 136 &&
                                     offsetof(gyro_body_def, half_height) == 144 &&
                                     offsetof(gyro_body_def, reserved2) == 148 &&
                                     offsetof(gyro_body_def, hull) == 152 && sizeof(gyro_body_def) == 160),
              body_def_64);

/* The ABI 1.3 sizeof(gyro_body_def) with 64-bit pointers. */
#define BODY_DEF_SIZE_1_3 144u

static const float kDt = 1.0f / 60.0f;

static gyro_vec3 vec3(float x, float y, float z) {
  gyro_vec3 v;
  v.x = x, v.y = y, v.z = z;
  return v;
}

static int near(float a, float b, float tol) { return fabsf(a - b) <= tol; }
static int near3(gyro_vec3 a, float x, float y, float z, float tol) {
  return near(a.x, x, tol) && near(a.y, y, tol) && near(a.z, z, tol);
}
static float dot(gyro_vec3 a, gyro_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static gyro_vec3 sub(gyro_vec3 a, gyro_vec3 b) { return vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
static gyro_vec3 cross(gyro_vec3 a, gyro_vec3 b) {
  return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* q v q* for a unit q. */
static gyro_vec3 rotate(gyro_quat q, gyro_vec3 v) {
  const gyro_vec3 u = vec3(q.x, q.y, q.z);
  const gyro_vec3 t = cross(u, v);
  const gyro_vec3 t2 = vec3(2.0f * t.x, 2.0f * t.y, 2.0f * t.z);
  const gyro_vec3 c = cross(u, t2);
  return vec3(v.x + q.w * t2.x + c.x, v.y + q.w * t2.y + c.y, v.z + q.w * t2.z + c.z);
}
static gyro_quat quat_mul(gyro_quat a, gyro_quat b) {
  gyro_quat r;
  r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
  r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
  r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
  r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
  return r;
}
static gyro_quat axis_angle(float x, float y, float z, float angle) {
  gyro_quat q;
  const float s = sinf(0.5f * angle);
  q.x = x * s, q.y = y * s, q.z = z * s, q.w = cosf(0.5f * angle);
  return q;
}

static gyro_convex_pose pose_at(float x, float y, float z) {
  gyro_convex_pose p;
  memset(&p, 0, sizeof p);
  p.position = vec3(x, y, z);
  p.rotation[0].x = p.rotation[1].y = p.rotation[2].z = 1.0f;
  return p;
}

static gyro_convex_shape sphere(float r) {
  gyro_convex_shape s;
  memset(&s, 0, sizeof s);
  s.type = GYRO_CONVEX_SPHERE;
  s.radius = r;
  return s;
}
static gyro_convex_shape box(float hx, float hy, float hz) {
  gyro_convex_shape s;
  memset(&s, 0, sizeof s);
  s.type = GYRO_CONVEX_BOX;
  s.half_extents = vec3(hx, hy, hz);
  return s;
}
static gyro_convex_shape capsule(float r, float hh) {
  gyro_convex_shape s;
  memset(&s, 0, sizeof s);
  s.type = GYRO_CONVEX_CAPSULE;
  s.radius = r, s.half_height = hh;
  return s;
}
static gyro_convex_shape cylinder(float r, float hh) {
  gyro_convex_shape s = capsule(r, hh);
  s.type = GYRO_CONVEX_CYLINDER;
  return s;
}
static gyro_convex_shape hull_shape(const gyro_convex_hull* h) {
  gyro_convex_shape s;
  memset(&s, 0, sizeof s);
  s.type = GYRO_CONVEX_HULL;
  s.hull = h;
  return s;
}

/* A cube's 8 corners (+-1), each corner twice, an exact duplicate block and the centre:
 * 17 points, 8 on the hull. */
static gyro_convex_hull* cube_hull(void) {
  gyro_vec3 p[17];
  gyro_convex_hull* h = NULL;
  int i;
  for (i = 0; i < 8; ++i) {
    p[i] = vec3(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
    p[8 + i] = p[i];
  }
  p[16] = vec3(0.0f, 0.0f, 0.0f);
  CHECK(gyro_convex_hull_create(p, 17, &h) == GYRO_OK && h != NULL);
  return h;
}

/* The hull of the box [x0, x0 + sx] x [y0, y0 + sy] x [z0, z0 + sz]. */
static gyro_convex_hull* box_hull(float x0, float y0, float z0, float sx, float sy, float sz) {
  gyro_vec3 p[8];
  gyro_convex_hull* h = NULL;
  int i;
  for (i = 0; i < 8; ++i) p[i] = vec3(i & 1 ? x0 + sx : x0, i & 2 ? y0 + sy : y0, i & 4 ? z0 + sz : z0);
  CHECK(gyro_convex_hull_create(p, 8, &h) == GYRO_OK && h != NULL);
  return h;
}

static void test_versions(void) {
  CHECK(gyro_abi_version() >> 16 == GYRO_ABI_VERSION >> 16);
  CHECK((gyro_abi_version() & 0xFFFFu) >= 4u); /* convex shapes arrived in ABI 1.4 */
  CHECK(GYRO_ABI_VERSION >= ((1u << 16) | 4u)); /* this header is at least 1.4 */
  CHECK(gyro_features() & GYRO_FEATURE_GEOMETRY);
  CHECK(gyro_features() & GYRO_FEATURE_CONVEX);
}

static void test_cube_hull(void) {
  gyro_convex_hull* h = cube_hull();
  gyro_convex_hull_info info;
  gyro_vec3 v[8], few[4];
  gyro_convex_plane planes[6];
  gyro_convex_edge edges[12];
  uint32_t starts[7], fv[24];
  int32_t n = -7, i, k;
  int on_plane = 1, ccw = 1, unit = 1, edges_ok = 1, axis_planes = 1;
  if (!h) return;
  CHECK(gyro_convex_hull_get_info(h, &info) == GYRO_OK);
  CHECK(info.vertex_count == 8 && info.face_count == 6 && info.edge_count == 12 && info.face_vertex_count == 24);

  /* the size alone, then a short array (the rest untouched), then the whole */
  CHECK(gyro_convex_hull_get_vertices(h, NULL, 0, &n) == GYRO_OK && n == 8);
  few[3] = vec3(42.0f, 42.0f, 42.0f);
  n = -7;
  CHECK(gyro_convex_hull_get_vertices(h, few, 3, &n) == GYRO_OK && n == 8);
  CHECK(few[3].x == 42.0f && few[3].y == 42.0f);
  CHECK(gyro_convex_hull_get_vertices(h, v, 8, &n) == GYRO_OK && n == 8);
  for (i = 0; i < 3; ++i) CHECK(few[i].x == v[i].x && few[i].y == v[i].y && few[i].z == v[i].z);
  /* in the order of their first input index: the corners as given */
  for (i = 0; i < 8; ++i)
    CHECK(v[i].x == (i & 1 ? 1.0f : -1.0f) && v[i].y == (i & 2 ? 1.0f : -1.0f) && v[i].z == (i & 4 ? 1.0f : -1.0f));

  CHECK(gyro_convex_hull_get_planes(h, planes, 6, &n) == GYRO_OK && n == 6);
  for (i = 0; i < 6; ++i) {
    const gyro_vec3 nn = planes[i].normal;
    unit &= near(dot(nn, nn), 1.0f, 1e-6f) && near(planes[i].d, 1.0f, 1e-6f);
    axis_planes &= near(fabsf(nn.x) + fabsf(nn.y) + fabsf(nn.z), 1.0f, 1e-6f);
  }
  CHECK(unit && axis_planes);

  CHECK(gyro_convex_hull_get_face_starts(h, starts, 7, &n) == GYRO_OK && n == 7);
  CHECK(gyro_convex_hull_get_face_vertices(h, fv, 24, &n) == GYRO_OK && n == 24);
  CHECK(starts[0] == 0 && starts[6] == 24);
  for (i = 0; i < 6; ++i) {
    const int32_t s0 = (int32_t)starts[i], m = (int32_t)starts[i + 1] - s0;
    CHECK(m == 4);
    if (m != 4) continue;
    for (k = 0; k < m; ++k) { /* each corner (a, b, c) of the face's loop */
      const uint32_t a = fv[s0 + k], b = fv[s0 + (k + 1) % m], c = fv[s0 + (k + 2) % m];
      if (a >= 8 || b >= 8 || c >= 8) {
        ccw = on_plane = 0;
        continue;
      }
      on_plane &= near(dot(planes[i].normal, v[a]), planes[i].d, 1e-6f);
      /* counter-clockwise seen from outside: the corner's turn points along the normal */
      ccw &= dot(cross(sub(v[b], v[a]), sub(v[c], v[b])), planes[i].normal) > 0.0f;
    }
  }
  CHECK(on_plane && ccw);

  CHECK(gyro_convex_hull_get_edges(h, edges, 12, &n) == GYRO_OK && n == 12);
  for (i = 0; i < 12; ++i) {
    edges_ok &= edges[i].a < edges[i].b && edges[i].b < 8;
    if (edges[i].b < 8) edges_ok &= near(dot(sub(v[edges[i].b], v[edges[i].a]), sub(v[edges[i].b], v[edges[i].a])), 4.0f, 1e-6f);
    if (i > 0) edges_ok &= edges[i - 1].a < edges[i].a || (edges[i - 1].a == edges[i].a && edges[i - 1].b < edges[i].b);
  }
  CHECK(edges_ok);

  /* bad getter calls write nothing */
  n = -7;
  CHECK(gyro_convex_hull_get_vertices(h, v, -1, &n) == GYRO_STATUS_INVALID_COUNT && n == -7);
  CHECK(gyro_convex_hull_get_vertices(h, NULL, 2, &n) == GYRO_STATUS_NULL_ARGUMENT && n == -7);
  CHECK(gyro_convex_hull_get_vertices(h, v, 8, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_hull_get_vertices(NULL, v, 8, &n) == GYRO_STATUS_NULL_ARGUMENT && n == -7);
  CHECK(gyro_convex_hull_get_planes(NULL, planes, 6, &n) == GYRO_STATUS_NULL_ARGUMENT && n == -7);
  CHECK(gyro_convex_hull_get_face_starts(h, starts, -3, &n) == GYRO_STATUS_INVALID_COUNT && n == -7);
  CHECK(gyro_convex_hull_get_face_vertices(h, NULL, 1, &n) == GYRO_STATUS_NULL_ARGUMENT && n == -7);
  CHECK(gyro_convex_hull_get_edges(h, edges, 12, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_hull_get_info(NULL, &info) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_hull_get_info(h, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  gyro_convex_hull_destroy(h);
  gyro_convex_hull_destroy(NULL);
}

static void test_hull_errors(void) {
  gyro_convex_hull* const sentinel = (gyro_convex_hull*)&failures;
  gyro_convex_hull* out = sentinel;
  gyro_vec3 p[8];
  int i;
  for (i = 0; i < 8; ++i) p[i] = vec3((float)(i & 1), (float)((i >> 1) & 1), (float)((i >> 2) & 1));
  CHECK(gyro_convex_hull_create(p, 3, &out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(gyro_convex_hull_create(p, 0, &out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(gyro_convex_hull_create(p, -1, &out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(gyro_convex_hull_create(NULL, 8, &out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_hull_create(p, 8, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  /* coplanar: the four corners of the z = 0 face and their midpoints */
  {
    gyro_vec3 q[6];
    q[0] = p[0], q[1] = p[1], q[2] = p[2], q[3] = p[3];
    q[4] = vec3(0.5f, 0.0f, 0.0f), q[5] = vec3(0.5f, 0.5f, 0.0f);
    CHECK(gyro_convex_hull_create(q, 6, &out) == GYRO_STATUS_INVALID_ARGUMENT);
    /* collinear */
    for (i = 0; i < 6; ++i) q[i] = vec3((float)i, 2.0f * (float)i, -(float)i);
    CHECK(gyro_convex_hull_create(q, 6, &out) == GYRO_STATUS_INVALID_ARGUMENT);
    /* all the same point */
    for (i = 0; i < 6; ++i) q[i] = vec3(1.0f, 2.0f, 3.0f);
    CHECK(gyro_convex_hull_create(q, 6, &out) == GYRO_STATUS_INVALID_ARGUMENT);
  }
  p[5].y = NAN;
  CHECK(gyro_convex_hull_create(p, 8, &out) == GYRO_STATUS_NON_FINITE);
  p[5].y = INFINITY;
  CHECK(gyro_convex_hull_create(p, 8, &out) == GYRO_STATUS_NON_FINITE);
  CHECK(strlen(gyro_last_error()) > 0);
  CHECK(out == sentinel);
}

/* The box [0, 2] x [0, 4] x [0, 6]: volume 48, centroid (1, 2, 3), inertia about the centroid
 * diag(m (b^2 + c^2) / 12, ...) = diag(208, 160, 80) at density 1. Waits on convex_hull_mass. */
static void test_hull_mass(void) {
  gyro_convex_hull* h = box_hull(0.0f, 0.0f, 0.0f, 2.0f, 4.0f, 6.0f);
  gyro_convex_mass m, untouched;
  gyro_vec3 det_cross;
  gyro_status s;
  if (!h) return;
  memset(&m, 0, sizeof m);
  s = gyro_convex_hull_mass(h, &m);
  CHECK(s == GYRO_OK);
  if (s == GYRO_OK) {
    CHECK(near(m.volume, 48.0f, 48.0f * 1e-6f));
    CHECK(near3(m.centroid, 1.0f, 2.0f, 3.0f, 1e-5f));
    CHECK(near3(m.inertia[0], 208.0f, 0.0f, 0.0f, 208.0f * 1e-5f));
    CHECK(near3(m.inertia[1], 0.0f, 160.0f, 0.0f, 208.0f * 1e-5f));
    CHECK(near3(m.inertia[2], 0.0f, 0.0f, 80.0f, 208.0f * 1e-5f));
    CHECK(near3(m.principal_moments, 80.0f, 160.0f, 208.0f, 208.0f * 1e-5f)); /* ascending */
    /* the axes of the moments: z, y, x (up to sign), a right-handed frame */
    CHECK(near(fabsf(m.principal_axes[0].z), 1.0f, 1e-5f));
    CHECK(near(fabsf(m.principal_axes[1].y), 1.0f, 1e-5f));
    CHECK(near(fabsf(m.principal_axes[2].x), 1.0f, 1e-5f));
    det_cross = cross(m.principal_axes[1], m.principal_axes[2]);
    CHECK(near(dot(m.principal_axes[0], det_cross), 1.0f, 1e-5f));
  }
  memset(&untouched, 0x5A, sizeof untouched);
  m = untouched;
  CHECK(gyro_convex_hull_mass(NULL, &m) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_hull_mass(h, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(memcmp(&m, &untouched, sizeof m) == 0);
  gyro_convex_hull_destroy(h);
}

static void test_pose_from_quat(void) {
  gyro_convex_pose p, before;
  gyro_quat q = axis_angle(0.0f, 0.0f, 1.0f, 1.5707963f), zero = {0.0f, 0.0f, 0.0f, 0.0f};
  CHECK(gyro_convex_pose_from_quat(vec3(1.0f, 2.0f, 3.0f), q, &p) == GYRO_OK);
  /* 90 degrees about z: local x is world y, local y is world -x */
  CHECK(near3(p.position, 1.0f, 2.0f, 3.0f, 0.0f));
  CHECK(near3(p.rotation[0], 0.0f, 1.0f, 0.0f, 1e-6f));
  CHECK(near3(p.rotation[1], -1.0f, 0.0f, 0.0f, 1e-6f));
  CHECK(near3(p.rotation[2], 0.0f, 0.0f, 1.0f, 1e-6f));
  /* a quaternion that is not unit is normalised */
  q.x *= 3.0f, q.y *= 3.0f, q.z *= 3.0f, q.w *= 3.0f;
  CHECK(gyro_convex_pose_from_quat(vec3(1.0f, 2.0f, 3.0f), q, &p) == GYRO_OK);
  CHECK(near3(p.rotation[0], 0.0f, 1.0f, 0.0f, 1e-6f));
  before = p;
  CHECK(gyro_convex_pose_from_quat(vec3(0.0f, 0.0f, 0.0f), zero, &p) == GYRO_STATUS_INVALID_ARGUMENT);
  q.w = NAN;
  CHECK(gyro_convex_pose_from_quat(vec3(0.0f, 0.0f, 0.0f), q, &p) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_convex_pose_from_quat(vec3(NAN, 0.0f, 0.0f), zero, &p) == GYRO_STATUS_NON_FINITE);
  CHECK(gyro_convex_pose_from_quat(vec3(0.0f, 0.0f, 0.0f), zero, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(memcmp(&p, &before, sizeof p) == 0);
}

/* Known answers, all pairs in one batch. */
#define KNOWN 8
static void test_known_answers(void) {
  gyro_convex_hull* cube = cube_hull();
  gyro_convex_shape a[KNOWN], b[KNOWN];
  gyro_convex_pose pa[KNOWN], pb[KNOWN];
  gyro_convex_result dist[KNOWN], pen[KNOWN], hit[KNOWN], contact[KNOWN];
  int i;
  if (!cube) return;
  for (i = 0; i < KNOWN; ++i) pa[i] = pose_at(0.0f, 0.0f, 0.0f);
  /* 0: unit spheres 3 apart: gap 1 */
  a[0] = sphere(1.0f), b[0] = sphere(1.0f), pb[0] = pose_at(3.0f, 0.0f, 0.0f);
  /* 1: boxes of half extent 1, 1.5 apart: 0.5 deep along x */
  a[1] = box(1.0f, 1.0f, 1.0f), b[1] = box(1.0f, 1.0f, 1.0f), pb[1] = pose_at(1.5f, 0.0f, 0.0f);
  /* 2: parallel capsules (radius 0.5, half height 1) 3 apart, one shifted along its axis: gap 2 */
  a[2] = capsule(0.5f, 1.0f), b[2] = capsule(0.5f, 1.0f), pb[2] = pose_at(3.0f, 0.5f, 0.0f);
  /* 3: a capsule lying along x above a standing one: top at 1.5, bottom at 2.5: gap 1 */
  a[3] = capsule(0.5f, 1.0f), b[3] = capsule(0.5f, 1.0f);
  CHECK(gyro_convex_pose_from_quat(vec3(0.0f, 3.0f, 0.0f), axis_angle(0.0f, 0.0f, 1.0f, 1.5707963f), &pb[3]) ==
        GYRO_OK);
  /* 4: the cube hull (+-1) and a sphere of radius 0.5 at x = 3: gap 1.5 */
  a[4] = hull_shape(cube), b[4] = sphere(0.5f), pb[4] = pose_at(3.0f, 0.0f, 0.0f);
  /* 5: a triangle in y = 0 and a sphere of radius 0.5 at y = 2: gap 1.5 */
  memset(&a[5], 0, sizeof a[5]);
  a[5].type = GYRO_CONVEX_TRIANGLE;
  a[5].triangle[0] = vec3(-1.0f, 0.0f, -1.0f), a[5].triangle[1] = vec3(1.0f, 0.0f, -1.0f);
  a[5].triangle[2] = vec3(0.0f, 0.0f, 1.0f);
  b[5] = sphere(0.5f), pb[5] = pose_at(0.0f, 2.0f, 0.0f);
  /* 6: a cylinder (radius 1, half height 1) and a box (half 0.5) at y = 3: gap 1.5 */
  a[6] = cylinder(1.0f, 1.0f), b[6] = box(0.5f, 0.5f, 0.5f), pb[6] = pose_at(0.0f, 3.0f, 0.0f);
  /* 7: the cube hull against itself moved 1.75 along z, far from the origin: 0.25 deep */
  a[7] = hull_shape(cube), b[7] = hull_shape(cube);
  pa[7] = pose_at(1e4f, -1e4f, 1e4f), pb[7] = pose_at(1e4f, -1e4f, 1e4f + 1.75f);

  CHECK(gyro_convex_distance_pairs(a, pa, b, pb, KNOWN, dist) == GYRO_OK);
  CHECK(gyro_convex_penetration_pairs(a, pa, b, pb, KNOWN, pen) == GYRO_OK);
  CHECK(gyro_convex_intersect_pairs(a, pa, b, pb, KNOWN, hit) == GYRO_OK);
  CHECK(gyro_convex_contact_pairs(a, pa, b, pb, KNOWN, contact) == GYRO_OK);
  /* contact (ABI 1.6): overlapping pairs get the penetration answer bit for bit, separated
     pairs stay separated with a distance no smaller than the gap */
  for (i = 0; i < KNOWN; ++i) {
    if (pen[i].status == GYRO_CONVEX_SEPARATED) {
      CHECK(contact[i].status == GYRO_CONVEX_SEPARATED && contact[i].distance >= pen[i].distance);
    } else {
      CHECK(memcmp(&contact[i], &pen[i], sizeof pen[i]) == 0);
    }
  }

  CHECK(dist[0].status == GYRO_CONVEX_SEPARATED && near(dist[0].distance, 1.0f, 1e-5f));
  CHECK(near3(dist[0].normal, 1.0f, 0.0f, 0.0f, 1e-5f));
  CHECK(near3(dist[0].point_a, 1.0f, 0.0f, 0.0f, 1e-5f) && near3(dist[0].point_b, 2.0f, 0.0f, 0.0f, 1e-5f));
  CHECK(pen[0].status == GYRO_CONVEX_SEPARATED && near(pen[0].distance, 1.0f, 1e-5f));
  CHECK(hit[0].status == GYRO_CONVEX_SEPARATED);

  CHECK(pen[1].status == GYRO_CONVEX_INTERSECTING && near(pen[1].distance, -0.5f, 1e-4f));
  CHECK(near3(pen[1].normal, 1.0f, 0.0f, 0.0f, 1e-4f));
  CHECK(near(pen[1].point_a.x, 1.0f, 1e-4f) && near(pen[1].point_b.x, 0.5f, 1e-4f));
  CHECK(dist[1].status == GYRO_CONVEX_INTERSECTING && dist[1].distance == 0.0f);
  CHECK(hit[1].status == GYRO_CONVEX_INTERSECTING);

  CHECK(dist[2].status == GYRO_CONVEX_SEPARATED && near(dist[2].distance, 2.0f, 1e-5f));
  CHECK(near3(dist[2].normal, 1.0f, 0.0f, 0.0f, 1e-5f));
  CHECK(near(dist[2].point_b.x - dist[2].point_a.x, 2.0f, 1e-5f));
  CHECK(dist[3].status == GYRO_CONVEX_SEPARATED && near(dist[3].distance, 1.0f, 1e-5f));
  CHECK(near3(dist[3].normal, 0.0f, 1.0f, 0.0f, 1e-5f));
  CHECK(dist[4].status == GYRO_CONVEX_SEPARATED && near(dist[4].distance, 1.5f, 1e-5f));
  CHECK(near(dist[4].point_a.x, 1.0f, 1e-5f) && near3(dist[4].point_b, 2.5f, 0.0f, 0.0f, 1e-5f));
  CHECK(dist[5].status == GYRO_CONVEX_SEPARATED && near(dist[5].distance, 1.5f, 1e-5f));
  CHECK(dist[6].status == GYRO_CONVEX_SEPARATED && near(dist[6].distance, 1.5f, 1e-5f));
  CHECK(pen[7].status == GYRO_CONVEX_INTERSECTING && near(pen[7].distance, -0.25f, 1e-3f));
  CHECK(near3(pen[7].normal, 0.0f, 0.0f, 1.0f, 1e-4f));
  /* point_b - point_a = distance * normal for the separated pairs and the penetrations */
  for (i = 0; i < KNOWN; ++i) {
    if (dist[i].status == GYRO_CONVEX_SEPARATED)
      CHECK(near3(sub(dist[i].point_b, dist[i].point_a), dist[i].distance * dist[i].normal.x,
                  dist[i].distance * dist[i].normal.y, dist[i].distance * dist[i].normal.z, 1e-4f));
    CHECK(near3(sub(pen[i].point_b, pen[i].point_a), pen[i].distance * pen[i].normal.x,
                pen[i].distance * pen[i].normal.y, pen[i].distance * pen[i].normal.z, 1e-3f));
  }
  CHECK(pen[1].iterations >= 1 && pen[7].iterations >= 1); /* GJK, then EPA */
  gyro_convex_hull_destroy(cube);
}

/* Bad pairs are flagged one by one; bad calls fail whole and write nothing. */
#define BAD 11
static void test_invalid_pairs(void) {
  gyro_convex_hull* cube = cube_hull();
  gyro_convex_shape a[BAD], b[BAD];
  gyro_convex_pose pa[BAD], pb[BAD];
  gyro_convex_result out[BAD], before[BAD];
  int i, zero_fields = 1;
  if (!cube) return;
  for (i = 0; i < BAD; ++i) {
    a[i] = sphere(1.0f), b[i] = sphere(1.0f);
    pa[i] = pose_at(0.0f, 0.0f, 0.0f), pb[i] = pose_at(3.0f, 0.0f, 0.0f);
  }
  pa[1].position.y = NAN;              /* a NaN position */
  pb[2].rotation[1].z = INFINITY;      /* an infinite rotation */
  a[3] = hull_shape(NULL);             /* a hull with no hull */
  b[4].radius = -1.0f;                 /* a negative size */
  a[5].type = 9;                       /* an unknown type */
  pb[6].rotation[0].x = 2.0f;          /* a row that is not unit */
  pa[7].rotation[2].z = -1.0f;         /* a reflection */
  b[8].reserved = 1;                   /* reserved not 0 */
  a[9].hull = cube;                    /* a hull for a sphere */
  b[10] = box(1.0f, NAN, 1.0f);        /* a NaN size */
  memset(out, 0xAB, sizeof out);
  CHECK(gyro_convex_distance_pairs(a, pa, b, pb, BAD, out) == GYRO_OK);
  CHECK(out[0].status == GYRO_CONVEX_SEPARATED && near(out[0].distance, 1.0f, 1e-5f));
  for (i = 1; i < BAD; ++i) {
    CHECK(out[i].status == GYRO_CONVEX_INVALID_INPUT);
    zero_fields &= out[i].distance == 0.0f && out[i].normal.x == 0.0f && out[i].point_a.y == 0.0f &&
                   out[i].point_b.z == 0.0f && out[i].iterations == 0;
  }
  CHECK(zero_fields);
  CHECK(strstr(gyro_last_error(), "pair 1") != NULL);
  CHECK(gyro_convex_penetration_pairs(a, pa, b, pb, BAD, out) == GYRO_OK);
  for (i = 1; i < BAD; ++i) CHECK(out[i].status == GYRO_CONVEX_INVALID_INPUT);
  CHECK(gyro_convex_intersect_pairs(a, pa, b, pb, BAD, out) == GYRO_OK);
  for (i = 1; i < BAD; ++i) CHECK(out[i].status == GYRO_CONVEX_INVALID_INPUT);
  CHECK(out[0].status == GYRO_CONVEX_SEPARATED);
  CHECK(gyro_convex_contact_pairs(a, pa, b, pb, BAD, out) == GYRO_OK);
  for (i = 1; i < BAD; ++i) CHECK(out[i].status == GYRO_CONVEX_INVALID_INPUT);
  CHECK(out[0].status == GYRO_CONVEX_SEPARATED);

  /* whole-call failures: nothing written */
  memset(out, 0xAB, sizeof out);
  memcpy(before, out, sizeof out);
  CHECK(gyro_convex_distance_pairs(NULL, pa, b, pb, BAD, out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_distance_pairs(a, NULL, b, pb, BAD, out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_penetration_pairs(a, pa, NULL, pb, BAD, out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_penetration_pairs(a, pa, b, NULL, BAD, out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_intersect_pairs(a, pa, b, pb, BAD, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_intersect_pairs(a, pa, b, pb, -1, out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(gyro_convex_distance_pairs(a, pa, b, pb, -5, out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(gyro_convex_contact_pairs(a, pa, b, NULL, BAD, out) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_convex_contact_pairs(a, pa, b, pb, -2, out) == GYRO_STATUS_INVALID_COUNT);
  CHECK(memcmp(out, before, sizeof out) == 0);
  /* an empty batch needs no arrays */
  CHECK(gyro_convex_distance_pairs(NULL, NULL, NULL, NULL, 0, NULL) == GYRO_OK);
  gyro_convex_hull_destroy(cube);
}

typedef gyro_status (*pairs_fn)(const gyro_convex_shape*, const gyro_convex_pose*, const gyro_convex_shape*,
                                const gyro_convex_pose*, int32_t, gyro_convex_result*);

/* Bad box-box pairs (the pair calls check those in columns, before the lanes): flagged one by
   one by every call, the good ones answered as one by one. */
#define BAD_BOXES 12
static void test_invalid_box_pairs(void) {
  gyro_convex_hull* cube = cube_hull();
  gyro_convex_shape a[BAD_BOXES], b[BAD_BOXES];
  gyro_convex_pose pa[BAD_BOXES], pb[BAD_BOXES];
  gyro_convex_result out[BAD_BOXES], one;
  pairs_fn queries[4] = {gyro_convex_intersect_pairs, gyro_convex_distance_pairs, gyro_convex_penetration_pairs,
                         gyro_convex_contact_pairs};
  int i, q;
  if (!cube) return;
  for (i = 0; i < BAD_BOXES; ++i) {
    a[i] = box(1.0f, 1.0f, 1.0f), b[i] = box(0.5f, 1.0f, 1.5f);
    pa[i] = pose_at(0.0f, 0.0f, 0.0f), pb[i] = pose_at(1.5f + 0.5f * (float)(i % 3), 0.2f, 0.0f);
  }
  pa[1].position.y = NAN;         /* a NaN position */
  pb[2].rotation[1].z = INFINITY; /* an infinite rotation */
  b[3].half_extents.y = -1.0f;    /* a negative size */
  pb[4].rotation[0].x = 2.0f;     /* a row that is not unit */
  pa[5].rotation[2].z = -1.0f;    /* a reflection */
  b[6].reserved = 1;              /* reserved not 0 */
  a[7].hull = cube;               /* a hull for a box */
  b[8].half_extents.z = NAN;      /* a NaN size */
  pb[9].rotation[0].y = 0.01f;    /* rows 1% off orthogonal: beyond the 1e-3 tolerance */
  pa[10].rotation[0].z = NAN;     /* a NaN rotation (only the rotation test sees it) */
  pb[11].rotation[2].x = -INFINITY;
  for (q = 0; q < 4; ++q) {
    memset(out, 0xAB, sizeof out);
    CHECK(queries[q](a, pa, b, pb, BAD_BOXES, out) == GYRO_OK);
    CHECK(out[0].status == GYRO_CONVEX_INTERSECTING || out[0].status == GYRO_CONVEX_TOUCHING);
    CHECK(queries[q](a, pa, b, pb, 1, &one) == GYRO_OK); /* pair 0 alone: the same bytes */
    CHECK(memcmp(&one, &out[0], sizeof one) == 0);
    for (i = 1; i < BAD_BOXES; ++i) {
      CHECK(out[i].status == GYRO_CONVEX_INVALID_INPUT);
      CHECK(out[i].distance == 0.0f && out[i].normal.x == 0.0f && out[i].point_b.z == 0.0f && out[i].iterations == 0);
    }
    CHECK(strstr(gyro_last_error(), "pair 1") != NULL);
  }
  gyro_convex_hull_destroy(cube);
}

/* A seeded batch of mixed pairs, a third of them box-box (those run over SIMD lanes): every
   query gives the same bits at 1 and 4 threads and at the scalar level (pair by pair). */
#define MANY 2000
static uint32_t rng = 12345u;
static float rnd(float lo, float hi) {
  rng = rng * 1664525u + 1013904223u;
  return lo + (hi - lo) * (float)(rng >> 8) / 16777216.0f;
}
static gyro_convex_shape random_shape(const gyro_convex_hull* h) {
  switch ((int)rnd(0.0f, 5.0f)) {
    case 0: return sphere(rnd(0.1f, 1.0f));
    case 1: return box(rnd(0.1f, 1.0f), rnd(0.1f, 1.0f), rnd(0.1f, 1.0f));
    case 2: return capsule(rnd(0.1f, 1.0f), rnd(0.0f, 1.0f));
    case 3: return cylinder(rnd(0.1f, 1.0f), rnd(0.1f, 1.0f));
    default: return hull_shape(h);
  }
}
static gyro_convex_pose random_pose(void) {
  gyro_convex_pose p;
  gyro_quat q;
  q.x = rnd(-1.0f, 1.0f), q.y = rnd(-1.0f, 1.0f), q.z = rnd(-1.0f, 1.0f), q.w = rnd(0.1f, 1.0f);
  CHECK(gyro_convex_pose_from_quat(vec3(rnd(-2.0f, 2.0f), rnd(-2.0f, 2.0f), rnd(-2.0f, 2.0f)), q, &p) == GYRO_OK);
  return p;
}
static void test_thread_invariance(void) {
  gyro_convex_hull* cube = cube_hull();
  gyro_convex_shape* a = malloc(MANY * sizeof *a);
  gyro_convex_shape* b = malloc(MANY * sizeof *b);
  gyro_convex_pose* pa = malloc(MANY * sizeof *pa);
  gyro_convex_pose* pb = malloc(MANY * sizeof *pb);
  gyro_convex_result* r1 = malloc(MANY * sizeof *r1);
  gyro_convex_result* r4 = malloc(MANY * sizeof *r4);
  gyro_convex_result* rs = malloc(MANY * sizeof *rs);
  int i, overlapping = 0, separated = 0;
  if (!cube || !a || !b || !pa || !pb || !r1 || !r4 || !rs) {
    CHECK(0);
  } else {
    pairs_fn queries[4] = {gyro_convex_intersect_pairs, gyro_convex_distance_pairs, gyro_convex_penetration_pairs,
                           gyro_convex_contact_pairs};
    const int order[4] = {0, 1, 3, 2}; /* penetration last: its results are checked below */
    int q;
    for (i = 0; i < MANY; ++i) {
      a[i] = random_shape(cube), b[i] = random_shape(cube);
      if (i % 3 == 0) a[i] = box(rnd(0.1f, 1.0f), rnd(0.1f, 1.0f), rnd(0.1f, 1.0f)), b[i] = box(rnd(0.1f, 1.0f), 0.5f, 1.0f);
      pa[i] = random_pose(), pb[i] = random_pose();
    }
    pb[MANY / 2].position.x = NAN; /* one bad pair in the middle of a chunk */
    pb[MANY / 2 + 3].position.y = NAN; /* and a bad box-box pair */
    for (q = 0; q < 4; ++q) {
      pairs_fn f = queries[order[q]];
      CHECK(gyro_set_thread_count(1) == GYRO_OK);
      CHECK(f(a, pa, b, pb, MANY, r1) == GYRO_OK);
      CHECK(gyro_set_thread_count(4) == GYRO_OK);
      CHECK(f(a, pa, b, pb, MANY, r4) == GYRO_OK);
      CHECK(memcmp(r1, r4, MANY * sizeof *r1) == 0);
      CHECK(gyro_set_simd_level(GYRO_SIMD_SCALAR) == GYRO_OK);
      CHECK(f(a, pa, b, pb, MANY, rs) == GYRO_OK);
      CHECK(memcmp(r1, rs, MANY * sizeof *r1) == 0);
      CHECK(gyro_set_simd_level(GYRO_SIMD_AUTO) == GYRO_OK);
      CHECK(r1[MANY / 2].status == GYRO_CONVEX_INVALID_INPUT && r1[MANY / 2 + 3].status == GYRO_CONVEX_INVALID_INPUT);
    }
    CHECK(gyro_set_thread_count(0) == GYRO_OK);
    CHECK(r1[MANY / 2].status == GYRO_CONVEX_INVALID_INPUT);
    for (i = 0; i < MANY; ++i) {
      overlapping += r1[i].status == GYRO_CONVEX_INTERSECTING || r1[i].status == GYRO_CONVEX_TOUCHING;
      separated += r1[i].status == GYRO_CONVEX_SEPARATED;
    }
    CHECK(overlapping > MANY / 20 && separated > MANY / 20); /* the batch has both kinds */
    CHECK(overlapping + separated >= MANY - 2);
  }
  free(a), free(b), free(pa), free(pb), free(r1), free(r4), free(rs);
  gyro_convex_hull_destroy(cube);
}

static uint64_t hash_of(const gyro_world* w) {
  uint64_t h = 0;
  CHECK(gyro_world_hash(w, &h) == GYRO_OK);
  return h;
}

/* A world with a static ground plane at y = 0 and sleep off. */
static gyro_world* plane_world(void) {
  gyro_world_def wd = gyro_world_def_default();
  gyro_body_def gd = gyro_body_def_default();
  gyro_world* w = NULL;
  gyro_body_id ground;
  wd.enable_sleep = 0;
  CHECK(gyro_world_create(&wd, &w) == GYRO_OK && w != NULL);
  if (!w) return NULL;
  gd.type = GYRO_BODY_STATIC;
  gd.shape = GYRO_BODY_SHAPE_PLANE;
  CHECK(gyro_body_create(w, &gd, &ground) == GYRO_OK);
  return w;
}

static void test_body_def(void) {
  gyro_body_def d = gyro_body_def_default();
  gyro_world* w = plane_world();
  unsigned char* old;
  gyro_body_id id, out_id = {0, 0};
  float mass = 0.0f;
  int32_t count = 0;
  CHECK(d.struct_size == sizeof d && d.half_height == 0.5f && d.hull == NULL && d.reserved2 == 0);
  CHECK(d.mesh == NULL && d.shape == GYRO_BODY_SHAPE_BOX);
  if (!w) return;
  /* an ABI 1.3 caller: its struct ends before half_height; exactly that many bytes exist */
  if (sizeof(void*) == 8) {
    old = malloc(BODY_DEF_SIZE_1_3);
    if (old) {
      d.struct_size = BODY_DEF_SIZE_1_3;
      d.position = vec3(0.0f, 3.0f, 0.0f);
      memcpy(old, &d, BODY_DEF_SIZE_1_3);
      CHECK(gyro_body_create(w, (const gyro_body_def*)old, &id) == GYRO_OK);
      CHECK(gyro_body_get_mass(w, id, &mass) == GYRO_OK && near(mass, 1.0f, 1e-6f));
      /* a 1.3 struct cannot describe the new shapes */
      d.shape = GYRO_BODY_SHAPE_CAPSULE;
      memcpy(old, &d, BODY_DEF_SIZE_1_3);
      CHECK(gyro_body_create(w, (const gyro_body_def*)old, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
      d.shape = GYRO_BODY_SHAPE_HULL;
      memcpy(old, &d, BODY_DEF_SIZE_1_3);
      CHECK(gyro_body_create(w, (const gyro_body_def*)old, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
      free(old);
    }
  }
  d = gyro_body_def_default();
  d.struct_size = sizeof d - 8; /* neither size */
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d.struct_size = sizeof d + 8;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(out_id.index == 0 && out_id.generation == 0);
  CHECK(gyro_world_body_count(w, &count) == GYRO_OK && count == (sizeof(void*) == 8 ? 2 : 1)); /* ground (+ old) */
  gyro_world_destroy(w);
}

/* Capsule and hull bodies fall onto the plane and rest at the right height. Waits on the
 * world's capsule and hull bodies (World::create_body, World::get_shape_frame). */
static void test_convex_bodies(void) {
  gyro_world* w = plane_world();
  gyro_convex_hull* slab = box_hull(4.0f, 2.0f, -1.5f, 2.0f, 1.0f, 3.0f); /* [4,6] x [2,3] x [-1.5,1.5] */
  gyro_convex_hull* cube = cube_hull();
  gyro_body_def d = gyro_body_def_default();
  gyro_body_id cap = {0, 0}, hull = {0, 0}, crate, out_id = {0, 0}, null_id = {0, 0};
  gyro_vec3 p, offset;
  gyro_quat q, r, world_rot;
  float mass = 0.0f;
  uint64_t h;
  int32_t count = 0;
  int step, cap_ok = 0, hull_ok = 0;
  if (!w || !slab || !cube) return;

  /* a box's shape frame is the identity */
  d.position = vec3(-5.0f, 0.5f, 0.0f);
  CHECK(gyro_body_create(w, &d, &crate) == GYRO_OK);
  offset = vec3(9.0f, 9.0f, 9.0f);
  r.x = r.y = r.z = r.w = 9.0f;
  CHECK(gyro_body_get_shape_frame(w, crate, &offset, &r) == GYRO_OK);
  CHECK(offset.x == 0.0f && offset.y == 0.0f && offset.z == 0.0f);
  CHECK(r.x == 0.0f && r.y == 0.0f && r.z == 0.0f && r.w == 1.0f);

  /* a capsule (radius 0.5, half height 0.5) lying along x: at rest its centre is 0.5 up */
  d = gyro_body_def_default();
  d.shape = GYRO_BODY_SHAPE_CAPSULE;
  d.radius = 0.5f, d.half_height = 0.5f;
  d.position = vec3(0.0f, 2.0f, 0.0f);
  d.orientation = axis_angle(0.0f, 0.0f, 1.0f, 1.5707963f);
  cap_ok = gyro_body_create(w, &d, &cap) == GYRO_OK;
  CHECK(cap_ok);
  /* a hull (the 2 x 1 x 3 slab, as built 2 m up); the handle is released at once */
  d = gyro_body_def_default();
  d.shape = GYRO_BODY_SHAPE_HULL;
  d.hull = slab;
  hull_ok = gyro_body_create(w, &d, &hull) == GYRO_OK;
  CHECK(hull_ok);
  gyro_convex_hull_destroy(slab);
  slab = NULL;
  if (cap_ok) { /* pi r^2 2 hh + 4/3 pi r^3 at density 1 */
    CHECK(gyro_body_get_mass(w, cap, &mass) == GYRO_OK && near(mass, 1.3089969f, 1e-3f));
  }
  if (hull_ok) {
    CHECK(gyro_body_get_mass(w, hull, &mass) == GYRO_OK && near(mass, 6.0f, 1e-4f));
    /* the body frame is the mass frame: the body starts at the slab's centroid */
    CHECK(gyro_body_get_transform(w, hull, &p, NULL) == GYRO_OK && near3(p, 5.0f, 2.5f, 0.0f, 1e-5f));
  }
  for (step = 0; step < 180; ++step) CHECK(gyro_world_step(w, kDt) == GYRO_OK); /* 3 s */
  if (cap_ok) {
    CHECK(gyro_body_get_transform(w, cap, &p, &q) == GYRO_OK);
    CHECK(near(p.y, 0.5f, 0.01f));
    CHECK(gyro_body_get_shape_frame(w, cap, &offset, &r) == GYRO_OK);
    CHECK(offset.x == 0.0f && offset.y == 0.0f && offset.z == 0.0f && r.w == 1.0f);
  }
  if (hull_ok) {
    CHECK(gyro_body_get_transform(w, hull, &p, &q) == GYRO_OK);
    CHECK(near(p.y, 0.5f, 0.01f) && near(p.x, 5.0f, 0.01f) && near(p.z, 0.0f, 0.01f));
    CHECK(gyro_body_get_shape_frame(w, hull, &offset, &r) == GYRO_OK);
    /* the hull as built, at the body's pose: its origin (built at the world origin) came
     * down 2 m with the slab, unrotated */
    world_rot = quat_mul(q, r);
    offset = rotate(q, offset);
    CHECK(near3(vec3(p.x + offset.x, p.y + offset.y, p.z + offset.z), 0.0f, -2.0f, 0.0f, 0.01f));
    CHECK(fabsf(world_rot.w) > 0.9999f);
    CHECK(gyro_body_get_shape_frame(w, hull, &offset, NULL) == GYRO_OK);
    CHECK(gyro_body_get_shape_frame(w, hull, NULL, &r) == GYRO_OK);
  }

  /* bad definitions change nothing */
  h = hash_of(w);
  d = gyro_body_def_default();
  d.hull = cube; /* a hull for a box */
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d.shape = GYRO_BODY_SHAPE_SPHERE;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d.shape = GYRO_BODY_SHAPE_CAPSULE;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d = gyro_body_def_default();
  d.shape = GYRO_BODY_SHAPE_HULL; /* with no hull: like a mesh body without its mesh */
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_NULL_ARGUMENT);
  d = gyro_body_def_default();
  d.reserved2 = 1;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d = gyro_body_def_default();
  d.shape = GYRO_BODY_SHAPE_CAPSULE;
  d.half_height = NAN;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_NON_FINITE);
  d.half_height = -0.5f;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  d = gyro_body_def_default();
  d.shape = 6;
  CHECK(gyro_body_create(w, &d, &out_id) == GYRO_STATUS_INVALID_ARGUMENT);
  CHECK(out_id.index == 0 && out_id.generation == 0);
  CHECK(gyro_body_get_shape_frame(w, crate, NULL, NULL) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_shape_frame(NULL, crate, &offset, &r) == GYRO_STATUS_NULL_ARGUMENT);
  CHECK(gyro_body_get_shape_frame(w, null_id, &offset, &r) == GYRO_STATUS_STALE_ID);
  CHECK(gyro_world_body_count(w, &count) == GYRO_OK && count == 2 + cap_ok + hull_ok);
  CHECK(hash_of(w) == h);
  gyro_world_destroy(w);
  gyro_convex_hull_destroy(cube);
}

/* ABI 1.4's world def gained convex_manifold: both models step hull stacks; a 1.3-sized
 * def is accepted with the default; unknown values are refused. */
static void test_world_def_convex_manifold(void) {
  gyro_world_def def = gyro_world_def_default();
  gyro_world* w = NULL;
  CHECK(def.convex_manifold == GYRO_CONVEX_MANIFOLD_CLIPPING);
  def.convex_manifold = 2;
  CHECK(gyro_world_create(&def, &w) == GYRO_STATUS_INVALID_ARGUMENT && w == NULL);
  def.convex_manifold = GYRO_CONVEX_MANIFOLD_INCREMENTAL;
  CHECK(gyro_world_create(&def, &w) == GYRO_OK && w != NULL);
  gyro_world_destroy(w);
  w = NULL;
  def = gyro_world_def_default();
  def.struct_size = (uint32_t)offsetof(gyro_world_def, convex_manifold);
  CHECK(gyro_world_create(&def, &w) == GYRO_OK && w != NULL);
  gyro_world_destroy(w);
  w = NULL;
  def.struct_size = 7;
  CHECK(gyro_world_create(&def, &w) == GYRO_STATUS_INVALID_ARGUMENT && w == NULL);
}

int main(void) {
  test_versions();
  test_world_def_convex_manifold();
  test_cube_hull();
  test_hull_errors();
  test_hull_mass();
  test_pose_from_quat();
  test_known_answers();
  test_invalid_pairs();
  test_invalid_box_pairs();
  test_thread_invariance();
  test_body_def();
  test_convex_bodies();
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("capi convex: all checks passed\n");
  return 0;
}
