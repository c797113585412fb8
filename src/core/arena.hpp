// Arena: per-world scratch memory for one step.
//
// allocate() bumps a pointer; reset() frees everything at once. When a step needed more
// than the first block, reset() replaces the blocks by one block of their total size, so
// after the first steps (warm-up) a step makes no heap allocation at all. Not thread-safe:
// allocate before a parallel loop, then hand out disjoint ranges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gyro::detail {

class Arena {
 public:
  explicit Arena(std::size_t initial_bytes = 0);
  ~Arena();
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;

  /// 64-byte aligned unless asked otherwise; nullptr only when memory runs out.
  void* allocate(std::size_t bytes, std::size_t align = 64);

  template <class T> std::span<T> array(std::size_t n) {
    void* p = allocate(n * sizeof(T), alignof(T) > 64 ? alignof(T) : 64);
    return p ? std::span<T>(static_cast<T*>(p), n) : std::span<T>();
  }

  void reset();

  std::size_t used_bytes() const { return used_total_; }
  std::size_t capacity_bytes() const;
  /// Heap allocations made since construction (tests count them across steps).
  uint64_t heap_allocations() const { return heap_allocations_; }

 private:
  struct Block {
    std::byte* data;
    std::size_t size;
  };
  bool grow(std::size_t at_least);

  std::vector<Block> blocks_;
  std::size_t offset_ = 0;      // in the last block
  std::size_t used_total_ = 0;  // bytes handed out since reset, padding included
  uint64_t heap_allocations_ = 0;
};

}  // namespace gyro::detail
