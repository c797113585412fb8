// Transform, view and projection matrices of Cookbook chapter 3.
//
// Conventions (all of them the book's, which are DirectX's, unless a name ends in _rh):
//  - Row vectors on the left, v' = v * M, row-major storage (see math_mat.hpp). A transform
//    is scale * rotation * translation: scale first, then rotate, then translate, and the
//    translation sits in row 3.
//  - Angles are radians (the book's functions take degrees: convert with deg_to_rad).
//  - rotation_x/y/z(a) turn by a about that axis by the right-hand rule: rotation_z(pi/2)
//    takes +x to +y, rotation_x(pi/2) takes +y to +z, rotation_y(pi/2) takes +z to +x.
//    rotation_axis_angle and from_axis_angle (math_quat.hpp) agree with them.
//  - Euler angles are (pitch about x, yaw about y, roll about z) and apply roll first, then
//    pitch, then yaw: rotation_euler(p, y, r) = rotation_z(r) * rotation_x(p) * rotation_y(y).
//    As a vec3 they are (x = pitch, y = yaw, z = roll).
//  - View matrices: look_at is left-handed (the book's): the camera looks down +z, +x is to
//    its right, +y up. look_at_rh is right-handed (OpenGL's gluLookAt): the camera looks
//    down -z. Both map the eye to the origin and are rigid (inverse_rigid inverts them).
//  - Projection matrices map the view volume to x, y in [-1, 1] and depth z/w in [0, 1]
//    (Direct3D, Vulkan and Metal clip space, not OpenGL's [-1, 1]): the near plane goes to
//    depth 0 exactly and the far plane to 1 up to rounding. perspective and orthographic
//    expect left-handed view space (visible z in [near, far], w = z); the _rh variants
//    expect right-handed view space (visible z in [-far, -near], w = -z). The result is a
//    vec4: transform vec4{x, y, z, 1} * P and divide by w.
//  - Every function is deterministic: gyro's own sin/cos/tan, + - * / and sqrt only.
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/math_trig.hpp"
#include "gyro/math_vec.hpp"

namespace gyro {

/// The translation by t: identity with row 3 = (t, 1).
constexpr mat4 translation(const vec3& t) {
  return {{{1.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f, 0.0f}, {t.x, t.y, t.z, 1.0f}}};
}
/// The translation by (x, y, z).
constexpr mat4 translation(float x, float y, float z) { return translation(vec3{x, y, z}); }
/// Row 3 of an affine transform: where it takes the origin (the book's GetTranslation).
constexpr vec3 translation_of(const mat4& a) { return {a.m[3][0], a.m[3][1], a.m[3][2]}; }

/// The scale by s along x, y, z: diag(s, 1).
constexpr mat4 scale(const vec3& s) {
  return {{{s.x, 0.0f, 0.0f, 0.0f}, {0.0f, s.y, 0.0f, 0.0f}, {0.0f, 0.0f, s.z, 0.0f}, {0.0f, 0.0f, 0.0f, 1.0f}}};
}
/// The scale by (x, y, z).
constexpr mat4 scale(float x, float y, float z) { return scale(vec3{x, y, z}); }

/// Rotation by angle radians about +x: +y turns towards +z.
inline mat3 rotation3_x(float angle) {
  float s, c;
  gyro::sincos(angle, &s, &c);
  return {{{1.0f, 0.0f, 0.0f}, {0.0f, c, s}, {0.0f, -s, c}}};
}
/// Rotation by angle radians about +y: +z turns towards +x.
inline mat3 rotation3_y(float angle) {
  float s, c;
  gyro::sincos(angle, &s, &c);
  return {{{c, 0.0f, -s}, {0.0f, 1.0f, 0.0f}, {s, 0.0f, c}}};
}
/// Rotation by angle radians about +z: +x turns towards +y.
inline mat3 rotation3_z(float angle) {
  float s, c;
  gyro::sincos(angle, &s, &c);
  return {{{c, s, 0.0f}, {-s, c, 0.0f}, {0.0f, 0.0f, 1.0f}}};
}
/// rotation3_x as a 4x4 transform.
inline mat4 rotation_x(float angle) { return to_mat4(rotation3_x(angle)); }
/// rotation3_y as a 4x4 transform.
inline mat4 rotation_y(float angle) { return to_mat4(rotation3_y(angle)); }
/// rotation3_z as a 4x4 transform.
inline mat4 rotation_z(float angle) { return to_mat4(rotation3_z(angle)); }

/// The book's Euler rotation: roll (z) first, then pitch (x), then yaw (y), i.e.
/// rotation3_z(roll) * rotation3_x(pitch) * rotation3_y(yaw). to_mat3(from_euler(...)) is
/// the same rotation.
inline mat3 rotation3_euler(float pitch, float yaw, float roll) {
  return rotation3_z(roll) * rotation3_x(pitch) * rotation3_y(yaw);
}
/// rotation3_euler as a 4x4 transform.
inline mat4 rotation_euler(float pitch, float yaw, float roll) { return to_mat4(rotation3_euler(pitch, yaw, roll)); }

/// Rotation by angle radians about axis (right-hand rule; the book's AxisAngle, in row
/// vector form). axis need not be unit length; a zero axis gives the identity.
inline mat3 rotation3_axis_angle(const vec3& axis, float angle) {
  const vec3 n = normalized(axis);
  if (n == vec3{}) return mat3::identity();
  float s, c;
  gyro::sincos(angle, &s, &c);
  const float t = 1.0f - c;
  return {{{t * n.x * n.x + c, t * n.x * n.y + s * n.z, t * n.x * n.z - s * n.y},
           {t * n.x * n.y - s * n.z, t * n.y * n.y + c, t * n.y * n.z + s * n.x},
           {t * n.x * n.z + s * n.y, t * n.y * n.z - s * n.x, t * n.z * n.z + c}}};
}
/// rotation3_axis_angle as a 4x4 transform.
inline mat4 rotation_axis_angle(const vec3& axis, float angle) { return to_mat4(rotation3_axis_angle(axis, angle)); }

namespace detail {
/// scale(s) * to_mat4(r) * translation(t), built directly: row i of r times s_i, then t.
/// Equal (==) to the three products for finite inputs, because the terms the products add
/// are exact zeros.
constexpr mat4 compose_trs(const vec3& s, const mat3& r, const vec3& t) {
  return {{{s.x * r.m[0][0], s.x * r.m[0][1], s.x * r.m[0][2], 0.0f},
           {s.y * r.m[1][0], s.y * r.m[1][1], s.y * r.m[1][2], 0.0f},
           {s.z * r.m[2][0], s.z * r.m[2][1], s.z * r.m[2][2], 0.0f},
           {t.x, t.y, t.z, 1.0f}}};
}
}  // namespace detail

/// scale(s) * rotation_euler(euler.x, euler.y, euler.z) * translation(t): the book's
/// Transform with Euler angles (x = pitch, y = yaw, z = roll), in radians.
inline mat4 transform(const vec3& s, const vec3& euler, const vec3& t) {
  return detail::compose_trs(s, rotation3_euler(euler.x, euler.y, euler.z), t);
}
/// scale(s) * rotation_axis_angle(axis, angle) * translation(t).
inline mat4 transform(const vec3& s, const vec3& axis, float angle, const vec3& t) {
  return detail::compose_trs(s, rotation3_axis_angle(axis, angle), t);
}
/// scale(s) * to_mat4(q) * translation(t), for a unit q.
constexpr mat4 transform(const vec3& s, const quat& q, const vec3& t) { return detail::compose_trs(s, to_mat3(q), t); }

/// Left-handed view matrix (the book's LookAt): the eye goes to the origin, the target to
/// +z at its distance, and up (which must not be parallel to target - eye) to the +y half
/// of the yz plane. Rows 0-2 hold the camera's right, up and forward axes as columns.
inline mat4 look_at(const vec3& eye, const vec3& target, const vec3& up) {
  const vec3 f = normalized(target - eye);
  const vec3 r = normalized(cross(up, f));
  const vec3 u = cross(f, r);
  return {{{r.x, u.x, f.x, 0.0f},
           {r.y, u.y, f.y, 0.0f},
           {r.z, u.z, f.z, 0.0f},
           {-dot(r, eye), -dot(u, eye), -dot(f, eye), 1.0f}}};
}
/// Right-handed view matrix (gluLookAt's): the eye goes to the origin, the target to -z at
/// its distance, up to the +y half of the yz plane, and the camera's right to +x.
inline mat4 look_at_rh(const vec3& eye, const vec3& target, const vec3& up) {
  const vec3 b = normalized(eye - target);  // the camera's back axis, view +z
  const vec3 r = normalized(cross(up, b));
  const vec3 u = cross(b, r);
  return {{{r.x, u.x, b.x, 0.0f},
           {r.y, u.y, b.y, 0.0f},
           {r.z, u.z, b.z, 0.0f},
           {-dot(r, eye), -dot(u, eye), -dot(b, eye), 1.0f}}};
}

/// Left-handed perspective projection (the book's Projection): vertical field of view fovy
/// radians in (0, pi), aspect = width / height > 0, 0 < z_near < z_far. View z = z_near
/// goes to depth exactly 0, z = z_far to 1; w = view z.
inline mat4 perspective(float fovy, float aspect, float z_near, float z_far) {
  const float cot = 1.0f / gyro::tan(fovy * 0.5f);
  const float a = z_far / (z_far - z_near);
  return {{{cot / aspect, 0.0f, 0.0f, 0.0f},
           {0.0f, cot, 0.0f, 0.0f},
           {0.0f, 0.0f, a, 1.0f},
           {0.0f, 0.0f, -z_near * a, 0.0f}}};
}
/// Right-handed perspective projection with depth in [0, 1]: view z = -z_near goes to depth
/// exactly 0, z = -z_far to 1; w = -view z. Parameters as for perspective.
inline mat4 perspective_rh(float fovy, float aspect, float z_near, float z_far) {
  const float cot = 1.0f / gyro::tan(fovy * 0.5f);
  const float a = z_far / (z_near - z_far);
  return {{{cot / aspect, 0.0f, 0.0f, 0.0f},
           {0.0f, cot, 0.0f, 0.0f},
           {0.0f, 0.0f, a, -1.0f},
           {0.0f, 0.0f, z_near * a, 0.0f}}};
}

/// Left-handed orthographic projection (the book's Ortho): the box [left, right] x
/// [bottom, top] x [z_near, z_far] goes to [-1, 1]^2 x [0, 1], z_near to depth exactly 0.
/// Needs left != right, bottom != top, z_near != z_far.
inline mat4 orthographic(float left, float right, float bottom, float top, float z_near, float z_far) {
  const float d = 1.0f / (z_far - z_near);
  return {{{2.0f / (right - left), 0.0f, 0.0f, 0.0f},
           {0.0f, 2.0f / (top - bottom), 0.0f, 0.0f},
           {0.0f, 0.0f, d, 0.0f},
           {(left + right) / (left - right), (top + bottom) / (bottom - top), -z_near * d, 1.0f}}};
}
/// Right-handed orthographic projection with depth in [0, 1]: view z = -z_near goes to
/// depth exactly 0, z = -z_far to 1. Parameters as for orthographic.
inline mat4 orthographic_rh(float left, float right, float bottom, float top, float z_near, float z_far) {
  const float d = 1.0f / (z_near - z_far);
  return {{{2.0f / (right - left), 0.0f, 0.0f, 0.0f},
           {0.0f, 2.0f / (top - bottom), 0.0f, 0.0f},
           {0.0f, 0.0f, d, 0.0f},
           {(left + right) / (left - right), (top + bottom) / (bottom - top), z_near * d, 1.0f}}};
}

}  // namespace gyro
