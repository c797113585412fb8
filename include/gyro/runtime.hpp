// Process-wide execution settings: which SIMD level runs the kernels and how many
// threads batch calls use. Results are bit-identical whatever these are set to; they
// only change speed. Environment: GYRO_SIMD=scalar|sse2|avx2|avx512|neon, GYRO_THREADS=N.
#pragma once

#include "gyro/status.hpp"

#include <cstdint>

namespace gyro {

/// Instruction-set levels. Values are part of the C ABI (gyro_simd_level).
enum class SimdLevel : uint32_t {
  automatic = 0,  ///< the best level the CPU and the build support (or GYRO_SIMD)
  scalar = 1,     ///< one float at a time: the reference every level reproduces bit for bit
  sse2 = 2,       ///< 4 lanes
  avx2 = 3,       ///< 8 lanes
  avx512 = 4,     ///< 16 lanes
  neon = 5,       ///< 4 lanes, aarch64
};

const char* simd_level_name(SimdLevel level);
/// Parses "scalar", "sse2", ... ; returns false for an unknown name.
bool parse_simd_level(const char* name, SimdLevel* out);
/// Lanes per batch at a level (1 for scalar; 0 for automatic or an unknown value).
uint32_t simd_level_width(SimdLevel level);
/// True if this build compiled the level's kernels (whatever this CPU can run).
bool simd_level_built(SimdLevel level);
/// True if this build has the level and this CPU (and OS) can run it.
bool simd_level_available(SimdLevel level);
/// The best available level, ignoring GYRO_SIMD and set_simd_level.
SimdLevel detected_simd_level();
/// The level kernels run at now.
SimdLevel simd_level();
/// Forces a level for the whole process; automatic returns to the default. A level that
/// is not available returns Status::unsupported and changes nothing.
Status set_simd_level(SimdLevel level);

/// Threads batch calls may use (1 means the calling thread only).
uint32_t thread_count();
/// Sets the thread count for the process; 0 returns to the default (GYRO_THREADS, else
/// the OpenMP default). Values above 1024 return Status::invalid_count.
Status set_thread_count(uint32_t threads);
/// True if the build has OpenMP (otherwise every call runs on the calling thread).
bool has_threads();

}  // namespace gyro
