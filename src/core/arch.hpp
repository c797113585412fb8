// Which instruction-set level this translation unit is compiled for.
//
// Every kernel source is compiled once per SIMD level, each time with only that level's
// compiler flags and with GYRO_ARCH_<LEVEL> and GYRO_ARCH_NS defined by the build. All lane
// code lives in namespace gyro::GYRO_ARCH_NS, so an inline function or template compiled
// with AVX flags gets its own symbol and can never be picked by the linker for the SSE2
// or scalar path (xsimd pitfall 6 in TOOLCHAIN.md). Generic engine code is compiled as
// the scalar level.
#pragma once

#if !defined(GYRO_ARCH_NS)
#define GYRO_ARCH_NS arch_scalar
#define GYRO_ARCH_SCALAR 1
#endif

#if defined(GYRO_ARCH_SCALAR)
#define GYRO_ARCH_WIDTH 1
#elif defined(GYRO_ARCH_SSE2) || defined(GYRO_ARCH_NEON)
#define GYRO_ARCH_WIDTH 4
#elif defined(GYRO_ARCH_AVX2)
#define GYRO_ARCH_WIDTH 8
#elif defined(GYRO_ARCH_AVX512)
#define GYRO_ARCH_WIDTH 16
#else
#error "GYRO_ARCH_NS is set but no GYRO_ARCH_<LEVEL> is defined"
#endif

// GYRO_FOR_EACH_ARCH(X) expands X(level, namespace) for every level this build has; the
// build writes it (CMake option GYRO_SIMD_LEVELS) into gyro_build_config.hpp.
#include "gyro_build_config.hpp"

// Kernel entry points inline their whole per-batch body (shapes stay in registers instead
// of being returned through the stack). Sanitizer builds turn it off: instrumented and
// flattened, one kernel file took minutes to compile, and speed does not matter there.
#if defined(GYRO_NO_FLATTEN)
#define GYRO_FLATTEN
#else
#define GYRO_FLATTEN [[gnu::flatten]]
#endif
