// A triangle mesh with its bounding volume hierarchy, ready for queries (Cookbook chapter 11,
// rebuilt as a modern ray tracer's acceleration structure).
//
// The BVH is built with binned SAH and stored as 8-wide nodes (the eight children's bounds as
// structure of arrays, tested against a ray in one SIMD operation) over triangles copied in
// leaf order into compact SoA leaves of up to four. Queries run the same watertight, double-
// sided triangle test as gyro/triangle.hpp, so:
//  - a closest-hit raycast returns exactly the brute-force answer: the smallest t in
//    [tmin, tmax] over all triangles, ties going to the lowest triangle index (input order).
//    The traversal is conservative (the slab test's bounds are widened by a few ulps, Ize's
//    robust traversal), so no triangle the brute-force test hits is ever culled;
//  - results are bit-identical at every SIMD level and thread count, and whatever order the
//    traversal visits nodes in.
// The mesh is immutable after create(); it may be queried from many threads at once.
#pragma once

#include "gyro/batch_raycast.hpp"
#include "gyro/mesh.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace gyro {

/// Shape of a built BVH, for benchmarks and tests.
struct BvhStats {
  std::size_t nodes = 0;       ///< interior nodes (8 children in a mesh, 4 in a scene)
  std::size_t leaves = 0;      ///< leaf blocks of up to 4 triangles
  std::size_t max_depth = 0;   ///< in interior nodes, root = 1
  std::size_t bytes = 0;       ///< nodes, leaf triangles and index map
  double sah_cost = 0.0;       ///< expected cost (node tests + triangle tests) of a random ray
};

/// The closest hit of one ray, or hit = false.
struct MeshHit {
  RaycastResult hit;       ///< t, point, unit normal facing the ray's origin side
  uint32_t triangle = 0;   ///< index in the input mesh (valid when hit.hit)
  float u = 0.0f, v = 0.0f;  ///< barycentric weights of corners b and c (a's is 1 - u - v)
};

/// hits.primitive value of a ray the mesh and scene queries cannot answer.
inline constexpr int32_t kRayInvalid = -2;

class TriangleMesh {
 public:
  TriangleMesh();
  ~TriangleMesh();
  TriangleMesh(TriangleMesh&&) noexcept;
  TriangleMesh& operator=(TriangleMesh&&) noexcept;

  /// Validates the mesh (gyro/mesh.hpp's rules) and builds its BVH. On failure `out` is left
  /// unchanged. The build is deterministic: the same mesh gives the same BVH bit for bit.
  static Status create(const MeshData& mesh, TriangleMesh& out);

  bool empty() const { return impl_ == nullptr; }
  std::size_t triangle_count() const;
  /// The vertices and indices it was created from (empty for a mesh never created).
  const MeshData& data() const;
  /// Corners of triangle i in input order.
  Triangle triangle(std::size_t i) const;
  AABB bounds() const;
  BvhStats stats() const;
  /// The number of triangles whose bounds (the box of their corners) touch `box`, closed
  /// (touching counts), with box's corners as aabb_min(box) and aabb_max(box) round them;
  /// writes the smallest min(count, capacity) of their indices to out in ascending order, so
  /// the answer is the brute-force one whatever the tree's shape. No allocation. A mesh that
  /// was never created, or a box with a NaN, gives 0.
  std::size_t triangles_overlapping(const AABB& box, uint32_t* out, std::size_t capacity) const;

  struct Impl;
  const Impl* impl() const { return impl_.get(); }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Closest hit with t in [tmin, tmax] (t in units of |direction|).
MeshHit raycast(const TriangleMesh& mesh, const Ray& ray, float tmin = 0.0f, float tmax = __builtin_inff());
/// True when some triangle is hit with t in [tmin, tmax] (stops at the first found).
bool raycast_any(const TriangleMesh& mesh, const Ray& ray, float tmin = 0.0f, float tmax = __builtin_inff());
/// True when the segment touches a triangle of the mesh.
bool linetest(const TriangleMesh& mesh, const Line& line);

/// True when some triangle of the mesh touches the shape (gyro/triangle.hpp's tests).
bool overlaps(const TriangleMesh& mesh, const Sphere& sphere);
bool overlaps(const TriangleMesh& mesh, const AABB& box);
bool overlaps(const TriangleMesh& mesh, const OBB& box);
bool overlaps(const TriangleMesh& mesh, const Triangle& triangle);

/// Batch closest hit: hits.primitive[i] is the triangle index (input order), -1 for a miss,
/// or kRayInvalid for a ray the query cannot answer (a NaN or infinite coordinate, a zero
/// direction, tmin NaN, infinite or negative, tmax NaN or below tmin): such a ray gets
/// t = +infinity and zero normal and barycentrics, and the other rays are answered. Null
/// arrays, counts of 2^31 or more and a mesh that was never created fail the call (nothing
/// written). Parallel over fixed chunks of rays; bit-identical at every SIMD level and
/// thread count.
Status raycast_closest(const TriangleMesh& mesh, const RaysView& rays, std::size_t ray_count, const HitsOut& hits);
/// Batch any hit: primitive[i] is some triangle hit in range (the first one the traversal
/// finds, the same at every level and thread count), -1 or kRayInvalid; t is that hit's t.
Status raycast_any(const TriangleMesh& mesh, const RaysView& rays, std::size_t ray_count, const HitsOut& hits);

}  // namespace gyro
