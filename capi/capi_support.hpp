// Shared by the C ABI's implementation files: exception fence, count checks, view casts.
// Internal: never installed, never included by gyro.h users.
#pragma once

#include "gyro.h"

#include "core/error.hpp"
#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"

#include <bit>
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

// The C views have exactly the C++ views' layout (asserted below), so they convert by copy.
template <class To, class From> To view_of(const From& f) { return std::bit_cast<To>(f); }
static_assert(sizeof(gyro_ray_soa) == sizeof(RaysView) && sizeof(gyro_hit_soa) == sizeof(HitsOut));
static_assert(sizeof(gyro_sphere_soa) == sizeof(SpheresView) && sizeof(gyro_aabb_soa) == sizeof(AabbsView) &&
              sizeof(gyro_obb_soa) == sizeof(ObbsView) && sizeof(gyro_plane_soa) == sizeof(PlanesView) &&
              sizeof(gyro_triangle_soa) == sizeof(TrianglesView));

}  // namespace gyro::capi
