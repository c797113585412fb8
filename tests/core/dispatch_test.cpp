#include "core/cpu_features.hpp"
#include "gyro/runtime.hpp"

#include <gtest/gtest.h>

namespace gyro {
namespace {

class SimdLevelTest : public ::testing::Test {
 protected:
  void TearDown() override { set_simd_level(SimdLevel::automatic); }
};

TEST_F(SimdLevelTest, ScalarIsAlwaysAvailableAndNamesRoundTrip) {
  EXPECT_TRUE(simd_level_available(SimdLevel::scalar));
  for (uint32_t v = 0; v <= 5; ++v) {
    SimdLevel l = static_cast<SimdLevel>(v), back;
    ASSERT_TRUE(parse_simd_level(simd_level_name(l), &back));
    EXPECT_EQ(back, l);
  }
  SimdLevel out;
  EXPECT_FALSE(parse_simd_level("avx1024", &out));
  EXPECT_FALSE(parse_simd_level(nullptr, &out));
}

TEST_F(SimdLevelTest, DetectionMatchesTheCpu) {
  const auto& f = detail::cpu_features();
#if defined(__x86_64__)
  EXPECT_TRUE(f.sse2);
  EXPECT_EQ(simd_level_available(SimdLevel::avx512), f.avx512f && simd_level_built(SimdLevel::avx512));
  EXPECT_EQ(simd_level_available(SimdLevel::avx2), f.avx2 && simd_level_built(SimdLevel::avx2));
  EXPECT_FALSE(simd_level_available(SimdLevel::neon));
#endif
  EXPECT_TRUE(simd_level_available(detected_simd_level()));
}

TEST_F(SimdLevelTest, ForcingALevelAndRejectingUnavailableOnes) {
  ASSERT_EQ(set_simd_level(SimdLevel::scalar), Status::ok);
  EXPECT_EQ(simd_level(), SimdLevel::scalar);
  for (uint32_t v = 1; v <= 5; ++v) {
    SimdLevel l = static_cast<SimdLevel>(v);
    Status s = set_simd_level(l);
    if (simd_level_available(l)) {
      EXPECT_EQ(s, Status::ok);
      EXPECT_EQ(simd_level(), l);
    } else {
      EXPECT_EQ(s, Status::unsupported);
      EXPECT_NE(simd_level(), l);  // unchanged
    }
  }
  EXPECT_EQ(set_simd_level(static_cast<SimdLevel>(99)), Status::invalid_argument);
  ASSERT_EQ(set_simd_level(SimdLevel::automatic), Status::ok);
}

TEST(ThreadCount, SetAndReset) {
  const uint32_t initial = thread_count();
  EXPECT_GE(initial, 1u);
  EXPECT_EQ(set_thread_count(3), Status::ok);
  EXPECT_EQ(thread_count(), has_threads() ? 3u : 1u);
  EXPECT_EQ(set_thread_count(5000), Status::invalid_count);
  EXPECT_EQ(thread_count(), has_threads() ? 3u : 1u);
  EXPECT_EQ(set_thread_count(0), Status::ok);
  EXPECT_EQ(thread_count(), initial);
}

}  // namespace
}  // namespace gyro
