// Integration of the solver bodies' positions over a sub-step, as a per-level kernel: the
// position and orientation columns of the body store advance by the solver body's velocity,
// and its displacement and rotation since the step began (which the contact passes read)
// grow with them.
#pragma once

#include "core/dispatch.hpp"
#include "dynamics/contact_solver.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {
namespace detail {

struct IntegrateArgs {
  SolverBody* bodies = nullptr;
  const uint32_t* solver_index = nullptr;  ///< 0, 1, 2, ...: solver body b is lane b
  const uint32_t* slot_of_body = nullptr;  ///< solver body -> body store slot (ascending)
  float *px = nullptr, *py = nullptr, *pz = nullptr;
  float *qx = nullptr, *qy = nullptr, *qz = nullptr, *qw = nullptr;
  float h = 0.0f;
  // Velocity integration only:
  const float* lin_acc[3] = {};  ///< per solver body, constant over the step
  const float* ang_acc[3] = {};
  const float *linear_damping = nullptr, *angular_damping = nullptr;  ///< per body store slot
  const float *inv_ix = nullptr, *inv_iy = nullptr, *inv_iz = nullptr;  ///< principal inverse inertia, per slot
};

}  // namespace detail

/// p += v h, q = normalized(q + (w, 0) q h / 2), dp += v h, dtheta += w h, for solver bodies
/// [begin, end).
using integrate_positions_fn = void(const detail::IntegrateArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(integrate_positions, integrate_positions_fn)
/// For the dynamic solver bodies of [begin, end): v += h a, damped; w += h alpha, then the
/// gyroscopic torque -w x (I w) integrated implicitly in the body frame (one Newton step,
/// Catto 2015: stable for long thin bodies where the explicit form gains energy), damped.
GYRO_KERNEL(integrate_velocities, integrate_positions_fn)

}  // namespace gyro
