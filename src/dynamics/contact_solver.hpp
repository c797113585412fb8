// The contact solver: sequential impulses with accumulated, clamped totals (the appendix's
// arbiters), warm starting, Coulomb friction along two tangents and restitution, run colour
// by colour so every pass is parallel and deterministic.
//
// Layout: constraints live in structure-of-arrays fields, one colour after another, each
// colour's range padded with inert constraints, so a SIMD batch never spans two colours.
// Within a colour no two constraints share a dynamic body, so a kernel may solve
// them in any grouping: lane k computes exactly what the scalar path computes for
// constraint k, and the result is the same at every SIMD width and thread count.
//
// Body state during the step is a dense array of SolverBody (one cache line each, two rows
// of 8 floats: a batch of constraints loads a row of each of its bodies and transposes them
// into lanes, solver_body_rows.hpp). Index `dummy` is a body that never moves (static or
// sleeping bodies map to it); only bodies flagged dynamic are written back.
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

inline constexpr std::size_t kConstraintAlign = 16;

struct alignas(64) SolverBody {
  // First half: what every pass reads and writes (kernels move it as one 8-float row).
  float v[3];        ///< linear velocity
  float w[3];        ///< angular velocity (world)
  uint32_t dynamic;  ///< written by the solver
  float pad0;
  // Second half: read by the biased passes only.
  float dp[3];      ///< displacement since the start of the step
  float dtheta[3];  ///< rotation since the start of the step, as the sum of h w (small angles)
  float pad1[2];
};
static_assert(sizeof(SolverBody) == 64);

// Field indices of a constraint (one manifold of up to 4 points). Non-penetration is solved
// per point; friction per manifold at the points' centre (patch friction, as PhysX does):
// two tangent rows and one twist row about the normal, bounded by mu times the manifold's
// total normal impulse. Three rows instead of eight, and no spurious torque from solving the
// points' friction one after another. For every row the lever arms (r x d) and their images
// under the inverse world inertia are precomputed, so a pass needs no matrix and no anchor:
// an impulse lambda along d changes wa by -(Ia (ra x d)) lambda, and the velocity along d is
// dot(vb - va, d) + dot(wb, rb x d) - dot(wa, ra x d).
enum ConstraintField : uint32_t {
  kNx, kNy, kNz, kT1x, kT1y, kT1z, kT2x, kT2y, kT2z,
  kFriction, kRestitution, kMassA, kMassB,
  kFrictionBase,                    ///< + 12 * tangent (0, 1): armA, armB, impA, impB (3 each)
  kTwistImpA = kFrictionBase + 24,  ///< Ia n (3)
  kTwistImpB = kTwistImpA + 3,      ///< Ib n (3)
  kTangentMass1 = kTwistImpB + 3, kTangentMass2, kTwistMass,
  kTangentImpulse1, kTangentImpulse2, kTwistImpulse,
  kTwistRadius,  ///< mean distance of the points from their centre
  kPointBase,
};
// Per point j, field kPointBase + j * kPointFields + offset.
enum PointField : uint32_t {
  kArmA = 0,   ///< ra x n (3 floats)
  kArmB = 3,   ///< rb x n
  kImpA = 6,   ///< Ia (ra x n)
  kImpB = 9,   ///< Ib (rb x n)
  kSeparation = 12,  ///< at the start of the step; moves with dp and dtheta
  kNormalMass, kNormalImpulse, kMaxNormalImpulse, kRelativeVelocity,
  kPointFields,
};
// Offsets inside a row block (friction rows and points share the layout).
inline constexpr uint32_t kRowArmA = 0, kRowArmB = 3, kRowImpA = 6, kRowImpB = 9;
// (Casts: with gyro's templated vector operators in scope, clang resolves enum * integer
// against them and fails instead of falling back to the built-in operator.)
inline constexpr uint32_t kConstraintFields = uint32_t(kPointBase) + 4u * uint32_t(kPointFields);
inline constexpr uint32_t point_field(uint32_t j, uint32_t f) {
  return uint32_t(kPointBase) + j * uint32_t(kPointFields) + f;
}
// The fields are stored in blocks of kConstraintAlign constraints (AoSoA): block b holds
// field 0 of its constraints, then field 1, ... A SIMD batch (of at most kConstraintAlign
// lanes, starting at a multiple of its width) reads each field with one aligned load, and
// all its fields lie in one contiguous run of memory instead of one stream per field.
inline constexpr std::size_t field_index(uint32_t field, std::size_t k) {
  return ((k / kConstraintAlign) * kConstraintFields + field) * kConstraintAlign + k % kConstraintAlign;
}

// Inputs of the prepare kernel that the fields do not hold, staged per constraint by the
// scalar code in blocks laid out like the fields (stage_index).
enum StageField : uint32_t {
  kStagePa = 0,       ///< position of body a (3)
  kStagePb = 3,       ///< position of body b (3)
  kStageIa = 6,       ///< world inverse inertia of a, symmetric (6)
  kStageIb = 12,      ///< of b (6)
  kStageCount = 18,   ///< point count, as a float (0 for padding)
  kStagePoints = 19,  ///< + 3 * j: position of point j (3)
  kStageFields = 31,
};
inline constexpr std::size_t stage_index(uint32_t field, std::size_t k) {
  return ((k / kConstraintAlign) * std::size_t(kStageFields) + field) * kConstraintAlign + k % kConstraintAlign;
}

/// How the velocity iterations push penetrating contacts apart.
enum class BiasMode : uint32_t {
  none = 0,       ///< speculative only (relaxation, linear projection)
  soft = 1,       ///< soft constraint (Box2D v3's soft step)
  baumgarte = 2,  ///< rigid constraint with a Baumgarte velocity bias beyond the slop
};

struct Softness {
  float bias_rate = 0.0f, mass_scale = 1.0f, impulse_scale = 0.0f;
};

struct ContactKernelArgs {
  SolverBody* bodies = nullptr;
  const uint32_t* body_a = nullptr;
  const uint32_t* body_b = nullptr;
  float* f = nullptr;  ///< the constraint fields, blocks as field_index() lays them out
  BiasMode mode = BiasMode::none;
  float inv_h = 0.0f;          ///< 1 / sub-step
  Softness soft, soft_static;  ///< between two movable bodies / against an immovable one
  float baumgarte_rate = 0.0f; ///< baumgarte: fraction per second (beta / h)
  float slop = 0.0f;
  float max_push = 0.0f;       ///< cap on the bias velocity
  float restitution_threshold = 0.0f;
  uint32_t track_max_impulse = 0;  ///< keep each point's largest applied impulse (only restitution reads it)
  uint32_t reverse = 0;  ///< solve a manifold's points 3..0 instead of 0..3 (alternated per pass)
};

/// The prepare kernel's view: it reads the normal and masses already in the fields and the
/// staged inputs, and writes the friction basis, every row's lever arms, inertia images and
/// effective mass, the points' relative normal velocities and the twist radius.
struct ContactPrepareArgs {
  const SolverBody* bodies = nullptr;
  const uint32_t* body_a = nullptr;
  const uint32_t* body_b = nullptr;
  float* f = nullptr;
  const float* stage = nullptr;
};

}  // namespace detail

using contact_prepare_fn = void(const detail::ContactPrepareArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(contact_prepare, contact_prepare_fn)
using contact_pass_fn = void(const detail::ContactKernelArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(contact_warm_start, contact_pass_fn)
GYRO_KERNEL(contact_solve, contact_pass_fn)
GYRO_KERNEL(contact_restitution, contact_pass_fn)

}  // namespace gyro

#include "core/columns.hpp"
#include "dynamics/constraint_graph.hpp"
#include "dynamics/contacts.hpp"
#include "gyro/world.hpp"

#include <vector>

namespace gyro::detail {

/// Per-step inputs of the solver's prepare(): the bodies as the solver sees them.
struct SolverBodies {
  SolverBody* bodies = nullptr;      ///< count + 1 entries; the last is the immovable dummy
  const float* inv_inertia = nullptr;  ///< 6 per body: world inverse inertia at the step start
  const float* inv_mass = nullptr;     ///< per body
  const uint8_t* writable = nullptr;   ///< per body: dynamic (count + 1 entries, dummy 0)
  const uint32_t* index_of_slot = nullptr;  ///< per body slot: solver body, or the dummy
  std::size_t count = 0;
  uint32_t dummy() const { return uint32_t(count); }
};

class ContactSolver {
 public:
  /// Builds the constraints of the records that touch a solver body, colours them and fills
  /// the SoA fields (anchors, masses, warm-start impulses). Returns the colour count.
  uint32_t prepare(const BodyStore& store, const std::vector<ContactRecord>& records, const SolverBodies& sb,
                   const WorldDef& def, float dt, float h);
  void warm_start();
  /// One velocity iteration with the given bias.
  void solve(BiasMode mode);
  void restitution();
  /// The book's linear projection: pushes penetrating bodies apart along the normal.
  void project_positions(BodyStore& store, const uint32_t* slot_of_body);
  /// Accumulated impulses back to the records (for warm starting next step).
  void store_impulses(std::vector<ContactRecord>& records) const;

  std::size_t constraint_count() const { return count_; }
  uint32_t colors() const { return plan_.colors(); }

 private:
  void run(contact_pass_fn* pass, const ContactKernelArgs& args) const;
  ContactKernelArgs args_for(BiasMode mode) const;

  ConstraintGraph graph_;
  ColorPlan plan_;
  std::vector<uint32_t> record_;                // constraint -> record
  std::vector<uint32_t> cand_a_, cand_b_;       // constraint -> solver bodies (colouring input)
  Column<uint32_t> body_a_, body_b_;            // padded slot -> solver bodies
  Column<uint32_t> record_of_slot_;             // padded slot -> record (kNoRecord for padding)
  Column<float> fields_;  // field_index() layout
  Column<float> stage_;   // stage_index() layout
  std::size_t count_ = 0;
  bool any_restitution_ = false;
  uint32_t passes_ = 0;  // solve passes this step: odd ones visit the points in reverse
  SolverBodies sb_;
  const WorldDef* def_ = nullptr;
  float dt_ = 0.0f, h_ = 0.0f;
};

}  // namespace gyro::detail
