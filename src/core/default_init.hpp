// A vector whose resize() leaves trivially constructible elements unwritten.
//
// std::vector's resize() value-initializes, which writes (and so first-touches) every new
// page on the calling thread. A builder that writes every element afterwards in a parallel
// loop wants those pages first touched there instead: in a fresh 35 MB BVH the page faults
// were most of the build's serial emission. Only resize() without a value changes; every
// other construction is std::allocator's. Large blocks come from allocate_large().
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gyro::detail {

// Blocks from this size up are 2 MiB aligned and, on Linux, offered as transparent huge
// pages: a fresh 35 MB BVH then takes 18 page faults instead of 9,000 (first builds in a
// process, and every build in a virtual machine whose host faults pages in lazily, paid
// those faults; where the system leaves huge pages off, madvise is a no-op).
inline constexpr std::size_t kHugeBlock = std::size_t(2) << 20;
void* allocate_large(std::size_t bytes);
void deallocate_large(void* p, std::size_t bytes) noexcept;

template <class T> struct DefaultInitAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U> struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) < kHugeBlock) return std::allocator<T>::allocate(n);
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugeBlock) std::allocator<T>::deallocate(p, n);
    else deallocate_large(p, n * sizeof(T));
  }
  // Default-initialization: no write for a trivially default-constructible U.
  template <class U> void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... A> void construct(U* p, A&&... a) {
    std::construct_at(p, std::forward<A>(a)...);
  }
};

/// Callers of resize() must write every element before reading it.
template <class T> using DefaultInitVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace gyro::detail
