// An octree as the 8-wide nodes the scene's ray kernel walks (scene_kernels.cpp), so a scene
// under the octree casts its rays through the same kernel as one under the BVH: only the
// tree's shape differs between the two modes.
//
// An inner octree node becomes a BvhNode8 whose slots are its eight children with their
// content bounds (an empty child, an empty slot). A leaf's items go in blocks of
// kBoxBvhLeafItems (bvh.hpp), a block straight in the parent's slot when the leaf holds no
// more, under nodes of their own otherwise (each slot with its block's own bounds). An item stored in several leaves is
// in several blocks: the kernel then tests it more than once, which changes no closest hit
// (the same t, the same tie-break).
#pragma once

#include "gyro/octree.hpp"
#include "spatial/bvh.hpp"

namespace gyro::detail {

/// The 8-wide form of a built octree whose item ids are 0..n-1, boxes[id] each item's box
/// (the corners its octree box has). Deterministic: a function of the octree and the boxes.
BoxBvh8 octree_bvh8(const Octree& octree, const BvhBox* boxes);

}  // namespace gyro::detail
