// Shared by the C ABI's implementation files: exception fence, count checks, view casts.
// Internal: never installed, never included by gyro.h users.
#pragma once

#include "gyro.h"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/math_vec.hpp"
#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"

#include <bit>
#include <cstddef>
#include <new>

namespace gyro::capi {

/// Runs f, turning any exception into a status: none crosses the C boundary.
template <class F> gyro_status guarded(F&& f) noexcept {
  try {
    return static_cast<gyro_status>(f());
  } catch (const std::bad_alloc&) {
    return static_cast<gyro_status>(detail::fail(Status::out_of_memory, "out of memory"));
  } catch (...) {
    return static_cast<gyro_status>(detail::fail(Status::internal, "unexpected exception"));
  }
}

inline Status check_count(int32_t n, const char* name) {
  return n < 0 ? detail::fail(Status::invalid_count, "%s = %d is negative", name, n) : Status::ok;
}

inline Status require(const void* p, const char* name) {
  return p ? Status::ok : detail::fail(Status::null_argument, "%s is null", name);
}

// Vectors cross the boundary by value; checks shared by the world and soft-body calls.
inline vec3 v3(gyro_vec3 v) { return {v.x, v.y, v.z}; }
inline gyro_vec3 c_v3(const vec3& v) { return {v.x, v.y, v.z}; }

inline Status check_finite(float v, const char* name) {
  return detail::is_finite(v) ? Status::ok : detail::fail(Status::non_finite, "%s = %g is not finite", name, double(v));
}
inline Status check_finite(gyro_vec3 v, const char* name) {
  if (detail::is_finite(v.x) && detail::is_finite(v.y) && detail::is_finite(v.z)) return Status::ok;
  return detail::fail(Status::non_finite, "%s has a NaN or infinite component", name);
}
inline Status check_bool(uint32_t v, const char* name) {
  return v <= 1 ? Status::ok : detail::fail(Status::invalid_argument, "%s = %u: booleans are 0 or 1", name, v);
}

// The C views have exactly the C++ views' layout (asserted below), so they convert by copy.
template <class To, class From> To view_of(const From& f) { return std::bit_cast<To>(f); }
// RaysView adds the per-ray masks after the C view's pointers (the scenes' masked calls
// take them separately, so gyro_ray_soa kept its layout): here every ray sees every layer.
template <> inline RaysView view_of<RaysView>(const gyro_ray_soa& r) {
  return {r.ox, r.oy, r.oz, r.dx, r.dy, r.dz, r.tmin, r.tmax, nullptr};
}
static_assert(sizeof(gyro_ray_soa) == offsetof(RaysView, mask) && sizeof(gyro_hit_soa) == sizeof(HitsOut));
static_assert(sizeof(gyro_sphere_soa) == sizeof(SpheresView) && sizeof(gyro_aabb_soa) == sizeof(AabbsView) &&
              sizeof(gyro_obb_soa) == sizeof(ObbsView) && sizeof(gyro_plane_soa) == sizeof(PlanesView) &&
              sizeof(gyro_triangle_soa) == sizeof(TrianglesView));

}  // namespace gyro::capi
