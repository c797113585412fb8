#include "workloads.hpp"

#include "core/state_hash.hpp"

#include <cmath>

namespace gyro::testing {
namespace {
constexpr double kTwoPi = 6.283185307179586;
constexpr double kPi = 3.141592653589793;
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

double r2_height(double x, double z) {
  return ((5 * std::sin(0.1 * x)) * std::cos(0.13 * z)) + (2 * std::sin((0.7 * x) + (0.3 * z)));
}

MeshData sliver_mesh(std::size_t n, SplitMix64& rng, float box, float spread) {
  MeshData m;
  for (std::size_t t = 0; t < n; ++t) {
    const vec3 c{float(box * rng.u()), float(box * rng.u()), float(box * rng.u())};
    const vec3 a = c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * spread;
    const vec3 b = c + vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * spread;
    const float f = float(rng.u()), w = float(1e-4 + 9e-4 * rng.u()) * length(b - a);
    const vec3 off{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)};
    const uint32_t v = uint32_t(m.vertex_count());
    m.add_vertex(a), m.add_vertex(b), m.add_vertex(a + (b - a) * f + off * w);
    m.add_triangle(v, v + 1, v + 2);
  }
  return m;
}

MeshData r2_mesh() {
  constexpr uint32_t n = kR2GridVertices;
  MeshData m;
  for (auto* c : {&m.x, &m.y, &m.z}) c->reserve(std::size_t(n) * n);
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const double x = (100.0 * i) / 511, z = (100.0 * j) / 511;
      m.x.push_back(f32(x)), m.y.push_back(f32(r2_height(x, z))), m.z.push_back(f32(z));
    }
  }
  m.indices.reserve(std::size_t(6) * (n - 1) * (n - 1));
  for (uint32_t j = 0; j + 1 < n; ++j) {
    for (uint32_t i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      m.add_triangle(a, c, b);
      m.add_triangle(b, c, d);
    }
  }
  return m;
}

RaySet r2_rays(std::size_t count) {
  SplitMix64 rng(3);
  RaySet r;
  for (auto* c : {&r.ox, &r.oy, &r.oz, &r.dx, &r.dy, &r.dz}) c->reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const float ox = f32(100 * rng.u()), oz = f32(100 * rng.u()), tx = f32(100 * rng.u()), tz = f32(100 * rng.u());
    const double ex = double(tx) - double(ox), ey = -30.0, ez = double(tz) - double(oz);
    const double len = std::sqrt((ex * ex + ey * ey) + ez * ez);
    r.push(ox, 20.0f, oz, f32(ex / len), f32(ey / len), f32(ez / len));
  }
  return r;
}

uint64_t mesh_vertices_fnv(const MeshData& m) { return fnv_rows(m.vertex_count(), m.x, m.y, m.z); }

uint64_t mesh_indices_fnv(const MeshData& m) {
  return detail::fnv1a64(m.indices.data(), m.indices.size() * sizeof(uint32_t));
}

RaySet lidar_rays() {
  RaySet r;
  r.resize(std::size_t(kLidarChannels) * kLidarColumns);
  const float oy = f32(r2_height(50, 50) + 2);
  for (uint32_t c = 0; c < kLidarColumns; ++c) {
    const double a = (kTwoPi * c) / kLidarColumns;
    for (uint32_t k = 0; k < kLidarChannels; ++k) {
      const double e = (-25 + (40.0 * k) / (kLidarChannels - 1)) * (kPi / 180);
      const std::size_t i = std::size_t(c) * kLidarChannels + k;
      r.ox[i] = 50.0f, r.oy[i] = oy, r.oz[i] = 50.0f;
      r.dx[i] = f32(std::cos(e) * std::cos(a)), r.dy[i] = f32(std::sin(e)), r.dz[i] = f32(std::cos(e) * std::sin(a));
    }
  }
  return r;
}

RaySet camera_rays(uint32_t width, uint32_t height) {
  RaySet r;
  r.resize(std::size_t(width) * height);
  const double half = kPi / 6, s = std::sin(half), c = std::cos(half), th = std::tan(half);
  const double aspect = double(width) / height;
  const double f[3] = {0, -s, c}, u[3] = {0, c, s}, rt[3] = {-1, 0, 0};
  for (uint32_t py = 0; py < height; ++py) {
    const double sy = (1 - (2 * (py + 0.5)) / height) * th;
    for (uint32_t px = 0; px < width; ++px) {
      const double sx = ((2 * (px + 0.5)) / width - 1) * th * aspect;
      double w[3];
      for (int k = 0; k < 3; ++k) w[k] = f[k] + sx * rt[k] + sy * u[k];
      const double len = std::sqrt((w[0] * w[0] + w[1] * w[1]) + w[2] * w[2]);
      const std::size_t i = std::size_t(py) * width + px;
      r.ox[i] = 50.0f, r.oy[i] = 30.0f, r.oz[i] = 10.0f;
      r.dx[i] = f32(w[0] / len), r.dy[i] = f32(w[1] / len), r.dz[i] = f32(w[2] / len);
    }
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
