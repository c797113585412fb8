// Static colliders shared by particles and soft bodies: what a point moving along a segment
// can hit (spheres, boxes, oriented boxes, planes), the first entering crossing and the
// push-out of a point caught inside a solid. Deterministic: gyro's raycasts and + - * / sqrt.
#pragma once

#include "core/state_hash.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstdint>

namespace gyro::detail {

enum class ColliderKind : uint32_t { none = 0, sphere = 1, aabb = 2, obb = 3, plane = 4 };

/// One collider; only the member named by kind is used (the others stay default so the hash
/// of a collider is a function of its kind and shape alone).
struct Collider {
  ColliderKind kind = ColliderKind::none;
  Sphere sphere;
  AABB aabb;
  OBB obb;
  Plane plane;
};

inline constexpr float kSkin = 1e-3f;             // m left between a stopped point and the surface ...
inline constexpr float kSkinRelative = 0x1p-16f;  // ... plus this fraction of its largest coordinate (>> raycast error)

float max_abs3(const vec3& v);
inline float skin_at(const vec3& p) { return kSkin + max_abs3(p) * kSkinRelative; }

/// The first entering crossing of the segment s -> s + d with collider c: t in [0, 1] (units
/// of |d|) and the outward normal; exits (the segment leaving a solid) do not count.
bool first_hit(const Collider& c, const vec3& s, const vec3& d, float* t, vec3* point, vec3* normal);

/// If p is strictly inside collider c (behind it, for a plane), the point `extra` plus the
/// skin outside the closest surface (and that surface's normal in *normal when given);
/// otherwise p. Box faces: the shallowest, ties to the lower axis, then the positive side.
vec3 push_out(const Collider& c, const vec3& p, float extra = 0.0f, vec3* normal = nullptr);

/// An axis-aligned box around c (planes: unbounded, reported by returning false).
bool collider_bounds(const Collider& c, vec3* lo, vec3* hi);

/// Checks a shape and makes it a collider (sizes >= 0, finite; an OBB's orientation
/// orthonormal to 1e-3; a plane's normal non-zero, normalised with its distance). On failure
/// *out is untouched and gyro::last_error() says why.
Status to_collider(const Sphere& sphere, Collider* out);
Status to_collider(const AABB& box, Collider* out);
Status to_collider(const OBB& box, Collider* out);
Status to_collider(const Plane& plane, Collider* out);

void hash_collider(const Collider& c, StateHasher& h);

}  // namespace gyro::detail
