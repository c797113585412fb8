// The C ABI over the C++ API: argument translation, and no exception ever crosses it.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"

#include <new>

namespace {

using gyro::Status;

template <class F> gyro_status guarded(F&& f) noexcept {
  try {
    return static_cast<gyro_status>(f());
  } catch (const std::bad_alloc&) {
    return static_cast<gyro_status>(gyro::detail::fail(Status::out_of_memory, "out of memory"));
  } catch (...) {
    return static_cast<gyro_status>(gyro::detail::fail(Status::internal, "unexpected exception"));
  }
}

Status check_count(int32_t n, const char* name) {
  return n < 0 ? gyro::detail::fail(Status::invalid_count, "%s = %d is negative", name, n) : Status::ok;
}

}  // namespace

extern "C" {

GYRO_API uint32_t gyro_abi_version(void) { return GYRO_ABI_VERSION; }
GYRO_API const char* gyro_version_string(void) { return GYRO_VERSION_STRING; }

GYRO_API uint32_t gyro_features(void) {
  uint32_t f = GYRO_FEATURE_MATH;
  if (gyro::has_threads()) f |= GYRO_FEATURE_OPENMP;
  using gyro::SimdLevel;
  if (gyro::simd_level_built(SimdLevel::sse2)) f |= GYRO_FEATURE_SIMD_SSE2;
  if (gyro::simd_level_built(SimdLevel::avx2)) f |= GYRO_FEATURE_SIMD_AVX2;
  if (gyro::simd_level_built(SimdLevel::avx512)) f |= GYRO_FEATURE_SIMD_AVX512;
  if (gyro::simd_level_built(SimdLevel::neon)) f |= GYRO_FEATURE_SIMD_NEON;
#if defined(GYRO_HAS_GEOMETRY)
  f |= GYRO_FEATURE_GEOMETRY;
#endif
  return f;
}

GYRO_API const char* gyro_last_error(void) { return gyro::last_error(); }
GYRO_API const char* gyro_status_name(gyro_status status) {
  if (status < 0 || status > GYRO_STATUS_INTERNAL) return "unknown_status";
  return gyro::status_name(static_cast<Status>(status));
}

GYRO_API gyro_status gyro_set_simd_level(gyro_simd_level level) {
  return guarded([&] { return gyro::set_simd_level(static_cast<gyro::SimdLevel>(level)); });
}
GYRO_API gyro_simd_level gyro_get_simd_level(void) { return static_cast<gyro_simd_level>(gyro::simd_level()); }
GYRO_API uint32_t gyro_simd_level_available(gyro_simd_level level) {
  return gyro::simd_level_available(static_cast<gyro::SimdLevel>(level)) ? 1u : 0u;
}
GYRO_API const char* gyro_simd_level_name(gyro_simd_level level) {
  return gyro::simd_level_name(static_cast<gyro::SimdLevel>(level));
}

GYRO_API gyro_status gyro_set_thread_count(uint32_t threads) {
  return guarded([&] { return gyro::set_thread_count(threads); });
}
GYRO_API uint32_t gyro_get_thread_count(void) { return gyro::thread_count(); }

GYRO_API gyro_status gyro_raycast_spheres_closest(const gyro_ray_soa* rays, int32_t ray_count,
                                                  const gyro_sphere_soa* spheres, int32_t sphere_count,
                                                  const gyro_hit_soa* hits) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(ray_count, "ray_count"));
    GYRO_TRY(check_count(sphere_count, "sphere_count"));
    if (!rays) return gyro::detail::fail(Status::null_argument, "rays is null");
    if (!spheres) return gyro::detail::fail(Status::null_argument, "spheres is null");
    if (!hits) return gyro::detail::fail(Status::null_argument, "hits is null");
    const gyro::RaysView r{rays->ox, rays->oy, rays->oz, rays->dx, rays->dy, rays->dz, rays->tmin, rays->tmax};
    const gyro::SpheresView s{spheres->cx, spheres->cy, spheres->cz, spheres->r};
    const gyro::HitsOut h{hits->t, hits->primitive, hits->nx, hits->ny, hits->nz};
    return gyro::raycast_spheres_closest(r, static_cast<std::size_t>(ray_count), s,
                                         static_cast<std::size_t>(sphere_count), h);
  });
}

}  // extern "C"
