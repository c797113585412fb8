// Capsules and convex hulls as rigid bodies: mass frames, resting heights, stacks of hulls
// (clipped one-shot manifolds against the appendix's incremental arbiter), meshes, bad input.
#include "gyro/convex.hpp"
#include "gyro/mesh.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/triangle_mesh.hpp"
#include "world_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace gyro {
namespace {

using test::add_ground;
using test::add_plane;
using test::max_drift;
using test::positions;
using test::make_world;
using test::position_of;

constexpr float kDt = 1.0f / 60.0f;
constexpr float kPi = 3.14159265f;

ConvexHull box_hull(vec3 half, vec3 offset = {}) {
  std::vector<vec3> pts;
  for (int i = 0; i < 8; ++i)
    pts.push_back(offset + vec3{(i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y, (i & 4) ? half.z : -half.z});
  ConvexHull h;
  EXPECT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  return h;
}

// A prism over a regular polygon with `sides` corners, axis y, height 2 hy.
ConvexHull prism_hull(int sides, float radius, float hy) {
  std::vector<vec3> pts;
  for (int i = 0; i < sides; ++i) {
    const float a = 2.0f * kPi * float(i) / float(sides);
    float s, c;
    gyro::sincos(a, &s, &c);
    pts.push_back({radius * c, -hy, radius * s});
    pts.push_back({radius * c, hy, radius * s});
  }
  ConvexHull h;
  EXPECT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  return h;
}

BodyId add_hull(World& w, const ConvexHull& h, vec3 p, quat q = {}, float friction = 0.6f) {
  BodyDef d;
  d.shape.type = BodyShape::hull;
  d.shape.hull = &h;
  d.position = p;
  d.orientation = q;
  d.friction = friction;
  BodyId id;
  EXPECT_EQ(w.create_body(d, &id), Status::ok);
  return id;
}

BodyId add_capsule(World& w, float r, float hh, vec3 p, quat q = {}) {
  BodyDef d;
  d.shape.type = BodyShape::capsule;
  d.shape.radius = r;
  d.shape.half_height = hh;
  d.position = p;
  d.orientation = q;
  BodyId id;
  EXPECT_EQ(w.create_body(d, &id), Status::ok);
  return id;
}

// The lowest point of a hull body in the world.
float lowest_y(const World& w, BodyId id, const ConvexHull& built) {
  vec3 p, off;
  quat q, r;
  w.get_transform(id, &p, &q);
  w.get_shape_frame(id, &off, &r);
  float lo = 1e30f;
  for (const vec3& v : built.vertices) lo = std::min(lo, (p + rotate(q, off + rotate(r, v))).y);
  return lo;
}

// EPA's witnesses on a flat side of the Minkowski difference: coplanar triangles tie in
// distance and the one holding the origin's projection must place them (clamping onto a
// neighbour put them 7.5 m off for a tilted unit box on a 100 m slab, which made the
// incremental manifold drop its points and a pyramid sink).
TEST(ConvexBodies, EpaWitnessesHoldOnAHundredToOneFacePair) {
  ConvexShape slab, box;
  ASSERT_EQ(make_box({50.0f, 0.5f, 50.0f}, slab), Status::ok);
  ASSERT_EQ(make_box({0.5f, 0.5f, 0.5f}, box), Status::ok);
  const ConvexPose ps{{0.0f, -0.5f, 0.0f}, mat3{}};
  float worst = 0.0f;
  for (int t = 0; t < 40; ++t) {
    const ConvexPose pb{{-10.5f + 0.37f * float(t), 0.49f, 0.2f * float(t % 7)},
                        to_mat3(from_axis_angle(normalized(vec3{0.3f * float(t % 3), 1.0f, 1.0f}), 0.005f * float(t)))};
    const ConvexResult r = convex_penetration(slab, ps, box, pb);
    ASSERT_EQ(r.status, ConvexStatus::intersecting);
    const vec3 residual = r.point_b - r.point_a - r.normal * r.distance;
    worst = std::max(worst, length(residual));
    // The witness on the box lies on the box.
    const vec3 local = r.point_b - pb.position;
    for (int k = 0; k < 3; ++k)
      EXPECT_LE(std::abs(dot(local, vec3{pb.rotation.m[k][0], pb.rotation.m[k][1], pb.rotation.m[k][2]})), 0.5f + 1e-4f);
  }
  std::printf("EPA witnesses, 100:1 face pairs: max |pb - pa - d n| %.2e m\n", worst);
  EXPECT_LT(worst, 1e-4f);
}

TEST(ConvexBodies, CapsuleMassAndInertiaMatchClosedForm) {
  auto w = make_world();
  const float r = 0.3f, hh = 0.5f;
  const BodyId id = add_capsule(*w, r, hh, {});
  float m = 0.0f;
  ASSERT_EQ(w->get_mass(id, &m), Status::ok);
  const float volume = kPi * r * r * 2.0f * hh + 4.0f / 3.0f * kPi * r * r * r;
  EXPECT_NEAR(m, volume, 1e-5f * volume);
  // Spinning about its axis: the angular impulse / axial inertia is the spin rate.
  const float axial = kPi * r * r * 2.0f * hh * 0.5f * r * r + 4.0f / 3.0f * kPi * r * r * r * 0.4f * r * r;
  ASSERT_EQ(w->apply_angular_impulse(id, {0.0f, axial, 0.0f}), Status::ok);
  vec3 wv;
  w->get_velocity(id, nullptr, &wv);
  EXPECT_NEAR(wv.y, 1.0f, 1e-5f);
}

TEST(ConvexBodies, HullBodyFrameIsItsMassFrame) {
  auto w = make_world();
  // An off-centre box: the body origin moves to its centroid, the shape frame says where
  // the caller's frame is.
  const ConvexHull h = box_hull({1.0f, 0.25f, 0.5f}, {2.0f, 3.0f, 4.0f});
  const quat q = from_axis_angle(normalized(vec3{1.0f, 2.0f, 3.0f}), 0.7f);
  const vec3 p{1.0f, 5.0f, -2.0f};
  const BodyId id = add_hull(*w, h, p, q);
  vec3 bp, off;
  quat bq, r;
  ASSERT_EQ(w->get_transform(id, &bp, &bq), Status::ok);
  ASSERT_EQ(w->get_shape_frame(id, &off, &r), Status::ok);
  const vec3 centroid = p + rotate(q, vec3{2.0f, 3.0f, 4.0f});
  EXPECT_NEAR(length(bp - centroid), 0.0f, 1e-4f);
  // Every built vertex maps back to where the caller put it.
  for (const vec3& v : h.vertices) {
    const vec3 caller = p + rotate(q, v);
    const vec3 body = bp + rotate(bq, off + rotate(r, v));
    EXPECT_NEAR(length(caller - body), 0.0f, 2e-4f);
  }
  float m = 0.0f;
  w->get_mass(id, &m);
  EXPECT_NEAR(m, 1.0f, 1e-4f);  // volume 2 x 0.5 x 1 = 1 m^3, density 1
  // Other shapes: identity.
  BodyDef d;
  BodyId b;
  ASSERT_EQ(w->create_body(d, &b), Status::ok);
  ASSERT_EQ(w->get_shape_frame(b, &off, &r), Status::ok);
  EXPECT_EQ(off, vec3{});
  EXPECT_EQ(r.w, 1.0f);
}

TEST(ConvexBodies, CapsulesRestAtTheirHeightOnPlaneBoxAndHull) {
  for (int ground = 0; ground < 3; ++ground) {
    auto w = make_world();
    if (ground == 0) {
      ASSERT_FALSE(add_plane(*w).is_null());
    } else if (ground == 1) {
      add_ground(*w);
    } else {
      const ConvexHull slab = box_hull({20.0f, 0.5f, 20.0f});
      BodyDef g;
      g.type = BodyType::static_body;
      g.shape.type = BodyShape::hull;
      g.shape.hull = &slab;
      g.position = {0.0f, -0.5f, 0.0f};
      BodyId gid;
      ASSERT_EQ(w->create_body(g, &gid), Status::ok);
    }
    const float r = 0.25f, hh = 0.5f;
    const BodyId lying = add_capsule(*w, r, hh, {0.0f, 1.0f, 0.0f}, from_axis_angle({0.0f, 0.0f, 1.0f}, kPi / 2));
    const BodyId standing = add_capsule(*w, r, hh, {3.0f, 1.5f, 0.0f});
    for (int i = 0; i < 240; ++i) w->step(kDt);
    const float y_lying = position_of(*w, lying).y, y_standing = position_of(*w, standing).y;
    vec3 v;
    w->get_velocity(lying, &v, nullptr);
    std::printf("ground %d: lying capsule at %.4f (expect %.2f), standing at %.4f (expect %.2f), |v| %.2e\n", ground,
                y_lying, r, y_standing, r + hh, length(v));
    EXPECT_NEAR(y_lying, r, 0.01f) << ground;
    EXPECT_NEAR(y_standing, r + hh, 0.01f) << ground;
    EXPECT_LT(length(v), 0.01f);
  }
}

TEST(ConvexBodies, HullsRestOnPlaneAndOnEachOther) {
  auto w = make_world();
  ASSERT_FALSE(add_plane(*w).is_null());
  const ConvexHull prism = prism_hull(6, 0.5f, 0.25f);
  const BodyId a = add_hull(*w, prism, {0.0f, 0.5f, 0.0f});
  const BodyId b = add_hull(*w, prism, {0.05f, 1.2f, 0.0f}, from_axis_angle({0.0f, 1.0f, 0.0f}, 0.3f));
  for (int i = 0; i < 300; ++i) w->step(kDt);
  const float la = lowest_y(*w, a, prism), lb = lowest_y(*w, b, prism);
  std::printf("hexagonal prisms: bottom of a %.4f (expect 0), of b %.4f (expect 0.5)\n", la, lb);
  EXPECT_NEAR(la, 0.0f, 0.01f);
  EXPECT_NEAR(lb, 0.5f, 0.015f);
}

// The criterion: a stack of convex hulls stays for 10 s. Both manifold models run;
// the clipped one-shot manifold (the default) must hold within 1 cm.
double hull_stack_drift(ConvexManifold model, int levels, double* tilt_out, bool boxes = false) {
  WorldDef def;
  def.enable_sleep = false;
  def.convex_manifold = model;
  auto w = make_world(def);
  add_ground(*w);
  const ConvexHull cube = box_hull({0.5f, 0.5f, 0.5f});
  std::vector<BodyId> ids;
  for (int i = 0; i < levels; ++i)
    ids.push_back(boxes ? test::add_box(*w, {0.0f, 0.5f + float(i), 0.0f}) : add_hull(*w, cube, {0.0f, 0.5f + float(i), 0.0f}));
  const std::vector<vec3> start = positions(*w, ids);
  for (int i = 0; i < 600; ++i) w->step(kDt);
  double tilt = 0.0;
  for (BodyId id : ids) {
    quat q;
    w->get_transform(id, nullptr, &q);
    const vec3 up = rotate(q, vec3{0.0f, 1.0f, 0.0f});
    tilt = std::max(tilt, double(std::abs(up.y)) < 1.0 ? std::acos(std::min(1.0, double(std::abs(up.y)))) : 0.0);
  }
  *tilt_out = tilt;
  return max_drift(*w, ids, start);
}

TEST(ConvexBodies, TenHullStackStandsForTenSecondsClippingVersusIncremental) {
  double tilt_clip = 0, tilt_inc = 0;
  const double clip = hull_stack_drift(ConvexManifold::clipping, 10, &tilt_clip);
  const double inc = hull_stack_drift(ConvexManifold::incremental, 10, &tilt_inc);
  std::printf("10 hull cubes, 10 s: clipping drift %.5f m tilt %.5f rad; incremental drift %.5f m tilt %.5f rad\n",
              clip, tilt_clip, inc, tilt_inc);
  EXPECT_LT(clip, 0.01);
  EXPECT_LT(tilt_clip, 0.01);
  // Twice as tall: the gap between the models widens (printed for the record).
  const double clip20 = hull_stack_drift(ConvexManifold::clipping, 20, &tilt_clip);
  const double inc20 = hull_stack_drift(ConvexManifold::incremental, 20, &tilt_inc);
  double tilt_box = 0;
  const double box20 = hull_stack_drift(ConvexManifold::clipping, 20, &tilt_box, true);
  std::printf("20 hull cubes, 10 s: clipping drift %.5f m tilt %.5f rad; incremental drift %.5f m tilt %.5f rad;"
              " box shapes (SAT) drift %.5f m\n", clip20, tilt_clip, inc20, tilt_inc, box20);
  EXPECT_LT(clip20, 1.2 * box20 + 0.002);  // as good as the box-box path
}

TEST(ConvexBodies, PrismStackStandsForTenSeconds) {
  WorldDef def;
  def.enable_sleep = false;
  auto w = make_world(def);
  add_ground(*w);
  const ConvexHull prism = prism_hull(7, 0.6f, 0.2f);  // odd sides: no face pairs parallel to an axis
  std::vector<BodyId> ids;
  for (int i = 0; i < 8; ++i)
    ids.push_back(add_hull(*w, prism, {0.0f, 0.2f + 0.4f * float(i), 0.0f}, from_axis_angle({0, 1, 0}, 0.2f * float(i))));
  const std::vector<vec3> start = positions(*w, ids);
  for (int i = 0; i < 600; ++i) w->step(kDt);
  const double drift = max_drift(*w, ids, start);
  std::printf("8 heptagonal prisms, 10 s: drift %.5f m\n", drift);
  EXPECT_LT(drift, 0.01);
}

TEST(ConvexBodies, CapsuleAndHullRestOnATriangleMesh) {
  // A 20 x 20 m floor of two triangles at y = 0.
  MeshData floor;
  for (const vec3& v : {vec3{-10, 0, -10}, vec3{10, 0, -10}, vec3{10, 0, 10}, vec3{-10, 0, 10}}) floor.add_vertex(v);
  floor.add_triangle(0, 2, 1);
  floor.add_triangle(0, 3, 2);
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(floor, mesh), Status::ok);
  auto w = make_world();
  BodyDef g;
  g.type = BodyType::static_body;
  g.shape.type = BodyShape::mesh;
  g.shape.mesh = &mesh;
  BodyId gid;
  ASSERT_EQ(w->create_body(g, &gid), Status::ok);
  const ConvexHull cube = box_hull({0.5f, 0.5f, 0.5f});
  const BodyId h = add_hull(*w, cube, {0.0f, 1.0f, 0.0f});
  const BodyId c = add_capsule(*w, 0.2f, 0.3f, {3.0f, 1.0f, 0.0f}, from_axis_angle({1.0f, 0.0f, 0.0f}, kPi / 2));
  for (int i = 0; i < 240; ++i) w->step(kDt);
  std::printf("on a mesh: hull centre %.4f (0.5), capsule %.4f (0.2)\n", position_of(*w, h).y, position_of(*w, c).y);
  EXPECT_NEAR(position_of(*w, h).y, 0.5f, 0.01f);
  EXPECT_NEAR(position_of(*w, c).y, 0.2f, 0.01f);
}

TEST(ConvexBodies, CapsuleRollsDownAnIncline) {
  // A capsule lying across a 20-degree incline rolls: it gains speed like a rolling body
  // (a = g sin(theta) / (1 + I / (m r^2))) instead of sliding or sticking.
  auto w = make_world();
  const float theta = 20.0f * kPi / 180.0f;
  const quat tilt = from_axis_angle({0.0f, 0.0f, 1.0f}, theta);
  BodyDef g;
  g.type = BodyType::static_body;
  g.shape.half_extents = {50.0f, 0.5f, 5.0f};
  g.orientation = tilt;
  g.position = rotate(tilt, vec3{0.0f, -0.5f, 0.0f});
  BodyId gid;
  ASSERT_EQ(w->create_body(g, &gid), Status::ok);
  const float r = 0.2f, hh = 0.4f;
  const BodyId c = add_capsule(*w, r, hh, rotate(tilt, vec3{0.0f, r, 0.0f}), tilt * from_axis_angle({1, 0, 0}, kPi / 2));
  for (int i = 0; i < 30; ++i) w->step(kDt);
  vec3 v0, v1;
  w->get_velocity(c, &v0, nullptr);
  for (int i = 0; i < 60; ++i) w->step(kDt);
  w->get_velocity(c, &v1, nullptr);
  const float a = (length(v1) - length(v0)) / (60 * kDt);
  const float m = kPi * r * r * 2 * hh + 4.0f / 3.0f * kPi * r * r * r;
  const float axial = kPi * r * r * 2 * hh * 0.5f * r * r + 4.0f / 3.0f * kPi * r * r * r * 0.4f * r * r;
  const float expected = 9.81f * std::sin(theta) / (1.0f + axial / (m * r * r));
  std::printf("capsule rolling: a = %.4f m/s^2, expected %.4f\n", a, expected);
  EXPECT_NEAR(a, expected, 0.03f * expected);
}

TEST(ConvexBodies, ClothDrapesOverAHullAndACapsuleWithoutEnteringThem) {
  auto w = make_world();
  const ConvexHull cube = box_hull({0.5f, 0.5f, 0.5f});
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::hull;
  d.shape.hull = &cube;
  d.position = {-1.0f, 0.5f, 0.0f};
  d.orientation = from_axis_angle({0.0f, 1.0f, 0.0f}, 0.4f);
  BodyId hid;
  ASSERT_EQ(w->create_body(d, &hid), Status::ok);
  d = BodyDef{};
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::capsule;
  d.shape.radius = 0.3f, d.shape.half_height = 0.6f;
  d.position = {1.0f, 0.3f, 0.0f};
  d.orientation = from_axis_angle({1.0f, 0.0f, 0.0f}, kPi / 2);
  BodyId cid;
  ASSERT_EQ(w->create_body(d, &cid), Status::ok);
  ClothDef cd;
  cd.nx = cd.nz = 24;
  cd.size_x = cd.size_z = 4.0f;
  cd.center = {0.0f, 1.5f, 0.0f};
  SoftBody cloth;
  ASSERT_EQ(SoftBody::make_cloth(cd, &cloth), Status::ok);
  SoftBodyId sid;
  ASSERT_EQ(w->add_soft_body(cloth, &sid), Status::ok);
  for (int i = 0; i < 120; ++i) ASSERT_EQ(w->step(kDt), Status::ok);
  const SoftBody* sb = w->soft_body(sid);
  vec3 hp, off;
  quat hq, r;
  w->get_transform(hid, &hp, &hq);
  w->get_shape_frame(hid, &off, &r);
  float worst_hull = 1e30f, worst_capsule = 1e30f;
  float lowest_over_hull = 1e30f;
  for (uint32_t i = 0; i < sb->particle_count(); ++i) {
    vec3 p;
    sb->get_position(i, &p);
    // Signed distance to the hull: the largest plane distance (caller's frame: planes of `cube`).
    const vec3 local = rotate(conjugate(hq * r), p - (hp + rotate(hq, off)));
    float dist = -1e30f;
    for (const Plane& pl : cube.planes) dist = std::max(dist, dot(pl.normal, local) - pl.distance);
    worst_hull = std::min(worst_hull, dist);
    if (std::abs(local.x) < 0.4f && std::abs(local.z) < 0.4f) lowest_over_hull = std::min(lowest_over_hull, p.y);
    // Distance to the capsule's segment (along z at x = 1, y = 0.3).
    const float z = std::max(-0.6f, std::min(0.6f, p.z));
    const vec3 q{1.0f, 0.3f, z};
    worst_capsule = std::min(worst_capsule, length(p - q) - 0.3f);
  }
  std::printf("cloth over a hull and a capsule: min distance %.4f m (hull) %.4f m (capsule), lowest over the hull %.3f\n",
              worst_hull, worst_capsule, lowest_over_hull);
  EXPECT_GT(worst_hull, -1e-3f);
  EXPECT_GT(worst_capsule, -1e-3f);
  EXPECT_GT(lowest_over_hull, 0.99f);  // resting on the top face, not fallen through
}

TEST(ConvexBodies, BadShapesAreRejectedAndChangeNothing) {
  auto w = make_world();
  add_ground(*w);
  const uint64_t before = w->hash();
  BodyId id;
  BodyDef d;
  d.shape.type = BodyShape::capsule;
  d.shape.radius = 0.0f;
  EXPECT_EQ(w->create_body(d, &id), Status::invalid_argument);
  d.shape.radius = 0.2f, d.shape.half_height = -1.0f;
  EXPECT_EQ(w->create_body(d, &id), Status::invalid_argument);
  d.shape.half_height = std::nanf("");
  EXPECT_EQ(w->create_body(d, &id), Status::invalid_argument);
  d.shape.type = BodyShape::hull;
  d.shape.hull = nullptr;
  EXPECT_EQ(w->create_body(d, &id), Status::null_argument);
  ConvexHull empty;
  d.shape.hull = &empty;
  EXPECT_EQ(w->create_body(d, &id), Status::invalid_argument);
  ConvexHull bad = box_hull({0.5f, 0.5f, 0.5f});
  bad.vertices[3].x = std::nanf("");
  d.shape.hull = &bad;
  EXPECT_EQ(w->create_body(d, &id), Status::non_finite);
  EXPECT_EQ(w->hash(), before);
  EXPECT_EQ(w->body_count(), 1u);
  vec3 off;
  EXPECT_EQ(w->get_shape_frame(BodyId{77, 1}, &off, nullptr), Status::stale_id);
}

TEST(ConvexBodies, DestroyedHullBodiesFreeTheirSlotsAndTheRestGoesOn) {
  auto w = make_world();
  add_ground(*w);
  const ConvexHull cube = box_hull({0.5f, 0.5f, 0.5f});
  std::vector<BodyId> ids;
  for (int i = 0; i < 6; ++i) ids.push_back(add_hull(*w, cube, {1.2f * float(i), 0.5f, 0.0f}));
  for (int i = 0; i < 30; ++i) w->step(kDt);
  ASSERT_EQ(w->destroy_body(ids[1]), Status::ok);
  ASSERT_EQ(w->destroy_body(ids[4]), Status::ok);
  const BodyId again = add_hull(*w, cube, {1.2f, 2.0f, 0.0f});
  for (int i = 0; i < 120; ++i) w->step(kDt);
  EXPECT_NEAR(position_of(*w, again).y, 0.5f, 0.01f);
  EXPECT_NEAR(position_of(*w, ids[5]).y, 0.5f, 0.01f);
}

}  // namespace
}  // namespace gyro
