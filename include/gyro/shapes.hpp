// The 3D primitives of Cookbook chapters 7-10, as plain data.
//
// Conventions:
//  - Ray: o + t d for t >= 0. d need not be unit length: every t gyro returns is in units
//    of |d| (so a unit d gives distances). make_ray() normalises, as the book's Ray does.
//  - Line: the segment from start to end (the book's Line); linetests are hits with t in [0, 1].
//  - AABB and OBB: a centre and half extents (the book's position and size). An OBB's
//    orientation is a rotation matrix whose rows are the box's local x, y, z axes (the
//    row-vector convention of gyro/math_mat.hpp: world = local * orientation + center).
//  - Plane: the points p with dot(normal, p) = distance; normal is unit length.
//  - Degenerate shapes are valid: a sphere of radius 0 is a point, a box with a zero half
//    extent is a rectangle, a triangle with collinear corners is a segment. Every function
//    gives them a defined answer.
//  - Touching counts as overlapping.
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_vec.hpp"

#include <cmath>
#include <cstdint>

namespace gyro {

/// A segment from start to end.
struct Line {
  vec3 start, end;
};

/// A ray from origin along direction (t in units of |direction|).
struct Ray {
  vec3 origin;
  vec3 direction{0.0f, 0.0f, 1.0f};
};

/// A ray with a unit direction (a zero direction stays zero: such a ray hits nothing).
inline Ray make_ray(const vec3& origin, const vec3& direction) { return {origin, normalized(direction)}; }

/// A ray from a to b, with t = 1 at b.
inline Ray ray_from_points(const vec3& a, const vec3& b) { return {a, b - a}; }

struct Sphere {
  vec3 center;
  float radius = 1.0f;
};

/// Axis-aligned box: center and half extents (>= 0).
struct AABB {
  vec3 center;
  vec3 half_extents{1.0f, 1.0f, 1.0f};
};

/// AABB from its minimum and maximum corners.
inline AABB aabb_from_min_max(const vec3& lo, const vec3& hi) { return {(lo + hi) * 0.5f, (hi - lo) * 0.5f}; }
inline vec3 aabb_min(const AABB& b) { return b.center - b.half_extents; }
inline vec3 aabb_max(const AABB& b) { return b.center + b.half_extents; }

/// Oriented box: center, half extents (>= 0) and a rotation whose rows are its axes.
struct OBB {
  vec3 center;
  vec3 half_extents{1.0f, 1.0f, 1.0f};
  mat3 orientation;
};

/// Half extents of the AABB around a box with these half extents and a rotation whose rows
/// are its axes (as OBB::orientation): sum over k of |row k| * half[k].
inline vec3 aabb_half_extents(const mat3& rows, const vec3& half) {
  vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = (std::abs(rows.m[0][c]) * half.x + std::abs(rows.m[1][c]) * half.y) + std::abs(rows.m[2][c]) * half.z;
  return out;
}

/// The points p with dot(normal, p) = distance.
struct Plane {
  vec3 normal{0.0f, 1.0f, 0.0f};
  float distance = 0.0f;
};

/// Plane through a point with a (not necessarily unit) normal.
inline Plane plane_from_point_normal(const vec3& point, const vec3& normal) {
  const vec3 n = normalized(normal);
  return {n, dot(n, point)};
}

struct Triangle {
  vec3 a, b, c;
};

/// Result of a raycast. When hit is false the other fields are zero.
struct RaycastResult {
  vec3 point;
  vec3 normal;   ///< unit, facing the ray's origin side for planes and triangles; outward for solids
  float t = 0.0f;
  bool hit = false;
};

}  // namespace gyro
