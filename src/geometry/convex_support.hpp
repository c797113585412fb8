// Private pieces shared by gjk.cpp and epa.cpp: the pair of shapes seen from A's frame, the
// simplex GJK leaves behind, and the EPA entry point.
//
// Everything is computed in A's local frame: B's pose relative to A is formed once (one
// subtraction of positions, one 3x3 product), so a pair far from the world origin is
// worked on near the origin and keeps float precision.
#pragma once

#include "gyro/convex.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>

namespace gyro::detail {

/// A support point of A - B with the points of A and B it came from (A's frame).
struct SupportPoint {
  vec3 w, a, b;  // w = a - b
};

/// Sphere and capsule are a core (point, segment) plus a margin (their radius).
inline float margin_of(const ConvexShape& s) {
  return (s.type == ConvexType::sphere || s.type == ConvexType::capsule) ? s.radius : 0.0f;
}

/// Support of a shape in its own frame; with core, spheres and capsules lose their radius.
// Ties of dot products go to the first (lowest-index) vertex.
inline vec3 max_dot(const vec3* p, uint32_t n, const vec3& d) {
  uint32_t best = 0;
  float bd = dot(p[0], d);
  for (uint32_t i = 1; i < n; ++i) {
    const float t = dot(p[i], d);
    if (t > bd) bd = t, best = i;
  }
  return p[best];
}

// d scaled to length r (a zero d gives r along +x: any surface point is a valid support).
inline vec3 along(const vec3& d, float r) {
  const float dd = dot(d, d);
  if (!(dd > 0.0f)) return {r, 0.0f, 0.0f};
  return normalized(d) * r;
}

// d >= 0 ? h : -h, without a branch: the sign bit flipped by the comparison (the signs of
// support directions are coin flips, and a mispredicted branch costs more than the work).
inline float signed_by(float h, float d) {
  return std::bit_cast<float>(std::bit_cast<uint32_t>(h) ^ (uint32_t(!(d >= 0.0f)) << 31));
}

inline vec3 local_support(const ConvexShape& s, const vec3& d, bool core) {
  switch (s.type) {
    case ConvexType::sphere:
      return core ? vec3{} : along(d, s.radius);
    case ConvexType::box:
      return {signed_by(s.half_extents.x, d.x), signed_by(s.half_extents.y, d.y), signed_by(s.half_extents.z, d.z)};
    case ConvexType::capsule: {
      const vec3 c{0.0f, d.y >= 0.0f ? s.half_height : -s.half_height, 0.0f};
      return core ? c : c + along(d, s.radius);
    }
    case ConvexType::cylinder: {
      const float y = d.y >= 0.0f ? s.half_height : -s.half_height;
      const float rr = d.x * d.x + d.z * d.z;
      if (!(rr > 0.0f)) return {0.0f, y, 0.0f};  // along the axis: the cap's centre is a support point
      // Scale first so tiny or huge radial parts normalise without underflow or overflow.
      const vec3 radial = normalized(vec3{d.x, 0.0f, d.z});
      return {radial.x * s.radius, y, radial.z * s.radius};
    }
    case ConvexType::triangle:
      return max_dot(s.v, 3, d);
    case ConvexType::points:
      return max_dot(s.points, s.count, d);
  }
  return {};
}


/// A and B with B placed in A's frame: x_A = x_B * rot_b + pos_b.
struct PairFrame {
  const ConvexShape* a = nullptr;
  const ConvexShape* b = nullptr;
  mat3 rot_b;    // rows: B's local axes in A's frame
  vec3 pos_b;    // B's origin in A's frame
  bool core = false;  // true: supports of the cores (margins left out)
  float scale = 1.0f; // size of the pair: tolerances are relative to it

  SupportPoint support(const vec3& d) const {
    const vec3 pa = local_support(*a, d, core);
    // -d in B's frame: component k is -d . (B's axis k).
    const vec3 db{-dot(d, vec3{rot_b.m[0][0], rot_b.m[0][1], rot_b.m[0][2]}),
                  -dot(d, vec3{rot_b.m[1][0], rot_b.m[1][1], rot_b.m[1][2]}),
                  -dot(d, vec3{rot_b.m[2][0], rot_b.m[2][1], rot_b.m[2][2]})};
    const vec3 lb = local_support(*b, db, core);
    const vec3 pb = lb * rot_b + pos_b;
    return {pa - pb, pa, pb};
  }
};

/// GJK's final simplex (1 to 4 points) with the barycentric weights of its closest point.
struct Simplex {
  SupportPoint p[4];
  float lambda[4] = {0, 0, 0, 0};
  int n = 0;
};

/// What EPA found, in A's frame: depth >= 0 along normal (unit, A towards B), witnesses.
struct EpaOutcome {
  bool converged = false;  // false: iteration or capacity limit; the fields are the best so far
  bool flat = false;       // A - B has no volume: depth 0 along a normal of the flat set
  float depth = 0.0f;
  vec3 normal, point_a, point_b;
  uint32_t iterations = 0;
};

/// Expanding polytope from a simplex whose hull contains the origin (on its boundary is
/// allowed: GJK exits with 1 to 4 points). Fixed capacity, no heap.
EpaOutcome epa(const PairFrame& pair, const Simplex& start, uint32_t max_iterations);

/// out[i] = epa(*pairs[i], starts[i], max_iterations) for i in [0, count), bit for bit, where
/// every pair is two boxes' cores: up to 16 polytopes grow side by side, their supports and
/// new faces' planes computed over SIMD lanes (epa_lanes.hpp) and their topology per polytope.
void epa_boxes(const PairFrame* const* pairs, const Simplex* starts, std::size_t count, uint32_t max_iterations,
               EpaOutcome* out);

}  // namespace gyro::detail
