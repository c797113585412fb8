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

/// The world and the mesh references its mesh bodies hold: gyro::ShapeDef::mesh is not owned,
/// so the C layer keeps each mesh alive until its body (or the world) is destroyed.
struct gyro_world {
  std::unique_ptr<gyro::World> world;
  std::map<std::pair<uint32_t, uint32_t>, std::shared_ptr<const gyro::TriangleMesh>> meshes;
};
