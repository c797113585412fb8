// The dynamics world (Cookbook chapters 14-15 and the appendix's stability topics): rigid
// bodies in structure-of-arrays storage, contacts with persistent arbiters, and a
// deterministic, colour-by-colour impulse solver.
//
// Conventions:
//  - Units are SI (m, kg, s); gravity defaults to (0, -9.81, 0). Quaternions are (x, y, z, w),
//    rotating body-local vectors into the world (gyro/math_quat.hpp's rotate()).
//  - Bodies are named by BodyIds {index, generation}; all-zero is null. A destroyed body's
//    id is stale: every call with it returns Status::stale_id and changes nothing.
//  - Shapes: a sphere (radius), a box (half extents) or a capsule (radius around the segment
//    (0, +-half_height, 0)) centred on the body's origin; a convex hull (gyro/convex.hpp,
//    copied into its mass frame: the body's origin is its centroid, see get_shape_frame); a
//    static plane (the body frame's y = 0 plane, normal +y, i.e. normal = rotate(q, +y)
//    through the body's position); a static triangle mesh (a TriangleMesh the caller keeps
//    alive while the body exists, in the body's frame). Pairs with a capsule or a hull go
//    through GJK/EPA and face clipping (WorldDef::convex_manifold); the others through
//    dedicated separating-axis and closest-point routines.
//  - Static bodies never move. Kinematic bodies move by their velocity and push dynamic
//    bodies, which never push back. Dynamic bodies get their mass and inertia from shape and
//    density (or from BodyDef::mass when it is > 0).
//  - A step runs the stages in the Cookbook's order: forces, broadphase, narrowphase and
//    arbiters, islands and sleeping, the solver (velocity integration, warm start, impulse
//    iterations, position integration, position correction, restitution), particles. A
//    stage with nothing to do is skipped and allocates nothing; after warm-up a step makes
//    no heap allocation.
//  - Determinism: for the same sequence of calls the state after every step is bit-identical
//    at every SIMD level and thread count, with g++ and clang++, on x86-64 and aarch64.
//    hash() is the witness: it covers every state column, the contacts' accumulated impulses
//    and the id allocator.
//  - Bad input (NaN or infinite values, a negative or NaN mass or density, a zero-size or
//    negative shape, a zero quaternion, a plane or mesh on a non-static body, a stale id, a
//    step with dt <= 0 or NaN) returns a Status with a detail in last_error() and changes
//    nothing.
//  - One world must not be used from two threads at once; separate worlds may step in
//    parallel. A step's batches run on gyro::thread_count() threads unless WorldDef::threads
//    says otherwise.
#pragma once

#include "gyro/math_quat.hpp"
#include "gyro/math_vec.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace gyro {

class TriangleMesh;
class ParticleSystem;
class SoftBody;
struct ConvexHull;

/// A stable body name; all-zero is null. Ordered by index, then generation.
struct BodyId {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return index == 0 && generation == 0; }
  friend bool operator==(BodyId a, BodyId b) { return a.index == b.index && a.generation == b.generation; }
  friend bool operator<(BodyId a, BodyId b) {
    return a.index < b.index || (a.index == b.index && a.generation < b.generation);
  }
};

/// A soft body (cloth, soft body, springs) in a world; all-zero is null.
struct SoftBodyId {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return index == 0 && generation == 0; }
  friend bool operator==(SoftBodyId a, SoftBodyId b) { return a.index == b.index && a.generation == b.generation; }
};

/// Values are part of the C ABI.
enum class BodyType : uint32_t {
  static_body = 0,  ///< never moves; infinite mass
  kinematic = 1,    ///< moves by its velocity only; infinite mass
  dynamic = 2,      ///< moved by forces, gravity and contacts
};

/// Values are part of the C ABI.
enum class BodyShape : uint32_t {
  sphere = 0,  ///< ShapeDef::radius
  box = 1,     ///< ShapeDef::half_extents
  plane = 2,   ///< static only: the body frame's y = 0 plane, normal +y
  mesh = 3,    ///< static only: ShapeDef::mesh in the body frame
  capsule = 4, ///< ShapeDef::radius and half_height: the segment (0, +-half_height, 0) plus radius
  hull = 5,    ///< ShapeDef::hull (copied): the body frame is the hull's mass frame, see get_shape_frame
};

struct ShapeDef {
  BodyShape type = BodyShape::box;
  float radius = 0.5f;
  vec3 half_extents{0.5f, 0.5f, 0.5f};
  const TriangleMesh* mesh = nullptr;  ///< not owned; must outlive the body
  float half_height = 0.5f;            ///< capsule: half the length of its core segment (>= 0)
  /// hull: the world keeps its own copy, moved into the hull's mass frame (centroid at the
  /// body origin, principal axes along the body axes), so the caller may free it at once.
  /// BodyDef::position and orientation place the hull as built; get_transform then reports
  /// the mass frame (see World::get_shape_frame).
  const ConvexHull* hull = nullptr;
};

struct BodyDef {
  BodyType type = BodyType::dynamic;
  ShapeDef shape;
  vec3 position;
  quat orientation;  ///< normalised on input; must not be zero
  vec3 linear_velocity;
  vec3 angular_velocity;  ///< world frame, rad/s
  float density = 1.0f;   ///< kg/m^3, used when mass is 0
  float mass = 0.0f;      ///< kg; > 0 overrides density (inertia scales with it)
  float friction = 0.6f;  ///< Coulomb coefficient; a pair uses sqrt(fa * fb), applied as patch friction
  float restitution = 0.0f;  ///< a pair uses max(ea, eb)
  float linear_damping = 0.0f;   ///< 1/s: v *= 1 / (1 + h * damping) per sub-step
  float angular_damping = 0.0f;  ///< 1/s
  float gravity_scale = 1.0f;
  uint32_t category = 1;         ///< collision filtering: a pair collides when
  uint32_t mask = 0xFFFFFFFFu;   ///< (catA & maskB) != 0 and (catB & maskA) != 0
  bool allow_sleep = true;
  bool awake = true;
  uint64_t user_data = 0;
};

/// How contacts correct position errors. Values are part of the C ABI.
enum class ContactModel : uint32_t {
  soft_step = 0,          ///< Box2D v3's soft step: sub-steps, soft constraints, relaxation (default)
  baumgarte = 1,          ///< the appendix's Baumgarte bias with slop, in the velocity iterations
  linear_projection = 2,  ///< the book's chapter 15: no bias, positions projected apart after the step
};

/// How pairs with a capsule or hull build their manifolds. Values are part of the C ABI.
enum class ConvexManifold : uint32_t {
  clipping = 0,     ///< one shot: GJK/EPA's normal, then face clipping (up to 4 points); default
  incremental = 1,  ///< the appendix's arbiter: one GJK/EPA point per step, kept over steps
};

struct WorldDef {
  vec3 gravity{0.0f, -9.81f, 0.0f};
  ContactModel contact_model = ContactModel::soft_step;
  uint32_t substeps = 8;             ///< soft step only; the other models run 1
  uint32_t velocity_iterations = 2;  ///< per sub-step (soft step) or per step (others: try 10)
  uint32_t relax_iterations = 1;     ///< soft step: iterations without bias after each sub-step
  uint32_t position_iterations = 1;  ///< linear projection passes
  float linear_slop = 0.005f;        ///< m of penetration left uncorrected (keeps contacts alive)
  float baumgarte = 0.2f;            ///< baumgarte / linear projection: fraction corrected per step
  float contact_hertz = 60.0f;       ///< soft step: contact stiffness (capped at a quarter of the sub-step rate)
  float contact_damping_ratio = 10.0f;
  float max_push_velocity = 3.0f;    ///< m/s: cap on the speed penetration is resolved with
  float restitution_threshold = 1.0f;  ///< m/s: slower approaches do not bounce
  bool enable_warm_starting = true;
  bool enable_sleep = true;
  float sleep_time = 0.5f;              ///< s a whole island must rest before it sleeps
  float sleep_linear_velocity = 0.05f;  ///< m/s
  float sleep_angular_velocity = 0.05f; ///< rad/s
  bool enable_continuous = true;  ///< speculative contacts sized by the motion of the step
  ConvexManifold convex_manifold = ConvexManifold::clipping;
  uint32_t threads = 0;           ///< 0: gyro::thread_count()
};

/// Time spent in each stage of the last step, in milliseconds (0 for a skipped stage).
struct StepTimings {
  double forces = 0, broadphase = 0, narrowphase = 0, islands = 0, solver = 0, particles = 0, total = 0;
  double soft_bodies = 0;  ///< springs, cloth and soft bodies (after the particles)
};

/// Counters of the last step.
struct StepStats {
  uint32_t bodies = 0, awake_bodies = 0;
  uint32_t pairs = 0;        ///< broadphase pairs
  uint32_t manifolds = 0;    ///< manifolds with at least one point
  uint32_t contacts = 0;     ///< contact points
  uint32_t colors = 0;       ///< constraint graph colours used by the solver
  uint32_t islands = 0;      ///< islands of touching awake bodies
};

/// A pair that started or stopped touching in the last step (bodies in id order).
struct ContactEvent {
  BodyId a, b;
};

/// Zero-copy read views of the SoA state, dense slots 0..count-1, valid until the next
/// create_body, destroy_body or step. ids[i] names the body in slot i.
struct BodyView {
  std::size_t count = 0;
  const BodyId* ids = nullptr;
  const float *px = nullptr, *py = nullptr, *pz = nullptr;
  const float *qx = nullptr, *qy = nullptr, *qz = nullptr, *qw = nullptr;
  const float *vx = nullptr, *vy = nullptr, *vz = nullptr;
  const float *wx = nullptr, *wy = nullptr, *wz = nullptr;
};

class World {
 public:
  /// Validates def (finite gravity, substeps and iterations in 1..64, slop >= 0, ...).
  static Status create(const WorldDef& def, std::unique_ptr<World>* out);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  Status create_body(const BodyDef& def, BodyId* out);
  Status destroy_body(BodyId id);
  bool is_valid(BodyId id) const;
  std::size_t body_count() const;

  Status get_transform(BodyId id, vec3* position, quat* orientation) const;
  /// Teleports the body (and wakes it); contacts are recomputed next step.
  Status set_transform(BodyId id, const vec3& position, const quat& orientation);
  Status get_velocity(BodyId id, vec3* linear, vec3* angular) const;
  Status set_velocity(BodyId id, const vec3& linear, const vec3& angular);
  Status get_mass(BodyId id, float* mass) const;
  Status get_type(BodyId id, BodyType* type) const;
  Status get_user_data(BodyId id, uint64_t* user_data) const;
  /// Where the shape's own frame sits in the body frame: a hull body's frame is the hull's
  /// mass frame (its origin the centroid, its axes the principal axes), so the hull as the
  /// caller built it is at body_transform * (offset, rotation). Identity for other shapes.
  /// Render a hull body with position + rotate(q, offset) and q * rotation.
  Status get_shape_frame(BodyId id, vec3* offset, quat* rotation) const;
  /// The mesh of a mesh body (null for other shapes).
  Status get_mesh(BodyId id, const TriangleMesh** mesh) const;

  /// Forces and torques last for the next step only (cleared after it).
  Status apply_force(BodyId id, const vec3& force, const vec3& world_point);
  Status apply_force_at_center(BodyId id, const vec3& force);
  Status apply_torque(BodyId id, const vec3& torque);
  /// Impulses change the velocity at once.
  Status apply_linear_impulse(BodyId id, const vec3& impulse, const vec3& world_point);
  Status apply_angular_impulse(BodyId id, const vec3& impulse);

  Status set_awake(BodyId id, bool awake);
  Status is_awake(BodyId id, bool* awake) const;

  /// Advances the world by dt seconds (dt > 0 and finite).
  Status step(float dt);

  /// The 64-bit witness of the whole state (see the conventions above).
  uint64_t hash() const;

  /// Snapshots: the whole state as bytes (settings, bodies with their hull and mesh
  /// geometry, the id allocators, the contacts with their warm-start impulses, particles and
  /// soft bodies), versioned, checksummed, little-endian. A world restored from a snapshot
  /// steps on bit-identically to the one it was taken from (equal hash() after every step).
  /// Not kept: the last step's timings, stats and contact events (the next step's events
  /// are measured against the restored contacts, as they would have been).
  std::size_t snapshot_size() const;
  /// Writes the snapshot (invalid_count, nothing written, when capacity < snapshot_size()).
  Status snapshot(void* buffer, std::size_t capacity, std::size_t* size) const;
  /// Replaces the whole state with the snapshot's, its settings included (threads stays this
  /// world's: it changes no result). A mesh body reuses a mesh this world references when its
  /// geometry is bit-identical (the caller keeps such a mesh alive while a body uses it), else
  /// the world keeps its own copy. corrupt_data (truncated, bad checksum, another format
  /// version, inconsistent contents) or out_of_memory leave the world unchanged.
  Status restore(const void* data, std::size_t size);
  static Status create_from_snapshot(const void* data, std::size_t size, std::unique_ptr<World>* out);

  BodyView bodies() const;
  const StepTimings& timings() const;
  const StepStats& stats() const;
  /// Pairs that began / ended touching in the last step, sorted by (a, b).
  std::size_t begin_events(const ContactEvent** events) const;
  std::size_t end_events(const ContactEvent** events) const;

  const WorldDef& def() const;

  /// The world's particles (Cookbook chapter 14), stepped after the rigid bodies; created on
  /// first use with the world's gravity. A world whose particle system is empty skips the
  /// stage. Particles collide with the system's own colliders (gyro/particles.hpp).
  ParticleSystem& particles();

  /// Springs, cloth and soft bodies (gyro/soft_body.hpp), stepped after the particles. The
  /// world keeps a copy of `body`; besides its own colliders, each soft body collides with
  /// every rigid body's shape at its current pose (one-way: cloth does not push bodies).
  /// A world without soft bodies skips the stage.
  Status add_soft_body(const SoftBody& body, SoftBodyId* out);
  Status destroy_soft_body(SoftBodyId id);
  bool is_valid(SoftBodyId id) const;
  std::size_t soft_body_count() const;
  /// The world's soft body, to read or change (null for a stale id); valid until it is destroyed.
  SoftBody* soft_body(SoftBodyId id);
  const SoftBody* soft_body(SoftBodyId id) const;

  struct Impl;

 private:
  World();
  /// Builds a world from a snapshot; `current` (may be null) lends meshes with identical geometry.
  static Status from_snapshot(const void* data, std::size_t size, const Impl* current, std::unique_ptr<World>* out);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gyro
