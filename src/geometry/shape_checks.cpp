// Input checks for SoA shape arrays.
#include "geometry/shape_checks.hpp"

#include "core/validate.hpp"

namespace gyro::detail {
namespace {

struct Column {
  const float* p;
  const char* name;
  bool non_negative;
};

// The component arrays of a shape array, in a fixed order; returns how many.
int columns_of(const ShapeArray& s, Column out[15]) {
  int n = 0;
  auto add = [&](const float* p, const char* name, bool nonneg = false) { out[n++] = {p, name, nonneg}; };
  switch (s.type) {
    case ShapeType::sphere:
      add(s.spheres.cx, "cx"), add(s.spheres.cy, "cy"), add(s.spheres.cz, "cz"), add(s.spheres.r, "r", true);
      break;
    case ShapeType::aabb:
      add(s.aabbs.cx, "cx"), add(s.aabbs.cy, "cy"), add(s.aabbs.cz, "cz");
      add(s.aabbs.ex, "ex", true), add(s.aabbs.ey, "ey", true), add(s.aabbs.ez, "ez", true);
      break;
    case ShapeType::obb:
      add(s.obbs.cx, "cx"), add(s.obbs.cy, "cy"), add(s.obbs.cz, "cz");
      add(s.obbs.ex, "ex", true), add(s.obbs.ey, "ey", true), add(s.obbs.ez, "ez", true);
      add(s.obbs.u0x, "u0x"), add(s.obbs.u0y, "u0y"), add(s.obbs.u0z, "u0z");
      add(s.obbs.u1x, "u1x"), add(s.obbs.u1y, "u1y"), add(s.obbs.u1z, "u1z");
      add(s.obbs.u2x, "u2x"), add(s.obbs.u2y, "u2y"), add(s.obbs.u2z, "u2z");
      break;
    case ShapeType::plane:
      add(s.planes.nx, "nx"), add(s.planes.ny, "ny"), add(s.planes.nz, "nz"), add(s.planes.d, "d");
      break;
    case ShapeType::triangle:
      add(s.triangles.ax, "ax"), add(s.triangles.ay, "ay"), add(s.triangles.az, "az");
      add(s.triangles.bx, "bx"), add(s.triangles.by, "by"), add(s.triangles.bz, "bz");
      add(s.triangles.cx, "cx"), add(s.triangles.cy, "cy"), add(s.triangles.cz, "cz");
      break;
  }
  return n;
}

bool known_type(ShapeType t) { return static_cast<uint32_t>(t) >= 1 && static_cast<uint32_t>(t) <= 5; }

}  // namespace

Status check_shape_array(const ShapeArray& s, std::size_t n, const char* which, bool strict) {
  if (!known_type(s.type)) return fail(Status::invalid_argument, "%s.type = %u is not a shape type", which, unsigned(s.type));
  if (n == 0) return Status::ok;  // nothing is read: an empty array may have null pointers
  Column cols[15];
  const int nc = columns_of(s, cols);
  for (int c = 0; c < nc; ++c)
    if (!cols[c].p) return fail(Status::null_argument, "%s.%s is null", which, cols[c].name);
  if (!strict) return Status::ok;
  for (int c = 0; c < nc; ++c) {
    const std::size_t bad = first_non_finite(cols[c].p, n);
    if (bad < n) return fail(Status::non_finite, "%s.%s[%zu] is not finite", which, cols[c].name, bad);
    if (cols[c].non_negative)
      for (std::size_t i = 0; i < n; ++i)
        if (cols[c].p[i] < 0.0f)
          return fail(Status::invalid_argument, "%s.%s[%zu] = %g is negative", which, cols[c].name, i, double(cols[c].p[i]));
  }
  return Status::ok;
}

Status check_rays(const RaysView& r, std::size_t n, bool values) {
  GYRO_TRY(require_not_null(r.ox, "rays.ox"));
  GYRO_TRY(require_not_null(r.oy, "rays.oy"));
  GYRO_TRY(require_not_null(r.oz, "rays.oz"));
  GYRO_TRY(require_not_null(r.dx, "rays.dx"));
  GYRO_TRY(require_not_null(r.dy, "rays.dy"));
  GYRO_TRY(require_not_null(r.dz, "rays.dz"));
  if (!values) return Status::ok;
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

Status check_hit_columns(const float* nx, const float* ny, const float* nz, const float* u, const float* v) {
  const int normals = (nx != nullptr) + (ny != nullptr) + (nz != nullptr);
  if (normals != 0 && normals != 3) return fail(Status::null_argument, "hits.nx, ny, nz: give all three or none");
  if ((u == nullptr) != (v == nullptr)) return fail(Status::null_argument, "hits.u, v: give both or none");
  return Status::ok;
}

}  // namespace gyro::detail
