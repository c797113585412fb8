// Static colliders shared by particles and soft bodies: what a point moving along a segment
// can hit (spheres, boxes, oriented boxes, planes, capsules, convex hulls), the first
// entering crossing and the push-out of a point caught inside a solid. Deterministic:
// gyro's raycasts and + - * / sqrt in a fixed order.
#pragma once

#include "core/state_hash.hpp"
#include "gyro/convex.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstdint>

namespace gyro::detail {

enum class ColliderKind : uint32_t { none = 0, sphere = 1, aabb = 2, obb = 3, plane = 4, capsule = 5, hull = 6 };

/// A capsule in the world: the points within radius of the segment a-b (a == b: a sphere).
struct CapsuleCollider {
  vec3 a, b;
  float radius = 0.0f;
};

/// A convex hull placed in the world with the OBB convention: world = local * rotation +
/// position, rows of rotation = the hull's local axes (orthonormal). The hull (vertices and
/// planes in its own frame) is not owned and must outlive the collider. margin >= 0 moves
/// every face plane out (a mitred inflation, sharp corners kept): it is how a particle's
/// thickness is added, as a sphere's radius grows.
struct HullCollider {
  const ConvexHull* hull = nullptr;
  vec3 position;
  mat3 rotation;
  float margin = 0.0f;
};

/// One collider; only the member named by kind is used. sphere, aabb, obb and plane stay
/// default when unused, so the hash of a collider is a function of its kind and shape alone;
/// capsule and hull share storage (a union: the collider grows by one hull, not by both).
struct Collider {
  Collider() : capsule{} {}  // the union needs a member to start with
  ColliderKind kind = ColliderKind::none;
  Sphere sphere;
  AABB aabb;
  OBB obb;
  Plane plane;
  union {
    CapsuleCollider capsule;
    HullCollider hull;
  };
};

inline constexpr float kSkin = 1e-3f;             // m left between a stopped point and the surface ...
inline constexpr float kSkinRelative = 0x1p-16f;  // ... plus this fraction of its largest coordinate (>> raycast error)

float max_abs3(const vec3& v);
inline float skin_at(const vec3& p) { return kSkin + max_abs3(p) * kSkinRelative; }

/// The first entering crossing of the segment s -> s + d with collider c: t in [0, 1] (units
/// of |d|) and the outward normal; exits (the segment leaving a solid) do not count.
/// Capsule: the first entry into the union of the two end spheres and the side (a segment
/// that starts strictly inside the capsule has no hit). Hull: Cyrus-Beck clipping against the
/// face planes moved out by the margin; the normal is the plane that clips last (ties to
/// the lowest face index). A segment starting strictly inside has no hit; one starting on the
/// surface and moving in hits at t = 0; one parallel to a face plane and outside it never
/// hits (a grazing segment lying in a face plane can only hit a neighbouring face).
bool first_hit(const Collider& c, const vec3& s, const vec3& d, float* t, vec3* point, vec3* normal);

/// If p is strictly inside collider c (behind it, for a plane), the point `extra` plus the
/// skin outside the closest surface (and that surface's normal in *normal when given);
/// otherwise p. Box faces: the shallowest, ties to the lower axis, then the positive side.
/// Capsule: along the line from the closest point of the segment (a point on the segment
/// itself goes along a fixed direction perpendicular to it: the cross product of the axis with
/// the world axis it is least aligned with; +y for a point capsule). Hull: out through the
/// least-penetrated face plane (moved out by the margin), ties to the lowest face index.
vec3 push_out(const Collider& c, const vec3& p, float extra = 0.0f, vec3* normal = nullptr);

/// An axis-aligned box around c (planes: unbounded, reported by returning false). Hulls: the
/// rotated box of the vertices, exact with no margin; with a margin it is that box scaled
/// about the vertex average by 1 + margin / (that point's distance to the nearest face),
/// which contains the mitred corners however sharp (false if that distance is not > 0).
bool collider_bounds(const Collider& c, vec3* lo, vec3* hi);

/// c grown by t >= 0: sphere and capsule radii, box half extents, hull margin grow by t; a
/// plane moves out by t. Soft bodies add their thickness this way.
Collider inflated(const Collider& c, float t);

/// Checks a shape and makes it a collider (sizes >= 0, finite; an OBB's orientation
/// orthonormal to 1e-3; a plane's normal non-zero, normalised with its distance). On failure
/// *out is untouched and gyro::last_error() says why.
Status to_collider(const Sphere& sphere, Collider* out);
Status to_collider(const AABB& box, Collider* out);
Status to_collider(const OBB& box, Collider* out);
Status to_collider(const Plane& plane, Collider* out);
/// Capsule: finite, radius >= 0.
Status to_collider(const CapsuleCollider& capsule, Collider* out);
/// Hull: non-null with at least 4 faces and vertices, finite pose, rotation orthonormal to
/// 1e-3, margin finite and >= 0.
Status to_collider(const HullCollider& hull, Collider* out);

/// The kind and shape; a hull adds its pose, margin, vertices and planes (never its address).
/// Sphere, box and plane colliders hash as they did before capsules and hulls existed.
void hash_collider(const Collider& c, StateHasher& h);

}  // namespace gyro::detail
