// Scenes (gyro/scene.hpp): models in dense slots under an IdPool, world transforms and the
// top-level structure (a BVH over boxes from spatial/bvh.hpp, or gyro::Octree) recomputed
// lazily (the BVH refit when only transforms changed: SceneSettings::refit), and the
// queries over them.
//
// Exactness of the traversal. Every model's tree box is its world shape's AABB padded by
// 2^-16 of its magnitude (|centre| + half extent), and a ray widens every box it tests by
// 2^-17 of its origin's magnitude (the BVH kernels move the origin by that pad instead, once
// per ray: the origin's rounding, an ulp of it, is far inside the pads); together they
// exceed the 16 ulps of M (|origin - centre| + size) by which gyro's raycasts may stray from
// the exact surface (gyro/raycast.hpp), and the rounding of a mesh ray's move into its
// frame. So a model hit at t has the exact point at t inside every box above it, and the
// slab test (Ize's robust traversal: entry may exceed exit by 2^-18 of the exit; a slab
// product that is NaN, 0 * inf, is ignored) enters them all. A subtree is skipped only
// when it is entered beyond the best t by 2^-16 of it, far more than the few ulps by which
// a box's computed entry can follow the exact one. Ties go to the lowest id index, so
// neither the structure nor the visiting order can change the answer: both modes give the
// brute-force loop's bits. Overlap queries prune with boxes padded the same way around the
// query shape (far more than the 1e-6 relative slack of gyro's box tests), then run the
// exact test on each candidate.
#include "gyro/scene.hpp"

#include "core/error.hpp"
#include "core/float_env.hpp"
#include "core/id_pool.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/raycast_at.hpp"
#include "geometry/shape_checks.hpp"
#include "gyro/overlap.hpp"
#include "gyro/raycast.hpp"
#include "spatial/bvh.hpp"
#include "spatial/bvh_refit.hpp"
#include "spatial/octree_bvh.hpp"
#include "spatial/scene_rays.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <mutex>

namespace gyro {
namespace {

using detail::fail;

constexpr float kInf = __builtin_inff();
constexpr std::size_t kMaxCount = 0x7FFFFFFF;
constexpr std::size_t kRayChunk = 64;
constexpr float kBoxPad = 0x1p-16f;
constexpr float kRayPad = 0x1p-17f;
constexpr float kSlabSlack = 0x1p-18f;
constexpr float kSlabScale = 1.0f + kSlabSlack;  // the lanes' rule (scene_kernels.cpp)
constexpr float kTinyPad = 1e-30f;
constexpr std::size_t kFetchBytes = std::size_t(8) << 20;  // RayPrefetch::automatic (gyro/scene.hpp)
constexpr uint32_t kNoIndex = 0xFFFFFFFFu;
// Slots per parallel chunk when every model is placed again (about 160 instructions a
// sphere: 10^4 spheres make five chunks).
constexpr std::size_t kPlaceChunk = 2048;
// Entries on a traversal stack: a node pushes at most 7 siblings per level.
constexpr std::size_t kStackSize = 8 * (detail::kBvhMaxDepth + 2);

float max_abs3(const vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// v * R^T: the coordinates of v along R's rows.
vec3 along_rows(const vec3& v, const mat3& r) {
  return {dot(v, vec3{r.m[0][0], r.m[0][1], r.m[0][2]}), dot(v, vec3{r.m[1][0], r.m[1][1], r.m[1][2]}),
          dot(v, vec3{r.m[2][0], r.m[2][1], r.m[2][2]})};
}

// Half extents of the world AABB of a box with these rows and half extents.

// [c - h, c + h] padded by kBoxPad of its magnitude (see the header comment).
AABB padded_bounds(const vec3& c, const vec3& h) {
  const float pad = kBoxPad * (max_abs3(c) + max_abs3(h)) + kTinyPad;
  const vec3 p{pad, pad, pad};
  return aabb_from_min_max(c - h - p, c + h + p);
}

Status check_transform(const ModelTransform& t, const char* what) {
  if (!gyro::is_finite(t.position)) return fail(Status::non_finite, "%s.position is not finite", what);
  const quat& q = t.rotation;
  if (!detail::is_finite(q.x) || !detail::is_finite(q.y) || !detail::is_finite(q.z) || !detail::is_finite(q.w))
    return fail(Status::non_finite, "%s.rotation is not finite", what);
  if (q.x == 0.0f && q.y == 0.0f && q.z == 0.0f && q.w == 0.0f)
    return fail(Status::invalid_argument, "%s.rotation is the zero quaternion", what);
  if (!detail::is_finite(t.scale)) return fail(Status::non_finite, "%s.scale is not finite", what);
  if (!(t.scale > 0.0f)) return fail(Status::invalid_argument, "%s.scale = %g must be > 0", what, double(t.scale));
  return Status::ok;
}

ModelTransform normalized_transform(const ModelTransform& t) { return {t.position, normalized(t.rotation), t.scale}; }

Status check_shape(const ModelDef& d) {
  switch (d.shape) {
    case ModelShape::sphere:
      if (!detail::is_finite(d.radius)) return fail(Status::non_finite, "ModelDef.radius is not finite");
      if (!(d.radius >= 0.0f)) return fail(Status::invalid_argument, "ModelDef.radius = %g is negative", double(d.radius));
      return Status::ok;
    case ModelShape::box:
      if (!gyro::is_finite(d.half_extents)) return fail(Status::non_finite, "ModelDef.half_extents is not finite");
      if (!(d.half_extents.x >= 0.0f && d.half_extents.y >= 0.0f && d.half_extents.z >= 0.0f))
        return fail(Status::invalid_argument, "ModelDef.half_extents has a negative component");
      return Status::ok;
    case ModelShape::plane: {
      if (!gyro::is_finite(d.plane.normal) || !detail::is_finite(d.plane.distance))
        return fail(Status::non_finite, "ModelDef.plane is not finite");
      const float n2 = dot(d.plane.normal, d.plane.normal);
      if (!(std::abs(n2 - 1.0f) <= 2e-3f))
        return fail(Status::invalid_argument, "ModelDef.plane.normal has length^2 %g, not 1", double(n2));
      return Status::ok;
    }
    case ModelShape::mesh:
      if (!d.mesh) return fail(Status::null_argument, "ModelDef.mesh is null");
      if (d.mesh->empty()) return fail(Status::invalid_argument, "ModelDef.mesh was not created (TriangleMesh::create)");
      return Status::ok;
  }
  return fail(Status::invalid_argument, "ModelDef.shape = %u is not a model shape", unsigned(d.shape));
}

// A model's world placement: what every query reads (dense, by slot). One OBB holds the
// world shape of every kind (a sphere's centre and radius, a plane's normal and distance,
// in its first fields), and the tree's corners are computed from the bounds (Corners), so a
// model costs 136 bytes here, not the 232 of a field per kind, a rotation matrix (which
// equals a box's orientation) and the corners stored beside the bounds.
struct Placed {
  ModelShape shape = ModelShape::sphere;
  uint32_t index = 0;  // the id's index: the tie-break of every query
  bool placed = false;
  // What a refit reads of every moved model, the shape, the bounds and a sphere's centre and
  // radius, in the first 60 bytes (two cache lines at most instead of three: the refit
  // gathers them in the tree's order, not the slots').
  AABB bounds;
  OBB box;  // a box's box, a mesh's oriented bounds (orientation: the world rotation)
  ModelTransform world;
  const TriangleMesh* mesh = nullptr;

  Sphere sphere() const { return {box.center, box.half_extents.x}; }
  Plane plane() const { return {box.center, box.half_extents.x}; }
  void set_sphere(const Sphere& s) { box.center = s.center, box.half_extents.x = s.radius; }
  void set_plane(const Plane& p) { box.center = p.normal, box.half_extents.x = p.distance; }
};
static_assert(sizeof(Placed) <= 136, "the per-model placement grew");

// A model's box in the tree: aabb_min(bounds) and aabb_max(bounds), computed where needed
// (the same expressions every time, so the same bits as when they were stored).
struct Corners {
  float lo[3], hi[3];
  explicit Corners(const Placed& p) {
    const vec3 l = aabb_min(p.bounds), h = aabb_max(p.bounds);
    lo[0] = l.x, lo[1] = l.y, lo[2] = l.z, hi[0] = h.x, hi[1] = h.y, hi[2] = h.z;
  }
};

// Four floats in the base level's vector registers (SSE2, NEON or the compiler's lowering):
// IEEE operations lane by lane, the bits of the same scalar expressions.
using F4 = float __attribute__((vector_size(16)));
using U4 = uint32_t __attribute__((vector_size(16)));

// Which lanes are not finite (all ones), by the bits; and whether none is.
inline U4 not_finite4(F4 v) {
  const U4 e = U4{} + 0x7f800000u;
  return U4((std::bit_cast<U4>(v) & e) == e);
}
inline bool none4(U4 v) {
  uint64_t half[2];
  std::memcpy(half, &v, sizeof half);
  return (half[0] | half[1]) == 0;
}

// x, y, z to the first three lanes and back (the fourth lane 0 in, not stored out).
inline F4 lanes(const vec3& v) {
  F4 r{};
  std::memcpy(&r, &v, sizeof v);
  return r;
}
inline void store3(vec3& v, F4 r) { std::memcpy(static_cast<void*>(&v), &r, sizeof v); }


// A sphere's placement (place() below). A sphere (most of a moving scene's models, often)
// writes only its own fields, in place: the others hold what Placed{} gave them, since a
// slot keeps its shape until compute_world() starts every slot afresh (a remove, which may
// move another model into the slot, places everything). Building a whole Placed and copying
// it was most of an all-moved frame's placing (R1M: 201 instructions a sphere).
[[gnu::always_inline]] inline void place_sphere(Placed& p, const ModelDef& d, const ModelTransform& w, uint32_t index) {
  if (p.shape != ModelShape::sphere) p = Placed{};
  p.index = index;
  p.world = w;
  p.mesh = d.mesh.get();
  const float r = d.radius * w.scale;
  p.set_sphere({w.position, r});
  // padded_bounds(position, {r, r, r}) written out: its max_abs3 of three equal values is
  // |r|, and max_abs3 is std::max's rule (the first of the largest), here without a list.
  const vec3& c = w.position;
  float m = std::abs(c.x);
  if (m < std::abs(c.y)) m = std::abs(c.y);
  if (m < std::abs(c.z)) m = std::abs(c.z);
  const float pad = kBoxPad * (m + std::abs(r)) + kTinyPad;
  // The bounds and Corners' values of them in lanes x, y, z (and a fourth, from a zero
  // centre, never stored): the scalar expressions lane by lane, so the same bits, in fewer
  // instructions (R1M, every sphere moved: place() 134 -> 100 a sphere).
  const F4 c4 = lanes(c), r4 = F4{} + r, pad4 = F4{} + pad;
  const F4 lo = c4 - r4 - pad4, hi = c4 + r4 + pad4;
  const F4 centre = (lo + hi) * 0.5f, half = (hi - lo) * 0.5f;
  store3(p.bounds.center, centre);
  store3(p.bounds.half_extents, half);
  // The other shapes' test, of fewer values: finite corners imply a finite centre and
  // half extent of the bounds (else one corner is inf or NaN), so a finite position, r and
  // pad, and with the radius finite (check_shape) a finite scale. The fourth lane is not
  // finite only when r or pad is not, and then neither is any other.
  const quat& q = w.rotation;
  const F4 q4 = {q.x, q.y, q.z, q.w};
  p.placed = none4(not_finite4(centre - half) | not_finite4(centre + half) | not_finite4(q4));
}

// The other shapes (place()'s).
[[gnu::noinline]] void place_other(Placed& p, const ModelDef& d, const ModelTransform& w, uint32_t index) {
  p = Placed{};
  p.shape = d.shape;
  p.index = index;
  p.world = w;
  // Only the shapes that turn need the matrix.
  const auto rot = [&w] { return to_mat3(w.rotation); };
  p.mesh = d.mesh.get();
  vec3 centre = w.position, half{0.0f, 0.0f, 0.0f};
  switch (d.shape) {
    case ModelShape::sphere:
      break;
    case ModelShape::box:
      p.box = {w.position, d.half_extents * w.scale, rot()};
      half = aabb_half_extents(p.box.orientation, p.box.half_extents);
      break;
    case ModelShape::mesh: {
      const AABB local = d.mesh->bounds();
      p.box = {transform_point(w, local.center), local.half_extents * w.scale, rot()};
      centre = p.box.center;
      half = aabb_half_extents(p.box.orientation, p.box.half_extents);
      break;
    }
    case ModelShape::plane: {
      const vec3 n = d.plane.normal * rot();
      const Plane plane{n, d.plane.distance * w.scale + dot(n, w.position)};
      p.set_plane(plane);
      p.bounds = {{0.0f, 0.0f, 0.0f}, {kInf, kInf, kInf}};
      p.placed = gyro::is_finite(plane.normal) && detail::is_finite(plane.distance) && gyro::is_finite(w.position);
      return;
    }
  }
  p.bounds = padded_bounds(centre, half);
  const float q[4] = {w.rotation.x, w.rotation.y, w.rotation.z, w.rotation.w};
  bool ok = gyro::is_finite(w.position) && detail::is_finite(w.scale) && gyro::is_finite(half) && gyro::is_finite(aabb_min(p.bounds)) &&
            gyro::is_finite(aabb_max(p.bounds)) && gyro::is_finite(p.bounds.half_extents);
  for (float v : q) ok = ok && detail::is_finite(v);
  p.placed = ok;
}

// Writes p as the placement of a model with def d at world transform w: a sphere's inline in
// the loops that place every model (R1M, every sphere moved: 10 instructions a sphere fewer
// than a call), the other shapes' out of line.
inline void place(Placed& p, const ModelDef& d, const ModelTransform& w, uint32_t index) {
  if (d.shape == ModelShape::sphere) place_sphere(p, d, w, index);
  else place_other(p, d, w, index);
}

// An AABB query region [lo, hi] widened like the models' boxes.
struct Region {
  float lo[3], hi[3];
};

Region region_of(const vec3& c, const vec3& h) {
  const float pad = kBoxPad * (max_abs3(c) + max_abs3(h)) + kTinyPad;
  const vec3 lo = c - h - vec3{pad, pad, pad}, hi = c + h + vec3{pad, pad, pad};
  return {{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}};
}

bool region_touches(const Region& r, const float lo[3], const float hi[3]) {
  return lo[0] <= r.hi[0] && r.lo[0] <= hi[0] && lo[1] <= r.hi[1] && r.lo[1] <= hi[1] && lo[2] <= r.hi[2] &&
         r.lo[2] <= hi[2];
}

ModelId id_of(detail::Id id) { return {id.index, id.generation}; }
detail::Id to_detail(ModelId id) { return {id.index, id.generation}; }

}  // namespace

// ------------------------------------------------------------------------ transforms

ModelTransform compose(const ModelTransform& local, const ModelTransform& parent) {
  return {transform_point(parent, local.position), normalized(parent.rotation * local.rotation),
          parent.scale * local.scale};
}

vec3 transform_point(const ModelTransform& t, const vec3& p) { return (p * to_mat3(t.rotation)) * t.scale + t.position; }

Ray to_local(const ModelTransform& t, const Ray& ray) {
  const mat3 r = to_mat3(t.rotation);
  return {along_rows(ray.origin - t.position, r) / t.scale, along_rows(ray.direction, r) / t.scale};
}

Sphere to_local(const ModelTransform& t, const Sphere& s) {
  const mat3 r = to_mat3(t.rotation);
  return {along_rows(s.center - t.position, r) / t.scale, s.radius / t.scale};
}

OBB to_local(const ModelTransform& t, const OBB& b) {
  const mat3 r = to_mat3(t.rotation);
  mat3 axes;
  for (int k = 0; k < 3; ++k) {
    const vec3 u = along_rows(vec3{b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]}, r);
    axes.m[k][0] = u.x, axes.m[k][1] = u.y, axes.m[k][2] = u.z;
  }
  return {along_rows(b.center - t.position, r) / t.scale, b.half_extents / t.scale, axes};
}

OBB to_local(const ModelTransform& t, const AABB& b) { return to_local(t, OBB{b.center, b.half_extents, mat3::identity()}); }

// ------------------------------------------------------------------------ the scene

struct Scene::Impl {
  SceneSettings settings;
  detail::IdPool pool;
  std::vector<ModelDef> defs;    // by dense slot
  std::vector<Placed> placed;    // by dense slot, valid once world_ready
  std::vector<uint32_t> tree_slots;   // tree item k -> slot, ascending id index
  std::vector<uint32_t> plane_slots;  // placed planes, ascending id index
  detail::BoxBvh8 bvh;
  std::vector<detail::SceneLeaf> ray_leaves;  // bvh.leaves as the ray kernel reads them
  std::vector<detail::SceneBox> ray_boxes;    // their box models
  bool rays_large = false;                     // beyond kFetchBytes (RayPrefetch::automatic)
  bool layers_changed = false;                 // a model's layers set since the leaves were written
  Octree octree;
  SceneAccel built = SceneAccel::bvh;
  std::mutex mutex;
  std::atomic<bool> world_ready{true};
  std::atomic<bool> tree_ready{false};
  bool tree_stale = true;  // the tree needs build_tree() (false while only layers changed)
  bool rebuild = true;      // a change other than transforms: the next build_tree() starts afresh
  double built_sah = 0.0;   // the last full BVH build's sah_cost, which a refit may not exceed by kSceneRefitCost
  std::size_t builds = 0, refits = 0;
  // A frame pays for what moved. compute_world() places again only the models moved since it
  // last ran, with their descendants, unless world_all (after an add, a remove or a
  // reparenting: it links the models again and places every one) or moves_all (the moves
  // reached a quarter of the models: it places every one in place_order, parents first,
  // over the same slots, which allocates nothing).
  bool world_all = true;
  bool moves_all = false;
  std::vector<uint32_t> place_order;  // every slot, each after its parent (set with world_all)
  std::vector<uint8_t> chunk_flips;   // moves_all's, per chunk of kPlaceChunk slots: a model became (un)placed
  std::vector<uint32_t> moved;        // slots, each once
  std::vector<uint8_t> moved_mark;    // by slot
  std::vector<uint32_t> child_begin;  // children by slot (child_slots[child_begin[s] ..]); empty: no model has a parent
  std::vector<uint32_t> child_slots;
  std::vector<uint32_t> place_stack;  // place_from()'s, kept to spare an allocation per move
  // The models placed again since the tree was last built or refit (each once), or every
  // model (tree_all); and whether one of them became placed or unplaced (the items changed).
  std::vector<uint32_t> replaced;
  std::vector<uint8_t> replaced_mark;  // by slot
  bool tree_all = true;
  bool items_changed = false;
  // The BVH's tree item of each slot (kNoIndex: none) and its links for a partial refit.
  std::vector<uint32_t> slot_item;
  detail::BvhRefit links;
  // A refit's new boxes by leaf, and the leaves of the models other than spheres among
  // them (refit_bvh()).
  std::vector<detail::BvhBox> leaf_box;
  std::vector<uint32_t> leaf_again;
  // Set by a compute_world() that placed every model of a tree linked for a refit and staged
  // the spheres among them as it went (stage_sphere()), the placements still in cache; the
  // chunks of slots where it met another shape are flagged in chunk_other. Cleared by any
  // other placement, and by refit_bvh(), which stages what is left.
  bool spheres_staged = false;
  std::vector<uint8_t> chunk_other;
  // Adds and removes of root models in a scene without parents keep the tree (patch_tree()):
  // a removed model's item is detached at the next build_tree(), a new one attached, and the
  // tree refit. tree_slots keeps a hole (kNoIndex) for each item taken out since the build.
  std::vector<uint32_t> detached;
  std::size_t tree_holes = 0;

  // Whether an add or remove can keep the placements (and so maybe the tree): the world was
  // placed since the last structural change and no model has a parent (so removing one
  // reparents none, and the placement order is the slots').
  bool patchable() const {
    return !world_all && child_begin.empty() && placed.size() == pool.size() && place_order.size() == pool.size();
  }

  void changed() {
    world_ready.store(false, std::memory_order_relaxed);
    tree_ready.store(false, std::memory_order_relaxed);
    tree_stale = true;
  }

  uint32_t slot(ModelId id) const { return pool.slot(to_detail(id)); }

  // A move of slot s: noted for the next compute_world(), unless that places every model.
  void note_move(uint32_t s) {
    if (world_all || moves_all || moved_mark[s]) return;
    if (4 * (moved.size() + 1) > pool.size()) {
      moves_all = true;
      for (uint32_t m : moved) moved_mark[m] = 0;
      moved.clear();
      return;
    }
    moved_mark[s] = 1;
    moved.push_back(s);
  }

  void compute_world() {
    const uint32_t n = pool.size();
    if (!world_all && placed.size() == n && place_order.size() == n) {
      if (moves_all) {
        // Every model again, the tree's items kept unless one became placed or unplaced.
        moves_all = false;
        for (uint32_t s : replaced) replaced_mark[s] = 0;
        replaced.clear();
        tree_all = true;
        bool flips = false;
        if (child_begin.empty()) {
          // No model has a parent: each placement stands alone, so fixed chunks of slots on
          // any threads give the same bytes, and each chunk notes its own flips.
          // Each chunk also stages its spheres for the refit while their placements are in
          // cache (R1M, every sphere moved, one thread: a separate pass re-reading them cost
          // 0.09 of 0.55 ms a frame). Stages write leaves of their own, so the bytes are the
          // same on any threads; a refit that does not follow (the items changed, a rebuild)
          // writes every leaf afresh.
          const bool stage = refit_linked();
          if (stage) leaf_box.resize(bvh.leaves.size());
          const std::size_t chunks = (n + kPlaceChunk - 1) / kPlaceChunk;
          chunk_flips.assign(chunks, 0);
          chunk_other.assign(chunks, 0);
          detail::parallel_for(n, kPlaceChunk, [&](std::size_t b, std::size_t e) {
            uint8_t f = 0, other = 0;
            for (std::size_t c = b; c < e; ++c) {
              Placed& p = placed[c];
              const bool was = p.placed;
              place(p, defs[c], defs[c].transform, pool.id_at(uint32_t(c)).index);
              f |= uint8_t(p.placed != was);
              if (!stage) continue;
              if (p.shape == ModelShape::sphere) stage_sphere(p, uint32_t(c));
              else other = 1;
            }
            chunk_flips[b / kPlaceChunk] = f;
            chunk_other[b / kPlaceChunk] = other;
          });
          for (uint8_t f : chunk_flips) flips = flips || f != 0;
          spheres_staged = stage;
        } else {
          spheres_staged = false;
          for (uint32_t c : place_order) {
            const ModelDef& d = defs[c];
            const bool was = placed[c].placed;
            if (d.parent.is_null()) place(placed[c], d, d.transform, pool.id_at(c).index);
            else place(placed[c], d, compose(d.transform, placed[slot(d.parent)].world), pool.id_at(c).index);
            flips |= placed[c].placed != was;
          }
        }
        items_changed = items_changed || flips;
        return;
      }
      if (!moved.empty()) spheres_staged = false;
      for (uint32_t s : moved) place_from(s);
      for (uint32_t s : moved) moved_mark[s] = 0;
      moved.clear();
      return;
    }
    world_all = false;
    moves_all = false;
    spheres_staged = false;
    moved.clear();
    moved_mark.assign(n, 0);
    replaced.clear();
    replaced_mark.assign(n, 0);
    tree_all = true;
    items_changed = true;
    link_children();
    placed.assign(n, Placed{});
    place_order.clear();
    place_order.reserve(n);
    std::vector<uint8_t> done(n, 0);
    std::vector<uint32_t> chain;
    for (uint32_t s = 0; s < n; ++s) {
      // Walk up to the first placed ancestor (or a root), then place downwards.
      chain.clear();
      for (uint32_t c = s; !done[c];) {
        chain.push_back(c);
        if (defs[c].parent.is_null()) break;
        c = slot(defs[c].parent);
      }
      while (!chain.empty()) {
        const uint32_t c = chain.back();
        chain.pop_back();
        const ModelDef& d = defs[c];
        const ModelTransform w = d.parent.is_null() ? d.transform : compose(d.transform, placed[slot(d.parent)].world);
        place(placed[c], d, w, pool.id_at(c).index);
        place_order.push_back(c);
        done[c] = 1;
      }
    }
  }

  // Places slot s again and, depth first, its descendants (each from its parent's world,
  // which is current: the parent was either not moved or placed just before it), noting
  // each for the tree. Moves of both a model and its ancestor place it twice, the second
  // time from its ancestor's new world: the same result in either order.
  void place_from(uint32_t s) {
    std::vector<uint32_t>& stack = place_stack;
    stack.assign(1, s);
    while (!stack.empty()) {
      const uint32_t c = stack.back();
      stack.pop_back();
      const ModelDef& d = defs[c];
      const ModelTransform w = d.parent.is_null() ? d.transform : compose(d.transform, placed[slot(d.parent)].world);
      const bool was = placed[c].placed;
      place(placed[c], d, w, pool.id_at(c).index);
      items_changed = items_changed || placed[c].placed != was;
      if (!tree_all && !replaced_mark[c]) replaced_mark[c] = 1, replaced.push_back(c);
      if (!child_begin.empty()) stack.insert(stack.end(), child_slots.begin() + child_begin[c], child_slots.begin() + child_begin[c + 1]);
    }
  }

  // child_begin and child_slots from the defs (in slot order), or empty when no model has a parent.
  void link_children() {
    const uint32_t n = pool.size();
    child_begin.clear();
    child_slots.clear();
    std::vector<uint32_t> parent(n, kNoIndex);
    bool any = false;
    for (uint32_t s = 0; s < n; ++s)
      if (!defs[s].parent.is_null()) parent[s] = slot(defs[s].parent), any = true;
    if (!any) return;
    child_begin.assign(n + 1, 0);
    for (uint32_t s = 0; s < n; ++s)
      if (parent[s] != kNoIndex) ++child_begin[parent[s] + 1];
    for (uint32_t s = 0; s < n; ++s) child_begin[s + 1] += child_begin[s];
    child_slots.resize(child_begin[n]);
    std::vector<uint32_t> at(child_begin.begin(), child_begin.end() - 1);
    for (uint32_t s = 0; s < n; ++s)
      if (parent[s] != kNoIndex) child_slots[at[parent[s]]++] = s;
  }

  // After a build or refit: nothing is pending for the tree.
  void tree_settled() {
    for (uint32_t s : replaced) replaced_mark[s] = 0;
    replaced.clear();
    tree_all = false;
    items_changed = false;
  }

  void build_tree() {
    if (!rebuild && (items_changed || !detached.empty()) && patch_tree()) {
      ++refits;
      tree_settled();
      return;
    }
    // Moves that placed or unplaced no model keep the items (and the plane list) as they are.
    bool same_items = !rebuild && !items_changed;
    if (!same_items) {
      std::vector<uint32_t> tree, planes;
      for (uint32_t s = 0; s < pool.size(); ++s) {
        if (!placed[s].placed) continue;
        (placed[s].shape == ModelShape::plane ? planes : tree).push_back(s);
      }
      // Slots are in id order until a remove moves the last slot into the gap, so the check
      // usually spares the sort (R1's 10^4 spheres: a tenth of prepare()'s instructions).
      const auto by_index = [&](uint32_t a, uint32_t b) { return placed[a].index < placed[b].index; };
      for (std::vector<uint32_t>* slots : {&tree, &planes})
        if (!std::is_sorted(slots->begin(), slots->end(), by_index)) std::sort(slots->begin(), slots->end(), by_index);
      plane_slots = std::move(planes);
      same_items = tree == tree_slots;
      tree_slots = std::move(tree);
    }
    if (!rebuild && same_items && settings.refit && built == SceneAccel::bvh && settings.accel == SceneAccel::bvh &&
        refit_bvh()) {
      ++refits;
      tree_settled();
      return;
    }
    tree_settled();
    rebuild = false;
    detached.clear();
    tree_holes = 0;
    ++builds;
    built = settings.accel;
    bvh = detail::BoxBvh8{};
    ray_leaves.clear();
    ray_boxes.clear();
    rays_large = false;
    octree.clear();
    std::vector<detail::BvhBox> boxes(tree_slots.size());
    for (std::size_t k = 0; k < tree_slots.size(); ++k) {
      const Corners c(placed[tree_slots[k]]);
      boxes[k] = {{c.lo[0], c.lo[1], c.lo[2]}, {c.hi[0], c.hi[1], c.hi[2]}};
    }
    slot_item.clear();  // refit_bvh() refits only a tree linked when it was built
    if (built == SceneAccel::bvh) {
      bvh = detail::build_box_bvh8(boxes.data(), boxes.size());
      if (settings.refit) {
        links.link(bvh, tree_slots.size());
        slot_item.assign(pool.size(), kNoIndex);
        for (std::size_t k = 0; k < tree_slots.size(); ++k) slot_item[tree_slots[k]] = uint32_t(k);
      }
    } else {
      std::vector<AABB> bounds(tree_slots.size());
      std::vector<uint32_t> ids(tree_slots.size());
      for (std::size_t k = 0; k < tree_slots.size(); ++k) bounds[k] = placed[tree_slots[k]].bounds, ids[k] = uint32_t(k);
      // The boxes were checked finite when placed and the def when configured.
      if (octree.build(bounds.data(), ids.data(), bounds.size(), settings.octree) != Status::ok) octree.clear();
      // The rays walk the octree in the BVH's node form, through the same kernel
      // (octree_bvh.hpp); the queries walk the octree itself.
      bvh = detail::octree_bvh8(octree, boxes.data());
    }
    build_ray_leaves();
    // Rays take turns at every size; prefetching the next visit costs more than it saves
    // up to about 10^5 spheres at R1's density (R1-like closest-hit rays spread over the
    // scene, one thread, one model per leaf: at 10^4 9.1 Mrays/s without against 7.2 with,
    // at 10^5 (9 MB of tree) 4.2-4.3 either way, at 3 * 10^5 2.4 against 2.5, at 10^6 1.15
    // against 1.56).
    rays_large = ray_bytes() > kFetchBytes;
    built_sah = bvh.stats.sah_cost;
  }

  // The BVH's boxes from the models' current ones over the same topology, for the leaves
  // holding a model placed again and the nodes above them (bvh_refit.hpp: the same bytes as
  // refitting every node). False when the refit tree's expected ray cost (the build's
  // formula) exceeds kSceneRefitCost times the last build's: the caller then builds afresh,
  // which overwrites whatever this wrote.
  bool refit_bvh() {
    if (bvh.nodes.empty() || tree_slots.empty() || slot_item.size() != pool.size()) return false;
    if (tree_all) {
      links.mark_all();
    } else {
      for (uint32_t s : replaced)
        if (slot_item[s] != kNoIndex) links.mark_item(slot_item[s]);
    }
    // The moved models' boxes staged by leaf first, read in the models' order (which is
    // the slots', so the placements stream in), then the refit reads them by leaf, near the
    // nodes it writes. The refit gathering each placement itself, in the tree's order, was
    // a chain of dependent misses: R1M's refit of 10^5 spheres, all moved, 12.4 ms a frame
    // for 24 M instructions (one thread), and on two threads, with the placements written
    // by both, 10^4 spheres took half as long again as on one. A refit keeps the items, so
    // a sphere's ray leaf keeps all but its centre and radius, written here; the other
    // leaves are written again after the refit. A refit that is not kept ends in a rebuild,
    // which writes every ray leaf afresh.
    leaf_box.resize(bvh.leaves.size());
    leaf_again.clear();
    const auto stage = [&](uint32_t item) {
      const uint32_t l = links.leaf_of(item);
      if (l == detail::kNoItem) return;
      const Placed& p = placed[tree_slots[item]];
      if (p.shape == ModelShape::sphere) {
        stage_leaf(p, l);
        return;
      }
      const Corners c(p);
      leaf_box[l] = {{c.lo[0], c.lo[1], c.lo[2]}, {c.hi[0], c.hi[1], c.hi[2]}};
      leaf_again.push_back(l);
    };
    if (tree_all && spheres_staged) {
      // compute_world() staged the spheres; the other shapes are in the flagged chunks.
      for (std::size_t k = 0; k < chunk_other.size(); ++k) {
        if (!chunk_other[k]) continue;
        const std::size_t e = std::min<std::size_t>(slot_item.size(), (k + 1) * kPlaceChunk);
        for (std::size_t s = k * kPlaceChunk; s < e; ++s)
          if (slot_item[s] != kNoIndex && placed[s].shape != ModelShape::sphere) stage(slot_item[s]);
      }
    } else if (tree_all) {
      for (uint32_t item = 0; item < tree_slots.size(); ++item) stage(item);
    } else {
      for (uint32_t s : replaced)
        if (slot_item[s] != kNoIndex) stage(slot_item[s]);
    }
    const bool ok = links.refit(bvh, [&](uint32_t leaf, uint32_t, float lo[3], float hi[3]) {
      const detail::BvhBox& b = leaf_box[leaf];
      for (int a = 0; a < 3; ++a) lo[a] = b.lo[a], hi[a] = b.hi[a];
      return false;
    });
    spheres_staged = false;
    const bool keep = ok && bvh.stats.sah_cost <= kSceneRefitCost * built_sah;
    if (keep)
      for (uint32_t l : leaf_again) write_ray_leaf(l);
    links.clear_marks();
    return keep;
  }

  // The tree's items brought up to the models without a build: the removed models' items
  // and those of models no longer placed detached, the newly placed ones attached (in slot
  // order, each where its box grows the tree least: BvhRefit::attach), then the refit of what
  // changed. False when that cannot be done (no node on an attach's path has room, half the
  // items are holes, or the refit's cost check fails): the caller rebuilds from the models,
  // which overwrites whatever this wrote.
  bool patch_tree() {
    if (!refit_linked()) return false;
    for (uint32_t item : detached) links.detach(bvh, item);
    detached.clear();
    std::vector<uint32_t> planes;
    bool attached = false;
    for (uint32_t s = 0; s < pool.size(); ++s) {
      const Placed& p = placed[s];
      if (p.placed && p.shape == ModelShape::plane) planes.push_back(s);
      const bool want = p.placed && p.shape != ModelShape::plane;
      const uint32_t item = slot_item[s];
      if (want == (item != kNoIndex)) continue;
      if (!want) {
        links.detach(bvh, item);
        tree_slots[item] = kNoIndex, slot_item[s] = kNoIndex;
        ++tree_holes;
        continue;
      }
      const Corners c(p);
      const uint32_t next = uint32_t(tree_slots.size());
      const uint32_t l = links.attach(bvh, next, c.lo, c.hi);
      if (l == detail::kNoItem) return false;
      tree_slots.push_back(s), slot_item[s] = next;
      if (ray_leaves.size() < bvh.leaves.size()) {
        ray_leaves.resize(bvh.leaves.size());
        ray_leaves[l].box_block = detail::kNoItem;
      }
      write_ray_leaf(l);
      if (!tree_all && !replaced_mark[s]) replaced_mark[s] = 1, replaced.push_back(s);
      attached = true;
    }
    if (2 * tree_holes > tree_slots.size()) return false;  // compacted by a build
    const auto by_index = [&](uint32_t a, uint32_t b) { return placed[a].index < placed[b].index; };
    if (!std::is_sorted(planes.begin(), planes.end(), by_index)) std::sort(planes.begin(), planes.end(), by_index);
    plane_slots = std::move(planes);
    if (attached) spheres_staged = false;  // compute_world() could not stage what had no leaf
    if (!refit_bvh()) return false;
    rays_large = ray_bytes() > kFetchBytes;
    return true;
  }

  // What the rays walk: the nodes, their leaves and box models.
  std::size_t ray_bytes() const {
    return bvh.nodes.size() * sizeof(detail::BvhNode8) + ray_leaves.size() * sizeof(detail::SceneLeaf) +
           ray_boxes.size() * sizeof(detail::SceneBox);
  }

  // Whether the tree is one refit_bvh() may refit over the current slots (it still checks
  // that the items are the same).
  bool refit_linked() const {
    return !rebuild && settings.refit && built == SceneAccel::bvh && settings.accel == SceneAccel::bvh &&
           !bvh.nodes.empty() && !tree_slots.empty() && slot_item.size() == pool.size();
  }

  // A sphere's new box into leaf_box and its centre and radius into its ray leaf (a refit
  // keeps the items, so the leaf keeps the rest): the box as Corners gives it.
  void stage_leaf(const Placed& p, uint32_t l) {
    const Corners c(p);
    leaf_box[l] = {{c.lo[0], c.lo[1], c.lo[2]}, {c.hi[0], c.hi[1], c.hi[2]}};
    float* sphere = ray_leaves[l].sphere;
    sphere[0] = p.box.center.x, sphere[1] = p.box.center.y, sphere[2] = p.box.center.z, sphere[3] = p.box.half_extents.x;
  }
  // Slot s's sphere, if it is in the tree.
  void stage_sphere(const Placed& p, uint32_t s) {
    const uint32_t item = slot_item[s];
    if (item == kNoIndex) return;
    const uint32_t l = links.leaf_of(item);
    if (l != detail::kNoItem) stage_leaf(p, l);
  }

  // Each leaf's model for the ray kernel: a sphere or a box as its test reads it; a mesh goes
  // to the exact test.
  void build_ray_leaves() {
    ray_leaves.resize(bvh.leaves.size());
    for (std::size_t l = 0; l < bvh.leaves.size(); ++l) {
      ray_leaves[l].box_block = detail::kNoItem;
      write_ray_leaf(l);
    }
  }

  // Leaf l's model from its current placement. A leaf that had a box block keeps its place in
  // ray_boxes (a refit: the same item, so the same shape); one without gets a new block if
  // its model is a box.
  void write_ray_leaf(std::size_t l) {
    const float nan = __builtin_nanf("");
    detail::SceneLeaf& r = ray_leaves[l];
    const uint32_t block = r.box_block;
    const uint32_t item = bvh.leaves[l].item[0];
    const Placed* p = item == detail::kNoItem ? nullptr : &placed[tree_slots[item]];
    const bool sphere = p && p->shape == ModelShape::sphere;
    r.item = item;
    r.key = p ? p->index : detail::kNoItem;
    r.sphere[0] = sphere ? p->box.center.x : nan;  // Placed::sphere()'s fields
    r.sphere[1] = sphere ? p->box.center.y : nan;
    r.sphere[2] = sphere ? p->box.center.z : nan;
    r.sphere[3] = sphere ? p->box.half_extents.x : nan;
    r.layers = p ? defs[tree_slots[item]].layers : 0u;
    r.box_block = p && !sphere && p->shape != ModelShape::box ? detail::kExactLeaf : detail::kNoItem;
    if (p && p->shape == ModelShape::box) {
      const OBB& b = p->box;
      const mat3& o = b.orientation;
      const detail::SceneBox box{{b.center.x, b.center.y, b.center.z, b.half_extents.x, b.half_extents.y, b.half_extents.z,
                                  o.m[0][0], o.m[0][1], o.m[0][2], o.m[1][0], o.m[1][1], o.m[1][2], o.m[2][0], o.m[2][1],
                                  o.m[2][2]}};
      r.box_block = detail::has_box_block(block) ? block : uint32_t(ray_boxes.size());
      if (detail::has_box_block(block)) ray_boxes[block] = box;
      else ray_boxes.push_back(box);
    }
  }

  void ensure_world() {
    if (world_ready.load(std::memory_order_acquire)) return;
    std::lock_guard<std::mutex> lock(mutex);
    if (world_ready.load(std::memory_order_relaxed)) return;
    detail::FloatEnvGuard env;
    compute_world();
    world_ready.store(true, std::memory_order_release);
  }

  void ensure_tree() {
    if (tree_ready.load(std::memory_order_acquire)) return;
    ensure_world();
    std::lock_guard<std::mutex> lock(mutex);
    if (tree_ready.load(std::memory_order_relaxed)) return;
    detail::FloatEnvGuard env;
    if (tree_stale) build_tree();
    tree_stale = false;
    if (layers_changed) {
      // set_layers() changes what the leaves hold, not the tree: a build has written the
      // new masks already, a refit has not.
      for (std::size_t l = 0; l < ray_leaves.size(); ++l) {
        const uint32_t item = bvh.leaves[l].item[0];
        ray_leaves[l].layers = item == detail::kNoItem ? 0u : defs[tree_slots[item]].layers;
      }
      layers_changed = false;
    }
    tree_ready.store(true, std::memory_order_release);
  }

  // Calls leaf(slot) for each model whose own box, and every node box above it, passes
  // box_ok(lo, hi).
  template <class BoxOk, class Leaf> void walk(BoxOk&& box_ok, Leaf&& leaf) const {
    const auto visit = [&](uint32_t slot) {
      const Corners c(placed[slot]);
      if (box_ok(c.lo, c.hi)) leaf(slot);
    };
    uint32_t stack[kStackSize];
    int sp = 0;
    if (built == SceneAccel::bvh) {
      stack[sp++] = 0;
      while (sp > 0) {
        const uint32_t code = stack[--sp];
        if (code & detail::kLeafBit) {
          for (uint32_t item : bvh.leaves[code & ~detail::kLeafBit].item)
            if (item != detail::kNoItem) visit(tree_slots[item]);
          continue;
        }
        const detail::BvhNode8& node = bvh.nodes[code];
        for (int k = 7; k >= 0; --k) {
          if (node.child[k] == detail::kEmptyChild) continue;
          const float lo[3] = {node.bounds[0][k], node.bounds[2][k], node.bounds[4][k]};
          const float hi[3] = {node.bounds[1][k], node.bounds[3][k], node.bounds[5][k]};
          if (box_ok(lo, hi)) stack[sp++] = node.child[k];
        }
      }
      return;
    }
    const auto& nodes = octree.nodes();
    if (nodes.empty()) return;
    stack[sp++] = 0;
    while (sp > 0) {
      const OctreeNode& n = nodes[stack[--sp]];
      if (!(n.lo[0] <= n.hi[0]) || !box_ok(n.lo, n.hi)) continue;
      if (n.first_child == kOctreeLeaf) {
        for (uint32_t r = n.first_item; r < n.first_item + n.item_count; ++r) visit(tree_slots[octree.items()[r]]);
        continue;
      }
      for (uint32_t k = 8; k-- > 0;) stack[sp++] = n.first_child + k;
    }
  }
};

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::Scene(const SceneSettings& settings) : Scene() {
  if (configure(settings) != Status::ok) detail::clear_error();
}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

Status Scene::configure(const SceneSettings& s) {
  if (s.accel != SceneAccel::bvh && s.accel != SceneAccel::octree)
    return fail(Status::invalid_argument, "SceneSettings.accel = %u is not an acceleration mode", unsigned(s.accel));
  if (s.ray_prefetch != RayPrefetch::automatic && s.ray_prefetch != RayPrefetch::always && s.ray_prefetch != RayPrefetch::never)
    return fail(Status::invalid_argument, "SceneSettings.ray_prefetch = %u is not a prefetch mode", unsigned(s.ray_prefetch));
  Octree probe;
  GYRO_TRY(probe.build(nullptr, nullptr, 0, s.octree));  // checks the def
  impl_->settings = s;
  impl_->rebuild = true;
  impl_->tree_stale = true;
  impl_->tree_ready.store(false, std::memory_order_relaxed);
  return Status::ok;
}

const SceneSettings& Scene::settings() const { return impl_->settings; }

Status Scene::add_model(const ModelDef& def, ModelId* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  GYRO_TRY(check_shape(def));
  GYRO_TRY(check_transform(def.transform, "ModelDef.transform"));
  Impl& m = *impl_;
  if (!def.parent.is_null() && !m.pool.valid(to_detail(def.parent)))
    return fail(Status::stale_id, "ModelDef.parent {%u, %u} is not a live model", def.parent.index, def.parent.generation);
  if (m.pool.size() >= kMaxCount) return fail(Status::invalid_count, "a scene holds at most 2^31 - 1 models");
  ModelDef d = def;
  d.transform = normalized_transform(def.transform);
  // A root model added to a scene without parents is placed as a move of its own slot and
  // attached to the tree (patch_tree()); anything else places every model and rebuilds.
  const bool patch = m.patchable() && def.parent.is_null();
  const ModelId id = id_of(m.pool.create());
  m.defs.push_back(std::move(d));
  if (patch) {
    const uint32_t s = uint32_t(m.defs.size() - 1);
    m.placed.push_back(Placed{});  // not placed until compute_world()
    m.place_order.push_back(s);
    m.moved_mark.push_back(0);
    m.replaced_mark.push_back(0);
    if (m.slot_item.size() == s) m.slot_item.push_back(kNoIndex);
    m.note_move(s);
  } else {
    m.rebuild = true;
    m.world_all = true;
  }
  m.changed();
  *out = id;
  return Status::ok;
}

Status Scene::remove_model(ModelId id) {
  Impl& m = *impl_;
  if (!m.pool.valid(to_detail(id))) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  m.ensure_world();
  // In a scene without parents the placements stay, the last slot's moved into the gap,
  // and the tree loses the model's item at the next build_tree() (patch_tree()).
  const bool patch = m.patchable() && m.moved.empty();  // ensure_world() placed the moves
  if (!patch) {
    for (uint32_t s = 0; s < m.pool.size(); ++s) {
      ModelDef& d = m.defs[s];
      if (!(d.parent == id)) continue;
      if (m.placed[s].placed) d.transform = m.placed[s].world;
      d.parent = ModelId{};
    }
  }
  const std::size_t before = m.pool.size();
  const detail::IdPool::Removal r = m.pool.destroy(to_detail(id));
  if (r.moved_from != r.slot) m.defs[r.slot] = std::move(m.defs[r.moved_from]);
  m.defs.pop_back();
  if (patch) {
    const bool moved = r.moved_from != r.slot;
    if (m.slot_item.size() == before) {
      const uint32_t item = m.slot_item[r.slot];
      if (item != kNoIndex) m.tree_slots[item] = kNoIndex, m.detached.push_back(item), ++m.tree_holes;
      if (moved) {
        const uint32_t kept = m.slot_item[r.moved_from];
        m.slot_item[r.slot] = kept;
        if (kept != kNoIndex) m.tree_slots[kept] = r.slot;
      }
      m.slot_item.pop_back();
    }
    if (moved) m.placed[r.slot] = m.placed[r.moved_from];
    m.placed.pop_back();
    m.place_order.pop_back();  // the slots in order: no model has a parent
    m.moved_mark.pop_back();   // none is marked: ensure_world() placed the moves
    std::erase(m.replaced, r.slot);
    if (moved) {
      for (uint32_t& s : m.replaced)
        if (s == r.moved_from) s = r.slot;
      m.replaced_mark[r.slot] = m.replaced_mark[r.moved_from];
    }
    m.replaced_mark.pop_back();
    m.items_changed = true;
    m.spheres_staged = false;
  } else {
    m.rebuild = true;
    m.world_all = true;
  }
  m.changed();
  return Status::ok;
}

Status Scene::set_transform(ModelId id, const ModelTransform& local) {
  Impl& m = *impl_;
  const uint32_t s = m.slot(id);
  if (s == detail::IdPool::kNoSlot) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  GYRO_TRY(check_transform(local, "transform"));
  m.defs[s].transform = normalized_transform(local);
  m.note_move(s);
  m.changed();
  return Status::ok;
}

Status Scene::set_layers(ModelId id, uint32_t layers) {
  Impl& m = *impl_;
  const uint32_t s = m.slot(id);
  if (s == detail::IdPool::kNoSlot) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  if (m.defs[s].layers == layers) return Status::ok;
  m.defs[s].layers = layers;
  m.layers_changed = true;
  m.tree_ready.store(false, std::memory_order_relaxed);  // the leaves' masks, not the world or the tree
  return Status::ok;
}

Status Scene::set_parent(ModelId id, ModelId parent) {
  Impl& m = *impl_;
  const uint32_t s = m.slot(id);
  if (s == detail::IdPool::kNoSlot) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  if (!parent.is_null()) {
    if (!m.pool.valid(to_detail(parent)))
      return fail(Status::stale_id, "parent {%u, %u} is not live", parent.index, parent.generation);
    // The chains are acyclic, so this walk ends; it meets `id` only if parent descends from it.
    for (ModelId a = parent; !a.is_null(); a = m.defs[m.slot(a)].parent)
      if (a == id)
        return fail(Status::invalid_argument, "making {%u, %u} the parent of {%u, %u} would close a cycle", parent.index,
                    parent.generation, id.index, id.generation);
  }
  m.defs[s].parent = parent;
  m.rebuild = true;
  m.world_all = true;
  m.changed();
  return Status::ok;
}

bool Scene::contains(ModelId id) const { return impl_->pool.valid(to_detail(id)); }
std::size_t Scene::model_count() const { return impl_->pool.size(); }

std::vector<ModelId> Scene::model_ids() const {
  std::vector<ModelId> out(impl_->pool.size());
  for (uint32_t s = 0; s < impl_->pool.size(); ++s) out[s] = id_of(impl_->pool.id_at(s));
  std::sort(out.begin(), out.end());
  return out;
}

Status Scene::model(ModelId id, ModelInfo* out) const {
  GYRO_TRY(detail::require_not_null(out, "out"));
  Impl& m = *impl_;
  const uint32_t s = m.slot(id);
  if (s == detail::IdPool::kNoSlot) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  m.ensure_world();
  const Placed& p = m.placed[s];
  ModelInfo info;
  info.def = m.defs[s];
  info.world = p.world;
  // Only the model's own kind; the others keep their defaults.
  if (p.shape == ModelShape::sphere) info.sphere = p.sphere();
  if (p.shape == ModelShape::box || p.shape == ModelShape::mesh) info.box = p.box;
  if (p.shape == ModelShape::plane) info.plane = p.plane();
  info.bounds = p.bounds;
  info.placed = p.placed;
  *out = std::move(info);
  return Status::ok;
}

Status Scene::children(ModelId id, std::vector<ModelId>& out) const {
  out.clear();
  const Impl& m = *impl_;
  if (!m.pool.valid(to_detail(id))) return fail(Status::stale_id, "model {%u, %u} is not live", id.index, id.generation);
  for (uint32_t s = 0; s < m.pool.size(); ++s)
    if (m.defs[s].parent == id) out.push_back(id_of(m.pool.id_at(s)));
  std::sort(out.begin(), out.end());
  return Status::ok;
}

void Scene::prepare() const { impl_->ensure_tree(); }

SceneStats Scene::stats() const {
  const Impl& m = *impl_;
  prepare();
  SceneStats s;
  s.accel = m.built;
  s.models = m.pool.size();
  s.tree_models = m.tree_slots.size() - m.tree_holes;
  s.planes = m.plane_slots.size();
  s.builds = m.builds, s.refits = m.refits;
  if (m.built == SceneAccel::bvh) s.sah_cost = m.bvh.stats.sah_cost;
  // Both modes' rays walk m.bvh (under the octree, its node form: octree_bvh.hpp).
  s.bytes = m.bvh.stats.bytes + m.ray_leaves.size() * sizeof(detail::SceneLeaf) + m.ray_boxes.size() * sizeof(detail::SceneBox);
  if (m.built == SceneAccel::bvh) {
    // Adds and removes since the build (patch_tree()) add leaf blocks and holes.
    s.nodes = m.bvh.nodes.size(), s.leaves = m.bvh.leaves.size(), s.max_depth = m.bvh.stats.max_depth;
    s.references = m.tree_slots.size() - m.tree_holes;
  } else {
    const OctreeStats o = m.octree.stats();
    s.nodes = o.nodes, s.leaves = o.leaves, s.max_depth = o.max_depth, s.references = o.references, s.bytes += o.bytes;
  }
  s.bytes += m.placed.size() * sizeof(Placed) + m.defs.size() * sizeof(ModelDef);
  // The bookkeeping that lets a frame pay for what moved.
  s.bytes += m.links.bytes() + (m.slot_item.capacity() + m.moved.capacity() + m.replaced.capacity() +
                                m.child_begin.capacity() + m.child_slots.capacity()) * sizeof(uint32_t) +
             m.moved_mark.capacity() + m.replaced_mark.capacity() + m.leaf_box.capacity() * sizeof(detail::BvhBox) +
             m.leaf_again.capacity() * sizeof(uint32_t);
  return s;
}

// ------------------------------------------------------------------------ raycasts
//
// Rays go in blocks: the planes here (scalar), the tree in the per-level kernel of
// scene_kernels.cpp (one model per leaf, spheres and boxes by their scalar tests, meshes
// through exact_t below, eight rays taking turns), then the winner's point, normal,
// triangle and barycentrics here, computed once per ray. Under the octree the kernel walks
// the octree's node form (octree_bvh.hpp): the Cookbook's scalar walk of the octree, one
// child box and one model at a time, ran R1 at 1.1 Mrays/s, the kernel on the same octree
// at 5.3-5.8 (one thread). Both modes give the brute-force loop's bits (the header comment).

namespace {

// One ray against the planes and single models: the slab test of a model's box and the
// running best (closest) or first (any) hit.
class RayWalk {
 public:
  RayWalk(const Scene::Impl& m, const Ray& ray, float tmin, float tmax, bool any, uint32_t mask)
      : m_(m), ray_(ray), tmin_(tmin), tmax_(tmax), any_(any), mask_(mask) {
    const float o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const float d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    const float pad = pad_of(ray);
    for (int a = 0; a < 3; ++a) {
      o_[a] = o[a];
      inv_[a] = 1.0f / d[a];
      neg_[a] = std::bit_cast<uint32_t>(inv_[a]) >> 31;
      pad_[a] = pad;
    }
  }

  // How far a ray widens every box it tests.
  static float pad_of(const Ray& ray) { return kRayPad * max_abs3(ray.origin); }

  // The planes' best (any hit: the first in id order).
  const SceneHit& planes() {
    for (uint32_t s : m_.plane_slots) {
      if ((m_.defs[s].layers & mask_) == 0) continue;  // a layer the ray does not see
      test(s);
      if (any_ && found()) break;
    }
    return best_;
  }
  float best_t() const { return best_t_; }
  uint32_t best_index() const { return best_index_; }

  // A mesh tree model for the kernel: its box entered by `limit`, then the exact
  // test, a mesh's range cut to the best t so far (closest hit). +inf when not hit.
  float exact_t(uint32_t slot, float best_t, float limit, SceneHit* out) const {
    const Placed& p = m_.placed[slot];
    const Corners c(p);
    if (!(enter(c.lo, c.hi, limit) < kInf)) return kInf;
    *out = hit_of(slot, best_t < kInf && !any_ ? std::min(tmax_, best_t) : tmax_);
    return out->hit.hit ? out->hit.t : kInf;
  }

  // The model's hit in [tmin, tmax] (a mesh's in [tmin, mesh_tmax]), with its details.
  SceneHit hit_of(uint32_t slot, float mesh_tmax) const {
    const Placed& p = m_.placed[slot];
    SceneHit h;
    switch (p.shape) {
      case ModelShape::sphere: h.hit = raycast(p.sphere(), ray_, tmin_, tmax_); break;
      case ModelShape::box: h.hit = raycast(p.box, ray_, tmin_, tmax_); break;
      case ModelShape::plane: h.hit = raycast(p.plane(), ray_, tmin_, tmax_); break;
      case ModelShape::mesh: {
        const MeshHit mh = raycast(*p.mesh, to_local(p.world, ray_), tmin_, mesh_tmax);
        if (!mh.hit.hit) return h;
        h.hit.hit = true;
        h.hit.t = mh.hit.t;
        h.hit.point = ray_.origin + ray_.direction * mh.hit.t;
        h.hit.normal = mh.hit.normal * p.box.orientation;
        h.primitive = mh.triangle;
        h.u = mh.u, h.v = mh.v;
        break;
      }
    }
    if (h.hit.hit) h.model = id_of(m_.pool.id_at(slot));
    return h;
  }

 private:
  const Scene::Impl& m_;
  Ray ray_;
  float tmin_, tmax_;
  bool any_;
  uint32_t mask_;
  float o_[3], inv_[3], pad_[3];
  uint32_t neg_[3];
  float best_t_ = kInf;
  uint32_t best_index_ = kNoIndex;
  SceneHit best_;

  bool found() const { return best_index_ != kNoIndex; }
  // Entry t of the box (kInf when the ray does not enter it within [tmin, limit]).
  float enter(const float lo[3], const float hi[3], float limit) const {
    float tn = tmin_, tf = limit;
    for (int a = 0; a < 3; ++a) {
      const float l = lo[a] - pad_[a], h = hi[a] + pad_[a];
      const float t0 = ((neg_[a] ? h : l) - o_[a]) * inv_[a];
      const float t1 = ((neg_[a] ? l : h) - o_[a]) * inv_[a];
      tn = t0 > tn ? t0 : tn;  // a NaN slab (0 * inf) leaves tn as it was
      tf = t1 < tf ? t1 : tf;
    }
    return tn <= tf * kSlabScale && tn < kInf ? tn : kInf;
  }

  void take(float t, uint32_t index, const SceneHit& h) {
    if (t < best_t_ || (t == best_t_ && index < best_index_)) best_t_ = t, best_index_ = index, best_ = h;
  }

  void test(uint32_t slot) {
    // A smaller tmax only drops triangles beyond the best hit, which cannot win.
    const SceneHit h = hit_of(slot, found() && !any_ ? std::min(tmax_, best_t_) : tmax_);
    if (h.hit.hit) take(h.hit.t, m_.placed[slot].index, h);
  }
};

// The rays the mesh queries flag as kRayInvalid (triangle_mesh.hpp): a NaN or infinite
// coordinate, a zero direction, tmin not finite or negative, tmax NaN or below tmin.
bool valid_ray(const Ray& ray, float tmin, float tmax) {
  const vec3& d = ray.direction;
  return gyro::is_finite(ray.origin) && gyro::is_finite(d) && (d.x != 0.0f || d.y != 0.0f || d.z != 0.0f) && detail::is_finite(tmin) &&
         tmin >= 0.0f && tmax >= tmin;
}

// Rays in a block: the kernel's per-ray state lives on the stack.
constexpr std::size_t kBlock = 64;
constexpr uint32_t kPlaneItem = 0xFFFFFFFEu;

// A block of rays as the kernel's exact callback sees them, with the details of the hits
// already computed: the planes' winner, then any mesh hit that was the best when
// it was tested (item says which), so the winner's details are rarely computed twice.
struct Block {
  const Scene::Impl* m;
  const RaysView* rays;
  std::size_t begin;
  bool any;
  SceneHit cached[kBlock];
  uint32_t cached_item[kBlock];

  Ray ray(std::size_t k) const {
    const std::size_t i = begin + k;
    return {{rays->ox[i], rays->oy[i], rays->oz[i]}, {rays->dx[i], rays->dy[i], rays->dz[i]}};
  }
  float tmin(std::size_t k) const { return rays->tmin ? rays->tmin[begin + k] : 0.0f; }
  float tmax(std::size_t k) const { return rays->tmax ? rays->tmax[begin + k] : kInf; }
  uint32_t mask(std::size_t k) const { return rays->mask ? rays->mask[begin + k] : kAllLayers; }
  RayWalk walker(std::size_t k) const { return RayWalk(*m, ray(k), tmin(k), tmax(k), any, mask(k)); }
};

float exact_t(void* ctx, std::size_t k, uint32_t item, float best_t, uint32_t best_key, float limit) {
  Block& b = *static_cast<Block*>(ctx);
  const uint32_t slot = b.m->tree_slots[item];
  SceneHit h;
  const float t = b.walker(k).exact_t(slot, best_t, limit, &h);
  const uint32_t key = b.m->placed[slot].index;
  if (t < best_t || (t == best_t && t < kInf && key < best_key)) b.cached[k] = h, b.cached_item[k] = item;
  return t;
}

// Rays [begin, begin + n), n <= kBlock, of a prepared BVH scene into out[0, n). A sphere or
// box winner's t is the scalar raycast's to the bit, so its hit is not solved again: its
// point and normal come from that t (raycast_at), and without `details` (a batch that
// asked for no normals) it gets its t and model only. Solving it again (a RayWalk's three
// divisions, then the scalar raycast) cost R1 a tenth of its time: 6.1 -> 6.8 Mrays/s.
void trace_block(const Scene::Impl& m, const RaysView& rays, std::size_t begin, std::size_t n, bool any, bool details,
                 SceneHit* out, bool* valid) {
  Block b{&m, &rays, begin, any, {}, {}};
  float best_t[kBlock], pad[kBlock];
  uint32_t best_key[kBlock], best_item[kBlock];
  uint8_t walk[kBlock];
  for (std::size_t k = 0; k < n; ++k) {
    const Ray ray = b.ray(k);
    valid[k] = valid_ray(ray, b.tmin(k), b.tmax(k));
    best_t[k] = kInf, best_key[k] = kNoIndex, best_item[k] = detail::kNoItem, pad[k] = 0.0f, walk[k] = 0;
    b.cached_item[k] = detail::kNoItem;
    if (!valid[k] || b.mask(k) == 0) continue;  // a ray of no layer sees nothing
    if (!m.plane_slots.empty()) {  // (a walker's three divisions only where there are planes)
      RayWalk w = b.walker(k);
      b.cached[k] = w.planes();
      best_t[k] = w.best_t(), best_key[k] = w.best_index();
      if (best_key[k] != kNoIndex) b.cached_item[k] = kPlaneItem;
    }
    pad[k] = RayWalk::pad_of(ray);
    walk[k] = !m.tree_slots.empty() && !(any && best_key[k] != kNoIndex);
  }
  if (!m.tree_slots.empty()) {
    const auto shift = [&](const float* p) { return p ? p + begin : nullptr; };
    const RayPrefetch rp = m.settings.ray_prefetch;
    const bool prefetch = rp == RayPrefetch::always || (rp == RayPrefetch::automatic && m.rays_large);
    const SceneRaycastArgs args{m.bvh.nodes.data(), m.ray_leaves.data(), m.ray_boxes.data(), rays.ox + begin, rays.oy + begin,
                                rays.oz + begin,    rays.dx + begin,      rays.dy + begin, rays.dz + begin,
                                shift(rays.tmin),   shift(rays.tmax),     pad,             walk,
                                rays.mask ? rays.mask + begin : nullptr,  any,             prefetch,
                                best_t,             best_key,
                                best_item,          exact_t,              &b};
    GYRO_DISPATCH(scene_raycast)(args, 0, n);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const uint32_t item = best_item[k];
    if (item != detail::kNoItem) {
      const uint32_t slot = m.tree_slots[item];
      if (b.cached_item[k] == item) {
        out[k] = b.cached[k];
      } else if (const Placed& p = m.placed[slot]; p.shape != ModelShape::mesh) {
        out[k] = SceneHit{};
        if (!details) out[k].hit.hit = true, out[k].hit.t = best_t[k];
        else out[k].hit = p.shape == ModelShape::sphere ? detail::raycast_at(p.sphere(), b.ray(k), best_t[k])
                                                         : detail::raycast_at(p.box, b.ray(k), best_t[k]);
        out[k].model = id_of(m.pool.id_at(slot));
      } else {
        out[k] = b.walker(k).hit_of(slot, b.tmax(k));
      }
    } else {
      out[k] = b.cached_item[k] == kPlaneItem ? b.cached[k] : SceneHit{};
    }
  }
}

SceneHit trace(const Scene& scene, const Ray& ray, float tmin, float tmax, bool any, uint32_t mask) {
  if (!valid_ray(ray, tmin, tmax)) return {};
  const Scene::Impl& m = *scene.impl();
  const RaysView view{&ray.origin.x, &ray.origin.y, &ray.origin.z, &ray.direction.x, &ray.direction.y,
                      &ray.direction.z, &tmin, &tmax, &mask};
  SceneHit h;
  bool valid;
  trace_block(m, view, 0, 1, any, true, &h, &valid);
  return h;
}

void write_hit(const SceneHitsOut& hits, std::size_t i, const SceneHit& h, bool valid, bool normals) {
  hits.t[i] = h.hit.hit ? h.hit.t : kInf;
  hits.model[i] = h.model;
  if (hits.primitive) hits.primitive[i] = h.hit.hit ? int32_t(h.primitive) : valid ? -1 : kRayInvalid;
  if (normals) hits.nx[i] = h.hit.normal.x, hits.ny[i] = h.hit.normal.y, hits.nz[i] = h.hit.normal.z;
  if (hits.u) hits.u[i] = h.u, hits.v[i] = h.v;
}

Status run_batch(const Scene& scene, const RaysView& rays, std::size_t n, const SceneHitsOut& hits, bool any) {
  if (n > kMaxCount) return fail(Status::invalid_count, "ray count %zu must be below 2^31", n);
  if (n == 0) return Status::ok;
  GYRO_TRY(detail::require_not_null(hits.t, "hits.t"));
  GYRO_TRY(detail::require_not_null(hits.model, "hits.model"));
  GYRO_TRY(detail::check_hit_columns(hits.nx, hits.ny, hits.nz, hits.u, hits.v));
  const bool normals = hits.nx != nullptr;  // all three, checked above
  GYRO_TRY(detail::check_rays(rays, n, false));  // bad values are flagged per ray
  detail::FloatEnvGuard env;
  scene.prepare();
  const Scene::Impl& m = *scene.impl();
  detail::parallel_for(n, kRayChunk, [&](std::size_t b, std::size_t e) {
    SceneHit out[kBlock];
    bool valid[kBlock];
    for (std::size_t s = b; s < e; s += kBlock) {
      const std::size_t count = std::min(kBlock, e - s);
      trace_block(m, rays, s, count, any, normals, out, valid);
      for (std::size_t k = 0; k < count; ++k) write_hit(hits, s + k, out[k], valid[k], normals);
    }
  });
  return Status::ok;
}

}  // namespace

SceneHit raycast(const Scene& scene, const Ray& ray, float tmin, float tmax, uint32_t mask) {
  detail::FloatEnvGuard env;
  scene.prepare();
  return trace(scene, ray, tmin, tmax, false, mask);
}

SceneHit raycast_any(const Scene& scene, const Ray& ray, float tmin, float tmax, uint32_t mask) {
  detail::FloatEnvGuard env;
  scene.prepare();
  return trace(scene, ray, tmin, tmax, true, mask);
}

Status raycast_closest(const Scene& scene, const RaysView& rays, std::size_t ray_count, const SceneHitsOut& hits) {
  return run_batch(scene, rays, ray_count, hits, false);
}

Status raycast_any(const Scene& scene, const RaysView& rays, std::size_t ray_count, const SceneHitsOut& hits) {
  return run_batch(scene, rays, ray_count, hits, true);
}

// ------------------------------------------------------------------------ queries

namespace {

// Candidates from the tree (box_ok on node boxes), every plane, then the exact test;
// ids ascending, each once.
template <class BoxOk, class Exact>
void collect(const Scene& scene, uint32_t mask, BoxOk&& box_ok, Exact&& exact, std::vector<ModelId>& out) {
  scene.prepare();
  const Scene::Impl& m = *scene.impl();
  std::vector<uint32_t> slots;
  // A model in none of the query's layers is skipped before its exact test.
  const auto wanted = [&](uint32_t s) { return (m.defs[s].layers & mask) != 0 && exact(m.placed[s]); };
  for (uint32_t s : m.plane_slots)
    if (wanted(s)) slots.push_back(s);
  m.walk(box_ok, [&](uint32_t s) {
    if (wanted(s)) slots.push_back(s);
  });
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  out.reserve(slots.size());
  for (uint32_t s : slots) out.push_back(id_of(m.pool.id_at(s)));
  std::sort(out.begin(), out.end());
}

Status check_obb(const OBB& b) {
  if (!gyro::is_finite(b.center) || !gyro::is_finite(b.half_extents)) return fail(Status::non_finite, "box is not finite");
  for (int k = 0; k < 3; ++k)
    if (!gyro::is_finite({b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]}))
      return fail(Status::non_finite, "box orientation is not finite");
  if (!(b.half_extents.x >= 0.0f && b.half_extents.y >= 0.0f && b.half_extents.z >= 0.0f))
    return fail(Status::invalid_argument, "box has a negative half extent");
  return Status::ok;
}

// The exact test of a query shape (Sphere, AABB or OBB) against a model, and the pruning
// region around it; the three shape queries share it.
template <class Shape> bool model_overlaps(const Shape& q, const Placed& p) {
  switch (p.shape) {
    case ModelShape::sphere: return overlaps(q, p.sphere());
    case ModelShape::box: return overlaps(q, p.box);
    case ModelShape::plane: return overlaps(q, p.plane());
    case ModelShape::mesh: return overlaps(*p.mesh, to_local(p.world, q));
  }
  return false;
}

template <class Shape>
Status query_shape(const Scene& scene, const Shape& q, const Region& r, uint32_t mask, std::vector<ModelId>& out) {
  detail::FloatEnvGuard env;
  collect(
      scene, mask, [&](const float lo[3], const float hi[3]) { return region_touches(r, lo, hi); },
      [&](const Placed& p) { return model_overlaps(q, p); }, out);
  return Status::ok;
}

// The plane model against the frustum's corners: out only when all eight lie strictly on
// one side (by more than the rounding of the corners and of the distances).
bool plane_touches(const Frustum& f, const Plane& p) {
  vec3 c[8];
  frustum_corners(f, c);
  float mag = std::abs(p.distance);
  for (const vec3& v : c) mag = std::max(mag, max_abs3(v));
  const float tol = 1e-5f * mag + 1e-30f;
  int above = 0, below = 0;
  for (const vec3& v : c) {
    const float d = dot(p.normal, v) - p.distance;
    above += d > tol;
    below += d < -tol;
  }
  return above != 8 && below != 8;
}

}  // namespace

Status query(const Scene& scene, const Sphere& q, std::vector<ModelId>& out, uint32_t mask) {
  out.clear();
  if (!gyro::is_finite(q.center) || !detail::is_finite(q.radius)) return fail(Status::non_finite, "sphere is not finite");
  if (!(q.radius >= 0.0f)) return fail(Status::invalid_argument, "sphere radius %g is negative", double(q.radius));
  return query_shape(scene, q, region_of(q.center, {q.radius, q.radius, q.radius}), mask, out);
}

Status query(const Scene& scene, const AABB& q, std::vector<ModelId>& out, uint32_t mask) {
  out.clear();
  if (!gyro::is_finite(q.center) || !gyro::is_finite(q.half_extents)) return fail(Status::non_finite, "box is not finite");
  if (!(q.half_extents.x >= 0.0f && q.half_extents.y >= 0.0f && q.half_extents.z >= 0.0f))
    return fail(Status::invalid_argument, "box has a negative half extent");
  return query_shape(scene, q, region_of(q.center, q.half_extents), mask, out);
}

Status query(const Scene& scene, const OBB& q, std::vector<ModelId>& out, uint32_t mask) {
  out.clear();
  GYRO_TRY(check_obb(q));
  return query_shape(scene, q, region_of(q.center, aabb_half_extents(q.orientation, q.half_extents)), mask, out);
}

Status query(const Scene& scene, const Frustum& f, std::vector<ModelId>& out, uint32_t mask) {
  out.clear();
  GYRO_TRY(detail::check_frustum(f, "frustum"));
  detail::FloatEnvGuard env;
  collect(
      scene, mask, [&](const float lo[3], const float hi[3]) { return detail::frustum_may_touch(f, lo, hi); },
      [&](const Placed& p) {
        switch (p.shape) {
          case ModelShape::sphere: return intersects(f, p.sphere());
          case ModelShape::box:
          case ModelShape::mesh: return intersects(f, p.box);
          case ModelShape::plane: return plane_touches(f, p.plane());
        }
        return false;
      },
      out);
  return Status::ok;
}

Status pick(const Scene& scene, const Camera& camera, vec2 screen_point, vec2 viewport_size, SceneHit* out,
            uint32_t mask) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  *out = SceneHit{};
  GYRO_TRY(check_camera(camera));
  if (!detail::is_finite(screen_point.x) || !detail::is_finite(screen_point.y) || !detail::is_finite(viewport_size.x) ||
      !detail::is_finite(viewport_size.y))
    return fail(Status::non_finite, "pick: screen point or viewport size is not finite");
  if (!(viewport_size.x > 0.0f && viewport_size.y > 0.0f))
    return fail(Status::invalid_argument, "pick: viewport size (%g, %g) must be > 0", double(viewport_size.x),
                double(viewport_size.y));
  *out = raycast(scene, picking_ray(camera, screen_point, viewport_size), 0.0f, kInf, mask);
  return Status::ok;
}

}  // namespace gyro
