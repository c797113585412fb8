// The octant orders of the nodes a refit changed, brought up to date at each SIMD level.
//
// A refit changes the boxes of many nodes (R1M with every model moved: all 3,030 a frame) and
// few of their orders (a fifth of the nodes there, each mostly in one or two of its four
// octant pairs). Checking an order costs less than sorting it: the AVX levels check each pair
// first in binary32 lanes with a margin, then in binary64 where that cannot decide, and sort
// by ranks in SIMD compares only the pairs that fail (bvh_orders_kernels.cpp; R1M all moved,
// AVX2: 2.3 -> 1.1 M instructions a frame against the portable insertion sorts), each giving
// the build's bytes; so every level writes the same orders, the sort's.
#pragma once

#include "core/dispatch.hpp"
#include "spatial/bvh.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Leaves nodes[which[i]].order, for i in [0, count), exactly as detail::set_child_orders()
/// would write them for the nodes' bounds.
using bvh_orders_refresh_fn = void(detail::BvhNode8* nodes, const uint32_t* which, std::size_t count);
GYRO_KERNEL(bvh_orders_refresh, bvh_orders_refresh_fn)

/// Writes node.order as detail::set_child_orders() does, without checking what it held: the
/// build's (the AVX levels sort by ranks in SIMD compares, a quarter of the portable sort's
/// instructions).
using bvh_orders_set_fn = void(detail::BvhNode8& node);
GYRO_KERNEL(bvh_orders_set, bvh_orders_set_fn)

}  // namespace gyro
