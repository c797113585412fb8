#include "core/default_init.hpp"
#include "spatial/bvh.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace gyro::detail {
namespace {

// Large blocks are huge-page aligned (what lets madvise give them 2 MiB pages); small ones
// come from std::allocator with their type's alignment. Growth keeps the elements through
// either kind of block.
TEST(DefaultInitVector, LargeBlocksAreHugePageAlignedAndKeepTheirElements) {
  DefaultInitVector<uint32_t> v;
  for (uint32_t i = 0; i < 3u << 20; ++i) v.push_back(i * 2654435761u);  // 12 MiB, through every size
  EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % kHugeBlock, 0u);
  uint32_t wrong = 0;
  for (uint32_t i = 0; i < v.size(); ++i) wrong += v[i] != i * 2654435761u;
  EXPECT_EQ(wrong, 0u);

  DefaultInitVector<BvhNode8> nodes(3);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(nodes.data()) % alignof(BvhNode8), 0u);
  nodes.resize(kHugeBlock / sizeof(BvhNode8) + 1);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(nodes.data()) % kHugeBlock, 0u);
}

}  // namespace
}  // namespace gyro::detail
