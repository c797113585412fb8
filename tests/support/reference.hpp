// Double-precision references: the answers gyro's float kernels are measured against.
#pragma once

#include "workloads.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro::testing {

struct RefHit {
  double t = 0;          // +inf on a miss
  int32_t primitive = -1;
};

/// Closest sphere-surface crossing with t in [tmin, tmax], in binary64 from the binary32
/// inputs (the textbook quadratic: binary64 has the bits to spare).
RefHit ref_ray_spheres(double ox, double oy, double oz, double dx, double dy, double dz, double tmin, double tmax,
                       const SphereSet& spheres);

/// The reference for rays [0, count), in parallel over rays (order does not matter here).
std::vector<RefHit> ref_raycast_spheres(const RaySet& rays, std::size_t count, const SphereSet& spheres);

/// How a float answer compares with the reference.
struct RaycastError {
  std::size_t rays = 0;
  std::size_t hits = 0;               // gyro hits
  std::size_t ref_hits = 0;
  std::size_t disagreements = 0;      // hit/miss or primitive differ
  double max_abs_t = 0;               // over rays where both agree
  double max_rel_t = 0;
  double sum_t = 0;                   // gyro: sum of float t over hits, in ray order, in binary64
  double ref_sum_t = 0;               // reference t rounded to float, summed the same way
};
RaycastError compare_raycast(const HitSet& hits, const std::vector<RefHit>& ref, std::size_t count);

/// OBB-OBB in binary64 from the float inputs: the largest gap over the 15 SAT axes, each
/// normalised (> 0 separated; <= 0 overlapping, -value = minimum translation depth). Cross
/// axes shorter than 1e-2 (|a x b|^2 < 1e-4, gyro's definition) are skipped: along them a
/// gap divided by a tiny length is ill-conditioned, and face axes decide those pairs.
double ref_obb_obb_separation(const BoxSet& a, std::size_t i, const BoxSet& b, std::size_t j);

// Small binary64 references for the benchmark error figures (float inputs, double math).
struct D3 {
  double x, y, z;
};
inline D3 d3(float x, float y, float z) { return {x, y, z}; }
/// Sphere-sphere: signed gap |c1 - c2| - (r1 + r2) (<= 0 overlapping).
double ref_sphere_sphere_gap(D3 c1, double r1, D3 c2, double r2);
/// Sphere-AABB: signed gap |clamp(c) - c| - r (<= 0 overlapping; 0 also when inside).
double ref_sphere_aabb_gap(D3 c, double r, D3 bc, D3 be);
/// AABB-AABB: largest per-axis gap (<= 0 overlapping).
double ref_aabb_aabb_gap(D3 ac, D3 ae, D3 bc, D3 be);
/// Ray-AABB by slabs in binary64: first surface crossing t in [0, inf), or inf.
double ref_ray_aabb_t(D3 o, D3 d, D3 bc, D3 be);
/// Ray-triangle (double-sided, Moller-Trumbore in binary64): t >= 0 or inf.
double ref_ray_triangle_t(D3 o, D3 d, D3 a, D3 b, D3 c);

}  // namespace gyro::testing
