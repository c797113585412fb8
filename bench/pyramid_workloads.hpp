// The rigid-body workloads P1, P2, P3 (BENCHMARKS.md): box pyramids on a static ground box,
// described once so gyro and Bullet build exactly the same scene, and the final state both
// engines report so every figure (drift, penetration, energy) is computed the same way.
#pragma once

#include <cstddef>
#include <vector>

namespace gyro::bench {

struct PyramidScene {
  const char* name = "";
  std::vector<float> x, y, z;  // box centres at the start (binary32, BENCHMARKS.md's rule)
  float half = 0.5f;           // box half extent
  float mass = 1.0f;
  float friction = 0.6f;
  float restitution = 0.0f;
  float ground_half[3] = {50.0f, 0.5f, 50.0f};
  float ground_centre[3] = {0.0f, -0.5f, 0.0f};
  float gravity = -9.81f;
  float dt = 1.0f / 60.0f;
  int steps = 600;
  /// Every box a convex hull of its 8 corners (gyro: BodyShape::hull with clipped or
  /// incremental manifolds; Bullet: btConvexHullShape of the corners pulled in by its default
  /// 0.04 margin, so its rounded surface is the box, as btBoxShape keeps its margin inside).
  bool hull_boxes = false;
  std::size_t size() const { return x.size(); }
};

/// Per box, in scene order: position, orientation (x, y, z, w), linear and angular velocity
/// (world frame) after the last step.
struct BodyStates {
  std::vector<float> px, py, pz, qx, qy, qz, qw, vx, vy, vz, wx, wy, wz;
  void resize(std::size_t n);
};

/// One run of a scene in one engine: the scene built (build_ms) and stepped (step_ms, the
/// stepping alone), and the state after the last step.
struct PyramidRun {
  double build_ms = 0, step_ms = 0;
  BodyStates state;
};

bool bullet_dynamics_available();
/// btDiscreteDynamicsWorld + btDbvtBroadphase + btSequentialImpulseConstraintSolver with
/// 10 iterations, deactivation disabled, one stepSimulation(dt, 1, dt) per step. Returns
/// false (and does nothing) when Bullet is not built in.
bool bullet_run_pyramid(const PyramidScene& scene, PyramidRun& out);
/// "3.24" (the linked library's btGetVersion()).
int bullet_version();

}  // namespace gyro::bench
