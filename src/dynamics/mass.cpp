#include "dynamics/mass.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

bool positive_finite(float v) { return is_finite(v) && v > 0.0f; }

Status check_shape(const BodyDef& def) {
  const ShapeDef& s = def.shape;
  switch (s.type) {
    case BodyShape::sphere:
      if (!positive_finite(s.radius)) return fail(Status::invalid_argument, "sphere radius must be finite and > 0");
      return Status::ok;
    case BodyShape::box:
      if (!positive_finite(s.half_extents.x) || !positive_finite(s.half_extents.y) ||
          !positive_finite(s.half_extents.z))
        return fail(Status::invalid_argument, "box half extents must be finite and > 0");
      return Status::ok;
    case BodyShape::plane:
      if (def.type != BodyType::static_body) return fail(Status::invalid_argument, "a plane body must be static");
      return Status::ok;
    case BodyShape::mesh:
      if (def.type != BodyType::static_body) return fail(Status::invalid_argument, "a mesh body must be static");
      if (s.mesh == nullptr) return fail(Status::null_argument, "shape.mesh is null");
      if (s.mesh->empty()) return fail(Status::invalid_argument, "shape.mesh was not created");
      return Status::ok;
  }
  return fail(Status::invalid_argument, "unknown shape type %u", unsigned(s.type));
}

}  // namespace

float bounding_radius(const ShapeDef& s) {
  switch (s.type) {
    case BodyShape::sphere: return s.radius;
    case BodyShape::box: return std::sqrt(dot(s.half_extents, s.half_extents));
    case BodyShape::mesh: {
      const AABB b = s.mesh->bounds();
      const vec3 far = abs(b.center) + b.half_extents;
      return std::sqrt(dot(far, far));
    }
    case BodyShape::plane: return 0.0f;
  }
  return 0.0f;
}

Status compute_mass(const BodyDef& def, MassProperties* out) {
  GYRO_TRY(check_shape(def));
  *out = MassProperties{};
  if (def.type != BodyType::dynamic) return Status::ok;
  if (!is_finite(def.density) || !is_finite(def.mass) || def.mass < 0.0f)
    return fail(Status::invalid_argument, "mass must be finite and >= 0, density finite");
  if (def.mass == 0.0f && !(def.density > 0.0f))
    return fail(Status::invalid_argument, "a dynamic body needs mass > 0 or density > 0");
  const ShapeDef& s = def.shape;
  constexpr float kPi = 3.14159265358979323846f;
  // Inertia per unit mass, then scaled: so a mass override keeps the shape's distribution.
  float volume, ix, iy, iz;
  if (s.type == BodyShape::sphere) {
    const float r = s.radius;
    volume = (4.0f / 3.0f) * kPi * (r * r * r);
    ix = iy = iz = 0.4f * (r * r);
  } else {
    const vec3 h = s.half_extents;
    volume = 8.0f * (h.x * h.y * h.z);
    ix = (h.y * h.y + h.z * h.z) / 3.0f;
    iy = (h.x * h.x + h.z * h.z) / 3.0f;
    iz = (h.x * h.x + h.y * h.y) / 3.0f;
  }
  const float m = def.mass > 0.0f ? def.mass : def.density * volume;
  if (!positive_finite(m) || !positive_finite(m * ix) || !positive_finite(m * iy) || !positive_finite(m * iz))
    return fail(Status::invalid_argument, "mass or inertia is zero or overflows float");
  out->mass = m;
  out->inv_mass = 1.0f / m;
  out->inv_inertia = {1.0f / (m * ix), 1.0f / (m * iy), 1.0f / (m * iz)};
  return Status::ok;
}

}  // namespace gyro::detail
