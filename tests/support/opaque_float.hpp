// Binary64 test inputs rounded to float behind an optimiser barrier.
//
// g++ 12.2 at -O3 was seen to fold double(float(x)) back to x when a case is generated and
// measured in one inlined block (the rounding to float vanished after SLP vectorisation),
// so the binary64 reference measured another input than the float API received. opaque()
// makes the compiler forget what it knows about a value, so every later read loads the
// float bits the API receives.
#pragma once

namespace gyro::testing {

template <class T> inline void opaque_one(T& value) { asm volatile("" : : "r"(&value) : "memory"); }
template <class... T> inline void opaque(T&... values) { (opaque_one(values), ...); }

/// A binary64 value rounded to float, opaque to the optimiser.
inline float f32(double v) {
  float f = float(v);
  opaque(f);
  return f;
}

}  // namespace gyro::testing
