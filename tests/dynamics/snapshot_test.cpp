// World snapshots: a restored world retraces the original step for step; bad buffers change
// nothing; meshes are shared when identical and owned when not.
#include "core/byte_stream.hpp"
#include "gyro/world.hpp"
#include "mixed_world.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace gyro {
namespace {

constexpr float kDt = 1.0f / 60.0f;

std::vector<uint8_t> take_snapshot(const World& w) {
  std::vector<uint8_t> bytes(w.snapshot_size());
  std::size_t size = 0;
  EXPECT_EQ(w.snapshot(bytes.data(), bytes.size(), &size), Status::ok);
  EXPECT_EQ(size, bytes.size());
  return bytes;
}

std::vector<uint64_t> step_hashes(World& w, int steps) {
  std::vector<uint64_t> h;
  for (int i = 0; i < steps; ++i) {
    EXPECT_EQ(w.step(kDt), Status::ok);
    h.push_back(w.hash());
  }
  return h;
}

struct MixedWorld : ::testing::Test {
  TriangleMesh ramp = test::make_mixed_world_ramp();
  std::unique_ptr<World> w;
  void SetUp() override {
    ASSERT_EQ(World::create(WorldDef{}, &w), Status::ok);
    ASSERT_TRUE(test::build_mixed_world(*w, ramp));
    for (int i = 0; i < 30; ++i) ASSERT_EQ(w->step(kDt), Status::ok);
  }
};

TEST_F(MixedWorld, RestoreRetracesEveryStepEvenAfterTheWorldChanged) {
  const std::vector<uint8_t> snap = take_snapshot(*w);
  const uint64_t at = w->hash();
  const std::vector<uint64_t> ahead = step_hashes(*w, 90);
  // Change the world beyond recognition: the restore must undo all of it.
  const BodyView v = w->bodies();
  ASSERT_EQ(w->destroy_body(v.ids[v.count - 1]), Status::ok);
  BodyDef extra;
  extra.position = {0.0f, 9.0f, 0.0f};
  BodyId id;
  ASSERT_EQ(w->create_body(extra, &id), Status::ok);
  ASSERT_EQ(w->destroy_soft_body(SoftBodyId{0, 1}), Status::ok);
  step_hashes(*w, 5);

  ASSERT_EQ(w->restore(snap.data(), snap.size()), Status::ok);
  EXPECT_EQ(w->hash(), at);
  EXPECT_EQ(step_hashes(*w, 90), ahead);
  // Restoring twice in a row is the same as once.
  ASSERT_EQ(w->restore(snap.data(), snap.size()), Status::ok);
  ASSERT_EQ(w->restore(snap.data(), snap.size()), Status::ok);
  EXPECT_EQ(step_hashes(*w, 10), std::vector<uint64_t>(ahead.begin(), ahead.begin() + 10));
}

TEST_F(MixedWorld, AWorldBuiltFromTheBytesRetracesTooAndOwnsItsMesh) {
  const std::vector<uint8_t> snap = take_snapshot(*w);
  std::unique_ptr<World> copy;
  ASSERT_EQ(World::create_from_snapshot(snap.data(), snap.size(), &copy), Status::ok);
  EXPECT_EQ(copy->hash(), w->hash());
  EXPECT_EQ(copy->body_count(), w->body_count());
  EXPECT_EQ(copy->soft_body_count(), 2u);
  const BodyView v = copy->bodies();
  const TriangleMesh* mesh = nullptr;
  ASSERT_EQ(copy->get_mesh(v.ids[1], &mesh), Status::ok);
  ASSERT_NE(mesh, nullptr);
  EXPECT_NE(mesh, &ramp);  // a copy the new world owns: the caller's mesh need not outlive it
  EXPECT_EQ(mesh->triangle_count(), ramp.triangle_count());
  EXPECT_EQ(step_hashes(*copy, 60), step_hashes(*w, 60));
  // The same snapshot taken again from the copy is byte-identical.
  std::unique_ptr<World> a, b;
  const std::vector<uint8_t> s1 = take_snapshot(*w), s2 = take_snapshot(*copy);
  EXPECT_EQ(s1, s2);
}

TEST_F(MixedWorld, RestoreInPlaceSharesTheCallersMesh) {
  const std::vector<uint8_t> snap = take_snapshot(*w);
  step_hashes(*w, 3);
  ASSERT_EQ(w->restore(snap.data(), snap.size()), Status::ok);
  const TriangleMesh* mesh = nullptr;
  ASSERT_EQ(w->get_mesh(w->bodies().ids[1], &mesh), Status::ok);
  EXPECT_EQ(mesh, &ramp);
  uint64_t user = 0;
  ASSERT_EQ(w->get_user_data(w->bodies().ids[3], &user), Status::ok);
  EXPECT_EQ(user, 1000u);
}

TEST_F(MixedWorld, BadBuffersAreRejectedAndChangeNothing) {
  std::vector<uint8_t> snap = take_snapshot(*w);
  step_hashes(*w, 2);
  const uint64_t before = w->hash();
  EXPECT_EQ(w->restore(nullptr, 10), Status::null_argument);
  // Truncated anywhere, or padded.
  for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(31), std::size_t(32), snap.size() / 2, snap.size() - 1}) {
    EXPECT_EQ(w->restore(snap.data(), n), Status::corrupt_data) << n;
    EXPECT_EQ(w->hash(), before);
  }
  std::vector<uint8_t> padded = snap;
  padded.push_back(0);
  EXPECT_EQ(w->restore(padded.data(), padded.size()), Status::corrupt_data);
  // Any flipped bit is caught by the checksum (header bytes by their own checks).
  for (std::size_t i = 0; i < snap.size(); i += 37) {
    std::vector<uint8_t> bad = snap;
    bad[i] ^= uint8_t(1u << (i % 8));
    EXPECT_EQ(w->restore(bad.data(), bad.size()), Status::corrupt_data) << "byte " << i;
  }
  EXPECT_EQ(w->hash(), before);
  // Another format version.
  std::vector<uint8_t> other = snap;
  other[8] = 2;
  EXPECT_EQ(w->restore(other.data(), other.size()), Status::corrupt_data);
  EXPECT_EQ(w->hash(), before);
  std::unique_ptr<World> none;
  EXPECT_EQ(World::create_from_snapshot(other.data(), other.size(), &none), Status::corrupt_data);
  EXPECT_EQ(none, nullptr);
}

// Bytes changed behind a valid checksum (what a buggy writer or a deliberate edit could make):
// every result is either a consistent world or corrupt_data, never a crash (the sanitizer
// build runs this too). Values that only change a number (a position) restore fine.
TEST_F(MixedWorld, ValidChecksumOverInconsistentContentIsCaughtOrHarmless) {
  const std::vector<uint8_t> snap = take_snapshot(*w);
  const uint64_t before = w->hash();
  int rejected = 0, accepted = 0;
  // About 500 positions spread over the payload (the whole payload, a value per stride, ran
  // clean at stride 11 with three values when this test was written).
  const std::size_t stride = (snap.size() - 32) / 500 + 1;
  for (std::size_t i = 32; i < snap.size(); i += stride) {
    for (uint8_t value : {uint8_t(0xFF), uint8_t(0x7F)}) {
      std::vector<uint8_t> bad = snap;
      if (bad[i] == value) continue;
      bad[i] = value;
      const uint64_t sum = detail::checksum64(bad.data() + 32, bad.size() - 32);
      std::memcpy(bad.data() + 24, &sum, 8);
      std::unique_ptr<World> c;
      const Status s = World::create_from_snapshot(bad.data(), bad.size(), &c);
      if (s == Status::ok) {
        ++accepted;
        for (int k = 0; k < 2; ++k) c->step(kDt);  // must not crash, whatever the values
      } else {
        ++rejected;
        EXPECT_EQ(s, Status::corrupt_data);
      }
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_GT(accepted, 0);
  EXPECT_EQ(w->hash(), before);
}

TEST(Snapshot, SmallCapacityWritesNothing) {
  std::unique_ptr<World> w;
  ASSERT_EQ(World::create(WorldDef{}, &w), Status::ok);
  const std::size_t need = w->snapshot_size();
  EXPECT_LT(need, 1024u);  // an empty world: the header, its settings and empty columns
  std::vector<uint8_t> buf(need - 1, 0xAB);
  std::size_t size = 7;
  EXPECT_EQ(w->snapshot(buf.data(), buf.size(), &size), Status::invalid_count);
  EXPECT_EQ(size, 7u);
  for (uint8_t b : buf) ASSERT_EQ(b, 0xAB);
  EXPECT_EQ(w->snapshot(nullptr, need, &size), Status::null_argument);
}

TEST(Snapshot, SettingsTravelButThreadsStay) {
  WorldDef def;
  def.contact_model = ContactModel::baumgarte;
  def.velocity_iterations = 9;
  def.gravity = {0.0f, -3.0f, 0.5f};
  def.threads = 3;
  std::unique_ptr<World> a, b;
  ASSERT_EQ(World::create(def, &a), Status::ok);
  ASSERT_EQ(World::create(WorldDef{}, &b), Status::ok);
  const std::vector<uint8_t> snap = take_snapshot(*a);
  ASSERT_EQ(b->restore(snap.data(), snap.size()), Status::ok);
  EXPECT_EQ(b->def().contact_model, ContactModel::baumgarte);
  EXPECT_EQ(b->def().velocity_iterations, 9u);
  EXPECT_EQ(b->def().gravity.z, 0.5f);
  EXPECT_EQ(b->def().threads, 0u);
}

}  // namespace
}  // namespace gyro
