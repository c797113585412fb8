#include "core/arena.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace gyro::detail {
namespace {

TEST(Arena, AlignsAndKeepsAllocationsDisjoint) {
  Arena a;
  auto* p = static_cast<unsigned char*>(a.allocate(3));
  auto* q = static_cast<unsigned char*>(a.allocate(100, 16));
  auto* r = static_cast<unsigned char*>(a.allocate(8, 256));
  ASSERT_TRUE(p && q && r);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % 64, 0u);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(q) % 16, 0u);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(r) % 256, 0u);
  EXPECT_GE(q, p + 3);
  EXPECT_GE(r, q + 100);
}

TEST(Arena, RejectsBadAlignment) {
  Arena a;
  EXPECT_EQ(a.allocate(8, 3), nullptr);
  EXPECT_EQ(a.allocate(8, 0), nullptr);
}

TEST(Arena, StopsAllocatingAfterWarmUp) {
  // A "step" that needs 1 MB in many pieces: the first steps grow the arena, then reset
  // merges the blocks and later steps make no heap allocation.
  Arena a;
  auto step = [&] {
    for (int i = 0; i < 100; ++i) ASSERT_NE(a.allocate(10000), nullptr);
    a.reset();
  };
  step();
  step();
  const uint64_t after_warmup = a.heap_allocations();
  for (int i = 0; i < 10; ++i) step();
  EXPECT_EQ(a.heap_allocations(), after_warmup);
  EXPECT_GE(a.capacity_bytes(), 1000000u);
}

TEST(Arena, TypedArrays) {
  Arena a;
  auto v = a.array<double>(1000);
  ASSERT_EQ(v.size(), 1000u);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = double(i);
  EXPECT_EQ(v[999], 999.0);
  EXPECT_EQ(a.used_bytes(), 8000u);
}

}  // namespace
}  // namespace gyro::detail
