#include "core/parallel.hpp"
#include "gyro/runtime.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <vector>

namespace gyro::detail {
namespace {

class ParallelTest : public ::testing::Test {
 protected:
  void TearDown() override { set_thread_count(0); }
};

TEST_F(ParallelTest, ChunksAreFixedAndCoverEverythingOnce) {
  for (uint32_t threads : {1u, 2u, 3u, 8u}) {
    set_thread_count(threads);
    const std::size_t n = 10007, chunk = 256;
    std::vector<std::atomic<int>> seen(n);
    std::vector<std::atomic<int>> starts(n);
    parallel_for(n, chunk, [&](std::size_t b, std::size_t e) {
      starts[b]++;
      EXPECT_EQ(b % chunk, 0u);
      EXPECT_EQ(e, std::min(n, b + chunk));
      for (std::size_t i = b; i < e; ++i) seen[i]++;
    });
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << i;
    int chunks = 0;
    for (auto& s : starts) chunks += s.load();
    EXPECT_EQ(chunks, int((n + chunk - 1) / chunk));
  }
}

TEST_F(ParallelTest, EmptyAndSingleChunkRunInline) {
  int calls = 0;
  parallel_for(0, 16, [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
  set_thread_count(8);
  parallel_for(10, 16, [&](std::size_t b, std::size_t e) {
    ++calls;  // not atomic: must run on this thread
    EXPECT_EQ(b, 0u);
    EXPECT_EQ(e, 10u);
  });
  EXPECT_EQ(calls, 1);
}

TEST_F(ParallelTest, OrderedReduceIsBitIdenticalForAnyThreadCount) {
  // Terms of wildly different magnitudes: any change of summation order changes the bits.
  const std::size_t n = 1000003;
  std::vector<float> v(n);
  uint64_t s = 99;
  for (auto& x : v) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    const int e = int(s >> 59) * 3 - 20;
    x = std::ldexp(float(int32_t(s >> 40) - (1 << 23)) / float(1 << 23), e);
  }
  auto sum = [&] {
    std::vector<float> scratch(reduce_block_count(n));
    return ordered_reduce<float>(n, scratch, [&](std::size_t b, std::size_t e) {
      float acc = 0.0f;
      for (std::size_t i = b; i < e; ++i) acc += v[i];
      return acc;
    });
  };
  set_thread_count(1);
  const uint32_t ref = std::bit_cast<uint32_t>(sum());
  for (uint32_t t : {2u, 3u, 7u, 8u}) {
    set_thread_count(t);
    for (int rep = 0; rep < 3; ++rep) EXPECT_EQ(std::bit_cast<uint32_t>(sum()), ref) << t << " threads";
  }
  // The block order is part of the contract: a plain left-to-right sum differs.
  float plain = 0.0f;
  for (float x : v) plain += x;
  EXPECT_NE(std::bit_cast<uint32_t>(plain), ref);
}

}  // namespace
}  // namespace gyro::detail
