// Snapshot IO shared by the dynamics stores: the mesh table (meshes are named by their index
// in the snapshot, never by address) and the static colliders of particle systems and soft
// bodies. The world writes the table first, so every reader can resolve an index at once.
#pragma once

#include "core/byte_stream.hpp"
#include "dynamics/particle_colliders.hpp"

#include <cstdint>
#include <vector>

namespace gyro {
class TriangleMesh;
}

namespace gyro::detail {

struct SnapshotMeshes {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  std::vector<const TriangleMesh*> list;

  /// Adds a mesh once (first-seen order); null is ignored.
  void add(const TriangleMesh* m) {
    if (m && index_of(m) == kNone) list.push_back(m);
  }
  uint32_t index_of(const TriangleMesh* m) const {
    if (!m) return kNone;
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i] == m) return static_cast<uint32_t>(i);
    return kNone;
  }
  /// null for kNone; the reader fails for any other index out of range.
  const TriangleMesh* at(uint32_t i, ByteReader& r) const {
    if (i == kNone) return nullptr;
    r.require(i < list.size());
    return r.ok() ? list[i] : nullptr;
  }
};

/// A collider kept by a particle system or soft body (sphere, box, oriented box or plane:
/// the capsule and hull kinds exist only during a world step and are never stored).
template <class Io, class C> void io_collider(Io& io, C& c) {
  io.enumeration(c.kind, uint32_t(ColliderKind::plane));
  io.v3(c.sphere.center), io.f32(c.sphere.radius);
  io.v3(c.aabb.center), io.v3(c.aabb.half_extents);
  io.v3(c.obb.center), io.v3(c.obb.half_extents), io.m3(c.obb.orientation);
  io.v3(c.plane.normal), io.f32(c.plane.distance);
}

}  // namespace gyro::detail
