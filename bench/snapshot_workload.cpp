// SNAP: snapshot and restore of piles of 1,000 and 10,000 boxes that have been stepped until
// their contacts are warm (what rollback networking does every frame). Reported: bytes,
// snapshot, restore-in-place and build-from-bytes times, against a plain memcpy of the same
// bytes (the floor), and the error figure: steps whose hash differs after the restore (0).
#include "scenario.hpp"

#include "gyro/world.hpp"

#include <cstring>
#include <memory>
#include <vector>

namespace gyro::bench {

namespace {

std::unique_ptr<World> pile(int boxes) {
  std::unique_ptr<World> w;
  WorldDef def;
  def.enable_sleep = false;  // every body awake: the largest snapshot the pile makes
  if (World::create(def, &w) != Status::ok) return nullptr;
  BodyDef g;
  g.type = BodyType::static_body;
  g.shape.half_extents = {200.0f, 0.5f, 200.0f};
  g.position = {0.0f, -0.5f, 0.0f};
  BodyId id;
  w->create_body(g, &id);
  const int side = 1 + int(__builtin_sqrt(double(boxes) / 5.0));
  for (int i = 0; i < boxes; ++i) {
    BodyDef b;
    b.shape.half_extents = {0.5f, 0.5f, 0.5f};
    const int layer = i / (side * side), k = i % (side * side);
    b.position = {1.1f * float(k % side), 0.5f + 1.05f * float(layer), 1.1f * float(k / side)};
    w->create_body(b, &id);
  }
  for (int s = 0; s < 30; ++s) w->step(1.0f / 60.0f);
  return w;
}

}  // namespace

void run_snap(const Options& o) {
  for (int boxes : {1000, 10000}) {
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      std::unique_ptr<World> w = pile(boxes);
      if (!w) return;
      std::vector<uint8_t> bytes(w->snapshot_size()), copy(bytes.size());
      std::size_t size = 0;
      const double snap_ms = median_ms(o.reps, [&] { w->snapshot(bytes.data(), bytes.size(), &size); });
      const double memcpy_ms = median_ms(o.reps, [&] { std::memcpy(copy.data(), bytes.data(), bytes.size()); });
      const double restore_ms = median_ms(o.reps, [&] { w->restore(bytes.data(), size); });
      std::unique_ptr<World> built;
      const double build_ms = median_ms(o.reps, [&] { World::create_from_snapshot(bytes.data(), size, &built); });
      // Error figure: the restored world and the rebuilt one retrace the original's hashes.
      std::vector<uint64_t> ahead;
      for (int s = 0; s < 20; ++s) w->step(1.0f / 60.0f), ahead.push_back(w->hash());
      w->restore(bytes.data(), size);
      int diverged = 0;
      for (int s = 0; s < 20; ++s) {
        w->step(1.0f / 60.0f), built->step(1.0f / 60.0f);
        diverged += w->hash() != ahead[std::size_t(s)] || built->hash() != ahead[std::size_t(s)];
      }
      JsonLine()
          .str("workload", "SNAP")
          .integer("bodies", boxes + 1)
          .integer("threads", threads)
          .integer("bytes", int64_t(size))
          .num("bytes_per_body", double(size) / double(boxes + 1), 4)
          .num("snapshot_ms", snap_ms, 4)
          .num("restore_ms", restore_ms, 4)
          .num("create_from_snapshot_ms", build_ms, 4)
          .num("memcpy_ms", memcpy_ms, 4)
          .integer("diverged_steps", diverged)
          .print();
    }
  }
  set_thread_count(0);
}

}  // namespace gyro::bench
