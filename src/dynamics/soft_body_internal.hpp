// The world's access to a SoftBody beyond the public API: stepping with the world's bodies
// as extra colliders, and hashing into the world's witness.
#pragma once

#include "core/byte_stream.hpp"
#include "core/state_hash.hpp"
#include "dynamics/snapshot_io.hpp"
#include "dynamics/particle_colliders.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/soft_body.hpp"

#include <span>

namespace gyro::detail {

/// A triangle mesh placed in the world (the mesh is in its own frame).
struct MeshCollider {
  const TriangleMesh* mesh = nullptr;
  vec3 position;
  quat orientation;
};

struct SoftAccess {
  /// step(dt) with these colliders besides the body's own (valid during the call only).
  static Status step_with(SoftBody& body, float dt, std::span<const Collider> colliders, std::span<const MeshCollider> meshes);
  /// A box the particles cannot leave over a step of dt: around every particle now, widened
  /// by the fastest one's travel (speed and gravity) and the thickness (false when empty).
  static bool step_bounds(const SoftBody& body, float dt, vec3* lo, vec3* hi);
  static void hash_into(const SoftBody& body, StateHasher& h);
  /// The meshes its colliders reference (for the snapshot's mesh table).
  static void add_meshes(const SoftBody& body, SnapshotMeshes& meshes);
  /// The whole state as snapshot bytes, and back (read into a fresh body; it checks sizes,
  /// indices and settings and marks the reader failed on any inconsistency).
  static void write(const SoftBody& body, ByteWriter& w, const SnapshotMeshes& meshes);
  static void read(ByteReader& r, SoftBody& body, const SnapshotMeshes& meshes);
};

}  // namespace gyro::detail
