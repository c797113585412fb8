// Views of primitives stored as structure of arrays (one pointer per component), owned by
// the caller and never copied: what the batch calls take. Conventions as gyro/shapes.hpp.
#pragma once

namespace gyro {

/// Spheres: centre and radius (>= 0).
struct SpheresView {
  const float* cx = nullptr;
  const float* cy = nullptr;
  const float* cz = nullptr;
  const float* r = nullptr;
};

/// Axis-aligned boxes: centre and half extents (>= 0).
struct AabbsView {
  const float *cx = nullptr, *cy = nullptr, *cz = nullptr;
  const float *ex = nullptr, *ey = nullptr, *ez = nullptr;
};

/// Oriented boxes: centre, half extents (>= 0) and the three unit axes u0, u1, u2 (the rows
/// of the orientation matrix).
struct ObbsView {
  const float *cx = nullptr, *cy = nullptr, *cz = nullptr;
  const float *ex = nullptr, *ey = nullptr, *ez = nullptr;
  const float *u0x = nullptr, *u0y = nullptr, *u0z = nullptr;
  const float *u1x = nullptr, *u1y = nullptr, *u1z = nullptr;
  const float *u2x = nullptr, *u2y = nullptr, *u2z = nullptr;
};

/// Planes dot(n, p) = d with unit n.
struct PlanesView {
  const float *nx = nullptr, *ny = nullptr, *nz = nullptr;
  const float* d = nullptr;
};

/// Triangles with corners a, b, c.
struct TrianglesView {
  const float *ax = nullptr, *ay = nullptr, *az = nullptr;
  const float *bx = nullptr, *by = nullptr, *bz = nullptr;
  const float *cx = nullptr, *cy = nullptr, *cz = nullptr;
};

}  // namespace gyro
