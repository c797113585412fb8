#include "core/columns.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace gyro::detail {
namespace {

TEST(Column, AlignedAndPaddedWithThePadValue) {
  Column<float> c(1.0f);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(c.push_back(float(i) + 10.0f));
  EXPECT_EQ(c.size(), 20u);
  EXPECT_EQ(c.padded_size(), 32u);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(c.data()) % kColumnAlign, 0u);
  for (std::size_t i = 20; i < c.padded_size(); ++i) EXPECT_EQ(c[i], 1.0f) << i;
}

TEST(Column, SwapRemoveMovesTheLastAndRestoresThePad) {
  Column<int> c(-1);
  for (int i = 0; i < 5; ++i) c.push_back(i);
  c.swap_remove(1);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0], 0);
  EXPECT_EQ(c[1], 4);
  EXPECT_EQ(c[2], 2);
  EXPECT_EQ(c[3], 3);
  EXPECT_EQ(c[4], -1);
}

TEST(Column, ResizeShrinkAndCopy) {
  Column<float> c(0.5f);
  ASSERT_TRUE(c.resize(40, 2.0f));
  ASSERT_TRUE(c.resize(3, 7.0f));
  EXPECT_EQ(c[2], 2.0f);
  EXPECT_EQ(c[3], 0.5f);
  Column<float> d = c;
  EXPECT_EQ(d.size(), 3u);
  EXPECT_EQ(d[1], 2.0f);
  EXPECT_EQ(d[5], 0.5f);
  Column<float> e = std::move(d);
  EXPECT_EQ(e.size(), 3u);
}

}  // namespace
}  // namespace gyro::detail
