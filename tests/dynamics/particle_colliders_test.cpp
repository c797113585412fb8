// Capsule and convex-hull colliders for particles and soft bodies
// (src/dynamics/particle_colliders.hpp): fast swept segments never pass through a thin
// capsule or a thin hull plate, push-out lands on the inflated surface, bounds contain the
// (inflated) shape, grazing and start-inside cases behave as documented, a box hull agrees
// with the AABB collider, checks and hashes, and a fast cloth stopped by both kinds.
#include "dynamics/particle_colliders.hpp"
#include "dynamics/soft_body_internal.hpp"
#include "workloads.hpp"

#include "gyro/soft_body.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace gyro {
namespace {

using detail::CapsuleCollider;
using detail::Collider;
using detail::ColliderKind;
using detail::HullCollider;
using detail::StateHasher;
using testing::SplitMix64;

ConvexHull box_hull(const vec3& half) {
  std::vector<vec3> pts;
  for (int c = 0; c < 8; ++c) pts.push_back({c & 1 ? half.x : -half.x, c & 2 ? half.y : -half.y, c & 4 ? half.z : -half.z});
  ConvexHull h;
  EXPECT_EQ(build_convex_hull(pts.data(), pts.size(), h), Status::ok);
  return h;
}

mat3 tilt(float ax, float az) {
  const mat3 rx = from_rows({1, 0, 0}, {0, std::cos(ax), std::sin(ax)}, {0, -std::sin(ax), std::cos(ax)});
  const mat3 rz = from_rows({std::cos(az), std::sin(az), 0}, {-std::sin(az), std::cos(az), 0}, {0, 0, 1});
  return rx * rz;
}

Collider capsule(const vec3& a, const vec3& b, float r) {
  Collider c;
  EXPECT_EQ(detail::to_collider(CapsuleCollider{a, b, r}, &c), Status::ok);
  return c;
}

Collider hull(const ConvexHull* h, const vec3& p, const mat3& rot, float margin = 0.0f) {
  Collider c;
  EXPECT_EQ(detail::to_collider(HullCollider{h, p, rot, margin}, &c), Status::ok);
  return c;
}

float segment_distance(const vec3& a, const vec3& b, const vec3& p) {
  const vec3 u = b - a;
  float w = dot(p - a, u) / dot(u, u);
  w = w < 0 ? 0 : (w > 1 ? 1 : w);
  return length(p - (a + u * w));
}

vec3 hull_local(const HullCollider& k, const vec3& p) { return (p - k.position) * transpose(k.rotation); }

// Largest signed distance of p outside the hull's margin-moved planes (< 0 inside).
float hull_outside(const HullCollider& k, const vec3& p) {
  const vec3 l = hull_local(k, p);
  float worst = -1e30f;
  for (const Plane& pl : k.hull->planes) worst = std::max(worst, dot(pl.normal, l) - pl.distance - k.margin);
  return worst;
}

TEST(ParticleColliders, FastSegmentsNeverPassThroughAThinCapsule) {
  // A 1 cm thick capsule far from the origin; segments 100 m long cross it in every direction.
  const vec3 a{99.0f, -20.0f, 5.0f}, b{101.0f, -20.0f, 5.5f};
  const float r = 0.005f;
  const Collider c = capsule(a, b, r);
  SplitMix64 rng(1);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    // A target on the capsule's core, offset within the radius; a direction mostly across.
    const float w = float(rng.u());
    const vec3 target = a + (b - a) * w + vec3{0.0f, float(rng.u() - 0.5), float(rng.u() - 0.5)} * (1.9f * r);
    const vec3 dir = normalized(vec3{float(rng.u() - 0.5) * 0.5f, float(rng.u() - 0.5) * 2.0f, float(rng.u() - 0.5) * 2.0f});
    const vec3 s = target - dir * 50.0f, d = dir * 100.0f;
    float t;
    vec3 p, n;
    if (segment_distance(a, b, target) >= r) continue;  // the target must be inside
    ASSERT_TRUE(detail::first_hit(c, s, d, &t, &p, &n)) << i;
    ++hits;
    EXPECT_LT(dot(n, d), 0.0f);
    EXPECT_NEAR(length(n), 1.0f, 1e-5f);
    EXPECT_NEAR(segment_distance(a, b, p), r, 2e-4f) << i;  // on the surface (float, 100 m step)
    // Where a particle stops (one skin out along the normal): outside, before the capsule.
    const vec3 stop = p + n * detail::skin_at(p);
    EXPECT_GT(segment_distance(a, b, stop), r) << i;
    EXPECT_LE(t, 0.5f);  // not after the point inside the capsule the segment aims at
  }
  EXPECT_GT(hits, 1000);
}

TEST(ParticleColliders, FastSegmentsNeverPassThroughAThinHullPlate) {
  // A 1 cm plate (2 x 0.01 x 2) tilted and placed far out; 100 m segments through it.
  const ConvexHull plate = box_hull({1.0f, 0.005f, 1.0f});
  const mat3 rot = tilt(0.3f, -0.7f);
  const Collider c = hull(&plate, {-40.0f, 12.0f, 7.0f}, rot);
  const vec3 up = row(rot, 1);
  SplitMix64 rng(2);
  for (int i = 0; i < 2000; ++i) {
    const vec3 local{float(rng.u() * 1.9 - 0.95), float(rng.u() - 0.5) * 0.009f, float(rng.u() * 1.9 - 0.95)};
    const vec3 target = local * rot + c.hull.position;
    vec3 dir = normalized(vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)});
    if (std::abs(dot(dir, up)) < 0.2f) continue;  // nearly along the plate: may come in through its rim
    const float side = dot(dir, up) < 0 ? 1.0f : -1.0f;  // the face it comes through
    const vec3 s = target - dir * 50.0f, d = dir * 100.0f;
    float t;
    vec3 p, n;
    ASSERT_TRUE(detail::first_hit(c, s, d, &t, &p, &n)) << i;
    EXPECT_LT(dot(n, d), 0.0f);
    EXPECT_NEAR(dot(n, up), side, 1e-5f) << i;
    EXPECT_NEAR(hull_outside(c.hull, p), 0.0f, 1e-4f) << i;
    const vec3 stop = p + n * detail::skin_at(p);
    EXPECT_GT(side * dot(stop - c.hull.position, up), 0.005f) << i;  // still on the side it came from
  }
}

TEST(ParticleColliders, BoxHullAgreesWithTheAabbCollider) {
  const vec3 half{0.7f, 0.2f, 1.3f}, center{3.0f, -1.0f, 2.0f};
  const ConvexHull h = box_hull(half);
  const Collider ch = hull(&h, center, mat3::identity());
  Collider cb;
  ASSERT_EQ(detail::to_collider(AABB{center, half}, &cb), Status::ok);
  SplitMix64 rng(3);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const vec3 s = center + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * 6.0f;
    const vec3 d = vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * 8.0f;
    float t1, t2;
    vec3 p1, p2, n1, n2;
    const bool a = detail::first_hit(ch, s, d, &t1, &p1, &n1), b = detail::first_hit(cb, s, d, &t2, &p2, &n2);
    ASSERT_EQ(a, b) << i;
    if (a) {
      ++hits;
      EXPECT_NEAR(t1, t2, 1e-5f);
      EXPECT_NEAR(dot(n1, n2), 1.0f, 1e-6f);
    }
    const vec3 q1 = detail::push_out(ch, s, 0.01f), q2 = detail::push_out(cb, s, 0.01f);
    EXPECT_NEAR(length(q1 - q2), 0.0f, 1e-5f) << i;
  }
  EXPECT_GT(hits, 100);
}

TEST(ParticleColliders, PushOutLandsOnTheInflatedSurface) {
  // Capsule: radius 0.3 inflated by 0.05; push-out with extra 0.01 lands one skin plus the
  // extra outside radius 0.35.
  const vec3 a{1.0f, 2.0f, 3.0f}, b{2.0f, 2.5f, 2.0f};
  const Collider c = detail::inflated(capsule(a, b, 0.3f), 0.05f);
  EXPECT_EQ(c.capsule.radius, 0.3f + 0.05f);
  SplitMix64 rng(4);
  for (int i = 0; i < 500; ++i) {
    const vec3 p = a + (b - a) * float(rng.u() * 1.4 - 0.2) + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * 0.4f;
    vec3 n;
    const vec3 q = detail::push_out(c, p, 0.01f, &n);
    if (segment_distance(a, b, p) >= 0.35f) {
      EXPECT_EQ(q, p);  // outside: untouched
      continue;
    }
    const float want = 0.35f + 0.01f;
    EXPECT_NEAR(segment_distance(a, b, q), want, detail::skin_at(q) + 1e-5f) << i;
    EXPECT_GE(segment_distance(a, b, q), want) << i;
    EXPECT_NEAR(length(n), 1.0f, 1e-5f);
  }
  // A point on the core goes across the axis, the same way every time.
  vec3 n1, n2;
  const vec3 mid = (a + b) * 0.5f;
  detail::push_out(c, mid, 0.0f, &n1), detail::push_out(c, mid, 0.0f, &n2);
  EXPECT_EQ(n1, n2);
  EXPECT_NEAR(dot(n1, b - a), 0.0f, 1e-6f);

  // Hull: margin 0.05; out through the least-penetrated plane, one skin plus extra beyond it.
  const ConvexHull h = box_hull({0.5f, 1.0f, 1.5f});
  const Collider ch = detail::inflated(hull(&h, {5.0f, 0.0f, -2.0f}, tilt(0.9f, 0.4f)), 0.05f);
  EXPECT_EQ(ch.hull.margin, 0.05f);
  for (int i = 0; i < 500; ++i) {
    const vec3 local{float(rng.u() - 0.5) * 1.2f, float(rng.u() - 0.5) * 2.2f, float(rng.u() - 0.5) * 3.2f};
    const vec3 p = local * ch.hull.rotation + ch.hull.position;
    vec3 n;
    const vec3 q = detail::push_out(ch, p, 0.02f, &n);
    if (!(hull_outside(ch.hull, p) < 0.0f)) {
      EXPECT_EQ(q, p);
      continue;
    }
    EXPECT_NEAR(hull_outside(ch.hull, q), 0.02f + detail::skin_at(q), 1e-4f) << i;
    EXPECT_EQ(detail::push_out(ch, q), q);  // out now
    EXPECT_NEAR(length(n), 1.0f, 1e-5f);
  }
}

TEST(ParticleColliders, BoundsContainTheShape) {
  vec3 lo, hi;
  auto inside = [&](const vec3& p, float tol) {
    for (int k = 0; k < 3; ++k)
      if (p[k] < lo[k] - tol || p[k] > hi[k] + tol) return false;
    return true;
  };
  const vec3 a{-1.0f, 2.0f, 0.5f}, b{3.0f, -1.0f, 1.0f};
  const Collider c = capsule(a, b, 0.25f);
  ASSERT_TRUE(detail::collider_bounds(c, &lo, &hi));
  EXPECT_EQ(lo, (vec3{-1.25f, -1.25f, 0.25f}));
  EXPECT_EQ(hi, (vec3{3.25f, 2.25f, 1.25f}));

  // A sharp tetrahedron with a margin: the mitred tip reaches well past vertex box + margin,
  // and the bounds still hold every corner of the inflated hull (three planes meet there).
  const std::vector<vec3> pts{{0, 0, 0}, {0.2f, 0, 0}, {0, 0.2f, 0}, {0, 0, 3.0f}};
  ConvexHull tet;
  ASSERT_EQ(build_convex_hull(pts.data(), pts.size(), tet), Status::ok);
  for (float margin : {0.0f, 0.05f, 0.5f}) {
    const Collider ch = hull(&tet, {2.0f, 1.0f, -3.0f}, tilt(0.5f, 1.2f), margin);
    ASSERT_TRUE(detail::collider_bounds(ch, &lo, &hi));
    const std::size_t f = tet.face_count();
    for (std::size_t i = 0; i < f; ++i)
      for (std::size_t j = i + 1; j < f; ++j)
        for (std::size_t k = j + 1; k < f; ++k) {
          // The corner of planes i, j, k moved out by the margin (Cramer's rule in double).
          const Plane* p[3] = {&tet.planes[i], &tet.planes[j], &tet.planes[k]};
          double m[3][3], rhs[3];
          for (int r = 0; r < 3; ++r) {
            m[r][0] = p[r]->normal.x, m[r][1] = p[r]->normal.y, m[r][2] = p[r]->normal.z;
            rhs[r] = double(p[r]->distance) + margin;
          }
          auto det = [](double q[3][3]) {
            return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                   q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
          };
          const double dm = det(m);
          double x[3];
          for (int col = 0; col < 3; ++col) {
            double q[3][3];
            std::memcpy(q, m, sizeof q);
            for (int r = 0; r < 3; ++r) q[r][col] = rhs[r];
            x[col] = det(q) / dm;
          }
          const vec3 corner = vec3{float(x[0]), float(x[1]), float(x[2])} * ch.hull.rotation + ch.hull.position;
          EXPECT_TRUE(inside(corner, 1e-5f)) << "margin " << margin << " corner " << i << j << k;
        }
    if (margin == 0.5f) {
      // The tip moved far more than the margin: a plain vertex box + margin would miss it.
      const vec3 tip = pts[3] * ch.hull.rotation + ch.hull.position;
      EXPECT_GT(hi.z - tip.z, margin);
    }
  }
}

TEST(ParticleColliders, GrazingAndStartInside) {
  // Capsule along x, radius 0.5. A segment passing just outside misses; just inside hits.
  const Collider c = capsule({-1, 0, 0}, {1, 0, 0}, 0.5f);
  float t;
  vec3 p, n;
  EXPECT_FALSE(detail::first_hit(c, {-3.0f, 0.501f, 0.0f}, {6.0f, 0.0f, 0.0f}, &t, &p, &n));
  EXPECT_FALSE(detail::first_hit(c, {0.0f, 0.501f, -3.0f}, {0.0f, 0.0f, 6.0f}, &t, &p, &n));
  ASSERT_TRUE(detail::first_hit(c, {0.0f, 0.499f, -3.0f}, {0.0f, 0.0f, 6.0f}, &t, &p, &n));
  EXPECT_NEAR(n.y, 0.998f, 1e-3f);
  // Along the axis into an end cap: the sphere at that end.
  ASSERT_TRUE(detail::first_hit(c, {-5.0f, 0.0f, 0.0f}, {10.0f, 0.0f, 0.0f}, &t, &p, &n));
  EXPECT_NEAR(t, 0.35f, 1e-6f);
  EXPECT_EQ(n, (vec3{-1.0f, 0.0f, 0.0f}));
  // Starting strictly inside: no hit (push_out's job); starting on the surface moving in: t = 0.
  EXPECT_FALSE(detail::first_hit(c, {0.0f, 0.2f, 0.0f}, {0.0f, 5.0f, 0.0f}, &t, &p, &n));
  EXPECT_FALSE(detail::first_hit(c, {0.0f, 0.2f, 0.0f}, {0.0f, -5.0f, 0.0f}, &t, &p, &n));
  ASSERT_TRUE(detail::first_hit(c, {0.0f, 0.5f, 0.0f}, {0.0f, -5.0f, 0.0f}, &t, &p, &n));
  EXPECT_EQ(t, 0.0f);
  // Leaving from the surface: not an entry.
  EXPECT_FALSE(detail::first_hit(c, {0.0f, 0.5f, 0.0f}, {0.0f, 5.0f, 0.0f}, &t, &p, &n));

  // Hull: the unit cube. Parallel to the top face just above it: miss. Lying in the top
  // face's plane: it touches the side face where it meets the cube (as the AABB raycast).
  const ConvexHull h = box_hull({1.0f, 1.0f, 1.0f});
  const Collider ch = hull(&h, {0, 0, 0}, mat3::identity());
  EXPECT_FALSE(detail::first_hit(ch, {-3.0f, 1.0001f, 0.0f}, {6.0f, 0.0f, 0.0f}, &t, &p, &n));
  ASSERT_TRUE(detail::first_hit(ch, {-3.0f, 1.0f, 0.0f}, {6.0f, 0.0f, 0.0f}, &t, &p, &n));
  EXPECT_NEAR(t, 2.0f / 6.0f, 1e-6f);
  EXPECT_EQ(n, (vec3{-1.0f, 0.0f, 0.0f}));
  // Inside: no hit, push-out through the nearest face; on the face moving in: t = 0.
  EXPECT_FALSE(detail::first_hit(ch, {0.0f, 0.9f, 0.0f}, {0.0f, -5.0f, 0.0f}, &t, &p, &n));
  const vec3 q = detail::push_out(ch, {0.2f, 0.9f, -0.3f}, 0.0f, &n);
  EXPECT_EQ(n, (vec3{0.0f, 1.0f, 0.0f}));
  EXPECT_NEAR(q.y, 1.0f + detail::skin_at(q), 1e-6f);
  ASSERT_TRUE(detail::first_hit(ch, {0.0f, 1.0f, 0.0f}, {0.0f, -5.0f, 0.0f}, &t, &p, &n));
  EXPECT_EQ(t, 0.0f);
  EXPECT_FALSE(detail::first_hit(ch, {0.0f, 1.0f, 0.0f}, {0.0f, 5.0f, 0.0f}, &t, &p, &n));
  // Past the end of the segment, or the hull behind it: no hit.
  EXPECT_FALSE(detail::first_hit(ch, {0.0f, 5.0f, 0.0f}, {0.0f, -3.9f, 0.0f}, &t, &p, &n));
  EXPECT_FALSE(detail::first_hit(ch, {0.0f, 5.0f, 0.0f}, {0.0f, 3.0f, 0.0f}, &t, &p, &n));
  // The margin moves the face out: the same segment stops 0.25 earlier.
  const Collider cm = detail::inflated(ch, 0.25f);
  ASSERT_TRUE(detail::first_hit(cm, {0.0f, 5.0f, 0.0f}, {0.0f, -5.0f, 0.0f}, &t, &p, &n));
  EXPECT_NEAR(p.y, 1.25f, 1e-6f);
}

TEST(ParticleColliders, ChecksAndHashes) {
  Collider keep = capsule({0, 0, 0}, {1, 0, 0}, 1.0f), out = keep;
  const ConvexHull h = box_hull({1, 1, 1});
  auto untouched = [&] {
    StateHasher a, b;
    detail::hash_collider(out, a), detail::hash_collider(keep, b);
    return out.kind == keep.kind && a.digest() == b.digest();
  };
  EXPECT_EQ(detail::to_collider(CapsuleCollider{{0, 0, 0}, {1, 0, 0}, -1.0f}, &out), Status::invalid_argument);
  EXPECT_TRUE(untouched());
  EXPECT_EQ(detail::to_collider(CapsuleCollider{{std::nanf(""), 0, 0}, {1, 0, 0}, 1.0f}, &out), Status::non_finite);
  EXPECT_TRUE(untouched());
  EXPECT_EQ(detail::to_collider(HullCollider{nullptr, {}, {}, 0.0f}, &out), Status::null_argument);
  EXPECT_TRUE(untouched());
  const ConvexHull empty;
  EXPECT_EQ(detail::to_collider(HullCollider{&empty, {}, {}, 0.0f}, &out), Status::invalid_argument);
  EXPECT_TRUE(untouched());
  EXPECT_EQ(detail::to_collider(HullCollider{&h, {}, mat3{} * 2.0f, 0.0f}, &out), Status::invalid_argument);
  EXPECT_NE(std::string(last_error()).find("orthonormal"), std::string::npos);
  EXPECT_TRUE(untouched());
  EXPECT_EQ(detail::to_collider(HullCollider{&h, {}, {}, -0.1f}, &out), Status::invalid_argument);
  EXPECT_EQ(detail::to_collider(HullCollider{&h, {0, std::numeric_limits<float>::infinity(), 0}, {}, 0.0f}, &out), Status::non_finite);
  EXPECT_TRUE(untouched());

  // Hashes: a function of the shape, not of where the hull lives in memory; any change shows.
  const ConvexHull copy = h;
  auto hash = [](const Collider& c) {
    StateHasher s;
    detail::hash_collider(c, s);
    return s.digest();
  };
  const Collider h1 = hull(&h, {1, 2, 3}, tilt(0.1f, 0.2f)), h2 = hull(&copy, {1, 2, 3}, tilt(0.1f, 0.2f));
  EXPECT_EQ(hash(h1), hash(h2));
  EXPECT_NE(hash(h1), hash(detail::inflated(h1, 0.01f)));
  EXPECT_NE(hash(h1), hash(hull(&h, {1, 2, 3.5f}, tilt(0.1f, 0.2f))));
  const ConvexHull bigger = box_hull({1, 1, 2});
  EXPECT_NE(hash(h1), hash(hull(&bigger, {1, 2, 3}, tilt(0.1f, 0.2f))));
  EXPECT_NE(hash(keep), hash(capsule({0, 0, 0}, {1, 0, 0}, 1.5f)));
  EXPECT_NE(hash(keep), hash(capsule({0, 0, 0}, {1, 0.5f, 0}, 1.0f)));
  EXPECT_NE(hash(keep), hash(h1));
}

// A 13 x 13 particle cloth at 20 m/s onto a thin hull plate (1 cm, tilted) and onto a thin
// capsule (1 cm radius) under its middle row of particles, through the soft body's collision
// path. No particle is ever inside the true shape, and none crosses it: the side of the
// plate (local y) or of the capsule (y) never flips between two step ends at which the
// particle is over the shape (within the plate's extent; within the capsule's radius of its
// vertical plane). The cloth must touch the shape at some step. (At 1 sub-step a cloth
// folding over a rod this thin whips up and flies off after landing, with an OBB rod as with
// the capsule; the checks hold over the whole run regardless.)
TEST(ParticleColliders, FastClothStopsOnThinPlateAndCapsule) {
  const ConvexHull plate = box_hull({1.1f, 0.005f, 1.1f});
  const mat3 rot = tilt(0.0f, 0.25f);
  for (int kind = 0; kind < 2; ++kind) {
    for (uint32_t substeps : {1u, 8u}) {
      ClothDef def;
      def.nx = def.nz = 13;  // a row of particles at z = 0, over the capsule
      def.size_x = def.size_z = 1.6f;
      def.center = {0.0f, 0.6f, 0.0f};
      def.particle_mass = 0.05f;
      SoftBody b;
      SoftSettings s;
      s.substeps = substeps;
      ASSERT_EQ(b.set_settings(s), Status::ok);
      ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
      for (uint32_t i = 0; i < b.particle_count(); ++i) ASSERT_EQ(b.set_velocity(i, {0.0f, -20.0f, 0.0f}), Status::ok);
      const float r = 0.01f;
      const Collider c = kind == 0 ? hull(&plate, {0, 0, 0}, rot) : capsule({-1.5f, 0.0f, 0.0f}, {1.5f, 0.0f, 0.0f}, r);
      // Which side of the shape p is on (*side), and whether it is over the shape.
      auto where = [&](const vec3& p, float* side) {
        if (kind == 0) {
          const vec3 l = hull_local(c.hull, p);
          *side = l.y;
          return std::abs(l.x) < 1.1f && std::abs(l.z) < 1.1f;
        }
        *side = p.y;
        return std::abs(p.x) < 1.5f && std::abs(p.z) < r;
      };
      auto gap = [&](const vec3& p) {
        return kind == 0 ? hull_outside(c.hull, p) : segment_distance(c.capsule.a, c.capsule.b, p) - r;
      };
      std::vector<vec3> last(b.particle_count());
      for (uint32_t i = 0; i < b.particle_count(); ++i) ASSERT_EQ(b.get_position(i, &last[i]), Status::ok);
      int inside = 0, crossed = 0;
      float closest = 1e9f;
      for (int n = 0; n < 30; ++n) {
        ASSERT_EQ(detail::SoftAccess::step_with(b, 1.0f / 60.0f, {&c, 1}, {}), Status::ok);
        const SoftView v = b.view();
        for (std::size_t i = 0; i < v.count; ++i) {
          const vec3 p{v.px[i], v.py[i], v.pz[i]};
          const float g = gap(p);
          if (g < 0.0f) ++inside;
          closest = std::min(closest, g);
          float s0, s1;
          const bool over0 = where(last[i], &s0), over1 = where(p, &s1);
          if (over0 && over1 && (s0 > 0.0f) != (s1 > 0.0f)) ++crossed;
          last[i] = p;
        }
      }
      const std::string what = std::string(kind ? "capsule" : "hull plate") + ", substeps " + std::to_string(substeps);
      EXPECT_EQ(inside, 0) << what;
      EXPECT_EQ(crossed, 0) << what;
      EXPECT_LT(closest, 0.05f) << what;  // the cloth did land on it
    }
  }
}

}  // namespace
}  // namespace gyro
