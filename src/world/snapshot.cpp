// World snapshots: the whole state to bytes and back.
//
// Layout: a 32-byte header (magic "GYROSNAP", format version, flags, payload bytes, checksum
// of the payload), then the payload: settings, step count, the mesh table (every mesh a body
// or soft collider references, by first use), the body id allocator and every body column,
// the hull bodies' hulls, the contact records, the particles and the soft bodies. Each part
// is described once by a template that both writes and reads (core/byte_stream.hpp), so the
// two directions cannot drift apart. A restore reads into a fresh world and swaps it in only
// when everything read is consistent, so a bad buffer leaves the world as it was.
#include "core/byte_stream.hpp"
#include "core/error.hpp"
#include "core/validate.hpp"
#include "dynamics/particles_internal.hpp"
#include "dynamics/snapshot_io.hpp"
#include "dynamics/soft_body_internal.hpp"
#include "gyro/particles.hpp"
#include "gyro/soft_body.hpp"
#include "gyro/triangle_mesh.hpp"
#include "world/world_impl.hpp"

#include <cstring>
#include <new>

namespace gyro {
namespace {

using detail::ByteReader;
using detail::ByteWriter;
using detail::fail;

constexpr char kMagic[8] = {'G', 'Y', 'R', 'O', 'S', 'N', 'A', 'P'};
constexpr uint32_t kFormatVersion = 1;
constexpr std::size_t kHeaderBytes = 32;

template <class Io, class D> void io_def(Io& io, D& d) {
  io.v3(d.gravity);
  io.enumeration(d.contact_model, uint32_t(ContactModel::linear_projection));
  io.u32(d.substeps), io.u32(d.velocity_iterations), io.u32(d.relax_iterations), io.u32(d.position_iterations);
  io.f32(d.linear_slop), io.f32(d.baumgarte), io.f32(d.contact_hertz), io.f32(d.contact_damping_ratio);
  io.f32(d.max_push_velocity), io.f32(d.restitution_threshold);
  io.boolean(d.enable_warm_starting), io.boolean(d.enable_sleep);
  io.f32(d.sleep_time), io.f32(d.sleep_linear_velocity), io.f32(d.sleep_angular_velocity);
  io.boolean(d.enable_continuous);
  io.enumeration(d.convex_manifold, uint32_t(ConvexManifold::incremental));
  io.u32(d.threads);
}

template <class Io, class S> void io_body_columns(Io& io, S& s, std::size_t n) {
  io.column(s.id, n);
  for (auto* c : {&s.px, &s.py, &s.pz, &s.qx, &s.qy, &s.qz, &s.qw, &s.vx, &s.vy, &s.vz, &s.wx, &s.wy, &s.wz, &s.fx,
                  &s.fy, &s.fz, &s.tx, &s.ty, &s.tz, &s.mass, &s.inv_mass, &s.inv_ix, &s.inv_iy, &s.inv_iz,
                  &s.linear_damping, &s.angular_damping, &s.gravity_scale, &s.sleep_time, &s.radius, &s.hx, &s.hy,
                  &s.hz, &s.friction, &s.restitution})
    io.column(*c, n);
  for (auto* c : {&s.type, &s.shape, &s.category, &s.mask, &s.flags}) io.column(*c, n);
  io.column(s.user_data, n);
}

template <class Io, class H> void io_hull(Io& io, H& b) {
  auto& h = b.hull;
  io.vec3s(h.vertices);
  io.array(h.face_start), io.array(h.face_vertices), io.array(h.edges);
  std::size_t planes = h.planes.size();
  io.count(planes, io.remaining() / 16);
  if constexpr (Io::reading) {
    if (!io.ok()) return;
    h.planes.assign(planes, Plane{});
  }
  for (auto& p : h.planes) io.v3(p.normal), io.f32(p.distance);
  io.v3(b.shape_offset), io.q4(b.shape_rotation);
  io.v3(b.local_bounds.center), io.v3(b.local_bounds.half_extents);
  io.f32(b.bound_radius), io.v3(b.unit_inertia), io.f32(b.volume);
}

/// What GJK, EPA and the clipping index with must be in range.
bool hull_consistent(const ConvexHull& h) {
  const std::size_t nv = h.vertices.size(), nf = h.planes.size();
  if (nv < 4 || nf < 4 || h.face_start.size() != nf + 1 || h.face_start[0] != 0 ||
      h.face_start[nf] != h.face_vertices.size() || h.edges.size() % 2 != 0)
    return false;
  for (std::size_t f = 0; f < nf; ++f)
    if (h.face_start[f + 1] < h.face_start[f] + 3) return false;
  for (uint32_t v : h.face_vertices)
    if (v >= nv) return false;
  for (uint32_t v : h.edges)
    if (v >= nv) return false;
  return true;
}

template <class Io, class R> void io_record(Io& io, R& r) {
  io.u64(r.key), io.u32(r.sub), io.u32(r.gen_a), io.u32(r.gen_b), io.u32(r.slot_a), io.u32(r.slot_b);
  io.f32(r.friction), io.f32(r.restitution);
  io.v3(r.manifold.normal), io.u32(r.manifold.count);
  for (auto& p : r.manifold.points) io.v3(p.position), io.f32(p.separation), io.u32(p.feature_id);
  for (auto& f : r.normal_impulse) io.f32(f);
  for (auto& f : r.friction_impulse) io.f32(f);
  for (auto& a : r.anchors.a) io.v3(a);
  for (auto& b : r.anchors.b) io.v3(b);
}

bool same_mesh(const MeshData& a, const MeshData& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z) && same(a.indices, b.indices);
}

/// Every mesh the world references, bodies first in slot order, then soft colliders.
detail::SnapshotMeshes mesh_table(const World::Impl& m) {
  detail::SnapshotMeshes t;
  for (uint32_t i = 0; i < m.bodies.size(); ++i) t.add(m.bodies.mesh[i]);
  for (const auto& body : m.soft_bodies) detail::SoftAccess::add_meshes(*body, t);
  return t;
}

void write_payload(ByteWriter& w, const World::Impl& m) {
  io_def(w, m.def);
  w.u64(m.steps);

  const detail::SnapshotMeshes meshes = mesh_table(m);
  w.u64(meshes.list.size());
  for (const TriangleMesh* mesh : meshes.list) {
    const MeshData& d = mesh->data();
    w.array(d.x), w.array(d.y), w.array(d.z), w.array(d.indices);
  }

  const detail::BodyStore& s = m.bodies;
  const std::size_t n = s.size();
  s.ids.write(w);
  io_body_columns(w, s, n);
  for (std::size_t i = 0; i < n; ++i) w.u32(meshes.index_of(s.mesh[i]));
  for (std::size_t i = 0; i < n; ++i)
    if (s.hull[i]) io_hull(w, *s.hull[i]);

  const auto& records = m.contacts.records();
  w.u64(records.size());
  for (const detail::ContactRecord& r : records) {
    // Entries past the manifold's count hold whatever the narrowphase's scratch held: they
    // are never read, and are written as zeros so equal states give equal bytes.
    detail::ContactRecord c = r;
    for (uint32_t j = c.manifold.count; j < detail::kMaxManifoldPoints; ++j) {
      c.manifold.points[j] = detail::ContactPoint{};
      c.normal_impulse[j] = 0.0f;
      c.anchors.a[j] = c.anchors.b[j] = vec3{};
    }
    io_record(w, c);
  }

  w.boolean(m.particles != nullptr);
  if (m.particles) detail::ParticleAccess::write(*m.particles, w);

  m.soft_pool.write(w);
  for (const auto& body : m.soft_bodies) detail::SoftAccess::write(*body, w, meshes);
}

/// Reads the payload into `out` (a fresh world created with the snapshot's settings by the
/// caller after io_def). `current` lends its meshes: identical geometry is shared, not rebuilt.
Status read_payload(ByteReader& r, World::Impl& out, const World::Impl* current) {
  r.u64(out.steps);

  // Meshes: shared with the current world when bit-identical, else rebuilt (the BVH build is
  // deterministic, so a rebuilt mesh answers every query as the original did).
  std::size_t mesh_count = 0;
  r.count(mesh_count, r.remaining() / 32);
  detail::SnapshotMeshes meshes;
  detail::SnapshotMeshes lendable;
  std::vector<std::shared_ptr<const TriangleMesh>> lendable_owned;
  if (current) {
    lendable = mesh_table(*current);
    for (const auto& owned : current->owned_meshes) lendable.add(owned.get());
  }
  for (std::size_t k = 0; r.ok() && k < mesh_count; ++k) {
    MeshData d;
    r.array(d.x), r.array(d.y), r.array(d.z), r.array(d.indices);
    if (!r.ok()) break;
    const TriangleMesh* found = nullptr;
    for (const TriangleMesh* cand : lendable.list)
      if (same_mesh(cand->data(), d)) {
        found = cand;
        break;
      }
    if (found) {
      // Keep the world's own copy alive if that is what matched.
      for (const auto& owned : current->owned_meshes)
        if (owned.get() == found) out.owned_meshes.push_back(owned);
    } else {
      std::shared_ptr<TriangleMesh> mesh(new (std::nothrow) TriangleMesh());
      if (!mesh) return fail(Status::out_of_memory, "snapshot mesh");
      if (TriangleMesh::create(d, *mesh) != Status::ok) return fail(Status::corrupt_data, "snapshot: mesh %zu is invalid", k);
      out.owned_meshes.push_back(mesh);
      found = mesh.get();
    }
    meshes.list.push_back(found);
  }

  detail::BodyStore& s = out.bodies;
  s.ids.read(r);
  const std::size_t n = r.ok() ? s.ids.size() : 0;
  io_body_columns(r, s, n);
  if (!r.ok()) return r.out_of_memory() ? fail(Status::out_of_memory, "snapshot bodies") : fail(Status::corrupt_data, "snapshot: bodies");
  if (!s.mesh.resize(n, nullptr) || !s.hull.resize(n, nullptr)) return fail(Status::out_of_memory, "snapshot bodies");
  for (std::size_t i = 0; r.ok() && i < n; ++i) {
    const detail::Id id = s.ids.id_at(uint32_t(i));
    r.require(s.id[i] == BodyId{id.index, id.generation});
    r.require(s.type[i] <= uint32_t(BodyType::dynamic) && s.shape[i] <= uint32_t(BodyShape::hull) && s.flags[i] <= 3u);
    uint32_t mesh = 0;
    r.u32(mesh);
    s.mesh[i] = meshes.at(mesh, r);
    r.require((s.mesh[i] != nullptr) == (s.shape[i] == uint32_t(BodyShape::mesh)));
    r.require(s.shape[i] == uint32_t(BodyShape::box) || s.shape[i] == uint32_t(BodyShape::capsule) || s.hx[i] == 0.0f);
  }
  if (!r.ok()) return fail(Status::corrupt_data, "snapshot: body shapes");
  for (std::size_t i = 0; i < n; ++i) {
    if (s.shape[i] != uint32_t(BodyShape::hull)) continue;
    const uint32_t index = s.id[i].index;
    try {
      if (out.hulls.size() <= index) out.hulls.resize(std::size_t(index) + 1);
    } catch (const std::bad_alloc&) {
      return fail(Status::out_of_memory, "snapshot hulls");
    }
    out.hulls[index].reset(new (std::nothrow) detail::BodyHull);
    if (!out.hulls[index]) return fail(Status::out_of_memory, "snapshot hulls");
    io_hull(r, *out.hulls[index]);
    if (!r.ok() || !hull_consistent(out.hulls[index]->hull)) return fail(Status::corrupt_data, "snapshot: hull of body %zu", i);
    s.hull[i] = out.hulls[index].get();
  }

  std::size_t record_count = 0;
  r.count(record_count, r.remaining() / 64);
  std::vector<detail::ContactRecord> records;
  try {
    records.resize(record_count);
  } catch (const std::bad_alloc&) {
    return fail(Status::out_of_memory, "snapshot contacts");
  }
  for (std::size_t k = 0; r.ok() && k < record_count; ++k) {
    detail::ContactRecord& c = records[k];
    io_record(r, c);
    // The solver indexes bodies by these slots, and the merge relies on the order.
    const uint32_t sa = s.ids.slot({c.index_a(), c.gen_a}), sb = s.ids.slot({c.index_b(), c.gen_b});
    r.require(c.index_a() < c.index_b() && sa != detail::IdPool::kNoSlot && sb != detail::IdPool::kNoSlot);
    r.require(sa == c.slot_a && sb == c.slot_b && c.manifold.count <= detail::kMaxManifoldPoints);
    if (k > 0) {
      const detail::ContactRecord& p = records[k - 1];
      r.require(p.key < c.key || (p.key == c.key && p.sub < c.sub));
    }
  }
  if (!r.ok()) return fail(Status::corrupt_data, "snapshot: contacts");
  out.contacts.set_records(std::move(records));

  bool particles = false;
  r.boolean(particles);
  if (r.ok() && particles) {
    out.particles.reset(new (std::nothrow) ParticleSystem());
    if (!out.particles) return fail(Status::out_of_memory, "snapshot particles");
    detail::ParticleAccess::read(r, *out.particles);
  }
  if (!r.ok()) return r.out_of_memory() ? fail(Status::out_of_memory, "snapshot particles") : fail(Status::corrupt_data, "snapshot: particles");

  out.soft_pool.read(r);
  const std::size_t soft = r.ok() ? out.soft_pool.size() : 0;
  for (std::size_t k = 0; r.ok() && k < soft; ++k) {
    std::unique_ptr<SoftBody> body(new (std::nothrow) SoftBody());
    if (!body) return fail(Status::out_of_memory, "snapshot soft bodies");
    detail::SoftAccess::read(r, *body, meshes);
    out.soft_bodies.push_back(std::move(body));
  }
  if (!r.ok()) return r.out_of_memory() ? fail(Status::out_of_memory, "snapshot soft bodies") : fail(Status::corrupt_data, "snapshot: soft bodies");
  if (!r.at_end()) return fail(Status::corrupt_data, "snapshot: bytes after the end");
  return Status::ok;
}

uint32_t load_u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
uint64_t load_u64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

}  // namespace

/// Checks the header and checksum and builds a world from the payload.
Status World::from_snapshot(const void* data, std::size_t size, const Impl* current, std::unique_ptr<World>* out) {
  if (!data) return fail(Status::null_argument, "snapshot data is null");
  const auto* p = static_cast<const uint8_t*>(data);
  if (size < kHeaderBytes || std::memcmp(p, kMagic, 8) != 0)
    return fail(Status::corrupt_data, "not a gyro snapshot (%zu bytes, no GYROSNAP header)", size);
  if (load_u32(p + 8) != kFormatVersion)
    return fail(Status::corrupt_data, "snapshot format version %u; this library reads version %u", load_u32(p + 8), kFormatVersion);
  const uint64_t payload = load_u64(p + 16);
  if (load_u32(p + 12) != 0 || payload != size - kHeaderBytes)
    return fail(Status::corrupt_data, "snapshot is truncated or padded (%zu bytes, header says %llu)", size,
                static_cast<unsigned long long>(payload + kHeaderBytes));
  if (detail::checksum64(p + kHeaderBytes, payload) != load_u64(p + 24))
    return fail(Status::corrupt_data, "snapshot checksum mismatch");
  ByteReader r(p + kHeaderBytes, payload);
  WorldDef def;
  io_def(r, def);
  std::unique_ptr<World> world;
  if (!r.ok() || World::create(def, &world) != Status::ok) return fail(Status::corrupt_data, "snapshot: world settings");
  GYRO_TRY(read_payload(r, *world->impl_, current));
  *out = std::move(world);
  return Status::ok;
}

std::size_t World::snapshot_size() const {
  ByteWriter counter;
  write_payload(counter, *impl_);
  return kHeaderBytes + counter.size();
}

Status World::snapshot(void* buffer, std::size_t capacity, std::size_t* size) const {
  if (!buffer) return fail(Status::null_argument, "buffer is null");
  if (!size) return fail(Status::null_argument, "size is null");
  const std::size_t need = snapshot_size();
  if (capacity < need) return fail(Status::invalid_count, "snapshot needs %zu bytes, capacity is %zu", need, capacity);
  auto* p = static_cast<uint8_t*>(buffer);
  ByteWriter w(p + kHeaderBytes);
  write_payload(w, *impl_);
  const uint64_t payload = w.size();
  const uint64_t sum = detail::checksum64(p + kHeaderBytes, payload);
  std::memcpy(p, kMagic, 8);
  std::memcpy(p + 8, &kFormatVersion, 4);
  std::memset(p + 12, 0, 4);
  std::memcpy(p + 16, &payload, 8);
  std::memcpy(p + 24, &sum, 8);
  *size = need;
  return Status::ok;
}

Status World::restore(const void* data, std::size_t size) {
  std::unique_ptr<World> fresh;
  GYRO_TRY(from_snapshot(data, size, impl_.get(), &fresh));
  fresh->impl_->def.threads = impl_->def.threads;
  impl_.swap(fresh->impl_);
  return Status::ok;
}

Status World::create_from_snapshot(const void* data, std::size_t size, std::unique_ptr<World>* out) {
  if (!out) return fail(Status::null_argument, "out is null");
  return from_snapshot(data, size, nullptr, out);
}

}  // namespace gyro
