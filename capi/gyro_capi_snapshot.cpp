// The C ABI's snapshot and restore (in progress).
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_world.hpp"
#include "core/error.hpp"

extern "C" {
GYRO_API gyro_status gyro_world_snapshot_size(const gyro_world*, uint64_t*) {
  return static_cast<gyro_status>(gyro::detail::fail(gyro::Status::unsupported, "snapshot: not built yet"));
}
GYRO_API gyro_status gyro_world_snapshot(const gyro_world*, void*, uint64_t, uint64_t*) {
  return static_cast<gyro_status>(gyro::detail::fail(gyro::Status::unsupported, "snapshot: not built yet"));
}
GYRO_API gyro_status gyro_world_restore(gyro_world*, const void*, uint64_t) {
  return static_cast<gyro_status>(gyro::detail::fail(gyro::Status::unsupported, "snapshot: not built yet"));
}
GYRO_API gyro_status gyro_world_create_from_snapshot(const void*, uint64_t, gyro_world**) {
  return static_cast<gyro_status>(gyro::detail::fail(gyro::Status::unsupported, "snapshot: not built yet"));
}
}
