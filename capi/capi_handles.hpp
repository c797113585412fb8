// The C ABI's opaque handles and the conversions more than one implementation file needs.
// Internal: never installed.
#pragma once

#include "gyro.h"

#include "gyro/camera.hpp"
#include "gyro/frustum.hpp"
#include "gyro/triangle_mesh.hpp"

#include <memory>

/// A shared reference, so scenes can keep a mesh alive after the caller destroys its handle.
struct gyro_mesh {
  std::shared_ptr<const gyro::TriangleMesh> mesh;
};

namespace gyro::capi {

/// The C camera as a checked gyro::Camera (check_camera's statuses; out untouched on error).
Status camera_of(const gyro_camera* c, Camera& out);

/// The C frustum's six planes (nx, ny, nz, d) as a gyro::Frustum.
inline Frustum frustum_of(const gyro_frustum& c) {
  Frustum f;
  for (int p = 0; p < 6; ++p) f.planes[p] = {{c.planes[p][0], c.planes[p][1], c.planes[p][2]}, c.planes[p][3]};
  return f;
}

}  // namespace gyro::capi
