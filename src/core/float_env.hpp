// Pins the floating-point environment while gyro computes.
//
// The determinism contract needs IEEE round-to-nearest with subnormals kept. A host may
// have turned on flush-to-zero / denormals-are-zero (game engines and audio code do,
// and so does any shared library linked with -ffast-math); subnormal results would then
// differ from a host that has not. Every entry point that computes (batch calls, the
// world step) holds a guard, and so does every worker thread of a parallel loop. The
// scalar inline helpers (gyro::sin, vec3 math) are too small to pay for it: they run in
// the caller's environment. On exit the whole register is restored, status flags too, so
// the divisions by zero that branch-free kernels compute and discard never reach the host.
#pragma once

#include <cstdint>

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace gyro::detail {

class FloatEnvGuard {
 public:
#if defined(__x86_64__)
  FloatEnvGuard() : saved_(_mm_getcsr()) {
    // Keep the exception masks; clear FTZ (bit 15), DAZ (bit 6) and rounding (bits 13-14).
    const uint32_t wanted = saved_ & ~((1u << 15) | (1u << 6) | (3u << 13));
    if (wanted != saved_) _mm_setcsr(wanted);
  }
  ~FloatEnvGuard() { _mm_setcsr(saved_); }

 private:
  uint32_t saved_;
#elif defined(__aarch64__)
  FloatEnvGuard() : saved_(__builtin_aarch64_get_fpcr64()) {
    // Clear DN (25), FZ (24), RMode (22-23) and FZ16 (19).
    const uint64_t wanted = saved_ & ~((1ull << 25) | (1ull << 24) | (3ull << 22) | (1ull << 19));
    if (wanted != saved_) __builtin_aarch64_set_fpcr64(wanted);
  }
  ~FloatEnvGuard() {
    if (__builtin_aarch64_get_fpcr64() != saved_) __builtin_aarch64_set_fpcr64(saved_);
  }

 private:
  uint64_t saved_;
#else
  FloatEnvGuard() = default;
#endif
 public:
  FloatEnvGuard(const FloatEnvGuard&) = delete;
  FloatEnvGuard& operator=(const FloatEnvGuard&) = delete;
};

}  // namespace gyro::detail
