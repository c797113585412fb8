// The C ABI's snapshot and restore (gyro/world.hpp's World::snapshot and restore), and the
// mesh references the C layer keeps for the restored mesh bodies.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_recorder.hpp"
#include "capi_support.hpp"
#include "capi_world.hpp"

#include "gyro/triangle_mesh.hpp"

#include <cstdint>
#include <limits>

namespace {

using gyro::Status;
using gyro::capi::guarded;
using gyro::capi::require;
using gyro::detail::fail;

Status check_size(uint64_t size) {
  if (size > std::numeric_limits<std::size_t>::max()) return fail(Status::invalid_count, "size does not fit in memory");
  return Status::ok;
}

/// After a restore, each mesh body that uses one of the caller's meshes gets that mesh's
/// reference again (under its restored id); meshes no body uses any more are released.
/// Meshes the snapshot brought are the C++ world's own.
void rekey_meshes(gyro_world* w) {
  decltype(w->meshes) fresh;
  const gyro::BodyView v = w->world->bodies();
  for (std::size_t i = 0; i < v.count; ++i) {
    const gyro::TriangleMesh* mesh = nullptr;
    if (w->world->get_mesh(v.ids[i], &mesh) != Status::ok || !mesh) continue;
    for (const auto& [key, ref] : w->meshes)
      if (ref.get() == mesh) {
        fresh.emplace(std::pair<uint32_t, uint32_t>{v.ids[i].index, v.ids[i].generation}, ref);
        break;
      }
  }
  w->meshes.swap(fresh);
}

}  // namespace

extern "C" {

GYRO_API gyro_status gyro_world_snapshot_size(const gyro_world* world, uint64_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(world, "world"));
    GYRO_TRY(require(out, "out"));
    *out = world->world->snapshot_size();
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_snapshot(const gyro_world* world, void* buffer, uint64_t capacity, uint64_t* out_size) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(world, "world"));
    GYRO_TRY(require(buffer, "buffer"));
    GYRO_TRY(require(out_size, "out_size"));
    const std::size_t cap =
        capacity > std::numeric_limits<std::size_t>::max() ? std::numeric_limits<std::size_t>::max() : std::size_t(capacity);
    std::size_t size = 0;
    GYRO_TRY(world->world->snapshot(buffer, cap, &size));
    *out_size = size;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_restore(gyro_world* world, const void* buffer, uint64_t size) {
  const gyro_status st = guarded([&]() -> Status {
    GYRO_TRY(require(world, "world"));
    GYRO_TRY(require(buffer, "buffer"));
    GYRO_TRY(check_size(size));
    GYRO_TRY(world->world->restore(buffer, std::size_t(size)));
    // The references are re-keyed after the swap; a map node allocation failing here (the
    // only thing that can) leaves the old references in place, which keeps every mesh alive.
    rekey_meshes(world);
    return Status::ok;
  });
  // A recording follows the restore (capi_recorder.hpp): replay restores the same bytes.
  return gyro::capi::rec::recorded<&gyro_world_restore>(st, world, buffer, size);
}

GYRO_API gyro_status gyro_world_create_from_snapshot(const void* buffer, uint64_t size, gyro_world** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(buffer, "buffer"));
    GYRO_TRY(require(out, "out"));
    GYRO_TRY(check_size(size));
    auto w = std::make_unique<gyro_world>();
    GYRO_TRY(gyro::World::create_from_snapshot(buffer, std::size_t(size), &w->world));
    *out = w.release();
    return Status::ok;
  });
}

}  // extern "C"
