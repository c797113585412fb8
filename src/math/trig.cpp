// gyro's scalar trigonometry: the float instantiation of the lane templates.
#include "gyro/math_trig.hpp"

#include "math/trig_lanes.hpp"

namespace gyro {
namespace lanes = GYRO_ARCH_NS;

float sin(float x) { return lanes::sin(x); }
float cos(float x) { return lanes::cos(x); }
void sincos(float x, float* s, float* c) {
  float ss, cc;
  lanes::sincos(x, ss, cc);
  if (s) *s = ss;
  if (c) *c = cc;
}
float tan(float x) { return lanes::tan(x); }
float asin(float x) { return lanes::asin(x); }
float acos(float x) { return lanes::acos(x); }
float atan(float x) { return lanes::atan(x); }
float atan2(float y, float x) { return lanes::atan2(y, x); }

}  // namespace gyro
