// The C ABI's convex hull handle, shared by the convex and world implementation files.
// Internal: never installed.
#pragma once

#include "gyro.h"

#include "gyro/convex.hpp"

/// An immutable hull: built once by gyro_convex_hull_create, read by the getters and queries,
/// copied by the world for hull bodies.
struct gyro_convex_hull {
  gyro::ConvexHull hull;
};
