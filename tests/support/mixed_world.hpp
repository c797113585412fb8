// A world with one of everything a snapshot must carry: every body shape and type (a mesh
// ramp shared by a soft collider too), sleeping and awake bodies, particles with colliders,
// a pinned cloth with a joint and a soft cube. Used by the snapshot tests and the
// determinism scene that pins the snapshot bytes.
#pragma once

#include "gyro/convex.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/mesh.hpp"
#include "gyro/particles.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/triangle_mesh.hpp"
#include "gyro/world.hpp"

#include <vector>

namespace gyro::test {

/// The static mesh the mixed world's ramp and cloth collider use (the caller keeps it alive).
inline TriangleMesh make_mixed_world_ramp() {
  TriangleMesh m;
  MeshData grid = make_grid_mesh(6, 6, 1.0f, [](float x, float z, void*) { return 0.12f * x + 0.04f * z; });
  TriangleMesh::create(grid, m);
  return m;
}

/// Fills w (a fresh world); false if any call failed.
inline bool build_mixed_world(World& w, const TriangleMesh& ramp) {
  BodyId id;
  BodyDef d;
  d.type = BodyType::static_body;
  d.shape.type = BodyShape::plane;
  if (w.create_body(d, &id) != Status::ok) return false;
  d.shape.type = BodyShape::mesh;
  d.shape.mesh = &ramp;
  d.position = {5.0f, 0.01f, -3.0f};
  if (w.create_body(d, &id) != Status::ok) return false;

  BodyDef k;
  k.type = BodyType::kinematic;
  k.shape.half_extents = {1.5f, 0.1f, 0.3f};
  k.position = {-5.0f, 0.5f, 0.0f};
  k.angular_velocity = {0.0f, 1.2f, 0.0f};
  if (w.create_body(k, &id) != Status::ok) return false;

  std::vector<vec3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back({(i & 1) ? 0.3f : -0.3f, (i & 2) ? 0.25f : -0.25f, (i & 4) ? 0.35f : -0.35f});
  pts.push_back({0.0f, 0.45f, 0.0f});
  ConvexHull hull;
  if (build_convex_hull(pts.data(), pts.size(), hull) != Status::ok) return false;

  std::vector<BodyId> bodies;
  for (int i = 0; i < 18; ++i) {
    BodyDef b;
    const int kind = i % 6;
    b.shape.type = kind == 0 ? BodyShape::sphere : kind == 1 ? BodyShape::capsule : kind == 2 ? BodyShape::hull : BodyShape::box;
    b.shape.radius = 0.25f + 0.02f * float(i % 4);
    b.shape.half_height = 0.3f;
    b.shape.half_extents = {0.3f + 0.02f * float(i % 3), 0.3f, 0.35f};
    b.shape.hull = &hull;
    b.position = {-2.0f + 0.9f * float(i % 5), 0.5f + 0.8f * float(i / 5), -0.5f + 0.3f * float(i % 3)};
    b.orientation = from_axis_angle({0.3f, 1.0f, 0.1f * float(i)}, 0.2f * float(i));
    b.restitution = i % 4 == 0 ? 0.3f : 0.0f;
    b.angular_velocity = {0.1f * float(i % 3), 0.0f, -0.1f};
    b.user_data = uint64_t(1000 + i);
    b.awake = i != 7;
    if (w.create_body(b, &id) != Status::ok) return false;
    bodies.push_back(id);
  }
  // A destroyed body leaves a free id, so the allocator's order is exercised too.
  if (w.destroy_body(bodies[4]) != Status::ok) return false;

  ParticleSystem& ps = w.particles();
  uint32_t index;
  if (ps.add_collider(Plane{{0.0f, 1.0f, 0.0f}, 0.0f}, &index) != Status::ok) return false;
  if (ps.add_collider(Sphere{{3.0f, 1.0f, 3.0f}, 0.6f}, &index) != Status::ok) return false;
  for (int i = 0; i < 24; ++i) {
    ParticleDef p;
    p.position = {2.5f + 0.05f * float(i % 5), 2.0f + 0.1f * float(i), 3.0f + 0.03f * float(i % 7)};
    p.velocity = {0.2f * float(i % 3) - 0.2f, 0.0f, 0.1f};
    p.pinned = i == 5;
    ParticleId pid;
    if (ps.create(p, &pid) != Status::ok) return false;
  }

  ClothDef cd;
  cd.nx = cd.nz = 10;
  cd.size_x = cd.size_z = 1.8f;
  cd.center = {5.0f, 1.6f, -3.0f};
  cd.particle_mass = 0.05f;
  SoftBody cloth;
  if (SoftBody::make_cloth(cd, &cloth) != Status::ok) return false;
  if (cloth.cloth_index(0, 0, &index) != Status::ok || cloth.pin(index) != Status::ok) return false;
  uint32_t a, b;
  if (cloth.cloth_index(0, 9, &a) != Status::ok || cloth.cloth_index(9, 9, &b) != Status::ok) return false;
  if (cloth.add_joint({a, b, 1.5f}) != Status::ok) return false;
  if (cloth.add_collider(ramp, &index) != Status::ok) return false;
  SoftBodyId sid;
  if (w.add_soft_body(cloth, &sid) != Status::ok) return false;
  SoftBody cube;
  SoftCubeDef cu;
  cu.center = {0.0f, 4.0f, 2.0f};
  cu.half_extent = 0.2f;
  if (SoftBody::make_cube(cu, &cube) != Status::ok) return false;
  return w.add_soft_body(cube, &sid) == Status::ok;
}

}  // namespace gyro::test
