// Mesh checks, bounds, closedness, welding and generators (gyro/mesh.hpp).
//
// Determinism: every sort is on integer keys that include the vertex or edge index as the
// last tie-break (or are whole values), so std::sort's instability never shows; the
// tolerance weld always picks the lowest-index candidate, so the order it visits the
// candidates in cannot change the answer. The generators use gyro::sincos and exact
// integer-to-float arithmetic, so they give the same bits on every platform.
#include "gyro/mesh.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/math_trig.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

namespace gyro {
namespace {

constexpr std::size_t kMaxCount = std::size_t(1) << 31;  // vertex and triangle limit (exclusive)

// The structural half of validate_mesh (no coordinates), reporting through fail() only
// when asked, so that is_closed can use it quietly.
Status check_structure(const MeshData& m, bool report) {
  const std::size_t nv = m.x.size();
  if (m.y.size() != nv || m.z.size() != nv)
    return report ? detail::fail(Status::invalid_count, "mesh vertex columns differ in size: x %zu, y %zu, z %zu", nv,
                                 m.y.size(), m.z.size())
                  : Status::invalid_count;
  if (m.indices.size() % 3 != 0)
    return report ? detail::fail(Status::invalid_count, "mesh has %zu indices, not a multiple of 3", m.indices.size())
                  : Status::invalid_count;
  const std::size_t nt = m.indices.size() / 3;
  if (nt == 0)
    return report ? detail::fail(Status::invalid_count, "mesh has no triangles (%zu vertices)", nv)
                  : Status::invalid_count;
  if (nv >= kMaxCount || nt >= kMaxCount)
    return report ? detail::fail(Status::invalid_count,
                                 "mesh has %zu vertices and %zu triangles; each must be below 2^31", nv, nt)
                  : Status::invalid_count;
  for (std::size_t i = 0; i < m.indices.size(); ++i)
    if (m.indices[i] >= nv)
      return report ? detail::fail(Status::invalid_argument,
                                   "mesh triangle %zu has index %u, not below the vertex count %zu", i / 3,
                                   unsigned(m.indices[i]), nv)
                    : Status::invalid_argument;
  return Status::ok;
}

// Checks a generator's argument; the caller returns an empty mesh on failure.
bool finite_nonnegative(float v) { return detail::is_finite(v) && v >= 0.0f; }

// One axis of a conservative box: the midpoint, then a half extent grown until both
// corners cover lo and hi in float arithmetic (rounding of the midpoint and of the
// difference can otherwise leave a corner an ulp inside). Halving before adding keeps
// lo + hi from overflowing.
void conservative_axis(float lo, float hi, float& center, float& half) {
  const float c = lo * 0.5f + hi * 0.5f;
  float h = hi * 0.5f - lo * 0.5f;
  for (int iter = 0; c + h < hi || c - h > lo; ++iter)
    h = iter < 16 ? std::nextafter(h, std::numeric_limits<float>::infinity())
                  : std::max(h * 2.0f, std::numeric_limits<float>::denorm_min());
  center = c;
  half = h;
}

// Vertex order key for the exact weld: the position's bits, then the index.
struct BitsKey {
  uint32_t x, y, z, index;
  bool operator<(const BitsKey& o) const {
    if (x != o.x) return x < o.x;
    if (y != o.y) return y < o.y;
    if (z != o.z) return z < o.z;
    return index < o.index;
  }
};

// rep[v] for every referenced vertex (its own index for a representative) with exact
// (bit-identical) merging: equal keys sort together and the lowest index leads its run.
void reps_exact(const MeshData& m, const std::vector<uint8_t>& used, std::vector<uint32_t>& rep) {
  std::vector<BitsKey> keys;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v])
      keys.push_back({std::bit_cast<uint32_t>(m.x[v]), std::bit_cast<uint32_t>(m.y[v]), std::bit_cast<uint32_t>(m.z[v]),
                      uint32_t(v)});
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j].x == keys[i].x && keys[j].y == keys[i].y && keys[j].z == keys[i].z)
      rep[keys[j++].index] = keys[i].index;
    i = j;
  }
}

// Greedy tolerance clustering in index order over a grid of cells of side h >= 2 tol.
// Completeness: if |dx| <= tol in float then the exact |dx| <= tol (1 + 2^-24), so the
// exact cell coordinates x / h differ by at most about 0.5; h is also at least
// max|coordinate| * 2^-19, so |x / h| <= 2^19 and the double quotient's rounding is below
// 2^-33. The floors therefore differ by at most 1 and the 27 neighbouring cells hold every
// representative within tolerance. Cells are packed into one uint64 (21 bits per axis,
// offset so that a neighbour's field never leaves [0, 2^21)), sorted, and their
// neighbours found by one merge pass per offset: no hashing, and the answer (the lowest
// index within tolerance) does not depend on any container's layout.
void reps_tolerance(const MeshData& m, const std::vector<uint8_t>& used, float tol, std::vector<uint32_t>& rep) {
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  const std::size_t nv = used.size();
  double max_abs = 0.0;
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v])
      max_abs = std::max({max_abs, double(std::abs(m.x[v])), double(std::abs(m.y[v])), double(std::abs(m.z[v]))});
  const double h = std::max(2.0 * double(tol), max_abs * 0x1p-19);
  const auto field = [h](float c) { return uint64_t(int64_t(std::floor(double(c) / h)) + (int64_t(1) << 20)); };

  std::vector<std::pair<uint64_t, uint32_t>> order;  // (cell, vertex), unique, so sorting is deterministic
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v]) order.push_back({field(m.x[v]) << 42 | field(m.y[v]) << 21 | field(m.z[v]), uint32_t(v)});
  std::sort(order.begin(), order.end());
  std::vector<uint64_t> cells;
  std::vector<uint32_t> cell_of(nv, kNone);
  for (const auto& [key, v] : order) {
    if (cells.empty() || cells.back() != key) cells.push_back(key);
    cell_of[v] = uint32_t(cells.size() - 1);
  }
  order = {};

  // Adding a per-field offset of -1, 0 or +1 keeps the cells' order, so each offset's
  // neighbours are found by walking the sorted cells once.
  const std::size_t nc = cells.size();
  std::vector<uint32_t> neighbour(27 * nc, kNone);
  int slot = 0;
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dz = -1; dz <= 1; ++dz, ++slot) {
        const uint64_t offset = uint64_t(dx * (int64_t(1) << 42) + dy * (int64_t(1) << 21) + dz);
        for (std::size_t i = 0, j = 0; i < nc; ++i) {
          const uint64_t target = cells[i] + offset;
          while (j < nc && cells[j] < target) ++j;
          if (j < nc && cells[j] == target) neighbour[27 * i + std::size_t(slot)] = uint32_t(j);
        }
      }

  // Each cell's representatives as a linked list (head per cell, next per vertex).
  std::vector<uint32_t> head(nc, kNone), next(nv, kNone);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    const std::size_t c = cell_of[v];
    uint32_t best = kNone;
    for (std::size_t k = 0; k < 27; ++k) {
      const uint32_t n = neighbour[27 * c + k];
      if (n == kNone) continue;
      for (uint32_t r = head[n]; r != kNone; r = next[r])
        if (r < best && std::abs(m.x[v] - m.x[r]) <= tol && std::abs(m.y[v] - m.y[r]) <= tol &&
            std::abs(m.z[v] - m.z[r]) <= tol)
          best = r;
    }
    if (best != kNone) {
      rep[v] = best;
    } else {
      rep[v] = uint32_t(v);
      next[v] = head[c];
      head[c] = uint32_t(v);
    }
  }
}

}  // namespace

Status validate_mesh(const MeshData& mesh) {
  GYRO_TRY(check_structure(mesh, true));
  const std::size_t nv = mesh.vertex_count();
  const std::size_t bad =
      std::min({detail::first_non_finite(mesh.x.data(), nv), detail::first_non_finite(mesh.y.data(), nv),
                detail::first_non_finite(mesh.z.data(), nv)});
  if (bad < nv)
    return detail::fail(Status::non_finite, "mesh vertex %zu is not finite: (%g, %g, %g)", bad, double(mesh.x[bad]),
                        double(mesh.y[bad]), double(mesh.z[bad]));
  return Status::ok;
}

AABB mesh_bounds(const MeshData& mesh) {
  const std::size_t nv = mesh.vertex_count();
  if (mesh.y.size() != nv || mesh.z.size() != nv) return {{}, {}};
  const std::size_t ni = mesh.triangle_count() * 3;
  bool any = false;
  vec3 lo, hi;
  for (std::size_t i = 0; i < ni; ++i) {
    const uint32_t v = mesh.indices[i];
    if (v >= nv) continue;
    const vec3 p = mesh.vertex(v);
    lo = any ? min(lo, p) : p;
    hi = any ? max(hi, p) : p;
    any = true;
  }
  if (!any) return {{}, {}};
  AABB box;
  for (int k = 0; k < 3; ++k) conservative_axis(lo[k], hi[k], box.center[k], box.half_extents[k]);
  return box;
}

bool is_closed(const MeshData& mesh) {
  if (check_structure(mesh, false) != Status::ok) return false;
  // One key per directed edge: (smaller index << 32) | (larger index << 1) | (1 if it runs
  // from the larger to the smaller). Indices are below 2^31, so the key is exact; a
  // closed, consistently oriented surface sorts into pairs (k | 0, k | 1).
  std::vector<uint64_t> keys(mesh.indices.size());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const uint64_t a = mesh.indices[3 * t + e], b = mesh.indices[3 * t + (e + 1) % 3];
      if (a == b) return false;
      keys[3 * t + e] = a < b ? (a << 32) | (b << 1) : (b << 32) | (a << 1) | 1u;
    }
  std::sort(keys.begin(), keys.end());
  // Walking in pairs: a third use of an edge would start the next pair with k | 1.
  for (std::size_t i = 0; i < keys.size(); i += 2)
    if (i + 1 >= keys.size() || (keys[i] & 1u) != 0 || keys[i + 1] != (keys[i] | 1u)) return false;
  return true;
}

MeshData weld_vertices(const MeshData& mesh, float tolerance) {
  if (!detail::is_finite(tolerance) || !(tolerance >= 0.0f)) {
    detail::fail(Status::invalid_argument, "weld_vertices: tolerance %g is not a finite value >= 0", double(tolerance));
    return {};
  }
  if (validate_mesh(mesh) != Status::ok) return {};
  const std::size_t nv = mesh.vertex_count();
  std::vector<uint8_t> used(nv, 0);
  for (const uint32_t v : mesh.indices) used[v] = 1;
  std::vector<uint32_t> rep(nv, 0);
  if (tolerance == 0.0f)
    reps_exact(mesh, used, rep);
  else
    reps_tolerance(mesh, used, tolerance, rep);

  // Representatives keep their original order; every other vertex maps to its one.
  MeshData out;
  std::vector<uint32_t> new_index(nv, 0);
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v] && rep[v] == v) {
      new_index[v] = uint32_t(out.vertex_count());
      out.add_vertex(mesh.vertex(v));
    }
  out.indices.resize(mesh.indices.size());
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) out.indices[i] = new_index[rep[mesh.indices[i]]];
  return out;
}

MeshData make_box_mesh(const vec3& half_extents) {
  if (!finite_nonnegative(half_extents.x) || !finite_nonnegative(half_extents.y) ||
      !finite_nonnegative(half_extents.z)) {
    detail::fail(Status::invalid_argument, "make_box_mesh: half extents (%g, %g, %g) must be finite and >= 0",
                 double(half_extents.x), double(half_extents.y), double(half_extents.z));
    return {};
  }
  MeshData m;
  // Vertex v has bit k set when its coordinate on axis k is +half_extents[k].
  for (uint32_t v = 0; v < 8; ++v)
    m.add_vertex({v & 1 ? half_extents.x : -half_extents.x, v & 2 ? half_extents.y : -half_extents.y,
                  v & 4 ? half_extents.z : -half_extents.z});
  // Face (axis k, side s) walks its corners around the in-face axes u = k+1, w = k+2: the
  // walk (0,0) (1,0) (1,1) (0,1) turns about u x w = +axis k, so the -k face walks it back.
  for (int k = 0; k < 3; ++k)
    for (uint32_t s = 0; s < 2; ++s) {
      const uint32_t u = 1u << ((k + 1) % 3), w = 1u << ((k + 2) % 3), base = s << k;
      std::array<uint32_t, 4> q{base, base | u, base | u | w, base | w};
      if (s == 0) std::swap(q[1], q[3]);
      m.add_triangle(q[0], q[1], q[2]);
      m.add_triangle(q[0], q[2], q[3]);
    }
  return m;
}

MeshData make_sphere_mesh(float radius, int stacks, int slices) {
  if (!finite_nonnegative(radius) || stacks < 2 || stacks > 4096 || slices < 3 || slices > 4096) {
    detail::fail(Status::invalid_argument,
                 "make_sphere_mesh: needs a finite radius >= 0 (got %g), stacks in [2, 4096] (got %d) and slices in "
                 "[3, 4096] (got %d)",
                 double(radius), stacks, slices);
    return {};
  }
  const uint32_t ns = uint32_t(slices), rings = uint32_t(stacks) - 1;
  MeshData m;
  m.add_vertex({0.0f, radius, 0.0f});
  for (uint32_t i = 1; i <= rings; ++i) {
    float st, ct;
    sincos(kPi * float(i) / float(stacks), &st, &ct);
    for (uint32_t j = 0; j < ns; ++j) {
      float sp, cp;
      sincos(kTwoPi * float(j) / float(slices), &sp, &cp);
      m.add_vertex({radius * st * cp, radius * ct, radius * st * sp});
    }
  }
  m.add_vertex({0.0f, -radius, 0.0f});
  const uint32_t north = 0, south = 1 + rings * ns;
  const auto ring = [ns](uint32_t i, uint32_t j) { return 1 + (i - 1) * ns + j % ns; };
  // Going down (t) then around (p) turns about the inward normal, so each quad a = (i, j),
  // b = (i + 1, j), c = (i, j + 1), d = (i + 1, j + 1) is split as (a, c, b), (c, d, b).
  for (uint32_t j = 0; j < ns; ++j) m.add_triangle(north, ring(1, j + 1), ring(1, j));
  for (uint32_t i = 1; i < rings; ++i)
    for (uint32_t j = 0; j < ns; ++j) {
      m.add_triangle(ring(i, j), ring(i, j + 1), ring(i + 1, j));
      m.add_triangle(ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
    }
  for (uint32_t j = 0; j < ns; ++j) m.add_triangle(ring(rings, j), ring(rings, j + 1), south);
  return m;
}

MeshData make_grid_mesh(int cells_x, int cells_z, float cell_size, GridHeightFn height, void* context) {
  if (cells_x < 1 || cells_x > 16384 || cells_z < 1 || cells_z > 16384 || !detail::is_finite(cell_size) ||
      !(cell_size > 0.0f)) {
    detail::fail(Status::invalid_argument,
                 "make_grid_mesh: needs cells_x and cells_z in [1, 16384] (got %d, %d) and a finite cell_size > 0 "
                 "(got %g)",
                 cells_x, cells_z, double(cell_size));
    return {};
  }
  const uint32_t nx = uint32_t(cells_x) + 1, nz = uint32_t(cells_z) + 1;
  MeshData m;
  m.x.reserve(std::size_t(nx) * nz), m.y.reserve(std::size_t(nx) * nz), m.z.reserve(std::size_t(nx) * nz);
  // i - cells / 2 is a small multiple of 0.5, exact in float, so the grid is symmetric.
  const float half_x = 0.5f * float(cells_x), half_z = 0.5f * float(cells_z);
  for (uint32_t j = 0; j < nz; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      const float x = (float(i) - half_x) * cell_size, z = (float(j) - half_z) * cell_size;
      const float y = height ? height(x, z, context) : 0.0f;
      if (!detail::is_finite(y)) {
        detail::fail(Status::non_finite, "make_grid_mesh: height(%g, %g) = %g is not finite", double(x), double(z),
                     double(y));
        return {};
      }
      m.add_vertex({x, y, z});
    }
  m.indices.reserve(std::size_t(6) * uint32_t(cells_x) * uint32_t(cells_z));
  // (c - a) x (b - a) = z x x = +y: a = (i, j), b = (i + 1, j), c = (i, j + 1), d = (i + 1, j + 1).
  for (uint32_t j = 0; j + 1 < nz; ++j)
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      m.add_triangle(a, c, b);
      m.add_triangle(b, c, d);
    }
  return m;
}

}  // namespace gyro
