// ByteWriter and ByteReader: the snapshot format's primitives.
//
// Values are written little-endian at fixed widths (floats by their bits, so a restored
// value is the same bits), arrays with a 64-bit count in front. The two classes have the
// same member names, so one template function can describe a structure once and serve
// both directions: `io.u32(x)` writes x, or reads into it. A writer with no buffer only
// counts bytes (the size query). A reader never reads past its end: the first short read,
// oversized count or out-of-range value marks it failed, and every later read yields zeros,
// so a truncated or corrupted buffer is reported once at the end, never followed.
#pragma once

#include "core/columns.hpp"
#include "gyro/math_mat.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/math_vec.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <type_traits>
#include <vector>

namespace gyro::detail {

static_assert(std::endian::native == std::endian::little,
              "the snapshot format is little-endian; a big-endian port must byte-swap in ByteWriter/ByteReader");

/// A fast, stable 64-bit checksum of bytes (four independent multiply-rotate lanes over
/// 8-byte words, then the tail): detects corruption and truncation, not tampering.
inline uint64_t checksum64(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t lane[4] = {0x9E3779B97F4A7C15ull, 0xC2B2AE3D27D4EB4Full, 0x165667B19E3779F9ull, 0x27D4EB2F165667C5ull};
  auto mix = [](uint64_t h, uint64_t w) {
    h ^= w * 0x9E3779B97F4A7C15ull;
    return ((h << 31) | (h >> 33)) * 0xBF58476D1CE4E5B9ull;
  };
  std::size_t i = 0;
  for (; i + 32 <= bytes; i += 32)
    for (int k = 0; k < 4; ++k) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * k, 8);
      lane[k] = mix(lane[k], w);
    }
  uint64_t h = mix(mix(mix(mix(bytes, lane[0]), lane[1]), lane[2]), lane[3]);
  for (; i < bytes; ++i) h = mix(h, p[i]);
  h ^= h >> 29;
  h *= 0x94D049BB133111EBull;
  return h ^ (h >> 32);
}

class ByteWriter {
 public:
  static constexpr bool reading = false;
  /// out == nullptr: count only.
  explicit ByteWriter(uint8_t* out = nullptr) : out_(out) {}

  std::size_t size() const { return pos_; }
  bool ok() const { return true; }
  /// Unbounded: counts written are bounded only when read back.
  std::size_t remaining() const { return SIZE_MAX; }

  void bytes(const void* p, std::size_t n) {
    if (out_ && n) std::memcpy(out_ + pos_, p, n);
    pos_ += n;
  }
  void u8(const uint8_t& v) { bytes(&v, 1); }
  void u32(const uint32_t& v) { bytes(&v, 4); }
  void u64(const uint64_t& v) { bytes(&v, 8); }
  void f32(const float& v) { bytes(&v, 4); }
  void boolean(const bool& b) { u8(b ? 1 : 0); }
  template <class E> void enumeration(const E& e, uint32_t /*max*/) { u32(static_cast<uint32_t>(e)); }
  void v3(const vec3& v) { f32(v.x), f32(v.y), f32(v.z); }
  void q4(const quat& q) { f32(q.x), f32(q.y), f32(q.z), f32(q.w); }
  void m3(const mat3& m) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f32(m.m[r][c]);
  }
  /// A count written as 64 bits (read back with a bound).
  void count(const std::size_t& n, std::size_t /*max*/) { u64(n); }

  template <class T> void array(const std::vector<T>& v) {
    static_assert(std::is_arithmetic_v<T>);
    u64(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  void vec3s(const std::vector<vec3>& v) {
    u64(v.size());
    for (const vec3& x : v) v3(x);
  }
  /// The first n entries of a column (n is known to the reader from elsewhere, and checked).
  template <class T> void column(const Column<T>& c, std::size_t n) {
    u64(n);
    bytes(c.data(), n * sizeof(T));
  }

 private:
  uint8_t* out_;
  std::size_t pos_ = 0;
};

class ByteReader {
 public:
  static constexpr bool reading = true;
  ByteReader(const uint8_t* data, std::size_t size) : p_(data), n_(size) {}

  bool ok() const { return ok_; }
  void fail() { ok_ = false; }
  /// Failed unless c holds.
  void require(bool c) { ok_ = ok_ && c; }
  std::size_t remaining() const { return ok_ ? n_ - pos_ : 0; }
  bool at_end() const { return ok_ && pos_ == n_; }

  void bytes(void* dst, std::size_t n) {
    if (!ok_ || n > n_ - pos_) {
      ok_ = false;
      if (n) std::memset(dst, 0, n);
      return;
    }
    if (n) std::memcpy(dst, p_ + pos_, n);
    pos_ += n;
  }
  void u8(uint8_t& v) { bytes(&v, 1); }
  void u32(uint32_t& v) { bytes(&v, 4); }
  void u64(uint64_t& v) { bytes(&v, 8); }
  void f32(float& v) { bytes(&v, 4); }
  void boolean(bool& b) {
    uint8_t v = 0;
    u8(v);
    require(v <= 1);
    b = v == 1;
  }
  template <class E> void enumeration(E& e, uint32_t max) {
    uint32_t v = 0;
    u32(v);
    require(v <= max);
    e = static_cast<E>(ok_ ? v : 0u);
  }
  void v3(vec3& v) { f32(v.x), f32(v.y), f32(v.z); }
  void q4(quat& q) { f32(q.x), f32(q.y), f32(q.z), f32(q.w); }
  void m3(mat3& m) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f32(m.m[r][c]);
  }
  void count(std::size_t& n, std::size_t max) {
    uint64_t v = 0;
    u64(v);
    require(v <= max);
    n = ok_ ? static_cast<std::size_t>(v) : 0;
  }

  /// Reads a counted array; a count the remaining bytes cannot hold fails before allocating.
  template <class T> void array(std::vector<T>& v) {
    static_assert(std::is_arithmetic_v<T>);
    std::size_t n = 0;
    count(n, remaining() / sizeof(T));
    if (!ok_) return;
    if (!resize(v, n)) return;
    bytes(v.data(), n * sizeof(T));
  }
  void vec3s(std::vector<vec3>& v) {
    std::size_t n = 0;
    count(n, remaining() / 12);
    if (!ok_ || !resize(v, n)) return;
    for (vec3& x : v) v3(x);
  }
  template <class T> void column(Column<T>& c, std::size_t n) {
    std::size_t m = 0;
    count(m, remaining() / sizeof(T));
    require(m == n);
    if (!ok_) return;
    if (!c.resize(0, c.pad_value()) || !c.resize(n, c.pad_value())) {
      out_of_memory_ = true;
      ok_ = false;
      return;
    }
    bytes(c.data(), n * sizeof(T));
  }

  /// True when a failure was an allocation, not the data.
  bool out_of_memory() const { return out_of_memory_; }

 private:
  template <class V> bool resize(V& v, std::size_t n) {
    try {
      v.resize(n);
      return true;
    } catch (const std::bad_alloc&) {
      out_of_memory_ = true;
      ok_ = false;
      return false;
    }
  }

  const uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
  bool ok_ = true;
  bool out_of_memory_ = false;
};

}  // namespace gyro::detail
