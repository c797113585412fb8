// Column<T>: one structure-of-arrays column.
//
// 64-byte aligned storage whose capacity is a multiple of kColumnPad elements; slots past
// size() up to padded_size() always hold the column's pad value, chosen by the owner to be
// harmless to compute on (0 for positions, 1 for a radius, ...), so a kernel may run full
// SIMD batches over padded_size() without a tail. Growth is geometric; a column that has
// reached its working size never allocates again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

namespace gyro::detail {

inline constexpr std::size_t kColumnPad = 16;
inline constexpr std::size_t kColumnAlign = 64;

inline constexpr std::size_t padded_count(std::size_t n) { return (n + kColumnPad - 1) / kColumnPad * kColumnPad; }

template <class T> class Column {
  static_assert(std::is_trivially_copyable_v<T>, "columns hold plain data");

 public:
  explicit Column(T pad = T{}) : pad_(pad) {}
  Column(const Column& o) : pad_(o.pad_) { assign(o); }
  Column& operator=(const Column& o) {
    if (this != &o) {
      pad_ = o.pad_;
      assign(o);
    }
    return *this;
  }
  Column(Column&& o) noexcept { swap(o); }
  Column& operator=(Column&& o) noexcept {
    swap(o);
    return *this;
  }
  ~Column() { release(); }

  std::size_t size() const { return size_; }
  std::size_t padded_size() const { return padded_count(size_); }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T pad_value() const { return pad_; }

  /// Ensures room for n elements (rounded up to the pad); false if memory ran out, in
  /// which case the column is unchanged.
  bool reserve(std::size_t n) {
    const std::size_t want = padded_count(n);
    if (want <= capacity_) return true;
    std::size_t cap = capacity_ ? capacity_ : kColumnPad;
    while (cap < want) cap *= 2;
    T* fresh = static_cast<T*>(::operator new(cap * sizeof(T), std::align_val_t{kColumnAlign}, std::nothrow));
    if (fresh == nullptr) return false;
    if (size_) std::memcpy(fresh, data_, size_ * sizeof(T));
    for (std::size_t i = size_; i < cap; ++i) fresh[i] = pad_;
    free_storage();
    data_ = fresh;
    capacity_ = cap;
    return true;
  }

  bool resize(std::size_t n, T value) {
    if (!reserve(n)) return false;
    for (std::size_t i = size_; i < n; ++i) data_[i] = value;
    for (std::size_t i = n; i < size_; ++i) data_[i] = pad_;
    size_ = n;
    return true;
  }

  bool push_back(T value) {
    if (!reserve(size_ + 1)) return false;
    data_[size_++] = value;
    return true;
  }

  /// Moves the last element into slot i and shrinks by one (the deterministic removal
  /// the id pool mirrors).
  void swap_remove(std::size_t i) {
    data_[i] = data_[size_ - 1];
    data_[--size_] = pad_;
  }

  void clear() {
    for (std::size_t i = 0; i < size_; ++i) data_[i] = pad_;
    size_ = 0;
  }

 private:
  void assign(const Column& o) {
    clear();
    if (reserve(o.size_)) {
      if (o.size_) std::memcpy(data_, o.data_, o.size_ * sizeof(T));
      size_ = o.size_;
    }
  }
  void free_storage() {
    if (data_) ::operator delete(data_, std::align_val_t{kColumnAlign});
    data_ = nullptr;
  }
  void release() {
    free_storage();
    capacity_ = size_ = 0;
  }
  void swap(Column& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    std::swap(pad_, o.pad_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
  T pad_{};
};

}  // namespace gyro::detail
