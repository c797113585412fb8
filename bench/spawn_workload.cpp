// R1A: R1's 10^4 spheres as scene models, spawning and despawning. Each of 120 frames
// removes k random spheres and adds k new ones (k = 1, 10, 100: the same script for every
// line), then calls prepare(). Per k and thread count: the median frame (the removes, the
// adds and prepare()) with SceneSettings::refit on, which keeps the tree (detached and
// attached leaves, then a refit), against the baseline in the same run, refit off (every
// frame a build); then R1's first 2 * 10^5 rays on the final kept tree against a fresh build
// of the same models. Error: rays whose closest hit (t to the bit, model) differs between
// the two trees, which must be none.
//
// With --peers, Embree on the same frames: it has no insertion into a built scene, so a
// frame is a build of the frame's sphere points (its default quality, as R1's), the median
// of 10 frames spread over the script.
#include "gyro/scene.hpp"
#include "peers.hpp"
#include "scenario.hpp"
#include "workloads.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <vector>

namespace gyro::bench {
namespace {

constexpr int kFrames = 120;
constexpr std::size_t kLive = 10000;
constexpr std::size_t kRays = 200000;

// Frame f removes the live spheres at positions out[f][..] of the live list (each swapped
// with the last, then dropped) and adds pool spheres next[f] .. next[f] + k.
struct Script {
  std::size_t k = 0;
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::vector<uint32_t>> live_after;  // the pool indices live after each frame
};

Script make_script(std::size_t k) {
  Script s;
  s.k = k;
  testing::SplitMix64 rng(21);
  std::vector<uint32_t> live(kLive);
  for (uint32_t i = 0; i < kLive; ++i) live[i] = i;
  uint32_t next = uint32_t(kLive);
  for (int f = 0; f < kFrames; ++f) {
    std::vector<std::size_t> out;
    for (std::size_t r = 0; r < k; ++r) {
      const std::size_t at = std::size_t(rng.next() % live.size());
      out.push_back(at);
      live[at] = live.back();
      live.pop_back();
    }
    for (std::size_t a = 0; a < k; ++a) live.push_back(next++);
    s.out.push_back(std::move(out));
    s.live_after.push_back(live);
  }
  return s;
}

testing::SphereSet subset(const testing::SphereSet& pool, const std::vector<uint32_t>& which) {
  testing::SphereSet s;
  for (uint32_t i : which) s.cx.push_back(pool.cx[i]), s.cy.push_back(pool.cy[i]), s.cz.push_back(pool.cz[i]), s.r.push_back(pool.r[i]);
  return s;
}

ModelDef sphere_def(const testing::SphereSet& pool, uint32_t i) {
  ModelDef d;
  d.shape = ModelShape::sphere;
  d.radius = pool.r[i];
  d.transform.position = {pool.cx[i], pool.cy[i], pool.cz[i]};
  return d;
}

// The script's frames on a scene with refit on or off: the median frame in ms.
double run_frames(Scene& scene, const testing::SphereSet& pool, const Script& script, bool refit) {
  SceneSettings settings;
  settings.refit = refit;
  scene = Scene(settings);
  std::vector<ModelId> ids(kLive);
  for (uint32_t i = 0; i < kLive; ++i) scene.add_model(sphere_def(pool, i), &ids[i]);
  scene.prepare();
  uint32_t next = uint32_t(kLive);
  std::vector<double> ms;
  for (int f = 0; f < kFrames; ++f) {
    const auto a = std::chrono::steady_clock::now();
    for (const std::size_t at : script.out[std::size_t(f)]) {
      scene.remove_model(ids[at]);
      ids[at] = ids.back();
      ids.pop_back();
    }
    for (std::size_t n = 0; n < script.k; ++n) {
      ModelId id;
      scene.add_model(sphere_def(pool, next++), &id);
      ids.push_back(id);
    }
    scene.prepare();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  return median(std::move(ms));
}

}  // namespace

void run_r1a(const Options& o) {
  const testing::SphereSet pool = testing::r1_spheres(kLive + std::size_t(kFrames) * 100);
  const testing::RaySet rays = testing::r1_rays(kRays);
  std::vector<float> tmax(rays.size(), 1000.0f);
  RaysView view = rays.view();
  view.tmax = tmax.data();
  std::printf("# R1A: %zu spheres, %d frames each removing k and adding k, then prepare(); rays: %zu of R1's\n", kLive,
              kFrames, rays.size());
  for (const std::size_t k : {std::size_t(1), std::size_t(10), std::size_t(100)}) {
    const Script script = make_script(k);
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      Scene kept, rebuilt;
      const double kept_ms = run_frames(kept, pool, script, true);
      const double rebuilt_ms = run_frames(rebuilt, pool, script, false);
      const SceneStats st = kept.stats();
      // The kept tree's rays against a fresh build of the same models.
      std::vector<float> t_kept(rays.size()), t_fresh(rays.size());
      std::vector<ModelId> m_kept(rays.size()), m_fresh(rays.size());
      const double kept_rays_ms =
          median_ms(o.reps, [&] { raycast_closest(kept, view, rays.size(), {t_kept.data(), m_kept.data()}); });
      SceneSettings fresh;
      fresh.refit = false;
      kept.configure(fresh);  // a build of the same models at the next query
      const double fresh_rays_ms =
          median_ms(o.reps, [&] { raycast_closest(kept, view, rays.size(), {t_fresh.data(), m_fresh.data()}); });
      const double fresh_sah = kept.stats().sah_cost;
      std::size_t differ = 0, hits = 0;
      double checksum = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        differ += std::bit_cast<uint32_t>(t_kept[i]) != std::bit_cast<uint32_t>(t_fresh[i]) || !(m_kept[i] == m_fresh[i]);
        if (!m_kept[i].is_null()) ++hits, checksum += double(t_kept[i]);
      }
      const std::string changes = std::to_string(k);
      const auto line = [&](const char* library, const char* method, double ms, double throughput, const char* unit) {
        JsonLine j;
        j.str("workload", "R1A").str("library", library).str("method", method).str("removed_and_added", changes)
            .str("simd", simd_level_name(detected_simd_level())).integer("threads", threads).num("time_ms", ms, 5)
            .num("throughput", throughput, 5).str("unit", unit).integer("hits", int64_t(hits)).num("checksum", checksum, 12)
            .num("error", double(differ))
            .str("error_metric", "rays whose closest hit (t bits, model) differs between the kept tree and a fresh build")
            .integer("reps", o.reps);
        return j;
      };
      line("gyro", "frame_kept_tree", kept_ms, 1000.0 / kept_ms, "frames/s")
          .num("ratio_vs_rebuild", rebuilt_ms / kept_ms, 4).integer("builds", int64_t(st.builds))
          .integer("refits", int64_t(st.refits)).num("sah_cost", st.sah_cost, 4).num("fresh_sah_cost", fresh_sah, 4).print();
      line("gyro", "frame_rebuild", rebuilt_ms, 1000.0 / rebuilt_ms, "frames/s").print();
      line("gyro", "closest_hit_kept_tree", kept_rays_ms, double(rays.size()) / kept_rays_ms / 1e3, "Mrays/s")
          .num("ratio_vs_fresh_tree", fresh_rays_ms / kept_rays_ms, 4).print();
      if (o.peers && embree_available()) {
        // Ten of the frames' sphere sets, each built as Embree builds R1's.
        std::vector<double> ms;
        for (int f = kFrames / 20; f < kFrames; f += kFrames / 10) {
          PeerBuild build;
          const auto scene = EmbreeScene::moving_spheres(subset(pool, script.live_after[std::size_t(f)]),
                                                         EmbreeScene::Update::rebuild, false, threads, build);
          if (!scene) {
            std::printf("# R1A: Embree scene build failed\n");
            break;
          }
          ms.push_back(build.ms);
        }
        if (!ms.empty()) {
          const double embree_ms = median(std::move(ms));
          JsonLine j;
          j.str("workload", "R1A").str("library", "embree").str("method", "frame_build sphere_point")
              .str("removed_and_added", changes).str("simd", "auto").integer("threads", threads)
              .num("time_ms", embree_ms, 5).num("throughput", 1000.0 / embree_ms, 5).str("unit", "frames/s")
              .num("gyro_kept_speedup", embree_ms / kept_ms, 4).num("error", 0.0)
              .str("error_metric", "none: a fresh build of the frame's spheres").integer("reps", 10).print();
        }
      }
    }
  }
  if (o.peers && !embree_available()) std::printf("# R1A: Embree not built in, no peer lines\n");
}

}  // namespace gyro::bench
