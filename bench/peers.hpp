// Peer libraries measured side by side on the same inputs (BENCHMARKS.md). Each peer is
// compiled only when its library is installed; its functions report availability (a peer
// that is not built returns false / a null object and does nothing).
//
// Ray conventions shared by every peer: ray i is o + t d with t in [0, tmax] (d as given,
// about unit length, so t is a distance); a peer reports, per ray, the closest t (+inf on a
// miss) and the primitive hit (triangle or sphere index in input order, -1 on a miss), so
// hits, checksums and errors are computed the same way for every library.
#pragma once

#include "workloads.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gyro::bench {

/// Verdict (and depth where the method gives one) for every N1 pair. Depth > 0 means
/// penetration; 0 when the method reports none.
struct PairResults {
  std::vector<uint8_t> hit;
  std::vector<double> depth;
};

enum class CcdMethod { gjk_intersect, mpr_intersect, gjk_epa_penetration, mpr_penetration };

bool bullet_available();
/// btBoxBoxDetector on pairs [0, n).
void bullet_box_box(const testing::BoxPairs& pairs, std::size_t n, PairResults& out);

bool ccd_available();
void ccd_box_box(const testing::BoxPairs& pairs, std::size_t n, CcdMethod method, PairResults& out);

/// Per-ray answers of a peer (see the conventions above).
struct RayResults {
  std::vector<float> t;
  std::vector<int32_t> primitive;
  void resize(std::size_t n) { t.assign(n, 0.0f), primitive.assign(n, -1); }
};

/// What building a peer's acceleration structure cost. bytes: memory the structure holds
/// after the build, not counting the input vertices/indices it shares with the caller
/// (0 when the library gives no way to know).
struct PeerBuild {
  double ms = 0;
  std::size_t bytes = 0;
  std::size_t peak_bytes = 0;  // Embree: the most memory held during the build
};

/// rtcIntersect1/16: the closest hit. rtcOccluded1/16: any hit (occlusion), reported as t = 0
/// and primitive 0 on a hit (Embree gives neither), +inf and -1 on a miss.
enum class EmbreeMethod { intersect1, intersect16, occluded1, occluded16 };

bool embree_available();
/// "3.13.5" and whether rtcIntersect16 runs natively (AVX-512), for the comment lines.
const char* embree_version();
bool embree_native_ray16();

/// An Embree 3 device and committed scene (RTC_SCENE_FLAG_ROBUST optional, Embree's default
/// build quality, RTC_BUILD_QUALITY_MEDIUM). The device's build threads are given (Embree
/// builds with TBB); queries are thread-safe and run on the threads trace() starts.
class EmbreeScene {
 public:
  /// A triangle mesh (RTC_GEOMETRY_TYPE_TRIANGLE over a copy of the vertices in AoS,
  /// shared with Embree, not counted in bytes). Null when Embree is not built in.
  static std::unique_ptr<EmbreeScene> triangles(const MeshData& mesh, bool robust, uint32_t build_threads,
                                                PeerBuild& build);
  /// Spheres as RTC_GEOMETRY_TYPE_SPHERE_POINT (float4 x, y, z, r). Embree's test keeps the
  /// far root when the near one lies before tnear, so a ray starting inside a sphere reports
  /// its exit point, as BENCHMARKS.md's reference does.
  static std::unique_ptr<EmbreeScene> spheres(const testing::SphereSet& spheres, uint32_t build_threads,
                                              PeerBuild& build);
  /// How a moving scene's commit (move_spheres) updates Embree's BVH: rebuild (the default
  /// scene, RTC_BUILD_QUALITY_MEDIUM, built again), low (RTC_SCENE_FLAG_DYNAMIC, scene and
  /// geometry RTC_BUILD_QUALITY_LOW: the fast rebuild Embree offers dynamic scenes) or refit
  /// (RTC_SCENE_FLAG_DYNAMIC, scene RTC_BUILD_QUALITY_LOW, geometry RTC_BUILD_QUALITY_REFIT:
  /// the BVH's topology kept and every node's box refit). Embree's two-level builder refits
  /// triangles, quads, user geometry and instances, not sphere points (their refit commit
  /// costs what a rebuild does), so `user` makes the spheres user geometry (a bounds and an
  /// intersect callback), the way an Embree user moving spheres gets a refit.
  enum class Update { rebuild, low, refit };
  /// spheres() for a scene whose spheres move (move_spheres) and are committed with `update`.
  static std::unique_ptr<EmbreeScene> moving_spheres(const testing::SphereSet& spheres, Update update, bool user,
                                                     uint32_t build_threads, PeerBuild& build);
  /// Moves sphere idx[k] to centre xyz[3k .. 3k+3) for k < n (untimed), then commits the
  /// geometry and the scene; returns the commit's milliseconds.
  double move_spheres(const uint32_t* idx, const float* xyz, std::size_t n);
  ~EmbreeScene();
  /// Closest hit (or any hit: EmbreeMethod) of rays [0, n) on [0, tmax], one ray per call or
  /// packets of 16 consecutive rays, on `threads` threads taking chunks of rays in turn.
  void trace(const testing::RaySet& rays, std::size_t n, float tmax, EmbreeMethod method, uint32_t threads,
             RayResults& out) const;

  struct Impl;

 private:
  explicit EmbreeScene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// A Bullet btCollisionWorld (btDbvtBroadphase) queried with rayTest and a closest-hit
/// callback. Debian's Bullet is single precision and not thread-safe: one thread only.
class BulletRayWorld {
 public:
  /// One static object with a btBvhTriangleMeshShape (quantized BVH) over a
  /// btTriangleIndexVertexArray sharing an AoS copy of the vertices and the mesh's indices.
  static std::unique_ptr<BulletRayWorld> triangles(const MeshData& mesh, PeerBuild& build);
  /// One object with a btSphereShape per sphere (bytes unknown: 0).
  static std::unique_ptr<BulletRayWorld> spheres(const testing::SphereSet& spheres, PeerBuild& build);
  ~BulletRayWorld();
  /// rayTest from o to o + tmax d for rays [0, n); t = closest hit fraction * tmax.
  void trace(const testing::RaySet& rays, std::size_t n, float tmax, RayResults& out) const;

  struct Impl;

 private:
  explicit BulletRayWorld(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gyro::bench
