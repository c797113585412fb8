#include "dynamics/contact_solver.hpp"

#include "core/parallel.hpp"

#include <cmath>

namespace gyro::detail {
namespace {

constexpr uint32_t kNoRecord = 0xFFFFFFFFu;
// A colour is cut into one chunk per thread (per_thread_chunk), of at least kMinSolveChunk
// constraints and a multiple of 16 (every chunk starts a SIMD batch); a pass with no colour
// of two chunks runs on the calling thread. A chunk of 128 is ~5 us of solving on one core,
// against ~1 us for an OpenMP barrier on a small VM. Within a colour the constraints share no
// dynamic body, so how the colour is cut (and so the thread count) cannot change a result.
constexpr std::size_t kMinSolveChunk = 128;
std::size_t solve_chunk(std::size_t n) { return per_thread_chunk(n, kMinSolveChunk, kConstraintAlign); }

// Box2D v3's soft constraint coefficients for a spring of `hertz` with damping ratio `zeta`
// stepped implicitly with sub-step h.
Softness make_soft(float hertz, float zeta, float h) {
  if (hertz == 0.0f) return {};
  const float omega = 6.28318530717958648f * hertz;
  const float a1 = 2.0f * zeta + h * omega;
  const float a2 = h * omega * a1;
  const float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

}  // namespace

uint32_t ContactSolver::prepare(const BodyStore& s, const std::vector<ContactRecord>& records, const SolverBodies& sb,
                                const WorldDef& def, float dt, float h) {
  sb_ = sb;
  def_ = &def;
  passes_ = 0;
  dt_ = dt, h_ = h;
  // 1. Constraints: records with points that involve at least one solver body that moves.
  record_.clear(), cand_a_.clear(), cand_b_.clear();
  for (uint32_t r = 0; r < records.size(); ++r) {
    const ContactRecord& rec = records[r];
    if (rec.manifold.count == 0) continue;
    const uint32_t a = sb.index_of_slot[rec.slot_a], b = sb.index_of_slot[rec.slot_b];
    if (!sb.writable[a] && !sb.writable[b]) continue;
    record_.push_back(r), cand_a_.push_back(a), cand_b_.push_back(b);
  }
  count_ = record_.size();
  any_restitution_ = false;
  for (uint32_t r : record_) any_restitution_ = any_restitution_ || records[r].restitution > 0.0f;

  // 2. Colours, and the padded SoA layout.
  graph_.color(cand_a_.data(), cand_b_.data(), count_, sb.writable, sb.count + 1, kConstraintAlign, plan_);
  const std::size_t slots = plan_.padded_total;
  body_a_.resize(slots, sb.dummy()), body_b_.resize(slots, sb.dummy());
  record_of_slot_.resize(slots, kNoRecord);
  for (std::size_t k = 0; k < slots; ++k) body_a_[k] = body_b_[k] = sb.dummy(), record_of_slot_[k] = kNoRecord;
  for (uint32_t c = 0; c < plan_.colors(); ++c) {
    for (uint32_t k = plan_.color_first[c]; k < plan_.color_first[c + 1]; ++k) {
      const uint32_t slot = plan_.padded_first[c] + (k - plan_.color_first[c]);
      const uint32_t i = plan_.order[k];
      body_a_[slot] = cand_a_[i], body_b_[slot] = cand_b_[i], record_of_slot_[slot] = record_[i];
    }
  }
  fields_.resize(slots * kConstraintFields, 0.0f);  // slots is a multiple of kConstraintAlign

  // 3. Fields, in parallel over fixed chunks of slots (each slot writes only its own): the
  // scalar code copies what needs no arithmetic and stages the rest, the prepare kernel
  // computes the rows in lanes.
  stage_.resize(slots * std::size_t(kStageFields), 0.0f);
  const bool warm = def.enable_warm_starting;
  contact_prepare_fn* const kernel = GYRO_DISPATCH(contact_prepare);
  ContactPrepareArgs pa_args;
  pa_args.bodies = sb.bodies, pa_args.body_a = body_a_.data(), pa_args.body_b = body_b_.data();
  pa_args.f = fields_.data(), pa_args.stage = stage_.data();
  parallel_for(slots, 1024, [&](std::size_t begin, std::size_t end) {
    float* const fields = fields_.data();
    float* const stage = stage_.data();
    for (std::size_t k = begin; k < end; ++k) {
      auto F = [&](uint32_t x) -> float& { return fields[field_index(x, k)]; };
      auto S = [&](uint32_t x) -> float& { return stage[stage_index(x, k)]; };
      const uint32_t r = record_of_slot_[k];
      if (r == kNoRecord) {  // padding: an inert constraint (zero masses and impulses)
        for (uint32_t x = 0; x < kConstraintFields; ++x) F(x) = 0.0f;
        for (uint32_t x = 0; x < kStageFields; ++x) S(x) = 0.0f;
        continue;
      }
      const ContactRecord& rec = records[r];
      const uint32_t count = rec.manifold.count;
      for (uint32_t x = point_field(count, 0); x < kConstraintFields; ++x) F(x) = 0.0f;
      const uint32_t a = body_a_[k], b = body_b_[k];
      const vec3 n = rec.manifold.normal;
      F(kNx) = n.x, F(kNy) = n.y, F(kNz) = n.z;
      F(kFriction) = rec.friction, F(kRestitution) = rec.restitution;
      F(kMassA) = sb.inv_mass[a], F(kMassB) = sb.inv_mass[b];
      for (uint32_t j = 0; j < count; ++j) {
        F(point_field(j, kSeparation)) = rec.manifold.points[j].separation;
        F(point_field(j, kNormalImpulse)) = warm ? rec.normal_impulse[j] : 0.0f;
        F(point_field(j, kMaxNormalImpulse)) = 0.0f;
      }
      F(kTangentImpulse1) = warm ? rec.friction_impulse[0] : 0.0f;
      F(kTangentImpulse2) = warm ? rec.friction_impulse[1] : 0.0f;
      F(kTwistImpulse) = warm ? rec.friction_impulse[2] : 0.0f;
      const vec3 pa = s.position(rec.slot_a), pb = s.position(rec.slot_b);
      for (uint32_t c = 0; c < 3; ++c) S(kStagePa + c) = pa[int(c)], S(kStagePb + c) = pb[int(c)];
      for (uint32_t c = 0; c < 6; ++c) {
        S(kStageIa + c) = sb.inv_inertia[6 * std::size_t(a) + c];
        S(kStageIb + c) = sb.inv_inertia[6 * std::size_t(b) + c];
      }
      S(kStageCount) = float(count);
      for (uint32_t j = 0; j < 4; ++j)
        for (uint32_t c = 0; c < 3; ++c) S(kStagePoints + 3 * j + c) = j < count ? rec.manifold.points[j].position[int(c)] : 0.0f;
    }
    kernel(pa_args, begin, end);
  });
  return plan_.colors();
}

ContactKernelArgs ContactSolver::args_for(BiasMode mode) const {
  ContactKernelArgs a;
  a.bodies = sb_.bodies;
  a.body_a = body_a_.data(), a.body_b = body_b_.data();
  a.f = const_cast<float*>(fields_.data());
  a.mode = mode;
  a.inv_h = 1.0f / h_;
  const float hertz = def_->contact_hertz < 0.25f * a.inv_h ? def_->contact_hertz : 0.25f * a.inv_h;
  a.soft = make_soft(hertz, def_->contact_damping_ratio, h_);
  a.soft_static = make_soft(2.0f * hertz, def_->contact_damping_ratio, h_);
  a.baumgarte_rate = def_->baumgarte * a.inv_h;
  a.slop = def_->linear_slop;
  a.max_push = def_->max_push_velocity;
  a.restitution_threshold = def_->restitution_threshold;
  a.track_max_impulse = any_restitution_ ? 1u : 0u;
  return a;
}

void ContactSolver::run(contact_pass_fn* pass, const ContactKernelArgs& args) const {
  // One parallel region for all colours of the pass, a barrier between colours.
  parallel_stages(
      plan_.colors(), 2,
      [&](std::size_t c, std::size_t* n, std::size_t* chunk) {
        *n = plan_.padded_end[c] - plan_.padded_first[c];
        *chunk = solve_chunk(*n);
      },
      [&](std::size_t c, std::size_t b, std::size_t e) { pass(args, plan_.padded_first[c] + b, plan_.padded_first[c] + e); });
}

void ContactSolver::warm_start() {
  if (count_ == 0 || !def_->enable_warm_starting) return;
  run(GYRO_DISPATCH(contact_warm_start), args_for(BiasMode::none));
}

void ContactSolver::solve(BiasMode mode) {
  if (count_ == 0) return;
  // Alternating the point order makes Gauss-Seidel symmetric over two passes: a fixed order
  // leaves a small torque on a resting box every pass (the first point takes more load),
  // which tilts tall stacks.
  ContactKernelArgs args = args_for(mode);
  args.reverse = passes_++ & 1u;
  run(GYRO_DISPATCH(contact_solve), args);
}

void ContactSolver::restitution() {
  if (count_ == 0 || !any_restitution_) return;
  run(GYRO_DISPATCH(contact_restitution), args_for(BiasMode::none));
}

void ContactSolver::project_positions(BodyStore& s, const uint32_t* slot_of_body) {
  if (count_ == 0) return;
  const float slop = def_->linear_slop, percent = def_->baumgarte;
  const float* const fields = fields_.data();
  for (uint32_t c = 0; c < plan_.colors(); ++c) {
    const std::size_t first = plan_.padded_first[c], n = plan_.padded_end[c] - first;
    parallel_for(n, solve_chunk(n), [&](std::size_t b, std::size_t e) {
      for (std::size_t k = first + b; k < first + e; ++k) {
        if (record_of_slot_[k] == kNoRecord) continue;
        auto F = [&](uint32_t x) { return fields[field_index(x, k)]; };
        SolverBody &ba = sb_.bodies[body_a_[k]], &bb = sb_.bodies[body_b_[k]];
        const float ma = F(kMassA), mb = F(kMassB);
        if (!(ma + mb > 0.0f)) continue;
        const vec3 nrm{F(kNx), F(kNy), F(kNz)};
        const vec3 d0 = vec3{bb.dp[0], bb.dp[1], bb.dp[2]} - vec3{ba.dp[0], ba.dp[1], ba.dp[2]};
        const vec3 ta{ba.dtheta[0], ba.dtheta[1], ba.dtheta[2]}, tb{bb.dtheta[0], bb.dtheta[1], bb.dtheta[2]};
        float deepest = 0.0f;
        for (uint32_t j = 0; j < 4; ++j) {
          if (F(point_field(j, kNormalMass)) == 0.0f) continue;
          auto arm = [&](uint32_t base) {
            return vec3{F(point_field(j, base)), F(point_field(j, base + 1)), F(point_field(j, base + 2))};
          };
          const float sep = ((dot(d0, nrm) + dot(tb, arm(kArmB))) - dot(ta, arm(kArmA))) + F(point_field(j, kSeparation));
          deepest = sep < deepest ? sep : deepest;
        }
        const float depth = -(deepest + slop);
        if (!(depth > 0.0f)) continue;
        const vec3 corr = nrm * (depth * percent / (ma + mb));
        auto move = [&](SolverBody& body, uint32_t solver_index, const vec3& delta) {
          if (!body.dynamic) return;
          body.dp[0] += delta.x, body.dp[1] += delta.y, body.dp[2] += delta.z;
          const uint32_t slot = slot_of_body[solver_index];
          s.px[slot] += delta.x, s.py[slot] += delta.y, s.pz[slot] += delta.z;
        };
        move(ba, body_a_[k], corr * -ma);
        move(bb, body_b_[k], corr * mb);
      }
    });
  }
}

void ContactSolver::store_impulses(std::vector<ContactRecord>& records) const {
  const float* const fields = fields_.data();
  for (std::size_t k = 0; k < plan_.padded_total; ++k) {
    const uint32_t r = record_of_slot_[k];
    if (r == kNoRecord) continue;
    auto F = [&](uint32_t x) { return fields[field_index(x, k)]; };
    ContactRecord& rec = records[r];
    for (uint32_t j = 0; j < rec.manifold.count; ++j) rec.normal_impulse[j] = F(point_field(j, kNormalImpulse));
    rec.friction_impulse[0] = F(kTangentImpulse1);
    rec.friction_impulse[1] = F(kTangentImpulse2);
    rec.friction_impulse[2] = F(kTwistImpulse);
  }
}

}  // namespace gyro::detail
