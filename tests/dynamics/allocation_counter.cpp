// Replaces the global allocation functions to count heap allocations (the world's "no
// allocation per step after warm-up" test reads the count before and after). In its own
// file: with the replacements visible where a new/delete pair is inlined, g++ -O1 flags
// free() on operator new's pointer as a mismatch, though it is what these functions pair.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define GYRO_COUNT_ALLOCATIONS 0  // AddressSanitizer owns the allocator (it flags a replacement)
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GYRO_COUNT_ALLOCATIONS 0
#endif
#endif
#if !defined(GYRO_COUNT_ALLOCATIONS)
#define GYRO_COUNT_ALLOCATIONS 1
#endif

bool gyro_test_counts_allocations() { return GYRO_COUNT_ALLOCATIONS != 0; }

#if GYRO_COUNT_ALLOCATIONS
namespace {
std::atomic<uint64_t> g_allocations{0};

void* counted(std::size_t n, std::size_t align) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (align <= alignof(std::max_align_t)) return std::malloc(n ? n : 1);
  return std::aligned_alloc(align, (n + align - 1) / align * align);
}
}  // namespace

uint64_t gyro_test_allocation_count() { return g_allocations.load(std::memory_order_relaxed); }

void* operator new(std::size_t n) {
  if (void* p = counted(n, 0)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t a) {
  if (void* p = counted(n, static_cast<std::size_t>(a))) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted(n, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
#else
uint64_t gyro_test_allocation_count() { return 0; }
#endif
