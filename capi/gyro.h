/* gyro: deterministic, SIMD, data-oriented game physics. The flat C ABI (C99).
 *
 * Conventions
 * - Every fallible call returns gyro_status (GYRO_OK = 0); results go through out
 *   pointers. On failure nothing is written, and gyro_last_error() tells why (per thread).
 * - Counts are int32_t: a negative count is reported (GYRO_STATUS_INVALID_COUNT).
 * - Arrays are structure-of-arrays views: one pointer per component, owned by the caller,
 *   never copied or kept after the call returns.
 * - Results are bit-identical for every SIMD level and thread count, on x86-64 and
 *   aarch64, with g++ or clang++. The SIMD level and threads only change speed.
 * - Booleans are uint32_t, enums are int32_t or uint32_t typedefs, structs are plain data.
 * - No call keeps a pointer you pass; separate worlds may be used from separate threads.
 */
#ifndef GYRO_H
#define GYRO_H

#include <stdint.h>

#if defined(_WIN32)
#if defined(GYRO_BUILDING)
#define GYRO_API __declspec(dllexport)
#else
#define GYRO_API
#endif
#else
#define GYRO_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ version, features */

/** ABI version this header describes: (major << 16) | minor. A library with the same
 *  major and a minor >= the header's is compatible. */
#define GYRO_ABI_VERSION ((1u << 16) | 9u)

/** The ABI version of the linked library; compare with GYRO_ABI_VERSION. */
GYRO_API uint32_t gyro_abi_version(void);
/** Library version, e.g. "0.1.0". */
GYRO_API const char* gyro_version_string(void);

/** Bits of gyro_features(): what this build has. */
enum {
  GYRO_FEATURE_OPENMP = 1u << 0,        /**< batch calls can use several threads */
  GYRO_FEATURE_SIMD_SSE2 = 1u << 1,     /**< SSE2 kernels compiled in (gyro_simd_level_available: and the CPU has it) */
  GYRO_FEATURE_SIMD_AVX2 = 1u << 2,     /**< AVX2 kernels compiled in */
  GYRO_FEATURE_SIMD_AVX512 = 1u << 3,
  GYRO_FEATURE_SIMD_NEON = 1u << 4,
  GYRO_FEATURE_MATH = 1u << 8,          /**< math and deterministic trigonometry */
  GYRO_FEATURE_GEOMETRY = 1u << 9,      /**< 3D primitives, batch tests and raycasts */
  GYRO_FEATURE_2D = 1u << 10,           /**< 2D primitives and the quadtree (C++ API) */
  GYRO_FEATURE_SPATIAL = 1u << 11,      /**< meshes, BVH, OBJ reader, camera, frustum culling */
  GYRO_FEATURE_DYNAMICS = 1u << 12,     /**< rigid bodies, contacts, the solver and the world (ABI 1.2) */
  GYRO_FEATURE_SOFT_BODIES = 1u << 13,  /**< springs, cloth, soft bodies and particle joints (ABI 1.3) */
  GYRO_FEATURE_CONVEX = 1u << 14,       /**< convex hulls, GJK/EPA queries on pairs, capsule and hull bodies (ABI 1.4) */
  GYRO_FEATURE_SNAPSHOT = 1u << 15,     /**< world snapshot and restore (ABI 1.5) */
  GYRO_FEATURE_REPLAY = 1u << 16        /**< recording a world's calls and replaying them (ABI 1.5) */
};
GYRO_API uint32_t gyro_features(void);

/* ------------------------------------------------------------------ status and errors */

typedef int32_t gyro_status;
enum {
  GYRO_OK = 0,
  GYRO_STATUS_NULL_ARGUMENT = 1,    /**< a required pointer was NULL */
  GYRO_STATUS_INVALID_COUNT = 2,    /**< a count was negative or too large */
  GYRO_STATUS_NON_FINITE = 3,       /**< an input was NaN or infinite */
  GYRO_STATUS_INVALID_ARGUMENT = 4, /**< a value out of its documented range */
  GYRO_STATUS_UNSUPPORTED = 5,      /**< the build or the CPU lacks the feature */
  GYRO_STATUS_OUT_OF_MEMORY = 6,
  GYRO_STATUS_STALE_ID = 7,         /**< the id names an object that no longer exists */
  GYRO_STATUS_INTERNAL = 8,         /**< a bug in gyro */
  GYRO_STATUS_CORRUPT_DATA = 9      /**< a snapshot or recording is truncated, corrupted or of another version (ABI 1.5) */
};

/** The detail of this thread's last failed call ("" if none). Valid until its next failure. */
GYRO_API const char* gyro_last_error(void);
/** "ok", "null_argument", ... */
GYRO_API const char* gyro_status_name(gyro_status status);

/* ------------------------------------------------------------------ execution settings */

typedef uint32_t gyro_simd_level;
enum {
  GYRO_SIMD_AUTO = 0,   /**< the best the CPU and build support (or env GYRO_SIMD) */
  GYRO_SIMD_SCALAR = 1, /**< the reference every level reproduces bit for bit */
  GYRO_SIMD_SSE2 = 2,
  GYRO_SIMD_AVX2 = 3,
  GYRO_SIMD_AVX512 = 4,
  GYRO_SIMD_NEON = 5
};

/** Forces the SIMD level for the process; GYRO_SIMD_AUTO returns to the default.
 *  GYRO_STATUS_UNSUPPORTED if the build or the CPU lacks it. */
GYRO_API gyro_status gyro_set_simd_level(gyro_simd_level level);
/** The level kernels run at now. */
GYRO_API gyro_simd_level gyro_get_simd_level(void);
/** 1 if the build has the level and this CPU can run it. */
GYRO_API uint32_t gyro_simd_level_available(gyro_simd_level level);
/** "scalar", "sse2", "avx2", "avx512", "neon" or "auto". */
GYRO_API const char* gyro_simd_level_name(gyro_simd_level level);

/** Threads batch calls may use; 0 returns to the default (env GYRO_THREADS, else the
 *  OpenMP default). Results do not depend on it. */
GYRO_API gyro_status gyro_set_thread_count(uint32_t threads);
GYRO_API uint32_t gyro_get_thread_count(void);

/* ------------------------------------------------------------------ shape arrays, batch raycasts */

/** Rays o + t d, t in [tmin, tmax]. tmin and tmax may be NULL (0 and +infinity). d need
 *  not be unit length (t is then in units of |d|); a zero or subnormal d never hits. */
typedef struct gyro_ray_soa {
  const float* ox;
  const float* oy;
  const float* oz;
  const float* dx;
  const float* dy;
  const float* dz;
  const float* tmin;
  const float* tmax;
} gyro_ray_soa;

/** Spheres: centre and radius (>= 0). */
typedef struct gyro_sphere_soa {
  const float* cx;
  const float* cy;
  const float* cz;
  const float* r;
} gyro_sphere_soa;

/** Axis-aligned boxes: centre and half extents (>= 0). */
typedef struct gyro_aabb_soa {
  const float *cx, *cy, *cz;
  const float *ex, *ey, *ez;
} gyro_aabb_soa;

/** Oriented boxes: centre, half extents (>= 0) and the unit axes u0, u1, u2 (the rows of
 *  the orientation matrix: world = local * orientation + centre). */
typedef struct gyro_obb_soa {
  const float *cx, *cy, *cz;
  const float *ex, *ey, *ez;
  const float *u0x, *u0y, *u0z;
  const float *u1x, *u1y, *u1z;
  const float *u2x, *u2y, *u2z;
} gyro_obb_soa;

/** Planes dot(n, p) = d, n unit length. */
typedef struct gyro_plane_soa {
  const float *nx, *ny, *nz;
  const float* d;
} gyro_plane_soa;

/** Triangles with corners a, b, c. */
typedef struct gyro_triangle_soa {
  const float *ax, *ay, *az;
  const float *bx, *by, *bz;
  const float *cx, *cy, *cz;
} gyro_triangle_soa;

typedef uint32_t gyro_shape_type;
enum {
  GYRO_SHAPE_SPHERE = 1,
  GYRO_SHAPE_AABB = 2,
  GYRO_SHAPE_OBB = 3,
  GYRO_SHAPE_PLANE = 4,
  GYRO_SHAPE_TRIANGLE = 5
};

/** An array of one type of shape: set `type` and the matching member of `as`. */
typedef struct gyro_shape_soa {
  gyro_shape_type type;
  uint32_t reserved; /**< 0 */
  union {
    gyro_sphere_soa sphere;
    gyro_aabb_soa aabb;
    gyro_obb_soa obb;
    gyro_plane_soa plane;
    gyro_triangle_soa triangle;
  } as;
} gyro_shape_soa;

/** Per-ray results. primitive: index of the primitive hit, or -1 (t is then +infinity and
 *  the other outputs 0). Optional outputs, NULL to skip: the unit normal nx, ny, nz (all
 *  three or none; outward for solids, facing the ray for planes and triangles) and the
 *  barycentric u, v of a triangle hit (point = a + u (b - a) + v (c - a); both or none). */
typedef struct gyro_hit_soa {
  float* t;
  int32_t* primitive;
  float* nx;
  float* ny;
  float* nz;
  float* u;
  float* v;
} gyro_hit_soa;

/** Closest hit of every ray against every primitive of one array (brute force). The hit is
 *  the first crossing of a surface in [tmin, tmax]: a ray starting inside a solid reports
 *  where it leaves; planes and triangles are double-sided; triangles are watertight. Ties go
 *  to the lower primitive index. Errors (nothing written): NULL_ARGUMENT, INVALID_COUNT
 *  (negative), NON_FINITE (NaN or infinite coordinate or size), INVALID_ARGUMENT (negative
 *  size, unknown type, tmin < 0 or not finite, tmax NaN or < 0; tmax may be +infinity). */
GYRO_API gyro_status gyro_raycast_closest(const gyro_ray_soa* rays, int32_t ray_count, const gyro_shape_soa* prims,
                                          int32_t prim_count, const gyro_hit_soa* hits);

/** Any hit (occlusion, line of sight): the lowest-index primitive crossed in [tmin, tmax]
 *  and its t. Faster than the closest hit: it stops at the first. Same errors. */
GYRO_API gyro_status gyro_raycast_any(const gyro_ray_soa* rays, int32_t ray_count, const gyro_shape_soa* prims,
                                      int32_t prim_count, const gyro_hit_soa* hits);

/** gyro_raycast_closest against spheres. */
GYRO_API gyro_status gyro_raycast_spheres_closest(const gyro_ray_soa* rays, int32_t ray_count,
                                                  const gyro_sphere_soa* spheres, int32_t sphere_count,
                                                  const gyro_hit_soa* hits);

/* ------------------------------------------------------------------ batch overlap tests */

/** Per-pair results of the overlap calls. */
enum {
  GYRO_SEPARATED = 0,
  GYRO_OVERLAPPING = 1,  /**< touching included */
  GYRO_INVALID_INPUT = 2 /**< an input of the pair is NaN or infinite, or a size is negative */
};

/** Flags of the batch calls. */
enum {
  /** Check the whole input first and fail the call (GYRO_STATUS_NON_FINITE or
   *  GYRO_STATUS_INVALID_ARGUMENT, nothing written) on any bad element, instead of
   *  flagging that pair GYRO_INVALID_INPUT. Costs a pass over the input. */
  GYRO_BATCH_STRICT = 1u << 0
};

/** out[i] = overlap of a[i] and b[i] for i < count; every type pair (sphere, AABB, OBB,
 *  plane, triangle). Errors (nothing written): NULL_ARGUMENT, INVALID_COUNT, and
 *  INVALID_ARGUMENT for an unknown type or flag. Bit-identical at every SIMD level. */
GYRO_API gyro_status gyro_overlap_pairwise(const gyro_shape_soa* a, const gyro_shape_soa* b, int32_t count,
                                           uint32_t* out, uint32_t flags);

/** out[i] = overlap of one[0] and many[i] for i < count. */
GYRO_API gyro_status gyro_overlap_one_against_many(const gyro_shape_soa* one, const gyro_shape_soa* many,
                                                   int32_t count, uint32_t* out, uint32_t flags);

/** OBB pairs: out[i] = signed separation over the 15 separating axes: > 0 the gap, <= 0
 *  minus the penetration depth (the minimum translation distance). Strict input check. */
GYRO_API gyro_status gyro_obb_separation_pairwise(const gyro_obb_soa* a, const gyro_obb_soa* b, int32_t count,
                                                  float* out);


/* ------------------------------------------------------------------ meshes (spatial module) */

/** primitive value of a ray that mesh and scene queries cannot answer: a NaN or infinite
 *  coordinate, a zero direction, tmin NaN, infinite or negative, or tmax NaN or below
 *  tmin. Its t is +infinity and its normal and barycentrics 0; the other rays of the batch
 *  are answered. (The brute-force calls above fail the whole call instead.) */
enum { GYRO_RAY_INVALID = -2 };

/** A triangle mesh with its BVH (8-wide, binned SAH). Immutable; may be queried from many
 *  threads at once. */
typedef struct gyro_mesh gyro_mesh;

/** Vertex positions (SoA, copied) and 3 vertex indices per triangle. */
typedef struct gyro_mesh_def {
  uint32_t struct_size; /**< sizeof(gyro_mesh_def): set by gyro_mesh_def_default */
  int32_t vertex_count;
  const float* x;
  const float* y;
  const float* z;
  const uint32_t* indices;
  int32_t triangle_count;
  uint32_t reserved; /**< 0 */
} gyro_mesh_def;

GYRO_API gyro_mesh_def gyro_mesh_def_default(void);
/** Copies the mesh and builds its BVH. Errors (*out untouched): NULL_ARGUMENT,
 *  INVALID_COUNT (no triangles, negative counts), NON_FINITE (a NaN or infinite vertex),
 *  INVALID_ARGUMENT (an index out of range, a wrong struct_size). */
GYRO_API gyro_status gyro_mesh_create(const gyro_mesh_def* def, gyro_mesh** out);
/** Reads a Wavefront OBJ file (v and f lines; faces fan-triangulated). A malformed file
 *  gives INVALID_ARGUMENT with the line number in gyro_last_error(). */
GYRO_API gyro_status gyro_mesh_load_obj(const char* path, gyro_mesh** out);
/** Releases the caller's reference; scenes that use the mesh keep it alive. NULL is fine. */
GYRO_API void gyro_mesh_destroy(gyro_mesh* mesh);

typedef struct gyro_mesh_info {
  int32_t triangle_count;
  int32_t bvh_nodes;  /**< 8-wide interior nodes */
  int32_t bvh_leaves; /**< leaf blocks of up to 4 triangles */
  int32_t bvh_depth;
  uint64_t bytes;     /**< BVH, leaf triangles and the mesh copy */
  float bounds_min[3];
  float bounds_max[3];
} gyro_mesh_info;

GYRO_API gyro_status gyro_mesh_get_info(const gyro_mesh* mesh, gyro_mesh_info* out);

/** Closest hit of every ray against the mesh: primitive is the triangle index, -1 for a
 *  miss or GYRO_RAY_INVALID. Exactly the brute-force answer (ties to the lower index), the
 *  same bits at every SIMD level and thread count. Errors (nothing written): NULL_ARGUMENT,
 *  INVALID_COUNT. */
GYRO_API gyro_status gyro_mesh_raycast_closest(const gyro_mesh* mesh, const gyro_ray_soa* rays, int32_t ray_count,
                                               const gyro_hit_soa* hits);
/** Any hit (occlusion): some triangle hit in [tmin, tmax] (the first the traversal finds). */
GYRO_API gyro_status gyro_mesh_raycast_any(const gyro_mesh* mesh, const gyro_ray_soa* rays, int32_t ray_count,
                                           const gyro_hit_soa* hits);

/* ------------------------------------------------------------------ camera and frustum */

typedef uint32_t gyro_projection;
enum { GYRO_PROJECTION_PERSPECTIVE = 0, GYRO_PROJECTION_ORTHOGRAPHIC = 1 };

/** A camera: the eye, its axes (rows: right, up, forward; view space looks down +forward)
 *  and a projection. Conventions of gyro/camera.hpp (row vectors, depth in [0, 1]). */
typedef struct gyro_camera {
  float position[3];
  float orientation[9]; /**< row-major 3x3: right, up, forward */
  gyro_projection mode;
  float fov_y;  /**< perspective: vertical field of view, radians */
  float aspect; /**< perspective: width / height */
  float width;  /**< orthographic: view volume size in world units */
  float height;
  float z_near;
  float z_far;
} gyro_camera;

/** A perspective camera at the origin looking down +z. */
GYRO_API gyro_camera gyro_camera_perspective(float fov_y, float aspect, float z_near, float z_far);
/** Points the camera from eye at target (up: the world's up direction). */
GYRO_API gyro_status gyro_camera_look_at(gyro_camera* camera, const float eye[3], const float target[3],
                                         const float up[3]);
/** The view-projection matrix (row-major, row vectors: clip = world * M). */
GYRO_API gyro_status gyro_camera_view_projection(const gyro_camera* camera, float out[16]);
/** The ray through a screen point (pixels, origin top-left, y down) of a viewport of the
 *  given size: origin on the near plane, unit direction. */
GYRO_API gyro_status gyro_camera_picking_ray(const gyro_camera* camera, float screen_x, float screen_y,
                                             float viewport_width, float viewport_height, float origin[3],
                                             float direction[3]);

/** Six planes (left, right, bottom, top, near, far) nx, ny, nz, d with unit normals
 *  pointing into the frustum: inside is dot(n, p) >= d. */
typedef struct gyro_frustum {
  float planes[6][4];
} gyro_frustum;

/** The frustum of a view-projection matrix (row-major, row vectors). */
GYRO_API gyro_status gyro_frustum_from_matrix(const float view_projection[16], gyro_frustum* out);
/** The frustum of a camera. */
GYRO_API gyro_status gyro_camera_frustum(const gyro_camera* camera, gyro_frustum* out);
/** visible[i] = 1 when shape i may be visible, 0 when it is certainly outside (a visible
 *  shape is never culled; a few invisible ones near the frustum's corners are kept). Shapes:
 *  spheres, AABBs or OBBs. Errors (nothing written): NULL_ARGUMENT, INVALID_COUNT,
 *  NON_FINITE, INVALID_ARGUMENT (another shape type, planes not unit length). */
GYRO_API gyro_status gyro_frustum_cull(const gyro_frustum* frustum, const gyro_shape_soa* shapes, int32_t count,
                                       uint32_t* visible);


/* ------------------------------------------------------------------ scenes */

/** A set of models (spheres, boxes, planes, instanced meshes) placed by transforms and
 *  parents, under a BVH (default) or the Cookbook's octree. Conventions of gyro/scene.hpp. */
typedef struct gyro_scene gyro_scene;

/** A model's id; all-zero is null. A removed model's id is stale (GYRO_STATUS_STALE_ID). */
typedef struct gyro_model_id {
  uint32_t index;
  uint32_t generation;
} gyro_model_id;

typedef uint32_t gyro_model_shape;
enum { GYRO_MODEL_SPHERE = 0, GYRO_MODEL_BOX = 1, GYRO_MODEL_MESH = 2, GYRO_MODEL_PLANE = 3 };

typedef uint32_t gyro_scene_accel;
enum { GYRO_SCENE_BVH = 0, GYRO_SCENE_OCTREE = 1 };

/** Whether a scene's ray batches (either structure) prefetch each next visit's cache lines (ABI 1.7).
 *  Speed only, never a result. AUTO (the default): when the tree exceeds 8 MiB, where it paid
 *  on the machine the default was measured on (1 MiB L2 per core, 32 MiB L3). */
typedef uint32_t gyro_ray_prefetch;
enum { GYRO_RAY_PREFETCH_AUTO = 0, GYRO_RAY_PREFETCH_ALWAYS = 1, GYRO_RAY_PREFETCH_NEVER = 2 };

/** Scale, then rotate (unit quaternion x, y, z, w), then translate (row vectors). */
typedef struct gyro_transform {
  float position[3];
  float rotation[4];
  float scale; /**< uniform, > 0 */
} gyro_transform;

typedef struct gyro_model_def {
  uint32_t struct_size; /**< sizeof(gyro_model_def): set by gyro_model_def_default */
  gyro_model_shape shape;
  float radius;          /**< sphere */
  float half_extents[3]; /**< box */
  float plane[4];        /**< plane: unit normal nx, ny, nz and d (dot(n, p) = d), in the model's frame */
  const gyro_mesh* mesh; /**< mesh: the scene keeps its own reference */
  gyro_transform transform; /**< relative to the parent (the world for a root) */
  gyro_model_id parent;     /**< null: a root */
} gyro_model_def;

/** A unit sphere at the origin, identity transform, no parent. */
GYRO_API gyro_model_def gyro_model_def_default(void);

GYRO_API gyro_status gyro_scene_create(gyro_scene_accel accel, gyro_scene** out);
GYRO_API void gyro_scene_destroy(gyro_scene* scene);
/** Sets the scene's gyro_ray_prefetch (ABI 1.7). NULL_ARGUMENT, or INVALID_ARGUMENT for an
 *  unknown mode; either changes nothing. */
GYRO_API gyro_status gyro_scene_set_ray_prefetch(gyro_scene* scene, gyro_ray_prefetch mode);
/** Whether moves (gyro_scene_set_transform), and adds and removes in a scene without parents,
 *  refit the scene's BVH instead of rebuilding it (ABI 1.8; 1, the default, or 0): see
 *  SceneSettings::refit in gyro/scene.hpp. Hits are
 *  the same either way, except which model an any hit names, which then depends on the
 *  sequence of calls, not on the models alone. NULL_ARGUMENT, or INVALID_ARGUMENT for a
 *  value other than 0 and 1; either changes nothing. */
GYRO_API gyro_status gyro_scene_set_refit(gyro_scene* scene, uint32_t enabled);
/** Errors change nothing: NULL_ARGUMENT, NON_FINITE, INVALID_ARGUMENT (negative size, zero
 *  rotation, scale <= 0, plane normal not unit, unknown shape, a parent cycle), STALE_ID. */
GYRO_API gyro_status gyro_scene_add_model(gyro_scene* scene, const gyro_model_def* def, gyro_model_id* out);
GYRO_API gyro_status gyro_scene_remove_model(gyro_scene* scene, gyro_model_id id);
GYRO_API gyro_status gyro_scene_set_transform(gyro_scene* scene, gyro_model_id id, const gyro_transform* local);
/** A null parent detaches the model; its local transform is kept. */
GYRO_API gyro_status gyro_scene_set_parent(gyro_scene* scene, gyro_model_id id, gyro_model_id parent);
/** Sets the layers a model is in (ABI 1.9; every model starts in all 32, 0xFFFFFFFF): the
 *  masked raycasts, queries and picks (the _masked calls) see a model only when their mask
 *  shares a bit with its layers; the unmasked calls see every layer. 0 hides the model
 *  from every raycast, query and pick, masked or not.
 *  Not a structural change (the tree is neither rebuilt nor refit). STALE_ID or
 *  NULL_ARGUMENT change nothing. */
GYRO_API gyro_status gyro_scene_set_layers(gyro_scene* scene, gyro_model_id id, uint32_t layers);
GYRO_API int32_t gyro_scene_model_count(const gyro_scene* scene);

/** Per-ray scene results: t and model required, the rest optional (NULL to skip; normal
 *  all three or none, u and v both or none). primitive: the triangle for mesh models, 0 for
 *  other shapes, -1 for a miss, GYRO_RAY_INVALID for a ray that cannot be answered. What is
 *  skipped is not computed: without normals a sphere or box hit costs its t alone. */
typedef struct gyro_scene_hit_soa {
  float* t;
  gyro_model_id* model;
  int32_t* primitive;
  float* nx;
  float* ny;
  float* nz;
  float* u;
  float* v;
} gyro_scene_hit_soa;

/** Closest hit of every ray: the brute-force answer over every model (ties to the lower id
 *  index), the same bits in both acceleration modes, at every SIMD level and thread count. */
GYRO_API gyro_status gyro_scene_raycast_closest(const gyro_scene* scene, const gyro_ray_soa* rays, int32_t ray_count,
                                                const gyro_scene_hit_soa* hits);
/** Any hit (occlusion, line of sight). */
GYRO_API gyro_status gyro_scene_raycast_any(const gyro_scene* scene, const gyro_ray_soa* rays, int32_t ray_count,
                                            const gyro_scene_hit_soa* hits);
/** gyro_scene_raycast_closest with layers (ABI 1.9): ray i sees only the models whose
 *  layers (gyro_scene_set_layers) share a bit with masks[i]. masks may be NULL: every
 *  ray sees every layer, as gyro_scene_raycast_closest. */
GYRO_API gyro_status gyro_scene_raycast_closest_masked(const gyro_scene* scene, const gyro_ray_soa* rays,
                                                       const uint32_t* masks, int32_t ray_count,
                                                       const gyro_scene_hit_soa* hits);
/** gyro_scene_raycast_any with layers (ABI 1.9), as gyro_scene_raycast_closest_masked. */
GYRO_API gyro_status gyro_scene_raycast_any_masked(const gyro_scene* scene, const gyro_ray_soa* rays,
                                                   const uint32_t* masks, int32_t ray_count,
                                                   const gyro_scene_hit_soa* hits);

/** Models overlapping shape 0 of `shape` (a sphere, AABB or OBB), ascending ids. The first
 *  min(*count, capacity) are written to out; *count gets how many there are. */
GYRO_API gyro_status gyro_scene_query(const gyro_scene* scene, const gyro_shape_soa* shape, gyro_model_id* out,
                                      int32_t capacity, int32_t* count);
/** Models whose bounding volume intersects the frustum, ascending ids (as gyro_scene_query). */
GYRO_API gyro_status gyro_scene_query_frustum(const gyro_scene* scene, const gyro_frustum* frustum, gyro_model_id* out,
                                              int32_t capacity, int32_t* count);
/** gyro_scene_query for the models whose layers (gyro_scene_set_layers) share a bit with
 *  `mask` (ABI 1.9). */
GYRO_API gyro_status gyro_scene_query_masked(const gyro_scene* scene, const gyro_shape_soa* shape, uint32_t mask,
                                             gyro_model_id* out, int32_t capacity, int32_t* count);
/** gyro_scene_query_frustum for the models whose layers share a bit with `mask` (ABI 1.9). */
GYRO_API gyro_status gyro_scene_query_frustum_masked(const gyro_scene* scene, const gyro_frustum* frustum, uint32_t mask,
                                                     gyro_model_id* out, int32_t capacity, int32_t* count);

typedef struct gyro_scene_hit {
  uint32_t hit; /**< 1 for a hit; 0 and the rest zero otherwise */
  float t;
  float point[3];
  float normal[3];
  gyro_model_id model;
  int32_t primitive;
  float u;
  float v;
} gyro_scene_hit;

/** The closest model under a screen point (pixels, origin top-left, y down). */
GYRO_API gyro_status gyro_scene_pick(const gyro_scene* scene, const gyro_camera* camera, float screen_x, float screen_y,
                                     float viewport_width, float viewport_height, gyro_scene_hit* out);
/** gyro_scene_pick among the models whose layers share a bit with `mask` (ABI 1.9). */
GYRO_API gyro_status gyro_scene_pick_masked(const gyro_scene* scene, const gyro_camera* camera, float screen_x,
                                            float screen_y, float viewport_width, float viewport_height, uint32_t mask,
                                            gyro_scene_hit* out);

/* ------------------------------------------------------------------ dynamics world (ABI 1.2) */

/** Rigid bodies, contacts and the solver (conventions of gyro/world.hpp): SI units, gravity
 *  (0, -9.81, 0) by default, quaternions (x, y, z, w) rotating body-local vectors into the
 *  world. Present when gyro_features() has GYRO_FEATURE_DYNAMICS.
 *  - Every call with a stale id (a destroyed body, or the null id) returns
 *    GYRO_STATUS_STALE_ID and changes nothing.
 *  - Bad input (NULL, NaN or infinite values, a wrong struct_size, an unknown enum value, a
 *    boolean other than 0 or 1, a non-zero reserved field, dt <= 0) gets a status and changes
 *    nothing: the world's state and gyro_world_hash() are as before the call.
 *  - The state after every step is bit-identical at every SIMD level and thread count;
 *    gyro_world_hash() is the witness.
 *  - One world must not be used from two threads at once; separate worlds may step in
 *    parallel. */
typedef struct gyro_world gyro_world;

typedef struct gyro_vec3 {
  float x, y, z;
} gyro_vec3;

/** A rotation (x, y, z, w); w is the scalar part. Normalised on input; must not be zero. */
typedef struct gyro_quat {
  float x, y, z, w;
} gyro_quat;

/** A body's id; all-zero is null. Ordered by index, then generation. */
typedef struct gyro_body_id {
  uint32_t index;
  uint32_t generation;
} gyro_body_id;

typedef uint32_t gyro_body_type;
enum {
  GYRO_BODY_STATIC = 0,    /**< never moves; infinite mass */
  GYRO_BODY_KINEMATIC = 1, /**< moves by its velocity only; pushes dynamic bodies */
  GYRO_BODY_DYNAMIC = 2    /**< moved by forces, gravity and contacts */
};

typedef uint32_t gyro_body_shape;
enum {
  GYRO_BODY_SHAPE_SPHERE = 0, /**< radius, centred on the body's origin */
  GYRO_BODY_SHAPE_BOX = 1,    /**< half_extents, centred on the body's origin */
  GYRO_BODY_SHAPE_PLANE = 2,  /**< static only: the body frame's y = 0 plane, normal +y */
  GYRO_BODY_SHAPE_MESH = 3,   /**< static only: mesh, in the body's frame */
  GYRO_BODY_SHAPE_CAPSULE = 4, /**< ABI 1.4: the segment (0, +-half_height, 0) plus radius, in the body's frame */
  GYRO_BODY_SHAPE_HULL = 5     /**< ABI 1.4: hull (copied); the body frame is the hull's mass frame
                                    (see gyro_body_get_shape_frame) */
};

/** How contacts correct position errors. */
typedef uint32_t gyro_contact_model;
enum {
  GYRO_CONTACT_SOFT_STEP = 0,        /**< sub-steps, soft constraints, relaxation (default) */
  GYRO_CONTACT_BAUMGARTE = 1,        /**< Baumgarte bias with slop in the velocity iterations */
  GYRO_CONTACT_LINEAR_PROJECTION = 2 /**< no bias; positions projected apart after the step */
};

/** How pairs with a capsule or hull build their manifolds (ABI 1.4). */
typedef uint32_t gyro_convex_manifold;
enum {
  GYRO_CONVEX_MANIFOLD_CLIPPING = 0,   /**< GJK/EPA's normal, then face clipping, up to 4 points (default) */
  GYRO_CONVEX_MANIFOLD_INCREMENTAL = 1 /**< the appendix's arbiter: one GJK/EPA point per step, kept over steps */
};

/** The world's settings (gyro::WorldDef). Booleans are 0 or 1. gyro_world_create also
 *  accepts ABI 1.3's struct (struct_size without convex_manifold: it keeps its default). */
typedef struct gyro_world_def {
  uint32_t struct_size; /**< sizeof(gyro_world_def): set by gyro_world_def_default */
  gyro_contact_model contact_model;
  gyro_vec3 gravity;
  uint32_t substeps;            /**< soft step only (1..64); the other models run 1 */
  uint32_t velocity_iterations; /**< per sub-step (soft step) or per step (others: try 10) */
  uint32_t relax_iterations;    /**< soft step: iterations without bias after each sub-step */
  uint32_t position_iterations; /**< linear projection passes */
  float linear_slop;            /**< m of penetration left uncorrected */
  float baumgarte;              /**< Baumgarte / linear projection: fraction corrected per step */
  float contact_hertz;          /**< soft step: stiffness of the contact softness */
  float contact_damping_ratio;
  float max_push_velocity;      /**< m/s: cap on the speed penetration is resolved with */
  float restitution_threshold;  /**< m/s: slower approaches do not bounce */
  uint32_t enable_warm_starting;
  uint32_t enable_sleep;
  float sleep_time;             /**< s a whole island must rest before it sleeps */
  float sleep_linear_velocity;  /**< m/s */
  float sleep_angular_velocity; /**< rad/s */
  uint32_t enable_continuous;   /**< speculative contacts sized by the motion of the step */
  uint32_t threads;             /**< 0: gyro_get_thread_count() */
  gyro_convex_manifold convex_manifold; /**< ABI 1.4 */
} gyro_world_def;

/** gyro::WorldDef's defaults (gyro/world.hpp): the soft step with its sub-steps, sleeping on. */
GYRO_API gyro_world_def gyro_world_def_default(void);
/** Errors (*out untouched): NULL_ARGUMENT, NON_FINITE, INVALID_ARGUMENT (struct_size,
 *  contact_model, convex_manifold, a boolean, iterations or sub-steps outside 1..64, negative slop, ...). */
GYRO_API gyro_status gyro_world_create(const gyro_world_def* def, gyro_world** out);
/** Destroys the world and its bodies (releasing their mesh references). NULL is fine. */
GYRO_API void gyro_world_destroy(gyro_world* world);
/** Advances the world by dt seconds. Errors (nothing changed): NULL_ARGUMENT, NON_FINITE
 *  (dt NaN or infinite), INVALID_ARGUMENT (dt <= 0). */
GYRO_API gyro_status gyro_world_step(gyro_world* world, float dt);
/** The 64-bit witness of the whole state (every state column, the contacts' accumulated
 *  impulses, the id allocator): equal hashes for equal call sequences. */
GYRO_API gyro_status gyro_world_hash(const gyro_world* world, uint64_t* out);
GYRO_API gyro_status gyro_world_body_count(const gyro_world* world, int32_t* out);

/** A convex polyhedron built by gyro_convex_hull_create (the convex section below). */
typedef struct gyro_convex_hull gyro_convex_hull;

/** A body's definition (gyro::BodyDef). Booleans are 0 or 1.
 *  ABI 1.4 appended half_height, reserved2 and hull. gyro_body_create also accepts the ABI
 *  1.3 struct_size (the struct up to and without half_height, padded as the compiler pads
 *  it: 144 bytes with 64-bit pointers): it then reads nothing past mesh, and such a
 *  definition cannot describe a capsule or a hull. */
typedef struct gyro_body_def {
  uint32_t struct_size; /**< sizeof(gyro_body_def): set by gyro_body_def_default */
  gyro_body_type type;
  gyro_body_shape shape;
  float radius;           /**< sphere, > 0 */
  gyro_vec3 half_extents; /**< box, each > 0 */
  gyro_vec3 position;
  gyro_quat orientation;
  gyro_vec3 linear_velocity;
  gyro_vec3 angular_velocity; /**< world frame, rad/s */
  float density;              /**< kg/m^3, used when mass is 0 */
  float mass;                 /**< kg; > 0 overrides density (inertia scales with it) */
  float friction;             /**< Coulomb coefficient; a pair uses sqrt(fa * fb) */
  float restitution;          /**< a pair uses max(ea, eb) */
  float linear_damping;       /**< 1/s */
  float angular_damping;      /**< 1/s */
  float gravity_scale;
  uint32_t category; /**< a pair collides when (catA & maskB) != 0 and (catB & maskA) != 0 */
  uint32_t mask;
  uint32_t allow_sleep;
  uint32_t awake;
  uint32_t reserved; /**< 0 */
  uint64_t user_data;
  /** GYRO_BODY_SHAPE_MESH: the world keeps its own reference until the body is destroyed,
   *  so the caller may gyro_mesh_destroy its handle at once. NULL for other shapes. */
  const gyro_mesh* mesh;
  float half_height;  /**< capsule (ABI 1.4): half the length of its core segment, >= 0 */
  uint32_t reserved2; /**< 0 */
  /** GYRO_BODY_SHAPE_HULL (ABI 1.4): the world copies the hull, so the caller may
   *  gyro_convex_hull_destroy its handle at once. NULL for other shapes. */
  const gyro_convex_hull* hull;
} gyro_body_def;

/** A dynamic unit box (half extents 0.5, density 1: 1 kg) at the origin, at rest, awake,
 *  friction 0.6, restitution 0, colliding with everything; half_height 0.5, hull NULL. */
GYRO_API gyro_body_def gyro_body_def_default(void);
/** Errors (*out untouched, the world unchanged): NULL_ARGUMENT (def, out, or the mesh of a
 *  mesh body, or the hull of a hull body), NON_FINITE, INVALID_ARGUMENT (struct_size: neither this header's nor ABI
 *  1.3's, an unknown type or shape, a boolean, reserved or reserved2, a negative mass, a
 *  dynamic body with neither mass nor density > 0, a zero-size shape, a negative
 *  half_height, a zero quaternion, a plane or mesh on a non-static body, a mesh given for
 *  another shape, a hull given for another shape, a capsule
 *  or hull in an ABI 1.3 struct). */
GYRO_API gyro_status gyro_body_create(gyro_world* world, const gyro_body_def* def, gyro_body_id* out);
/** The id becomes stale. */
GYRO_API gyro_status gyro_body_destroy(gyro_world* world, gyro_body_id id);
/** 1 if id names a live body of the world, else 0 (also for a NULL world). */
GYRO_API uint32_t gyro_body_is_valid(const gyro_world* world, gyro_body_id id);

/** Either out pointer may be NULL (not both). */
GYRO_API gyro_status gyro_body_get_transform(const gyro_world* world, gyro_body_id id, gyro_vec3* position,
                                             gyro_quat* orientation);
/** Where the shape's own frame sits in the body frame (ABI 1.4). A hull body's frame is the
 *  hull's mass frame (origin at the centroid, axes along the principal axes), so the hull as
 *  built by gyro_convex_hull_create is at position + rotate(orientation, *offset) with the
 *  rotation orientation * *rotation (position and orientation from gyro_body_get_transform).
 *  Identity (offset 0, rotation (0, 0, 0, 1)) for every other shape. Either out pointer may
 *  be NULL (not both). Errors: NULL_ARGUMENT, STALE_ID. */
GYRO_API gyro_status gyro_body_get_shape_frame(const gyro_world* world, gyro_body_id id, gyro_vec3* offset,
                                               gyro_quat* rotation);
/** Teleports the body (and wakes it); contacts are recomputed next step. */
GYRO_API gyro_status gyro_body_set_transform(gyro_world* world, gyro_body_id id, gyro_vec3 position,
                                             gyro_quat orientation);
/** Either out pointer may be NULL (not both). */
GYRO_API gyro_status gyro_body_get_velocity(const gyro_world* world, gyro_body_id id, gyro_vec3* linear,
                                            gyro_vec3* angular);
GYRO_API gyro_status gyro_body_set_velocity(gyro_world* world, gyro_body_id id, gyro_vec3 linear, gyro_vec3 angular);
/** 0 for static and kinematic bodies. */
GYRO_API gyro_status gyro_body_get_mass(const gyro_world* world, gyro_body_id id, float* out);
GYRO_API gyro_status gyro_body_get_type(const gyro_world* world, gyro_body_id id, gyro_body_type* out);
GYRO_API gyro_status gyro_body_get_user_data(const gyro_world* world, gyro_body_id id, uint64_t* out);

/** Forces and torques act during the next step only. */
GYRO_API gyro_status gyro_body_apply_force(gyro_world* world, gyro_body_id id, gyro_vec3 force, gyro_vec3 world_point);
GYRO_API gyro_status gyro_body_apply_force_at_center(gyro_world* world, gyro_body_id id, gyro_vec3 force);
GYRO_API gyro_status gyro_body_apply_torque(gyro_world* world, gyro_body_id id, gyro_vec3 torque);
/** Impulses change the velocity at once. */
GYRO_API gyro_status gyro_body_apply_linear_impulse(gyro_world* world, gyro_body_id id, gyro_vec3 impulse,
                                                    gyro_vec3 world_point);
GYRO_API gyro_status gyro_body_apply_angular_impulse(gyro_world* world, gyro_body_id id, gyro_vec3 impulse);

/** awake: 0 or 1. */
GYRO_API gyro_status gyro_body_set_awake(gyro_world* world, gyro_body_id id, uint32_t awake);
GYRO_API gyro_status gyro_body_is_awake(const gyro_world* world, gyro_body_id id, uint32_t* out);

/** Zero-copy views of the bodies' state, dense slots 0..count-1 (ids[i] names slot i).
 *  Valid until the next gyro_body_create, gyro_body_destroy, gyro_world_step or
 *  gyro_world_destroy; read only. */
typedef struct gyro_body_view {
  int32_t count;
  uint32_t reserved; /**< 0 */
  const gyro_body_id* ids;
  const float *px, *py, *pz;
  const float *qx, *qy, *qz, *qw;
  const float *vx, *vy, *vz;
  const float *wx, *wy, *wz;
} gyro_body_view;

GYRO_API gyro_status gyro_world_get_body_view(const gyro_world* world, gyro_body_view* out);

/** Milliseconds spent in each stage of the last step (0 for a skipped stage). */
typedef struct gyro_step_timings {
  double forces, broadphase, narrowphase, islands, solver, particles, total;
} gyro_step_timings;

/** Counters of the last step. */
typedef struct gyro_step_stats {
  uint32_t bodies, awake_bodies;
  uint32_t pairs;     /**< broadphase pairs */
  uint32_t manifolds; /**< manifolds with at least one point */
  uint32_t contacts;  /**< contact points */
  uint32_t colors;    /**< constraint graph colours used by the solver */
  uint32_t islands;   /**< islands of touching awake bodies */
  uint32_t reserved;  /**< 0 */
} gyro_step_stats;

GYRO_API gyro_status gyro_world_get_timings(const gyro_world* world, gyro_step_timings* out);
GYRO_API gyro_status gyro_world_get_stats(const gyro_world* world, gyro_step_stats* out);

/** Stages of a step, for gyro_world_get_stage_time (ABI 1.3). gyro_step_timings keeps its
 *  ABI 1.2 layout; stages added later (soft bodies first) are read only through this call. */
typedef uint32_t gyro_step_stage;
enum {
  GYRO_STAGE_FORCES = 0,
  GYRO_STAGE_BROADPHASE = 1,
  GYRO_STAGE_NARROWPHASE = 2,
  GYRO_STAGE_ISLANDS = 3,
  GYRO_STAGE_SOLVER = 4,
  GYRO_STAGE_PARTICLES = 5,
  GYRO_STAGE_TOTAL = 6,
  GYRO_STAGE_SOFT_BODIES = 7 /**< springs, cloth and soft bodies (after the particles) */
};

/** Milliseconds the last step spent in one stage (0 for a skipped stage). Errors:
 *  NULL_ARGUMENT, INVALID_ARGUMENT (an unknown stage: a newer stage on an older library). */
GYRO_API gyro_status gyro_world_get_stage_time(const gyro_world* world, gyro_step_stage stage, double* out_ms);

/** A pair of bodies that started or stopped touching (a < b in id order). */
typedef struct gyro_contact_event {
  gyro_body_id a, b;
} gyro_contact_event;

/** The last step's contact events, sorted by (a, b): zero-copy arrays valid until the next
 *  gyro_world_step or gyro_world_destroy (NULL when the count is 0). */
typedef struct gyro_contact_events {
  const gyro_contact_event* begin;
  const gyro_contact_event* end;
  int32_t begin_count;
  int32_t end_count;
} gyro_contact_events;

GYRO_API gyro_status gyro_world_get_contact_events(const gyro_world* world, gyro_contact_events* out);

/* ------------------------------------------------------------------ springs, cloth and soft bodies (ABI 1.3) */

/** Springs, cloth and soft bodies owned by a world (conventions of gyro/soft_body.hpp).
 *  Present when gyro_features() has GYRO_FEATURE_SOFT_BODIES.
 *  - A soft body is a network of particles (dense indices 0..count-1, fixed at creation)
 *    joined by distance springs; every spring belongs to a family whose constants apply to
 *    all its springs. The world steps its soft bodies after the particles (stage
 *    GYRO_STAGE_SOFT_BODIES); each collides with every rigid body's shape at its current
 *    pose (one way: cloth does not push bodies), so the world's bodies are the colliders.
 *  - Two models: XPBD (default; stable for any stiffness and dt, stiffness may be +infinity)
 *    and the book's explicit Hooke springs (unstable when a sub-step exceeds ~2 sqrt(m/k)).
 *  - Pinned particles have inverse mass 0 and move only when gyro_soft_body_set_position
 *    moves them.
 *  - Particle indices are uint32_t; an index >= the particle count is INVALID_ARGUMENT.
 *  - A stale id (destroyed, null, or of another world) is GYRO_STATUS_STALE_ID. Bad input
 *    (NULL, NaN or infinite values, a wrong struct_size, an unknown enum value, a boolean
 *    other than 0 or 1, a grid smaller than 2 x 2, stiffness <= 0 or NaN,
 *    damping or mass out of range) gets a status and changes nothing: the world's state and
 *    gyro_world_hash(), which covers the soft bodies, are as before the call.
 *  - Bit-identical at every SIMD level and thread count; gyro_soft_body_hash() is the
 *    witness of one body, gyro_world_hash() of the whole world. */

/** A soft body's id; all-zero is null. */
typedef struct gyro_soft_body_id {
  uint32_t index;
  uint32_t generation;
} gyro_soft_body_id;

typedef uint32_t gyro_soft_model;
enum {
  GYRO_SOFT_MODEL_XPBD = 0,   /**< constraints with compliance 1/k, sub-stepped (default) */
  GYRO_SOFT_MODEL_SPRINGS = 1 /**< the book's explicit Hooke springs with damping */
};

typedef uint32_t gyro_spring_family;
enum {
  GYRO_SPRING_STRUCTURAL = 0, /**< grid neighbours along x and z; mesh edges; cube edges */
  GYRO_SPRING_SHEAR = 1,      /**< grid cell diagonals; cube face diagonals */
  GYRO_SPRING_BEND = 2,       /**< grid neighbours two apart; across mesh edges; cube body diagonals */
  GYRO_SPRING_RADIAL = 3,     /**< mesh soft bodies: surface particles to the centre particle */
  GYRO_SPRING_JOINT = 4       /**< particle joints */
};

typedef uint32_t gyro_collision_response;
enum {
  GYRO_COLLISION_PROJECTION = 0, /**< particles are moved out of colliders (default) */
  GYRO_COLLISION_PENALTY = 1     /**< a penalty spring pushes particles out (soft bodies that squash) */
};

/** One family's constants. */
typedef struct gyro_spring_constants {
  float stiffness; /**< N/m, > 0; +INFINITY: inextensible (XPBD only) */
  float damping;   /**< N s/m along the spring, >= 0 and finite */
} gyro_spring_constants;

/** How a soft body steps (gyro::SoftSettings). */
typedef struct gyro_soft_settings {
  uint32_t struct_size; /**< sizeof(gyro_soft_settings): set by gyro_soft_settings_default */
  gyro_soft_model model;
  uint32_t substeps;   /**< per step, 1..256 */
  uint32_t iterations; /**< XPBD passes over the springs per sub-step, 1..64 */
  gyro_vec3 gravity;   /**< the soft body's own gravity (not the world's) */
  float damping;       /**< 1/s, >= 0: v *= 1 / (1 + h damping) per sub-step h */
  float thickness;     /**< m kept between particles and collider surfaces, >= 0 */
  float friction;      /**< Coulomb coefficient at collider contacts, in [0, 1] */
  gyro_collision_response response;
  float penalty_stiffness; /**< N/m per particle (penalty response), > 0 */
} gyro_soft_settings;

/** gyro::SoftSettings' defaults: XPBD, 16 sub-steps, 1 iteration, gravity (0, -9.81, 0),
 *  thickness 1 cm, friction 0.3, projection. */
GYRO_API gyro_soft_settings gyro_soft_settings_default(void);

/** A grid cloth on the x-z plane: nx * nz particles over size_x * size_z metres, centred. */
typedef struct gyro_cloth_def {
  uint32_t struct_size; /**< sizeof(gyro_cloth_def): set by gyro_cloth_def_default */
  int32_t nx, nz;       /**< particles along x and z, >= 2 each */
  float size_x, size_z; /**< m, > 0 */
  gyro_vec3 center;
  float particle_mass;     /**< kg per particle, > 0 */
  uint32_t both_diagonals; /**< 1: two shear springs per cell; 0: one, alternating by parity */
  uint32_t bend;           /**< 1: bend springs between grid neighbours two apart */
  gyro_spring_constants structural;
  gyro_spring_constants shear;
  gyro_spring_constants bend_constants;
} gyro_cloth_def;

/** gyro::ClothDef's defaults: 32 x 32 particles over 10 x 10 m at the origin, 1 kg each. */
GYRO_API gyro_cloth_def gyro_cloth_def_default(void);

/** The appendix's soft cube: 8 particles, 28 springs (edges: structural, face diagonals:
 *  shear, body diagonals: bend). */
typedef struct gyro_soft_cube_def {
  uint32_t struct_size; /**< sizeof(gyro_soft_cube_def): set by gyro_soft_cube_def_default */
  gyro_vec3 center;
  float half_extent;   /**< m, > 0 */
  float particle_mass; /**< kg per corner, > 0 */
  gyro_spring_constants structural;
  gyro_spring_constants shear;
  gyro_spring_constants bend;
} gyro_soft_cube_def;

GYRO_API gyro_soft_cube_def gyro_soft_cube_def_default(void);

/** A soft body from a closed triangle mesh: one particle per vertex (positions SoA, copied),
 *  structural springs on the edges, bend springs across each edge, and radial springs from
 *  every vertex to one extra particle at the vertices' centroid (particle vertex_count). */
typedef struct gyro_soft_mesh_def {
  uint32_t struct_size; /**< sizeof(gyro_soft_mesh_def): set by gyro_soft_mesh_def_default */
  int32_t vertex_count; /**< >= 4 */
  const float* x;
  const float* y;
  const float* z;
  const uint32_t* indices; /**< three per triangle */
  int32_t triangle_count;  /**< >= 4 */
  float particle_mass;     /**< kg per particle (the centre too), > 0 */
  gyro_spring_constants structural;
  gyro_spring_constants bend;
  gyro_spring_constants radial;
} gyro_soft_mesh_def;

GYRO_API gyro_soft_mesh_def gyro_soft_mesh_def_default(void);

/** Builds a soft body and adds it to the world with default settings. Errors (*out
 *  untouched, the world unchanged): NULL_ARGUMENT, INVALID_COUNT (a grid smaller than
 *  2 x 2, negative nx or nz included; fewer than 4 mesh vertices or triangles; more than
 *  2^24 particles), NON_FINITE, INVALID_ARGUMENT (struct_size, a boolean, size or mass <= 0,
 *  stiffness <= 0, damping < 0, an index out of range, a triangle repeating a vertex, a
 *  mesh that is not closed: every edge shared by exactly two triangles). */
GYRO_API gyro_status gyro_world_create_cloth(gyro_world* world, const gyro_cloth_def* def, gyro_soft_body_id* out);
GYRO_API gyro_status gyro_world_create_soft_cube(gyro_world* world, const gyro_soft_cube_def* def,
                                                 gyro_soft_body_id* out);
GYRO_API gyro_status gyro_world_create_soft_mesh(gyro_world* world, const gyro_soft_mesh_def* def,
                                                 gyro_soft_body_id* out);
/** The id becomes stale. */
GYRO_API gyro_status gyro_world_destroy_soft_body(gyro_world* world, gyro_soft_body_id id);
/** 1 if id names a live soft body of the world, else 0 (also for a NULL world). */
GYRO_API uint32_t gyro_soft_body_is_valid(const gyro_world* world, gyro_soft_body_id id);
GYRO_API gyro_status gyro_world_soft_body_count(const gyro_world* world, int32_t* out);

/** Errors: INVALID_ARGUMENT (struct_size, model, response, substeps outside 1..256,
 *  iterations outside 1..64, damping or thickness < 0, friction outside [0, 1],
 *  penalty_stiffness <= 0), NON_FINITE. */
GYRO_API gyro_status gyro_soft_body_set_settings(gyro_world* world, gyro_soft_body_id id,
                                                 const gyro_soft_settings* settings);
/** out->struct_size must be set (start from gyro_soft_settings_default()). */
GYRO_API gyro_status gyro_soft_body_get_settings(const gyro_world* world, gyro_soft_body_id id,
                                                 gyro_soft_settings* out);
/** Constants of every spring of one family. Errors: INVALID_ARGUMENT (an unknown family,
 *  stiffness <= 0, damping < 0), NON_FINITE (NaN stiffness or damping, infinite damping). */
GYRO_API gyro_status gyro_soft_body_set_family(gyro_world* world, gyro_soft_body_id id, gyro_spring_family family,
                                               const gyro_spring_constants* constants);
GYRO_API gyro_status gyro_soft_body_get_family(const gyro_world* world, gyro_soft_body_id id,
                                               gyro_spring_family family, gyro_spring_constants* out);

/** Every particle's mass (kg, > 0 and finite); pinned particles stay pinned. */
GYRO_API gyro_status gyro_soft_body_set_mass(gyro_world* world, gyro_soft_body_id id, float mass);
GYRO_API gyro_status gyro_soft_body_set_particle_mass(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                      float mass);
/** Pinning sets the inverse mass to 0; unpinning restores the particle's mass. */
GYRO_API gyro_status gyro_soft_body_pin(gyro_world* world, gyro_soft_body_id id, uint32_t particle);
GYRO_API gyro_status gyro_soft_body_unpin(gyro_world* world, gyro_soft_body_id id, uint32_t particle);
GYRO_API gyro_status gyro_soft_body_is_pinned(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                              uint32_t* out);
GYRO_API gyro_status gyro_soft_body_get_position(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3* out);
/** Teleports the particle (how a pinned particle is moved); its velocity is kept. */
GYRO_API gyro_status gyro_soft_body_set_position(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3 position);
GYRO_API gyro_status gyro_soft_body_get_velocity(const gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3* out);
GYRO_API gyro_status gyro_soft_body_set_velocity(gyro_world* world, gyro_soft_body_id id, uint32_t particle,
                                                 gyro_vec3 velocity);
/** A cloth's particle at grid column ix (along x, < nx) and row iz (along z, < nz).
 *  INVALID_ARGUMENT for a soft body that is not a cloth or a cell outside the grid. */
GYRO_API gyro_status gyro_soft_body_cloth_index(const gyro_world* world, gyro_soft_body_id id, uint32_t ix,
                                                uint32_t iz, uint32_t* out);

/** Particle joints (chapter 16), springs of the family GYRO_SPRING_JOINT between two
 *  different particles of one body. A distance joint keeps a and b rest_length apart
 *  (finite; a negative rest_length takes their current distance); out_joint (may be NULL)
 *  numbers it among the body's joints. */
GYRO_API gyro_status gyro_soft_body_add_distance_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a,
                                                       uint32_t b, float rest_length, uint32_t* out_joint);
/** A ball joint: a and b held together (a zero-length distance joint). */
GYRO_API gyro_status gyro_soft_body_add_ball_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a, uint32_t b);
/** A hinge: (a0, b0) and (a1, b1) held together, so the parts turn about the line a0-a1
 *  (a0 != a1, b0 != b1). */
GYRO_API gyro_status gyro_soft_body_add_hinge_joint(gyro_world* world, gyro_soft_body_id id, uint32_t a0,
                                                    uint32_t b0, uint32_t a1, uint32_t b1);

/** Zero-copy read view of one soft body's particles (dense, 0..count-1) and its triangles
 *  (three particle indices each; counter-clockwise seen from +y for a cloth). Valid until
 *  the next gyro_world_step, change of the body, creation or destruction of a soft body, or
 *  gyro_world_destroy; read only. */
typedef struct gyro_soft_body_view {
  int32_t count;
  int32_t triangle_count;
  const float *px, *py, *pz;
  const float *vx, *vy, *vz;
  const float* inverse_mass; /**< 0 for a pinned particle */
  const uint32_t* triangles;
} gyro_soft_body_view;

GYRO_API gyro_status gyro_soft_body_get_view(const gyro_world* world, gyro_soft_body_id id, gyro_soft_body_view* out);

/** Figures of the current state, computed on demand in double in a fixed order. */
typedef struct gyro_soft_body_stats {
  int32_t particles, springs;
  int32_t colors;    /**< independent spring sets of the Gauss-Seidel pass */
  uint32_t reserved; /**< 0 */
  double max_strain; /**< max |len - rest| / rest over structural springs */
  double mean_strain;
  double kinetic_energy, potential_energy, elastic_energy; /**< J (gravity potential from y = 0) */
  double min_y; /**< lowest particle */
} gyro_soft_body_stats;

GYRO_API gyro_status gyro_soft_body_get_stats(const gyro_world* world, gyro_soft_body_id id,
                                              gyro_soft_body_stats* out);
/** The 64-bit witness of one soft body (settings, families, particles, springs). */
GYRO_API gyro_status gyro_soft_body_hash(const gyro_world* world, gyro_soft_body_id id, uint64_t* out);

/* ------------------------------------------------------------------ convex shapes (ABI 1.4) */

/** Convex hulls and GJK/EPA queries on arrays of pairs (conventions of gyro/convex.hpp).
 *  Present when gyro_features() has GYRO_FEATURE_CONVEX.
 *  - A shape is described in its local frame; a pose places it with the OBB convention of
 *    gyro_obb_soa: world = local * rotation + position, the rows of rotation being the
 *    shape's local x, y, z axes in the world (a proper rotation: unit, orthogonal rows).
 *  - Capsules and cylinders run along their local y axis, from -half_height to +half_height.
 *  - The normal of a result points from A towards B: moving B by depth * normal separates an
 *    intersecting pair; a separated pair closes its gap by moving B by -distance * normal.
 *  - Results are bit-identical at every SIMD level and thread count.
 *  - gyro_convex_hull (typedef'd before gyro_body_def) is a convex polyhedron built by
 *    quickhull: welded vertices, planar faces (coplanar triangles merged, collinear boundary
 *    vertices removed) and unique edges. Immutable: it may be read and queried from many
 *    threads at once. */

/** Builds the convex hull of count points (copied; duplicates and near-duplicates welded,
 *  points within about 1e-6 of the cloud's extent of a face count as on it). Errors (*out
 *  untouched): NULL_ARGUMENT (out, or points with count > 0), INVALID_COUNT (count < 4,
 *  negative included), NON_FINITE (a NaN or infinite coordinate), INVALID_ARGUMENT (the
 *  points coincide, are collinear or coplanar: no volume), INTERNAL (a consistency check
 *  failed), OUT_OF_MEMORY. */
GYRO_API gyro_status gyro_convex_hull_create(const gyro_vec3* points, int32_t count, gyro_convex_hull** out);
/** Releases the hull; bodies built from it keep their own copy. NULL is fine. */
GYRO_API void gyro_convex_hull_destroy(gyro_convex_hull* hull);

typedef struct gyro_convex_hull_info {
  int32_t vertex_count;
  int32_t face_count;
  int32_t edge_count;
  int32_t face_vertex_count; /**< entries of gyro_convex_hull_get_face_vertices: the sum of the faces' sizes */
} gyro_convex_hull_info;

/** Errors: NULL_ARGUMENT. */
GYRO_API gyro_status gyro_convex_hull_get_info(const gyro_convex_hull* hull, gyro_convex_hull_info* out);

/** The copy-out getters below share one pattern: *count gets how many elements there are,
 *  and the first min(capacity, *count) are written to out (out may be NULL when capacity is
 *  0: a call that asks for the size). Errors (nothing written): NULL_ARGUMENT (hull, count,
 *  or out with capacity > 0), INVALID_COUNT (capacity < 0). */

/** The hull's vertices, in the order of their first index among the input points. */
GYRO_API gyro_status gyro_convex_hull_get_vertices(const gyro_convex_hull* hull, gyro_vec3* out, int32_t capacity,
                                                   int32_t* count);

/** A plane dot(normal, p) = d. */
typedef struct gyro_convex_plane {
  gyro_vec3 normal; /**< unit, pointing out of the hull */
  float d;
} gyro_convex_plane;

/** One plane per face, in face order. */
GYRO_API gyro_status gyro_convex_hull_get_planes(const gyro_convex_hull* hull, gyro_convex_plane* out,
                                                 int32_t capacity, int32_t* count);
/** face_count + 1 offsets: face f has the vertex indices face_vertices[start[f] .. start[f + 1]). */
GYRO_API gyro_status gyro_convex_hull_get_face_starts(const gyro_convex_hull* hull, uint32_t* out, int32_t capacity,
                                                      int32_t* count);
/** Every face's vertex indices (into the vertices), counter-clockwise seen from outside. */
GYRO_API gyro_status gyro_convex_hull_get_face_vertices(const gyro_convex_hull* hull, uint32_t* out, int32_t capacity,
                                                        int32_t* count);

/** An edge between two vertex indices, a < b. */
typedef struct gyro_convex_edge {
  uint32_t a, b;
} gyro_convex_edge;

/** The unique edges, sorted by (a, b). */
GYRO_API gyro_status gyro_convex_hull_get_edges(const gyro_convex_hull* hull, gyro_convex_edge* out,
                                                int32_t capacity, int32_t* count);

/** Mass properties of the solid hull at density 1 (multiply volume and inertia by a
 *  density), in the hull's own frame. */
typedef struct gyro_convex_mass {
  float volume;
  gyro_vec3 centroid;    /**< the centre of mass */
  gyro_vec3 inertia[3];  /**< rows of the inertia tensor about the centroid, density 1 */
  gyro_vec3 principal_moments; /**< eigenvalues of the inertia, ascending */
  /** Rows: the matching unit eigenvectors, a right-handed rotation (inertia =
   *  axes^T diag(moments) axes). */
  gyro_vec3 principal_axes[3];
} gyro_convex_mass;

/** Volume, centroid, inertia and principal frame (divergence theorem in binary64, Jacobi
 *  rotations; deterministic). Errors (*out untouched): NULL_ARGUMENT, INVALID_ARGUMENT (a
 *  hull with no volume). */
GYRO_API gyro_status gyro_convex_hull_mass(const gyro_convex_hull* hull, gyro_convex_mass* out);

typedef uint32_t gyro_convex_type;
enum {
  GYRO_CONVEX_SPHERE = 0,   /**< radius around the origin */
  GYRO_CONVEX_BOX = 1,      /**< half_extents around the origin */
  GYRO_CONVEX_CAPSULE = 2,  /**< the segment (0, +-half_height, 0) plus radius */
  GYRO_CONVEX_CYLINDER = 3, /**< the axis (0, +-half_height, 0), radius */
  GYRO_CONVEX_TRIANGLE = 4, /**< corners triangle[0..2] (flat: it has no inside) */
  GYRO_CONVEX_HULL = 5      /**< hull, in the frame its points were given in */
};

/** A convex shape in its local frame: set type and the type's members; the others are
 *  ignored, except hull, which must be NULL for the other types. Sizes are >= 0. */
typedef struct gyro_convex_shape {
  gyro_convex_type type;
  float radius;           /**< sphere, capsule, cylinder */
  float half_height;      /**< capsule, cylinder */
  gyro_vec3 half_extents; /**< box */
  gyro_vec3 triangle[3];  /**< triangle */
  uint32_t reserved;      /**< 0 */
  /** hull: not copied; it must stay alive during the call. */
  const gyro_convex_hull* hull;
} gyro_convex_shape;

/** Where a shape is: world = local * rotation + position (rows: the local axes in the world). */
typedef struct gyro_convex_pose {
  gyro_vec3 position;
  gyro_vec3 rotation[3];
} gyro_convex_pose;

/** The pose of a body transform (a quaternion rotating local vectors into the world, as
 *  gyro_body_get_transform gives it; normalised here). Errors (*out untouched):
 *  NULL_ARGUMENT, NON_FINITE, INVALID_ARGUMENT (a zero quaternion). */
GYRO_API gyro_status gyro_convex_pose_from_quat(gyro_vec3 position, gyro_quat orientation, gyro_convex_pose* out);

/** How a query ended (gyro::ConvexStatus). GYRO_CONVEX_ITERATION_LIMIT is never a verdict of
 *  separation: the fields hold the best estimate, and the caller decides. */
typedef uint32_t gyro_convex_status;
enum {
  GYRO_CONVEX_SEPARATED = 0,       /**< the gap is larger than the touching tolerance */
  GYRO_CONVEX_TOUCHING = 1,        /**< |signed distance| <= about 1e-6 of the pair's size (overlapping) */
  GYRO_CONVEX_INTERSECTING = 2,    /**< overlapping by more than the tolerance */
  GYRO_CONVEX_ITERATION_LIMIT = 3, /**< no convergence in 64 GJK (and 64 EPA) iterations */
  /** This pair could not be answered: a NaN or infinite value, a negative size, an unknown
   *  type, a non-zero reserved, a NULL hull for GYRO_CONVEX_HULL or a hull for another
   *  type, or a pose rotation whose rows are not orthonormal and right-handed (to 1e-3).
   *  Every other field is 0. */
  GYRO_CONVEX_INVALID_INPUT = 4
};

/** One pair's answer, in world coordinates. */
typedef struct gyro_convex_result {
  gyro_convex_status status;
  /** Signed distance: > 0 the gap, <= 0 minus the penetration depth. The intersect and
   *  distance calls give 0 for intersecting pairs; the penetration call gives -depth. */
  float distance;
  gyro_vec3 normal;  /**< unit, from A towards B; 0 where undefined (coincident cores) */
  gyro_vec3 point_a; /**< witness on A: the closest point, or A's deepest point inside B */
  gyro_vec3 point_b; /**< witness on B: point_b - point_a = distance * normal */
  uint32_t iterations; /**< GJK plus EPA iterations */
} gyro_convex_result;

/** out[i] = the query on the pair (a[i] at pa[i], b[i] at pb[i]) for i < count. A pair that
 *  cannot be answered gets GYRO_CONVEX_INVALID_INPUT (and gyro_last_error() names the first
 *  such pair) without failing the call: the other pairs are answered. The pairs run on
 *  gyro_get_thread_count() threads in fixed chunks: the same bits for any thread count.
 *  Errors (nothing written): NULL_ARGUMENT (an array NULL with count > 0; all may be NULL
 *  when count is 0), INVALID_COUNT (count < 0).
 *  gyro_convex_intersect_pairs: the boolean verdict by GJK, which stops at the first
 *  separating axis or enclosing simplex (distance, normal and witnesses are those at the
 *  exit, exact only when it converged). */
GYRO_API gyro_status gyro_convex_intersect_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                 const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                 int32_t count, gyro_convex_result* out);
/** Distance and closest points by GJK; intersecting pairs report distance 0 (no EPA). */
GYRO_API gyro_status gyro_convex_distance_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                int32_t count, gyro_convex_result* out);
/** The distance of separated pairs; the penetration depth (distance = -depth), normal and
 *  contact points by EPA for overlapping ones. */
GYRO_API gyro_status gyro_convex_penetration_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                   const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                   int32_t count, gyro_convex_result* out);
/** Contact generation's query (ABI 1.6): overlapping pairs get gyro_convex_penetration_pairs'
 *  answer bit for bit; separated pairs stop at the first separating axis, as in
 *  gyro_convex_intersect_pairs (GYRO_CONVEX_SEPARATED; distance, normal and witnesses are
 *  those at the exit, the distance an upper bound of the gap). Faster where most pairs are
 *  apart: a broadphase's candidate pairs.
 *  All four pair calls run box-box pairs over SIMD lanes (16 pairs at once with AVX-512), with
 *  the same bits as the other pairs' one-by-one path (ABI 1.6). */
GYRO_API gyro_status gyro_convex_contact_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                               const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                               int32_t count, gyro_convex_result* out);

/* ------------------------------------------------------------------ snapshot and restore (ABI 1.5)
 *
 * A snapshot is the world's whole state as bytes: settings, bodies (hulls and meshes
 * included, so a snapshot is self-contained), the id allocators, the persistent contacts
 * with their warm-start impulses, sleeping islands, particles and soft bodies. A world
 * restored from it steps on bit-identically to the world it was taken from (same hash after
 * every step). The format is versioned and checksummed, little-endian, and the same on every
 * platform. Rollback networking: snapshot every frame, restore and re-simulate on a late input. */

/** Bytes gyro_world_snapshot needs for the world as it is now. */
GYRO_API gyro_status gyro_world_snapshot_size(const gyro_world* world, uint64_t* out);
/** Writes the snapshot into buffer (capacity bytes) and its size to *out_size. Errors (nothing
 *  written): NULL_ARGUMENT, INVALID_COUNT (capacity below gyro_world_snapshot_size). */
GYRO_API gyro_status gyro_world_snapshot(const gyro_world* world, void* buffer, uint64_t capacity,
                                         uint64_t* out_size);
/** Replaces the world's whole state with the snapshot's (its settings included). Mesh bodies
 *  reuse a mesh the world already holds when the geometry is identical, else the world keeps
 *  its own copy. Errors (the world unchanged): NULL_ARGUMENT, CORRUPT_DATA (truncated, bad
 *  checksum, another format version, inconsistent contents), OUT_OF_MEMORY. */
GYRO_API gyro_status gyro_world_restore(gyro_world* world, const void* buffer, uint64_t size);
/** A new world holding the snapshot's state. Errors (*out untouched): as gyro_world_restore. */
GYRO_API gyro_status gyro_world_create_from_snapshot(const void* buffer, uint64_t size, gyro_world** out);

/* ------------------------------------------------------------------ record and replay (ABI 1.5) */
/* A recording holds the world's snapshot when recording began, then every mutating call made
 * on that world through this ABI in order (bodies, forces, impulses, velocities, transforms,
 * sleep, soft bodies, steps; meshes and hulls a call names are stored with it), and the world
 * hash after every step. Replaying rebuilds the world from the snapshot, makes the calls again
 * and compares the hash after every step: the first step that differs is reported. Golden
 * recordings in the tests catch any change that alters results. */

/** Starts recording the world's calls (a snapshot of the world now is the recording's start).
 *  Errors: NULL_ARGUMENT, INVALID_ARGUMENT (already recording), OUT_OF_MEMORY. */
GYRO_API gyro_status gyro_world_record_begin(gyro_world* world);
/** The recording so far: its size in bytes. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (not
 *  recording), OUT_OF_MEMORY (a call could not be recorded for lack of memory: the recording
 *  is incomplete and stays so until gyro_world_record_end). */
GYRO_API gyro_status gyro_world_record_size(const gyro_world* world, uint64_t* out);
/** Copies the recording so far (a valid recording on its own: it is sealed with its end record
 *  and checksum). Errors: as gyro_world_record_size, INVALID_COUNT (capacity below the size;
 *  nothing written). */
GYRO_API gyro_status gyro_world_record_copy(const gyro_world* world, void* buffer, uint64_t capacity,
                                            uint64_t* out_size);
/** Writes the recording so far to a file. Errors: as above, INVALID_ARGUMENT (cannot write). */
GYRO_API gyro_status gyro_world_record_save(const gyro_world* world, const char* path);
/** Stops recording and frees the recording. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (not recording). */
GYRO_API gyro_status gyro_world_record_end(gyro_world* world);

/** What a replay found. */
typedef struct gyro_replay_report {
  uint32_t struct_size;          /**< sizeof(gyro_replay_report) */
  uint32_t diverged;             /**< 1 if a step's hash differed from the recorded one */
  int64_t steps;                 /**< steps replayed */
  int64_t calls;                 /**< calls replayed (steps included) */
  int64_t first_divergent_step;  /**< 0-based; -1 if none */
  uint64_t expected_hash;        /**< the recorded and the replayed hash at that step (0 if none) */
  uint64_t actual_hash;
  uint64_t final_hash;           /**< the replayed world's hash at the end */
} gyro_replay_report;

/** Replays a recording held in memory; out->struct_size must be set. A divergence is a result
 *  (GYRO_OK, diverged = 1), not an error: a step whose hash differs (first_divergent_step is
 *  that step, with both hashes), or a call that fails on replay or returns another id than it
 *  did when recorded (first_divergent_step is the next step, both hashes 0). Replay goes on to
 *  the end, so the counts and final_hash cover the whole recording. Errors (*out untouched):
 *  NULL_ARGUMENT, INVALID_ARGUMENT (struct_size), CORRUPT_DATA (truncated, bad checksum,
 *  unknown call, bad geometry, another format version, a start snapshot that does not load). */
GYRO_API gyro_status gyro_replay(const void* data, uint64_t size, gyro_replay_report* out);
/** Replays a recording file (see gyro_world_record_save). Errors: as gyro_replay,
 *  INVALID_ARGUMENT (the file cannot be read, or is over 1 GiB). */
GYRO_API gyro_status gyro_replay_file(const char* path, gyro_replay_report* out);

#ifdef __cplusplus
}
#endif

#endif /* GYRO_H */
