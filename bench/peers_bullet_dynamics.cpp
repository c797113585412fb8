// Bullet 3 (Debian's single-precision build) as the rigid-body peer of P1, P2, P3: the
// settings BENCHMARKS.md gives, built fresh per run so every rep does the same work.
//
// Bullet combines the two bodies' friction as a product (0.6 * 0.6 = 0.36 per contact)
// where gyro uses sqrt(fa * fb) = 0.6: the scenes set the same per-body values, and the
// runner's comment line says so. Boxes keep btBoxShape's default margin (0.04, kept inside
// the half extents), as a user of Bullet would.
#include "pyramid_workloads.hpp"

#include <chrono>
#include <memory>

#if defined(GYRO_BENCH_HAS_BULLET)
#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#endif

namespace gyro::bench {

void BodyStates::resize(std::size_t n) {
  for (auto* v : {&px, &py, &pz, &qx, &qy, &qz, &qw, &vx, &vy, &vz, &wx, &wy, &wz}) v->assign(n, 0.0f);
}

#if defined(GYRO_BENCH_HAS_BULLET)
namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The world and everything it points at, torn down in the order Bullet needs (bodies out of
// the world before they die; the world before its solver, broadphase and dispatcher).
struct BulletWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::unique_ptr<btBoxShape> ground_shape;
  std::unique_ptr<btConvexShape> box_shape;
  std::vector<std::unique_ptr<btRigidBody>> boxes;
  std::unique_ptr<btRigidBody> ground;

  ~BulletWorld() {
    for (auto& b : boxes) world.removeRigidBody(b.get());
    if (ground) world.removeRigidBody(ground.get());
  }

  // No motion state: the bodies' own world transforms are what we read back, never an
  // interpolated copy.
  std::unique_ptr<btRigidBody> make_body(btScalar mass, btConvexShape* shape, const btVector3& at, const PyramidScene& s) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), at);
    info.m_friction = s.friction;
    info.m_restitution = s.restitution;
    auto body = std::make_unique<btRigidBody>(info);
    body->setActivationState(DISABLE_DEACTIVATION);  // sleeping disabled: every step does the full work
    world.addRigidBody(body.get());
    return body;
  }

  explicit BulletWorld(const PyramidScene& s) {
    world.setGravity(btVector3(0, s.gravity, 0));
    world.getSolverInfo().m_numIterations = 10;
    ground_shape = std::make_unique<btBoxShape>(btVector3(s.ground_half[0], s.ground_half[1], s.ground_half[2]));
    ground = make_body(0, ground_shape.get(), btVector3(s.ground_centre[0], s.ground_centre[1], s.ground_centre[2]), s);
    if (s.hull_boxes) {
      auto hull = std::make_unique<btConvexHullShape>();
      const btScalar h = s.half - hull->getMargin();  // the margin rounds the corners outside
      for (int k = 0; k < 8; ++k) hull->addPoint(btVector3((k & 1) ? h : -h, (k & 2) ? h : -h, (k & 4) ? h : -h), false);
      hull->recalcLocalAabb();
      box_shape = std::move(hull);
    } else {
      box_shape = std::make_unique<btBoxShape>(btVector3(s.half, s.half, s.half));
    }
    boxes.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
      boxes.push_back(make_body(s.mass, box_shape.get(), btVector3(s.x[i], s.y[i], s.z[i]), s));
  }
};

}  // namespace

bool bullet_dynamics_available() { return true; }
int bullet_version() { return btGetVersion(); }

bool bullet_run_pyramid(const PyramidScene& s, PyramidRun& out) {
  const auto t0 = Clock::now();
  auto w = std::make_unique<BulletWorld>(s);
  const auto t1 = Clock::now();
  for (int i = 0; i < s.steps; ++i) w->world.stepSimulation(s.dt, 1, s.dt);
  const auto t2 = Clock::now();
  out.build_ms = ms_between(t0, t1);
  out.step_ms = ms_between(t1, t2);
  BodyStates& st = out.state;
  st.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const btRigidBody& b = *w->boxes[i];
    const btTransform& t = b.getWorldTransform();
    const btQuaternion q = t.getRotation();
    const btVector3 &p = t.getOrigin(), &v = b.getLinearVelocity(), &a = b.getAngularVelocity();
    st.px[i] = p.x(), st.py[i] = p.y(), st.pz[i] = p.z();
    st.qx[i] = q.x(), st.qy[i] = q.y(), st.qz[i] = q.z(), st.qw[i] = q.w();
    st.vx[i] = v.x(), st.vy[i] = v.y(), st.vz[i] = v.z();
    st.wx[i] = a.x(), st.wy[i] = a.y(), st.wz[i] = a.z();
  }
  return true;
}

#else
bool bullet_dynamics_available() { return false; }
int bullet_version() { return 0; }
bool bullet_run_pyramid(const PyramidScene&, PyramidRun&) { return false; }
#endif

}  // namespace gyro::bench
