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
  const uint32_t* slot_of_body = nullptr;  ///< solver body -> body store slot
  float *px = nullptr, *py = nullptr, *pz = nullptr;
  float *qx = nullptr, *qy = nullptr, *qz = nullptr, *qw = nullptr;
  float h = 0.0f;
};

}  // namespace detail

/// p += v h, q = normalized(q + (w, 0) q h / 2), dp += v h, dtheta += w h, for solver bodies
/// [begin, end).
using integrate_positions_fn = void(const detail::IntegrateArgs&, std::size_t begin, std::size_t end);
GYRO_KERNEL(integrate_positions, integrate_positions_fn)

}  // namespace gyro
