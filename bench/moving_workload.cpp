// R1M: R1's 10^4 spheres as scene models, moving. Each of 120 frames moves a fraction of the
// spheres (all of them, a tenth, a hundredth, a thousandth; the same random choice and steps of
// up to 0.1 m per axis at every setting, and at "all" every sphere once, in index order: what a
// physics step does to a scene of awake bodies) and then calls prepare(). Per fraction and thread count:
// the median prepare() with SceneSettings::refit on (the BVH refit over what moved) against
// the baseline in the same run, refit off (every frame a rebuild); then R1's first 2 * 10^5
// rays on the final refit tree against a fresh build of the same models. Error: rays whose
// closest hit (t to the bit, model) differs between the two trees, which must be none (the
// answer does not depend on the tree).
//
// With --peers, Embree on the same moves: its sphere-point scene committed after each frame's
// moves as a rebuild (default quality), a dynamic low-quality rebuild, or a refit (peers.hpp:
// EmbreeScene::Update). Embree refits the whole tree at every commit; gyro's refit redoes
// only what moved. Embree's rays on its final tree against a fresh build of the same spheres,
// error: rays whose hit (t bits, sphere) differs between those two.
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
constexpr std::size_t kRays = 200000;

// Every frame's moves, computed once so that gyro and the peers get the same ones: frame f
// moves spheres index[k] to centre xyz[3k..3k+3) for k in [begin[f], begin[f + 1]).
struct Script {
  std::vector<std::size_t> begin;
  std::vector<uint32_t> index;
  std::vector<float> xyz;
  testing::SphereSet final;  // the spheres after the last frame
};

Script make_script(const testing::SphereSet& spheres, double fraction) {
  Script s;
  s.final = spheres;
  testing::SplitMix64 rng(9);
  const auto moves = std::size_t(double(spheres.size()) * fraction);
  for (int frame = 0; frame < kFrames; ++frame) {
    s.begin.push_back(s.index.size());
    for (std::size_t k = 0; k < moves; ++k) {
      const std::size_t i = fraction >= 1.0 ? k : rng.next() % spheres.size();
      float step[3];
      for (float& v : step) v = float((rng.u() - 0.5) * 0.2);
      const vec3 p = vec3{s.final.cx[i], s.final.cy[i], s.final.cz[i]} + vec3{step[0], step[1], step[2]};
      s.final.cx[i] = p.x, s.final.cy[i] = p.y, s.final.cz[i] = p.z;
      s.index.push_back(uint32_t(i));
      s.xyz.insert(s.xyz.end(), {p.x, p.y, p.z});
    }
  }
  s.begin.push_back(s.index.size());
  return s;
}

struct Frames {
  Scene scene;
  double prepare_ms = 0;  // median per frame
};

// The spheres added and prepared, then the script's frames of moves and prepare().
void run_frames(Frames& f, const testing::SphereSet& spheres, bool refit, const Script& script) {
  SceneSettings settings;
  settings.refit = refit;
  f.scene = Scene(settings);
  std::vector<ModelId> ids(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    ModelDef d;
    d.shape = ModelShape::sphere;
    d.radius = spheres.r[i];
    d.transform.position = {spheres.cx[i], spheres.cy[i], spheres.cz[i]};
    f.scene.add_model(d, &ids[i]);
  }
  f.scene.prepare();
  std::vector<double> ms;
  for (int frame = 0; frame < kFrames; ++frame) {
    for (std::size_t k = script.begin[frame]; k < script.begin[frame + 1]; ++k) {
      ModelTransform t;
      t.position = {script.xyz[3 * k], script.xyz[3 * k + 1], script.xyz[3 * k + 2]};
      f.scene.set_transform(ids[script.index[k]], t);
    }
    const auto a = std::chrono::steady_clock::now();
    f.scene.prepare();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  f.prepare_ms = median(std::move(ms));
}

// Embree's lines for one fraction and thread count: per update mode, the median commit after
// a frame's moves, and rtcIntersect1 on the final tree against a fresh build.
void run_embree(const Options& o, const testing::SphereSet& spheres, const testing::RaySet& rays, const Script& script,
                const std::string& moved, uint32_t threads, double gyro_refit_ms) {
  using Update = EmbreeScene::Update;
  // Sphere points as R1 builds them, rebuilt (default) or rebuilt fast (low); user-geometry
  // spheres refit (sphere points cannot be: peers.hpp).
  struct Mode {
    Update update;
    bool user;
    const char* name;
  };
  for (const Mode m : {Mode{Update::refit, true, "refit user_sphere"}, Mode{Update::low, false, "low sphere_point"},
                       Mode{Update::rebuild, false, "rebuild sphere_point"}}) {
    PeerBuild fresh_build;
    const auto fresh = EmbreeScene::moving_spheres(script.final, Update::rebuild, m.user, threads, fresh_build);
    if (!fresh) {
      std::printf("# R1M: Embree scene build failed\n");
      return;
    }
    RayResults fresh_hits, hits;
    const double fresh_ms = median_ms(
        o.reps, [&] { fresh->trace(rays, rays.size(), 1000.0f, EmbreeMethod::intersect1, threads, fresh_hits); });
    PeerBuild build;
    const auto scene = EmbreeScene::moving_spheres(spheres, m.update, m.user, threads, build);
    if (!scene) {
      std::printf("# R1M: Embree scene build failed\n");
      return;
    }
    std::vector<double> ms;
    for (int frame = 0; frame < kFrames; ++frame) {
      const std::size_t b = script.begin[frame], n = script.begin[frame + 1] - b;
      ms.push_back(scene->move_spheres(script.index.data() + b, script.xyz.data() + 3 * b, n));
    }
    const double commit_ms = median(std::move(ms));
    const double rays_ms =
        median_ms(o.reps, [&] { scene->trace(rays, rays.size(), 1000.0f, EmbreeMethod::intersect1, threads, hits); });
    std::size_t differ = 0, hit_count = 0;
    double checksum = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      differ += std::bit_cast<uint32_t>(hits.t[i]) != std::bit_cast<uint32_t>(fresh_hits.t[i]) ||
                hits.primitive[i] != fresh_hits.primitive[i];
      if (hits.primitive[i] >= 0) ++hit_count, checksum += double(hits.t[i]);
    }
    const std::string commit = std::string("commit_") + m.name, trace = std::string("rtcIntersect1 on the ") + m.name + " tree";
    const auto line = [&](const std::string& method, double time, double throughput, const char* unit) {
      JsonLine j;
      j.str("workload", "R1M").str("library", "embree").str("method", method).str("moved", moved)
          .str("simd", "auto").integer("threads", threads).num("build_ms", build.ms, 5).num("time_ms", time, 5)
          .num("throughput", throughput, 5).str("unit", unit).integer("hits", int64_t(hit_count))
          .num("checksum", checksum, 12).num("error", double(differ))
          .str("error_metric", "rays whose closest hit (t bits, sphere) differs between the updated tree and a fresh build")
          .integer("reps", o.reps);
      return j;
    };
    line(commit, commit_ms, 1000.0 / commit_ms, "frames/s").num("gyro_refit_speedup", commit_ms / gyro_refit_ms, 4).print();
    line(trace, rays_ms, double(rays.size()) / rays_ms / 1e3, "Mrays/s")
        .num("ratio_vs_fresh_tree", fresh_ms / rays_ms, 4).print();
  }
}

}  // namespace

void run_r1m(const Options& o) {
  const testing::SphereSet spheres = testing::r1_spheres();
  const testing::RaySet rays = testing::r1_rays(kRays);
  std::vector<float> tmax(rays.size(), 1000.0f);
  RaysView view = rays.view();
  view.tmax = tmax.data();
  std::printf("# R1M: %zu spheres, %d frames each moving a fraction of them, then prepare(); rays: %zu of R1's\n",
              spheres.size(), kFrames, rays.size());
  for (const double fraction : {1.0, 0.1, 0.01, 0.001}) {
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      const Script script = make_script(spheres, fraction);
      Frames refit, rebuild;
      run_frames(refit, spheres, true, script);
      run_frames(rebuild, spheres, false, script);
      const SceneStats st = refit.scene.stats();
      // The final refit tree's rays against a fresh build of the same models.
      std::vector<float> t_refit(rays.size()), t_fresh(rays.size());
      std::vector<ModelId> m_refit(rays.size()), m_fresh(rays.size());
      const double refit_rays_ms =
          median_ms(o.reps, [&] { raycast_closest(refit.scene, view, rays.size(), {t_refit.data(), m_refit.data()}); });
      SceneSettings fresh;
      fresh.refit = false;
      refit.scene.configure(fresh);  // a rebuild of the same models at the next query
      const double fresh_rays_ms =
          median_ms(o.reps, [&] { raycast_closest(refit.scene, view, rays.size(), {t_fresh.data(), m_fresh.data()}); });
      std::size_t differ = 0, hits = 0;
      double checksum = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        differ += std::bit_cast<uint32_t>(t_refit[i]) != std::bit_cast<uint32_t>(t_fresh[i]) || !(m_refit[i] == m_fresh[i]);
        if (!m_refit[i].is_null()) ++hits, checksum += double(t_refit[i]);
      }
      const std::string moved = std::to_string(int(fraction * 1000 + 0.5)) + "/1000";
      const auto line = [&](const char* method, double ms, double throughput, const char* unit) {
        JsonLine j;
        j.str("workload", "R1M").str("library", "gyro").str("method", method).str("moved", moved)
            .str("simd", simd_level_name(detected_simd_level())).integer("threads", threads).num("build_ms", 0.0)
            .num("time_ms", ms, 5).num("throughput", throughput, 5).str("unit", unit)
            .integer("hits", int64_t(hits)).num("checksum", checksum, 12).num("error", double(differ))
            .str("error_metric", "rays whose closest hit (t bits, model) differs between the refit tree and a fresh build")
            .integer("refits", int64_t(st.refits)).integer("builds", int64_t(st.builds)).num("sah_cost", st.sah_cost, 4)
            .integer("reps", o.reps);
        return j;
      };
      line("prepare_refit", refit.prepare_ms, 1000.0 / refit.prepare_ms, "frames/s")
          .num("ratio_vs_rebuild", rebuild.prepare_ms / refit.prepare_ms, 4).print();
      line("prepare_rebuild", rebuild.prepare_ms, 1000.0 / rebuild.prepare_ms, "frames/s").print();
      line("closest_hit_refit_tree", refit_rays_ms, double(rays.size()) / refit_rays_ms / 1e3, "Mrays/s")
          .num("ratio_vs_fresh_tree", fresh_rays_ms / refit_rays_ms, 4).print();
      line("closest_hit_fresh_tree", fresh_rays_ms, double(rays.size()) / fresh_rays_ms / 1e3, "Mrays/s").print();
      if (o.peers && embree_available()) run_embree(o, spheres, rays, script, moved, threads, refit.prepare_ms);
    }
  }
  set_thread_count(0);
  if (o.peers && !embree_available()) std::printf("# R1M: Embree not built in, no peer lines\n");
}

}  // namespace gyro::bench
