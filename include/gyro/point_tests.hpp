// Point tests of Cookbook chapter 8: is a point in a shape, which point of a shape is
// closest to it, and signed distances, for spheres, AABBs, OBBs, planes, segments (Line)
// and rays.
//
// Conventions (see also gyro/shapes.hpp):
//  - Spheres and boxes are solid and closed: a point inside or on the surface is contained,
//    and a point inside is its own closest point (the book's sphere returns the surface
//    point even for a point inside; gyro returns the nearest point of the solid, as it does
//    for boxes). Containment is exact in float: no tolerance.
//  - Planes, segments and rays are surfaces with no interior. contains() accepts a point
//    whose distance to them is at most max(kSurfaceAbsTolerance, kSurfaceRelTolerance * m),
//    m the largest coordinate magnitude among the point and the shape's defining values
//    (plane: |distance|; segment: start and end; ray: origin). This is the book's CMP
//    in the style of nearly_equal(a, b, abs_tol, rel_tol): absolute near the origin,
//    relative far from it, where float spacing grows. A point computed to lie on the
//    surface (closest_point, o + t d, a point rounded from the exact surface) passes;
//    one ten tolerances away does not.
//  - Degenerate shapes: a sphere of radius 0 is its centre; a box with zero half extents is
//    a rectangle, segment or point; a segment with start == end is a point; a ray with a
//    zero direction is its origin.
//  - The results are the bits gyro's batch kernels compute at every SIMD level (one lane
//    template, src/geometry/point_lanes.hpp). NaN inputs give a defined result (NaN
//    coordinates or false) and never trap; sizes must be >= 0 and OBB axes orthonormal.
#pragma once

#include "gyro/shapes.hpp"

namespace gyro {

/// The absolute part of the surface tolerance of contains() on planes, segments and rays.
inline constexpr float kSurfaceAbsTolerance = 1e-6f;
/// The relative part: per unit of the largest coordinate magnitude involved (about 17 ulp).
inline constexpr float kSurfaceRelTolerance = 1e-6f;

/// True if |point - center|^2 <= radius^2 (inside or on the surface).
bool contains(const Sphere& sphere, const vec3& point);
/// True if center - half_extents <= point <= center + half_extents on every axis (each
/// bound rounded once in float, the same bounds closest_point and overlaps use).
bool contains(const AABB& box, const vec3& point);
/// True if |dot(point - center, axis_i)| <= half_extents_i for the three axes.
bool contains(const OBB& box, const vec3& point);
/// True if |dot(normal, point) - distance| is within the surface tolerance (see above).
bool contains(const Plane& plane, const vec3& point);
/// True if the point's distance to the segment is within the surface tolerance.
bool contains(const Line& line, const vec3& point);
/// True if the point's distance to the ray (t >= 0) is within the surface tolerance.
bool contains(const Ray& ray, const vec3& point);

/// The point of the solid ball nearest to point: point itself when inside, else
/// center + (point - center) * radius / |point - center|. Valid for |point - center| up
/// to about 1e19 (the squared length overflows beyond).
vec3 closest_point(const Sphere& sphere, const vec3& point);
/// point clamped to the box (point itself when inside).
vec3 closest_point(const AABB& box, const vec3& point);
/// point itself when inside; else its coordinates along the box axes clamped to the half
/// extents, mapped back to world space.
vec3 closest_point(const OBB& box, const vec3& point);
/// The projection of point onto the plane along its normal, corrected once for the
/// rounding of a far point, so that contains(plane, result) holds.
vec3 closest_point(const Plane& plane, const vec3& point);
/// The point of the segment nearest to point: start or end (exactly) beyond them; start
/// for a zero-length segment.
vec3 closest_point(const Line& line, const vec3& point);
/// The point of the ray (t >= 0) nearest to point: the origin when point is behind it or
/// the direction is zero.
vec3 closest_point(const Ray& ray, const vec3& point);

/// dot(normal, point) - distance: positive on the side the normal points to.
float signed_distance(const Plane& plane, const vec3& point);
/// |point - center| - radius: negative inside.
float signed_distance(const Sphere& sphere, const vec3& point);

}  // namespace gyro
