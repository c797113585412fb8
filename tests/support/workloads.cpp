#include "workloads.hpp"

#include "core/state_hash.hpp"

#include <cmath>

namespace gyro::testing {
namespace {
constexpr double kTwoPi = 6.283185307179586;
float f32(double v) { return static_cast<float>(v); }

template <class... Columns> uint64_t fnv_rows(std::size_t n, const Columns&... cols) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < n; ++i) ((h = detail::fnv1a64(&cols[i], sizeof(float), h)), ...);
  return h;
}
}  // namespace

void RaySet::resize(std::size_t n) {
  for (auto* c : {&ox, &oy, &oz, &dx, &dy, &dz}) c->resize(n);
}
void RaySet::push(float a, float b, float c, float d, float e, float f) {
  ox.push_back(a), oy.push_back(b), oz.push_back(c), dx.push_back(d), dy.push_back(e), dz.push_back(f);
}
uint64_t RaySet::fnv() const { return fnv_rows(size(), ox, oy, oz, dx, dy, dz); }
uint64_t SphereSet::fnv() const { return fnv_rows(size(), cx, cy, cz, r); }

SphereSet r1_spheres(std::size_t count) {
  SplitMix64 rng(1);
  SphereSet s;
  for (std::size_t i = 0; i < count; ++i) {
    const double u0 = rng.u(), u1 = rng.u(), u2 = rng.u(), u3 = rng.u();
    s.cx.push_back(f32(100 * u0));
    s.cy.push_back(f32(100 * u1));
    s.cz.push_back(f32(100 * u2));
    s.r.push_back(f32(0.1 + 0.9 * u3));
  }
  return s;
}

RaySet r1_rays(std::size_t count) {
  SplitMix64 rng(2);
  RaySet r;
  for (auto* c : {&r.ox, &r.oy, &r.oz, &r.dx, &r.dy, &r.dz}) c->reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double a = rng.u(), b = rng.u(), c = rng.u(), u = rng.u(), v = rng.u();
    const double z = 1 - 2 * u;
    const double phi = kTwoPi * v;
    const double rad = std::sqrt(1 - z * z);
    r.push(f32(100 * a), f32(100 * b), f32(100 * c), f32(rad * std::cos(phi)), f32(rad * std::sin(phi)), f32(z));
  }
  return r;
}

}  // namespace gyro::testing
