// The world's soft bodies: their ids, and the stage that steps them after the particles with
// every rigid body near them as a collider at its current pose (one-way coupling).
#include "core/error.hpp"
#include "core/validate.hpp"
#include "dynamics/body_bounds.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/triangle_mesh.hpp"
#include "world/world_impl.hpp"

namespace gyro {
namespace {

detail::Id to_id(SoftBodyId id) { return {id.index, id.generation}; }

}  // namespace

Status World::add_soft_body(const SoftBody& body, SoftBodyId* out) {
  GYRO_TRY(detail::require_not_null(out, "out"));
  Impl& m = *impl_;
  auto copy = std::make_unique<SoftBody>(body);
  const detail::Id id = m.soft_pool.create();
  m.soft_bodies.push_back(std::move(copy));  // the new dense slot is the last
  *out = {id.index, id.generation};
  return Status::ok;
}

Status World::destroy_soft_body(SoftBodyId id) {
  Impl& m = *impl_;
  if (!m.soft_pool.valid(to_id(id)))
    return detail::fail(Status::stale_id, "soft body id {%u, %u} is stale or null", id.index, id.generation);
  const detail::IdPool::Removal r = m.soft_pool.destroy(to_id(id));
  m.soft_bodies[r.slot] = std::move(m.soft_bodies.back());  // the pool moved the last slot into the hole too
  m.soft_bodies.pop_back();
  return Status::ok;
}

bool World::is_valid(SoftBodyId id) const { return impl_->soft_pool.valid(to_id(id)); }
std::size_t World::soft_body_count() const { return impl_->soft_bodies.size(); }

SoftBody* World::soft_body(SoftBodyId id) {
  const uint32_t slot = impl_->soft_pool.slot(to_id(id));
  return slot == detail::IdPool::kNoSlot ? nullptr : impl_->soft_bodies[slot].get();
}

const SoftBody* World::soft_body(SoftBodyId id) const {
  const uint32_t slot = impl_->soft_pool.slot(to_id(id));
  return slot == detail::IdPool::kNoSlot ? nullptr : impl_->soft_bodies[slot].get();
}

void World::Impl::step_soft_bodies(float dt) {
  detail::BodyStore& s = bodies;
  const uint32_t n = static_cast<uint32_t>(s.size());
  for (auto& body : soft_bodies) {
    // The bodies whose boxes meet the box the soft body can reach this step become its
    // colliders, in slot order.
    vec3 lo, hi;
    if (!detail::SoftAccess::step_bounds(*body, dt, &lo, &hi)) continue;
    soft_shapes.clear();
    soft_meshes.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const vec3 p{s.px[i], s.py[i], s.pz[i]};
      const quat q{s.qx[i], s.qy[i], s.qz[i], s.qw[i]};
      const auto shape = static_cast<BodyShape>(s.shape[i]);
      detail::Collider c;
      if (shape == BodyShape::plane) {
        const vec3 normal = rotate(q, vec3{0.0f, 1.0f, 0.0f});
        c.kind = detail::ColliderKind::plane, c.plane = {normal, dot(normal, p)};
        soft_shapes.push_back(c);
        continue;
      }
      if (shape == BodyShape::mesh && (!s.mesh[i] || s.mesh[i]->empty())) continue;
      const AABB box = detail::shape_bounds(s, i, p, q);
      bool meets = true;
      for (int k = 0; k < 3; ++k)
        meets = meets && box.center[k] - box.half_extents[k] <= hi[k] && box.center[k] + box.half_extents[k] >= lo[k];
      if (!meets) continue;
      switch (shape) {
        case BodyShape::sphere: c.kind = detail::ColliderKind::sphere, c.sphere = {p, s.radius[i]}; break;
        case BodyShape::box:
          c.kind = detail::ColliderKind::obb;
          c.obb.center = p, c.obb.half_extents = {s.hx[i], s.hy[i], s.hz[i]}, c.obb.orientation = to_mat3(q);
          break;
        case BodyShape::capsule: {
          const vec3 axis = rotate(q, vec3{0.0f, 1.0f, 0.0f}) * s.hy[i];
          c.kind = detail::ColliderKind::capsule, c.capsule = {p - axis, p + axis, s.hx[i]};
          break;
        }
        case BodyShape::hull:
          c.kind = detail::ColliderKind::hull, c.hull = {&s.hull[i]->hull, p, to_mat3(q), 0.0f};
          break;
        case BodyShape::mesh: soft_meshes.push_back({s.mesh[i], p, q}); continue;
        case BodyShape::plane: continue;
      }
      soft_shapes.push_back(c);
    }
    detail::SoftAccess::step_with(*body, dt, soft_shapes, soft_meshes);
  }
}

}  // namespace gyro
