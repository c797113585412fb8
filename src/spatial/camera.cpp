// gyro/camera.hpp: camera matrices, the orbit controller, project / unproject and the
// picking ray. Plain float math from gyro/math*.hpp (its own trigonometry, + - * / and sqrt
// in a fixed order), so every result is bit-identical across CPUs and compilers.
#include "gyro/camera.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/math_transform.hpp"

#include <cmath>
#include <limits>

namespace gyro {
namespace {

using detail::fail;


vec3 row3(const mat3& m, int r) { return {m.m[r][0], m.m[r][1], m.m[r][2]}; }

// A unit vector perpendicular to the unit f: f crossed with the world axis least aligned
// with it (that axis is never within 54 degrees of f, so the cross product is well sized).
vec3 any_perpendicular(const vec3& f) {
  const vec3 a = std::abs(f.x) <= std::abs(f.y) && std::abs(f.x) <= std::abs(f.z) ? vec3{1.0f, 0.0f, 0.0f}
                 : std::abs(f.y) <= std::abs(f.z)                                 ? vec3{0.0f, 1.0f, 0.0f}
                                                                                  : vec3{0.0f, 0.0f, 1.0f};
  return normalized(cross(a, f));
}

// |a x b|^2 small against |a|^2 |b|^2: the vectors are too close to parallel (within about
// 1e-3 radians) for their cross product to define a direction well.
bool nearly_parallel(const vec3& a, const vec3& b) {
  return !(length_squared(cross(a, b)) > 1e-6f * (length_squared(a) * length_squared(b)));
}

Status check_orbit(const OrbitCamera& o) {
  if (!gyro::is_finite(o.target) || !detail::is_finite(o.distance) || !detail::is_finite(o.yaw) || !detail::is_finite(o.pitch))
    return fail(Status::non_finite, "orbit: target, distance, yaw and pitch must be finite");
  if (!(o.max_pitch >= 0.0f && o.max_pitch < kHalfPi))
    return fail(Status::invalid_argument, "orbit.max_pitch = %g: must be in [0, pi/2)", double(o.max_pitch));
  if (!(o.min_distance > 0.0f && o.min_distance <= o.max_distance && detail::is_finite(o.max_distance)))
    return fail(Status::invalid_argument, "orbit distance limits [%g, %g]: need 0 < min_distance <= max_distance",
                double(o.min_distance), double(o.max_distance));
  return Status::ok;
}

Status check_deltas(float a, float b) {
  if (!detail::is_finite(a) || !detail::is_finite(b))
    return fail(Status::non_finite, "orbit delta (%g, %g) is not finite", double(a), double(b));
  return Status::ok;
}

mat3 orbit_orientation(const OrbitCamera& o) { return rotation3_euler(o.pitch, o.yaw, 0.0f); }

// vec4{p, w} * m.
vec4 times(const vec3& p, float w, const mat4& m) { return vec4{p.x, p.y, p.z, w} * m; }

}  // namespace

Camera perspective_camera(float fov_y, float aspect, float z_near, float z_far) {
  Camera c;
  c.mode = ProjectionMode::perspective;
  c.fov_y = fov_y, c.aspect = aspect, c.z_near = z_near, c.z_far = z_far;
  return c;
}

Camera orthographic_camera(float width, float height, float z_near, float z_far) {
  Camera c;
  c.mode = ProjectionMode::orthographic;
  c.width = width, c.height = height, c.z_near = z_near, c.z_far = z_far;
  return c;
}

Status check_camera(const Camera& c) {
  if (!gyro::is_finite(c.position)) return fail(Status::non_finite, "camera.position is not finite");
  for (int r = 0; r < 3; ++r)
    if (!gyro::is_finite(row3(c.orientation, r))) return fail(Status::non_finite, "camera.orientation row %d is not finite", r);
  if (row3(c.orientation, 2) == vec3{}) return fail(Status::invalid_argument, "camera.orientation: the forward axis is zero");
  if (!detail::is_finite(c.z_near) || !detail::is_finite(c.z_far))
    return fail(Status::non_finite, "camera z_near = %g, z_far = %g: must be finite", double(c.z_near), double(c.z_far));
  if (!(c.z_near < c.z_far))
    return fail(Status::invalid_argument, "camera z_near = %g, z_far = %g: need z_near < z_far", double(c.z_near),
                double(c.z_far));
  switch (c.mode) {
    case ProjectionMode::perspective:
      if (!(c.fov_y > 0.0f && c.fov_y < kPi))
        return fail(Status::invalid_argument, "camera.fov_y = %g: must be in (0, pi) radians", double(c.fov_y));
      if (!(c.aspect > 0.0f) || !detail::is_finite(c.aspect))
        return fail(Status::invalid_argument, "camera.aspect = %g: must be finite and > 0", double(c.aspect));
      if (!(c.z_near > 0.0f))
        return fail(Status::invalid_argument, "camera.z_near = %g: a perspective camera needs z_near > 0", double(c.z_near));
      return Status::ok;
    case ProjectionMode::orthographic:
      if (!(c.width > 0.0f && c.height > 0.0f) || !detail::is_finite(c.width) || !detail::is_finite(c.height))
        return fail(Status::invalid_argument, "camera width = %g, height = %g: must be finite and > 0", double(c.width),
                    double(c.height));
      return Status::ok;
  }
  return fail(Status::invalid_argument, "camera.mode = %u is not a projection mode", unsigned(c.mode));
}

void set_look_at(Camera& camera, const vec3& eye, const vec3& target, const vec3& up) {
  // The rows of look_at's rotation, transposed back: they are the camera's axes in world space.
  const vec3 f = normalized(target - eye);
  const vec3 r = normalized(cross(up, f));
  const vec3 u = cross(f, r);
  camera.position = eye;
  camera.orientation = from_rows(r, u, f);
}

mat3 orthonormalized(const mat3& o) {
  vec3 f = normalized(row3(o, 2));
  if (f == vec3{}) f = {0.0f, 0.0f, 1.0f};
  const vec3 up = row3(o, 1), right = row3(o, 0);
  vec3 r;
  if (!nearly_parallel(up, f)) {
    r = normalized(cross(up, f));
  } else if (!nearly_parallel(right, f)) {
    r = normalized(right - f * dot(right, f));
  } else {
    r = any_perpendicular(f);
  }
  return from_rows(r, cross(f, r), f);
}

mat4 world_matrix(const Camera& camera) {
  return detail::compose_trs({1.0f, 1.0f, 1.0f}, orthonormalized(camera.orientation), camera.position);
}

mat4 view_matrix(const Camera& camera) { return inverse_rigid(world_matrix(camera)); }

mat4 projection_matrix(const Camera& c) {
  if (c.mode == ProjectionMode::orthographic) {
    const float hw = c.width * 0.5f, hh = c.height * 0.5f;
    return orthographic(-hw, hw, -hh, hh, c.z_near, c.z_far);
  }
  return perspective(c.fov_y, c.aspect, c.z_near, c.z_far);
}

mat4 view_projection_matrix(const Camera& camera) { return view_matrix(camera) * projection_matrix(camera); }

Status orbit_rotate(OrbitCamera& o, float delta_yaw, float delta_pitch) {
  GYRO_TRY(check_orbit(o));
  GYRO_TRY(check_deltas(delta_yaw, delta_pitch));
  float yaw = o.yaw + delta_yaw;
  // Wrap into [-pi, pi) by whole turns (one floor, not a loop: a huge delta costs nothing);
  // gyro's sin and cos are most accurate there.
  if (!(yaw >= -kPi && yaw < kPi)) yaw = yaw - kTwoPi * std::floor((yaw + kPi) / kTwoPi);
  o.yaw = yaw;
  o.pitch = clamp(o.pitch + delta_pitch, -o.max_pitch, o.max_pitch);
  return Status::ok;
}

Status orbit_zoom(OrbitCamera& o, float delta_distance) {
  GYRO_TRY(check_orbit(o));
  GYRO_TRY(check_deltas(delta_distance, 0.0f));
  o.distance = clamp(o.distance + delta_distance, o.min_distance, o.max_distance);
  return Status::ok;
}

Status orbit_pan(OrbitCamera& o, float right, float up) {
  GYRO_TRY(check_orbit(o));
  GYRO_TRY(check_deltas(right, up));
  const mat3 r = orbit_orientation(o);
  o.target = o.target + row3(r, 0) * right + row3(r, 1) * up;
  return Status::ok;
}

vec3 orbit_eye(const OrbitCamera& o) { return o.target - row3(orbit_orientation(o), 2) * o.distance; }

Camera orbit_camera(const OrbitCamera& orbit, const Camera& lens) {
  Camera c = lens;
  c.orientation = orbit_orientation(orbit);
  c.position = orbit.target - row3(c.orientation, 2) * orbit.distance;
  return c;
}

vec3 unproject(const vec3& viewport_point, const vec2& viewport_origin, const vec2& viewport_size, const mat4& view,
               const mat4& projection) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  mat4 inv_projection, inv_view;
  if (!(viewport_size.x != 0.0f && viewport_size.y != 0.0f)) return {nan, nan, nan};
  if (!inverse(projection, &inv_projection) || !inverse(view, &inv_view)) return {nan, nan, nan};
  // Pixels (y down) to normalised device coordinates (y up); the depth is already clip z/w.
  const float nx = (viewport_point.x - viewport_origin.x) / viewport_size.x;
  const float ny = (viewport_point.y - viewport_origin.y) / viewport_size.y;
  const vec3 ndc{nx * 2.0f - 1.0f, 1.0f - ny * 2.0f, viewport_point.z};
  const vec4 eye = times(ndc, 1.0f, inv_projection);
  const vec4 world = times(vec3{eye.x / eye.w, eye.y / eye.w, eye.z / eye.w}, 1.0f, inv_view);
  return {world.x / world.w, world.y / world.w, world.z / world.w};
}

vec3 project(const vec3& world_point, const vec2& viewport_origin, const vec2& viewport_size, const mat4& view,
             const mat4& projection) {
  const vec4 v = times(world_point, 1.0f, view);
  const vec4 clip = times(vec3{v.x / v.w, v.y / v.w, v.z / v.w}, 1.0f, projection);
  const vec3 ndc{clip.x / clip.w, clip.y / clip.w, clip.z / clip.w};
  return {viewport_origin.x + (ndc.x + 1.0f) * 0.5f * viewport_size.x,
          viewport_origin.y + (1.0f - ndc.y) * 0.5f * viewport_size.y, ndc.z};
}

Ray picking_ray(const Camera& camera, vec2 screen_point, vec2 viewport_size) {
  const mat4 view = view_matrix(camera), projection = projection_matrix(camera);
  const vec2 origin{0.0f, 0.0f};
  const vec3 near_point = unproject({screen_point.x, screen_point.y, 0.0f}, origin, viewport_size, view, projection);
  const vec3 far_point = unproject({screen_point.x, screen_point.y, 1.0f}, origin, viewport_size, view, projection);
  return make_ray(near_point, far_point - near_point);
}

}  // namespace gyro
