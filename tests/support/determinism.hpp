// The determinism harness: scenes whose whole output is reduced to one 64-bit hash, run
// under every SIMD level this CPU has x thread counts {1, 2, 3, 8}. Every stage of gyro adds
// its scenes here with a pinned golden hash; tests/determinism checks them in-process and
// the gyro-dethash tool prints them so `make determinism` can compare builds (g++,
// clang++, aarch64 under qemu).
#pragma once

#include "gyro/runtime.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace gyro::testing {

struct DetScene {
  const char* name;
  uint64_t (*run)();  // runs at the current SIMD level and thread count
  uint64_t golden;    // pinned: the same on every level, thread count, compiler and CPU
};

std::span<const DetScene> determinism_scenes();

struct DetRun {
  SimdLevel level;
  uint32_t threads;
  uint64_t hash;
};

inline constexpr uint32_t kDetThreadCounts[] = {1, 2, 3, 8};

/// The SIMD levels this build and CPU can run, scalar first.
std::vector<SimdLevel> available_levels();

/// Runs the scene under every available level x thread count; restores the settings.
std::vector<DetRun> run_matrix(const DetScene& scene, std::span<const uint32_t> threads = kDetThreadCounts);

}  // namespace gyro::testing
