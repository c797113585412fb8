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

BoxPairs n1_pairs(std::size_t pairs) {
  SplitMix64 rng(4);
  BoxPairs out;
  for (std::size_t k = 0; k < 2 * pairs; ++k) {
    BoxSet& s = (k % 2 == 0) ? out.a : out.b;
    double u[9];
    for (double& v : u) v = rng.u();
    s.cx.push_back(f32(4 * u[0])), s.cy.push_back(f32(4 * u[1])), s.cz.push_back(f32(4 * u[2]));
    s.hx.push_back(f32(0.2 + 0.8 * u[3])), s.hy.push_back(f32(0.2 + 0.8 * u[4])), s.hz.push_back(f32(0.2 + 0.8 * u[5]));
    const double s1 = std::sqrt(1 - u[6]), s2 = std::sqrt(u[6]), a = kTwoPi * u[7], b = kTwoPi * u[8];
    const double x = s1 * std::sin(a), y = s1 * std::cos(a), z = s2 * std::sin(b), w = s2 * std::cos(b);
    const double R[9] = {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w),
                         2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w),
                         2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)};
    for (int e = 0; e < 9; ++e) s.r[e].push_back(f32(R[e]));
  }
  return out;
}

uint64_t BoxPairs::fnv() const {
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t p = 0; p < a.size(); ++p) {
    for (const BoxSet* s : {&a, &b}) {
      const float v[15] = {s->cx[p], s->cy[p], s->cz[p], s->hx[p], s->hy[p], s->hz[p], s->r[0][p], s->r[1][p],
                           s->r[2][p], s->r[3][p], s->r[4][p], s->r[5][p], s->r[6][p], s->r[7][p], s->r[8][p]};
      h = detail::fnv1a64(v, sizeof v, h);
    }
  }
  return h;
}

}  // namespace gyro::testing
