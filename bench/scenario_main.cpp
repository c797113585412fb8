// gyro-bench: the scenario runner. One JSON line per measurement (BENCHMARKS.md).
//   gyro-bench [--workload NAME] [--threads N[,N...]] [--simd LEVEL[,LEVEL...]] [--reps N]
//              [--peers] [--list]
#include "scenario.hpp"

#include <cstdlib>
#include <cstring>
#include <sstream>

namespace gyro::bench {
void run_r1s(const Options&);
void run_n1(const Options&);
void run_g1(const Options&);
void run_r1(const Options&);
void run_r1m(const Options&);
void run_r1a(const Options&);
void run_r2(const Options&);
void run_lidar(const Options&);
void run_camera(const Options&);
void run_b1(const Options&);
void run_p1(const Options&);
void run_p1h(const Options&);
void run_p2(const Options&);
void run_p3(const Options&);
void run_c1(const Options&);
void run_gjk(const Options&);
void run_snap(const Options&);

namespace {
const Workload kWorkloads[] = {
    {"R1S", "10k R1 rays x 10k spheres, closest hit, brute force, per SIMD level and thread count", run_r1s},
    {"N1", "10^6 OBB pairs, separating axes (boolean and depth); peers: Bullet box-box, libccd GJK/MPR/EPA", run_n1},
    {"G1", "geometry kernels per SIMD level: pairwise overlaps (10^6 pairs), brute-force raycasts", run_g1},
    {"R1", "10^6 rays x 10k spheres, closest hit (gyro: brute force on 20k rays); peers: Embree sphere points, Bullet",
     run_r1},
    {"R1M", "R1's spheres as scene models, 120 frames moving all, 10%, 1%, 0.1% of them: prepare() refit vs rebuild, rays on "
     "the refit tree vs a fresh one", run_r1m},
    {"R1A", "R1's spheres as scene models, 120 frames each removing and adding 1, 10, 100: the kept tree vs a rebuild, "
     "rays on it vs a fresh one; peer: an Embree build per frame", run_r1a},
    {"R2", "10^6 rays onto a 522k-triangle terrain, closest hit through gyro's BVH; peers: Embree, Bullet", run_r2},
    {"LIDAR", "64 x 2048 lidar fan inside the R2 terrain, tmax 120; peers: Embree, Bullet", run_lidar},
    {"CAMERA", "1920 x 1080 primary rays over the R2 terrain; peers: Embree, Bullet", run_camera},
    {"B1", "broadphase on pile-like scenes of 1k, 10k, 100k boxes plus a ground box; error against brute force / grid", run_b1},
    {"P1", "box pyramid, base 20 (210 boxes), 600 steps, sleeping off; gyro soft step and Baumgarte; peer: Bullet",
     run_p1},
    {"P1H", "P1 with every box a convex hull of its corners; gyro clipping vs incremental manifolds; peer: Bullet "
     "btConvexHullShape", run_p1h},
    {"P2", "box pyramid, base 100 (5,050 boxes), 300 steps, sleeping off; peer: Bullet", run_p2},
    {"P3", "16 pyramids of base 10 (880 boxes) on one ground, 300 steps, sleeping off; peer: Bullet", run_p3},
    {"C1", "hanging cloth 32^2..256^2, two corners pinned, 600 steps; xpbd and springs; peer: Bullet btSoftBody", run_c1},
    {"GJK", "GJK / EPA on the N1 OBB pairs and random hulls: intersection, distance, penetration; peers: libccd, Bullet", run_gjk},
    {"SNAP", "snapshot / restore of 1k and 10k warm boxes (rollback), against memcpy of the bytes; hash check after", run_snap},
};

int usage() {
  std::fprintf(stderr,
               "usage: gyro-bench [--workload NAME] [--threads N,...] [--simd LEVEL,...] [--reps N] [--peers] [--list]\n");
  return 2;
}

std::vector<std::string> split(const char* s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}
}  // namespace
}  // namespace gyro::bench

int main(int argc, char** argv) {
  using namespace gyro::bench;
  Options o;
  for (int i = 1; i < argc; ++i) {
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (!std::strcmp(argv[i], "--list")) {
      for (const Workload& w : kWorkloads) std::printf("%-6s %s\n", w.name, w.description);
      return 0;
    } else if (!std::strcmp(argv[i], "--peers")) {
      o.peers = true;
    } else if (!std::strcmp(argv[i], "--workload")) {
      const char* v = value();
      if (!v) return usage();
      o.workload = v;
    } else if (!std::strcmp(argv[i], "--reps")) {
      const char* v = value();
      if (!v || std::atoi(v) < 1) return usage();
      o.reps = std::atoi(v);
    } else if (!std::strcmp(argv[i], "--threads")) {
      const char* v = value();
      if (!v) return usage();
      for (const auto& t : split(v)) {
        const int n = std::atoi(t.c_str());
        if (n < 1 || n > 1024) return usage();
        o.threads.push_back(uint32_t(n));
      }
    } else if (!std::strcmp(argv[i], "--simd")) {
      const char* v = value();
      if (!v) return usage();
      for (const auto& name : split(v)) {
        gyro::SimdLevel l;
        if (!gyro::parse_simd_level(name.c_str(), &l)) return usage();
        o.levels.push_back(l);
      }
    } else {
      return usage();
    }
  }
  std::printf("# gyro-bench: simd %s detected, %u threads default; times are medians of %d reps\n",
              gyro::simd_level_name(gyro::detected_simd_level()), gyro::thread_count(), o.reps);
  bool any = false;
  for (const Workload& w : kWorkloads) {
    if (!o.workload.empty() && o.workload != w.name) continue;
    any = true;
    w.run(o);
  }
  if (!any) {
    std::fprintf(stderr, "gyro-bench: unknown workload '%s' (--list)\n", o.workload.c_str());
    return 2;
  }
  return 0;
}
