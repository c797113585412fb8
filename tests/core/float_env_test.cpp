#include "core/float_env.hpp"
#include "gyro/batch_raycast.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

namespace gyro {
namespace {

#if defined(__x86_64__)
// A host that turned on flush-to-zero and denormals-are-zero (as code built with
// -ffast-math does) must get the same bits from gyro as a host that did not.
struct Results {
  float t;
  int32_t prim;
};

Results compute() {
  // r^2 and c = |o - c|^2 - r^2 are subnormal here: flushed, the hit would move to t = 0.
  const float ox[] = {0}, oy[] = {0}, oz[] = {0}, dx[] = {1}, dy[] = {0}, dz[] = {0};
  const float cx[] = {3e-20f}, cy[] = {0}, cz[] = {0}, r[] = {1e-20f};
  Results out{};
  const Status s = raycast_spheres_closest({ox, oy, oz, dx, dy, dz, nullptr, nullptr}, 1, {cx, cy, cz, r}, 1,
                                           {&out.t, &out.prim, nullptr, nullptr, nullptr});
  EXPECT_EQ(s, Status::ok);
  return out;
}

TEST(FloatEnv, HostFtzDazDoesNotChangeResults) {
  const unsigned saved = _mm_getcsr();
  const unsigned ftz_daz = saved | (1u << 15) | (1u << 6);
  const Results clean = compute();
  _mm_setcsr(ftz_daz);
  const Results flushed = compute();
  const unsigned after = _mm_getcsr();
  _mm_setcsr(saved);
  EXPECT_EQ(after, ftz_daz) << "the host's MXCSR must be restored";
  EXPECT_EQ(clean.prim, 0);
  EXPECT_NEAR(clean.t, 2e-20f, 2e-26f);  // c is subnormal here: fewer bits
  EXPECT_EQ(std::bit_cast<uint32_t>(clean.t), std::bit_cast<uint32_t>(flushed.t));
  EXPECT_EQ(clean.prim, flushed.prim);
}

TEST(FloatEnv, WithoutTheGuardTheHostModeWouldLeak) {
  // Shows the test above can fail: the same subnormal arithmetic, unguarded, is flushed.
  const unsigned saved = _mm_getcsr();
  volatile float a = 1e-20f;
  _mm_setcsr(saved | (1u << 15) | (1u << 6));
  const float sq = a * a;
  _mm_setcsr(saved);
  EXPECT_EQ(sq, 0.0f);
  EXPECT_NE(a * a, 0.0f);
}
#endif

}  // namespace
}  // namespace gyro
