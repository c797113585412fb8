// Cameras, projection, unprojection and picking (Cookbook chapters 12-13).
//
// Conventions (those of gyro/math_transform.hpp):
//  - Row vectors, world = local * M. A camera's world transform has its right, up and
//    forward axes as rows 0-2 and its position as row 3; view space is look_at's
//    left-handed one: the camera looks down +z, +x is to its right, +y up. The view matrix
//    is the inverse of the world transform.
//  - Projections map the view volume to clip space with x, y in [-1, 1] and depth z/w in
//    [0, 1] (Direct3D / Vulkan): the near plane goes to depth 0, the far plane to 1.
//  - Screen and viewport points are in pixels with the origin at the top-left corner and
//    y growing DOWN; they are continuous coordinates, so the centre of pixel (i, j) is
//    (i + 0.5, j + 0.5) and the viewport covers [0, width] x [0, height]. A viewport point
//    carries the depth as z in [0, 1].
//  - Angles are radians; all trigonometry is gyro's own (gyro/math_trig.hpp), so every
//    function here gives the same bits on every CPU and compiler.
//  - Functions that return a matrix or a ray expect a valid camera (check_camera); for an
//    invalid one they return NaN or meaningless values but never crash.
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_scalar.hpp"
#include "gyro/math_vec.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstdint>

namespace gyro {

/// How a camera projects: with perspective (a pyramid of vision) or orthographically (a box).
enum class ProjectionMode : uint32_t {
  perspective = 0,   ///< uses fov_y and aspect
  orthographic = 1,  ///< uses width and height
};

/// A camera: a rigid world transform (position and orientation) and a projection.
struct Camera {
  vec3 position;     ///< the eye, in world space
  /// Rows: the camera's right, up and forward axes in world space (view +x, +y, +z). Kept
  /// as given; view_matrix() re-orthonormalises it on every call, so a drifting rotation
  /// never skews the view. The default (identity) looks down world +z with +y up.
  mat3 orientation;
  ProjectionMode mode = ProjectionMode::perspective;  ///< which of the parameters below apply
  float fov_y = kPi / 3.0f;  ///< perspective: vertical field of view in radians, in (0, pi)
  float aspect = 1.0f;       ///< perspective: viewport width / height, > 0
  float width = 2.0f;        ///< orthographic: width of the view volume in world units, > 0
  float height = 2.0f;       ///< orthographic: height of the view volume in world units, > 0
  float z_near = 0.1f;       ///< distance to the near plane: 0 < z_near < z_far (orthographic: any z_near < z_far)
  float z_far = 1000.0f;     ///< distance to the far plane
};

/// A perspective camera at the origin looking down +z.
Camera perspective_camera(float fov_y, float aspect, float z_near, float z_far);
/// An orthographic camera at the origin looking down +z, seeing width x height world units.
Camera orthographic_camera(float width, float height, float z_near, float z_far);

/// Status::ok for a usable camera; otherwise non_finite (a NaN or infinite field) or
/// invalid_argument (fov_y outside (0, pi), aspect, width or height <= 0, z_near >= z_far,
/// z_near <= 0 for a perspective camera, a zero forward axis, an unknown mode), with the
/// detail in last_error().
Status check_camera(const Camera& camera);

/// Places the camera at eye looking at target, with up (not parallel to target - eye) in
/// the upper half of the view: afterwards view_matrix(camera) equals look_at(eye, target,
/// up) up to rounding. The projection is unchanged.
void set_look_at(Camera& camera, const vec3& eye, const vec3& target, const vec3& up);

/// The nearest rotation to a drifted one, by Gram-Schmidt with the forward axis (row 2)
/// kept: forward normalised, right = up x forward normalised, up = forward x right. If up is
/// (nearly) parallel to forward the old right axis is used instead, and if that fails too
/// a world axis; a zero forward becomes +z. The result is orthonormal with determinant +1.
mat3 orthonormalized(const mat3& orientation);

/// The camera's world transform: rows right, up, forward (orthonormalised) and position.
mat4 world_matrix(const Camera& camera);
/// The view matrix: the rigid inverse of world_matrix() (transposed rotation, -position
/// times it); world space to view space.
mat4 view_matrix(const Camera& camera);
/// perspective(fov_y, aspect, z_near, z_far) or orthographic(-width/2, width/2, -height/2,
/// height/2, z_near, z_far) of gyro/math_transform.hpp.
mat4 projection_matrix(const Camera& camera);
/// view_matrix(camera) * projection_matrix(camera): world space to clip space.
mat4 view_projection_matrix(const Camera& camera);

/// A camera that orbits a target (the Cookbook's OrbitCamera), for editors and viewers.
/// Yaw turns about world +y (0: the camera looks along +z; pi/2: along +x), pitch tilts
/// it (positive: the camera is above the target looking down). Its orientation is
/// rotation3_euler(pitch, yaw, 0) and its eye is target - distance * forward.
struct OrbitCamera {
  vec3 target;               ///< the point looked at
  float distance = 10.0f;    ///< from the eye to the target, in [min_distance, max_distance]
  float yaw = 0.0f;          ///< radians, kept in about [-pi, pi]
  float pitch = 0.0f;        ///< radians, kept in [-max_pitch, max_pitch]
  float max_pitch = 1.48352986f;  ///< 85 degrees: in [0, pi/2), so the view never flips over the pole
  float min_distance = 0.1f;      ///< zoom limits, 0 < min_distance <= max_distance
  float max_distance = 1000.0f;
};

/// Turns the orbit: yaw += delta_yaw (wrapped into about [-pi, pi]), pitch += delta_pitch
/// clamped to [-max_pitch, max_pitch]. Returns non_finite for a NaN or infinite delta and
/// invalid_argument for an orbit whose limits are out of range; then nothing changes.
Status orbit_rotate(OrbitCamera& orbit, float delta_yaw, float delta_pitch);
/// Moves the eye towards (negative delta) or away from the target: distance += delta,
/// clamped to [min_distance, max_distance]. Statuses as orbit_rotate.
Status orbit_zoom(OrbitCamera& orbit, float delta_distance);
/// Slides the target (and so the eye) along the camera's right and up axes by the given
/// world distances. Statuses as orbit_rotate.
Status orbit_pan(OrbitCamera& orbit, float right, float up);
/// Where the orbit puts the eye.
vec3 orbit_eye(const OrbitCamera& orbit);
/// A camera with the orbit's position and orientation and the projection of lens.
Camera orbit_camera(const OrbitCamera& orbit, const Camera& lens);

/// The world point that a viewport point (pixels from the top-left, y down; z = depth in
/// [0, 1]) came from, through the viewport [origin, origin + size] and the given matrices:
/// the pixel goes to clip space, through inverse(projection) (then divided by w) and
/// inverse(view) (the book's Unproject). If either matrix is singular, or size has a zero
/// component, the result is NaN.
vec3 unproject(const vec3& viewport_point, const vec2& viewport_origin, const vec2& viewport_size, const mat4& view,
               const mat4& projection);
/// The inverse of unproject: where a world point lands in the viewport (pixels from the
/// top-left, y down) and at what depth (z; in [0, 1] between the near and far planes). A
/// point with clip w = 0 (in the eye's plane) gives infinities or NaN.
vec3 project(const vec3& world_point, const vec2& viewport_origin, const vec2& viewport_size, const mat4& view,
             const mat4& projection);

/// The ray under a screen point (pixels from the top-left corner, y down, of a viewport of
/// viewport_size pixels that the camera fills): it starts where the pixel meets the near
/// plane and its unit direction points to where it meets the far plane. So the ray through
/// the centre of the screen is the camera's forward axis, through a corner it runs along a
/// frustum edge, and for an orthographic camera every ray is parallel to forward.
Ray picking_ray(const Camera& camera, vec2 screen_point, vec2 viewport_size);

}  // namespace gyro
