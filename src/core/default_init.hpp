// A vector whose resize() leaves trivially constructible elements unwritten.
//
// std::vector's resize() value-initializes, which writes (and so first-touches) every new
// page on the calling thread. A builder that writes every element afterwards in a parallel
// loop wants those pages first touched there instead: in a fresh 35 MB BVH the page faults
// were most of the build's serial emission. Only resize() without a value changes; every
// other construction is std::allocator's.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gyro::detail {

template <class T> struct DefaultInitAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U> struct rebind {
    using other = DefaultInitAllocator<U>;
  };
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
