// The scene raycast kernel: rays through the scene's 8-wide BVH over its models (a node's
// eight child boxes in one 8-wide lane, each leaf one model: a sphere or a box tested by the
// scalar raycast's expressions, a mesh through the scene's exact test). Closest or any hit.
#pragma once

#include "core/dispatch.hpp"
#include "spatial/bvh.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

static_assert(kBoxBvhLeafItems == 1, "a scene's ray leaf holds one model");

/// A scene leaf block as the ray kernel reads it (its one model), built next to the BVH's
/// BvhItems: two to a cache line.
struct alignas(32) SceneLeaf {
  float sphere[4];     ///< cx, cy, cz, r; r is NaN where the model is not a sphere (no ray hits it)
  uint32_t key;        ///< the model's id index (the tie-break), kNoItem where there is none
  uint32_t item;       ///< the tree item, kNoItem where there is none
  uint32_t layers;   ///< the model's ModelDef::layers (0 where there is none)
  /// Index of the model's SceneBox; kExactLeaf: the exact callback tests the model (a mesh);
  /// kNoItem: neither (a sphere, or no model).
  uint32_t box_block;
};
inline constexpr uint32_t kExactLeaf = 0xFFFFFFFEu;
/// Whether a leaf's box_block names a SceneBox.
inline bool has_box_block(uint32_t block) { return block < kExactLeaf; }

/// A box model for ray_obb_t: the OBB exactly as the scalar raycast reads it (centre, half
/// extents, the orientation's rows), so the same bits.
struct alignas(64) SceneBox {
  float obb[15];  ///< cx, cy, cz, ex, ey, ez, u0 xyz, u1 xyz, u2 xyz
  uint32_t unused = 0;
};

}  // namespace detail

/// The exact t of tree item `item` for ray `ray` (the index into the arrays), +inf when it
/// is not hit in [tmin, tmax] or its box is not entered by `limit`. best_t and best_key are
/// the ray's best so far (the callback may cache the details of a hit that beats them).
using scene_exact_fn = float(void* ctx, std::size_t ray, uint32_t item, float best_t, uint32_t best_key, float limit);

struct SceneRaycastArgs {
  const detail::BvhNode8* nodes;  ///< nodes[0] is the root
  const detail::SceneLeaf* leaves;
  const detail::SceneBox* boxes;  ///< by SceneLeaf::box_block
  const float *ox, *oy, *oz, *dx, *dy, *dz;
  const float* tmin;      ///< null: 0
  const float* tmax;      ///< null: +inf
  const float* pad;       ///< per ray: how far every box is widened (the scene's ray pad)
  const uint8_t* walk;    ///< per ray: 0 = leave it (invalid, or already answered)
  const uint32_t* mask;   ///< per ray: the layers it sees (SceneLeaf::layers); null: all
  bool any_hit;
  /// The tree is large enough that prefetching each next visit pays for its instructions
  /// (rays take turns, scene_kernels.cpp; it changes no answer).
  bool prefetch;
  /// In: the best hit before the tree (the planes'); out: the best over planes and tree.
  float* best_t;          ///< +inf: none
  uint32_t* best_key;     ///< the winner's id index
  uint32_t* best_item;    ///< the winning tree item; untouched when no tree model wins
  scene_exact_fn* exact;
  void* ctx;
};

/// Rays [begin, end).
using scene_raycast_fn = void(const SceneRaycastArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(scene_raycast, scene_raycast_fn)

}  // namespace gyro
