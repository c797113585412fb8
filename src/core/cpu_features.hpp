// What this CPU and OS can run, read directly (cpuid + xgetbv on x86-64). xsimd 8.1's own
// detection reads the AVX bit from the wrong leaf and skips the XGETBV check, so gyro
// never relies on it (TOOLCHAIN.md).
#pragma once

namespace gyro::detail {

struct CpuFeatures {
  bool sse2 = false;
  bool avx2 = false;     // AVX2 instructions and the OS saves YMM state
  bool avx512f = false;  // AVX-512F instructions and the OS saves ZMM and mask state
  bool neon = false;
};

/// Read once; cheap to call.
const CpuFeatures& cpu_features();

}  // namespace gyro::detail
