// The scene raycast kernel: rays through the scene's 8-wide BVH over its models (a node's
// eight child boxes in one 8-wide lane), a leaf's sphere models and its box models each
// tested in one 4-wide lane, its meshes through the scene's exact test. Closest or any hit.
#pragma once

#include "core/dispatch.hpp"
#include "spatial/bvh.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

/// A scene leaf block as the ray kernel reads it, built next to the BVH's BvhItems4.
struct alignas(64) SceneLeaf4 {
  float sphere[4][4];   ///< cx, cy, cz, r per lane; r is NaN where the item is not a sphere (no ray hits it)
  uint32_t key[4];      ///< the model's id index (the tie-break), kNoItem where there is no item
  uint32_t item[4];     ///< the tree item, kNoItem where there is none
  uint32_t exact_mask;  ///< bit k: lane k is a model the exact callback tests (a mesh)
  uint32_t box_block;   ///< index of the leaf's SceneBoxes4, kNoItem when it has no box model
  uint32_t unused[6] = {};  ///< to the cache line, zeroed so the bytes are defined
};

/// The box models of a leaf as lanes, for ray_obb_t: the OBB exactly as the scalar raycast
/// reads it (centre, half extents, the orientation's rows), so the same bits.
struct alignas(64) SceneBoxes4 {
  float obb[15][4];  ///< cx, cy, cz, ex, ey, ez, u0 xyz, u1 xyz, u2 xyz per lane
  uint32_t mask;     ///< bit k: lane k is a box model (the others repeat one of them, unused)
  uint32_t unused[3] = {};
};

}  // namespace detail

/// The exact t of tree item `item` for ray `ray` (the index into the arrays), +inf when it
/// is not hit in [tmin, tmax] or its box is not entered by `limit`. best_t and best_key are
/// the ray's best so far (the callback may cache the details of a hit that beats them).
using scene_exact_fn = float(void* ctx, std::size_t ray, uint32_t item, float best_t, uint32_t best_key, float limit);

struct SceneRaycastArgs {
  const detail::BvhNode8* nodes;  ///< nodes[0] is the root
  const detail::SceneLeaf4* leaves;
  const detail::SceneBoxes4* boxes;  ///< by SceneLeaf4::box_block
  const float *ox, *oy, *oz, *dx, *dy, *dz;
  const float* tmin;      ///< null: 0
  const float* tmax;      ///< null: +inf
  const float* pad;       ///< per ray: how far every box is widened (the scene's ray pad)
  const uint8_t* walk;    ///< per ray: 0 = leave it (invalid, or already answered)
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
