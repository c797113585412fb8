// Springs, cloth and soft bodies (Cookbook chapter 16 and the appendix): a network of
// particles joined by distance springs, stepped by one of two models.
//
// Conventions:
//  - A SoftBody owns dense particles 0..count-1 (indices never change after creation) and
//    springs between them. Every spring belongs to a family (structural, shear, bend,
//    radial, joint) whose constants (stiffness k in N/m, damping b in N s/m) apply to all of
//    its springs. A spring's rest length is the distance at creation unless given.
//  - Models (SoftSettings::model), both over the same springs and constants:
//      xpbd (default): extended position-based dynamics with compliance 1/k (k may be
//        +infinity: inextensible) and the matching damping term, one pass per sub-step over
//        the springs colour by colour (Gauss-Seidel), `iterations` passes if asked. Stable
//        for any k and dt: stiff cloth converges with more sub-steps, never explodes.
//      springs: the book's Hooke springs F = -k (|d| - rest) - b (dv . n) along the spring,
//        in the book's order per sub-step (forces, integrate, spring forces, constraints).
//        Explicit: it explodes when the sub-step exceeds about 2 sqrt(m / k).
//  - Particles: mass > 0 or pinned (inverse mass 0: the book's missing per-particle
//    interface). A pinned particle moves only when set_position moves it (a kinematic pin).
//  - Collisions: the body's colliders (spheres, boxes, oriented boxes, planes, triangle
//    meshes; in a World also every rigid body's shape) are tested per sub-step along each
//    particle's segment from its sub-step start to its solved position, so particles do not
//    tunnel at any speed. Particles stay `thickness` outside surfaces (spheres, boxes and
//    planes are inflated by it; they are solid: a particle inside is pushed out; a mesh is a
//    two-sided surface). A contact stops the particle's motion into the surface (it never
//    throws it back: no bounce, no energy gained) and applies position-based Coulomb
//    friction: the sub-step's tangential motion is cancelled while it is under `friction`
//    times the contact's correction, else shortened by that much. CollisionResponse::penalty
//    replaces the projection by a penalty spring (penalty_stiffness, N/m per particle).
//  - Cloth grids store each row in four blocks (columns i % 4 = 0, 1, 2, 3) so every spring
//    family runs as unit-stride loads without gathers; cloth_index() maps (ix, iz) to the
//    particle index, and triangles() already use particle indices.
//  - Bad input (NaN or infinite values, a grid smaller than 2 x 2, negative stiffness or
//    damping, mass <= 0, an index out of range, dt <= 0 or NaN) returns a Status with a
//    detail in gyro::last_error() and changes nothing.
//  - Determinism: every sub-step is a fixed sequence of + - * / and sqrt (no FMA, no libm)
//    over springs in a fixed colour order; springs of one colour share no particle, so a
//    colour runs in any order on any number of threads and SIMD lanes with the same bits.
//    hash() is the witness of the whole state.
//  - One body must not be used from two threads at once; separate bodies may step in parallel.
#pragma once

#include "gyro/math_vec.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace gyro {

class TriangleMesh;

namespace detail {
struct SoftAccess;  // the world's stepping and hashing hooks (src/dynamics/soft_body_internal.hpp)
}

/// Values are part of the C ABI.
enum class SoftModel : uint32_t {
  xpbd = 0,
  springs = 1,
};

/// Values are part of the C ABI.
enum class SpringFamily : uint32_t {
  structural = 0,  ///< grid neighbours along x and z; mesh edges; cube edges
  shear = 1,       ///< grid cell diagonals; cube face diagonals
  bend = 2,        ///< grid neighbours two apart; across mesh edges; cube body diagonals
  radial = 3,      ///< mesh soft bodies: each surface particle to the centre particle (keeps volume)
  joint = 4,       ///< distance joints added with add_joint
};
inline constexpr uint32_t kSpringFamilyCount = 5;

/// Values are part of the C ABI.
enum class CollisionResponse : uint32_t {
  projection = 0,  ///< particles are moved out of colliders (default)
  penalty = 1,     ///< a penalty spring pushes particles out (soft bodies that should squash)
};

struct SpringConstants {
  float stiffness = 1.0e6f;  ///< N/m, > 0; +infinity: inextensible (xpbd only)
  float damping = 0.0f;      ///< N s/m along the spring, >= 0
};

struct SoftSettings {
  SoftModel model = SoftModel::xpbd;
  uint32_t substeps = 16;   ///< sub-steps per step, 1..256
  uint32_t iterations = 1;  ///< xpbd: passes over the springs per sub-step, 1..64
  vec3 gravity{0.0f, -9.81f, 0.0f};
  float damping = 0.0f;     ///< 1/s, >= 0: v *= 1 / (1 + h damping) per sub-step h
  float thickness = 0.01f;  ///< m kept between particles and collider surfaces, >= 0
  float friction = 0.3f;    ///< Coulomb coefficient at collider contacts, in [0, 1]
  CollisionResponse response = CollisionResponse::projection;
  float penalty_stiffness = 1.0e4f;  ///< N/m per particle (penalty response), > 0
};

/// A grid cloth on the x-z plane: nx * nz particles over size_x * size_z metres, centred.
struct ClothDef {
  uint32_t nx = 32, nz = 32;  ///< particles along x and z, >= 2 each
  float size_x = 10.0f, size_z = 10.0f;  ///< m, > 0
  vec3 center{0.0f, 0.0f, 0.0f};
  float particle_mass = 1.0f;  ///< kg per particle, > 0
  bool both_diagonals = true;  ///< false: one diagonal per cell, alternating by parity (Bullet's gendiags)
  bool bend = true;            ///< springs between grid neighbours two apart
  SpringConstants structural{1.0e6f, 0.0f};
  SpringConstants shear{1.0e6f, 0.0f};
  SpringConstants bend_constants{1.0e4f, 0.0f};
};

/// The appendix's soft cube: 8 particles, 28 springs (12 edges: structural, 12 face
/// diagonals: shear, 4 body diagonals: bend).
struct SoftCubeDef {
  vec3 center{0.0f, 0.0f, 0.0f};
  float half_extent = 0.5f;    ///< m, > 0
  float particle_mass = 1.0f;  ///< kg per corner, > 0
  SpringConstants structural{1.0e4f, 0.0f};
  SpringConstants shear{1.0e4f, 0.0f};
  SpringConstants bend{1.0e4f, 0.0f};
};

/// A soft body from a closed triangle mesh: one particle per vertex, structural springs on
/// the edges, bend springs across each edge (between the two opposite vertices), and radial
/// springs from every vertex to one extra particle at the vertices' centroid.
struct SoftMeshDef {
  const float* vertices = nullptr;    ///< x, y, z per vertex
  uint32_t vertex_count = 0;          ///< >= 4
  const uint32_t* indices = nullptr;  ///< three per triangle
  uint32_t triangle_count = 0;        ///< >= 4
  float particle_mass = 1.0f;         ///< kg per particle (the centre too), > 0
  SpringConstants structural{1.0e4f, 0.0f};
  SpringConstants bend{1.0e3f, 0.0f};
  SpringConstants radial{1.0e3f, 0.0f};
};

/// One spring of a general body; rest_length < 0 takes the particles' distance at creation.
struct SoftSpringDef {
  uint32_t a = 0, b = 0;
  SpringFamily family = SpringFamily::structural;
  float rest_length = -1.0f;
};

/// Any network of particles and springs (a single spring between two particles, a rope, a
/// lattice): the per-particle interface the book's cloth lacks.
struct SoftBodyDef {
  const vec3* positions = nullptr;   ///< particle_count positions
  const float* masses = nullptr;     ///< particle_count masses (kg, > 0); null: 1 kg each
  const uint8_t* pinned = nullptr;   ///< particle_count flags (non-zero: pinned); null: none
  uint32_t particle_count = 0;       ///< >= 1
  const SoftSpringDef* springs = nullptr;
  uint32_t spring_count = 0;
  const uint32_t* triangles = nullptr;  ///< three particle indices each, for rendering (optional)
  uint32_t triangle_count = 0;
};

/// A distance joint (chapter 16) between two particles of one body; rest_length < 0 takes
/// their current distance, 0 makes a ball joint (the two particles coincide).
struct ParticleJointDef {
  uint32_t a = 0, b = 0;
  float rest_length = -1.0f;
};

/// Zero-copy read view, valid until the next step or change. Triangles index particles.
struct SoftView {
  std::size_t count = 0;
  const float *px = nullptr, *py = nullptr, *pz = nullptr;
  const float *vx = nullptr, *vy = nullptr, *vz = nullptr;
  const float* inverse_mass = nullptr;
  std::size_t triangle_count = 0;
  const uint32_t* triangles = nullptr;  ///< three particle indices per triangle, counter-clockwise seen from +y for a cloth
};

/// Figures of the current state (computed on demand, in double, in a fixed order).
struct SoftStats {
  std::size_t particles = 0, springs = 0, colors = 0;
  double max_strain = 0.0;   ///< max |len - rest| / rest over structural springs
  double mean_strain = 0.0;  ///< mean of the same
  double kinetic_energy = 0.0, potential_energy = 0.0, elastic_energy = 0.0;  ///< J (gravity potential from y = 0)
  double min_y = 0.0;        ///< lowest particle
};

class SoftBody {
 public:
  SoftBody();
  ~SoftBody();
  /// Copies are deep and independent (a copy steps exactly as the original would).
  SoftBody(const SoftBody& other);
  SoftBody& operator=(const SoftBody& other);
  SoftBody(SoftBody&&) noexcept;
  SoftBody& operator=(SoftBody&&) noexcept;

  /// Builders: replace *out's particles and springs (its settings and colliders stay).
  static Status make(const SoftBodyDef& def, SoftBody* out);
  static Status make_cloth(const ClothDef& def, SoftBody* out);
  static Status make_cube(const SoftCubeDef& def, SoftBody* out);
  static Status make_from_mesh(const SoftMeshDef& def, SoftBody* out);

  /// Validates (substeps 1..256, iterations 1..64, finite gravity, damping >= 0, ...).
  Status set_settings(const SoftSettings& settings);
  const SoftSettings& settings() const;

  /// Constants of one family (stiffness > 0 or +infinity, damping >= 0, finite).
  Status set_family(SpringFamily family, const SpringConstants& constants);
  SpringConstants family(SpringFamily family) const;

  std::size_t particle_count() const;
  std::size_t spring_count() const;
  /// A cloth's particle at grid column ix (along x) and row iz (along z).
  Status cloth_index(uint32_t ix, uint32_t iz, uint32_t* index) const;

  Status set_particle_mass(uint32_t index, float mass);
  /// Sets every particle's mass (pinned particles stay pinned; unpin restores the mass).
  Status set_mass(float mass);
  Status pin(uint32_t index);
  Status unpin(uint32_t index);
  Status is_pinned(uint32_t index, bool* pinned) const;
  Status get_position(uint32_t index, vec3* position) const;
  Status get_velocity(uint32_t index, vec3* velocity) const;
  /// Teleports the particle (how a pinned particle is moved); its velocity is kept.
  Status set_position(uint32_t index, const vec3& position);
  Status set_velocity(uint32_t index, const vec3& velocity);

  /// Adds a distance joint (family joint); *index (optional) numbers it among joints.
  Status add_joint(const ParticleJointDef& def, uint32_t* index = nullptr);
  /// A ball joint: a and b held together (a zero-length distance joint).
  Status add_ball_joint(uint32_t a, uint32_t b);
  /// A hinge: (a0, b0) and (a1, b1) held together, so the parts turn about the line a0-a1.
  Status add_hinge_joint(uint32_t a0, uint32_t b0, uint32_t a1, uint32_t b1);

  /// Static colliders, as in ParticleSystem; *index names it until removed (reused lowest
  /// first). A mesh collider keeps a reference: the mesh must outlive the body's use of it.
  Status add_collider(const Sphere& sphere, uint32_t* index);
  Status add_collider(const AABB& box, uint32_t* index);
  Status add_collider(const OBB& box, uint32_t* index);
  Status add_collider(const Plane& plane, uint32_t* index);
  Status add_collider(const TriangleMesh& mesh, uint32_t* index);
  Status remove_collider(uint32_t index);
  void clear_colliders();
  std::size_t collider_count() const;

  /// Advances by dt seconds (dt > 0 and finite) in settings().substeps sub-steps.
  Status step(float dt);

  SoftView view() const;
  SoftStats stats() const;
  /// The 64-bit witness of the whole state (settings, families, particles, springs, colliders).
  uint64_t hash() const;

  struct Impl;

 private:
  friend struct detail::SoftAccess;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gyro
