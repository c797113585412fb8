// Deterministic trigonometry: the same bits on every CPU, SIMD level and compiler.
//
// The C library's sine, tangent and friends differ between libm versions and architectures
// (glibc's tan and atan2 differ between x86-64 and aarch64), so gyro never calls them on
// state. These are gyro's own polynomials (src/math/trig_lanes.hpp), the same template the
// SIMD kernels run.
//
// Measured maximum error against long double (tests/math/trig_test.cpp: 2^21 arguments
// per domain, half random, half on a uniform grid; the test fails above these bounds):
//
//   function  domain                  max error (ulp)   test bound
//   sin       |x| <= pi               1.35              1.5
//   cos       |x| <= pi               1.48              1.5
//   tan       |x| <= pi               2.39              2.5
//   sin, cos  |x| <= 4096             2.47              2.5
//   tan       |x| <= 4096             3.36              3.5
//   asin      [-1, 1]                 1.90              2.0
//   acos      [-1, 1]                 1.25              1.5
//   atan      |x| in [1e-30, 1e30]    1.93              2.0
//   atan2     |x|,|y| in [1e-20,1e20] 2.35              2.5
//
// Beyond |x| = 4096 the pi/2 reduction loses bits: sin/cos/tan stay deterministic and
// bounded but their error grows (about 1e-4 absolute near |x| = 1e5). sin and cos of
// +-inf and NaN are NaN; asin/acos outside [-1, 1] are NaN; atan2 follows C's special
// cases (atan2(+-0, -0) = +-pi, atan2(+-inf, +-inf) = +-pi/4 or +-3pi/4, ...).
#pragma once

namespace gyro {

float sin(float x);
float cos(float x);
/// sin and cos together, for the price of one reduction.
void sincos(float x, float* s, float* c);
float tan(float x);
float asin(float x);
float acos(float x);
float atan(float x);
float atan2(float y, float x);

}  // namespace gyro
