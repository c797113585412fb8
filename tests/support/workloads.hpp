// The workloads of BENCHMARKS.md, generated bit for bit (splitmix64, binary64 arithmetic
// rounded once to binary32), shared by tests, benchmarks and the determinism scenes.
#pragma once

#include "gyro/batch_raycast.hpp"
#include "gyro/mesh.hpp"
#include "gyro/shape_arrays.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro::testing {

/// splitmix64 with BENCHMARKS.md's uniform: 24 bits, exact in float and double.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double u() { return static_cast<double>(next() >> 40) * 0x1p-24; }

 private:
  uint64_t state_;
};

struct RaySet {
  std::vector<float> ox, oy, oz, dx, dy, dz;
  std::size_t size() const { return ox.size(); }
  void resize(std::size_t n);
  void push(float oxv, float oyv, float ozv, float dxv, float dyv, float dzv);
  RaysView view() const { return {ox.data(), oy.data(), oz.data(), dx.data(), dy.data(), dz.data(), nullptr, nullptr}; }
  /// fnv1a64 over ox,oy,oz,dx,dy,dz per ray, as BENCHMARKS.md hashes them.
  uint64_t fnv() const;
};

struct SphereSet {
  std::vector<float> cx, cy, cz, r;
  std::size_t size() const { return cx.size(); }
  SpheresView view() const { return {cx.data(), cy.data(), cz.data(), r.data()}; }
  uint64_t fnv() const;
};

struct HitSet {
  std::vector<float> t, nx, ny, nz;
  std::vector<int32_t> primitive;
  explicit HitSet(std::size_t n = 0) { resize(n); }
  void resize(std::size_t n) {
    t.assign(n, 0.0f), nx.assign(n, 0.0f), ny.assign(n, 0.0f), nz.assign(n, 0.0f), primitive.assign(n, 0);
  }
  HitsOut out(bool normals = true) {
    return {t.data(), primitive.data(), normals ? nx.data() : nullptr, normals ? ny.data() : nullptr,
            normals ? nz.data() : nullptr};
  }
};

/// Oriented boxes, SoA, with the orientation matrix R stored row-major (R[3*row + col]);
/// BENCHMARKS.md's convention: column k of R is the box's local axis k.
struct BoxSet {
  std::vector<float> cx, cy, cz, hx, hy, hz;
  std::vector<float> r[9];
  std::size_t size() const { return cx.size(); }
  /// gyro's view: axis u_k is column k of R.
  ObbsView view() const {
    return {cx.data(), cy.data(), cz.data(), hx.data(), hy.data(), hz.data(), r[0].data(), r[3].data(), r[6].data(),
            r[1].data(), r[4].data(), r[7].data(), r[2].data(), r[5].data(), r[8].data()};
  }
};

/// N1: 10^6 pairs of random boxes (seed 4); pair p is box 2p of `a` order and 2p+1, split
/// into the two sets a (even boxes) and b (odd boxes).
struct BoxPairs {
  BoxSet a, b;
  /// fnv1a64 over c[3], h[3], R[9] per box, boxes in generation order (BENCHMARKS.md).
  uint64_t fnv() const;
};
BoxPairs n1_pairs(std::size_t pairs = 1000000);
inline constexpr uint64_t kN1BoxesFnv = 0x88bccf7410be3a03ull;

/// R1 spheres: seed 1, 10,000 spheres in a 100 m cube.
SphereSet r1_spheres(std::size_t count = 10000);
/// R1 rays: seed 2, isotropic directions from origins in the cube; the first `count`.
RaySet r1_rays(std::size_t count = 1000000);

// Check values quoted in BENCHMARKS.md.
inline constexpr uint64_t kR1SpheresFnv = 0x10eb42770d113cf1ull;
inline constexpr uint64_t kR1RaysFnv = 0x849e1c43d71c3f3full;

/// R2 terrain: 512 x 512 vertices on [0, 100]^2 (vertex j*512 + i at x = 100 i/511,
/// z = 100 j/511), 522,242 triangles, two per cell in BENCHMARKS.md's order; normals +y.
inline constexpr uint32_t kR2GridVertices = 512;
MeshData r2_mesh();
/// R2's height y(x, z) in binary64, evaluated as BENCHMARKS.md writes it (the vertices store
/// f32 of it at the grid points).
double r2_height(double x, double z);
/// R2 rays: seed 3, from (ox, 20, oz) towards (tx, -10, tz); every one hits the terrain.
RaySet r2_rays(std::size_t count = 1000000);
/// n slivers: corners a and b around a centre drawn in [0, box]^3 (each coordinate within
/// spread / 2 of it), the third corner on segment ab moved off it by 1e-4 to 1e-3 of |b - a|:
/// most hits take the watertight test's double path (ray_triangle_lanes.hpp).
MeshData sliver_mesh(std::size_t n, SplitMix64& rng, float box, float spread);
/// fnv1a64 over x, y, z per vertex / over the uint32 indices, as BENCHMARKS.md hashes them.
uint64_t mesh_vertices_fnv(const MeshData& mesh);
uint64_t mesh_indices_fnv(const MeshData& mesh);
inline constexpr uint64_t kR2VerticesFnv = 0x83aaa9c151d2a02eull;
inline constexpr uint64_t kR2IndicesFnv = 0x52f75acd6aac20d4ull;
inline constexpr uint64_t kR2RaysFnv = 0x3306ae586b845988ull;
/// Every workload ray of R1, R2 and CAMERA is queried on [0, 1000].
inline constexpr float kRayTmax = 1000.0f;

/// LIDAR (gyro's own workload, no randomness): a spinning 64-channel sensor inside the R2
/// scene. Origin (50, f32(r2_height(50, 50) + 2), 50), 2 m above the terrain (the mesh
/// departs from r2_height by less than 1 cm between grid points). Ray c*64 + k (column
/// c = 0..2047 outer, channel k = 0..63 inner) has elevation e = (-25 + (40*k)/63) degrees
/// and azimuth a = (2*pi*c)/2048, both converted to radians in binary64 as e * (pi / 180), and
/// direction d = (f32(cos e * cos a), f32(sin e), f32(cos e * sin a)) with binary64 libm
/// sin/cos (unit to about 1e-7, not renormalised). Queried on [0, kLidarTmax].
/// The origin lies on the cell diagonals' line x + z = 100, so the columns at azimuth 135
/// and 315 degrees run along shared edges: a watertightness test. Binary64 reference (the
/// bench's grid walk): 129,896 hits, sum t 650,990.56.
inline constexpr uint32_t kLidarChannels = 64, kLidarColumns = 2048;
inline constexpr float kLidarTmax = 120.0f;
RaySet lidar_rays();

/// CAMERA (gyro's own workload, no randomness): one primary ray per pixel of a
/// width x height image from a pinhole camera above the R2 terrain, pitched 30 degrees
/// down, looking along +z, vertical field of view 60 degrees. In binary64:
///   eye = (50, 30, 10), 30deg = pi / 6, forward f = (0, -sin 30deg, cos 30deg), up
///   u = (0, cos 30deg, sin 30deg), right r = (-1, 0, 0) (a right-handed view: +x is on the image's left),
///   th = tan 30deg, aspect = width / height; pixel (px, py), py = 0 the top row, row-major:
///   sx = ((2*(px + 0.5))/width - 1) * th * aspect, sy = (1 - (2*(py + 0.5))/height) * th,
///   w = f + sx*r + sy*u (each component left to right), d = f32(w / |w|),
///   |w| = sqrt((wx*wx + wy*wy) + wz*wz); o = f32(eye) for every ray.
/// The top row looks at the horizon and mostly misses; the centre hits near z = 62.
/// Queried on [0, kRayTmax]. Binary64 reference: 1,283,638 hits, sum t 69,804,288.77.
RaySet camera_rays(uint32_t width = 1920, uint32_t height = 1080);

}  // namespace gyro::testing
