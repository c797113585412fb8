// Input checks for SoA shape arrays, shared by the batch calls.
#pragma once

#include "gyro/batch_overlap.hpp"
#include "gyro/batch_raycast.hpp"

#include <cstddef>

namespace gyro::detail {

/// Checks that the type is known and, when n > 0, that every component pointer is set;
/// with strict, also that elements [0, n) are finite with non-negative sizes. Reports the
/// array as `which`.
Status check_shape_array(const ShapeArray& s, std::size_t n, const char* which, bool strict);

/// Checks a ray array: origin and direction pointers set; with values, also finite
/// coordinates, tmin (if given) finite and >= 0, tmax (if given) >= 0 or +infinity.
/// Reports the first bad array and index.
Status check_rays(const RaysView& rays, std::size_t n, bool values = true);

/// The optional per-hit output columns of the batch raycasts: the normal all three or none,
/// the barycentrics u and v both or none.
Status check_hit_columns(const float* nx, const float* ny, const float* nz, const float* u, const float* v);

}  // namespace gyro::detail
