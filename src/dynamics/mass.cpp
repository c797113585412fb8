#include "dynamics/mass.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

bool positive_finite(float v) { return is_finite(v) && v > 0.0f; }

}  // namespace

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
    case BodyShape::capsule:
      if (!positive_finite(s.radius) || !is_finite(s.half_height) || s.half_height < 0.0f)
        return fail(Status::invalid_argument, "capsule radius must be finite and > 0, half_height finite and >= 0");
      return Status::ok;
    case BodyShape::hull:
      if (s.hull == nullptr) return fail(Status::null_argument, "shape.hull is null");
      if (s.hull->face_count() < 4 || s.hull->vertices.size() < 4)
        return fail(Status::invalid_argument, "shape.hull is not a polyhedron (build it with build_convex_hull)");
      for (const vec3& v : s.hull->vertices)
        if (!gyro::is_finite(v)) return fail(Status::non_finite, "shape.hull has a non-finite vertex");
      return Status::ok;
  }
  return fail(Status::invalid_argument, "unknown shape type %u", unsigned(s.type));
}

float bounding_radius(const ShapeDef& s, const BodyHull* hull) {
  switch (s.type) {
    case BodyShape::sphere: return s.radius;
    case BodyShape::box: return std::sqrt(dot(s.half_extents, s.half_extents));
    case BodyShape::mesh: {
      const AABB b = s.mesh->bounds();
      const vec3 far = abs(b.center) + b.half_extents;
      return std::sqrt(dot(far, far));
    }
    case BodyShape::plane: return 0.0f;
    case BodyShape::capsule: return s.radius + s.half_height;
    case BodyShape::hull: return hull ? hull->bound_radius : 0.0f;
  }
  return 0.0f;
}

Status compute_mass(const BodyDef& def, const BodyHull* hull, MassProperties* out) {
  GYRO_TRY(check_shape(def));
  if (def.shape.type == BodyShape::hull && hull == nullptr) return fail(Status::internal, "hull body without its copy");
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
  } else if (s.type == BodyShape::capsule) {
    // A cylinder of length 2h plus two hemispheres (whose centres of mass sit 3r/8 from the
    // flat faces: the parallel-axis term for the transverse axes).
    const float r = s.radius, h = s.half_height, r2 = r * r;
    const float vc = 2.0f * kPi * r2 * h, vs = (4.0f / 3.0f) * kPi * (r2 * r);
    volume = vc + vs;
    const float axial = vc * (0.5f * r2) + vs * (0.4f * r2);
    const float transverse = vc * (r2 / 4.0f + (h * h) / 3.0f) + vs * ((0.4f * r2 + h * h) + 0.75f * (h * r));
    iy = axial / volume;
    ix = iz = transverse / volume;
  } else if (s.type == BodyShape::hull) {
    volume = hull->volume;
    ix = hull->unit_inertia.x, iy = hull->unit_inertia.y, iz = hull->unit_inertia.z;
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
