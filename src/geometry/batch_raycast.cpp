// gyro::raycast_closest / raycast_any: check the whole input, run the kernel over fixed
// chunks of rays, then fill the optional per-hit outputs (normal, barycentrics) with the
// scalar instantiation of the same templates, once per ray, whatever the level.
#include "gyro/batch_raycast.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/ray_lanes.hpp"
#include "geometry/ray_triangle_lanes.hpp"
#include "geometry/raycast_batch.hpp"
#include "geometry/shape_checks.hpp"

namespace gyro {
namespace {

using detail::fail;
using detail::require_not_null;
namespace lanes = GYRO_ARCH_NS;

constexpr std::size_t kMaxCount = 0x7FFFFFFF;
// Rays per chunk: a multiple of 16 so every SIMD level runs full batches inside a chunk.
constexpr std::size_t kRayChunk = 256;

// Normal and barycentrics of ray i's hit on primitive k at t (scalar: the same bits at every level).
void hit_details(const RaysView& rays, std::size_t i, const ShapeArray& p, std::size_t k, float t, float n[3],
                 float uv[2]) {
  const lanes::RayL<float> ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
  lanes::V3<float> normal{0.0f, 0.0f, 0.0f};
  uv[0] = uv[1] = 0.0f;
  switch (p.type) {
    case ShapeType::sphere: normal = lanes::ray_sphere_normal(ray, lanes::splat_sphere<float>(p.spheres, k), t); break;
    case ShapeType::aabb: normal = lanes::ray_aabb_normal(ray, lanes::splat_aabb<float>(p.aabbs, k), t); break;
    case ShapeType::obb: normal = lanes::ray_obb_normal(ray, lanes::splat_obb<float>(p.obbs, k), t); break;
    case ShapeType::plane: normal = lanes::ray_plane_normal(ray, lanes::splat_plane<float>(p.planes, k)); break;
    case ShapeType::triangle: {
      const auto tri = lanes::splat_triangle<float>(p.triangles, k);
      normal = lanes::triangle_normal_facing(tri, ray.d);
      // The template gives the weights of a, b, c; the API's u, v are those of b and c.
      float wa, wb, wc;
      lanes::ray_triangle_t(lanes::watertight_ray(ray), tri, 0.0f, __builtin_inff(), wa, wb, wc);
      uv[0] = wb, uv[1] = wc;
      break;
    }
  }
  n[0] = normal.x, n[1] = normal.y, n[2] = normal.z;
}

Status run(const RaysView& rays, std::size_t ray_count, const ShapeArray& prims, std::size_t prim_count,
           const HitsOut& hits, bool any_hit) {
  if (ray_count > kMaxCount || prim_count > kMaxCount)
    return fail(Status::invalid_count, "counts must be below 2^31 (rays %zu, primitives %zu)", ray_count, prim_count);
  if (ray_count == 0) return Status::ok;
  GYRO_TRY(require_not_null(hits.t, "hits.t"));
  GYRO_TRY(require_not_null(hits.primitive, "hits.primitive"));
  GYRO_TRY(detail::check_hit_columns(hits.nx, hits.ny, hits.nz, hits.u, hits.v));
  const bool normals = hits.nx != nullptr;  // all three, checked above
  GYRO_TRY(detail::check_rays(rays, ray_count));
  GYRO_TRY(detail::check_shape_array(prims, prim_count, "prims", true));

  detail::FloatEnvGuard env;
  const RaycastArgs args{rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz, rays.tmin, rays.tmax, prims,
                         prim_count, any_hit, hits.t, reinterpret_cast<uint32_t*>(hits.primitive)};
  auto* kernel = GYRO_DISPATCH(raycast_batch);
  const bool details = normals || hits.u != nullptr;
  detail::parallel_for(ray_count, kRayChunk, [&](std::size_t b, std::size_t e) {
    kernel(args, b, e);
    if (!details) return;
    for (std::size_t i = b; i < e; ++i) {
      float n[3] = {0.0f, 0.0f, 0.0f}, uv[2] = {0.0f, 0.0f};
      const int32_t k = hits.primitive[i];
      if (k >= 0) hit_details(rays, i, prims, std::size_t(k), hits.t[i], n, uv);
      if (normals) hits.nx[i] = n[0], hits.ny[i] = n[1], hits.nz[i] = n[2];
      if (hits.u) hits.u[i] = uv[0], hits.v[i] = uv[1];
    }
  });
  return Status::ok;
}

}  // namespace

Status raycast_closest(const RaysView& rays, std::size_t ray_count, const ShapeArray& prims, std::size_t prim_count,
                       const HitsOut& hits) {
  return run(rays, ray_count, prims, prim_count, hits, false);
}

Status raycast_any(const RaysView& rays, std::size_t ray_count, const ShapeArray& prims, std::size_t prim_count,
                   const HitsOut& hits) {
  return run(rays, ray_count, prims, prim_count, hits, true);
}

}  // namespace gyro
