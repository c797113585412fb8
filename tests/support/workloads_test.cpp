// The generators reproduce BENCHMARKS.md bit for bit (its check values and hashes).
#include "workloads.hpp"

#include <gtest/gtest.h>

namespace gyro::testing {
namespace {

TEST(Workloads, SplitMixCheckValues) {
  EXPECT_EQ(SplitMix64(0).next(), 0xe220a8397b1dcdafull);
  SplitMix64 one(1);
  EXPECT_EQ(SplitMix64(1).next(), 0x910a2dec89025cc1ull);
  EXPECT_NEAR(one.u(), 0.56656152, 1e-8);
  EXPECT_NEAR(one.u(), 0.74578172, 1e-8);
  EXPECT_NEAR(one.u(), 0.971002698, 1e-9);
}

TEST(Workloads, R1MatchesThePublishedHashes) {
  EXPECT_EQ(r1_spheres().fnv(), kR1SpheresFnv);
  EXPECT_EQ(r1_rays().fnv(), kR1RaysFnv);
}

}  // namespace
}  // namespace gyro::testing
