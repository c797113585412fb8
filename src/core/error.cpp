#include "core/error.hpp"

#include <cstdarg>
#include <cstdio>

namespace gyro {
namespace {
// A fixed buffer: reporting an error never allocates, so it works when memory is short.
thread_local char t_last_error[512] = "";
}  // namespace

const char* status_name(Status s) {
  switch (s) {
    case Status::ok: return "ok";
    case Status::null_argument: return "null_argument";
    case Status::invalid_count: return "invalid_count";
    case Status::non_finite: return "non_finite";
    case Status::invalid_argument: return "invalid_argument";
    case Status::unsupported: return "unsupported";
    case Status::out_of_memory: return "out_of_memory";
    case Status::stale_id: return "stale_id";
    case Status::internal: return "internal";
    case Status::corrupt_data: return "corrupt_data";
  }
  return "unknown_status";
}

const char* last_error() { return t_last_error; }

namespace detail {
Status fail(Status s, const char* format, ...) {
  int n = std::snprintf(t_last_error, sizeof t_last_error, "%s: ", status_name(s));
  if (n < 0 || static_cast<unsigned>(n) >= sizeof t_last_error) n = 0;
  va_list args;
  va_start(args, format);
  std::vsnprintf(t_last_error + n, sizeof t_last_error - static_cast<unsigned>(n), format, args);
  va_end(args);
  return s;
}

void clear_error() { t_last_error[0] = '\0'; }
}  // namespace detail
}  // namespace gyro
