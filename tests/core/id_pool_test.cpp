#include "core/id_pool.hpp"

#include "core/state_hash.hpp"

#include <gtest/gtest.h>

namespace gyro::detail {
namespace {

TEST(IdPool, NullIsNeverValidAndIdsStartAtGenerationOne) {
  IdPool p;
  EXPECT_FALSE(p.valid(Id{}));
  Id a = p.create();
  EXPECT_EQ(a.index, 0u);
  EXPECT_EQ(a.generation, 1u);
  EXPECT_FALSE(a.is_null());
  EXPECT_TRUE(p.valid(a));
}

TEST(IdPool, StaleIdsAreDetectedAfterReuse) {
  IdPool p;
  Id a = p.create(), b = p.create(), c = p.create();
  auto rem = p.destroy(a);
  EXPECT_EQ(rem.slot, 0u);
  EXPECT_EQ(rem.moved_from, 2u);  // c moved into slot 0
  EXPECT_EQ(p.slot(c), 0u);
  EXPECT_EQ(p.slot(b), 1u);
  EXPECT_FALSE(p.valid(a));
  Id d = p.create();  // reuses index 0 with a new generation
  EXPECT_EQ(d.index, a.index);
  EXPECT_NE(d.generation, a.generation);
  EXPECT_FALSE(p.valid(a));
  EXPECT_EQ(p.slot(a), IdPool::kNoSlot);
  EXPECT_TRUE(p.valid(d));
  EXPECT_EQ(p.id_at(p.slot(d)), d);
}

TEST(IdPool, DenseSlotsStayConsistentUnderRandomChurn) {
  IdPool p;
  std::vector<Id> live;
  uint64_t s = 12345;
  auto rnd = [&] { s = s * 6364136223846793005ull + 1442695040888963407ull; return uint32_t(s >> 33); };
  for (int step = 0; step < 20000; ++step) {
    if (live.empty() || rnd() % 3 != 0) {
      live.push_back(p.create());
    } else {
      std::size_t k = rnd() % live.size();
      p.destroy(live[k]);
      live[k] = live.back();
      live.pop_back();
    }
    ASSERT_EQ(p.size(), live.size());
  }
  for (Id id : live) {
    ASSERT_TRUE(p.valid(id));
    ASSERT_EQ(p.id_at(p.slot(id)), id);
  }
}

TEST(IdPool, SameCallsGiveTheSameStateHash) {
  auto run = [] {
    IdPool p;
    std::vector<Id> ids;
    for (int i = 0; i < 100; ++i) ids.push_back(p.create());
    for (int i = 0; i < 100; i += 3) p.destroy(ids[i]);
    for (int i = 0; i < 10; ++i) p.create();
    StateHasher h;
    p.hash_into(h);
    return h.digest();
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace gyro::detail
