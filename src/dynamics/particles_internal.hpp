// The world's access to a ParticleSystem beyond the public API: hashing into the world's
// witness. Kept out of include/gyro so the public header needs no src/ header.
#pragma once

#include "core/byte_stream.hpp"
#include "core/state_hash.hpp"
#include "gyro/particles.hpp"

namespace gyro::detail {

struct ParticleAccess {
  /// Feeds the whole particle state to h: settings, the dt of the last step, the id
  /// allocator, every column (positions, velocities, previous positions, pending forces,
  /// inverse masses, bounce, friction, gravity scales, re-seed flags), the dense ids and the
  /// colliders, in that order.
  static void hash_into(const ParticleSystem& particles, StateHasher& h);
  /// The whole state as snapshot bytes, and back: read checks what it reads (sizes, ids,
  /// settings) and marks the reader failed on any inconsistency; read into a fresh system.
  static void write(const ParticleSystem& particles, ByteWriter& w);
  static void read(ByteReader& r, ParticleSystem& particles);
};

/// What the world calls after hashing its own state.
inline void hash_into(const ParticleSystem& particles, StateHasher& h) { ParticleAccess::hash_into(particles, h); }

}  // namespace gyro::detail
