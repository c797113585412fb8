// The soft-body passes at every SIMD level: particle prediction and velocity update, and the
// spring passes of both models over runs of one colour (soft_plan.hpp). A run's springs share
// no particle, so lane k computes exactly what the scalar path computes for spring k, and
// the bits do not depend on the SIMD width or on how runs are split among threads.
#pragma once

#include "core/dispatch.hpp"
#include "dynamics/soft_plan.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

struct SoftKernelArgs {
  // particles
  float *px, *py, *pz;  ///< positions
  float *vx, *vy, *vz;  ///< velocities
  float *qx, *qy, *qz;  ///< positions at the start of the sub-step
  const float* w;       ///< inverse masses (0: pinned)
  // springs, in solve order
  const uint32_t *a, *b;
  const float* rest;
  const float* stiffness;   ///< k (springs model)
  const float* compliance;  ///< 1 / k (xpbd; 0 for an inextensible spring)
  const float* damping;     ///< b, N s/m
  float* lambda;            ///< xpbd: accumulated multipliers (iterations > 1)
  // the sub-step
  float h, inv_h, inv_h2;
  float gx, gy, gz;   ///< gravity * h (the velocity change of a free particle)
  float damp;         ///< velocity factor 1 / (1 + h damping)
  uint32_t accumulate;  ///< xpbd: 1 reads and writes lambda; 0 treats it as 0 (one pass per sub-step)
  uint32_t damped;      ///< xpbd: 1 when a spring has damping (else its terms are skipped)
};

/// Particles [begin, end).
using soft_particles_fn = void(const SoftKernelArgs&, std::size_t begin, std::size_t end);
/// Runs [begin, end) of one colour.
using soft_runs_fn = void(const SoftKernelArgs&, const SpringRun* runs, std::size_t begin, std::size_t end);

}  // namespace detail

/// v = (v + g h) * damp for free particles, q = x, x += v h (pinned particles stay put).
GYRO_KERNEL(soft_predict, detail::soft_particles_fn)
/// xpbd: v = (x - q) / h * damp (pinned: 0).
GYRO_KERNEL(soft_update_velocity, detail::soft_particles_fn)
/// xpbd: one projection of each spring with compliance and damping (Macklin et al. 2016).
GYRO_KERNEL(soft_xpbd_runs, detail::soft_runs_fn)
/// springs model: v += w (k C + b dv.n) h n, the Hooke spring's impulse over the sub-step.
GYRO_KERNEL(soft_spring_runs, detail::soft_runs_fn)

}  // namespace gyro
