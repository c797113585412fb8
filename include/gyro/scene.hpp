// Models and scenes (Cookbook chapter 12): shapes placed in the world by a transform and an
// optional parent, kept under a top-level acceleration structure (a BVH or the Cookbook's
// octree) for raycasts, overlap queries, frustum queries and picking.
//
// Conventions:
//  - A model is a sphere (centred on its origin), a box (centred on its origin, along its
//    axes), a plane (given in its own frame) or a triangle mesh (a shared TriangleMesh, so
//    many models can instance one mesh), placed by a ModelTransform: a position, a unit
//    rotation and a uniform scale > 0. Local points map to the parent's frame (the world's
//    for a root) as p' = (p * to_mat3(rotation)) * scale + position; a model's world
//    transform is compose(local, parent's world). The rotation is normalised on input.
//  - Models are named by ModelIds {index, generation}; all-zero is null. A removed model's
//    id is stale: every call with it returns Status::stale_id and changes nothing.
//  - Planes are infinite: they are kept out of the tree, in a list every ray tests.
//  - Raycasts: the closest hit is the smallest t in [tmin, tmax] over every model's own
//    raycast (gyro/raycast.hpp on the world sphere, OBB or plane; for a mesh, gyro's mesh
//    raycast on the ray moved into the model's frame by to_local(), whose direction is NOT
//    normalised, so t is the same parameter of the same world ray). Ties in t go to the
//    model with the lowest id index, so the answer never depends on the structure or the
//    order of traversal: both acceleration modes give the brute-force answer bit for bit,
//    at every SIMD level and thread count. A ray's t is in units of |direction|.
//  - Queries (sphere, AABB, OBB) test each model's shape with gyro's overlap tests (for a
//    mesh, the query shape moved into its frame). The frustum query tests bounding
//    volumes, as culling does: a sphere model's sphere, a box model's box, a mesh model's
//    oriented bounds; a plane model is kept unless the frustum's corners lie strictly on
//    one side of it. Results are ids in ascending order (index, then generation).
//  - Changes (add, remove, set_transform, set_parent, configure) mark the world
//    transforms and the tree dirty; the next query (or prepare()) recomputes them, from
//    the set of models alone (models taken in id order), so equal scenes give equal trees
//    (with SceneSettings::refit, moves, and adds and removes without parents, refit the
//    tree and redo only what changed).
//    const queries may run concurrently; the first one after a change rebuilds under a
//    lock. Changes must not run alongside queries.
//  - Layers: each model is in the layers of ModelDef::layers (32 bits, all by default);
//    every raycast, query and pick takes a mask (all layers by default) and considers only
//    the models sharing a bit with it, as if the others were not in the scene: the answers
//    are the brute force over those models. set_layers() changes a model's layers without
//    a rebuild or a refit.
//  - A model whose world transform or bounds overflow float (a chain of huge scales) is
//    kept but never hit or found by a query.
//  - Bad input changes nothing and returns a Status with a detail in last_error(): NaN or
//    infinite values (non_finite), a zero rotation, a scale <= 0, a negative radius or half
//    extent, a plane normal that is not unit length within 1e-3, a mesh that was not
//    created, an unknown shape, a parent cycle (invalid_argument), null pointers
//    (null_argument), stale ids (stale_id), bad counts (invalid_count).
#pragma once

#include "gyro/batch_raycast.hpp"
#include "gyro/camera.hpp"
#include "gyro/frustum.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/octree.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gyro {

/// A stable model name; all-zero is null. Ordered by index, then generation.
struct ModelId {
  uint32_t index = 0;       ///< slot in the scene's id table (reused after a removal)
  uint32_t generation = 0;  ///< tells a live id from a stale one with the same index (>= 1 when live)
  /// True for the all-zero id.
  bool is_null() const { return index == 0 && generation == 0; }
  /// Same index and generation.
  friend bool operator==(ModelId a, ModelId b) { return a.index == b.index && a.generation == b.generation; }
  /// By index, then generation.
  friend bool operator<(ModelId a, ModelId b) {
    return a.index < b.index || (a.index == b.index && a.generation < b.generation);
  }
};

/// What a model is.
enum class ModelShape : uint32_t {
  sphere = 0,  ///< ModelDef::radius, centred on the model's origin
  box = 1,     ///< ModelDef::half_extents, centred on the origin, along the model's axes
  mesh = 2,    ///< ModelDef::mesh, in the model's frame
  plane = 3,   ///< ModelDef::plane, in the model's frame (infinite: kept outside the tree)
};

/// A similarity transform: scale, then rotate, then translate (row vectors:
/// p' = (p * to_mat3(rotation)) * scale + position).
struct ModelTransform {
  vec3 position;       ///< where the model's origin goes
  quat rotation;       ///< unit (a scene normalises what it is given)
  float scale = 1.0f;  ///< uniform, > 0
};

/// The world transform of a child: local applied first, then the parent's world transform.
/// position = transform_point(parent, local.position), rotation = normalized(parent.rotation
/// * local.rotation), scale = parent.scale * local.scale.
ModelTransform compose(const ModelTransform& local, const ModelTransform& parent);
/// A point of the model's frame in the parent's (or world) frame.
vec3 transform_point(const ModelTransform& t, const vec3& p);
/// The ray in the model's frame: origin ((o - position) * R^T) / scale, direction
/// (d * R^T) / scale with R = to_mat3(rotation). Not normalised: a point at parameter t
/// of the local ray maps to the point at t of the world ray.
Ray to_local(const ModelTransform& t, const Ray& ray);
/// The sphere in the model's frame (centre moved, radius / scale).
Sphere to_local(const ModelTransform& t, const Sphere& sphere);
/// The box in the model's frame (centre moved, axes turned, half extents / scale).
OBB to_local(const ModelTransform& t, const OBB& box);
/// The axis-aligned box in the model's frame, as an oriented box.
OBB to_local(const ModelTransform& t, const AABB& box);

/// How to make a model.
struct ModelDef {
  ModelShape shape = ModelShape::sphere;      ///< which of the fields below describe the shape
  float radius = 1.0f;                        ///< sphere: >= 0
  vec3 half_extents{1.0f, 1.0f, 1.0f};        ///< box: >= 0
  Plane plane;                                ///< plane: unit normal
  std::shared_ptr<const TriangleMesh> mesh;   ///< mesh: created (not empty); shared, never copied
  ModelTransform transform;                   ///< relative to the parent (the world for a root)
  ModelId parent;                             ///< null: a root
  /// The layers the model is in (as Box2D's category bits, Embree's geometry mask): a ray
  /// (RaysView::mask), a query or a pick whose mask shares no bit with them does not see
  /// the model. 0 hides it from all of them. Any value is valid.
  uint32_t layers = kAllLayers;
};

/// A model as the scene holds it, with its world placement.
struct ModelInfo {
  ModelDef def;            ///< as given (rotation normalised), with its current transform and parent
  ModelTransform world;    ///< compose(def.transform, parent's world)
  /// World shape: sphere models' sphere; box models' box; mesh models' bounds (the mesh's
  /// AABB in its frame, placed); planes leave them zero.
  Sphere sphere;
  OBB box;
  Plane plane;             ///< plane models' world plane
  /// Conservative world AABB (padded by about 2^-16 of its magnitude); planes: infinite.
  AABB bounds;
  bool placed = false;     ///< false when the world transform or bounds overflowed
};

/// Which top-level structure a scene builds over its models.
enum class SceneAccel : uint32_t {
  /// Binned-SAH 8-wide BVH over the models' bounds. The default: on 1000 to 4000 models it
  /// builds 1.5 to 2.4 times and answers closest-hit rays 1.8 to 6 times, any-hit rays 1.5
  /// to 3 times and frustum queries 1.7 to 5 times faster than the octree (SceneBench in
  /// tests/spatial/scene_test.cpp); on R1's 10^4 spheres, rays 1.7 times (gyro-bench).
  bvh = 0,
  /// The Cookbook's octree (gyro/octree.hpp) over the models' bounds: a model sits in every
  /// leaf it overlaps, so large or clustered models are stored many times. Rays walk it in
  /// the BVH's node form, through the same kernel, so the two modes differ only in the
  /// tree's shape; the queries walk the octree itself.
  octree = 1,
};

/// Whether ray batches through a scene's tree (closest and any hit) prefetch each next
/// visit's cache lines. It changes speed only, never a result. Prefetching pays once the tree outgrows the
/// caches and costs instructions before: on the machine the defaults were measured on (1 MiB
/// L2 per core, 32 MiB L3), without it up to about 8 MiB of tree (10^5 spheres), with it
/// beyond. Set it where your machine's caches differ.
enum class RayPrefetch : uint32_t {
  automatic = 0,  ///< when the tree (nodes and leaves) exceeds 8 MiB
  always = 1,
  never = 2,
};

/// Scene parameters.
struct SceneSettings {
  SceneAccel accel = SceneAccel::bvh;  ///< the structure queries walk
  OctreeDef octree;                    ///< used when accel == octree
  RayPrefetch ray_prefetch = RayPrefetch::automatic;  ///< for rays in either mode
  /// Under the BVH, when only transforms changed since the last build (set_transform, no
  /// set_parent or configure), the next query refits the tree (new boxes over the same
  /// topology) instead of rebuilding it, unless the refit tree's expected ray cost exceeds
  /// kSceneRefitCost times the last build's. In a scene where no model has a parent, adds
  /// and removes keep the tree too: a removed model's leaf is taken out, a new model's put
  /// where its box grows the tree least (a new node beside a leaf where the nodes on the way
  /// are full), and a model whose placement overflows leaves the tree and comes back the same
  /// way; then the refit. One sphere removed and one added a frame in R1's 10^4 spheres takes
  /// 0.019 ms against 7.0 ms for the rebuild it replaced (100 of each: 0.18 ms against 36;
  /// after 2 * 10^4 of them rays run 0.92x as fast as on a fresh tree; a /tmp driver, one
  /// thread). The tree rebuilds when half its items have been taken out since the build.
  /// A refit, like the world transforms before it, redoes only what the moves since the
  /// last query touched: the moved models and their descendants, the leaves holding them and
  /// the nodes above those. On R1's 10^4 spheres (one thread, gyro-bench R1M), prepare()
  /// after moving all of them takes 0.40 ms, a tenth 0.12 ms, a hundredth 0.021 ms, a
  /// thousandth 0.0055 ms, against 4.0 ms for a rebuild (Embree's refit of the same
  /// spheres: 0.080-0.086 ms whatever moved). Rays on a refit tree run up to about a fifth slower than on a fresh one
  /// (set false where rays dominate a frame). Answers are the same
  /// either way, except which model an any-hit names: that follows the tree, so the
  /// sequence of calls (deterministic, like every result), not the models alone. False:
  /// every change rebuilds, and the tree is a function of the models.
  bool refit = true;
};

/// How much worse (SceneStats::sah_cost) a refit tree may get than the last full build's
/// before a transform change rebuilds it instead.
inline constexpr double kSceneRefitCost = 1.25;

/// The shape of a scene's current structure.
struct SceneStats {
  SceneAccel accel = SceneAccel::bvh;  ///< the structure built
  std::size_t models = 0;              ///< live models
  std::size_t tree_models = 0;  ///< models in the tree (not planes, not unplaced)
  std::size_t planes = 0;       ///< placed plane models (tested by every ray)
  std::size_t nodes = 0;        ///< 8-wide BVH nodes, or octree nodes (leaves included)
  std::size_t leaves = 0;       ///< BVH leaf blocks, or octree leaves
  std::size_t references = 0;   ///< model entries over all leaves (octree: >= tree_models)
  std::size_t max_depth = 0;    ///< of the structure (BVH: in 8-wide nodes, root = 1; octree: root = 0)
  std::size_t bytes = 0;        ///< structure and per-model arrays
  double sah_cost = 0.0;        ///< BVH: expected node and leaf tests of a random ray (0 under the octree)
  std::size_t builds = 0;       ///< full builds of the structure since the scene was made
  std::size_t refits = 0;       ///< refits (SceneSettings::refit) since the scene was made
};

/// A set of models with a top-level acceleration structure.
class Scene {
 public:
  /// An empty scene with the default settings.
  Scene();
  /// A scene with these settings (invalid ones fall back to the defaults: check them with
  /// configure() when they come from outside).
  explicit Scene(const SceneSettings& settings);
  ~Scene();
  /// Moves the models and structure; the moved-from scene may only be destroyed or assigned to.
  Scene(Scene&&) noexcept;
  /// Moves the models and structure; the moved-from scene may only be destroyed or assigned to.
  Scene& operator=(Scene&&) noexcept;

  /// Replaces the settings (a bad OctreeDef or an unknown accel is invalid_argument).
  Status configure(const SceneSettings& settings);
  /// The current settings.
  const SceneSettings& settings() const;

  /// Adds a model; *out gets its id.
  Status add_model(const ModelDef& def, ModelId* out);
  /// Removes a model. Its children stay where they are: each becomes a root whose local
  /// transform is its former world transform.
  Status remove_model(ModelId id);
  /// Sets the model's local transform (relative to its parent).
  Status set_transform(ModelId id, const ModelTransform& local);
  /// Attaches the model to a parent (null: detaches it). The local transform is kept, so the
  /// model moves with its new parent. A parent that is the model or one of its descendants
  /// is invalid_argument.
  Status set_parent(ModelId id, ModelId parent);
  /// Sets the model's ModelDef::layers. Not a structural change: the next query rewrites
  /// the masks the tree's leaves hold, and neither rebuilds nor refits the tree.
  Status set_layers(ModelId id, uint32_t layers);

  /// True for a live id.
  bool contains(ModelId id) const;
  /// Number of live models (planes included).
  std::size_t model_count() const;
  /// Every live id, ascending.
  std::vector<ModelId> model_ids() const;
  /// The model's definition and world placement.
  Status model(ModelId id, ModelInfo* out) const;
  /// The model's direct children, ascending (the Cookbook's FindChildren).
  Status children(ModelId id, std::vector<ModelId>& out) const;

  /// Brings world transforms and the structure up to date now (queries do it lazily).
  void prepare() const;
  /// The structure after prepare().
  SceneStats stats() const;

  /// The internals (src/spatial/scene.cpp), for the query functions.
  struct Impl;
  /// The internals, read-only.
  const Impl* impl() const { return impl_.get(); }

 private:
  std::unique_ptr<Impl> impl_;
};

/// One ray's hit in a scene, or hit.hit == false (then model is null and the rest zero).
struct SceneHit {
  RaycastResult hit;       ///< t, world point (origin + t direction), world unit normal
  ModelId model;
  uint32_t primitive = 0;  ///< mesh models: the triangle index; 0 otherwise
  float u = 0.0f, v = 0.0f;  ///< mesh models: barycentric weights of corners b and c
};

/// Closest hit with t in [tmin, tmax] among the models whose layers share a bit with `mask`
/// (see the header comment). A ray the mesh queries call
/// invalid (a NaN or infinite coordinate, a zero direction, tmin not finite or negative,
/// tmax NaN or below tmin) hits nothing.
SceneHit raycast(const Scene& scene, const Ray& ray, float tmin = 0.0f, float tmax = __builtin_inff(),
                 uint32_t mask = kAllLayers);
/// Some hit with t in [tmin, tmax] (stops at the first found: planes first in id order,
/// then the tree's traversal order); hit.hit exactly when raycast() hits. The model
/// reported may differ between the acceleration modes, never between runs.
SceneHit raycast_any(const Scene& scene, const Ray& ray, float tmin = 0.0f, float tmax = __builtin_inff(),
                     uint32_t mask = kAllLayers);

/// Per-ray results of the batch raycasts: t and model are required, the rest optional
/// (null to skip; the normal all three or none, u and v both or none). A miss writes
/// t = +inf, primitive = -1, model = null and zeros; an invalid ray (see raycast()) the same
/// but primitive = kRayInvalid (gyro/triangle_mesh.hpp). What is skipped is not computed:
/// without normals a sphere or box hit costs its t alone.
struct SceneHitsOut {
  float* t = nullptr;            ///< hit t (units of |direction|), +inf on a miss
  ModelId* model = nullptr;      ///< the model hit, null on a miss
  int32_t* primitive = nullptr;  ///< triangle index for mesh models, 0 for other shapes, -1 on a miss, kRayInvalid
  float* nx = nullptr;           ///< world unit normal (outward for solids, facing the ray for planes and meshes)
  float* ny = nullptr;
  float* nz = nullptr;
  float* u = nullptr;            ///< mesh models: barycentric weight of corner b; 0 otherwise
  float* v = nullptr;            ///< mesh models: barycentric weight of corner c; 0 otherwise
};

/// Batch closest hit: raycast() for every ray. Like the mesh batch calls, an invalid ray is
/// flagged (kRayInvalid) and the others answered; null arrays, inconsistent optional
/// outputs and counts of 2^31 or more fail the call with nothing written. Parallel over
/// fixed chunks; bit-identical at every SIMD level and thread count.
Status raycast_closest(const Scene& scene, const RaysView& rays, std::size_t ray_count, const SceneHitsOut& hits);
/// Batch any hit: raycast_any() for every ray; as raycast_closest.
Status raycast_any(const Scene& scene, const RaysView& rays, std::size_t ray_count, const SceneHitsOut& hits);

/// Models whose shape overlaps the sphere, ascending; only those whose layers share a bit
/// with `mask` (ModelDef::layers), as for every query below.
Status query(const Scene& scene, const Sphere& sphere, std::vector<ModelId>& out, uint32_t mask = kAllLayers);
/// Models whose shape overlaps the box, ascending.
Status query(const Scene& scene, const AABB& box, std::vector<ModelId>& out, uint32_t mask = kAllLayers);
/// Models whose shape overlaps the oriented box, ascending.
Status query(const Scene& scene, const OBB& box, std::vector<ModelId>& out, uint32_t mask = kAllLayers);
/// Models whose bounding volume intersects the frustum (see the header comment), ascending.
Status query(const Scene& scene, const Frustum& frustum, std::vector<ModelId>& out, uint32_t mask = kAllLayers);

/// The closest model under a screen point: raycast(scene, picking_ray(camera, screen_point,
/// viewport_size)). A bad camera (check_camera) or a non-finite point or a viewport with a
/// size <= 0 returns its status and leaves *out a miss.
Status pick(const Scene& scene, const Camera& camera, vec2 screen_point, vec2 viewport_size, SceneHit* out,
            uint32_t mask = kAllLayers);

}  // namespace gyro
