// Parallel loops whose results never depend on the thread count.
//
// parallel_for cuts [0, n) into fixed chunks of `chunk` elements ([k*chunk, (k+1)*chunk)),
// a function of n and chunk only. Each chunk is one call; a kernel writes only the outputs
// of its own chunk, so which thread runs which chunk cannot change a result. With one
// thread, or a single chunk, everything runs on the calling thread with no OpenMP cost.
//
// ordered_reduce sums in fixed blocks of kReduceBlock elements, each block in index order,
// then the block sums in index order: bit-identical for any thread count and any SIMD
// width (an OpenMP reduction clause is not: TOOLCHAIN.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>

namespace gyro::detail {

/// Overrides the thread count for this thread's parallel loops while it lives (0 keeps the
/// process setting): how a world's own thread count applies to its step.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(uint32_t threads);
  ~ScopedThreadCount();
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  uint32_t saved_;
};

using ChunkFn = void (*)(void* context, std::size_t begin, std::size_t end);

/// Type-erased core of parallel_for (the only place OpenMP is used).
void parallel_for_chunks(std::size_t n, std::size_t chunk, ChunkFn fn, void* context);

template <class F> void parallel_for(std::size_t n, std::size_t chunk, F&& fn) {
  auto thunk = [](void* ctx, std::size_t b, std::size_t e) { (*static_cast<std::remove_reference_t<F>*>(ctx))(b, e); };
  parallel_for_chunks(n, chunk, thunk, const_cast<void*>(static_cast<const void*>(&fn)));
}

/// A sequence of dependent parallel loops in one parallel region: one fork and join for all
/// of them and a barrier between stages, instead of a region per loop (a solver sub-step of a
/// dozen colours would otherwise pay a dozen forks). Stage s has *n elements cut into fixed
/// chunks of *chunk (set by shape(s)); fn(s, begin, end) runs once per chunk. Results never
/// depend on the thread count for the same reason as parallel_for's. Chunk k of every stage
/// runs on thread k % threads (static schedule: locality from stage to stage). With one
/// thread, or when no stage has min_chunks chunks, everything runs on the calling thread in order.
using StageShapeFn = void (*)(void* context, std::size_t stage, std::size_t* n, std::size_t* chunk);
using StageFn = void (*)(void* context, std::size_t stage, std::size_t begin, std::size_t end);
void parallel_stages_erased(std::size_t stages, std::size_t min_chunks, StageShapeFn shape, StageFn fn, void* context);
template <class Shape, class F> void parallel_stages(std::size_t stages, std::size_t min_chunks, Shape&& shape, F&& fn) {
  struct Ctx {
    std::remove_reference_t<Shape>* shape;
    std::remove_reference_t<F>* fn;
  } ctx{&shape, &fn};
  auto shape_thunk = [](void* c, std::size_t s, std::size_t* n, std::size_t* chunk) { (*static_cast<Ctx*>(c)->shape)(s, n, chunk); };
  auto fn_thunk = [](void* c, std::size_t s, std::size_t b, std::size_t e) { (*static_cast<Ctx*>(c)->fn)(s, b, e); };
  parallel_stages_erased(stages, min_chunks, shape_thunk, fn_thunk, &ctx);
}

/// The chunk for a loop whose cut cannot change its results (a solver colour, an integration):
/// one chunk per thread, a multiple of `align`, and at least `min_chunk` elements, so a loop
/// too small to pay for a fork runs as one chunk on the calling thread.
std::size_t per_thread_chunk(std::size_t n, std::size_t min_chunk, std::size_t align);

inline constexpr std::size_t kReduceBlock = 4096;

inline std::size_t reduce_block_count(std::size_t n) { return (n + kReduceBlock - 1) / kReduceBlock; }

/// Sums block_sum(begin, end) over the fixed blocks of [0, n). `scratch` must hold
/// reduce_block_count(n) values. block_sum must sum its block in index order.
template <class T, class BlockSum> T ordered_reduce(std::size_t n, std::span<T> scratch, BlockSum&& block_sum) {
  parallel_for(n, kReduceBlock, [&](std::size_t b, std::size_t e) { scratch[b / kReduceBlock] = block_sum(b, e); });
  T acc{};
  const std::size_t blocks = reduce_block_count(n);
  for (std::size_t k = 0; k < blocks; ++k) acc = acc + scratch[k];
  return acc;
}

}  // namespace gyro::detail
