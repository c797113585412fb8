// The octant orders of the nodes a refit changed, brought up to date at each SIMD level.
//
// A refit changes the boxes of many nodes (R1M with every model moved: 3,700 a frame) and
// few of their orders (13% there, 4% with a tenth moved). Checking an order costs less than
// sorting it, and the check is mostly gathers and compares of eight binary64 keys, which the
// AVX levels do in a few permutes (bvh_orders_kernels.cpp). A node the fast check cannot
// clear (an order that no longer sorts, or tied keys) is sorted again: by ranks in mask
// compares on AVX-512, by set_child_orders() elsewhere, each giving the build's bytes; so
// every level writes the same orders, the sort's.
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

}  // namespace gyro
