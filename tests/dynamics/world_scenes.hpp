// Scene builders shared by the world tests, the determinism scenes and the benchmarks.
#pragma once

#include "gyro/world.hpp"

#include <memory>
#include <vector>

namespace gyro::test {

inline std::unique_ptr<World> make_world(const WorldDef& def = WorldDef{}) {
  std::unique_ptr<World> w;
  if (World::create(def, &w) != Status::ok) return nullptr;
  return w;
}

/// A static ground box whose top face is y = top.
inline BodyId add_ground(World& w, float top = 0.0f, vec3 half = {50.0f, 0.5f, 50.0f}, float friction = 0.6f) {
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::box;
  d.shape.half_extents = half;
  d.position = {0.0f, top - half.y, 0.0f};
  d.friction = friction;
  BodyId id;
  return w.create_body(d, &id) == Status::ok ? id : BodyId{};
}

inline BodyId add_box(World& w, vec3 p, vec3 half = {0.5f, 0.5f, 0.5f}, float mass = 1.0f, float friction = 0.6f) {
  BodyDef d;
  d.shape.type = BodyShape::box;
  d.shape.half_extents = half;
  d.position = p;
  d.mass = mass;
  d.friction = friction;
  BodyId id;
  return w.create_body(d, &id) == Status::ok ? id : BodyId{};
}

/// BENCHMARKS.md's P1 layout: rows of 1 m boxes with 0.1 m gaps, base `base`, mass 1.
inline std::vector<BodyId> add_pyramid(World& w, int base, float x0 = 0.0f, float z0 = 0.0f) {
  std::vector<BodyId> ids;
  for (int i = 0; i < base; ++i) {
    const int n = base - i;
    for (int k = 0; k < n; ++k) {
      const float x = x0 + (float(k) - float(n - 1) * 0.5f) * 1.1f;
      ids.push_back(add_box(w, {x, 0.5f + float(i), z0}));
    }
  }
  return ids;
}

inline vec3 position_of(const World& w, BodyId id) {
  vec3 p;
  w.get_transform(id, &p, nullptr);
  return p;
}

inline std::vector<vec3> positions(const World& w, const std::vector<BodyId>& ids) {
  std::vector<vec3> p;
  for (BodyId id : ids) p.push_back(position_of(w, id));
  return p;
}

/// The largest distance any of the bodies moved from `start` (positions(w, ids) earlier).
inline double max_drift(const World& w, const std::vector<BodyId>& ids, const std::vector<vec3>& start) {
  double m = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const double d = double(length(position_of(w, ids[i]) - start[i]));
    m = d > m ? d : m;
  }
  return m;
}

/// A static ground plane y = 0 (normal +y).
inline BodyId add_plane(World& w) {
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::plane;
  BodyId id;
  return w.create_body(d, &id) == Status::ok ? id : BodyId{};
}

}  // namespace gyro::test
