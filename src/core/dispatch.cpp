// The SIMD level setting behind gyro::simd_level() and gyro_set_simd_level().
#include "core/dispatch.hpp"

#include "core/cpu_features.hpp"
#include "core/error.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace gyro {
namespace {

bool cpu_runs(SimdLevel l) {
  const auto& f = detail::cpu_features();
  switch (l) {
    case SimdLevel::scalar: return true;
    case SimdLevel::sse2: return f.sse2;
    case SimdLevel::avx2: return f.avx2;
    case SimdLevel::avx512: return f.avx512f;
    case SimdLevel::neon: return f.neon;
    case SimdLevel::automatic: return false;
  }
  return false;
}

SimdLevel default_level() {
  // GYRO_SIMD may lower the level for the whole process; an unknown or unavailable value
  // falls back to the best available level below it, never above.
  SimdLevel best = detected_simd_level();
  const char* env = std::getenv("GYRO_SIMD");
  SimdLevel wanted;
  if (env == nullptr || !parse_simd_level(env, &wanted) || wanted == SimdLevel::automatic) return best;
  if (simd_level_available(wanted)) return wanted;
  for (uint32_t v = static_cast<uint32_t>(wanted); v >= 1; --v) {
    auto l = static_cast<SimdLevel>(v);
    if (simd_level_available(l) && simd_level_width(l) <= simd_level_width(wanted)) return l;
  }
  return SimdLevel::scalar;
}

std::atomic<uint32_t> g_forced{0};  // 0: not forced

}  // namespace

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::automatic: return "auto";
    case SimdLevel::scalar: return "scalar";
    case SimdLevel::sse2: return "sse2";
    case SimdLevel::avx2: return "avx2";
    case SimdLevel::avx512: return "avx512";
    case SimdLevel::neon: return "neon";
  }
  return "unknown";
}

bool parse_simd_level(const char* name, SimdLevel* out) {
  if (name == nullptr || out == nullptr) return false;
  for (uint32_t v = 0; v <= 5; ++v) {
    auto l = static_cast<SimdLevel>(v);
    if (std::strcmp(name, simd_level_name(l)) == 0) {
      *out = l;
      return true;
    }
  }
  return false;
}

uint32_t simd_level_width(SimdLevel level) {
  switch (level) {
    case SimdLevel::scalar: return 1;
    case SimdLevel::sse2: return 4;
    case SimdLevel::avx2: return 8;
    case SimdLevel::avx512: return 16;
    case SimdLevel::neon: return 4;
    case SimdLevel::automatic: return 0;
  }
  return 0;
}

#define GYRO_LEVEL_BUILT_(level, ns, ...) || l == SimdLevel::level
bool simd_level_built(SimdLevel l) { return false GYRO_FOR_EACH_ARCH(GYRO_LEVEL_BUILT_, ); }
#undef GYRO_LEVEL_BUILT_

bool simd_level_available(SimdLevel level) { return simd_level_built(level) && cpu_runs(level); }

SimdLevel detected_simd_level() {
  static const SimdLevel best = [] {
    SimdLevel b = SimdLevel::scalar;
    for (uint32_t v = 1; v <= 5; ++v) {
      auto l = static_cast<SimdLevel>(v);
      if (simd_level_available(l) && simd_level_width(l) > simd_level_width(b)) b = l;
    }
    return b;
  }();
  return best;
}

SimdLevel simd_level() {
  static const SimdLevel initial = default_level();
  uint32_t forced = g_forced.load(std::memory_order_relaxed);
  return forced != 0 ? static_cast<SimdLevel>(forced) : initial;
}

Status set_simd_level(SimdLevel level) {
  if (level == SimdLevel::automatic) {
    g_forced.store(0, std::memory_order_relaxed);
    return Status::ok;
  }
  if (simd_level_width(level) == 0) return detail::fail(Status::invalid_argument, "unknown SIMD level %u", static_cast<unsigned>(level));
  if (!simd_level_available(level))
    return detail::fail(Status::unsupported, "SIMD level %s is not available in this build on this CPU", simd_level_name(level));
  g_forced.store(static_cast<uint32_t>(level), std::memory_order_relaxed);
  return Status::ok;
}

}  // namespace gyro
