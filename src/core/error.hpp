// Per-thread error detail behind gyro::last_error() and gyro_last_error().
#pragma once

#include "gyro/status.hpp"

namespace gyro::detail {

/// Records a printf-style detail for this thread and returns `s`, so a failing path reads
/// `return fail(Status::null_argument, "rays.ox is null");`.
Status fail(Status s, const char* format, ...) __attribute__((format(printf, 2, 3)));

/// Clears this thread's detail (a successful call leaves the previous failure readable,
/// as errno does; only tests need this).
void clear_error();

}  // namespace gyro::detail
