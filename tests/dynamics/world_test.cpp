// The world's API, integration against closed forms, bad input, events, sleeping, the
// determinism witness and the no-allocation-per-step rule.
#include "world_scenes.hpp"
#include "gyro/runtime.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include <cstdint>

uint64_t gyro_test_allocation_count();  // allocation_counter.cpp: heap allocations so far
bool gyro_test_counts_allocations();     // false under AddressSanitizer

namespace gyro {
namespace {

using test::add_box;
using test::add_ground;
using test::make_world;
using test::position_of;

TEST(World, FreeFallMatchesClosedFormWithinTheIntegratorsError) {
  // Semi-implicit Euler per sub-step h: y(t) = y0 - g t^2 / 2 - g t h / 2 exactly (up to rounding).
  for (uint32_t substeps : {1u, 4u}) {
    WorldDef def;
    def.substeps = substeps;
    auto w = make_world(def);
    const BodyId b = add_box(*w, {0.0f, 100.0f, 0.0f});
    const float dt = 1.0f / 60.0f;
    for (int i = 0; i < 120; ++i) ASSERT_EQ(w->step(dt), Status::ok);
    const double t = 2.0, g = 9.81, h = double(dt) / substeps;
    const double exact = 100.0 - 0.5 * g * t * t;
    const double predicted = exact - 0.5 * g * t * h;  // the scheme's own error term
    const double y = position_of(*w, b).y;
    EXPECT_NEAR(y, predicted, 2e-4) << "substeps " << substeps;
    EXPECT_NEAR(y, exact, 0.5 * g * t * h + 2e-4);  // error bound stated per integrator: g t h / 2
  }
}

TEST(World, ProjectileRange) {
  auto w = make_world();
  BodyDef d;
  d.shape.type = BodyShape::sphere;
  d.shape.radius = 0.1f;
  d.linear_velocity = {10.0f, 10.0f, 0.0f};
  BodyId b;
  ASSERT_EQ(w->create_body(d, &b), Status::ok);
  const float dt = 1.0f / 240.0f;
  for (int i = 0; i < 240; ++i) w->step(dt);
  const vec3 p = position_of(*w, b);
  EXPECT_NEAR(p.x, 10.0, 1e-4);
  const double h = (1.0 / 240.0) / WorldDef{}.substeps;  // semi-implicit Euler error: g t h / 2
  EXPECT_NEAR(p.y, 10.0 - 0.5 * 9.81 - 0.5 * 9.81 * h, 1e-3);
}

TEST(World, TorqueFreeSpinningBoxConservesMomentumAndEnergy) {
  WorldDef def;
  def.gravity = {};
  auto w = make_world(def);
  BodyDef d;
  d.shape.half_extents = {0.1f, 0.5f, 1.0f};
  d.mass = 2.0f;
  d.angular_velocity = {4.0f, 0.2f, 0.1f};  // about the major axis (x: stable) with a wobble
  BodyId b;
  ASSERT_EQ(w->create_body(d, &b), Status::ok);
  auto invariants = [&](double* L, double* E) {
    vec3 wv;
    quat q;
    w->get_velocity(b, nullptr, &wv);
    w->get_transform(b, nullptr, &q);
    const double m = 2.0, hx = 0.1, hy = 0.5, hz = 1.0;
    const double I[3] = {m * (hy * hy + hz * hz) / 3, m * (hx * hx + hz * hz) / 3, m * (hx * hx + hy * hy) / 3};
    const vec3 wb = rotate(conjugate(q), wv);
    const double lb[3] = {I[0] * wb.x, I[1] * wb.y, I[2] * wb.z};
    *L = std::sqrt(lb[0] * lb[0] + lb[1] * lb[1] + lb[2] * lb[2]);
    *E = 0.5 * (lb[0] * wb.x + lb[1] * wb.y + lb[2] * wb.z);
    // World-frame momentum direction: rotate the body-frame L back.
    const vec3 lw = rotate(q, vec3{float(lb[0]), float(lb[1]), float(lb[2])});
    L[1] = lw.x, L[2] = lw.y, L[3] = lw.z;
  };
  double L0[4], E0, L1[4], E1;
  invariants(L0, &E0);
  for (int i = 0; i < 600; ++i) ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
  invariants(L1, &E1);
  // The implicit gyroscopic step is stable and slightly dissipative: stated tolerance 2% over 10 s.
  EXPECT_NEAR(L1[0], L0[0], 0.02 * L0[0]);
  EXPECT_NEAR(E1, E0, 0.02 * E0);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(L1[k], L0[k], 0.03 * L0[0]) << "component " << k;
}

TEST(World, BadInputChangesNothing) {
  auto w = make_world();
  add_ground(*w);
  const BodyId b = add_box(*w, {0.0f, 2.0f, 0.0f});
  w->step(1.0f / 60.0f);
  const uint64_t h0 = w->hash();
  const float nan = std::nanf(""), inf = INFINITY;
  BodyId out;
  BodyDef d;
  d.position = {nan, 0.0f, 0.0f};
  EXPECT_EQ(w->create_body(d, &out), Status::non_finite);
  d = BodyDef{};
  d.mass = -1.0f;
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);
  d.mass = nan;
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);
  d = BodyDef{};
  d.shape.half_extents = {0.0f, 1.0f, 1.0f};
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);
  d = BodyDef{};
  d.shape.type = BodyShape::sphere;
  d.shape.radius = -1.0f;
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);
  d = BodyDef{};
  d.orientation = {0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);
  d = BodyDef{};
  d.shape.type = BodyShape::plane;
  EXPECT_EQ(w->create_body(d, &out), Status::invalid_argument);  // a dynamic plane
  d = BodyDef{};
  d.shape.type = BodyShape::mesh;
  d.type = BodyType::static_body;
  EXPECT_EQ(w->create_body(d, &out), Status::null_argument);
  EXPECT_EQ(w->create_body(BodyDef{}, nullptr), Status::null_argument);
  EXPECT_EQ(w->apply_force_at_center(b, {inf, 0.0f, 0.0f}), Status::non_finite);
  EXPECT_EQ(w->apply_linear_impulse(b, {0.0f, nan, 0.0f}, {}), Status::non_finite);
  EXPECT_EQ(w->set_velocity(b, {nan, 0.0f, 0.0f}, {}), Status::non_finite);
  EXPECT_EQ(w->set_transform(b, {}, quat{0.0f, 0.0f, 0.0f, 0.0f}), Status::invalid_argument);
  EXPECT_EQ(w->step(0.0f), Status::invalid_argument);
  EXPECT_EQ(w->step(-1.0f), Status::invalid_argument);
  EXPECT_EQ(w->step(nan), Status::invalid_argument);
  EXPECT_EQ(w->step(inf), Status::invalid_argument);
  const BodyId stale{b.index, b.generation + 1};
  EXPECT_EQ(w->set_velocity(stale, {}, {}), Status::stale_id);
  EXPECT_EQ(w->destroy_body(stale), Status::stale_id);
  EXPECT_EQ(w->destroy_body(BodyId{}), Status::stale_id);
  EXPECT_EQ(w->hash(), h0);

  WorldDef bad;
  std::unique_ptr<World> none;
  bad.gravity = {nan, 0.0f, 0.0f};
  EXPECT_EQ(World::create(bad, &none), Status::non_finite);
  bad = WorldDef{};
  bad.substeps = 0;
  EXPECT_EQ(World::create(bad, &none), Status::invalid_argument);
  EXPECT_EQ(none, nullptr);
}

TEST(World, DestroyedIdsAreStaleAndSlotsStayDense) {
  auto w = make_world();
  const BodyId a = add_box(*w, {0.0f, 1.0f, 0.0f}), b = add_box(*w, {3.0f, 1.0f, 0.0f});
  const BodyId c = add_box(*w, {6.0f, 1.0f, 0.0f});
  ASSERT_EQ(w->destroy_body(a), Status::ok);
  EXPECT_FALSE(w->is_valid(a));
  EXPECT_TRUE(w->is_valid(b) && w->is_valid(c));
  EXPECT_EQ(w->body_count(), 2u);
  const BodyView v = w->bodies();
  ASSERT_EQ(v.count, 2u);
  for (std::size_t i = 0; i < v.count; ++i) {
    vec3 p;
    ASSERT_EQ(w->get_transform(v.ids[i], &p, nullptr), Status::ok);
    EXPECT_EQ(p.x, v.px[i]);
  }
  const BodyId d = add_box(*w, {9.0f, 1.0f, 0.0f});
  EXPECT_EQ(d.index, a.index);  // the index is reused with a new generation
  EXPECT_NE(d.generation, a.generation);
}

TEST(World, BoxComesToRestOnGroundAndEventsReportTheTouch) {
  auto w = make_world();
  const BodyId g = add_ground(*w);
  const BodyId b = add_box(*w, {0.0f, 1.0f, 0.0f});
  int begins = 0, ends = 0;
  for (int i = 0; i < 120; ++i) {
    w->step(1.0f / 60.0f);
    const ContactEvent* e;
    const std::size_t nb = w->begin_events(&e);
    for (std::size_t k = 0; k < nb; ++k) {
      EXPECT_TRUE((e[k].a == g && e[k].b == b) || (e[k].a == b && e[k].b == g));
      ++begins;
    }
    ends += int(w->end_events(nullptr));
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 0);
  EXPECT_NEAR(position_of(*w, b).y, 0.5, 0.01);
}

TEST(World, RestingBodiesSleepAndWakeOnImpulse) {
  auto w = make_world();
  add_ground(*w);
  const BodyId b = add_box(*w, {0.0f, 0.5f, 0.0f});
  const BodyId c = add_box(*w, {0.0f, 1.5f, 0.0f});
  bool awake = true;
  for (int i = 0; i < 180 && awake; ++i) {
    w->step(1.0f / 60.0f);
    w->is_awake(c, &awake);
  }
  EXPECT_FALSE(awake);
  w->is_awake(b, &awake);
  EXPECT_FALSE(awake);  // the island sleeps as a whole
  EXPECT_EQ(w->stats().awake_bodies, 0u);
  const uint64_t h = w->hash();
  for (int i = 0; i < 10; ++i) w->step(1.0f / 60.0f);
  vec3 p;
  w->get_transform(c, &p, nullptr);
  EXPECT_NEAR(p.y, 1.5, 0.02);
  EXPECT_NE(h, w->hash());  // the step counter moves, the bodies do not
  ASSERT_EQ(w->apply_linear_impulse(b, {3.0f, 0.0f, 0.0f}, position_of(*w, b)), Status::ok);
  w->step(1.0f / 60.0f);
  w->is_awake(c, &awake);
  EXPECT_TRUE(awake);  // woken through the island
}

uint64_t run_pile(uint32_t threads, SimdLevel level, int steps) {
  EXPECT_EQ(set_simd_level(level), Status::ok);
  WorldDef def;
  def.threads = threads;
  auto w = make_world(def);
  add_ground(*w);
  test::add_pyramid(*w, 8);
  BodyDef s;
  s.shape.type = BodyShape::sphere;
  s.shape.radius = 0.3f;
  s.position = {0.3f, 12.0f, 0.1f};
  s.restitution = 0.5f;
  BodyId id;
  w->create_body(s, &id);
  for (int i = 0; i < steps; ++i) w->step(1.0f / 60.0f);
  set_simd_level(SimdLevel::automatic);
  return w->hash();
}

TEST(World, HashIsIdenticalAcrossThreadsAndSimdLevels) {
  const uint64_t ref = run_pile(1, SimdLevel::scalar, 90);
  for (SimdLevel level : {SimdLevel::scalar, SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    for (uint32_t t : {1u, 2u, 3u}) EXPECT_EQ(run_pile(t, level, 90), ref) << simd_level_name(level) << " x" << t;
  }
}

// A body spinning so fast that q + (w, 0) q h / 2 has a squared length above 2^100: the
// position kernel hands its whole batch to the scalar code (normalized() rescales there).
// The bodies sharing the batch, and every level and thread count, must give the same bits.
uint64_t run_extreme_spin(uint32_t threads, SimdLevel level, quat* spun) {
  EXPECT_EQ(set_simd_level(level), Status::ok);
  WorldDef def;
  def.threads = threads;
  auto w = make_world(def);
  BodyDef d;
  d.shape.type = BodyShape::box;
  d.shape.half_extents = {0.5f, 0.5f, 0.5f};
  d.position = {40.0f, 5.0f, 0.0f};
  d.angular_velocity = {1.0e23f, 3.0e22f, -2.0e22f};  // squares of ~1e20 overflow float
  d.linear_damping = 0.0f;
  BodyId id;
  EXPECT_EQ(w->create_body(d, &id), Status::ok);  // first: solver body 0, in a full batch of lanes
  add_ground(*w);
  test::add_pyramid(*w, 6);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(w->step(1.0f / 60.0f), Status::ok);
  w->get_transform(id, nullptr, spun);
  set_simd_level(SimdLevel::automatic);
  return w->hash();
}

TEST(World, ExtremeSpinTakesTheScalarIntegrationWithTheSameBits) {
  quat q;
  const uint64_t ref = run_extreme_spin(1, SimdLevel::scalar, &q);
  EXPECT_NEAR(length(q), 1.0f, 1e-6f);  // rescaled, then normalised: still a rotation
  for (SimdLevel level : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    for (uint32_t t : {1u, 2u}) EXPECT_EQ(run_extreme_spin(t, level, &q), ref) << simd_level_name(level) << " x" << t;
  }
}

// Forty free bodies in batches of lanes: thin boxes (the gyroscopic Newton step), cubes (no
// gyroscopic term) and kinematic boxes (no integration) mixed in every batch, spinning at
// rates up to one where the Newton step's determinant overflows (the step is skipped).
uint64_t run_gyroscopic(uint32_t threads, SimdLevel level, float* momentum_change) {
  EXPECT_EQ(set_simd_level(level), Status::ok);
  WorldDef def;
  def.threads = threads;
  def.gravity = {0.0f, 0.0f, 0.0f};
  def.enable_continuous = false;  // body 17's swept bounds would reach every other body
  auto w = make_world(def);
  std::vector<BodyId> ids;
  for (int k = 0; k < 40; ++k) {
    BodyDef d;
    d.shape.type = BodyShape::box;
    d.shape.half_extents = k % 5 == 1 ? vec3{0.4f, 0.4f, 0.4f} : vec3{0.1f + 0.01f * float(k % 7), 0.5f, 1.0f};
    d.type = k % 9 == 4 ? BodyType::kinematic : BodyType::dynamic;
    d.position = {3.0f * float(k % 8), 3.0f * float(k / 8), 0.0f};
    d.orientation = normalized(quat{0.1f * float(k % 3), 0.2f, -0.05f * float(k % 4), 1.0f});
    const float rate = k == 17 ? 1.0e18f : 1.0f + 0.7f * float(k);
    d.angular_velocity = {rate, 0.3f * rate * float(k % 2), -0.2f * rate};
    d.angular_damping = k % 4 == 0 ? 0.5f : 0.0f;
    d.linear_velocity = {0.1f * float(k % 3), 0.0f, 0.0f};
    d.allow_sleep = false;
    BodyId id;
    EXPECT_EQ(w->create_body(d, &id), Status::ok);
    ids.push_back(id);
  }
  // Angular momentum of body 2 (thin box, undamped): I_world w, before and after.
  auto momentum = [&](BodyId id) {
    vec3 v, av;
    quat q;
    w->get_velocity(id, &v, &av);
    w->get_transform(id, nullptr, &q);
    const vec3 wb = rotate(conjugate(q), av);
    const float m = 1.0f * 0.22f * 1.0f * 2.0f * 8.0f;  // density 1: volume of half extents (0.12, 0.5, 1)
    const vec3 e{0.12f, 0.5f, 1.0f};
    const vec3 ib{m / 3.0f * (e.y * e.y + e.z * e.z), m / 3.0f * (e.x * e.x + e.z * e.z), m / 3.0f * (e.x * e.x + e.y * e.y)};
    return rotate(q, vec3{ib.x * wb.x, ib.y * wb.y, ib.z * wb.z});
  };
  const vec3 before = momentum(ids[2]);
  for (int i = 0; i < 60; ++i) EXPECT_EQ(w->step(1.0f / 60.0f), Status::ok);
  *momentum_change = length(momentum(ids[2]) - before) / length(before);
  set_simd_level(SimdLevel::automatic);
  return w->hash();
}

TEST(World, GyroscopicIntegrationInLanesMatchesTheScalarBits) {
  float dl = 0.0f;
  const uint64_t ref = run_gyroscopic(1, SimdLevel::scalar, &dl);
  std::printf("relative change of angular momentum over 1 s: %g\n", double(dl));
  EXPECT_LT(dl, 0.01f);  // a torque-free thin box: the implicit step keeps it within 1%
  for (SimdLevel level : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::neon}) {
    if (!simd_level_available(level)) continue;
    for (uint32_t t : {1u, 2u}) EXPECT_EQ(run_gyroscopic(t, level, &dl), ref) << simd_level_name(level) << " x" << t;
  }
}

TEST(World, NoHeapAllocationPerStepAfterWarmUp) {
  if (!gyro_test_counts_allocations()) GTEST_SKIP() << "the sanitizer owns the allocator; the plain build checks this";
  WorldDef def;
  def.threads = 1;
  auto w = make_world(def);
  add_ground(*w);
  test::add_pyramid(*w, 10);
  for (int i = 0; i < 60; ++i) w->step(1.0f / 60.0f);
  const uint64_t before = gyro_test_allocation_count();
  for (int i = 0; i < 60; ++i) w->step(1.0f / 60.0f);
  EXPECT_EQ(gyro_test_allocation_count() - before, 0u);
}

TEST(World, EmptyAndStaticWorldsSkipTheStages) {
  if (!gyro_test_counts_allocations()) GTEST_SKIP() << "the sanitizer owns the allocator; the plain build checks this";
  auto w = make_world();
  for (int i = 0; i < 3; ++i) ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
  add_ground(*w);
  add_ground(*w, 5.0f);
  w->step(1.0f / 60.0f);  // scratch sized for the new body count once
  const uint64_t before = gyro_test_allocation_count();
  for (int i = 0; i < 10; ++i) w->step(1.0f / 60.0f);
  EXPECT_EQ(gyro_test_allocation_count() - before, 0u);
  EXPECT_EQ(w->stats().pairs, 0u);
  EXPECT_EQ(w->stats().contacts, 0u);
}

// Finite but enormous settings let bodies overflow to infinity within a step or two; the
// world must keep stepping (those bodies drop out of the broadphase) and never crash. Found
// by restoring snapshots with altered bytes.
TEST(WorldBadInput, BodiesThatOverflowToInfinityDoNotBreakTheStep) {
  WorldDef def;
  def.gravity = {0.0f, -3.0e38f, 0.0f};
  auto w = make_world(def);
  ASSERT_NE(w, nullptr);
  add_ground(*w);
  for (int i = 0; i < 6; ++i) add_box(*w, {0.3f * float(i), 1.0f + 1.1f * float(i), 0.0f});
  BodyId fast = add_box(*w, {5.0f, 1.0f, 0.0f});
  ASSERT_EQ(w->set_velocity(fast, {3.0e38f, 3.0e38f, 0.0f}, {}), Status::ok);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(w->step(i < 4 ? 100.0f : 1.0f / 60.0f), Status::ok);
  vec3 p = position_of(*w, fast);
  EXPECT_FALSE(p.x >= -3.0e38f && p.x <= 3.0e38f);  // it did overflow
  EXPECT_NE(w->hash(), 0u);
}

}  // namespace
}  // namespace gyro
