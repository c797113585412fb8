// World::Impl: the state a world owns, and the stages of a step (step.cpp).
#pragma once

#include "core/columns.hpp"
#include "dynamics/body_store.hpp"
#include "dynamics/body_integrate.hpp"
#include "dynamics/broadphase.hpp"
#include "dynamics/contact_solver.hpp"
#include "dynamics/contacts.hpp"
#include "core/id_pool.hpp"
#include "dynamics/particle_colliders.hpp"
#include "dynamics/soft_body_internal.hpp"
#include "dynamics/islands.hpp"
#include "gyro/world.hpp"

#include <memory>
#include <vector>

namespace gyro {

struct World::Impl {
  WorldDef def;
  detail::BodyStore bodies;
  detail::ContactSet contacts;
  detail::Broadphase broadphase;
  detail::Islands islands;
  detail::ContactSolver solver;
  std::unique_ptr<ParticleSystem> particles;  // created on first use: a world without particles pays nothing
  detail::IdPool soft_pool;                    // soft bodies: ids over dense slots
  std::vector<std::unique_ptr<SoftBody>> soft_bodies;  // soft_bodies[slot]
  std::vector<std::unique_ptr<detail::BodyHull>> hulls;  // hull bodies' shapes, by body id index
  std::vector<std::shared_ptr<const TriangleMesh>> owned_meshes;  // meshes a restored snapshot brought
  StepTimings timings;
  StepStats stats;
  uint64_t steps = 0;

  // Step scratch, kept between steps so a warmed-up step does not allocate.
  std::vector<uint8_t> active, broad_flags;
  std::vector<float> bmin_x, bmin_y, bmin_z, bmax_x, bmax_y, bmax_z;
  std::vector<uint32_t> broad_slot, broad_key, broad_cat, broad_mask;
  std::vector<detail::BroadPair> broad_pairs;
  std::vector<detail::CandidatePair> candidates;
  std::vector<uint32_t> planes;
  std::vector<detail::SolverBody> solver_bodies;
  std::vector<float> inv_inertia, inv_mass;
  std::vector<uint8_t> writable;
  std::vector<uint32_t> index_of_slot, slot_of_body;
  std::vector<uint32_t> solver_index;   // 0, 1, 2, ... (the integration kernel's body lanes)
  std::vector<float> lin_acc, ang_acc;  // x, y, z columns of the solver bodies: constant over the step
  std::vector<uint8_t> island_awake;
  std::vector<float> island_rest;
  std::vector<detail::Collider> soft_shapes;        // the bodies near a soft body, as colliders
  std::vector<detail::MeshCollider> soft_meshes;

  void step(float dt);
  void find_pairs(float dt);
  void wake_islands();
  void build_solver_bodies();
  detail::IntegrateArgs integrate_args(float h);
  void integrate_velocities(float h);
  void integrate_positions(float h);
  void integrate_split(integrate_positions_fn* kernel, float h);
  void write_back();
  void update_sleep(float dt);
  void wake(uint32_t slot);
  void step_soft_bodies(float dt);  // world_soft.cpp
};

}  // namespace gyro
