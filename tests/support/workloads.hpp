// The workloads of BENCHMARKS.md, generated bit for bit (splitmix64, binary64 arithmetic
// rounded once to binary32), shared by tests, benchmarks and the determinism scenes.
#pragma once

#include "gyro/batch_raycast.hpp"
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

}  // namespace gyro::testing
