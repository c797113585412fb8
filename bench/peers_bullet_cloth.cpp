// Bullet 3 (Debian's single-precision build) as the cloth peer of C1: btSoftBody exactly as
// BENCHMARKS.md gives it (CreatePatch with gendiags, corners 1|2 fixed, Bullet's defaults:
// piterations 1, viterations 0, diterations 0, kLST 1, kDP 0, no aerodynamics, nothing to
// collide with), in a btSoftRigidDynamicsWorld stepped by stepSimulation(1/60, 1, 1/60).
// Built fresh per run so every rep does the same work. The final node positions are handed
// back in grid order (CreatePatch's node (ix, iy) is index iy * N + ix, already ours).
#include "cloth_peers.hpp"

#include <chrono>
#include <memory>

#if defined(GYRO_BENCH_HAS_BULLET)
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>
#endif

namespace gyro::bench {

#if defined(GYRO_BENCH_HAS_BULLET)
namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The world and the cloth, torn down in the order Bullet needs (the body out of the world
// before it dies; the world before its solver, broadphase and dispatcher).
struct BulletClothWorld {
  btSoftBodyRigidBodyCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btSoftBody* cloth = nullptr;

  BulletClothWorld(int n, bool bending2) {
    const btVector3 gravity(0, btScalar(-9.81), 0);
    world.setGravity(gravity);
    btSoftBodyWorldInfo& info = world.getWorldInfo();
    info.m_gravity = gravity;
    info.m_sparsesdf.Initialize();
    cloth = btSoftBodyHelpers::CreatePatch(info, btVector3(-5, 0, -5), btVector3(5, 0, -5), btVector3(-5, 0, 5),
                                           btVector3(5, 0, 5), n, n, 1 | 2, true);
    if (bending2) cloth->generateBendingConstraints(2);
    world.addSoftBody(cloth);
  }
  ~BulletClothWorld() {
    if (cloth) {
      world.removeSoftBody(cloth);
      delete cloth;
    }
  }
};

}  // namespace

bool bullet_cloth_available() { return true; }

bool bullet_run_cloth(int n, bool bending2, int steps, BulletClothRun& out) {
  const float dt = 1.0f / 60.0f;
  const auto t0 = Clock::now();
  auto w = std::make_unique<BulletClothWorld>(n, bending2);
  const auto t1 = Clock::now();
  for (int i = 0; i < steps; ++i) w->world.stepSimulation(dt, 1, dt);
  const auto t2 = Clock::now();
  out.build_ms = ms_between(t0, t1);
  out.step_ms = ms_between(t1, t2);
  out.links = std::size_t(w->cloth->m_links.size());
  out.state.resize(n);
  const btSoftBody::tNodeArray& nodes = w->cloth->m_nodes;
  if (nodes.size() != n * n) return false;
  for (int i = 0; i < n * n; ++i) {
    out.state.x[i] = nodes[i].m_x.x(), out.state.y[i] = nodes[i].m_x.y(), out.state.z[i] = nodes[i].m_x.z();
  }
  return true;
}

#else
bool bullet_cloth_available() { return false; }
bool bullet_run_cloth(int, bool, int, BulletClothRun&) { return false; }
#endif

}  // namespace gyro::bench
