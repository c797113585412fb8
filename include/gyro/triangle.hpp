// Triangles (Cookbook chapter 10): point tests, closest point, barycentric coordinates,
// overlap with every 3D primitive, and a watertight raycast.
//
// Conventions (beyond gyro/shapes.hpp's):
//  - Touching counts as overlapping; every overlaps() is symmetric (both argument orders
//    give the same answer).
//  - Degenerate triangles: a triangle whose corners are collinear or coincident to float
//    precision (sin^2 of its angle at a at most 2^-36, an angle under about 3.8e-6 rad:
//    |(b - a) x (c - a)|^2 <= 2^-36 |b - a|^2 |c - a|^2) is treated as the segment, or
//    point, it collapses to: closest_point() and contains() use that segment, overlaps()
//    tests it, barycentric() documents its own answer. Every function uses this one rule.
//  - Sizes (edge lengths) are expected in about [1e-9, 1e9] (fourth powers of the size are
//    formed); coordinates anywhere. Far from the origin the tests lose nothing beyond the
//    inputs' own precision: they work on differences of nearby coordinates.
//  - NaN or infinite inputs never crash; the answer is then unspecified.
//  - These are the same templates the batch kernels run (src/geometry/triangle_lanes.hpp,
//    src/geometry/ray_triangle_lanes.hpp): a batch call gives the same bits as these.
#pragma once

#include "gyro/shapes.hpp"

namespace gyro {

/// True when p is on the triangle: its distance to the triangle (to closest_point()) is at
/// most 1e-5 * (the largest side of the triangle's bounding box) + 2^-20 * (the largest
/// |coordinate| of the corners and p). The first term is the plane and edge tolerance; the
/// second allows for the 8 to 16 ulp that a point computed from the corners (a raycast hit,
/// an interpolation) carries far from the origin.
bool contains(const Triangle& t, const vec3& p);

/// The point of the triangle nearest to p (Ericson's Voronoi regions). A degenerate
/// triangle gives the nearest point of the segment or point it collapses to.
vec3 closest_point(const Triangle& t, const vec3& p);

/// Barycentric coordinates (u, v, w) of p's projection on the triangle's plane:
/// u a + v b + w c is that projection, u + v + w = 1 (w and v are computed, u = 1 - v - w),
/// and all three are >= 0 exactly when the projection is inside. Degenerate triangle: the
/// coordinates of p's projection on the line of its longest edge (ab, then ac, then bc on
/// ties), with 0 for the corner off that edge; all corners coincident: (1, 0, 0).
vec3 barycentric(const vec3& p, const Triangle& t);

/// Triangle and sphere overlap: the closest point of the triangle is within the radius.
bool overlaps(const Triangle& t, const Sphere& s);
/// Same as overlaps(t, s).
bool overlaps(const Sphere& s, const Triangle& t);

/// Triangle and AABB overlap: separating axes (3 box faces, the triangle normal, 9 box axis
/// x edge products with the book's fallback axis for an edge parallel to a box axis).
bool overlaps(const Triangle& t, const AABB& b);
/// Same as overlaps(t, b).
bool overlaps(const AABB& b, const Triangle& t);

/// Triangle and OBB overlap: the AABB test in the box's frame.
bool overlaps(const Triangle& t, const OBB& b);
/// Same as overlaps(t, b).
bool overlaps(const OBB& b, const Triangle& t);

/// Triangle and plane overlap: the corners are not all strictly on one side.
bool overlaps(const Triangle& t, const Plane& p);
/// Same as overlaps(t, p).
bool overlaps(const Plane& p, const Triangle& t);

/// Triangle and triangle overlap: separating axes (both normals, the 9 edge x edge products
/// with the book's fallback for parallel edges, the 6 in-plane edge normals that coplanar
/// triangles need, and for degenerate triangles the axes a segment or point needs).
bool overlaps(const Triangle& a, const Triangle& b);

/// Watertight, double-sided raycast (Woop, Benthin, Wald, JCGT 2013): the hit with t >= 0
/// (t in units of |direction|; a ray crosses a triangle at most once). A ray through an
/// edge or vertex shared by triangles of a mesh hits at least one of them (it may hit
/// both when it passes within rounding of the edge). The normal is the unit geometric
/// normal facing the ray's origin side. When barycentric is given it receives the weights
/// (u, v, w) of a, b, c at the hit (point ~ u a + v b + w c), or zero on a miss. A zero
/// direction hits nothing, nor does a triangle seen exactly edge-on. A degenerate triangle
/// is hit only where the ray passes within rounding of its segment; t is then between its
/// corners' depths and the normal is -direction / |direction|.
RaycastResult raycast(const Triangle& t, const Ray& ray, vec3* barycentric = nullptr);

/// True when the segment meets the triangle (the raycast from start towards end hits with
/// t in [0, 1]). A zero-length segment is its point: contains(t, line.start).
bool linetest(const Triangle& t, const Line& line);

}  // namespace gyro
