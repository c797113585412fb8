// quat: unit quaternions for orientation (not in the Cookbook, which keeps orientations as
// Euler angles and matrices; gyro's rigid bodies store quaternions).
//
// Conventions:
//  - quat{x, y, z, w} with w the scalar part; quat{} is the identity (0, 0, 0, 1).
//  - from_axis_angle(axis, a) = (axis * sin(a/2), cos(a/2)) rotates by a radians about axis
//    by the right-hand rule, exactly like rotation3_axis_angle in math_transform.hpp.
//  - a * b is Hamilton's product, so rotate(a * b, v) == rotate(a, rotate(b, v)): b applies
//    first. Row-vector matrices compose the other way round, so
//    to_mat3(a * b) == to_mat3(b) * to_mat3(a); to_mat3(q) is the row-vector matrix
//    (v * to_mat3(q) == rotate(q, v)), the transpose of the column-vector textbook one.
//  - Functions that rotate (rotate, to_mat3, to_mat4) assume a unit quaternion and do not
//    renormalise; normalize after accumulating products.
//  - Angles in radians; trigonometry is gyro's own (deterministic); sums in component order.
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_scalar.hpp"
#include "gyro/math_trig.hpp"
#include "gyro/math_vec.hpp"

#include <cmath>
#include <type_traits>

namespace gyro {

/// A quaternion x i + y j + z k + w; unit ones are rotations.
struct quat {
  float x = 0.0f, y = 0.0f, z = 0.0f, w = 1.0f;  ///< vector part x, y, z; scalar part w
  /// Exact per-component equality (q and -q are the same rotation but not ==).
  constexpr bool operator==(const quat&) const = default;
  /// The identity rotation (also what quat{} is).
  static constexpr quat identity() { return {}; }
};

static_assert(sizeof(quat) == 16 && std::is_standard_layout_v<quat> && std::is_trivially_copyable_v<quat>);

/// No component is NaN or infinite.
inline bool is_finite(const quat& q) { return is_finite(vec4{q.x, q.y, q.z, q.w}); }

/// Hamilton's product a * b: the rotation b followed by the rotation a.
constexpr quat operator*(const quat& a, const quat& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
/// a = a * b.
constexpr quat& operator*=(quat& a, const quat& b) { return a = a * b; }
/// Every component times s.
constexpr quat operator*(const quat& q, float s) { return {q.x * s, q.y * s, q.z * s, q.w * s}; }
/// Every component times s.
constexpr quat operator*(float s, const quat& q) { return q * s; }
/// Component-wise sum (for blending; the sum of rotations is not a rotation).
constexpr quat operator+(const quat& a, const quat& b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
/// Component-wise difference.
constexpr quat operator-(const quat& a, const quat& b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
/// Negation: the same rotation, from the other hemisphere.
constexpr quat operator-(const quat& q) { return {-q.x, -q.y, -q.z, -q.w}; }

/// The 4D dot product, summed x, y, z, w; |dot| is the cosine of half the angle between
/// two unit rotations.
constexpr float dot(const quat& a, const quat& b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
/// dot(q, q).
constexpr float length_squared(const quat& q) { return dot(q, q); }
/// sqrt(dot(q, q)).
inline float length(const quat& q) { return std::sqrt(dot(q, q)); }
/// (-x, -y, -z, w): the inverse of a unit quaternion.
constexpr quat conjugate(const quat& q) { return {-q.x, -q.y, -q.z, q.w}; }
/// conjugate(q) / dot(q, q), component by component; the zero quaternion has no inverse and
/// gives the zero quaternion.
constexpr quat inverse(const quat& q) {
  const float n = dot(q, q);
  if (n == 0.0f) return {0.0f, 0.0f, 0.0f, 0.0f};
  return {-q.x / n, -q.y / n, -q.z / n, q.w / n};
}
/// q divided by its length (with normalized(vec4)'s rescaling of tiny and huge values).
/// The zero quaternion gives the identity: an orientation must stay a rotation.
inline quat normalized(const quat& q) {
  const vec4 v = normalized(vec4{q.x, q.y, q.z, q.w});
  if (v == vec4{}) return quat::identity();
  return {v.x, v.y, v.z, v.w};
}
/// q = normalized(q).
inline void normalize(quat& q) { q = normalized(q); }

/// The rotation by angle radians about axis (right-hand rule). axis need not be unit
/// length; a zero axis gives the identity.
inline quat from_axis_angle(const vec3& axis, float angle) {
  const vec3 n = normalized(axis);
  if (n == vec3{}) return quat::identity();
  float s, c;
  gyro::sincos(angle * 0.5f, &s, &c);
  return {n.x * s, n.y * s, n.z * s, c};
}

/// The rotation of the book's Euler angles (radians): roll about z first, then pitch about
/// x, then yaw about y, i.e. from_y(yaw) * from_x(pitch) * from_z(roll); to_mat3 of it is
/// rotation3_euler(pitch, yaw, roll) = Rz(roll) * Rx(pitch) * Ry(yaw).
inline quat from_euler(float pitch, float yaw, float roll) {
  float sp, cp, sy, cy, sr, cr;
  gyro::sincos(pitch * 0.5f, &sp, &cp);
  gyro::sincos(yaw * 0.5f, &sy, &cy);
  gyro::sincos(roll * 0.5f, &sr, &cr);
  return quat{0.0f, sy, 0.0f, cy} * quat{sp, 0.0f, 0.0f, cp} * quat{0.0f, 0.0f, sr, cr};
}

/// The row-vector rotation matrix of a unit q: v * to_mat3(q) == rotate(q, v).
constexpr mat3 to_mat3(const quat& q) {
  const float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {{{1.0f - 2.0f * (yy + zz), 2.0f * (xy + wz), 2.0f * (xz - wy)},
           {2.0f * (xy - wz), 1.0f - 2.0f * (xx + zz), 2.0f * (yz + wx)},
           {2.0f * (xz + wy), 2.0f * (yz - wx), 1.0f - 2.0f * (xx + yy)}}};
}
/// to_mat3(q) as a 4x4 transform with no translation.
constexpr mat4 to_mat4(const quat& q) { return to_mat4(to_mat3(q)); }

/// v rotated by a unit q, q v q*, computed as v + w t + u x t with u = (x, y, z) and
/// t = 2 u x v (two cross products instead of two quaternion products).
constexpr vec3 rotate(const quat& q, const vec3& v) {
  const vec3 u{q.x, q.y, q.z};
  const vec3 t = cross(u, v) * 2.0f;
  return v + t * q.w + cross(u, t);
}

/// Normalised linear interpolation from a (t = 0) towards b (t = 1) along the shorter arc
/// (b is negated when dot(a, b) < 0). Cheap, unit length, but not constant angular speed.
inline quat nlerp(const quat& a, const quat& b, float t) {
  const quat e = dot(a, b) < 0.0f ? -b : b;
  return normalized(a + (e - a) * t);
}

/// Spherical linear interpolation along the shorter arc at constant angular speed. The
/// result is a at t = 0 and b (or -b, the same rotation, if dot(a, b) < 0) at t = 1,
/// exactly unless the two are within about 3.6 degrees (|dot| > 0.9995), where nlerp is
/// used because sin(theta) in the denominator loses its precision.
inline quat slerp(const quat& a, const quat& b, float t) {
  float d = dot(a, b);
  quat e = b;
  if (d < 0.0f) d = -d, e = -b;
  if (d > 0.9995f) return normalized(a + (e - a) * t);
  const float theta = gyro::acos(d);
  const float s = gyro::sin(theta);
  const float wa = gyro::sin((1.0f - t) * theta) / s;
  const float we = gyro::sin(t * theta) / s;
  return a * wa + e * we;
}

/// One explicit step of dq/dt = 0.5 (omega, 0) * q for a world-space angular velocity omega
/// (rad/s) over dt seconds, then normalised: q + 0.5 dt (omega, 0) * q. For constant omega
/// the axis is exact and each step turns by 2 atan(|omega| dt / 2) instead of |omega| dt.
inline quat integrate(const quat& q, const vec3& omega, float dt) {
  const quat spin = quat{omega.x, omega.y, omega.z, 0.0f} * q;
  const float h = 0.5f * dt;
  return normalized(q + spin * h);
}

/// Every component nearly_equal(a, b, eps) (q and -q are not near each other).
inline bool nearly_equal(const quat& a, const quat& b, float eps = kEpsilon) {
  return nearly_equal(vec4{a.x, a.y, a.z, a.w}, vec4{b.x, b.y, b.z, b.w}, eps);
}

}  // namespace gyro
