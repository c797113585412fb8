// Numeric criteria for contacts: restitution, friction on an incline, stacks, pyramids,
// mass ratios and a fast small body against a thin wall.
#include "world_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gyro {
namespace {

using test::add_box;
using test::add_ground;
using test::make_world;
using test::max_drift;
using test::position_of;
using test::positions;

constexpr float kDt = 1.0f / 60.0f;

TEST(Contacts, BounceHeightIsRestitutionSquaredTimesDropHeight) {
  for (float e : {0.5f, 0.8f}) {
    auto w = make_world();
    BodyDef g;
    g.type = BodyType::static_body;
    g.shape.type = BodyShape::plane;
    g.restitution = e;
    BodyId gid;
    ASSERT_EQ(w->create_body(g, &gid), Status::ok);
    BodyDef d;
    d.shape.type = BodyShape::sphere;
    d.shape.radius = 0.1f;
    const float h = 2.0f;
    d.position = {0.0f, h + 0.1f, 0.0f};
    d.restitution = e;
    BodyId b;
    ASSERT_EQ(w->create_body(d, &b), Status::ok);
    float apex = 0.0f;
    bool bounced = false;
    for (int i = 0; i < 240 * 3; ++i) {
      w->step(1.0f / 240.0f);
      vec3 v;
      w->get_velocity(b, &v, nullptr);
      const float y = position_of(*w, b).y - 0.1f;
      if (v.y > 0.0f) bounced = true;
      if (bounced && v.y <= 0.0f) {
        apex = y;
        break;
      }
    }
    std::printf("restitution %.2f: apex %.4f m, expected %.4f m\n", e, apex, e * e * h);
    EXPECT_NEAR(apex, e * e * h, 0.02f * e * e * h) << "e = " << e;
  }
}

// A box on a ground tilted by theta: sticks when tan(theta) < mu, else slides with
// a = g (sin theta - mu cos theta).
double incline_acceleration(float theta, float mu, double* slid) {
  auto w = make_world();
  const quat tilt = from_axis_angle({0.0f, 0.0f, 1.0f}, theta);
  BodyDef g;
  g.type = BodyType::static_body;
  g.shape.half_extents = {50.0f, 0.5f, 5.0f};
  g.orientation = tilt;
  g.position = rotate(tilt, vec3{0.0f, -0.5f, 0.0f});
  g.friction = mu;
  BodyId gid;
  w->create_body(g, &gid);
  BodyDef d;
  d.shape.half_extents = {0.5f, 0.5f, 0.5f};
  d.orientation = tilt;
  d.position = rotate(tilt, vec3{0.0f, 0.5f, 0.0f});
  d.mass = 1.0f;
  d.friction = mu;
  BodyId b;
  w->create_body(d, &b);
  for (int i = 0; i < 30; ++i) w->step(kDt);  // settle into contact
  const vec3 p0 = position_of(*w, b);
  vec3 v0;
  w->get_velocity(b, &v0, nullptr);
  const int n = 60;
  for (int i = 0; i < n; ++i) w->step(kDt);
  vec3 v1;
  w->get_velocity(b, &v1, nullptr);
  *slid = length(position_of(*w, b) - p0);
  const vec3 down = rotate(tilt, vec3{-1.0f, 0.0f, 0.0f});
  return (dot(v1, down) - dot(v0, down)) / (n * double(kDt));
}

TEST(Contacts, FrictionOnAnInclineSticksBelowTheAngleAndSlidesAbove) {
  const float mu = 0.5f;
  const float critical = std::atan(mu);
  double slid;
  for (float theta : {critical - 0.1f, critical - 0.03f}) {
    incline_acceleration(theta, mu, &slid);
    EXPECT_LT(slid, 0.01) << "theta " << theta;
  }
  for (float theta : {critical + 0.1f, critical + 0.3f}) {
    const double a = incline_acceleration(theta, mu, &slid);
    const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
    std::printf("incline %.3f rad: a = %.4f, expected %.4f (%.2f%%)\n", theta, a, expected,
                100.0 * (a - expected) / expected);
    EXPECT_NEAR(a, expected, 0.02 * expected) << "theta " << theta;
  }
}

TEST(Contacts, TenBoxStackStaysWithinOneCentimetreForTenSeconds) {
  WorldDef def;
  def.enable_sleep = false;
  auto w = make_world(def);
  add_ground(*w);
  std::vector<BodyId> ids;
  for (int i = 0; i < 10; ++i) ids.push_back(add_box(*w, {0.0f, 0.5f + float(i), 0.0f}));
  const auto start = positions(*w, ids);
  for (int i = 0; i < 600; ++i) w->step(kDt);
  const double drift = max_drift(*w, ids, start);
  std::printf("10-box stack: max drift %.5f m after 10 s\n", drift);
  EXPECT_LT(drift, 0.01);
}

TEST(Contacts, PyramidWithBaseTwentyStandsForTenSeconds) {
  WorldDef def;
  def.enable_sleep = false;
  def.threads = 1;  // the stages' parallel loops are tested elsewhere; keep this one quick
  auto w = make_world(def);
  add_ground(*w);
  const auto ids = test::add_pyramid(*w, 20);
  const auto start = positions(*w, ids);
  for (int i = 0; i < 600; ++i) w->step(kDt);
  const double drift = max_drift(*w, ids, start);
  const StepTimings& t = w->timings();
  std::printf("pyramid base 20: max drift %.5f m after 10 s, %u colours, %u contacts; last step %.3f ms (broad %.3f narrow %.3f "
              "islands %.3f solver %.3f)\n",
              drift, w->stats().colors, w->stats().contacts, t.total, t.broadphase, t.narrowphase, t.islands, t.solver);
  EXPECT_LT(drift, 0.05);
}

TEST(Contacts, MassRatioOneToHundredStackIsStable) {
  WorldDef def;
  def.enable_sleep = false;
  auto w = make_world(def);
  add_ground(*w);
  std::vector<BodyId> ids;
  ids.push_back(add_box(*w, {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, 1.0f));
  ids.push_back(add_box(*w, {0.0f, 1.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, 100.0f));
  ids.push_back(add_box(*w, {0.0f, 2.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, 1.0f));
  ids.push_back(add_box(*w, {0.0f, 3.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, 100.0f));
  const auto start = positions(*w, ids);
  for (int i = 0; i < 600; ++i) w->step(kDt);
  const double drift = max_drift(*w, ids, start);
  double speed = 0.0;
  for (BodyId id : ids) {
    vec3 v;
    w->get_velocity(id, &v, nullptr);
    speed = std::max(speed, double(length(v)));
  }
  std::printf("1:100 stack: max drift %.5f m after 10 s, max speed %.2e m/s\n", drift, speed);
  // Stable: upright, nearly at rest, nothing thrown. The soft contacts under the heavy boxes
  // settle deeper (their softness is scaled by the light boxes' effective mass): 3.2 cm of
  // sink over the four contacts, plus a slow sideways creep of 2-5 cm over 10 s that depends
  // on rounding (measured 7.5 cm in all and 1.6 cm/s at the end with the defaults). Bounded
  // here; a tighter mass-ratio answer (e.g. mass-scaled softness) is future work.
  EXPECT_LT(drift, 0.10);
  EXPECT_LT(speed, 0.05);
}

TEST(Contacts, SmallFastSphereDoesNotPassAThinWall) {
  for (ContactModel model : {ContactModel::soft_step, ContactModel::baumgarte}) {
    WorldDef def;
    def.gravity = {};
    def.contact_model = model;
    if (model != ContactModel::soft_step) def.velocity_iterations = 10;
    auto w = make_world(def);
    BodyDef wall;
    wall.type = BodyType::static_body;
    wall.shape.half_extents = {0.01f, 2.0f, 2.0f};
    wall.position = {5.0f, 0.0f, 0.0f};
    BodyId wid;
    ASSERT_EQ(w->create_body(wall, &wid), Status::ok);
    BodyDef d;
    d.shape.type = BodyShape::sphere;
    d.shape.radius = 0.005f;
    d.linear_velocity = {300.0f, 0.3f, -0.2f};
    BodyId b;
    ASSERT_EQ(w->create_body(d, &b), Status::ok);
    for (int i = 0; i < 60; ++i) w->step(kDt);
    const vec3 p = position_of(*w, b);
    EXPECT_LT(p.x, 5.0f - 0.01f) << "model " << unsigned(model);
  }
}

TEST(Contacts, LinearProjectionModelKeepsABoxOnTheGround) {
  WorldDef def;
  def.contact_model = ContactModel::linear_projection;
  def.velocity_iterations = 10;
  def.position_iterations = 2;
  auto w = make_world(def);
  add_ground(*w);
  const BodyId b = add_box(*w, {0.0f, 0.45f, 0.0f});  // starts 5 cm into the ground
  for (int i = 0; i < 120; ++i) w->step(kDt);
  EXPECT_NEAR(position_of(*w, b).y, 0.5, 0.01);
}

}  // namespace
}  // namespace gyro
