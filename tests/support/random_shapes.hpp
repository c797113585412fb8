// Seeded random primitives of every type, held both as public structs (for the scalar API)
// and as SoA columns (for the batch calls), so tests compare the two element by element.
// Rotations come from normalised random quaternions (only sqrt), so the same seed gives
// the same bits on every libm and CPU.
#pragma once

#include "gyro/batch_overlap.hpp"
#include "gyro/shapes.hpp"
#include "workloads.hpp"

#include <cstddef>
#include <vector>

namespace gyro::testing {

struct RandomShapes {
  ShapeType type = ShapeType::sphere;
  std::vector<Sphere> spheres;
  std::vector<AABB> aabbs;
  std::vector<OBB> obbs;
  std::vector<Plane> planes;
  std::vector<Triangle> triangles;
  std::vector<float> col[15];  // SoA, in the order of the type's view

  std::size_t size() const { return col[0].size(); }
  ShapeArray view() const;
};

/// n shapes of a type with centres in [0, box)^3 and sizes in [0.1, 1.1) (triangles: corners
/// within 1 of the centre; planes: random unit normal, distance in [0, box)).
RandomShapes random_shapes(ShapeType type, std::size_t n, SplitMix64& rng, float box = 4.0f);

/// A random rotation (rows are the axes).
mat3 random_rotation(SplitMix64& rng);

}  // namespace gyro::testing
