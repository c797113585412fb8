// The C ABI over the C++ API: argument translation, and no exception ever crosses it.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_support.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"
#include "gyro/runtime.hpp"

#include <bit>
#include <cstring>
#include <new>

namespace {

using gyro::Status;
using gyro::capi::check_count;
using gyro::capi::guarded;
using gyro::capi::view_of;

gyro::ShapeArray shape_array_of(const gyro_shape_soa& s) {
  gyro::ShapeArray a;
  a.type = static_cast<gyro::ShapeType>(s.type);
  switch (s.type) {
    case GYRO_SHAPE_SPHERE: a.spheres = view_of<gyro::SpheresView>(s.as.sphere); break;
    case GYRO_SHAPE_AABB: a.aabbs = view_of<gyro::AabbsView>(s.as.aabb); break;
    case GYRO_SHAPE_OBB: a.obbs = view_of<gyro::ObbsView>(s.as.obb); break;
    case GYRO_SHAPE_PLANE: a.planes = view_of<gyro::PlanesView>(s.as.plane); break;
    case GYRO_SHAPE_TRIANGLE: a.triangles = view_of<gyro::TrianglesView>(s.as.triangle); break;
    default: break;  // rejected by the call with invalid_argument
  }
  return a;
}

Status check_shapes(const gyro_shape_soa* s, const char* name) {
  if (!s) return gyro::detail::fail(Status::null_argument, "%s is null", name);
  if (s->reserved != 0) return gyro::detail::fail(Status::invalid_argument, "%s->reserved must be 0", name);
  return Status::ok;
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
#if defined(GYRO_HAS_2D)
  f |= GYRO_FEATURE_2D;
#endif
#if defined(GYRO_HAS_SPATIAL)
  f |= GYRO_FEATURE_SPATIAL;
#endif
#if defined(GYRO_HAS_DYNAMICS)
  f |= GYRO_FEATURE_DYNAMICS | GYRO_FEATURE_SOFT_BODIES;
#endif
#if defined(GYRO_HAS_GEOMETRY) && defined(GYRO_HAS_DYNAMICS)
  // The convex calls (capi/gyro_capi_convex.cpp) are built with the dynamics module, which
  // brings geometry; hull and capsule bodies need the world as well.
  f |= GYRO_FEATURE_CONVEX;
#endif
#if defined(GYRO_HAS_DYNAMICS)
  f |= GYRO_FEATURE_SNAPSHOT;
  f |= GYRO_FEATURE_REPLAY;
#endif
  return f;
}

GYRO_API const char* gyro_last_error(void) { return gyro::last_error(); }
GYRO_API const char* gyro_status_name(gyro_status status) {
  if (status < 0 || status > GYRO_STATUS_CORRUPT_DATA) return "unknown_status";
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

// Shared by the three raycast entry points.
static gyro_status raycast(const gyro_ray_soa* rays, int32_t ray_count, const gyro_shape_soa* prims, int32_t prim_count,
                           const gyro_hit_soa* hits, bool any) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(ray_count, "ray_count"));
    GYRO_TRY(check_count(prim_count, "prim_count"));
    if (!rays) return gyro::detail::fail(Status::null_argument, "rays is null");
    GYRO_TRY(check_shapes(prims, "prims"));
    if (!hits) return gyro::detail::fail(Status::null_argument, "hits is null");
    const gyro::RaysView r = view_of<gyro::RaysView>(*rays);
    const gyro::HitsOut h = view_of<gyro::HitsOut>(*hits);
    const auto n = static_cast<std::size_t>(ray_count), m = static_cast<std::size_t>(prim_count);
    return any ? gyro::raycast_any(r, n, shape_array_of(*prims), m, h)
               : gyro::raycast_closest(r, n, shape_array_of(*prims), m, h);
  });
}

GYRO_API gyro_status gyro_raycast_closest(const gyro_ray_soa* rays, int32_t ray_count, const gyro_shape_soa* prims,
                                          int32_t prim_count, const gyro_hit_soa* hits) {
  return raycast(rays, ray_count, prims, prim_count, hits, false);
}

GYRO_API gyro_status gyro_raycast_any(const gyro_ray_soa* rays, int32_t ray_count, const gyro_shape_soa* prims,
                                      int32_t prim_count, const gyro_hit_soa* hits) {
  return raycast(rays, ray_count, prims, prim_count, hits, true);
}

GYRO_API gyro_status gyro_raycast_spheres_closest(const gyro_ray_soa* rays, int32_t ray_count,
                                                  const gyro_sphere_soa* spheres, int32_t sphere_count,
                                                  const gyro_hit_soa* hits) {
  if (!spheres) {
    gyro::detail::fail(Status::null_argument, "spheres is null");
    return GYRO_STATUS_NULL_ARGUMENT;
  }
  gyro_shape_soa prims;
  std::memset(&prims, 0, sizeof prims);
  prims.type = GYRO_SHAPE_SPHERE;
  prims.as.sphere = *spheres;
  return raycast(rays, ray_count, &prims, sphere_count, hits, false);
}

GYRO_API gyro_status gyro_overlap_pairwise(const gyro_shape_soa* a, const gyro_shape_soa* b, int32_t count,
                                           uint32_t* out, uint32_t flags) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(count, "count"));
    GYRO_TRY(check_shapes(a, "a"));
    GYRO_TRY(check_shapes(b, "b"));
    return gyro::overlap_pairwise(shape_array_of(*a), shape_array_of(*b), static_cast<std::size_t>(count), out, flags);
  });
}

GYRO_API gyro_status gyro_overlap_one_against_many(const gyro_shape_soa* one, const gyro_shape_soa* many,
                                                   int32_t count, uint32_t* out, uint32_t flags) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(count, "count"));
    GYRO_TRY(check_shapes(one, "one"));
    GYRO_TRY(check_shapes(many, "many"));
    return gyro::overlap_one_against_many(shape_array_of(*one), shape_array_of(*many), static_cast<std::size_t>(count),
                                          out, flags);
  });
}

GYRO_API gyro_status gyro_obb_separation_pairwise(const gyro_obb_soa* a, const gyro_obb_soa* b, int32_t count,
                                                  float* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(count, "count"));
    if (!a || !b) return gyro::detail::fail(Status::null_argument, "%s is null", a ? "b" : "a");
    return gyro::obb_separation_pairwise(view_of<gyro::ObbsView>(*a), view_of<gyro::ObbsView>(*b),
                                         static_cast<std::size_t>(count), out);
  });
}

}  // extern "C"
