// Status codes shared by the C++ API and the C ABI (same values as gyro_status in gyro.h).
#pragma once

#include <cstdint>

namespace gyro {

/// Result of every fallible call. The values are part of the C ABI and never change.
enum class Status : int32_t {
  ok = 0,
  null_argument = 1,     ///< a required pointer was null
  invalid_count = 2,     ///< a count was negative or too large
  non_finite = 3,        ///< an input value was NaN or infinite where a finite one is needed
  invalid_argument = 4,  ///< a value was out of its documented range
  unsupported = 5,       ///< the build or the CPU lacks the requested feature
  out_of_memory = 6,
  stale_id = 7,          ///< an id names an object that no longer exists
  internal = 8,          ///< a bug in gyro: please report it
  corrupt_data = 9,      ///< a snapshot or recording is truncated, corrupted or of another version
};

/// A short constant name for a status ("ok", "null_argument", ...).
const char* status_name(Status s);

/// The detail of the last failed call made by this thread ("" if none). The text stays
/// valid until this thread's next failing call.
const char* last_error();

}  // namespace gyro
