// Every lane operation at every SIMD level gives the scalar lane's bits, on all pairs of
// special values: the primitive promise the whole determinism contract rests on.
#include "core/state_hash.hpp"
#include "gyro/runtime.hpp"
#include "lanes_probe.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <vector>

namespace gyro {
namespace {

TEST(Lanes, EveryOperationMatchesScalarOnSpecialValues) {
  const float specials[] = {0.0f,     -0.0f,    1.0f,      -1.0f,   0.5f,    3.0f,       -7.25f,   FLT_MIN,
                            -FLT_MIN, 1e-45f,   -1e-45f,   1e-40f,  FLT_MAX, -FLT_MAX,   INFINITY, -INFINITY,
                            NAN,      -NAN,     1e30f,     1e-30f,  2.0f,    0x1p-126f};
  std::vector<float> a, b;
  for (float x : specials)
    for (float y : specials) a.push_back(x), b.push_back(y);
  const std::size_t n = a.size();
  auto run = [&](SimdLevel level, int fixed) {
    std::vector<std::vector<float>> out(kLaneProbeOps, std::vector<float>(n));
    LaneProbeArgs args{a.data(), b.data(), {}};
    for (int k = 0; k < kLaneProbeOps; ++k) args.out[k] = out[k].data();
    (fixed == 4 ? detail::quad_probe_for(level) : fixed == 8 ? detail::oct_probe_for(level) : detail::lanes_probe_for(level))(args, 0, n);
    return out;
  };
  const auto ref = run(SimdLevel::scalar, 0);
  int levels = 0;
  // Every level's wide lane, and every level's Quad and Oct (the scalar level's included).
  for (uint32_t v = 1; v <= 5; ++v) {
    const SimdLevel level = SimdLevel(v);
    if (!simd_level_available(level)) continue;
    levels += v > 1;
    for (int fixed : {0, 4, 8}) {
      const auto got = run(level, fixed);
      for (int k = 0; k < kLaneProbeOps; ++k)
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(detail::canonical_float_bits(got[k][i]), detail::canonical_float_bits(ref[k][i]))
              << "op " << k << " at " << simd_level_name(level) << (fixed ? (fixed == 4 ? " (Quad)" : " (Oct)") : "") << " a=" << a[i]
              << " b=" << b[i];
    }
  }
  EXPECT_GE(levels, 1) << "no SIMD level available to compare";
}

TEST(Lanes, ScalarSemanticsAreCxxSemantics) {
  // The scalar lane is the reference; pin the rules the header promises.
  const float nan = NAN;
  std::vector<float> a = {nan, 1.0f, -0.0f}, b = {1.0f, nan, 0.0f};
  std::vector<std::vector<float>> out(kLaneProbeOps, std::vector<float>(3));
  LaneProbeArgs args{a.data(), b.data(), {}};
  for (int k = 0; k < kLaneProbeOps; ++k) args.out[k] = out[k].data();
  detail::lanes_probe_for(SimdLevel::scalar)(args, 0, 3);
  EXPECT_EQ(out[8][0], 1.0f);   // min(NaN, 1) = 1: the second operand wins
  EXPECT_TRUE(std::isnan(out[8][1]));  // min(1, NaN) = NaN
  EXPECT_EQ(out[15][0], 1.0f);  // NaN != 1
  EXPECT_EQ(out[14][2], 1.0f);  // -0 == +0
  EXPECT_EQ(std::bit_cast<uint32_t>(out[6][2]), 0u);           // -(-0) = +0
  EXPECT_EQ(std::bit_cast<uint32_t>(out[19][2]), 0u);          // -0 + 0 = +0
}

}  // namespace
}  // namespace gyro
