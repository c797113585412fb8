// The BVH over a triangle mesh: the layout the build writes and the kernels read.
//
// A node has eight children and holds their bounds as structure of arrays (bounds[2 * axis
// + 0] the minima, bounds[2 * axis + 1] the maxima, one float per child), so one 8-wide
// lane tests a ray against all of them at once. An unused
// child slot has bounds (+inf, -inf), which no ray's slab test can enter. A child is another
// node, a leaf block (kLeafBit set) or empty.
//
// Leaf blocks hold up to four triangles as structure of arrays (corner a, b, c coordinates,
// one float per triangle) in leaf order, with each triangle's index in the input mesh;
// unused lanes have NaN corners (no ray hits them) and index kNoTriangle.
//
// The same builder also makes a BVH over arbitrary boxes (BoxBvh8: the scene's top level
// over its models), with the same nodes and leaf blocks of item indices (kBoxBvhLeafItems each).
#pragma once

#include "core/default_init.hpp"
#include "gyro/mesh.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace gyro::detail {

inline constexpr uint32_t kLeafBit = 0x80000000u;
inline constexpr uint32_t kEmptyChild = 0xFFFFFFFFu;
inline constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;
inline constexpr uint32_t kNoItem = 0xFFFFFFFFu;
/// Written as the hit index of a ray the query cannot answer (-2 as int32_t).
inline constexpr uint32_t kInvalidRay = 0xFFFFFFFEu;
/// The build caps the binary depth so that a traversal stack of kBvhStackSize entries always
/// suffices (each 8-wide level pushes at most seven siblings).
inline constexpr std::size_t kBvhMaxDepth = 64;
inline constexpr std::size_t kBvhStackSize = 7 * kBvhMaxDepth + 8;

// Cache-line aligned: an 8-wide node is exactly four lines, a leaf three, so a visit never
// touches a line it does not need. The bounds stay binary32: nodes of 16-bit child bounds
// over a per-node frame (three lines, rounded outward, the same hits) made R2's rays 13%
// slower (one thread, AVX-512, min of 5 over four alternated runs: 258-260 against 223-232
// ms for 10^6 rays), the dequantizing costing more than the line saved; callgrind counts
// 37 L1 misses a ray, so the walk is bound by latency, which 16 rays in flight hide, more
// than by bandwidth.
struct alignas(64) BvhNode8 {
  float bounds[6][8];  ///< [2 * axis + (0: min, 1: max)][child]
  uint32_t child[8];   ///< node index, kLeafBit | leaf block index, or kEmptyChild
  /// order[o]: the slots front to back for a ray in octant o (bit k set: its direction is
  /// negative along axis k), nibble j the j-th: by the children's centres along the
  /// octant's diagonal, ties in slot order, empty slots last. A closest-hit walk pushes the
  /// entered children in this order without sorting their entry distances (bvh_order.hpp).
  uint32_t order[8];
};

struct alignas(64) BvhLeaf4 {
  float corner[9][4];  ///< ax, ay, az, bx, by, bz, cx, cy, cz per lane
  uint32_t triangle[4];
  uint32_t unused[8];  ///< to the cache line, zeroed so the bytes are defined
};

/// The offset in bytes of bounds row 2 * axis + side (side 0: the minima, 1: the maxima):
/// the ray kernels keep a ray's near and far rows as offsets, so a row's load is one add.
inline constexpr std::ptrdiff_t bounds_offset(int axis, int side) {
  return std::ptrdiff_t(sizeof(BvhNode8::bounds[0])) * (2 * axis + side);
}
/// The row at a bounds_offset() (through the node's bytes: an index into bounds[0] past its
/// eight floats would be out of that array's bounds).
inline const float* bounds_row(const BvhNode8& node, std::ptrdiff_t offset) {
  return reinterpret_cast<const float*>(reinterpret_cast<const char*>(node.bounds) + offset);
}

/// Asks for every cache line of the node or leaf block `code` names (a leaf block's lines
/// from `leaves`, of type Leaf) without a branch on which it is: rays taking turns visit
/// nodes and leaves in no predictable order, and a branch here was mispredicted twice per R2
/// ray (callgrind --branch-sim, a quarter of the walk's mispredictions). The address and
/// the line offsets are selected by a mask; a leaf block shorter than a node asks for its
/// last line again instead of a line past it.
template <class Leaf> inline void prefetch_visit(const BvhNode8* nodes, const Leaf* leaves, uint32_t code) {
  constexpr std::size_t kLine = 64, kNodeLines = sizeof(BvhNode8) / kLine;
  constexpr std::size_t kLeafLast = (sizeof(Leaf) - 1) / kLine * kLine;
  const uintptr_t leaf = uintptr_t(0) - uintptr_t(code >> 31);  // all ones for a leaf block
  const uintptr_t index = code & ~kLeafBit;
  const uintptr_t at = ((reinterpret_cast<uintptr_t>(nodes) + index * sizeof(BvhNode8)) & ~leaf) |
                       ((reinterpret_cast<uintptr_t>(leaves) + index * sizeof(Leaf)) & leaf);
  for (std::size_t k = 0; k < kNodeLines; ++k) {
    const uintptr_t node_off = k * kLine, leaf_off = k * kLine < kLeafLast ? k * kLine : kLeafLast;
    __builtin_prefetch(reinterpret_cast<const char*>(at + ((node_off & ~leaf) | (leaf_off & leaf))));
  }
}

// Trivial, so a build's resize() writes nothing and its parallel fill, which writes every
// byte of every node and leaf block (padding included: there is none), first-touches them.
static_assert(std::is_trivially_default_constructible_v<BvhNode8> && sizeof(BvhNode8) == 256);
static_assert(std::is_trivially_default_constructible_v<BvhLeaf4> && sizeof(BvhLeaf4) == 192);

struct Bvh8 {
  DefaultInitVector<BvhNode8> nodes;  ///< nodes[0] is the root
  DefaultInitVector<BvhLeaf4> leaves;
  AABB bounds;
  BvhStats stats;
};

/// The most items a leaf block of a BVH over boxes (a scene's models) holds: one. Each
/// model's own box is then tested in its parent's 8-wide lane before the model itself. With
/// up to four per block (blocks of a quarter of the SAH cost) R1's rays ran 6.98 Mrays/s,
/// with two 8.06-8.23, with one 8.5-9.0 (one thread, AVX-512): a block's box around four
/// spheres is entered far more often than any of them is hit. The price is three times the
/// nodes: a build of R1's 10^4 spheres 2.4 -> 3.6 ms, a refit after a tenth of them moved
/// 0.09-0.10 -> 0.16-0.20 ms (gyro-bench R1M).
inline constexpr uint32_t kBoxBvhLeafItems = 1;

/// A leaf block of a BVH over boxes: up to kBoxBvhLeafItems item indices, kNoItem in the
/// others.
struct BvhItems {
  uint32_t item[kBoxBvhLeafItems];
};

/// A BVH over boxes: nodes as Bvh8's, leaves holding item indices (the input order).
struct BoxBvh8 {
  DefaultInitVector<BvhNode8> nodes;  ///< nodes[0] is the root (all slots empty when there are no boxes)
  DefaultInitVector<BvhItems> leaves;
  AABB bounds;
  BvhStats stats;
};

/// An item's box for build_box_bvh8: finite corners with lo <= hi on every axis.
struct BvhBox {
  float lo[3];
  float hi[3];
};

/// A union of boxes given by float corners, starting empty (+inf, -inf), for code that fills
/// or refits 8-wide nodes outside the builder (whose own boxes are SIMD vectors).
struct BoxUnion {
  float lo[3] = {__builtin_inff(), __builtin_inff(), __builtin_inff()};
  float hi[3] = {-__builtin_inff(), -__builtin_inff(), -__builtin_inff()};
  void grow(const float l[3], const float h[3]) {
    for (int a = 0; a < 3; ++a) lo[a] = l[a] < lo[a] ? l[a] : lo[a], hi[a] = hi[a] < h[a] ? h[a] : hi[a];
  }
  /// Half the surface area in double, as the builder's SAH cost counts it (0 when empty).
  double half_area() const {
    if (!(lo[0] <= hi[0])) return 0.0;
    const double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

/// The expected cost of a random ray through a tree with these half areas (the nodes' boxes
/// and the leaf blocks', in index order, node 0 the root): every node and leaf block tested
/// with the probability of its area over the root's (the areas summed in a fixed order,
/// nodes first, then divided by the root's). The build's
/// BvhStats::sah_cost and a refit's (bvh_refit.hpp) both come from here.
double sah_cost(const double* node_area, std::size_t nodes, const double* leaf_area, std::size_t leaves);

/// A node whose slots are all empty: bounds (+inf, -inf), which no slab test enters.
BvhNode8 empty_node8();
/// Sets node.order from its children's bounds (the builder's rule: for each octant, the slots
/// by their centres along its diagonal, ties in slot order, empty slots last).
void set_child_orders(BvhNode8& node);
/// Whether node.order is exactly what set_child_orders() would write for its bounds.
bool child_orders_hold(const BvhNode8& node);

/// Builds the BVH of a valid mesh (binned SAH over triangle centroids, then collapsed from
/// binary to 8-wide). Deterministic: depends only on the mesh's values.
Bvh8 build_bvh8(const MeshData& mesh);

/// Builds a BVH over boxes[0..count) with the same binned SAH and collapse (a box's
/// centroid is the middle of its corners). Deterministic: depends only on the values.
BoxBvh8 build_box_bvh8(const BvhBox* boxes, std::size_t count);

}  // namespace gyro::detail
