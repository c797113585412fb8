#include "core/arena.hpp"

#include <cstdint>
#include <new>

namespace gyro::detail {
namespace {
constexpr std::size_t kMinBlock = 64 * 1024;
constexpr std::size_t kBlockAlign = 64;

std::byte* new_block(std::size_t size) {
  return static_cast<std::byte*>(::operator new(size, std::align_val_t{kBlockAlign}, std::nothrow));
}
void delete_block(std::byte* p) { ::operator delete(p, std::align_val_t{kBlockAlign}); }
}  // namespace

Arena::Arena(std::size_t initial_bytes) {
  blocks_.reserve(16);
  if (initial_bytes) grow(initial_bytes);
}

Arena::~Arena() {
  for (Block& b : blocks_) delete_block(b.data);
}

std::size_t Arena::capacity_bytes() const {
  std::size_t total = 0;
  for (const Block& b : blocks_) total += b.size;
  return total;
}

bool Arena::grow(std::size_t at_least) {
  std::size_t size = blocks_.empty() ? kMinBlock : blocks_.back().size * 2;
  while (size < at_least) size *= 2;
  std::byte* p = new_block(size);
  if (p == nullptr) return false;
  ++heap_allocations_;
  blocks_.push_back({p, size});
  offset_ = 0;
  return true;
}

void* Arena::allocate(std::size_t bytes, std::size_t align) {
  if (align == 0 || (align & (align - 1)) != 0 || align > 4096) return nullptr;
  if (bytes == 0) bytes = 1;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!blocks_.empty()) {
      Block& b = blocks_.back();
      // Align the address, not the offset: blocks are only 64-byte aligned.
      const uintptr_t base = reinterpret_cast<uintptr_t>(b.data);
      const std::size_t start = static_cast<std::size_t>(((base + offset_ + align - 1) & ~(uintptr_t{align} - 1)) - base);
      if (start <= b.size && bytes <= b.size - start) {
        used_total_ += (start - offset_) + bytes;
        offset_ = start + bytes;
        return b.data + start;
      }
    }
    if (!grow(bytes + align)) return nullptr;
  }
  return nullptr;
}

void Arena::reset() {
  if (blocks_.size() > 1) {
    // This step needed several blocks: keep one that holds them all.
    const std::size_t total = capacity_bytes();
    for (Block& b : blocks_) delete_block(b.data);
    blocks_.clear();
    grow(total);
  }
  offset_ = 0;
  used_total_ = 0;
}

}  // namespace gyro::detail
