// C1 (BENCHMARKS.md): a hanging 10 x 10 m cloth of N x N particles (N = 32, 64, 128, 256),
// the two corners of the z = -5 edge pinned, mass 1 per free particle, dt 1/60, 600 steps,
// in gyro (gyro/soft_body.hpp: xpbd, its default, and the book's springs model where that is
// stable) and in Bullet's btSoftBody (defaults, and +bending2) in the same run.
//
// Every figure comes from the final particle positions, computed by the same code for both
// engines (cloth_figures): the sag (min particle y - fixed-corner y), the max and mean strain
// |len - rest| / rest over the structural springs (grid neighbours along x and z, rest
// 10 / (N - 1)), and the sag error against a converged reference: a double-precision scalar
// XPBD of the same springs with many sub-steps at 32^2, gyro's own xpbd with many sub-steps
// at the larger sizes (the comment lines say which).
//
// Then the work-precision table at 64^2 and 32^2 (time per step against sag error and strain
// error, over sub-steps x iterations for xpbd and sub-steps for springs), plotted log-log to
// c1_work_precision.png in the current directory or in $GYRO_BENCH_OUT.
#include "cloth_peers.hpp"
#include "png_plot.hpp"
#include "scenario.hpp"

#include "gyro/soft_body.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace gyro::bench {
namespace {

constexpr int kSteps = 600;
constexpr float kDt = 1.0f / 60.0f;
constexpr double kSize = 10.0;
const int kSizes[] = {32, 64, 128, 256};

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// ------------------------------------------------------------------ figures

struct Figures {
  double sag = NAN;          // m: min particle y - fixed-corner y
  double max_strain = NAN;   // max |len - rest| / rest over structural springs
  double mean_strain = NAN;  // mean of the same
};

Figures cloth_figures(const ClothPositions& p) {
  Figures f;
  const int n = p.n;
  const double rest = kSize / (n - 1);
  double min_y = INFINITY, sum = 0, worst = 0;
  std::size_t count = 0;
  bool finite = true;
  auto strain = [&](int a, int b) {
    const double dx = double(p.x[a]) - p.x[b], dy = double(p.y[a]) - p.y[b], dz = double(p.z[a]) - p.z[b];
    const double s = std::fabs(std::sqrt(dx * dx + dy * dy + dz * dz) - rest) / rest;
    if (!std::isfinite(s)) finite = false;
    worst = std::max(worst, s), sum += s, ++count;
  };
  for (int iz = 0; iz < n; ++iz)
    for (int ix = 0; ix < n; ++ix) {
      const int i = iz * n + ix;
      if (!std::isfinite(p.y[i])) finite = false;
      min_y = std::min(min_y, double(p.y[i]));
      if (ix + 1 < n) strain(i, i + 1);
      if (iz + 1 < n) strain(i, i + n);
    }
  if (!finite) return f;
  f.sag = min_y - double(p.y[0]);  // node (0, 0) is a pinned corner
  f.max_strain = worst;
  f.mean_strain = count ? sum / double(count) : 0.0;
  return f;
}

// Blown up: not finite, or a 10 m cloth sagging more than 50 m or stretched 50-fold.
bool blew_up(const Figures& f) {
  return !std::isfinite(f.sag) || !std::isfinite(f.max_strain) || f.sag < -50.0 || f.max_strain > 50.0;
}

// ------------------------------------------------------------------ gyro

ClothDef c1_cloth(int n) {
  ClothDef def;
  def.nx = def.nz = uint32_t(n);
  def.size_x = def.size_z = float(kSize);
  def.center = {0.0f, 0.0f, 0.0f};
  def.particle_mass = 1.0f;
  def.both_diagonals = false;  // Bullet's gendiags: one diagonal per cell, by parity of ix + iz
  def.bend = true;
  return def;
}

struct GyroRun {
  double build_ms = 0, step_ms = 0;  // step_ms: all steps
  std::size_t springs = 0;
  uint64_t hash = 0;
  ClothPositions state;
};

// Builds the C1 cloth with these settings, pins the two corners of the z = -5 edge, steps it
// `steps` times and reads the positions back in grid order. False (with a comment) on error.
bool gyro_run_cloth(int n, const SoftSettings& settings, int steps, GyroRun& out) {
  const auto t0 = Clock::now();
  SoftBody body;
  uint32_t c0 = 0, c1 = 0;
  Status s = SoftBody::make_cloth(c1_cloth(n), &body);
  if (s == Status::ok) s = body.set_settings(settings);
  if (s == Status::ok) s = body.cloth_index(0, 0, &c0);
  if (s == Status::ok) s = body.cloth_index(uint32_t(n - 1), 0, &c1);
  if (s == Status::ok) s = body.pin(c0);
  if (s == Status::ok) s = body.pin(c1);
  if (s != Status::ok) {
    std::printf("# C1 %d^2: building gyro's cloth failed: %s: %s\n", n, status_name(s), last_error());
    return false;
  }
  const auto t1 = Clock::now();
  for (int k = 0; k < steps; ++k)
    if ((s = body.step(kDt)) != Status::ok) {
      std::printf("# C1 %d^2: step %d failed: %s: %s\n", n, k, status_name(s), last_error());
      return false;
    }
  const auto t2 = Clock::now();
  out.build_ms = ms_between(t0, t1);
  out.step_ms = ms_between(t1, t2);
  out.springs = body.spring_count();
  out.hash = body.hash();
  out.state.resize(n);
  const SoftView v = body.view();
  for (int iz = 0; iz < n; ++iz)
    for (int ix = 0; ix < n; ++ix) {
      uint32_t idx = 0;
      if (body.cloth_index(uint32_t(ix), uint32_t(iz), &idx) != Status::ok || idx >= v.count) return false;
      const std::size_t g = std::size_t(iz) * n + ix;
      out.state.x[g] = v.px[idx], out.state.y[g] = v.py[idx], out.state.z[g] = v.pz[idx];
    }
  return true;
}

SoftSettings settings_for(SoftModel model, uint32_t substeps, uint32_t iterations) {
  SoftSettings s;
  s.model = model;
  s.substeps = substeps;
  s.iterations = iterations;
  return s;
}

// ------------------------------------------------------------------ double reference

// The same springs as gyro's C1 cloth (ClothDef's defaults: structural and shear k = 1e6,
// bend k = 1e4 between grid neighbours two apart, no damping; the diagonal per cell as
// Bullet's gendiags) stepped by a plain scalar XPBD in binary64: per sub-step h, v += g h,
// x += v h, one Gauss-Seidel pass with compliance 1 / (k h^2), v = (x - x_start) / h. Its
// limit for h -> 0 is the spring model's own motion, whatever the solver's order.
ClothPositions double_reference(int n, int substeps) {
  const ClothDef def = c1_cloth(n);
  struct Spring {
    int a, b;
    double rest, compliance;
  };
  const std::size_t count = std::size_t(n) * n;
  std::vector<double> x(count), y(count, 0.0), z(count), vx(count, 0.0), vy(count, 0.0), vz(count, 0.0), w(count, 1.0);
  std::vector<double> sx(count), sy(count), sz(count);
  for (int iz = 0; iz < n; ++iz)
    for (int ix = 0; ix < n; ++ix) {
      x[iz * n + ix] = -0.5 * kSize + kSize * ix / (n - 1);
      z[iz * n + ix] = -0.5 * kSize + kSize * iz / (n - 1);
    }
  w[0] = w[n - 1] = 0.0;
  std::vector<Spring> springs;
  auto add = [&](int a, int b, double k) {
    const double dx = x[a] - x[b], dz = z[a] - z[b];
    springs.push_back({a, b, std::sqrt(dx * dx + dz * dz), 1.0 / k});
  };
  const double ks = def.structural.stiffness, kd = def.shear.stiffness, kb = def.bend_constants.stiffness;
  for (int iz = 0; iz < n; ++iz)
    for (int ix = 0; ix < n; ++ix) {
      const int i = iz * n + ix;
      if (ix + 1 < n) add(i, i + 1, ks);
      if (iz + 1 < n) add(i, i + n, ks);
    }
  for (int iz = 0; iz + 1 < n; ++iz)
    for (int ix = 0; ix + 1 < n; ++ix) {
      const int i = iz * n + ix;
      if ((ix + iz) & 1) add(i, i + n + 1, kd);
      else add(i + 1, i + n, kd);
    }
  for (int iz = 0; iz < n; ++iz)
    for (int ix = 0; ix < n; ++ix) {
      const int i = iz * n + ix;
      if (ix + 2 < n) add(i, i + 2, kb);
      if (iz + 2 < n) add(i, i + 2 * n, kb);
    }
  const double h = (1.0 / 60.0) / substeps, g = -9.81;
  for (int step = 0; step < kSteps; ++step)
    for (int sub = 0; sub < substeps; ++sub) {
      for (std::size_t i = 0; i < count; ++i) {
        sx[i] = x[i], sy[i] = y[i], sz[i] = z[i];
        if (w[i] == 0.0) continue;
        vy[i] += g * h;
        x[i] += vx[i] * h, y[i] += vy[i] * h, z[i] += vz[i] * h;
      }
      for (const Spring& s : springs) {
        const double dx = x[s.a] - x[s.b], dy = y[s.a] - y[s.b], dz = z[s.a] - z[s.b];
        const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double wsum = w[s.a] + w[s.b];
        if (len <= 0.0 || wsum == 0.0) continue;
        const double lambda = -(len - s.rest) / (wsum + s.compliance / (h * h));
        const double nx = dx / len, ny = dy / len, nz = dz / len;
        x[s.a] += w[s.a] * lambda * nx, y[s.a] += w[s.a] * lambda * ny, z[s.a] += w[s.a] * lambda * nz;
        x[s.b] -= w[s.b] * lambda * nx, y[s.b] -= w[s.b] * lambda * ny, z[s.b] -= w[s.b] * lambda * nz;
      }
      for (std::size_t i = 0; i < count; ++i) {
        if (w[i] == 0.0) continue;
        vx[i] = (x[i] - sx[i]) / h, vy[i] = (y[i] - sy[i]) / h, vz[i] = (z[i] - sz[i]) / h;
      }
    }
  ClothPositions p;
  p.resize(n);
  for (std::size_t i = 0; i < count; ++i) p.x[i] = float(x[i]), p.y[i] = float(y[i]), p.z[i] = float(z[i]);
  return p;
}

// ------------------------------------------------------------------ measuring

// Medians over reps of one engine and settings, and the last run's state. One warm-up run
// first; when it alone takes more than the budget it is the only sample, otherwise as many
// of `reps` as fit in the budget follow (at least one). `reps` reports what was used.
struct Measured {
  double build_ms = 0, step_ms = 0;  // step_ms: per step
  int reps = 0;
  GyroRun last;  // gyro: hash, springs; both: state (Bullet's filled by the caller)
  bool hash_stable = true;
};

constexpr double kBudgetMs = 2000.0;  // wall time one measured line may take (after warm-up)

template <class RunOnce> bool measure(int reps, RunOnce run_once, Measured& m) {
  const auto w0 = Clock::now();
  if (!run_once(m.last)) return false;
  const double warm_ms = ms_between(w0, Clock::now());
  std::vector<double> build, step;
  if (warm_ms > kBudgetMs) {
    build.push_back(m.last.build_ms), step.push_back(m.last.step_ms / kSteps);
  } else {
    const uint64_t first = m.last.hash;
    const int n = std::max(1, std::min(reps, int(kBudgetMs / std::max(warm_ms, 1e-3))));
    for (int r = 0; r < n; ++r) {
      if (!run_once(m.last)) return false;
      if (m.last.hash != first) m.hash_stable = false;
      build.push_back(m.last.build_ms), step.push_back(m.last.step_ms / kSteps);
    }
  }
  m.build_ms = median(build), m.step_ms = median(step), m.reps = int(step.size());
  return true;
}

struct Reference {
  bool have = false;
  Figures f;
  std::string what;
};

// One JSON line; error is the max strain, sag_error against the reference.
void emit(int n, const char* library, const std::string& method, const char* simd, uint32_t threads,
          uint32_t substeps, uint32_t iterations, const Measured& m, std::size_t springs, const Reference& ref,
          const uint64_t* hash, double bullet_ms, double bullet_bend_ms) {
  const Figures f = cloth_figures(m.last.state);
  const double updates = double(springs) * substeps * iterations;
  JsonLine line;
  line.str("workload", "C1").str("library", library).str("method", method).str("simd", simd)
      .integer("threads", threads).integer("n", n).integer("substeps", substeps).integer("iterations", iterations)
      .num("build_ms", m.build_ms, 4).num("time_ms", m.step_ms, 5).num("throughput", updates / m.step_ms * 1e-3, 5)
      .str("unit", "Mspring-updates/s").integer("hits", int64_t(springs)).num("checksum", f.sag, 7)
      .num("error", f.max_strain, 5).str("error_metric", "max strain |len-rest|/rest over structural springs at the end")
      .num("mean_strain", f.mean_strain, 5);
  if (ref.have) {
    line.num("sag_error", std::fabs(f.sag - ref.f.sag), 5)
        .num("strain_error", std::fabs(f.max_strain - ref.f.max_strain), 5);
  }
  line.str("stable", blew_up(f) ? "no" : "yes");
  if (hash) line.hex("state_hash", *hash);
  line.integer("steps", kSteps).integer("reps", m.reps);
  if (bullet_ms > 0) line.num("ratio_vs_bullet", bullet_ms / m.step_ms, 4);
  if (bullet_bend_ms > 0) line.num("ratio_vs_bullet_bending2", bullet_bend_ms / m.step_ms, 4);
  line.print();
}

// ------------------------------------------------------------------ reference per size

// 32^2 and 64^2: the double-precision XPBD at 256 / 128 sub-steps. Not gyro's own binary32
// xpbd at many sub-steps: in binary32 the per-sub-step moves (g h^2 = 4e-8 m at 256
// sub-steps) fall below the position's ulp (4.8e-7 m at 5 m) and v = (x - x0) / h is
// quantised to ulp / h (7 mm/s): at 32^2 and 256 sub-steps gyro's float run sags -6.53 m
// where the double one sags -8.57 m (the comment line after the reference prints both).
// The cloth is undamped and still swinging at t = 10 s, so its sag then converges slowly
// with the sub-step: an offline study of the double XPBD at 32^2 gave -8.213 / -8.303 /
// -8.558 / -8.572 / -8.448 m at 16 / 64 / 128 / 256 / 512 sub-steps, i.e. the reference
// itself is uncertain by about 0.1 m. 128^2 and 256^2 have no reference (a double run
// there takes minutes): their lines carry no sag_error.
Reference make_reference(int n) {
  Reference r;
  if (n > 64) {
    std::printf("# C1 %d^2: no converged reference (a double-precision run takes minutes): no sag_error\n", n);
    return r;
  }
  char buf[400];
  const auto t0 = Clock::now();
  const int substeps = n == 32 ? 256 : 128;
  const Figures b = cloth_figures(double_reference(n, substeps));
  r.have = !blew_up(b), r.f = b;
  std::snprintf(buf, sizeof buf,
                "double-precision scalar XPBD, %d sub-steps x 1: sag %.5f m, max strain %.5f, mean strain %.6f "
                "(undamped and still swinging at t = 10 s, the sag converges slowly: about 0.1 m uncertain)",
                substeps, b.sag, b.max_strain, b.mean_strain);
  r.what = buf;
  std::printf("# C1 %d^2 reference (%.1f s): %s\n", n, ms_between(t0, Clock::now()) * 1e-3, r.what.c_str());
  if (n == 32) {  // gyro's binary32 xpbd at the reference's sub-steps, against it
    GyroRun g;
    if (gyro_run_cloth(n, settings_for(SoftModel::xpbd, uint32_t(substeps), 1), kSteps, g)) {
      const Figures f = cloth_figures(g.state);
      std::printf("# C1 32^2 gyro xpbd %d x 1 (binary32): sag %.5f m, max strain %.5f, mean strain %.6f; the double "
                  "reference: %.5f, %.5f, %.6f\n",
                  substeps, f.sag, f.max_strain, f.mean_strain, r.f.sag, r.f.max_strain, r.f.mean_strain);
    }
  }
  return r;
}

// ------------------------------------------------------------------ work-precision

struct WpPoint {
  std::string method;
  double ms = NAN, sag_error = NAN, strain_error = NAN;
};

std::vector<WpPoint> work_precision(int n, const Options& o, const Reference& ref, uint32_t threads) {
  std::vector<WpPoint> out;
  struct Config {
    SoftModel model;
    uint32_t substeps, iterations;
  };
  const Config configs[] = {
      {SoftModel::xpbd, 1, 1},     {SoftModel::xpbd, 2, 1},     {SoftModel::xpbd, 4, 1},   {SoftModel::xpbd, 8, 1},
      {SoftModel::xpbd, 16, 1},    {SoftModel::xpbd, 32, 1},    {SoftModel::xpbd, 64, 1},  {SoftModel::xpbd, 8, 4},
      {SoftModel::xpbd, 4, 8},     {SoftModel::springs, 1, 1},  {SoftModel::springs, 4, 1}, {SoftModel::springs, 16, 1},
      {SoftModel::springs, 32, 1}, {SoftModel::springs, 64, 1}, {SoftModel::springs, 128, 1},
  };
  for (const Config& c : configs) {
    char name[64];
    if (c.model == SoftModel::xpbd) std::snprintf(name, sizeof name, "wp_xpbd_%ux%u", c.substeps, c.iterations);
    else std::snprintf(name, sizeof name, "wp_springs_%u", c.substeps);
    Measured m;
    const SoftSettings s = settings_for(c.model, c.substeps, c.iterations);
    if (!measure(o.reps, [&](GyroRun& r) { return gyro_run_cloth(n, s, kSteps, r); }, m)) continue;
    emit(n, "gyro", name, simd_level_name(simd_level()), threads, c.substeps, c.iterations, m, m.last.springs, ref,
         &m.last.hash, 0, 0);
    const Figures f = cloth_figures(m.last.state);
    WpPoint p;
    p.method = name, p.ms = m.step_ms;
    if (ref.have && !blew_up(f)) {
      p.sag_error = std::fabs(f.sag - ref.f.sag), p.strain_error = std::fabs(f.max_strain - ref.f.max_strain);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

void run_c1(const Options& o) {
  std::printf("# C1: %d steps of 1/60 s; cloth 10 x 10 m, N x N particles, corners (0,0) and (N-1,0) pinned, mass 1, "
              "gravity -9.81; gyro: ClothDef defaults (structural/shear k 1e6, bend k 1e4, no damping), one diagonal per "
              "cell; figures from final positions by the bench's own code\n",
              kSteps);
  const bool bullet = o.peers && bullet_cloth_available();
  if (o.peers && !bullet) std::printf("# bullet not installed\n");
  const std::vector<SimdLevel> levels = levels_to_run(o);
  const std::vector<uint32_t> threads = threads_to_run(o);
  // The springs model at k = 1e6, m = 1 is explicit: it needs a sub-step below about
  // 2 sqrt(m / k) / (a few neighbours); the table runs it at the fewest sub-steps that were
  // stable at 32^2 (found first), or not at all.
  uint32_t springs_substeps = 0;
  for (uint32_t s : {16u, 32u, 64u, 128u, 256u}) {
    GyroRun r;
    if (!gyro_run_cloth(32, settings_for(SoftModel::springs, s, 1), kSteps, r)) break;
    const Figures f = cloth_figures(r.state);
    std::printf("# C1 springs model at 32^2, %u sub-steps: sag %.4g m, max strain %.4g -> %s\n", s, f.sag, f.max_strain,
                blew_up(f) ? "blows up" : "stable");
    if (!blew_up(f)) {
      springs_substeps = s;
      break;
    }
  }
  Reference refs[4];
  WpPoint bullet_wp[4];  // Bullet+bending2 at each size, for the plot
  for (int ni = 0; ni < 4; ++ni) {
    const int n = kSizes[ni];
    std::printf("# ---- C1 %d^2 (%d particles)\n", n, n * n);
    refs[ni] = make_reference(n);
    const Reference& ref = refs[ni];
    double bullet_ms = 0, bullet_bend_ms = 0;
    std::string summary;
    char buf[200];
    if (bullet) {
      for (bool bend : {false, true}) {
        if (bend && n > 128) {
          std::printf("# C1 %d^2 Bullet +bending2 skipped: generateBendingConstraints builds an N^2 x N^2 adjacency "
                      "table (%.0f GiB at %d^2; 1 GiB at 128^2)\n",
                      n, double(n) * n * n * n * 4 / (1u << 30), n);
          continue;
        }
        Measured m;
        std::size_t links = 0;
        auto once = [&](GyroRun& r) {
          BulletClothRun b;
          if (!bullet_run_cloth(n, bend, kSteps, b)) return false;
          r.build_ms = b.build_ms, r.step_ms = b.step_ms, r.state = std::move(b.state), links = b.links;
          return true;
        };
        if (!measure(o.reps, once, m)) {
          std::printf("# C1 %d^2 Bullet run failed\n", n);
          continue;
        }
        (bend ? bullet_bend_ms : bullet_ms) = m.step_ms;
        if (bend) {
          const Figures fb = cloth_figures(m.last.state);
          bullet_wp[ni].method = "btSoftBody+bending2", bullet_wp[ni].ms = m.step_ms;
          if (ref.have && !blew_up(fb))
            bullet_wp[ni].sag_error = std::fabs(fb.sag - ref.f.sag),
            bullet_wp[ni].strain_error = std::fabs(fb.max_strain - ref.f.max_strain);
        }
        emit(n, "bullet", bend ? "btSoftBody+bending2" : "btSoftBody", "scalar", 1, 1, 1, m, links, ref, nullptr, 0, 0);
        const Figures f = cloth_figures(m.last.state);
        std::snprintf(buf, sizeof buf, "%sBullet%s %.3f ms (sag %.3g, max strain %.3g)", summary.empty() ? "" : ", ",
                      bend ? "+bending2" : "", m.step_ms, f.sag, f.max_strain);
        summary += buf;
      }
    }
    struct Model {
      SoftModel model;
      uint32_t substeps, iterations;
    };
    if (n > 64 && o.levels.empty())
      std::printf("# C1 %d^2: gyro at the best level only (%s; every level costs minutes here: --simd asks for others)\n",
                  n, simd_level_name(detected_simd_level()));
    std::vector<Model> models = {{SoftModel::xpbd, SoftSettings().substeps, SoftSettings().iterations}};
    if (springs_substeps) models.push_back({SoftModel::springs, springs_substeps, 1});
    for (const Model& model : models) {
      char method[64];
      if (model.model == SoftModel::xpbd) std::snprintf(method, sizeof method, "xpbd_%ux%u", model.substeps, model.iterations);
      else std::snprintf(method, sizeof method, "springs_%u", model.substeps);
      const SoftSettings s = settings_for(model.model, model.substeps, model.iterations);
      bool have_hash = false;
      uint64_t first_hash = 0;
      std::string model_summary;
      for (SimdLevel level : (n <= 64 || !o.levels.empty()) ? levels : std::vector<SimdLevel>{detected_simd_level()}) {
        set_simd_level(level);
        for (uint32_t t : threads) {
          set_thread_count(t);
          Measured m;
          if (!measure(o.reps, [&](GyroRun& r) { return gyro_run_cloth(n, s, kSteps, r); }, m)) continue;
          emit(n, "gyro", method, simd_level_name(level), t, model.substeps, model.iterations, m, m.last.springs, ref,
               &m.last.hash, bullet_ms, bullet_bend_ms);
          if (!m.hash_stable) std::printf("# WARNING: C1 %d^2 %s: state_hash differs between reps\n", n, method);
          if (have_hash && m.last.hash != first_hash)
            std::printf("# WARNING: C1 %d^2 %s: state_hash differs across SIMD levels / threads\n", n, method);
          if (!have_hash) have_hash = true, first_hash = m.last.hash;
          if (t == threads.front()) {  // the summary keeps the last level's figure on the first thread count
            std::string& summary = model_summary;
            summary.clear();
            const Figures f = cloth_figures(m.last.state);
            std::snprintf(buf, sizeof buf, "%sgyro %s %s %ut %.3f ms (sag %.3g, max strain %.3g", "; ",
                          method, simd_level_name(level), t, m.step_ms, f.sag, f.max_strain);
            summary += buf;
            if (bullet_ms > 0) std::snprintf(buf, sizeof buf, "; %.2fx Bullet", bullet_ms / m.step_ms), summary += buf;
            if (bullet_bend_ms > 0)
              std::snprintf(buf, sizeof buf, ", %.2fx Bullet+bending2", bullet_bend_ms / m.step_ms), summary += buf;
            summary += ")";
          }
        }
      }
      set_simd_level(SimdLevel::automatic);
      set_thread_count(0);
      summary += model_summary;
    }
    std::printf("# C1 %d^2 ms/step: %s\n", n, summary.c_str());
  }
  if (!springs_substeps) std::printf("# C1: the springs model blew up at every sub-step count up to 256: not in the table\n");
  std::printf("# C1: Bullet's links are PBD distance constraints with kLST = 1 (inextensible targets, one iteration), "
              "gyro's springs have k = 1e6 N/m: the converged gyro cloth itself stretches near the pinned corners, "
              "which carry the whole cloth's weight (N^2 kg)\n");

  // Work-precision: 64^2 and 32^2 at the best level, on the first thread count.
  set_thread_count(threads.front());
  PlotSpec plot;
  plot.width = 900, plot.height = 650;
  const Rgb colours[2][2] = {{{0, 70, 200}, {200, 40, 20}}, {{120, 170, 255}, {255, 150, 110}}};  // [n][xpbd, springs]
  int ni = 0;
  for (int n : {64, 32}) {
    const Reference& ref = refs[n == 32 ? 0 : 1];
    std::printf("# ---- C1 work-precision at %d^2 (%s, %u thread%s; reference: %s)\n", n, simd_level_name(simd_level()),
                threads.front(), threads.front() == 1 ? "" : "s", ref.have ? ref.what.c_str() : "none");
    const std::vector<WpPoint> pts = work_precision(n, o, ref, threads.front());
    for (int model = 0; model < 2; ++model) {
      const char* prefix = model == 0 ? "wp_xpbd_" : "wp_springs_";
      PlotSeries sag, strain;
      sag.color = strain.color = colours[ni][model];
      sag.marker = 0, strain.marker = 1;
      // The polyline joins the 1-iteration (or springs) runs in order of cost; the other
      // iteration counts are points alone.
      PlotSeries extra = sag;
      extra.polyline = false, extra.marker = 2;
      for (const WpPoint& p : pts) {
        if (p.method.rfind(prefix, 0) != 0) continue;
        const bool one_iteration = model == 1 || p.method.size() < 2 || p.method.substr(p.method.size() - 2) == "x1";
        PlotSeries& s = one_iteration ? sag : extra;
        s.x.push_back(p.ms), s.y.push_back(p.sag_error);
        if (one_iteration) strain.x.push_back(p.ms), strain.y.push_back(p.strain_error);
      }
      strain.polyline = true;
      plot.series.push_back(sag), plot.series.push_back(strain), plot.series.push_back(extra);
    }
    // Bullet+bending2 at this size (its own model: inextensible links), for comparison.
    PlotSeries bsag, bstrain;
    bsag.color = bstrain.color = ni == 0 ? Rgb{0, 0, 0} : Rgb{130, 130, 130};
    bsag.marker = 0, bstrain.marker = 1, bsag.polyline = bstrain.polyline = false;
    const WpPoint& b = bullet_wp[n == 32 ? 0 : 1];
    bsag.x = {b.ms}, bsag.y = {b.sag_error}, bstrain.x = {b.ms}, bstrain.y = {b.strain_error};
    plot.series.push_back(bsag), plot.series.push_back(bstrain);
    ++ni;
  }
  set_thread_count(0);
  std::string dir = ".";
  if (const char* env = std::getenv("GYRO_BENCH_OUT"); env && *env) dir = env;
  const std::string path = dir + "/c1_work_precision.png";
  if (plot_png(plot, path))
    std::printf("# C1 work-precision plot: %s (log-log; x: ms per step; y: error in m for sag / in strain units; "
                "blue: xpbd, red: springs, black (64^2) / grey (32^2): Bullet+bending2; dark: 64^2, light: 32^2; discs: sag error of sub-steps x 1 (joined), "
                "squares: |max strain - reference max strain| (joined), triangles: sag error of other "
                "sub-steps x iterations; blown-up runs left out)\n",
                path.c_str());
  else
    std::printf("# C1 work-precision plot: could not write %s\n", path.c_str());
}

}  // namespace gyro::bench
