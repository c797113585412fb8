#include "core/parallel.hpp"

#include "core/error.hpp"
#include "core/float_env.hpp"
#include "gyro/runtime.hpp"

#include <atomic>
#include <cstdlib>

#if defined(GYRO_HAS_OPENMP)
#include <omp.h>
#endif

namespace gyro {
namespace {

uint32_t default_threads() {
  if (const char* env = std::getenv("GYRO_THREADS")) {
    char* end = nullptr;
    unsigned long v = std::strtoul(env, &end, 10);
    if (end != env && *end == '\0' && v >= 1 && v <= 1024) return static_cast<uint32_t>(v);
  }
#if defined(GYRO_HAS_OPENMP)
  int n = omp_get_max_threads();  // honours OMP_NUM_THREADS
  return n >= 1 ? static_cast<uint32_t>(n) : 1u;
#else
  return 1;
#endif
}

std::atomic<uint32_t> g_threads{0};  // 0: default
thread_local uint32_t t_threads = 0;  // a ScopedThreadCount's override, 0: none

}  // namespace

uint32_t thread_count() {
#if defined(GYRO_HAS_OPENMP)
  static const uint32_t initial = default_threads();
  if (t_threads != 0) return t_threads;
  uint32_t t = g_threads.load(std::memory_order_relaxed);
  return t != 0 ? t : initial;
#else
  return 1;
#endif
}

Status set_thread_count(uint32_t threads) {
  if (threads > 1024) return detail::fail(Status::invalid_count, "thread count %u is above 1024", threads);
  g_threads.store(threads, std::memory_order_relaxed);
  return Status::ok;
}

bool has_threads() {
#if defined(GYRO_HAS_OPENMP)
  return true;
#else
  return false;
#endif
}

namespace detail {

ScopedThreadCount::ScopedThreadCount(uint32_t threads) : saved_(t_threads) {
  if (threads != 0) t_threads = threads;
}
ScopedThreadCount::~ScopedThreadCount() { t_threads = saved_; }

std::size_t per_thread_chunk(std::size_t n, std::size_t min_chunk, std::size_t align) {
  const std::size_t threads = thread_count();  // at least 1
  const std::size_t per_thread = (n + threads - 1) / threads;
  const std::size_t chunk = (per_thread + align - 1) / align * align;
  return chunk > min_chunk ? chunk : min_chunk;
}

void parallel_for_chunks(std::size_t n, std::size_t chunk, ChunkFn fn, void* context) {
  if (n == 0) return;
  if (chunk == 0) chunk = n;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const uint32_t threads = thread_count();
  if (threads <= 1 || chunks == 1) {
    FloatEnvGuard env;
    for (std::size_t k = 0; k < chunks; ++k) {
      const std::size_t b = k * chunk;
      fn(context, b, b + chunk < n ? b + chunk : n);
    }
    return;
  }
#if defined(GYRO_HAS_OPENMP)
  const int team = static_cast<int>(threads < chunks ? threads : chunks);
#pragma omp parallel num_threads(team)
  {
    FloatEnvGuard env;  // per worker: MXCSR / FPCR is per thread
    // Any schedule gives the same results: a chunk's outputs are its own. Dynamic
    // balances chunks of uneven cost (rays that traverse deep, pairs that early-out).
#pragma omp for schedule(dynamic, 1)  // detlint: allow (outputs are chunk-local)
    for (std::size_t k = 0; k < chunks; ++k) {
      const std::size_t b = k * chunk;
      fn(context, b, b + chunk < n ? b + chunk : n);
    }
  }
#endif
}

void parallel_stages_erased(std::size_t stages, std::size_t min_chunks, StageShapeFn shape, StageFn fn, void* context) {
  const uint32_t threads = thread_count();
  std::size_t widest = 0;
  if (min_chunks < 2) min_chunks = 2;
  for (std::size_t s = 0; s < stages && widest < min_chunks; ++s) {
    std::size_t n = 0, chunk = 0;
    shape(context, s, &n, &chunk);
    if (chunk == 0) chunk = n ? n : 1;
    const std::size_t chunks = (n + chunk - 1) / chunk;
    widest = chunks > widest ? chunks : widest;
  }
  auto run_stage = [&](std::size_t s, std::size_t k, std::size_t n, std::size_t chunk) {
    const std::size_t b = k * chunk;
    fn(context, s, b, b + chunk < n ? b + chunk : n);
  };
  if (threads <= 1 || widest < min_chunks) {
    FloatEnvGuard env;
    for (std::size_t s = 0; s < stages; ++s) {
      std::size_t n = 0, chunk = 0;
      shape(context, s, &n, &chunk);
      if (chunk == 0) chunk = n ? n : 1;
      for (std::size_t k = 0; k * chunk < n; ++k) run_stage(s, k, n, chunk);
    }
    return;
  }
#if defined(GYRO_HAS_OPENMP)
#pragma omp parallel num_threads(static_cast<int>(threads))
  {
    FloatEnvGuard env;
    for (std::size_t s = 0; s < stages; ++s) {
      std::size_t n = 0, chunk = 0;
      shape(context, s, &n, &chunk);  // every thread asks: a function of s alone
      if (chunk == 0) chunk = n ? n : 1;
      const std::size_t chunks = (n + chunk - 1) / chunk;
      // The implicit barrier at the end of each loop orders the stages. Static: chunk k of
      // every stage runs on thread k % threads, so data a thread touched in one stage is in
      // its cache for the next (solver colours, sub-step integration; measured ~10% faster
      // than dynamic on 16 pyramids with 2 threads).
#pragma omp for schedule(static, 1)  // detlint: allow (outputs are chunk-local)
      for (std::size_t k = 0; k < chunks; ++k) run_stage(s, k, n, chunk);
    }
  }
#endif
}

}  // namespace detail
}  // namespace gyro
