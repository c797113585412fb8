// BodyStore: every rigid body's state in structure-of-arrays columns, dense slots
// 0..size()-1 named by stable ids (core/id_pool.hpp).
//
// Hot columns (what integration and the solver read every sub-step) are separate floats;
// cold data (shape parameters, materials, user data) sits in its own columns and is read
// once per step when the solver is prepared. Destroying a body moves the last slot into the
// hole in every column, as the id pool does, so the layout depends only on the calls made.
#pragma once

#include "core/columns.hpp"
#include "core/id_pool.hpp"
#include "core/state_hash.hpp"
#include "dynamics/body_hull.hpp"
#include "gyro/shapes.hpp"
#include "gyro/world.hpp"

#include <cstdint>

namespace gyro::detail {

enum BodyFlags : uint32_t {
  kBodyAllowSleep = 1u << 0,
  kBodyAwake = 1u << 1,
};

struct BodyStore {
  IdPool ids;
  Column<BodyId> id{BodyId{}};  // ids[slot], for views

  // Pose and motion (hot).
  Column<float> px, py, pz;
  Column<float> qx, qy, qz, qw{1.0f};
  Column<float> vx, vy, vz;
  Column<float> wx, wy, wz;
  // Forces and torques accumulated for the next step.
  Column<float> fx, fy, fz;
  Column<float> tx, ty, tz;
  // Mass properties: inverse mass and the inverse of the diagonal body-frame inertia
  // (spheres and boxes have diagonal inertia in their own frame).
  Column<float> mass, inv_mass;
  Column<float> inv_ix, inv_iy, inv_iz;
  Column<float> linear_damping, angular_damping, gravity_scale;
  Column<float> sleep_time;

  // Cold.
  Column<uint32_t> type;   // BodyType
  Column<uint32_t> shape;  // BodyShape
  Column<float> radius;    // sphere radius (bounding radius for other shapes)
  Column<float> hx, hy, hz;  // box half extents; capsule radius, half height, 0
  Column<const TriangleMesh*> mesh{nullptr};
  Column<const BodyHull*> hull{nullptr};  // owned by the world
  Column<float> friction, restitution;
  Column<uint32_t> category, mask;
  Column<uint32_t> flags;
  Column<uint64_t> user_data;

  uint32_t size() const { return ids.size(); }

  template <class F> void for_each_column(F&& f) {
    f(id), f(px), f(py), f(pz), f(qx), f(qy), f(qz), f(qw), f(vx), f(vy), f(vz), f(wx), f(wy), f(wz);
    f(fx), f(fy), f(fz), f(tx), f(ty), f(tz), f(mass), f(inv_mass), f(inv_ix), f(inv_iy), f(inv_iz);
    f(linear_damping), f(angular_damping), f(gravity_scale), f(sleep_time);
    f(type), f(shape), f(radius), f(hx), f(hy), f(hz), f(mesh), f(hull), f(friction), f(restitution);
    f(category), f(mask), f(flags), f(user_data);
  }

  /// Every column gets room for n bodies (false if memory ran out; nothing lost).
  bool reserve(std::size_t n) {
    bool ok = true;
    for_each_column([&](auto& c) { ok = ok && c.reserve(n); });
    return ok;
  }

  bool is_dynamic(uint32_t s) const { return type[s] == uint32_t(BodyType::dynamic); }
  bool is_static(uint32_t s) const { return type[s] == uint32_t(BodyType::static_body); }
  bool is_awake(uint32_t s) const { return (flags[s] & kBodyAwake) != 0; }

  vec3 position(uint32_t s) const { return {px[s], py[s], pz[s]}; }
  quat orientation(uint32_t s) const { return {qx[s], qy[s], qz[s], qw[s]}; }
  vec3 linear_velocity(uint32_t s) const { return {vx[s], vy[s], vz[s]}; }
  vec3 angular_velocity(uint32_t s) const { return {wx[s], wy[s], wz[s]}; }
  void set_position(uint32_t s, const vec3& p) { px[s] = p.x, py[s] = p.y, pz[s] = p.z; }
  void set_orientation(uint32_t s, const quat& q) { qx[s] = q.x, qy[s] = q.y, qz[s] = q.z, qw[s] = q.w; }
  void set_linear_velocity(uint32_t s, const vec3& v) { vx[s] = v.x, vy[s] = v.y, vz[s] = v.z; }
  void set_angular_velocity(uint32_t s, const vec3& w) { wx[s] = w.x, wy[s] = w.y, wz[s] = w.z; }

  /// Hashes every column in slot order (the mesh pointer as its triangle count: pointers
  /// differ between runs).
  void hash_into(StateHasher& h) const;
};

}  // namespace gyro::detail
