// gyro's trigonometry against long double: the maximum error in ULP per function and
// domain (printed, and bounded by the figures stated in include/gyro/math_trig.hpp), and
// bit identity of every SIMD level with the scalar path.
#include "gyro/math_trig.hpp"
#include "gyro/runtime.hpp"
#include "core/state_hash.hpp"
#include "math/trig_batch.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <type_traits>
#include <vector>

namespace gyro {
namespace {

using testing::SplitMix64;

double ulp_error(float got, long double ref) {
  if (std::isnan(ref)) return std::isnan(got) ? 0.0 : INFINITY;
  if (std::isnan(got)) return INFINITY;
  const float rf = static_cast<float>(ref);
  const double ulp = std::fabs(rf) >= FLT_MIN ? std::ldexp(1.0, std::ilogb(rf) - 23) : std::ldexp(1.0, -149);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - ref) / ulp);
}

struct Domain {
  const char* name;
  std::vector<float> x, y;  // y only for atan2
};

constexpr int kSamples = 1 << 21;

Domain uniform(const char* name, double lo, double hi, uint64_t seed) {
  Domain d{name, {}, {}};
  SplitMix64 rng(seed);
  for (int i = 0; i < kSamples / 2; ++i) d.x.push_back(static_cast<float>(lo + (hi - lo) * rng.u()));
  for (int i = 0; i < kSamples / 2; ++i) d.x.push_back(static_cast<float>(lo + (hi - lo) * (i + 0.5) / (kSamples / 2)));
  return d;
}

float log_uniform(SplitMix64& rng, double lo_exp, double hi_exp) {
  const double e = lo_exp + (hi_exp - lo_exp) * rng.u();
  return static_cast<float>((rng.u() < 0.5 ? -1.0 : 1.0) * std::pow(10.0, e));
}

struct Row {
  const char* fn;
  const char* domain;
  double max_ulp;
  float worst_x;
};

template <class F, class R> Row measure(const char* fn, const Domain& d, F&& f, R&& ref) {
  Row row{fn, d.name, 0.0, 0.0f};
  for (std::size_t i = 0; i < d.x.size(); ++i) {
    double e;
    if constexpr (std::is_invocable_v<F, float>)
      e = ulp_error(f(d.x[i]), ref(d.x[i]));
    else
      e = ulp_error(f(d.y[i], d.x[i]), ref(d.y[i], d.x[i]));
    if (e > row.max_ulp) row.max_ulp = e, row.worst_x = d.x[i];
  }
  std::printf("  %-6s %-24s max %.3f ulp (at x = %.9g)\n", row.fn, row.domain, row.max_ulp, double(row.worst_x));
  return row;
}

// Bounds stated in include/gyro/math_trig.hpp (measured here, rounded up to a half ulp).
TEST(Trig, SinCosTanErrorAgainstLongDouble) {
  struct Case {
    Domain d;
    double sincos_bound, tan_bound;
  };
  for (const Case& c : {Case{uniform("|x| <= pi", -M_PI, M_PI, 11), 1.5, 2.5},
                        Case{uniform("|x| <= 100", -100, 100, 12), 2.5, 3.5},
                        Case{uniform("|x| <= 4096", -4096, 4096, 13), 2.5, 3.5}}) {
    EXPECT_LE(measure("sin", c.d, [](float x) { return gyro::sin(x); }, [](float x) { return sinl(x); }).max_ulp,
              c.sincos_bound);
    EXPECT_LE(measure("cos", c.d, [](float x) { return gyro::cos(x); }, [](float x) { return cosl(x); }).max_ulp,
              c.sincos_bound);
    EXPECT_LE(measure("tan", c.d, [](float x) { return gyro::tan(x); }, [](float x) { return tanl(x); }).max_ulp,
              c.tan_bound);
  }
}

TEST(Trig, InverseFunctionsErrorAgainstLongDouble) {
  const Domain unit = uniform("[-1, 1]", -1.0, 1.0, 21);
  EXPECT_LE(measure("asin", unit, [](float x) { return gyro::asin(x); }, [](float x) { return asinl(x); }).max_ulp, 2.0);
  EXPECT_LE(measure("acos", unit, [](float x) { return gyro::acos(x); }, [](float x) { return acosl(x); }).max_ulp, 1.5);
  Domain wide{"|x| in 1e-30..1e30", {}, {}};
  SplitMix64 rng(22);
  for (int i = 0; i < kSamples; ++i) wide.x.push_back(log_uniform(rng, -30, 30));
  const Domain mid = uniform("[-10, 10]", -10, 10, 23);
  for (const Domain* d : std::initializer_list<const Domain*>{&wide, &mid})
    EXPECT_LE(measure("atan", *d, [](float x) { return gyro::atan(x); }, [](float x) { return atanl(x); }).max_ulp, 2.0);
  Domain pairs{"y, x in +-1e-20..1e20", {}, {}};
  for (int i = 0; i < kSamples; ++i) pairs.x.push_back(log_uniform(rng, -20, 20)), pairs.y.push_back(log_uniform(rng, -20, 20));
  Domain box{"y, x in [-1, 1]^2", {}, {}};
  for (int i = 0; i < kSamples; ++i) box.x.push_back(float(rng.u() * 2 - 1)), box.y.push_back(float(rng.u() * 2 - 1));
  for (const Domain* d : std::initializer_list<const Domain*>{&pairs, &box})
    EXPECT_LE(measure("atan2", *d, [](float y, float x) { return gyro::atan2(y, x); },
                      [](float y, float x) { return atan2l(y, x); }).max_ulp, 2.5);
}

TEST(Trig, SpecialValuesFollowC) {
  const float inf = INFINITY, pi = 3.14159265f;
  EXPECT_TRUE(std::isnan(gyro::sin(inf)));
  EXPECT_TRUE(std::isnan(gyro::cos(-inf)));
  EXPECT_TRUE(std::isnan(gyro::sin(NAN)));
  EXPECT_TRUE(std::isnan(gyro::asin(1.0001f)));
  EXPECT_TRUE(std::isnan(gyro::acos(-1.0001f)));
  EXPECT_EQ(std::bit_cast<uint32_t>(gyro::sin(-0.0f)), std::bit_cast<uint32_t>(-0.0f));
  EXPECT_EQ(gyro::cos(0.0f), 1.0f);
  EXPECT_EQ(gyro::asin(1.0f), 1.57079637f);
  EXPECT_EQ(gyro::acos(-1.0f), pi);
  EXPECT_EQ(gyro::acos(1.0f), 0.0f);
  EXPECT_EQ(gyro::atan(inf), 1.57079637f);
  EXPECT_EQ(gyro::atan(-inf), -1.57079637f);
  EXPECT_EQ(std::bit_cast<uint32_t>(gyro::atan2(0.0f, 0.0f)), 0u);
  EXPECT_EQ(std::bit_cast<uint32_t>(gyro::atan2(-0.0f, 0.0f)), std::bit_cast<uint32_t>(-0.0f));
  EXPECT_EQ(gyro::atan2(0.0f, -0.0f), pi);
  EXPECT_EQ(gyro::atan2(-0.0f, -0.0f), -pi);
  EXPECT_EQ(gyro::atan2(inf, inf), 0.785398185f);
  EXPECT_EQ(gyro::atan2(-inf, -inf), -2.35619449f);
  EXPECT_EQ(gyro::atan2(1.0f, -inf), pi);
  EXPECT_EQ(gyro::atan2(-1.0f, inf), -0.0f);
  EXPECT_EQ(gyro::atan2(inf, 5.0f), 1.57079637f);
  EXPECT_EQ(gyro::atan2(1.0f, 0.0f), 1.57079637f);
  EXPECT_TRUE(std::isnan(gyro::atan2(NAN, 1.0f)));
  EXPECT_TRUE(std::isnan(gyro::atan2(1.0f, NAN)));
  float s, c;
  gyro::sincos(0.5f, &s, &c);
  EXPECT_EQ(s, gyro::sin(0.5f));
  EXPECT_EQ(c, gyro::cos(0.5f));
}

// Every SIMD level gives the scalar path's bits, argument by argument.
TEST(Trig, EverySimdLevelMatchesScalarBitForBit) {
  std::vector<float> x, y;
  SplitMix64 rng(31);
  for (int i = 0; i < 1 << 20; ++i) {
    x.push_back(i % 3 == 0 ? log_uniform(rng, -38, 38) : float((rng.u() - 0.5) * 20000));
    y.push_back(i % 5 == 0 ? log_uniform(rng, -38, 38) : float((rng.u() - 0.5) * 4));
  }
  for (float s : {0.0f, -0.0f, INFINITY, -INFINITY, NAN, 1.0f, -1.0f, 1e-45f, FLT_MAX}) x.push_back(s), y.push_back(-s);
  for (uint32_t op = 0; op <= uint32_t(TrigOp::atan2); ++op) {
    std::vector<float> ref(x.size()), out(x.size());
    const TrigBatchArgs scalar_args{TrigOp(op), x.data(), y.data(), ref.data()};
    detail::trig_batch_for(SimdLevel::scalar)(scalar_args, 0, x.size());
    for (uint32_t v = 2; v <= 5; ++v) {
      const SimdLevel level = SimdLevel(v);
      if (!simd_level_available(level)) continue;
      const TrigBatchArgs args{TrigOp(op), x.data(), y.data(), out.data()};
      // An odd start exercises the scalar tail and unaligned loads.
      detail::trig_batch_for(level)(args, 0, 3);
      detail::trig_batch_for(level)(args, 3, x.size());
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < x.size(); ++i)
        mismatches += detail::canonical_float_bits(out[i]) != detail::canonical_float_bits(ref[i]);
      EXPECT_EQ(mismatches, 0u) << "op " << op << " at " << simd_level_name(level);
    }
    // And the public scalar functions are the same instantiation.
    if (TrigOp(op) == TrigOp::sin) {
      EXPECT_EQ(std::bit_cast<uint32_t>(ref[12345]), std::bit_cast<uint32_t>(gyro::sin(x[12345])));
    }
  }
}

}  // namespace
}  // namespace gyro
