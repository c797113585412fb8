#include "core/default_init.hpp"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gyro::detail {

void* allocate_large(std::size_t bytes) {
  void* p = ::operator new(bytes, std::align_val_t(kHugeBlock));
#if defined(MADV_HUGEPAGE)
  // Advice only: a refusal leaves ordinary pages, which are correct, just slower to fault in.
  (void)madvise(p, bytes, MADV_HUGEPAGE);
#endif
  return p;
}

// The unsized form: Clang before 17 declares no sized deallocation unless asked to.
void deallocate_large(void* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kHugeBlock)); }

}  // namespace gyro::detail
