// Input checks shared by every entry point: a bad input is reported with the name of the
// array and the first bad index, before anything is written.
#pragma once

#include "core/error.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>

namespace gyro::detail {

inline bool is_finite(float v) { return (std::bit_cast<uint32_t>(v) & 0x7f800000u) != 0x7f800000u; }
inline bool is_nan(float v) { return (std::bit_cast<uint32_t>(v) & 0x7fffffffu) > 0x7f800000u; }

/// Index of the first NaN or infinity in v[0..n), or n.
inline std::size_t first_non_finite(const float* v, std::size_t n) {
  // Branch-free in blocks, so the common all-finite case runs at memory speed.
  std::size_t i = 0;
  for (; i + 64 <= n; i += 64) {
    uint32_t bad = 0;
    for (std::size_t k = 0; k < 64; ++k) bad |= ((std::bit_cast<uint32_t>(v[i + k]) & 0x7f800000u) == 0x7f800000u);
    if (bad) break;
  }
  for (; i < n; ++i)
    if (!is_finite(v[i])) return i;
  return n;
}

inline Status require_finite(const float* v, std::size_t n, const char* name) {
  const std::size_t bad = first_non_finite(v, n);
  if (bad == n) return Status::ok;
  return fail(Status::non_finite, "%s[%zu] is not finite", name, bad);
}

inline Status require_not_null(const void* p, const char* name) {
  return p ? Status::ok : fail(Status::null_argument, "%s is null", name);
}

#define GYRO_TRY(expr)                                  \
  do {                                                  \
    const ::gyro::Status gyro_try_s_ = (expr);          \
    if (gyro_try_s_ != ::gyro::Status::ok) return gyro_try_s_; \
  } while (0)

}  // namespace gyro::detail
