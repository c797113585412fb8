// R1M: R1's 10^4 spheres as scene models, moving. Each of 120 frames moves a fraction of the
// spheres (a tenth, a hundredth, a thousandth; the same random choice and steps of up to
// 0.1 m per axis at every setting) and then calls prepare(). Per fraction and thread count:
// the median prepare() with SceneSettings::refit on (the BVH refit over what moved) against
// the baseline in the same run, refit off (every frame a rebuild); then R1's first 2 * 10^5
// rays on the final refit tree against a fresh build of the same models. Error: rays whose
// closest hit (t to the bit, model) differs between the two trees, which must be none (the
// answer does not depend on the tree).
#include "gyro/scene.hpp"
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

struct Frames {
  Scene scene;
  std::vector<ModelId> ids;
  std::vector<vec3> pos;
  double prepare_ms = 0;  // median per frame
};

// The spheres added and prepared, then kFrames frames of moves and prepare().
void run_frames(Frames& f, const testing::SphereSet& spheres, bool refit, double fraction) {
  SceneSettings settings;
  settings.refit = refit;
  f.scene = Scene(settings);
  f.ids.assign(spheres.size(), ModelId{});
  f.pos.resize(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    ModelDef d;
    d.shape = ModelShape::sphere;
    d.radius = spheres.r[i];
    f.pos[i] = {spheres.cx[i], spheres.cy[i], spheres.cz[i]};
    d.transform.position = f.pos[i];
    f.scene.add_model(d, &f.ids[i]);
  }
  f.scene.prepare();
  testing::SplitMix64 rng(9);
  const auto moves = std::size_t(double(spheres.size()) * fraction);
  std::vector<double> ms;
  for (int frame = 0; frame < kFrames; ++frame) {
    for (std::size_t k = 0; k < moves; ++k) {
      const std::size_t i = rng.next() % spheres.size();
      float step[3];
      for (float& s : step) s = float((rng.u() - 0.5) * 0.2);
      f.pos[i] = f.pos[i] + vec3{step[0], step[1], step[2]};
      ModelTransform t;
      t.position = f.pos[i];
      f.scene.set_transform(f.ids[i], t);
    }
    const auto a = std::chrono::steady_clock::now();
    f.scene.prepare();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(ms.begin(), ms.end());
  f.prepare_ms = ms[ms.size() / 2];
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
  for (const double fraction : {0.1, 0.01, 0.001}) {
    for (uint32_t threads : threads_to_run(o)) {
      set_thread_count(threads);
      Frames refit, rebuild;
      run_frames(refit, spheres, true, fraction);
      run_frames(rebuild, spheres, false, fraction);
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
    }
  }
  set_thread_count(0);
  if (o.peers) std::printf("# R1M: no peer line yet (Embree's refit builds, RTC_BUILD_QUALITY_REFIT, would be one)\n");
}

}  // namespace gyro::bench
