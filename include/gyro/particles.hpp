// Particles (Cookbook chapter 14): point masses under gravity and forces, colliding with
// static spheres, boxes, oriented boxes and planes.
//
// Conventions:
//  - Units are SI; gravity defaults to (0, -9.81, 0). A particle has a mass (> 0) or is
//    pinned (inverse mass 0): a pinned particle ignores gravity, forces, damping and
//    colliders and moves only by its velocity (zero keeps it in place).
//  - Integrators, as the book describes them (a = gravity * gravity_scale + force / mass,
//    damping d applied as v *= 1 / (1 + dt d)):
//      explicit_euler:      x += v dt, then v += a dt (position error O(dt): g t dt / 2 in
//                           free fall, lagging);
//      semi_implicit_euler: v += a dt, then x += v dt (the default; O(dt): g t dt / 2 ahead);
//      verlet:              x' = x + (x - x_prev) + a dt^2, keeping the previous position
//                           (exact for constant acceleration, up to rounding). The velocity
//                           read back is (x' - x) / dt + a dt / 2. After create, set_position,
//                           set_velocity or a change of dt, x_prev is re-derived from the
//                           velocity so the next step starts from it exactly.
//  - Collisions: a step moves each particle along the segment from its old to its new
//    position; the first surface crossed (smallest t, ties to the lower collider index) stops
//    it just outside (a skin of 1 mm plus 2^-16 of its coordinates' size), its velocity's
//    normal part is reflected and scaled by bounce and its tangential part scaled by
//    (1 - friction), and the rest of the displacement is reflected the same way and swept
//    again, up to 4 bounces per step (the 5th surface stops the particle). So a particle
//    never tunnels through a collider, at any speed. Colliders are solid: a particle inside
//    one (or behind a plane: the side opposite its normal is solid) is first pushed out
//    along the closest-point normal. Verlet particles get the previous position that makes
//    the reflected velocity the implied one.
//  - Particles are named by ParticleIds {index, generation}; all-zero is null; a destroyed
//    particle's id is stale: every call with it returns Status::stale_id and changes nothing.
//    Destroying moves the last particle into the hole (views change order, ids do not).
//  - Bad input (NaN or infinite values, mass <= 0 on a particle that is not pinned, bounce or
//    friction outside [0, 1], a stale id, dt <= 0 or NaN, a collider of negative size or
//    with a zero plane normal or a non-orthonormal OBB orientation) returns a Status with a
//    detail in gyro::last_error() and changes nothing.
//  - Determinism: each particle's step is a fixed sequence of + - * / and sqrt (no FMA, no
//    libm), particles are independent and run in fixed chunks, so results are bit-identical
//    for any thread count; hash() is the witness of the whole state.
//  - One system must not be used from two threads at once.
#pragma once

#include "gyro/math_vec.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace gyro {

namespace detail {
struct ParticleAccess;  // the world's hashing and snapshot hooks (src/dynamics/particles_internal.hpp)
}

/// A stable particle name; all-zero is null. Ordered by index, then generation.
struct ParticleId {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return index == 0 && generation == 0; }
  friend bool operator==(ParticleId a, ParticleId b) { return a.index == b.index && a.generation == b.generation; }
  friend bool operator<(ParticleId a, ParticleId b) {
    return a.index < b.index || (a.index == b.index && a.generation < b.generation);
  }
};

/// Values are part of the C ABI.
enum class ParticleIntegrator : uint32_t {
  explicit_euler = 0,
  semi_implicit_euler = 1,
  verlet = 2,
};

struct ParticleDef {
  vec3 position;
  vec3 velocity;
  float mass = 1.0f;       ///< kg, > 0; ignored when pinned
  bool pinned = false;     ///< inverse mass 0: moves only by its velocity
  float bounce = 0.7f;     ///< restitution of the normal velocity at a collision, in [0, 1]
  float friction = 0.0f;   ///< the tangential velocity keeps (1 - friction) at a collision, in [0, 1]
  float gravity_scale = 1.0f;
};

struct ParticleSettings {
  vec3 gravity{0.0f, -9.81f, 0.0f};
  ParticleIntegrator integrator = ParticleIntegrator::semi_implicit_euler;
  float damping = 0.0f;  ///< 1/s, >= 0: v *= 1 / (1 + dt damping) per step
};

/// Zero-copy read views of the state, dense slots 0..count-1, valid until the next create,
/// destroy or step. ids[i] names the particle in slot i.
struct ParticleView {
  std::size_t count = 0;
  const ParticleId* ids = nullptr;
  const float *px = nullptr, *py = nullptr, *pz = nullptr;
  const float *vx = nullptr, *vy = nullptr, *vz = nullptr;
};

class ParticleSystem {
 public:
  ParticleSystem();
  ~ParticleSystem();
  /// Copies are deep and independent (a snapshot steps exactly as the original would).
  ParticleSystem(const ParticleSystem& other);
  ParticleSystem& operator=(const ParticleSystem& other);

  /// Validates (finite gravity, damping >= 0 and finite, a known integrator).
  Status set_settings(const ParticleSettings& settings);
  const ParticleSettings& settings() const;

  Status create(const ParticleDef& def, ParticleId* out);
  Status destroy(ParticleId id);
  bool is_valid(ParticleId id) const;
  std::size_t count() const;
  bool empty() const { return count() == 0; }

  Status get_position(ParticleId id, vec3* position) const;
  Status get_velocity(ParticleId id, vec3* velocity) const;
  /// Teleports the particle (no collision on the way); its velocity is kept.
  Status set_position(ParticleId id, const vec3& position);
  Status set_velocity(ParticleId id, const vec3& velocity);
  /// Adds a force (N) for the next step only.
  Status add_force(ParticleId id, const vec3& force);

  /// Static colliders; *index names the collider until it is removed (indices of removed
  /// colliders are reused, lowest first). Radius and half extents must be >= 0 (zero is a
  /// point or a flat box); a plane's normal must be non-zero (it is normalised); an OBB's
  /// orientation must be orthonormal to 1e-3.
  Status add_collider(const Sphere& sphere, uint32_t* index);
  Status add_collider(const AABB& box, uint32_t* index);
  Status add_collider(const OBB& box, uint32_t* index);
  Status add_collider(const Plane& plane, uint32_t* index);
  Status remove_collider(uint32_t index);
  void clear_colliders();
  std::size_t collider_count() const;

  /// Advances every particle by dt seconds (dt > 0 and finite); forces are then cleared.
  Status step(float dt);

  ParticleView view() const;

  /// The 64-bit witness of the whole state (settings, every column, colliders, ids).
  uint64_t hash() const;

  struct Impl;

 private:
  friend struct detail::ParticleAccess;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gyro
