// Raycasts and linetests against spheres, AABBs, OBBs and planes (Cookbook chapter 10).
//
// Conventions (see also gyro/shapes.hpp):
//  - A ray is o + t d with t in [tmin, tmax] (default [0, +inf)); d need not be unit
//    length, and t is in units of |d| (make_ray() gives a unit d, so t is a distance).
//  - The hit is the smallest t in [tmin, tmax] where the ray crosses the surface: a ray
//    that starts inside a solid reports where it leaves, with the outward normal there.
//    A ray starting on the surface hits it at t = 0 (touching counts).
//  - A ray whose |d|^2 is zero, subnormal or overflows float (|d| outside about
//    [1.1e-19, 1.8e19]) never hits.
//  - A plane is hit where the ray crosses it, from either side; its normal faces the
//    side the ray comes from. A ray parallel to the plane (dot(n, d) == 0 in float) never
//    hits, even one lying in it.
//  - Box normals are the face whose slab gave t; at an edge or corner the lowest axis
//    wins (x before y before z, the box's own axes for an OBB). A sphere of radius 0 (a
//    point) has no outward direction: its normal is -d / |d|.
//  - Rays along a box face (a zero or -0 component of d with the origin exactly on the
//    face's plane) touch the box: robust slabs, no NaN leaks into the answer.
//  - linetest(shape, line): true when the segment start-end touches the shape; for
//    solids a segment that starts or lies inside counts; a zero-length segment is the
//    point start. For a plane: the ends are not strictly on the same side.
//  - Accuracy, measured against binary64 on 10^5 random rays per shape (scales 1e-3 to
//    1e4, far from the origin; tests/geometry/raycast_test.cpp), with M the problem's
//    scale (|origin - centre| + size; |origin| + |distance| for planes):
//      * every answer is the exact answer of the problem moved by at most 16 ulps of M
//        (shape grown or shrunk, [tmin, tmax] moved, the ray moved or turned by a few
//        ulps): hit and miss differ from binary64 only that close to touching;
//      * where the ray crosses the surface at a healthy angle, |dt| |d| <= 2e-6 M (the
//        test's bound; measured 1.5e-7 to 7.1e-7); a grazing hit's t can legitimately
//        move along the surface by about sqrt(2^-24) times the sphere's size (measured
//        2e-4 M), or by (ulp of M) / cos on a flat face;
//      * linetests agree with binary64 except where the segment's depth in the shape
//        (or its distance to it) is below 1 ulp of M (measured 0.72 ulp).
//  - NaN inputs give some answer and never crash. The functions run in the caller's
//    floating-point environment (they are too small to pin it; the batch calls do).
//  - The same lane templates (src/geometry/ray_lanes.hpp) run in the batch kernels, so a
//    batch call gives these results bit for bit.
#pragma once

#include "gyro/shapes.hpp"

namespace gyro {

/// First crossing of the sphere's surface with t in [0, +inf).
RaycastResult raycast(const Sphere& sphere, const Ray& ray);
/// First crossing of the sphere's surface with t in [tmin, tmax].
RaycastResult raycast(const Sphere& sphere, const Ray& ray, float tmin, float tmax);
/// First crossing of the box's surface with t in [0, +inf).
RaycastResult raycast(const AABB& box, const Ray& ray);
/// First crossing of the box's surface with t in [tmin, tmax].
RaycastResult raycast(const AABB& box, const Ray& ray, float tmin, float tmax);
/// First crossing of the oriented box's surface with t in [0, +inf).
RaycastResult raycast(const OBB& box, const Ray& ray);
/// First crossing of the oriented box's surface with t in [tmin, tmax].
RaycastResult raycast(const OBB& box, const Ray& ray, float tmin, float tmax);
/// Where the ray crosses the plane, for t in [0, +inf); never for a parallel ray.
RaycastResult raycast(const Plane& plane, const Ray& ray);
/// Where the ray crosses the plane, for t in [tmin, tmax]; never for a parallel ray.
RaycastResult raycast(const Plane& plane, const Ray& ray, float tmin, float tmax);

/// The segment touches the sphere (closest point to the centre within the radius).
bool linetest(const Sphere& sphere, const Line& line);
/// The segment touches the box (robust slabs on t in [0, 1]).
bool linetest(const AABB& box, const Line& line);
/// The segment touches the oriented box (slabs in the box's frame).
bool linetest(const OBB& box, const Line& line);
/// The segment's ends are not strictly on the same side of the plane.
bool linetest(const Plane& plane, const Line& line);

}  // namespace gyro
