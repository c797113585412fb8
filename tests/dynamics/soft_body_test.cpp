// Springs, cloth and soft bodies (gyro/soft_body.hpp, issue 6): each model against closed
// forms and a double-precision reference, the stiffness sweep, collisions without tunnelling,
// soft cubes and mesh bodies, particle joints, the bad-input contract, copies, the world's
// soft-body stage and bit-identical results across thread counts and SIMD levels.
//
// Numbers are printed (printf) and recorded (RecordProperty) so a run's log is the table the
// issue asks for; every bound below says where it comes from.
#include "gyro/soft_body.hpp"

#include "gyro/math.hpp"
#include "gyro/mesh.hpp"
#include "gyro/runtime.hpp"
#include "gyro/triangle_mesh.hpp"
#include "gyro/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace gyro {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

const char* model_name(SoftModel m) { return m == SoftModel::xpbd ? "xpbd" : "springs"; }

uint32_t cidx(const SoftBody& b, uint32_t ix, uint32_t iz) {
  uint32_t i = ~0u;
  EXPECT_EQ(b.cloth_index(ix, iz, &i), Status::ok) << ix << "," << iz;
  return i;
}

vec3 pos(const SoftBody& b, uint32_t i) {
  vec3 p;
  EXPECT_EQ(b.get_position(i, &p), Status::ok);
  return p;
}

vec3 vel(const SoftBody& b, uint32_t i) {
  vec3 v;
  EXPECT_EQ(b.get_velocity(i, &v), Status::ok);
  return v;
}

bool all_finite(const SoftBody& b) {
  const SoftView v = b.view();
  for (std::size_t i = 0; i < v.count; ++i)
    if (!std::isfinite(v.px[i]) || !std::isfinite(v.py[i]) || !std::isfinite(v.pz[i]) || !std::isfinite(v.vx[i]) ||
        !std::isfinite(v.vy[i]) || !std::isfinite(v.vz[i]))
      return false;
  return true;
}

// Kinetic plus gravitational energy of the free particles (pinned ones never move, so they
// add a constant), in double, from the view: independent of SoftStats.
double mechanical_energy(const SoftBody& b, double g = 9.81) {
  const SoftView v = b.view();
  double e = 0.0;
  for (std::size_t i = 0; i < v.count; ++i) {
    if (!(v.inverse_mass[i] > 0.0f)) continue;
    const double m = 1.0 / double(v.inverse_mass[i]);
    const double vx = v.vx[i], vy = v.vy[i], vz = v.vz[i];
    e += m * (0.5 * (vx * vx + vy * vy + vz * vz) + g * double(v.py[i]));
  }
  return e;
}

double max_speed(const SoftBody& b) {
  const SoftView v = b.view();
  double s = 0.0;
  for (std::size_t i = 0; i < v.count; ++i)
    s = std::max(s, std::sqrt(double(v.vx[i]) * v.vx[i] + double(v.vy[i]) * v.vy[i] + double(v.vz[i]) * v.vz[i]));
  return s;
}

void record(const std::string& key, double value) {
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

// ======================================================================= 1. oscillator
//
// The API has no builder for an arbitrary two-particle body, so the oscillator is a 2 x 2
// cloth (1 m x 1 m): corners a = (0,0), b = (1,0), c = (0,1) pinned, f = (1,1) free. f's
// springs are the shear diagonal to a (rest sqrt 2) and the structural edges to b and c
// (rest 1); the other springs join pinned particles only. The pinned corners are moved onto
// the x axis behind f (a at 0, b at -0.3, c at -0.6, all distinct so no spring has zero
// length), f is put on the x axis and starts at rest: every force on f is along x, so f
// moves on the x axis under a sum of collinear linear springs, an exact 1-D harmonic
// oscillator. The structural family is 1e-5 N/m against the diagonal's k = 4 pi^2 N/m (and
// is still included exactly in K and x*), so the diagonal is the spring: m = 1 kg, omega =
// 2 pi (period 1 s), amplitude 0.1 m, gravity 0, 3 periods at dt = 1/60 in 1, 4 or 16
// sub-steps (h = 1/60, 1/240, 1/960).
//
// Expected, per model:
//  - springs (the book's explicit Hooke springs, one sub-step = kick and drift): symplectic
//    Euler. Its positions follow the Stormer-Verlet recurrence but from a start that is off
//    by O(h^2), which puts a sine component of amplitude A omega h / 2 on them: positions are
//    first order, |x - x_exact| <~ A (omega h / 2 + omega T (omega h)^2 / 24). Energy
//    (1/2 m v^2 + 1/2 K (x - x*)^2 with the reported velocity) is not conserved exactly but
//    stays in a band of relative half-width omega h / 2 (the shadow Hamiltonian differs by
//    h omega^2 x v / 2), with no secular drift.
//  - xpbd, one iteration: for one linear constraint with compliance 1/(k h^2), XPBD's update
//    x = x~ - w C / (w + alpha~) is exactly backward Euler, (x' - x*) (1 + (omega h)^2) =
//    x - x* + h v, v' = (x' - x) / h. So x(t) must match that recurrence (computed here in
//    double) to rounding, and the energy must never grow (backward Euler contracts the
//    norm (v, omega x) every sub-step): the amplitude decays, by (1 + (omega h)^2)^(-N/2).
struct OscResult {
  double omega_h = 0, max_err = 0, energy_band = 0, energy_drift = 0, energy_end = 0, max_dev_be = 0;
  double max_energy_increase = 0, max_off_axis = 0;
  bool finite = true;
};

OscResult run_oscillator(SoftModel model, uint32_t substeps) {
  OscResult r;
  const float k_f = float(4.0 * kPi * kPi), eps_f = 1.0e-5f;
  ClothDef def;
  def.nx = def.nz = 2;
  def.size_x = def.size_z = 1.0f;
  def.particle_mass = 1.0f;
  def.bend = false;
  def.structural = {eps_f, 0.0f};
  def.shear = {k_f, 0.0f};
  SoftBody b;
  SoftSettings s;
  s.model = model;
  s.substeps = substeps;
  s.gravity = {0.0f, 0.0f, 0.0f};
  EXPECT_EQ(b.set_settings(s), Status::ok);
  EXPECT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
  const uint32_t ia = cidx(b, 0, 0), ib = cidx(b, 1, 0), ic = cidx(b, 0, 1), f = cidx(b, 1, 1);
  // Rest lengths as the builder saw them: distances of the initial (float) positions.
  const vec3 pa = pos(b, ia), pb = pos(b, ib), pc = pos(b, ic), pf = pos(b, f);
  const auto dist = [](vec3 p, vec3 q) {
    const double dx = double(p.x) - q.x, dy = double(p.y) - q.y, dz = double(p.z) - q.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  const double rest_a = dist(pa, pf), rest_b = dist(pb, pf), rest_c = dist(pc, pf);
  for (uint32_t i : {ia, ib, ic}) EXPECT_EQ(b.pin(i), Status::ok);
  EXPECT_EQ(b.set_position(ia, {0.0f, 0.0f, 0.0f}), Status::ok);
  EXPECT_EQ(b.set_position(ib, {-0.3f, 0.0f, 0.0f}), Status::ok);
  EXPECT_EQ(b.set_position(ic, {-0.6f, 0.0f, 0.0f}), Status::ok);
  const double k = k_f, eps = eps_f, m = 1.0;
  const double K = k + 2.0 * eps;
  // b at -0.3: length x + 0.3, force -eps (x + 0.3 - rest_b); likewise c at -0.6.
  const double xs = (k * rest_a + eps * (rest_b - double(0.3f)) + eps * (rest_c - double(0.6f))) / K;
  const float x0 = float(xs + 0.1);
  EXPECT_EQ(b.set_position(f, {x0, 0.0f, 0.0f}), Status::ok);
  EXPECT_EQ(b.set_velocity(f, {0.0f, 0.0f, 0.0f}), Status::ok);
  const double A = double(x0) - xs, omega = std::sqrt(K / m);
  const float dt = 1.0f / 60.0f;
  const double h = double(dt) / substeps;
  r.omega_h = omega * h;
  const double E0 = 0.5 * K * A * A;
  double xbe = x0, vbe = 0.0, e_prev = E0;
  const int steps = 180, per_period = 60;
  double first_sum = 0, last_sum = 0;
  for (int n = 1; n <= steps; ++n) {
    if (b.step(dt) != Status::ok) {
      ADD_FAILURE() << "step failed";
      r.finite = false;
      return r;
    }
    for (uint32_t j = 0; j < substeps; ++j) {  // backward Euler in double
      const double xt = xbe + h * vbe;
      const double xn = xs + (xt - xs) / (1.0 + omega * omega * h * h);
      vbe = (xn - xbe) / h;
      xbe = xn;
    }
    const vec3 p = pos(b, f), v = vel(b, f);
    if (!is_finite(p) || !is_finite(v)) {
      r.finite = false;
      return r;
    }
    const double t = n * double(dt);
    const double exact = xs + A * std::cos(omega * t);
    r.max_err = std::max(r.max_err, std::abs(double(p.x) - exact) / A);
    r.max_dev_be = std::max(r.max_dev_be, std::abs(double(p.x) - xbe) / A);
    r.max_off_axis = std::max({r.max_off_axis, std::abs(double(p.y)), std::abs(double(p.z))});
    const double e = 0.5 * m * double(v.x) * v.x + 0.5 * K * (double(p.x) - xs) * (double(p.x) - xs);
    r.energy_band = std::max(r.energy_band, std::abs(e / E0 - 1.0));
    r.max_energy_increase = std::max(r.max_energy_increase, (e - e_prev) / E0);
    e_prev = e;
    if (n <= per_period) first_sum += e;
    if (n > steps - per_period) last_sum += e;
    r.energy_end = e / E0;
  }
  r.energy_drift = (last_sum - first_sum) / (per_period * E0);
  return r;
}

TEST(SoftSpringOscillator, MatchesAnalyticSolutionPerModelAndStep) {
  const uint32_t substeps[] = {1, 4, 16};
  std::printf("\n  spring-mass oscillator: omega = 2 pi, A = 0.1 m, T = 3 s (3 periods), dt = 1/60\n");
  std::printf("  %-8s %6s %8s %12s %12s %12s %12s %12s\n", "model", "h", "omega h", "max|x-x*|/A",
              "|dE|/E0 max", "drift/E0", "E_end/E0", "dev vs BE/A");
  for (SoftModel model : {SoftModel::springs, SoftModel::xpbd}) {
    double err[3] = {};
    for (int i = 0; i < 3; ++i) {
      const OscResult r = run_oscillator(model, substeps[i]);
      err[i] = r.max_err;
      std::printf("  %-8s 1/%-4u %8.4f %12.3e %12.3e %12.3e %12.4f %12.3e\n", model_name(model), 60 * substeps[i],
                  r.omega_h, r.max_err, r.energy_band, r.energy_drift, r.energy_end,
                  model == SoftModel::xpbd ? r.max_dev_be : 0.0);
      const std::string key = std::string("osc_") + model_name(model) + "_h1_" + std::to_string(60 * substeps[i]);
      record(key + "_max_err_rel", r.max_err);
      record(key + "_energy_band", r.energy_band);
      record(key + "_energy_drift", r.energy_drift);
      ASSERT_TRUE(r.finite) << model_name(model) << " substeps " << substeps[i];
      // The motion is 1-D by construction: every force on f is along x.
      EXPECT_LT(r.max_off_axis, 1e-6) << model_name(model);
      const double wh = r.omega_h, T = 3.0, wT = 2.0 * kPi * T;
      if (model == SoftModel::springs) {
        // First-order positions (A omega h / 2 plus the phase drift), 20% slack, plus a
        // rounding floor of 3e-5 m (float positions ~1.5 m over 2880 sub-steps) = 3e-4 A.
        EXPECT_LE(r.max_err, 1.2 * (wh / 2 + wT * wh * wh / 24) + 3e-4) << "substeps " << substeps[i];
        // Bounded energy: band of half-width omega h / 2 (50% slack) and no drift.
        EXPECT_LE(r.energy_band, 0.75 * wh + 1e-4) << "substeps " << substeps[i];
        EXPECT_LE(std::abs(r.energy_drift), 0.25 * wh + 1e-4) << "substeps " << substeps[i];
      } else {
        // XPBD on one spring is backward Euler: same trajectory up to rounding. XPBD's
        // velocity is (x' - x) / h, so a position rounding of ~ulp(1.5 m) = 1.2e-7 m becomes
        // a velocity error of ulp / h, i.e. ulp / (omega h) in the oscillator's norm; over N
        // sub-steps these add like a random walk: sqrt(N) ulp / (omega h), which the
        // contraction never amplifies. Bound: that (about 3.4 sigma) plus 1e-4 A.
        const double N = 180.0 * substeps[i], ulp = 1.1920929e-7;
        EXPECT_LE(r.max_dev_be, 1e-4 + std::sqrt(N) * ulp / (wh * 0.1)) << "substeps " << substeps[i];
        // Energy never grows (per step, up to rounding), and decays overall.
        EXPECT_LE(r.max_energy_increase, 1e-5) << "substeps " << substeps[i];
        EXPECT_LE(r.energy_end, 1.0) << "substeps " << substeps[i];
        // ... by about the backward-Euler factor (1 + (omega h)^2)^(-N): within 1%.
        const double predicted = std::pow(1.0 + wh * wh, -double(180 * substeps[i]));
        EXPECT_NEAR(r.energy_end, predicted, 0.01 + 0.05 * predicted) << "substeps " << substeps[i];
      }
    }
    // Convergence as the sub-step shrinks 16x: first order, ~16x for springs; xpbd's error
    // saturates near A at h = 1/60, so only over 4x there.
    if (model == SoftModel::springs) { EXPECT_LT(err[2], err[0] / 8) << "springs"; }
    else { EXPECT_LT(err[2], err[0] / 4) << "xpbd"; }
    EXPECT_LT(err[1], err[0]) << model_name(model);
    EXPECT_LT(err[2], err[1]) << model_name(model);
  }
}

// ======================================================================= 2. hanging cloth
//
// A 16 x 16 cloth, 2 m x 2 m, 0.05 kg per particle, pinned along both edges z = -1 and
// z = +1 (a hammock): its sag comes from the springs' stretch (the cloth's rest length is
// exactly the span), so the sag measures the stiffness the solver delivers (about 0.2 m
// here; a cable estimate gives d^3 = 3 W L^3 / (64 EA)). Unlike a cloth hung from one edge
// (whose drop is mostly its own length) or from two corners (which buckles and can settle in
// either of two wrinkled shapes), the hammock's equilibrium is unique: every spring along z is
// in tension.
//
// The reference is the static equilibrium of the same springs (the documented topology:
// structural, both shear diagonals, bend two apart; rest lengths from the initial positions)
// in double precision, by Newton's method on the total potential energy with a banded
// Cholesky factorisation (the Hessian's transverse terms are clamped at 0 for compressed
// springs, so every step descends; the gradient is exact, so the fixed point is exact) to a
// residual force under 1e-8 N.
struct RefSpring {
  uint32_t a, b;
  double k, rest;
};

std::vector<RefSpring> cloth_springs(const SoftBody& body, const ClothDef& def) {
  std::vector<RefSpring> out;
  const SoftView v = body.view();
  const auto add = [&](uint32_t ix0, uint32_t iz0, uint32_t ix1, uint32_t iz1, double k) {
    const uint32_t a = cidx(body, ix0, iz0), b = cidx(body, ix1, iz1);
    const double dx = double(v.px[b]) - v.px[a], dy = double(v.py[b]) - v.py[a], dz = double(v.pz[b]) - v.pz[a];
    out.push_back({a, b, k, std::sqrt(dx * dx + dy * dy + dz * dz)});
  };
  for (uint32_t z = 0; z < def.nz; ++z)
    for (uint32_t x = 0; x < def.nx; ++x) {
      if (x + 1 < def.nx) add(x, z, x + 1, z, def.structural.stiffness);
      if (z + 1 < def.nz) add(x, z, x, z + 1, def.structural.stiffness);
      if (x + 1 < def.nx && z + 1 < def.nz) {
        add(x, z, x + 1, z + 1, def.shear.stiffness);
        add(x + 1, z, x, z + 1, def.shear.stiffness);
      }
      if (def.bend && x + 2 < def.nx) add(x, z, x + 2, z, def.bend_constants.stiffness);
      if (def.bend && z + 2 < def.nz) add(x, z, x, z + 2, def.bend_constants.stiffness);
    }
  return out;
}

// Static equilibrium: positions p (3 per particle, in/out), masses, pinned flags; dof order
// follows `order` (grid order, so the band is ~3 * 2 nx wide). Returns the final residual.
double solve_equilibrium(std::vector<double>& p, const std::vector<double>& mass, const std::vector<bool>& pinned,
                         const std::vector<uint32_t>& order, const std::vector<RefSpring>& springs, double g) {
  const std::size_t np = mass.size();
  std::vector<int> slot(np, -1);
  int nfree = 0;
  for (uint32_t i : order)
    if (!pinned[i]) slot[i] = nfree++;
  const std::size_t n = std::size_t(nfree) * 3;
  std::size_t bw = 2;
  for (const RefSpring& s : springs)
    if (slot[s.a] >= 0 && slot[s.b] >= 0) bw = std::max<std::size_t>(bw, 3 * std::size_t(std::abs(slot[s.a] - slot[s.b])) + 2);
  const std::size_t W = bw + 1;
  const auto energy = [&](const std::vector<double>& q) {
    double e = 0;
    for (const RefSpring& s : springs) {
      const double dx = q[3 * s.b] - q[3 * s.a], dy = q[3 * s.b + 1] - q[3 * s.a + 1], dz = q[3 * s.b + 2] - q[3 * s.a + 2];
      const double l = std::sqrt(dx * dx + dy * dy + dz * dz) - s.rest;
      e += 0.5 * s.k * l * l;
    }
    for (std::size_t i = 0; i < np; ++i)
      if (!pinned[i]) e += mass[i] * g * q[3 * i + 1];
    return e;
  };
  std::vector<double> grad(n), H(n * W), L(n * W), delta(n), trial;
  double residual = 0;
  double lambda = 0;
  for (int it = 0; it < 200; ++it) {
    std::fill(grad.begin(), grad.end(), 0.0);
    std::fill(H.begin(), H.end(), 0.0);
    const auto hadd = [&](int si, int sj, int ci, int cj, double v) {  // lower band entry
      std::size_t r = std::size_t(si) * 3 + ci, c = std::size_t(sj) * 3 + cj;
      if (c > r) std::swap(r, c);
      H[r * W + (r - c)] += v;
    };
    for (std::size_t i = 0; i < np; ++i)
      if (slot[i] >= 0) grad[std::size_t(slot[i]) * 3 + 1] += mass[i] * g;
    for (const RefSpring& s : springs) {
      const double d[3] = {p[3 * s.b] - p[3 * s.a], p[3 * s.b + 1] - p[3 * s.a + 1], p[3 * s.b + 2] - p[3 * s.a + 2]};
      const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double nrm[3] = {d[0] / l, d[1] / l, d[2] / l};
      const double f = s.k * (l - s.rest);
      const double trans = std::max(0.0, s.k * (1.0 - s.rest / l));
      double blk[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) blk[r][c] = (s.k - trans) * nrm[r] * nrm[c] + (r == c ? trans : 0.0);
      const int sa = slot[s.a], sb = slot[s.b];
      for (int c = 0; c < 3; ++c) {
        if (sa >= 0) grad[std::size_t(sa) * 3 + c] -= f * nrm[c];
        if (sb >= 0) grad[std::size_t(sb) * 3 + c] += f * nrm[c];
      }
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          if (sa >= 0 && (std::size_t(sa) * 3 + r) >= (std::size_t(sa) * 3 + c)) hadd(sa, sa, r, c, blk[r][c]);
          if (sb >= 0 && (std::size_t(sb) * 3 + r) >= (std::size_t(sb) * 3 + c)) hadd(sb, sb, r, c, blk[r][c]);
          if (sa >= 0 && sb >= 0) hadd(sa, sb, r, c, -blk[r][c]);
        }
    }
    residual = 0;
    for (double v : grad) residual = std::max(residual, std::abs(v));
    if (residual < 1e-9) break;
    // Factor H + lambda I (banded Cholesky); raise lambda until it is positive definite.
    for (;;) {
      bool ok = true;
      for (std::size_t j = 0; j < n && ok; ++j) {
        double d = H[j * W] + lambda;
        const std::size_t k0 = j > bw ? j - bw : 0;
        for (std::size_t k = k0; k < j; ++k) d -= L[j * W + (j - k)] * L[j * W + (j - k)];
        if (!(d > 0)) {
          ok = false;
          break;
        }
        L[j * W] = std::sqrt(d);
        for (std::size_t i = j + 1; i < std::min(n, j + bw + 1); ++i) {
          double v = H[i * W + (i - j)];
          const std::size_t kk = i > bw ? i - bw : 0;
          for (std::size_t k = std::max(kk, k0); k < j; ++k) v -= L[i * W + (i - k)] * L[j * W + (j - k)];
          L[i * W + (i - j)] = v / L[j * W];
        }
      }
      if (ok) break;
      lambda = lambda > 0 ? lambda * 4 : 1e-6;
    }
    for (std::size_t i = 0; i < n; ++i) {  // forward: L y = -g
      double v = -grad[i];
      for (std::size_t k = i > bw ? i - bw : 0; k < i; ++k) v -= L[i * W + (i - k)] * delta[k];
      delta[i] = v / L[i * W];
    }
    for (std::size_t ii = n; ii-- > 0;) {  // back: L^T x = y
      double v = delta[ii];
      for (std::size_t k = ii + 1; k < std::min(n, ii + bw + 1); ++k) v -= L[k * W + (k - ii)] * delta[k];
      delta[ii] = v / L[ii * W];
    }
    double slope = 0;
    for (std::size_t i = 0; i < n; ++i) slope += grad[i] * delta[i];
    // Backtracking line search far from the solution; near it (forces under 1e-3 N) the
    // full Newton step is taken, since energy differences there are below rounding.
    const double e0 = energy(p);
    double t = 1.0;
    for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
      trial = p;
      for (std::size_t i = 0; i < np; ++i)
        if (slot[i] >= 0)
          for (int c = 0; c < 3; ++c) trial[3 * i + c] += t * delta[std::size_t(slot[i]) * 3 + c];
      if (residual < 1e-3 || energy(trial) <= e0 + 1e-4 * t * slope || ls == 39) break;
    }
    p = trial;
    lambda *= 0.25;
    if (lambda < 1e-9) lambda = 0;
  }
  return residual;
}

TEST(ClothHanging, SagMatchesDoubleEquilibriumAndConvergesWithSubsteps) {
  ClothDef def;
  def.nx = def.nz = 16;
  def.size_x = def.size_z = 2.0f;
  def.particle_mass = 0.05f;
  def.structural = {1.0e3f, 0.0f};
  def.shear = {1.0e3f, 0.0f};
  def.bend_constants = {1.0e2f, 0.0f};
  const double g = 9.81;  // the settings' default gravity (float 9.81 is within 1e-7)

  // Reference.
  SoftBody proto;
  ASSERT_EQ(SoftBody::make_cloth(def, &proto), Status::ok);
  const std::vector<RefSpring> springs = cloth_springs(proto, def);
  // The documented topology is the body's: structural 2*15*16, shear 2*15*15, bend 2*14*16.
  ASSERT_EQ(proto.spring_count(), springs.size());
  const std::size_t np = proto.particle_count();
  ASSERT_EQ(np, 256u);
  std::vector<double> p(3 * np), mass(np, double(def.particle_mass));
  std::vector<bool> pinned(np, false);
  std::vector<uint32_t> order;
  {
    const SoftView v = proto.view();
    for (std::size_t i = 0; i < np; ++i) p[3 * i] = v.px[i], p[3 * i + 1] = v.py[i], p[3 * i + 2] = v.pz[i];
    for (uint32_t z = 0; z < def.nz; ++z)
      for (uint32_t x = 0; x < def.nx; ++x) order.push_back(cidx(proto, x, z));
    for (uint32_t x = 0; x < def.nx; ++x) pinned[cidx(proto, x, 0)] = pinned[cidx(proto, x, def.nz - 1)] = true;
    // Start from a parabola so the z springs are in tension (the flat pose is singular in y).
    for (std::size_t i = 0; i < np; ++i)
      if (!pinned[i]) p[3 * i + 1] = -0.15 * (1.0 - p[3 * i + 2] * p[3 * i + 2]);
  }
  const double residual = solve_equilibrium(p, mass, pinned, order, springs, g);
  ASSERT_LT(residual, 1e-8) << "reference did not converge";
  double ref_min_y = 0;
  for (std::size_t i = 0; i < np; ++i) ref_min_y = std::min(ref_min_y, p[3 * i + 1]);
  const double ref_sag = -ref_min_y;  // the pins are at y = 0
  ASSERT_GT(ref_sag, 0.05);
  std::printf("\n  hammock cloth 16x16, 2 m, k = 1e3/1e3/1e2 N/m, 0.05 kg: reference sag %.6f m (residual %.1e N)\n",
              ref_sag, residual);
  std::printf("  %9s %12s %12s %14s %12s %12s\n", "substeps", "sag (m)", "sag err", "max |p-p_ref|", "max |v|",
              "moved 0.5s");
  record("hang_ref_sag_m", ref_sag);

  const uint32_t substeps[] = {4, 16, 64};
  double err[3];
  for (int k = 0; k < 3; ++k) {
    SoftBody b;
    SoftSettings s;
    s.substeps = substeps[k];
    s.damping = 6.0f;  // 1/s: settles the ~8 rad/s swing in 4 s; damping changes no equilibrium
    ASSERT_EQ(b.set_settings(s), Status::ok);
    ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
    for (uint32_t x = 0; x < def.nx; ++x) {
      ASSERT_EQ(b.pin(cidx(b, x, 0)), Status::ok);
      ASSERT_EQ(b.pin(cidx(b, x, def.nz - 1)), Status::ok);
    }
    std::vector<float> before;
    for (int n = 0; n < 240; ++n) {
      ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
      if (n == 209) before.assign(b.view().py, b.view().py + np);
    }
    ASSERT_TRUE(all_finite(b));
    const SoftView v = b.view();
    double moved = 0;  // over the last 0.5 s
    for (std::size_t i = 0; i < np; ++i) moved = std::max(moved, std::abs(double(v.py[i]) - before[i]));
    double min_y = 0, dev = 0;
    for (std::size_t i = 0; i < np; ++i) {
      min_y = std::min(min_y, double(v.py[i]));
      const double dx = v.px[i] - p[3 * i], dy = v.py[i] - p[3 * i + 1], dz = v.pz[i] - p[3 * i + 2];
      dev = std::max(dev, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    EXPECT_NEAR(b.stats().min_y, min_y, 1e-6);
    const double sag = -min_y, vmax = max_speed(b);
    err[k] = std::abs(sag - ref_sag) / ref_sag;
    std::printf("  %9u %12.6f %11.3f%% %14.3e %12.3e %12.3e\n", substeps[k], sag, 100 * err[k], dev, vmax, moved);
    record("hang_sag_err_substeps_" + std::to_string(substeps[k]), err[k]);
    // At rest: the swing has decayed by e^-12 (damping 6/s plus XPBD's own); no particle
    // moved more than 1 mm (0.4% of the sag, a fifth of the 2% tolerance) in the last 0.5 s.
    // (max |v| is not the witness: XPBD's v = dx / h turns position rounding into ~n ulp / h
    // of jitter, measured 9e-3 m/s at 64 sub-steps, 7e-4 at 16, 3e-5 at 4, and the jitter
    // moves particles by a few 0.1 mm.)
    EXPECT_LT(moved, 1e-3) << "substeps " << substeps[k];
  }
  // XPBD's stiffness error is O(k h^2 / m): 16x smaller per 4x sub-steps; at 64 sub-steps
  // (k_sum h^2 / m ~ 0.01) the sag is within 2% of the converged reference.
  EXPECT_LT(err[2], 0.02);
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
}

// ======================================================================= 3. stiffness sweep
//
// An 8 x 8 cloth, 1 m x 1 m, 1 kg per particle, pinned at two corners of one edge, starts
// flat at rest and falls (and swings) for 2 s; every family has stiffness k, no damping.
//
// Criterion for "non-growing energy". Nothing adds energy, so the true total energy
// KE + PE + elastic can only stay or fall. The elastic term of an XPBD state is not
// 1/2 k C^2 (with few iterations XPBD leaves constraint errors larger than k would: at
// k = 1e7 its "1/2 k C^2" can exceed the whole fall's energy while nothing is wrong), so the
// witness is the mechanical part E_mech = KE + PE (free particles, from the view): because
// elastic >= 0, a non-growing total forces E_mech(t) <= E_mech(0) for all t. Growth is
// reported as max_t (E_mech(t) - E_mech(0)) / E_ref with E_ref = M g L (the energy of
// the whole cloth dropping its own size, 608 J).
//  - xpbd (dissipative, backward-Euler-like) must be finite with growth <= 1e-3 for every k.
//  - springs (symplectic, explicit) keep a bounded energy error ~ omega h / 2 of the energy
//    in the stiff modes, so "stable" means finite with growth < 1 (never gains the fall's
//    energy); "exploded" means non-finite or growth > 10. Stability needs omega_max h < 2,
//    omega_max^2 between 4 k / m (a chain) and ~20 k / m (the grid with shear and bend):
//    1 sub-step (h = 1/60): stable for k <= 100 (< m / (5 h^2) = 720), explodes for
//    k >= 1e4 (> m / h^2 = 3600); 16 sub-steps (h = 1/960): stable for k <= 1e4 (< 1.8e5),
//    explodes at 1e7 (> 9.2e5). k between is reported only.
TEST(SoftSpringStiffness, SweepXpbdStableSpringsExplodeWhenStiff) {
  struct Config {
    SoftModel model;
    uint32_t substeps;
  };
  const Config configs[] = {{SoftModel::xpbd, SoftSettings{}.substeps}, {SoftModel::springs, 1}, {SoftModel::springs, 16}};
  std::printf("\n  stiffness sweep: 8x8 cloth, 1 m, 1 kg/particle, two corners pinned, dt = 1/60, 2 s\n");
  std::printf("  %10s %-8s %9s %7s %14s %12s %12s\n", "k (N/m)", "model", "substeps", "finite", "growth/E_ref",
              "max strain", "verdict");
  for (double kd = 10.0; kd <= 1.0e7 * 1.01; kd *= 10.0) {
    const float k = float(kd);
    for (const Config& c : configs) {
      ClothDef def;
      def.nx = def.nz = 8;
      def.size_x = def.size_z = 1.0f;
      def.particle_mass = 1.0f;
      def.structural = def.shear = def.bend_constants = {k, 0.0f};
      SoftBody b;
      SoftSettings s;
      s.model = c.model;
      s.substeps = c.substeps;
      ASSERT_EQ(b.set_settings(s), Status::ok);
      ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
      ASSERT_EQ(b.pin(cidx(b, 0, 0)), Status::ok);
      ASSERT_EQ(b.pin(cidx(b, 7, 0)), Status::ok);
      const double e0 = mechanical_energy(b), e_ref = 62.0 * 9.81 * 1.0;
      double growth = -kInf;
      bool finite = true;
      Status st = Status::ok;
      for (int n = 0; n < 120 && finite; ++n) {
        st = b.step(1.0f / 60.0f);  // an exploded state may be refused; it counts as non-finite
        finite = st == Status::ok && all_finite(b);
        if (finite) growth = std::max(growth, (mechanical_energy(b) - e0) / e_ref);
      }
      if (!finite) growth = kInf;
      const double strain = finite ? b.stats().max_strain : kInf;
      const bool stable = c.model == SoftModel::xpbd ? finite && growth <= 1e-3 : finite && growth < 1.0;
      const bool exploded = !finite || growth > 10.0;
      const char* verdict = stable ? "stable" : exploded ? "EXPLODED" : "unstable";
      std::printf("  %10.0e %-8s %9u %7s %14.3e %12.3e %12s\n", kd, model_name(c.model), c.substeps,
                  finite ? "yes" : "no", growth, strain, verdict);
      record("sweep_" + std::string(model_name(c.model)) + "_s" + std::to_string(c.substeps) + "_k" +
                 std::to_string(int(std::lround(std::log10(kd)))),
             growth);
      if (st != Status::ok) std::printf("  (step returned %s)\n", status_name(st));
      if (c.model == SoftModel::xpbd) {
        EXPECT_TRUE(finite) << "xpbd k " << kd;
        EXPECT_LE(growth, 1e-3) << "xpbd k " << kd;
      } else if (c.substeps == 1) {
        if (kd <= 100.0) { EXPECT_TRUE(stable) << "springs x1 k " << kd << " growth " << growth; }
        if (kd >= 1.0e4) { EXPECT_TRUE(exploded) << "springs x1 k " << kd << " growth " << growth; }
      } else {
        if (kd <= 1.0e4) { EXPECT_TRUE(stable) << "springs x16 k " << kd << " growth " << growth; }
        if (kd >= 1.0e7) { EXPECT_TRUE(exploded) << "springs x16 k " << kd << " growth " << growth; }
      }
    }
  }
}

// ======================================================================= 4. collisions

// A 16 x 16 cloth (2 m, 0.05 kg per particle, default stiff xpbd) dropped 0.4 m onto a
// sphere of radius 0.6 drapes over it: at the end of every step no particle is inside the
// sphere (the header: particles end `thickness` outside; checked at half of it), and the
// centre rests on top. Friction 1 (all tangential motion at a contact removed): the header's
// friction removes a share of the motion per sub-step and has no static regime, so with 0.3
// a centred cloth creeps off the sphere's top within 2 s (measured) and "settled" would mean
// "on the floor".
TEST(ClothCollision, DrapedOverSphereNoParticleInside) {
  ClothDef def;
  def.nx = def.nz = 16;
  def.size_x = def.size_z = 2.0f;
  def.center = {0.0f, 1.0f, 0.0f};
  def.particle_mass = 0.05f;
  SoftBody b;
  SoftSettings settings;
  settings.friction = 1.0f;
  ASSERT_EQ(b.set_settings(settings), Status::ok);
  ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
  const Sphere sphere{{0.0f, 0.0f, 0.0f}, 0.6f};
  uint32_t ci = 99;
  ASSERT_EQ(b.add_collider(sphere, &ci), Status::ok);
  EXPECT_EQ(ci, 0u);
  EXPECT_EQ(b.collider_count(), 1u);
  const float thickness = b.settings().thickness;
  double min_gap = 1e9;
  for (int n = 0; n < 120; ++n) {
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    const SoftView v = b.view();
    for (std::size_t i = 0; i < v.count; ++i) {
      const double dx = v.px[i], dy = v.py[i], dz = v.pz[i];
      min_gap = std::min(min_gap, std::sqrt(dx * dx + dy * dy + dz * dz) - sphere.radius);
    }
  }
  ASSERT_TRUE(all_finite(b));
  std::printf("\n  cloth over sphere: min distance to the surface over 120 steps %.3e m (thickness %.3g)\n", min_gap,
              double(thickness));
  record("sphere_min_gap_m", min_gap);
  EXPECT_GE(min_gap, 0.5 * thickness);
  // A particle of the middle four rests on the top of the sphere (the cloth did not slide off).
  const vec3 top = pos(b, cidx(b, 8, 8));
  EXPECT_GT(top.y, 0.5f);
  EXPECT_LT(length(top) - sphere.radius, 0.1f);
}

// Local coordinates of p in a box whose orientation rows are its axes.
vec3 box_local(const OBB& box, vec3 p) {
  const vec3 d = p - box.center;
  vec3 out;
  for (int r = 0; r < 3; ++r) out[r] = box.orientation.m[r][0] * d.x + box.orientation.m[r][1] * d.y + box.orientation.m[r][2] * d.z;
  return out;
}

// A 12 x 12 cloth (1.6 m) falling at 20 m/s onto a 0.02 m thin plate larger than the cloth
// (2.2 m x 2.2 m; so no particle can reach the underside around an edge), level (AABB) and
// tilted 0.3 rad (OBB), with 1 sub-step (0.33 m per sub-step: 16 plate thicknesses) and the
// default 16 (0.021 m per sub-step: about one thickness). No particle may ever be inside the
// plate or below it within its footprint: that is where a tunnelled particle ends up.
// The projection response has no restitution: the stiff cloth (1e6 N/m, landing flat, so
// storing almost no elastic energy) must not bounce: after the impact no particle rises
// more than 0.1 m above its lowest height (a bounce of v would rise v^2 / 2g).
TEST(ClothCollision, FastClothOnThinBoxDoesNotTunnelOrBounce) {
  const float a = 0.3f;
  const mat3 tilt = from_rows({std::cos(a), std::sin(a), 0.0f}, {-std::sin(a), std::cos(a), 0.0f}, {0.0f, 0.0f, 1.0f});
  const OBB boxes[] = {{{0.0f, 0.0f, 0.0f}, {1.1f, 0.01f, 1.1f}, mat3::identity()},
                       {{0.0f, 0.0f, 0.0f}, {1.1f, 0.01f, 1.1f}, tilt}};
  for (int kind = 0; kind < 2; ++kind) {
    for (uint32_t substeps : {1u, 16u}) {
      ClothDef def;
      def.nx = def.nz = 12;
      def.size_x = def.size_z = 1.6f;
      def.center = {0.0f, 0.6f, 0.0f};
      def.particle_mass = 0.05f;
      SoftBody b;
      SoftSettings s;
      s.substeps = substeps;
      ASSERT_EQ(b.set_settings(s), Status::ok);
      ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
      for (uint32_t i = 0; i < b.particle_count(); ++i) ASSERT_EQ(b.set_velocity(i, {0.0f, -20.0f, 0.0f}), Status::ok);
      const OBB& box = boxes[kind];
      uint32_t ci;
      if (kind == 0) { ASSERT_EQ(b.add_collider(AABB{box.center, box.half_extents}, &ci), Status::ok); }
      else { ASSERT_EQ(b.add_collider(box, &ci), Status::ok); }
      int tunnelled = 0, inside = 0;
      double min_top_gap = 1e9, rise = 0;
      std::vector<double> lowest(b.particle_count(), 1e9);
      for (int n = 0; n < 30; ++n) {
        ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
        const SoftView v = b.view();
        for (std::size_t i = 0; i < v.count; ++i) {
          const vec3 l = box_local(box, {v.px[i], v.py[i], v.pz[i]});
          if (std::abs(l.x) < box.half_extents.x && std::abs(l.z) < box.half_extents.z) {
            if (std::abs(l.y) < box.half_extents.y) ++inside;
            if (l.y <= -box.half_extents.y) ++tunnelled;
            min_top_gap = std::min(min_top_gap, double(l.y) - box.half_extents.y);
          }
          lowest[i] = std::min(lowest[i], double(l.y));
          rise = std::max(rise, double(l.y) - lowest[i]);
        }
      }
      ASSERT_TRUE(all_finite(b));
      std::printf("  thin %s, %2u sub-steps: tunnelled %d, inside %d, min gap above the top %.3e m, rise %.3f m\n",
                  kind == 0 ? "AABB" : "OBB ", substeps, tunnelled, inside, min_top_gap, rise);
      const std::string what = std::string(kind ? "OBB" : "AABB") + " substeps " + std::to_string(substeps);
      EXPECT_EQ(tunnelled, 0) << what;
      EXPECT_EQ(inside, 0) << what;
      EXPECT_GE(min_top_gap, 0.0) << what;
      EXPECT_LT(min_top_gap, 0.05) << what;  // it was stopped on the plate
      EXPECT_LT(rise, 0.1) << what;          // and did not bounce
    }
  }
}

// The cloth (13 x 13, 1.6 m, 20 m/s) falls onto the edge of a thin vertical blade (an OBB
// 0.02 m thick in x, 2 m tall, 2 m long, top at y = 0): the middle column lands on the
// 0.02 m wide edge. No particle may be inside the blade at a step's end, and none may pass
// from one side of the blade to the other beside it (x changing sign while -1.9 < y < -0.01
// and |z| < 0.98 at both step ends, i.e. neither over the top nor under the bottom nor
// round the ends): the cloth folds over the edge, it is not cut through it.
TEST(ClothCollision, FastClothOnBladeEdgeDoesNotTunnel) {
  for (uint32_t substeps : {1u, 16u}) {
    ClothDef def;
    def.nx = def.nz = 13;
    def.size_x = def.size_z = 1.6f;
    def.center = {0.0f, 0.4f, 0.0f};
    def.particle_mass = 0.05f;
    SoftBody b;
    SoftSettings s;
    s.substeps = substeps;
    ASSERT_EQ(b.set_settings(s), Status::ok);
    ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
    for (uint32_t i = 0; i < b.particle_count(); ++i) ASSERT_EQ(b.set_velocity(i, {0.0f, -20.0f, 0.0f}), Status::ok);
    const OBB blade{{0.0f, -1.0f, 0.0f}, {0.01f, 1.0f, 1.0f}, mat3::identity()};
    uint32_t ci;
    ASSERT_EQ(b.add_collider(blade, &ci), Status::ok);
    int inside = 0, crossed = 0;
    std::vector<float> px(b.particle_count()), py(b.particle_count());
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = b.view().px[i], py[i] = b.view().py[i];
    for (int n = 0; n < 30; ++n) {
      ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
      const SoftView v = b.view();
      for (std::size_t i = 0; i < v.count; ++i) {
        const vec3 l = box_local(blade, {v.px[i], v.py[i], v.pz[i]});
        if (std::abs(l.x) < blade.half_extents.x && std::abs(l.y) < blade.half_extents.y &&
            std::abs(l.z) < blade.half_extents.z)
          ++inside;
        if (py[i] < -0.01f && v.py[i] < -0.01f && py[i] > -1.9f && v.py[i] > -1.9f && std::abs(v.pz[i]) < 0.98f &&
            ((px[i] < -0.01f && v.px[i] > 0.01f) || (px[i] > 0.01f && v.px[i] < -0.01f)))
          ++crossed;
        px[i] = v.px[i], py[i] = v.py[i];
      }
    }
    ASSERT_TRUE(all_finite(b));
    std::printf("  blade edge, %2u sub-steps: inside %d, crossed %d\n", substeps, inside, crossed);
    EXPECT_EQ(inside, 0) << "substeps " << substeps;
    EXPECT_EQ(crossed, 0) << "substeps " << substeps;
  }
}

// A two-sided triangle-mesh collider: a 2 m x 2 m tent y = 0.2 - 0.3 |x| (the kink on a grid
// line, so the triangulated surface is exactly that function), cloth falling at 20 m/s.
// Every particle over the mesh stays on its upper side.
float tent(float x, float, void*) { return 0.2f - 0.3f * std::abs(x); }

TEST(ClothCollision, TriangleMeshColliderStopsFastCloth) {
  TriangleMesh mesh;
  ASSERT_EQ(TriangleMesh::create(make_grid_mesh(8, 8, 0.25f, tent), mesh), Status::ok);
  for (uint32_t substeps : {1u, 16u}) {
    ClothDef def;
    def.nx = def.nz = 12;
    def.size_x = def.size_z = 1.5f;
    def.center = {0.0f, 0.6f, 0.0f};
    def.particle_mass = 0.05f;
    SoftBody b;
    SoftSettings s;
    s.substeps = substeps;
    ASSERT_EQ(b.set_settings(s), Status::ok);
    ASSERT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
    for (uint32_t i = 0; i < b.particle_count(); ++i) ASSERT_EQ(b.set_velocity(i, {0.0f, -20.0f, 0.0f}), Status::ok);
    uint32_t ci;
    ASSERT_EQ(b.add_collider(mesh, &ci), Status::ok);
    double min_gap = 1e9;
    for (int n = 0; n < 40; ++n) {
      ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
      const SoftView v = b.view();
      for (std::size_t i = 0; i < v.count; ++i)
        if (std::abs(v.px[i]) < 0.98f && std::abs(v.pz[i]) < 0.98f)
          min_gap = std::min(min_gap, double(v.py[i]) - double(tent(v.px[i], 0, nullptr)));
    }
    ASSERT_TRUE(all_finite(b));
    std::printf("  tent mesh, %2u sub-steps: min height above the surface %.3e m\n", substeps, min_gap);
    record("mesh_min_gap_s" + std::to_string(substeps), min_gap);
    EXPECT_GE(min_gap, -1e-4) << "substeps " << substeps;
    EXPECT_LT(min_gap, 0.05) << "substeps " << substeps;  // it landed on the mesh
    // The header: a particle ends `thickness` outside the surface (spheres and boxes do: 0.010
    // m measured). IMPLEMENTATION FAILURE (reported): on the mesh the gap is 4.5e-6 m
    // (1 sub-step) and 8.0e-6 m (16): the thickness is not kept for mesh colliders.
    EXPECT_GE(min_gap, 0.5 * b.settings().thickness) << "substeps " << substeps;
  }
}

// ======================================================================= 5. soft bodies

// The appendix's soft cube (8 particles, 28 springs, k = 1e4 N/m, 1 kg corners, 0.5 m) dropped
// 0.75 m onto a plane: it never goes below the plane, comes to rest, and its deformation under
// its own weight stays small: the top's 39 N on a vertical stiffness of ~9e4 N/m compresses it
// ~0.4 mm (strain ~1e-3); bound: 1% strain, height within 1%.
TEST(SoftBodyCube, DroppedOnPlaneRestsWithBoundedDeformation) {
  SoftCubeDef def;
  def.center = {0.0f, 1.0f, 0.0f};
  def.half_extent = 0.25f;
  // Damped springs (b = 40 N s/m, ~0.2 of critical 2 sqrt(k m)): an undamped elastic cube
  // bounces back with the energy its springs stored in the impact (correctly: measured 0.6 m
  // after 3 s), so "comes to rest" needs internal damping.
  def.structural.damping = def.shear.damping = def.bend.damping = 40.0f;
  SoftBody b;
  ASSERT_EQ(SoftBody::make_cube(def, &b), Status::ok);
  EXPECT_EQ(b.particle_count(), 8u);
  EXPECT_EQ(b.spring_count(), 28u);
  uint32_t ci;
  ASSERT_EQ(b.add_collider(Plane{{0.0f, 1.0f, 0.0f}, 0.0f}, &ci), Status::ok);
  double min_y = 1e9;
  for (int n = 0; n < 180; ++n) {
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    min_y = std::min(min_y, b.stats().min_y);
  }
  ASSERT_TRUE(all_finite(b));
  const SoftStats st = b.stats();
  const SoftView v = b.view();
  double top = -1e9, bottom = 1e9;
  for (std::size_t i = 0; i < v.count; ++i) top = std::max(top, double(v.py[i])), bottom = std::min(bottom, double(v.py[i]));
  std::printf("\n  soft cube on a plane: min y %.3e, height %.5f m, max strain %.3e, KE %.3e J, max |v| %.3e\n", min_y,
              top - bottom, st.max_strain, st.kinetic_energy, max_speed(b));
  record("cube_max_strain", st.max_strain);
  EXPECT_GE(min_y, -1e-4);
  // IMPLEMENTATION FAILURE (reported, not a test problem): the resting contact never comes
  // to rest. With the springs damped (b = 40) or not, the cube lying on the plane runs a
  // limit cycle of period ~75 steps (1.25 s): its min y wanders 0.0102..0.0110 m while the
  // reported velocities grow to 0.16 m/s downward and reset, KE up to 0.05 J (measured at
  // step 180: max |v| 0.125 m/s, KE 0.032 J).
  EXPECT_LT(max_speed(b), 0.01);
  EXPECT_LT(st.max_strain, 0.01);
  EXPECT_NEAR(top - bottom, 0.5, 0.005);
  EXPECT_LT(bottom, 0.05);  // it landed
}

// Signed volume enclosed by triangles over the body's particles.
double enclosed_volume(const SoftBody& b) {
  const SoftView v = b.view();
  double vol = 0;
  for (std::size_t t = 0; t < v.triangle_count; ++t) {
    const uint32_t i = v.triangles[3 * t], j = v.triangles[3 * t + 1], k = v.triangles[3 * t + 2];
    const double ax = v.px[i], ay = v.py[i], az = v.pz[i], bx = v.px[j], by = v.py[j], bz = v.pz[j];
    const double cx = v.px[k], cy = v.py[k], cz = v.pz[k];
    vol += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6.0;
  }
  return std::abs(vol);
}

struct IcoMesh {
  std::vector<float> v;
  std::vector<uint32_t> t;
};

IcoMesh icosahedron(float radius, vec3 c) {
  const float p = 1.6180339887f, s = radius / std::sqrt(1.0f + p * p);
  const float base[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                             {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  IcoMesh m;
  for (auto& q : base) m.v.insert(m.v.end(), {c.x + s * q[0], c.y + s * q[1], c.z + s * q[2]});
  m.t = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
         3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  return m;
}

// An icosahedron (radius 0.4 m, 13 x 1 kg) built with make_from_mesh: 30 edge springs, 30
// bend springs across the edges, 12 radial springs to the centre particle. A closed
// triangulated surface is rigid (Cauchy), so under its own weight (128 N, stiffness ~1e4 N/m)
// it squashes by millimetres: volume within 5% after landing and resting on a plane.
TEST(SoftBodyMesh, ClosedMeshKeepsVolumeAfterLanding) {
  const IcoMesh m = icosahedron(0.4f, {0.0f, 1.0f, 0.0f});
  SoftMeshDef def;
  def.vertices = m.v.data();
  def.vertex_count = 12;
  def.indices = m.t.data();
  def.triangle_count = 20;
  def.structural.damping = 40.0f, def.bend.damping = 10.0f, def.radial.damping = 10.0f;  // to come to rest
  SoftBody b;
  ASSERT_EQ(SoftBody::make_from_mesh(def, &b), Status::ok);
  EXPECT_EQ(b.particle_count(), 13u);
  EXPECT_EQ(b.spring_count(), 30u + 30u + 12u);
  ASSERT_EQ(b.view().triangle_count, 20u);
  const double v0 = enclosed_volume(b);
  EXPECT_NEAR(v0, 2.53615 * 0.4 * 0.4 * 0.4, 1e-3);  // icosahedron volume 2.53615 r^3
  uint32_t ci;
  ASSERT_EQ(b.add_collider(Plane{{0.0f, 1.0f, 0.0f}, 0.0f}, &ci), Status::ok);
  double min_y = 1e9, worst = 0;
  for (int n = 0; n < 180; ++n) {
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    min_y = std::min(min_y, b.stats().min_y);
    worst = std::max(worst, std::abs(enclosed_volume(b) / v0 - 1.0));
  }
  ASSERT_TRUE(all_finite(b));
  const double v1 = enclosed_volume(b);
  std::printf("\n  icosahedron soft body: V0 %.5f m^3, V_end/V0 %.5f, worst |V/V0 - 1| %.3e, min y %.3e\n", v0,
              v1 / v0, worst, min_y);
  record("mesh_body_volume_ratio", v1 / v0);
  EXPECT_GE(min_y, -1e-4);
  EXPECT_NEAR(v1 / v0, 1.0, 0.05);
  EXPECT_LT(worst, 0.10);  // even during the impact
  EXPECT_LT(b.stats().min_y, 0.05);  // it landed
}

// ======================================================================= 6. joints
//
// A 4 x 4 cloth whose own families are negligible (1e-6 N/m: forces below 1e-6 N against
// 9.81 N of weight) serves as a set of particles; unused ones are pinned out of the way.
// Joints use the joint family at +infinity (inextensible), which XPBD projects exactly, so
// the errors below are rounding plus one sub-step of gravity (g h^2 ~ 1e-5 m).
SoftBody joint_body() {
  ClothDef def;
  def.nx = def.nz = 4;
  def.size_x = def.size_z = 0.3f;
  def.center = {0.0f, -2.0f, 0.0f};
  def.particle_mass = 1.0f;
  def.structural = def.shear = def.bend_constants = {1.0e-6f, 0.0f};
  SoftBody b;
  EXPECT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
  EXPECT_EQ(b.set_family(SpringFamily::joint, {kInf, 0.0f}), Status::ok);
  return b;
}

double dist(vec3 a, vec3 b) {
  const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

TEST(SoftBodyJoints, DistanceJointKeepsRestLength) {
  SoftBody b = joint_body();
  const uint32_t p = cidx(b, 0, 0), q = cidx(b, 1, 1), p2 = cidx(b, 3, 0), q2 = cidx(b, 3, 3);
  for (uint32_t i = 0; i < 16; ++i)
    if (i != q && i != q2) { ASSERT_EQ(b.pin(i), Status::ok); }
  ASSERT_EQ(b.set_position(p, {0.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(q, {0.5f, 1.0f, 0.0f}), Status::ok);  // a horizontal pendulum, 0.5 m
  ASSERT_EQ(b.set_position(p2, {2.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(q2, {2.5f, 1.0f, 0.0f}), Status::ok);
  uint32_t j0 = 99, j1 = 99;
  ASSERT_EQ(b.add_joint({p, q, -1.0f}, &j0), Status::ok);   // rest = current 0.5
  ASSERT_EQ(b.add_joint({p2, q2, 0.3f}, &j1), Status::ok);  // rest 0.3: pulls q2 in
  EXPECT_EQ(j0, 0u);
  EXPECT_EQ(j1, 1u);
  double worst = 0, worst2 = 0, min_qy = 1e9;
  for (int n = 0; n < 120; ++n) {
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    worst = std::max(worst, std::abs(dist(pos(b, p), pos(b, q)) - 0.5));
    worst2 = std::max(worst2, std::abs(dist(pos(b, p2), pos(b, q2)) - 0.3));
    min_qy = std::min(min_qy, double(pos(b, q).y));
  }
  std::printf("\n  distance joint: max | |pq| - 0.5 | = %.3e m, max | |pq| - 0.3 | = %.3e m, lowest q %.4f m\n", worst,
              worst2, min_qy);
  record("joint_distance_err_m", worst);
  EXPECT_LT(worst, 5e-4);   // 0.1% of the rest length
  EXPECT_LT(worst2, 5e-4);  // including the step that pulled it from 0.5 to 0.3
  EXPECT_LT(min_qy, 0.55);  // the pendulum swung through its lowest point (y = 0.5)
}

TEST(SoftBodyJoints, BallJointFollowsMovingPin) {
  SoftBody b = joint_body();
  const uint32_t a = cidx(b, 0, 0), q = cidx(b, 2, 2);
  for (uint32_t i = 0; i < 16; ++i)
    if (i != q) { ASSERT_EQ(b.pin(i), Status::ok); }
  ASSERT_EQ(b.set_position(a, {0.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(q, {0.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.add_ball_joint(a, q), Status::ok);
  double worst = 0;
  for (int n = 0; n < 120; ++n) {
    const double t = n / 60.0;  // the pin moves on a 0.3 m circle, 0.03 m per step
    ASSERT_EQ(b.set_position(a, {float(0.3 * std::cos(t * 1.7)), 1.0f, float(0.3 * std::sin(t * 1.7))}), Status::ok);
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    worst = std::max(worst, dist(pos(b, a), pos(b, q)));
  }
  std::printf("  ball joint: max |a - q| = %.3e m while a moves 0.0085 m per step\n", worst);
  record("joint_ball_err_m", worst);
  EXPECT_LT(worst, 1e-3);
}

// A hinge: a rigid triangle (b0, b1, c: three inextensible distance joints) hung by b0 and b1
// on two pinned particles a0, a1 of the x-axis line (y = 1, z = 0); c starts 0.3 m out along
// z and swings down. It may only turn about the axis: c.x stays 0.2, c's distance to the
// axis stays 0.3, b0 and b1 stay on a0 and a1.
TEST(SoftBodyJoints, HingeRotatesAboutItsAxisOnly) {
  SoftBody b = joint_body();
  // a0-b0 and a1-b1 start coincident: they are chosen with no cloth spring between them
  // (zero-length springs other than the joints themselves are not what this test is about).
  const uint32_t a0 = cidx(b, 0, 0), b0 = cidx(b, 3, 3), a1 = cidx(b, 3, 0), b1 = cidx(b, 0, 3), c = cidx(b, 1, 2);
  for (uint32_t i = 0; i < 16; ++i)
    if (i != b0 && i != b1 && i != c) { ASSERT_EQ(b.pin(i), Status::ok); }
  ASSERT_EQ(b.set_position(a0, {0.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(a1, {0.4f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(b0, {0.0f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(b1, {0.4f, 1.0f, 0.0f}), Status::ok);
  ASSERT_EQ(b.set_position(c, {0.2f, 1.0f, 0.3f}), Status::ok);
  ASSERT_EQ(b.add_joint({b0, b1, -1.0f}), Status::ok);
  ASSERT_EQ(b.add_joint({b0, c, -1.0f}), Status::ok);
  ASSERT_EQ(b.add_joint({b1, c, -1.0f}), Status::ok);
  ASSERT_EQ(b.add_hinge_joint(a0, b0, a1, b1), Status::ok);
  double worst_ball = 0, worst_x = 0, worst_r = 0, min_cy = 1e9, max_cy = -1e9;
  for (int n = 0; n < 120; ++n) {
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    const vec3 pc = pos(b, c);
    worst_ball = std::max({worst_ball, dist(pos(b, a0), pos(b, b0)), dist(pos(b, a1), pos(b, b1))});
    worst_x = std::max(worst_x, std::abs(double(pc.x) - 0.2));
    worst_r = std::max(worst_r, std::abs(std::sqrt((pc.y - 1.0) * (pc.y - 1.0) + double(pc.z) * pc.z) - 0.3));
    min_cy = std::min(min_cy, double(pc.y));
    max_cy = std::max(max_cy, double(pc.y));
  }
  std::printf("  hinge: max ball error %.3e m, max |c.x - 0.2| %.3e m, max |r - 0.3| %.3e m, c.y in [%.4f, %.4f]\n",
              worst_ball, worst_x, worst_r, min_cy, max_cy);
  record("joint_hinge_axis_err_m", worst_x);
  EXPECT_LT(worst_ball, 1e-3);
  EXPECT_LT(worst_x, 1e-3);
  EXPECT_LT(worst_r, 1e-3);
  EXPECT_LT(min_cy, 0.75);         // it swung down (lowest point 0.7)
  EXPECT_LT(max_cy, 1.0 + 1e-3);   // and never above its start (no energy gain)
}

// ======================================================================= 7. bad input
//
// Each bad call returns its status, leaves a detail in last_error() and changes nothing
// (hash before == hash after). Conventions as in the rest of gyro (particles.cpp):
// NaN/Inf -> non_finite, a value out of range -> invalid_argument, null -> null_argument.
// Counts below their minimum (grid < 2, substeps 0) may be reported as invalid_argument or
// invalid_count: both are accepted, nothing else is.
#define EXPECT_BAD(call, status)                                                      \
  do {                                                                                \
    const uint64_t h0_ = body.hash();                                                 \
    EXPECT_EQ((call), (status)) << #call;                                             \
    EXPECT_STRNE(last_error(), "") << #call;                                          \
    EXPECT_EQ(body.hash(), h0_) << #call << " changed the body";                      \
  } while (0)

#define EXPECT_BAD_COUNT(call)                                                                          \
  do {                                                                                                  \
    const uint64_t h0_ = body.hash();                                                                   \
    const Status s_ = (call);                                                                           \
    EXPECT_TRUE(s_ == Status::invalid_argument || s_ == Status::invalid_count) << #call << " -> "      \
                                                                               << status_name(s_);     \
    EXPECT_EQ(body.hash(), h0_) << #call << " changed the body";                                        \
  } while (0)

TEST(SoftBodyBadInput, ClearStatusAndNothingChanged) {
  ClothDef good;
  good.nx = good.nz = 6;
  good.size_x = good.size_z = 1.0f;
  SoftBody body;
  ASSERT_EQ(SoftBody::make_cloth(good, &body), Status::ok);
  uint32_t ci;
  ASSERT_EQ(body.add_collider(Sphere{{0.0f, -1.0f, 0.0f}, 0.5f}, &ci), Status::ok);
  ASSERT_EQ(body.step(1.0f / 60.0f), Status::ok);  // a state with velocities
  const uint64_t start = body.hash();

  // Grids.
  for (uint32_t n : {0u, 1u}) {
    ClothDef d = good;
    d.nx = n;
    EXPECT_BAD_COUNT(SoftBody::make_cloth(d, &body));
    d = good;
    d.nz = n;
    EXPECT_BAD_COUNT(SoftBody::make_cloth(d, &body));
  }
  for (float bad : {0.0f, -1.0f}) {
    ClothDef d = good;
    d.size_x = bad;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::invalid_argument);
    d = good;
    d.size_z = bad;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::invalid_argument);
    d = good;
    d.particle_mass = bad;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::invalid_argument);
  }
  {
    ClothDef d = good;
    d.size_x = kNaN;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::non_finite);
    d = good;
    d.center = {0.0f, kInf, 0.0f};
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::non_finite);
    d = good;
    d.structural.stiffness = kNaN;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::non_finite);
    d = good;
    d.shear.damping = kNaN;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::non_finite);
    d = good;
    d.bend_constants.stiffness = -5.0f;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::invalid_argument);
    d = good;
    d.structural.damping = -1.0f;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::invalid_argument);
    d = good;
    d.particle_mass = kNaN;
    EXPECT_BAD(SoftBody::make_cloth(d, &body), Status::non_finite);
    EXPECT_EQ(SoftBody::make_cloth(good, nullptr), Status::null_argument);
  }
  // Cubes and meshes.
  {
    SoftCubeDef d;
    d.half_extent = 0.0f;
    EXPECT_BAD(SoftBody::make_cube(d, &body), Status::invalid_argument);
    d = SoftCubeDef{};
    d.half_extent = kNaN;
    EXPECT_BAD(SoftBody::make_cube(d, &body), Status::non_finite);
    d = SoftCubeDef{};
    d.bend.stiffness = -1.0f;
    EXPECT_BAD(SoftBody::make_cube(d, &body), Status::invalid_argument);
    const IcoMesh m = icosahedron(0.5f, {});
    SoftMeshDef md;
    md.vertices = m.v.data(), md.vertex_count = 12, md.indices = m.t.data(), md.triangle_count = 20;
    SoftMeshDef e = md;
    e.vertices = nullptr;
    EXPECT_BAD(SoftBody::make_from_mesh(e, &body), Status::null_argument);
    e = md;
    e.indices = nullptr;
    EXPECT_BAD(SoftBody::make_from_mesh(e, &body), Status::null_argument);
    e = md;
    e.vertex_count = 3;
    EXPECT_BAD_COUNT(SoftBody::make_from_mesh(e, &body));
    std::vector<uint32_t> bad_index = m.t;
    bad_index[7] = 12;  // out of range
    e = md;
    e.indices = bad_index.data();
    EXPECT_BAD(SoftBody::make_from_mesh(e, &body), Status::invalid_argument);
    std::vector<float> nan_vertex = m.v;
    nan_vertex[4] = kNaN;
    e = md;
    e.vertices = nan_vertex.data();
    EXPECT_BAD(SoftBody::make_from_mesh(e, &body), Status::non_finite);
    e = md;
    e.radial.stiffness = -1.0f;
    EXPECT_BAD(SoftBody::make_from_mesh(e, &body), Status::invalid_argument);
  }
  // Families.
  EXPECT_BAD(body.set_family(SpringFamily::structural, {-1.0f, 0.0f}), Status::invalid_argument);
  EXPECT_BAD(body.set_family(SpringFamily::shear, {0.0f, 0.0f}), Status::invalid_argument);  // stiffness > 0
  EXPECT_BAD(body.set_family(SpringFamily::bend, {kNaN, 0.0f}), Status::non_finite);
  EXPECT_BAD(body.set_family(SpringFamily::bend, {100.0f, -0.5f}), Status::invalid_argument);
  EXPECT_BAD(body.set_family(SpringFamily::bend, {100.0f, kNaN}), Status::non_finite);
  EXPECT_BAD(body.set_family(static_cast<SpringFamily>(7), {100.0f, 0.0f}), Status::invalid_argument);
  // Settings.
  {
    SoftSettings s;
    s.substeps = 0;
    EXPECT_BAD_COUNT(body.set_settings(s));
    s.substeps = 257;
    EXPECT_BAD_COUNT(body.set_settings(s));
    s = SoftSettings{};
    s.iterations = 0;
    EXPECT_BAD_COUNT(body.set_settings(s));
    s.iterations = 65;
    EXPECT_BAD_COUNT(body.set_settings(s));
    s = SoftSettings{};
    s.gravity = {0.0f, kNaN, 0.0f};
    EXPECT_BAD(body.set_settings(s), Status::non_finite);
    s = SoftSettings{};
    s.damping = -1.0f;
    EXPECT_BAD(body.set_settings(s), Status::invalid_argument);
    s = SoftSettings{};
    s.thickness = -0.01f;
    EXPECT_BAD(body.set_settings(s), Status::invalid_argument);
    s = SoftSettings{};
    s.friction = 1.5f;
    EXPECT_BAD(body.set_settings(s), Status::invalid_argument);
    s = SoftSettings{};
    s.penalty_stiffness = 0.0f;
    EXPECT_BAD(body.set_settings(s), Status::invalid_argument);
    s = SoftSettings{};
    s.model = static_cast<SoftModel>(9);
    EXPECT_BAD(body.set_settings(s), Status::invalid_argument);
  }
  // Particles, pins, joints, colliders.
  const uint32_t n = uint32_t(body.particle_count());
  bool pinned;
  vec3 p;
  uint32_t idx;
  EXPECT_BAD(body.pin(n), Status::invalid_argument);
  EXPECT_BAD(body.pin(0xFFFFFFFFu), Status::invalid_argument);
  EXPECT_BAD(body.unpin(n), Status::invalid_argument);
  EXPECT_BAD(body.is_pinned(n, &pinned), Status::invalid_argument);
  EXPECT_BAD(body.set_particle_mass(n, 1.0f), Status::invalid_argument);
  EXPECT_BAD(body.set_particle_mass(0, 0.0f), Status::invalid_argument);
  EXPECT_BAD(body.set_particle_mass(0, -2.0f), Status::invalid_argument);
  EXPECT_BAD(body.set_particle_mass(0, kNaN), Status::non_finite);
  EXPECT_BAD(body.set_mass(0.0f), Status::invalid_argument);
  EXPECT_BAD(body.set_mass(kInf), Status::non_finite);
  EXPECT_BAD(body.get_position(n, &p), Status::invalid_argument);
  EXPECT_BAD(body.set_position(n, {}), Status::invalid_argument);
  EXPECT_BAD(body.set_position(0, {kNaN, 0.0f, 0.0f}), Status::non_finite);
  EXPECT_BAD(body.set_velocity(0, {0.0f, kInf, 0.0f}), Status::non_finite);
  EXPECT_BAD(body.cloth_index(6, 0, &idx), Status::invalid_argument);
  EXPECT_BAD(body.cloth_index(0, 6, &idx), Status::invalid_argument);
  EXPECT_BAD(body.add_joint({0, n, -1.0f}), Status::invalid_argument);
  EXPECT_BAD(body.add_joint({0, 1, kNaN}), Status::non_finite);
  EXPECT_BAD(body.add_ball_joint(n, 0), Status::invalid_argument);
  EXPECT_BAD(body.add_hinge_joint(0, 1, 2, n), Status::invalid_argument);
  EXPECT_BAD(body.add_collider(Sphere{{kNaN, 0.0f, 0.0f}, 1.0f}, &idx), Status::non_finite);
  EXPECT_BAD(body.add_collider(Sphere{{0.0f, 0.0f, 0.0f}, -1.0f}, &idx), Status::invalid_argument);
  EXPECT_BAD(body.add_collider(AABB{{0.0f, 0.0f, 0.0f}, {-1.0f, 1.0f, 1.0f}}, &idx), Status::invalid_argument);
  EXPECT_BAD(body.add_collider(Plane{{0.0f, 0.0f, 0.0f}, 1.0f}, &idx), Status::invalid_argument);
  EXPECT_BAD(body.add_collider(TriangleMesh{}, &idx), Status::invalid_argument);  // never created
  EXPECT_BAD(body.remove_collider(5), Status::invalid_argument);
  // Steps.
  EXPECT_BAD(body.step(0.0f), Status::invalid_argument);
  EXPECT_BAD(body.step(-1.0f / 60.0f), Status::invalid_argument);
  EXPECT_BAD(body.step(kNaN), Status::non_finite);
  EXPECT_BAD(body.step(kInf), Status::non_finite);

  EXPECT_EQ(body.hash(), start);
  // Still fully usable, and a good call does change the hash.
  ASSERT_EQ(body.step(1.0f / 60.0f), Status::ok);
  EXPECT_NE(body.hash(), start);
}

// ======================================================================= 8. copies

// A copy (constructor and assignment) steps bit-identically to the original, step by step,
// and is independent of it (stepping one leaves the other's hash alone). The body has pins,
// a joint, a sphere and a box collider.
TEST(SoftBodyCopy, CopiesStepBitIdenticallyAndIndependently) {
  ClothDef def;
  def.nx = 13, def.nz = 11;
  def.size_x = 1.3f, def.size_z = 1.1f;
  def.center = {0.0f, 1.0f, 0.0f};
  SoftBody a;
  ASSERT_EQ(SoftBody::make_cloth(def, &a), Status::ok);
  ASSERT_EQ(a.pin(cidx(a, 0, 0)), Status::ok);
  ASSERT_EQ(a.add_joint({cidx(a, 12, 10), cidx(a, 0, 10), 0.8f}), Status::ok);
  uint32_t ci;
  ASSERT_EQ(a.add_collider(Sphere{{0.3f, 0.2f, 0.0f}, 0.5f}, &ci), Status::ok);
  ASSERT_EQ(a.add_collider(AABB{{-0.5f, 0.0f, 0.0f}, {0.3f, 0.3f, 0.3f}}, &ci), Status::ok);
  for (int n = 0; n < 5; ++n) ASSERT_EQ(a.step(1.0f / 60.0f), Status::ok);
  SoftBody b(a);
  SoftBody c;
  c = a;
  ASSERT_EQ(b.hash(), a.hash());
  ASSERT_EQ(c.hash(), a.hash());
  EXPECT_EQ(b.particle_count(), a.particle_count());
  EXPECT_EQ(b.spring_count(), a.spring_count());
  EXPECT_EQ(b.collider_count(), 2u);
  for (int n = 0; n < 40; ++n) {
    ASSERT_EQ(a.step(1.0f / 60.0f), Status::ok);
    ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
    ASSERT_EQ(c.step(1.0f / 60.0f), Status::ok);
    ASSERT_EQ(a.hash(), b.hash()) << "step " << n;
    ASSERT_EQ(a.hash(), c.hash()) << "step " << n;
  }
  const uint64_t ha = a.hash();
  ASSERT_EQ(b.step(1.0f / 60.0f), Status::ok);
  EXPECT_NE(b.hash(), ha);
  EXPECT_EQ(a.hash(), ha);
  ASSERT_EQ(c.set_position(3, {9.0f, 9.0f, 9.0f}), Status::ok);
  EXPECT_EQ(a.hash(), ha);
  SoftBody moved(std::move(c));
  ASSERT_EQ(moved.step(1.0f / 60.0f), Status::ok);
  EXPECT_TRUE(all_finite(moved));
}

// ======================================================================= 9. world

TEST(SoftBodyWorld, ClothCollidesWithRigidSphereAndHashes) {
  std::unique_ptr<World> w;
  ASSERT_EQ(World::create(WorldDef{}, &w), Status::ok);
  // Without soft bodies the stage is skipped.
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::sphere;
  d.shape.radius = 0.5f;
  BodyId sphere;
  ASSERT_EQ(w->create_body(d, &sphere), Status::ok);
  ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
  EXPECT_EQ(w->timings().soft_bodies, 0.0);
  EXPECT_EQ(w->soft_body_count(), 0u);

  ClothDef def;
  def.nx = def.nz = 12;
  def.size_x = def.size_z = 1.6f;
  def.center = {0.0f, 1.0f, 0.0f};
  def.particle_mass = 0.05f;
  SoftBody cloth;
  ASSERT_EQ(SoftBody::make_cloth(def, &cloth), Status::ok);
  SoftBodyId id;
  ASSERT_EQ(w->add_soft_body(cloth, &id), Status::ok);
  EXPECT_TRUE(w->is_valid(id));
  EXPECT_EQ(w->soft_body_count(), 1u);
  ASSERT_NE(w->soft_body(id), nullptr);
  EXPECT_EQ(w->soft_body(id)->hash(), cloth.hash());  // the world keeps a copy
  double min_gap = 1e9;
  int unchanged = 0;
  for (int n = 0; n < 90; ++n) {
    const uint64_t before = w->hash();
    ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
    if (w->hash() == before) ++unchanged;
    const SoftView v = w->soft_body(id)->view();
    for (std::size_t i = 0; i < v.count; ++i) {
      const double dx = v.px[i], dy = v.py[i], dz = v.pz[i];
      min_gap = std::min(min_gap, std::sqrt(dx * dx + dy * dy + dz * dz) - 0.5);
    }
  }
  std::printf("\n  world cloth over a rigid sphere: min gap %.3e m, soft stage %.3f ms\n", min_gap,
              w->timings().soft_bodies);
  EXPECT_EQ(unchanged, 0);  // the world hash sees the cloth move every step
  EXPECT_GE(min_gap, 0.0);
  EXPECT_GT(w->timings().soft_bodies, 0.0);
  EXPECT_TRUE(all_finite(*w->soft_body(id)));
  // The hash covers the cloth: moving one particle changes it.
  const uint64_t h = w->hash();
  ASSERT_EQ(w->soft_body(id)->set_position(0, {0.0f, 3.0f, 0.0f}), Status::ok);
  EXPECT_NE(w->hash(), h);
  // The original body was copied, not shared.
  EXPECT_EQ(cloth.stats().min_y, 1.0);
  ASSERT_EQ(w->destroy_soft_body(id), Status::ok);
  EXPECT_FALSE(w->is_valid(id));
  EXPECT_EQ(w->soft_body(id), nullptr);
  EXPECT_EQ(w->destroy_soft_body(id), Status::stale_id);
  ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
  // IMPLEMENTATION FAILURE (reported): after the last soft body is destroyed the stage is
  // still entered and timed (measured 3.5e-5 ms), against StepTimings' "0 for a skipped
  // stage" and "a world without soft bodies skips the stage".
  EXPECT_EQ(w->timings().soft_bodies, 0.0);
}

// ======================================================================= 10. threads, SIMD
//
// A 45 x 43 cloth (odd sizes: every lane tail and the four column blocks' uneven lengths)
// with a sphere collider and a joint, both models, stepped at every available SIMD level
// with 1, 2 and 4 threads: one hash. And the same cloth in worlds with 1 and 4 threads.
uint64_t run_threads_cloth(SoftModel model) {
  ClothDef def;
  def.nx = 45, def.nz = 43;
  def.size_x = 4.5f, def.size_z = 4.3f;
  def.center = {0.0f, 1.0f, 0.0f};
  def.particle_mass = 1.0f;
  def.structural = def.shear = {1.0e4f, 0.5f};
  def.bend_constants = {1.0e3f, 0.1f};
  SoftBody b;
  SoftSettings s;
  s.model = model;
  s.substeps = 4;  // keeps the 2 models x levels x {1,2,4} threads runs short
  s.damping = 0.1f;
  EXPECT_EQ(b.set_settings(s), Status::ok);
  EXPECT_EQ(SoftBody::make_cloth(def, &b), Status::ok);
  EXPECT_EQ(b.pin(cidx(b, 0, 0)), Status::ok);
  EXPECT_EQ(b.add_joint({cidx(b, 44, 42), cidx(b, 20, 20), -1.0f}), Status::ok);
  uint32_t ci;
  EXPECT_EQ(b.add_collider(Sphere{{0.2f, 0.0f, -0.1f}, 1.0f}, &ci), Status::ok);
  uint64_t h = 0;
  for (int n = 0; n < 3; ++n) {
    EXPECT_EQ(b.step(1.0f / 60.0f), Status::ok);
    h = h * 0x100000001b3ull ^ b.hash();
  }
  return h;
}

TEST(SoftBodyDeterminism, SameHashAtEverySimdLevelAndThreadCount) {
  std::vector<SimdLevel> levels;
  for (uint32_t v = 1; v <= 5; ++v)
    if (simd_level_available(static_cast<SimdLevel>(v))) levels.push_back(static_cast<SimdLevel>(v));
  ASSERT_FALSE(levels.empty());
  // Every level with 1 thread; the scalar and the best level also with 2 and 4 threads (the
  // threaded runs are what is slow on a loaded 2-core machine).
  for (SoftModel model : {SoftModel::xpbd, SoftModel::springs}) {
    uint64_t ref = 0;
    bool first = true;
    for (SimdLevel level : levels)
      for (uint32_t threads : {1u, 2u, 4u}) {
        if (threads > 1 && level != levels.front() && level != levels.back()) continue;
        ASSERT_EQ(set_simd_level(level), Status::ok);
        ASSERT_EQ(set_thread_count(threads), Status::ok);
        const uint64_t h = run_threads_cloth(model);
        if (first) ref = h, first = false;
        EXPECT_EQ(h, ref) << model_name(model) << " " << simd_level_name(level) << " x" << threads;
      }
    std::printf("  %s cloth 45x43: hash 0x%016llx at %zu levels (1 thread), 2 levels x {2,4} threads\n", model_name(model),
                static_cast<unsigned long long>(ref), levels.size());
  }
  set_simd_level(SimdLevel::automatic);
  set_thread_count(0);

  uint64_t world_ref = 0;
  for (uint32_t threads : {1u, 4u}) {
    WorldDef wd;
    wd.threads = threads;
    std::unique_ptr<World> w;
    ASSERT_EQ(World::create(wd, &w), Status::ok);
    BodyDef d;
    d.type = BodyType::static_body;
    d.shape.type = BodyShape::sphere;
    d.shape.radius = 0.8f;
    BodyId sid;
    ASSERT_EQ(w->create_body(d, &sid), Status::ok);
    ClothDef def;
    def.nx = 37, def.nz = 29;
    def.size_x = 3.7f, def.size_z = 2.9f;
    def.center = {0.0f, 1.2f, 0.0f};
    SoftBody cloth;
    ASSERT_EQ(SoftBody::make_cloth(def, &cloth), Status::ok);
    SoftBodyId id;
    ASSERT_EQ(w->add_soft_body(cloth, &id), Status::ok);
    for (int n = 0; n < 10; ++n) ASSERT_EQ(w->step(1.0f / 60.0f), Status::ok);
    if (threads == 1) world_ref = w->hash();
    else { EXPECT_EQ(w->hash(), world_ref) << "world threads " << threads; }
  }
}

}  // namespace
}  // namespace gyro
