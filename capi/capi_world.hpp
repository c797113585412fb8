// The C ABI's world handle, shared by the world and soft-body implementation files.
// Internal: never installed.
#pragma once

#include "gyro.h"

#include "capi_handles.hpp"
#include "gyro/world.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <utility>

namespace gyro::capi::rec {
struct Recorder;  // capi_recorder.hpp
/// Frees a recording (defined with the recorder, in gyro_capi_replay.cpp).
struct RecorderDelete {
  void operator()(Recorder* r) const noexcept;
};
}  // namespace gyro::capi::rec

/// The world and the mesh references its mesh bodies hold: gyro::ShapeDef::mesh is not owned,
/// so the C layer keeps each mesh alive until its body (or the world) is destroyed.
struct gyro_world {
  std::unique_ptr<gyro::World> world;
  std::map<std::pair<uint32_t, uint32_t>, std::shared_ptr<const gyro::TriangleMesh>> meshes;
  /// The recording of this world's calls (gyro_world_record_begin), null when not recording:
  /// a call on a world that is not recording pays one null check (capi_recorder.hpp).
  std::unique_ptr<gyro::capi::rec::Recorder, gyro::capi::rec::RecorderDelete> recorder;
};
