// Overlap tests of Cookbook chapter 9 between spheres, AABBs, OBBs and planes: every pair,
// each callable in both argument orders.
//
// Conventions (see also gyro/shapes.hpp and gyro/point_tests.hpp):
//  - Solids are closed and touching counts as overlapping: two unit spheres 2 apart overlap.
//    Planes are infinite surfaces; a solid overlaps a plane when it touches or crosses it.
//  - Exact in float unless stated: no tolerance, so which way a pair within rounding of
//    touching goes is decided by float rounding (identically on every CPU and SIMD level).
//    Where it is cheap the tests are arranged so that no rounding can contradict an exact
//    fact: a sphere whose centre a sphere, AABB or OBB contains (gyro/point_tests.hpp)
//    overlaps it, and so does an AABB whose centre another AABB contains (the sphere-box
//    distance is measured where a centre inside gives exactly 0, and AABBs are compared
//    through contains()'s rounded bounds); sphere-sphere, AABB-AABB and plane-plane give
//    the same bits in both argument orders.
//  - Boxes against boxes use the separating axis theorem (15 axes) with a slack of 1e-6
//    per unit of box size on every axis (src/geometry/obb_obb_lanes.hpp), so edge-edge
//    axes of nearly parallel edges cannot report a false separation: pairs within about
//    1e-6 * size of touching may be reported as overlapping, and for OBB-OBB such a pair may
//    depend on the argument order. AABB-OBB treats the AABB as the first box either way.
//  - Two planes overlap unless they are parallel and distinct: parallel means the sine of the
//    angle between the normals is at most kPlaneParallelSine; parallel planes coincide when
//    their distances (negated for opposite normals) agree within the surface tolerance of
//    gyro/point_tests.hpp relative to max(|d1|, |d2|).
//  - Degenerate shapes: a sphere of radius 0 is a point, a box with zero half extents a
//    rectangle, segment or point; each gets the answer of that point set. NaN inputs give
//    a defined result and never trap; sizes must be >= 0, OBB axes and plane normals unit.
//  - The results are the bits of gyro's batch kernels at every SIMD level (one lane
//    template per pair, src/geometry/overlap_lanes.hpp).
#pragma once

#include "gyro/shapes.hpp"

namespace gyro {

/// Planes whose normals make an angle with sine at most this are parallel (about 2e-4
/// degrees: float unit normals cannot resolve much less).
inline constexpr float kPlaneParallelSine = 1e-6f;

/// |ca - cb| <= ra + rb (compared squared).
bool overlaps(const Sphere& a, const Sphere& b);
/// The sphere's centre is within radius of the solid box.
bool overlaps(const Sphere& sphere, const AABB& box);
/// The sphere's centre is within radius of the solid box.
bool overlaps(const AABB& box, const Sphere& sphere);
/// The sphere's centre is within radius of the solid box (distance measured in its frame).
bool overlaps(const Sphere& sphere, const OBB& box);
/// The sphere's centre is within radius of the solid box (distance measured in its frame).
bool overlaps(const OBB& box, const Sphere& sphere);
/// |dot(normal, center) - distance| <= radius.
bool overlaps(const Sphere& sphere, const Plane& plane);
/// |dot(normal, center) - distance| <= radius.
bool overlaps(const Plane& plane, const Sphere& sphere);

/// The boxes' [min, max] intervals overlap on all three axes.
bool overlaps(const AABB& a, const AABB& b);
/// Separating axes (15, with the slack described above).
bool overlaps(const AABB& aabb, const OBB& obb);
/// Separating axes (15, with the slack described above).
bool overlaps(const OBB& obb, const AABB& aabb);
/// The box's projection radius onto the normal reaches the plane.
bool overlaps(const AABB& box, const Plane& plane);
/// The box's projection radius onto the normal reaches the plane.
bool overlaps(const Plane& plane, const AABB& box);

/// Separating axes (15, with the slack described above).
bool overlaps(const OBB& a, const OBB& b);
/// The box's projection radius onto the normal reaches the plane.
bool overlaps(const OBB& box, const Plane& plane);
/// The box's projection radius onto the normal reaches the plane.
bool overlaps(const Plane& plane, const OBB& box);

/// False only for parallel, distinct planes (tolerances above).
bool overlaps(const Plane& a, const Plane& b);

}  // namespace gyro
