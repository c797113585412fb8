// Workload C1 (BENCHMARKS.md): a hanging 10 x 10 m cloth of N x N particles, the two corners
// of the z = -5 edge pinned, mass 1 per free particle, dt 1/60, 600 steps. Described once so
// gyro and Bullet build the same cloth, and both engines hand back their final particle
// positions in one grid order (index iz * N + ix, ix along x, iz along z) so every figure
// (sag, strain) is computed by the same code.
#pragma once

#include <cstddef>
#include <vector>

namespace gyro::bench {

struct ClothPositions {
  int n = 0;                   // particles per side
  std::vector<float> x, y, z;  // n * n, index iz * n + ix
  void resize(int side) {
    n = side;
    x.assign(std::size_t(side) * side, 0.0f), y = x, z = x;
  }
};

/// One Bullet run of C1 at N x N: build (build_ms), 600 x stepSimulation(1/60, 1, 1/60)
/// (step_ms: the stepping alone), and the final node positions.
struct BulletClothRun {
  double build_ms = 0, step_ms = 0;
  std::size_t links = 0;  // btSoftBody::m_links.size() (structural + gendiags (+ bending))
  ClothPositions state;
};

bool bullet_cloth_available();
/// btSoftBodyHelpers::CreatePatch((-5,0,-5), (5,0,-5), (-5,0,5), (5,0,5), n, n, 1|2, true)
/// in a btSoftRigidDynamicsWorld with Bullet's default soft-body settings; bending2 adds
/// generateBendingConstraints(2) with the default material. False when Bullet is not built in.
bool bullet_run_cloth(int n, bool bending2, int steps, BulletClothRun& out);

}  // namespace gyro::bench
