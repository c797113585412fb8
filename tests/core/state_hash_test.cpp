#include "core/state_hash.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gyro::detail {
namespace {

TEST(StateHash, CanonicalisesNaNButKeepsSignedZero) {
  const float nans[] = {std::bit_cast<float>(0x7fc00000u), std::bit_cast<float>(0xffc00001u),
                        std::bit_cast<float>(0x7f800001u)};
  uint64_t first = 0;
  for (float n : nans) {
    StateHasher h;
    h.add_float(n);
    if (first == 0) first = h.digest();
    EXPECT_EQ(h.digest(), first);
  }
  StateHasher pz, nz;
  pz.add_float(0.0f);
  nz.add_float(-0.0f);
  EXPECT_NE(pz.digest(), nz.digest());
}

TEST(StateHash, OrderAndLengthMatter) {
  StateHasher a, b, c;
  a.add_u64(1), a.add_u64(2);
  b.add_u64(2), b.add_u64(1);
  c.add_u64(1), c.add_u64(2), c.add_u64(0);
  EXPECT_NE(a.digest(), b.digest());
  EXPECT_NE(a.digest(), c.digest());
}

TEST(StateHash, PinnedValuesNeverChange) {
  // Golden hashes everywhere depend on this function: it must not change silently.
  StateHasher h;
  std::vector<float> v = {1.0f, -2.5f, 3.25f};
  h.add_floats(v);
  h.add_u32(7);
  EXPECT_EQ(h.digest(), 0x799ced11d42fd90dull) << std::hex << h.digest();
}

TEST(Fnv1a64, MatchesTheReferenceVector) {
  EXPECT_EQ(fnv1a64("", 0), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar", 6), 0x85944171f73967e8ull);
}

}  // namespace
}  // namespace gyro::detail
