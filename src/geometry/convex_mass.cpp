// Mass properties of a solid convex hull (density 1): volume, centroid, inertia about the
// centroid, and the principal frame.
//
// Integration: the hull is split into tetrahedra (r, a, b, c), one per triangle of each
// face's fan (a = the face's first corner), with r the average of the hull's vertices, a
// point inside the hull. So every tetrahedron's signed volume is positive for a valid hull,
// and the coordinates are small (relative to r), which keeps the second moments free of the
// cancellation a far-away origin would cause. This is the divergence theorem over the face
// triangles, written as a sum of exact per-tetrahedron integrals: for the tetrahedron with
// corners 0, A, B, C and D = det[A B C] (6 times its volume),
//   volume          = D / 6
//   integral of x   = D / 24 * (A + B + C)
//   integral of xx^T = D / 120 * (S S^T + A A^T + B B^T + C C^T),  S = A + B + C
// (the canonical tetrahedron's values, carried over by the linear map [A B C]).
//
// Principal frame: cyclic Jacobi rotations on the symmetric 3x3 tensor, pairs (0,1), (0,2),
// (1,2) in that order each sweep, at most kMaxSweeps sweeps, stopping when the off-diagonal
// is below kTolerance of the diagonal. An off-diagonal element that is negligible next to
// its two diagonal elements is set to zero instead of rotated, so a tensor that is diagonal
// up to rounding (a box, a cube) keeps the hull's own axes exactly.
//
// Everything runs in binary64 with + - * / sqrt, abs and comparisons in a fixed order,
// and is rounded to float once at the end: the result is bit-identical everywhere.
#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/convex.hpp"

#include <cmath>
#include <cstddef>

namespace gyro {
namespace {

struct D3 {
  double x, y, z;
};
inline D3 sub(const vec3& a, const D3& b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }
inline double det3(const D3& a, const D3& b, const D3& c) {
  return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
}

constexpr int kMaxSweeps = 32;         // 3x3 Jacobi converges quadratically: 4 to 6 sweeps in practice
constexpr double kTolerance = 1e-15;   // off-diagonal small next to the diagonal: converged
constexpr double kNegligible = 1e-15;  // |a_pq| below this times |a_pp| + |a_qq|: treated as zero
constexpr double kSameMoment = 1e-9;   // moments this close (relative) keep their axes' order

// The structure a face fan walk relies on: offsets in range and increasing, faces with at
// least three corners, corner indices naming vertices, finite vertices.
bool well_formed(const ConvexHull& h) {
  const std::size_t faces = h.face_count(), verts = h.vertices.size();
  if (faces < 4 || verts < 4 || h.face_start.size() != faces + 1 || h.face_start[0] != 0 ||
      h.face_start[faces] != h.face_vertices.size())
    return false;
  for (std::size_t f = 0; f < faces; ++f)
    if (h.face_start[f + 1] < h.face_start[f] + 3) return false;
  for (uint32_t v : h.face_vertices)
    if (v >= verts) return false;
  for (const vec3& v : h.vertices)
    if (!is_finite(v)) return false;
  return true;
}

// One Jacobi rotation in the (p, q) plane that zeroes a[p][q]; v accumulates the rotations
// (its columns are the eigenvectors). The angle is the smaller root (Golub and Van Loan,
// the symmetric Schur decomposition), so each rotation moves the matrix as little as
// possible and the sweep converges.
void rotate(double a[3][3], double v[3][3], int p, int q) {
  const double apq = a[p][q];
  if (apq == 0.0) return;
  if (std::abs(apq) <= kNegligible * (std::abs(a[p][p]) + std::abs(a[q][q]))) {
    a[p][q] = a[q][p] = 0.0;
    return;
  }
  const double tau = (a[q][q] - a[p][p]) / (2.0 * apq);
  // t = tan(angle) = sign(tau) / (|tau| + sqrt(1 + tau^2)); for a huge tau, 1 / (2 tau).
  double t;
  if (std::abs(tau) > 1e150) {
    t = 0.5 / tau;
  } else {
    const double mag = 1.0 / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
    t = tau < 0.0 ? -mag : mag;
  }
  const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
  const int r = 3 - p - q;  // the third index
  const double app = a[p][p], aqq = a[q][q], arp = a[r][p], arq = a[r][q];
  a[p][p] = app - t * apq;
  a[q][q] = aqq + t * apq;
  a[p][q] = a[q][p] = 0.0;
  a[r][p] = a[p][r] = c * arp - s * arq;
  a[r][q] = a[q][r] = s * arp + c * arq;
  for (int k = 0; k < 3; ++k) {
    const double vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

// Eigenvalues w and eigenvectors (columns of v) of the symmetric a (a is destroyed).
void jacobi(double a[3][3], double w[3], double v[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    const double diag = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]);
    if (!(off > kTolerance * diag)) break;
    rotate(a, v, 0, 1);
    rotate(a, v, 0, 2);
    rotate(a, v, 1, 2);
  }
  for (int i = 0; i < 3; ++i) w[i] = a[i][i];
}

}  // namespace

Status convex_hull_mass(const ConvexHull& hull, ConvexMass& out) {
  if (!well_formed(hull))
    return detail::fail(Status::invalid_argument, "convex hull mass: the hull is empty or malformed (%zu faces, %zu vertices)",
                        hull.face_count(), hull.vertices.size());

  // Reference point: the vertex average (inside a hull with volume).
  D3 r{0.0, 0.0, 0.0};
  for (const vec3& p : hull.vertices) r = {r.x + double(p.x), r.y + double(p.y), r.z + double(p.z)};
  const double inv_n = 1.0 / double(hull.vertices.size());
  r = {r.x * inv_n, r.y * inv_n, r.z * inv_n};

  // Sums of D, D * S and D * (S S^T + A A^T + B B^T + C C^T), scaled at the end.
  double sum_d = 0.0, first[3] = {0.0, 0.0, 0.0}, second[3][3] = {};
  for (std::size_t f = 0; f < hull.face_count(); ++f) {
    const uint32_t b = hull.face_start[f], e = hull.face_start[f + 1];
    const D3 a = sub(hull.vertices[hull.face_vertices[b]], r);
    for (uint32_t k = b + 1; k + 1 < e; ++k) {
      const D3 p = sub(hull.vertices[hull.face_vertices[k]], r);
      const D3 q = sub(hull.vertices[hull.face_vertices[k + 1]], r);
      const double d = det3(a, p, q);
      const double s[3] = {a.x + p.x + q.x, a.y + p.y + q.y, a.z + p.z + q.z};
      const double ca[3] = {a.x, a.y, a.z}, cp[3] = {p.x, p.y, p.z}, cq[3] = {q.x, q.y, q.z};
      sum_d += d;
      for (int i = 0; i < 3; ++i) {
        first[i] += d * s[i];
        for (int j = i; j < 3; ++j) second[i][j] += d * (s[i] * s[j] + ca[i] * ca[j] + cp[i] * cp[j] + cq[i] * cq[j]);
      }
    }
  }
  const double volume = sum_d / 6.0;
  if (!(volume > 0.0) || !std::isfinite(volume))
    return detail::fail(Status::invalid_argument, "convex hull mass: volume %g is not > 0", volume);

  // Centroid offset g from r, and the covariance sum over the hull of y y^T about the
  // centroid (y = x - centroid): about r minus volume * g g^T (parallel axis).
  const double g[3] = {first[0] / 24.0 / volume, first[1] / 24.0 / volume, first[2] / 24.0 / volume};
  double cov[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) cov[i][j] = cov[j][i] = second[i][j] / 120.0 - volume * g[i] * g[j];
  // Inertia = trace(cov) * identity - cov.
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  double inertia[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inertia[i][j] = (i == j ? trace : 0.0) - cov[i][j];

  double a[3][3], w[3], v[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = inertia[i][j];
  jacobi(a, w, v);

  // Ascending moments by three compare-and-swaps; moments within kSameMoment of each other
  // stay in the order Jacobi left them (the hull's axes for an already diagonal tensor).
  int order[3] = {0, 1, 2};
  const double scale = std::abs(w[0]) + std::abs(w[1]) + std::abs(w[2]);
  auto sort2 = [&](int i, int j) {
    if (w[order[j]] < w[order[i]] - kSameMoment * scale) {
      const int t = order[i];
      order[i] = order[j], order[j] = t;
    }
  };
  sort2(0, 1), sort2(1, 2), sort2(0, 1);

  // Axes: column order[k] of v. Sign: the largest-magnitude component positive (the lowest
  // index among equals); then the last axis flips if needed so the frame is right-handed.
  double axes[3][3];
  for (int k = 0; k < 3; ++k) {
    int big = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i][order[k]]) > std::abs(v[big][order[k]])) big = i;
    const double sign = v[big][order[k]] < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < 3; ++i) axes[k][i] = sign * v[i][order[k]];
  }
  const D3 e0{axes[0][0], axes[0][1], axes[0][2]}, e1{axes[1][0], axes[1][1], axes[1][2]},
      e2{axes[2][0], axes[2][1], axes[2][2]};
  if (det3(e0, e1, e2) < 0.0)
    for (int i = 0; i < 3; ++i) axes[2][i] = -axes[2][i];

  ConvexMass m;
  m.volume = float(volume);
  m.centroid = {float(r.x + g[0]), float(r.y + g[1]), float(r.z + g[2])};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.inertia.m[i][j] = float(inertia[i][j]), m.principal_axes.m[i][j] = float(axes[i][j]);
  // Near-equal moments may be out of order by up to kSameMoment: level them so the
  // reported moments never decrease.
  float prev = float(w[order[0]]);
  for (int k = 0; k < 3; ++k) {
    const float mk = float(w[order[k]]);
    prev = mk < prev ? prev : mk;
    m.principal_moments[k] = prev;
  }
  if (!is_finite(m.centroid) || !is_finite(m.principal_moments) || !detail::is_finite(m.volume))
    return detail::fail(Status::invalid_argument, "convex hull mass: the result overflows float");
  out = m;
  return Status::ok;
}

}  // namespace gyro
