// A refit's store of one node's slot boxes, at each SIMD level.
//
// A refit gathers a changed node's eight slots (its children's new boxes, the others as they
// were) into rows shaped like BvhNode8::bounds; this stores them when their bits differ from
// the node's and returns the rows' union. In scalar code the compare, the store and the
// union (48 compares and selects) were most of an all-moved refit's node work; at the AVX
// levels they are six lanes each.
//
// The union is over all eight slots: an empty slot's (+inf, -inf) changes no minimum or
// maximum, and the bounds hold no NaN and no -0 (bvh_refit.hpp), so any order of the
// operands gives the bits of BoxUnion::grow over the used slots.
#pragma once

#include "core/dispatch.hpp"
#include "spatial/bvh.hpp"

namespace gyro {

/// Stores rows into node.bounds when any of their bits differ and returns whether they did;
/// lo and hi get the union of the rows' boxes (BoxUnion's corners) either way.
using bvh_slots_store_fn = bool(detail::BvhNode8& node, const float (&rows)[6][8], float lo[3], float hi[3]);
GYRO_KERNEL(bvh_slots_store, bvh_slots_store_fn)

}  // namespace gyro
