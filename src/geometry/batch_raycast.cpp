// gyro::raycast_spheres_closest: checks the whole input, then runs the kernel over fixed
// chunks of rays on the configured SIMD level and threads.
#include "gyro/batch_raycast.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/ray_sphere.hpp"

#include <cmath>

namespace gyro {
namespace {

using detail::fail;
using detail::require_finite;
using detail::require_not_null;

constexpr std::size_t kMaxCount = 0x7FFFFFFF;
// Rays per chunk: a multiple of 16 so every SIMD level runs full batches inside a chunk.
constexpr std::size_t kRayChunk = 256;

Status check_rays(const RaysView& r, std::size_t n) {
  GYRO_TRY(require_not_null(r.ox, "rays.ox"));
  GYRO_TRY(require_not_null(r.oy, "rays.oy"));
  GYRO_TRY(require_not_null(r.oz, "rays.oz"));
  GYRO_TRY(require_not_null(r.dx, "rays.dx"));
  GYRO_TRY(require_not_null(r.dy, "rays.dy"));
  GYRO_TRY(require_not_null(r.dz, "rays.dz"));
  GYRO_TRY(require_finite(r.ox, n, "rays.ox"));
  GYRO_TRY(require_finite(r.oy, n, "rays.oy"));
  GYRO_TRY(require_finite(r.oz, n, "rays.oz"));
  GYRO_TRY(require_finite(r.dx, n, "rays.dx"));
  GYRO_TRY(require_finite(r.dy, n, "rays.dy"));
  GYRO_TRY(require_finite(r.dz, n, "rays.dz"));
  if (r.tmin) {
    for (std::size_t i = 0; i < n; ++i)
      if (!(r.tmin[i] >= 0.0f) || !detail::is_finite(r.tmin[i]))
        return fail(Status::invalid_argument, "rays.tmin[%zu] = %g: must be finite and >= 0", i, double(r.tmin[i]));
  }
  if (r.tmax) {
    for (std::size_t i = 0; i < n; ++i)
      if (detail::is_nan(r.tmax[i]) || r.tmax[i] < 0.0f)
        return fail(Status::invalid_argument, "rays.tmax[%zu] = %g: must be >= 0 (+inf allowed)", i, double(r.tmax[i]));
  }
  return Status::ok;
}

Status check_spheres(const SpheresView& s, std::size_t n) {
  GYRO_TRY(require_not_null(s.cx, "spheres.cx"));
  GYRO_TRY(require_not_null(s.cy, "spheres.cy"));
  GYRO_TRY(require_not_null(s.cz, "spheres.cz"));
  GYRO_TRY(require_not_null(s.r, "spheres.r"));
  GYRO_TRY(require_finite(s.cx, n, "spheres.cx"));
  GYRO_TRY(require_finite(s.cy, n, "spheres.cy"));
  GYRO_TRY(require_finite(s.cz, n, "spheres.cz"));
  GYRO_TRY(require_finite(s.r, n, "spheres.r"));
  for (std::size_t i = 0; i < n; ++i)
    if (s.r[i] < 0.0f) return fail(Status::invalid_argument, "spheres.r[%zu] = %g is negative", i, double(s.r[i]));
  return Status::ok;
}

}  // namespace

Status raycast_spheres_closest(const RaysView& rays, std::size_t ray_count, const SpheresView& spheres,
                               std::size_t sphere_count, const HitsOut& hits) {
  if (ray_count > kMaxCount || sphere_count > kMaxCount)
    return fail(Status::invalid_count, "counts must be below 2^31 (rays %zu, spheres %zu)", ray_count, sphere_count);
  if (ray_count == 0) return Status::ok;
  GYRO_TRY(require_not_null(hits.t, "hits.t"));
  GYRO_TRY(require_not_null(hits.primitive, "hits.primitive"));
  const int normals = (hits.nx != nullptr) + (hits.ny != nullptr) + (hits.nz != nullptr);
  if (normals != 0 && normals != 3) return fail(Status::null_argument, "hits.nx, ny, nz: give all three or none");
  GYRO_TRY(check_rays(rays, ray_count));
  if (sphere_count) GYRO_TRY(check_spheres(spheres, sphere_count));

  detail::FloatEnvGuard env;
  const RaySphereArgs args{rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz, rays.tmin, rays.tmax,
                           spheres.cx, spheres.cy, spheres.cz, spheres.r, sphere_count,
                           hits.t, reinterpret_cast<uint32_t*>(hits.primitive)};
  auto* kernel = GYRO_DISPATCH(ray_sphere_closest);
  detail::parallel_for(ray_count, kRayChunk, [&](std::size_t b, std::size_t e) {
    kernel(args, b, e);
    if (normals == 0) return;
    // The normal is computed once per ray by this one scalar routine whatever the level.
    for (std::size_t i = b; i < e; ++i) {
      const int32_t k = hits.primitive[i];
      float nx = 0.0f, ny = 0.0f, nz = 0.0f;
      if (k >= 0) {
        const float t = hits.t[i];
        const float px = rays.ox[i] + t * rays.dx[i] - spheres.cx[k];
        const float py = rays.oy[i] + t * rays.dy[i] - spheres.cy[k];
        const float pz = rays.oz[i] + t * rays.dz[i] - spheres.cz[k];
        const float len = std::sqrt((px * px + py * py) + pz * pz);
        if (len > 0.0f) {
          nx = px / len, ny = py / len, nz = pz / len;
        } else {  // a point sphere: face the ray
          const float dl = std::sqrt((rays.dx[i] * rays.dx[i] + rays.dy[i] * rays.dy[i]) + rays.dz[i] * rays.dz[i]);
          nx = -rays.dx[i] / dl, ny = -rays.dy[i] / dl, nz = -rays.dz[i] / dl;
        }
      }
      hits.nx[i] = nx, hits.ny[i] = ny, hits.nz[i] = nz;
    }
  });
  return Status::ok;
}

}  // namespace gyro
