// Every determinism scene gives its pinned golden hash at every SIMD level and thread
// count. The same hashes are compared across compilers and aarch64 by `make determinism`.
#include "determinism.hpp"

#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>

namespace gyro::testing {
namespace {

class Determinism : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Determinism, GoldenHashAtEveryLevelAndThreadCount) {
  const DetScene& scene = determinism_scenes()[GetParam()];
  for (const DetRun& run : run_matrix(scene)) {
    EXPECT_EQ(run.hash, scene.golden) << scene.name << " at " << simd_level_name(run.level) << " x " << run.threads
                                      << " threads: got 0x" << std::hex << run.hash;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Determinism, ::testing::Range<std::size_t>(0, determinism_scenes().size()),
                         [](const auto& info) { return std::string(determinism_scenes()[info.param].name); });

}  // namespace
}  // namespace gyro::testing
