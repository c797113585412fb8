// Batch overlap kernels: N1 boxes against the binary64 separating-axis reference, bit
// identity across SIMD levels, threads and batch splits, per-element invalid flags, bad input.
#include "gyro/batch_overlap.hpp"
#include "gyro/overlap.hpp"
#include "gyro/runtime.hpp"
#include "gyro/triangle.hpp"
#include "random_shapes.hpp"
#include "reference.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace gyro {
namespace {

using namespace gyro::testing;

class BatchOverlap : public ::testing::Test {
 protected:
  void TearDown() override {
    set_simd_level(SimdLevel::automatic);
    set_thread_count(0);
  }
};

// The first 200,000 N1 pairs. Verdicts may differ from binary64 only for pairs within the
// tolerance band of touching (the parallel-edge slack is 1e-6 * size; boxes are ~1 m).
TEST_F(BatchOverlap, N1VerdictsAndDepthsAgreeWithBinary64) {
  const std::size_t n = 200000;
  const BoxPairs p = n1_pairs(n);
  std::vector<uint32_t> out(n);
  std::vector<float> sep(n);
  ASSERT_EQ(overlap_pairwise(shape_array(p.a.view()), shape_array(p.b.view()), n, out.data()), Status::ok);
  ASSERT_EQ(obb_separation_pairwise(p.a.view(), p.b.view(), n, sep.data()), Status::ok);
  std::size_t hits = 0, outside_band = 0, inside_band = 0, sep_sign_wrong = 0;
  double max_depth_err = 0, max_gap_err = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ref = ref_obb_obb_separation(p.a, i, p.b, i);
    const bool hit = out[i] == kOverlapping;
    ASSERT_TRUE(out[i] == kOverlapping || out[i] == kSeparated);
    hits += hit;
    if (hit != (ref <= 0)) (std::abs(ref) <= 1e-5 ? inside_band : outside_band)++;
    if ((sep[i] <= 0) != (ref <= 0) && std::abs(ref) > 1e-5) ++sep_sign_wrong;
    if (ref <= 0) max_depth_err = std::max(max_depth_err, std::abs(double(sep[i]) - ref));
    else max_gap_err = std::max(max_gap_err, std::abs(double(sep[i]) - ref) / std::max(1.0, ref));
  }
  std::printf("  N1[0..%zu): %zu overlapping; verdicts differing from binary64: %zu within 1e-5 of touching, "
              "%zu outside; max error: depth %.3g (overlapping pairs), gap %.3g relative (separated pairs)\n",
              n, hits, inside_band, outside_band, max_depth_err, max_gap_err);
  EXPECT_EQ(outside_band, 0u);
  EXPECT_EQ(sep_sign_wrong, 0u);
  EXPECT_LT(max_depth_err, 2e-5);
  EXPECT_LT(max_gap_err, 5e-3);  // 1 - R^2 cancels for nearly parallel edges (see obb_obb_lanes.hpp)
}

TEST_F(BatchOverlap, BitIdenticalAcrossLevelsThreadsAndSplits) {
  const std::size_t n = 20011;  // not a multiple of any lane count
  const BoxPairs p = n1_pairs(n);
  const ShapeArray a = shape_array(p.a.view()), b = shape_array(p.b.view());
  std::vector<uint32_t> ref(n), out(n);
  std::vector<float> ref_sep(n), sep(n);
  set_simd_level(SimdLevel::scalar);
  set_thread_count(1);
  ASSERT_EQ(overlap_pairwise(a, b, n, ref.data()), Status::ok);
  ASSERT_EQ(obb_separation_pairwise(p.a.view(), p.b.view(), n, ref_sep.data()), Status::ok);
  for (uint32_t v = 2; v <= 5; ++v) {
    if (!simd_level_available(SimdLevel(v))) continue;
    set_simd_level(SimdLevel(v));
    for (uint32_t t : {1u, 3u, 8u}) {
      set_thread_count(t);
      ASSERT_EQ(overlap_pairwise(a, b, n, out.data()), Status::ok);
      ASSERT_EQ(obb_separation_pairwise(p.a.view(), p.b.view(), n, sep.data()), Status::ok);
      EXPECT_EQ(out, ref) << simd_level_name(SimdLevel(v)) << " x" << t;
      EXPECT_EQ(std::memcmp(sep.data(), ref_sep.data(), n * sizeof(float)), 0) << simd_level_name(SimdLevel(v));
    }
  }
  // One against many equals pairwise with the first box repeated.
  set_simd_level(SimdLevel::automatic);
  BoxPairs rep = p;
  for (auto* col : {&rep.a.cx, &rep.a.cy, &rep.a.cz, &rep.a.hx, &rep.a.hy, &rep.a.hz})
    std::fill(col->begin(), col->end(), (*col)[0]);
  for (auto& col : rep.a.r) std::fill(col.begin(), col.end(), col[0]);
  std::vector<uint32_t> one(n), pair(n);
  ASSERT_EQ(overlap_one_against_many(a, b, n, one.data()), Status::ok);
  ASSERT_EQ(overlap_pairwise(shape_array(rep.a.view()), b, n, pair.data()), Status::ok);
  EXPECT_EQ(one, pair);
  // Swapping the arrays swaps nothing (every test is symmetric).
  std::vector<uint32_t> swapped(n);
  ASSERT_EQ(overlap_pairwise(b, a, n, swapped.data()), Status::ok);
  ASSERT_EQ(overlap_pairwise(a, b, n, out.data()), Status::ok);
  EXPECT_EQ(swapped, out);
}

TEST_F(BatchOverlap, InvalidElementsAreFlaggedOrRejected) {
  const std::size_t n = 100;
  const BoxPairs clean = n1_pairs(n);
  BoxPairs p = clean;
  p.a.cx[3] = NAN;
  p.b.hy[7] = -1.0f;
  p.a.r[4][11] = INFINITY;
  std::vector<uint32_t> ref(n), out(n);
  ASSERT_EQ(overlap_pairwise(shape_array(clean.a.view()), shape_array(clean.b.view()), n, ref.data()), Status::ok);
  // Default: the bad pairs are flagged, the others computed as if nothing happened.
  ASSERT_EQ(overlap_pairwise(shape_array(p.a.view()), shape_array(p.b.view()), n, out.data()), Status::ok);
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 3 || i == 7 || i == 11) EXPECT_EQ(out[i], kInvalidInput) << i;
    else EXPECT_EQ(out[i], ref[i]) << i;
  }
  // One against many with a bad single shape: every pair is invalid.
  ASSERT_EQ(overlap_one_against_many(shape_array(p.a.view()), shape_array(clean.b.view()), 1, out.data()), Status::ok);
  ObbsView bad_one = p.a.view();
  bad_one.cx += 3;  // element 3 (NaN) as the single shape
  ASSERT_EQ(overlap_one_against_many(shape_array(bad_one), shape_array(clean.b.view()), n, out.data()), Status::ok);
  for (uint32_t v : out) EXPECT_EQ(v, kInvalidInput);

  // Strict: the call fails and nothing is written.
  std::vector<uint32_t> poison(n, 0xDEADu);
  out = poison;
  EXPECT_EQ(overlap_pairwise(shape_array(p.a.view()), shape_array(p.b.view()), n, out.data(), kFlagStrict),
            Status::non_finite);
  EXPECT_NE(std::strstr(last_error(), "a.cx[3]"), nullptr) << last_error();
  p.a.cx[3] = 1.0f, p.a.r[4][11] = 0.5f;
  EXPECT_EQ(overlap_pairwise(shape_array(p.a.view()), shape_array(p.b.view()), n, out.data(), kFlagStrict),
            Status::invalid_argument);
  EXPECT_NE(std::strstr(last_error(), "b.ey[7]"), nullptr) << last_error();
  EXPECT_EQ(out, poison);

  // Bad arguments: a status, nothing written.
  ObbsView missing = clean.b.view();
  missing.u1y = nullptr;
  EXPECT_EQ(overlap_pairwise(shape_array(clean.a.view()), shape_array(missing), n, out.data()), Status::null_argument);
  EXPECT_NE(std::strstr(last_error(), "b.u1y"), nullptr) << last_error();
  EXPECT_EQ(overlap_pairwise(shape_array(clean.a.view()), shape_array(clean.b.view()), n, nullptr), Status::null_argument);
  EXPECT_EQ(overlap_pairwise(shape_array(clean.a.view()), shape_array(clean.b.view()), std::size_t(1) << 31, out.data()),
            Status::invalid_count);
  EXPECT_EQ(overlap_pairwise(shape_array(clean.a.view()), shape_array(clean.b.view()), n, out.data(), 0x80u),
            Status::invalid_argument);
  ShapeArray unknown = shape_array(clean.a.view());
  unknown.type = static_cast<ShapeType>(9);
  EXPECT_EQ(overlap_pairwise(unknown, shape_array(clean.b.view()), n, out.data()), Status::invalid_argument);
  EXPECT_EQ(out, poison);
  EXPECT_EQ(overlap_pairwise(ShapeArray{}, ShapeArray{}, 0, nullptr), Status::ok);  // nothing to do
}

// ---- every pair type: the batch verdict equals the scalar overlaps() at every level

bool scalar_overlap(const RandomShapes& a, std::size_t i, const RandomShapes& b, std::size_t j) {
  auto with_b = [&](const auto& x) -> bool {
    switch (b.type) {
      case ShapeType::sphere: return overlaps(x, b.spheres[j]);
      case ShapeType::aabb: return overlaps(x, b.aabbs[j]);
      case ShapeType::obb: return overlaps(x, b.obbs[j]);
      case ShapeType::plane: return overlaps(x, b.planes[j]);
      case ShapeType::triangle: return overlaps(x, b.triangles[j]);
    }
    return false;
  };
  switch (a.type) {
    case ShapeType::sphere: return with_b(a.spheres[i]);
    case ShapeType::aabb: return with_b(a.aabbs[i]);
    case ShapeType::obb: return with_b(a.obbs[i]);
    case ShapeType::plane: return with_b(a.planes[i]);
    case ShapeType::triangle: return with_b(a.triangles[i]);
  }
  return false;
}

TEST_F(BatchOverlap, EveryPairTypeMatchesTheScalarApiAtEveryLevel) {
  const std::size_t n = 3001;
  SplitMix64 rng(77);
  int pairs = 0;
  for (uint32_t ta = 1; ta <= 5; ++ta)
    for (uint32_t tb = 1; tb <= 5; ++tb) {
      const RandomShapes a = random_shapes(ShapeType(ta), n, rng), b = random_shapes(ShapeType(tb), n, rng);
      std::vector<uint32_t> want(n), one_want(n), got(n);
      std::size_t hits = 0;
      for (std::size_t i = 0; i < n; ++i) {
        want[i] = scalar_overlap(a, i, b, i) ? kOverlapping : kSeparated;
        one_want[i] = scalar_overlap(a, 0, b, i) ? kOverlapping : kSeparated;
        hits += want[i] == kOverlapping;
      }
      ++pairs;
      EXPECT_GT(hits, 0u) << ta << "," << tb << ": the random scene should have overlaps";
      if (!(ta == 4 && tb == 4)) {  // random planes always meet
        EXPECT_LT(hits, n) << ta << "," << tb;
      }
      for (uint32_t v = 1; v <= 5; ++v) {
        if (!simd_level_available(SimdLevel(v))) continue;
        set_simd_level(SimdLevel(v));
        ASSERT_EQ(overlap_pairwise(a.view(), b.view(), n, got.data()), Status::ok);
        EXPECT_EQ(got, want) << "types " << ta << "," << tb << " at " << simd_level_name(SimdLevel(v));
        ASSERT_EQ(overlap_one_against_many(a.view(), b.view(), n, got.data()), Status::ok);
        EXPECT_EQ(got, one_want) << "one-against-many, types " << ta << "," << tb << " at " << simd_level_name(SimdLevel(v));
      }
    }
  EXPECT_EQ(pairs, 25);
}

}  // namespace
}  // namespace gyro
