// EPA's arithmetic over SIMD lanes, for many polytopes at once (epa.cpp's epa_boxes): the
// planes of new faces and the supports of box pairs. Each lane performs exactly the
// operations of the scalar code it stands for (Polytope::add_face, PairFrame::support for
// two boxes), so the lanes give the scalar EPA's bits; epa.cpp keeps the topology (the walk,
// the linking, the closest-face search) per polytope.
#pragma once

#include "core/dispatch.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Faces whose planes are pending: corners a, b, c (columns x, y, z each).
struct EpaPlaneJobs {
  static constexpr std::size_t kMax = 1024;
  float a[3][kMax], b[3][kMax], c[3][kMax];
  // Out: the unit normal and the distance from the origin (both 0 for a sliver), and 1 for a
  // sliver (normal not trusted), else 0.
  float n[3][kMax], d[kMax], sliver[kMax];
};
/// Planes of jobs [0, count).
using epa_planes_fn = void(EpaPlaneJobs&, std::size_t count);
GYRO_KERNEL(epa_planes, epa_planes_fn)

/// Box pairs in slots (B in A's frame: rot rows are B's axes, pos its origin), one support
/// request per slot along dir; out: the support point w = a - b, its points a and b, and
/// whether w is one of the polytope's vertices already (vw[c][v][k]: coordinate c of slot
/// k's vertex v; nv[k] of them), as Polytope::has_vertex says.
struct EpaBoxSlots {
  static constexpr std::size_t kSlots = 16, kVerts = 128;
  float ha[3][kSlots], hb[3][kSlots], rot[9][kSlots], pos[3][kSlots], dir[3][kSlots];
  float vw[3][kVerts][kSlots], nv[kSlots];
  float w[3][kSlots], a[3][kSlots], b[3][kSlots], repeat[kSlots];
};
/// rows: the largest nv.
using epa_box_support_fn = void(EpaBoxSlots&, std::size_t rows);
GYRO_KERNEL(epa_box_support, epa_box_support_fn)

/// The closest-face search of the slots' polytopes. d[f][k]: face f's distance in slot k, +inf
/// where the face is dead or its plane not trusted; nf[k]: slot k's face count (0 for a slot
/// with no search). best[k]: the first face with the least distance (ties to the lowest
/// index, -0 tying +0, as Polytope::closest()), or -1 if none is below +inf.
struct EpaClosest {
  static constexpr std::size_t kSlots = EpaBoxSlots::kSlots, kFaces = 256;
  float d[kFaces][kSlots];
  float nf[kSlots], best[kSlots];
};
using epa_closest_fn = void(EpaClosest&, std::size_t rows);
GYRO_KERNEL(epa_closest, epa_closest_fn)

}  // namespace gyro
