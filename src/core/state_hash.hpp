// StateHasher: the 64-bit witness of the determinism contract.
//
// Hashes state words in the order they are fed. Floats are hashed by their bits, so a
// different rounding anywhere shows; every NaN is first mapped to one canonical pattern,
// because NaN payloads and signs differ between x86 and NEON and carry no state. +0 and -0
// stay distinct. The mixing (a multiply-rotate per 64-bit word, a splitmix64 finaliser)
// is not cryptographic, only stable: its values are pinned in tests and must not change.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

namespace gyro::detail {

inline uint32_t canonical_float_bits(float f) {
  const uint32_t b = std::bit_cast<uint32_t>(f);
  return (b & 0x7fffffffu) > 0x7f800000u ? 0x7fc00000u : b;
}

class StateHasher {
 public:
  explicit StateHasher(uint64_t seed = 0x6779726f2d763031ull /* "gyro-v01" */) : h_(seed) {}

  void add_u64(uint64_t w) {
    h_ ^= w * 0x9E3779B97F4A7C15ull;
    h_ = ((h_ << 29) | (h_ >> 35)) * 0xBF58476D1CE4E5B9ull;
    ++words_;
  }
  void add_u32(uint32_t w) { add_u64(w); }
  void add_float(float f) { add_u64(canonical_float_bits(f)); }
  void add_floats(std::span<const float> v) {
    add_u64(v.size());
    std::size_t i = 0;
    for (; i + 2 <= v.size(); i += 2)
      add_u64((uint64_t{canonical_float_bits(v[i + 1])} << 32) | canonical_float_bits(v[i]));
    if (i < v.size()) add_u64(canonical_float_bits(v[i]));
  }
  void add_u32s(std::span<const uint32_t> v) {
    add_u64(v.size());
    for (uint32_t w : v) add_u64(w);
  }

  uint64_t digest() const {
    uint64_t z = h_ ^ words_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

 private:
  uint64_t h_;
  uint64_t words_ = 0;
};

/// FNV-1a 64 over bytes: the hash BENCHMARKS.md uses to check generated workloads.
inline uint64_t fnv1a64(const void* data, std::size_t bytes, uint64_t h = 0xcbf29ce484222325ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace gyro::detail
