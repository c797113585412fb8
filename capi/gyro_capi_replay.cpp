// The C ABI's record and replay (ABI 1.5): a recording world's log (capi_recorder.hpp holds
// the format, the opcodes and the argument codecs), the geometry it stores, and replay.
//
// Replay reads strictly: the checksum is verified before anything else, every count and
// payload is bounded by the bytes that remain, every record must be consumed exactly, and
// geometry references must name geometry read before. A recording that fails any of this is
// GYRO_STATUS_CORRUPT_DATA (and nothing is written to the report), never a crash.
//
// Divergence: a step whose hash differs from the recorded one, a recorded call that fails
// when replayed (it succeeded when recorded), a restore that fails, or a create call that
// returns another id than it did are all divergences: GYRO_OK with diverged = 1. For a step,
// first_divergent_step is that step and expected_hash / actual_hash are the two hashes (actual
// 0 when the step itself failed); for any other call, first_divergent_step is the index of the
// next step (the number of steps replayed before the call) and both hashes are 0. Replay goes
// on to the end after a divergence (a failed call is skipped), so calls, steps and final_hash
// always describe the whole recording.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_convex.hpp"
#include "capi_handles.hpp"
#include "capi_recorder.hpp"
#include "capi_support.hpp"
#include "capi_world.hpp"
#include "core/state_hash.hpp"
#include "core/validate.hpp"
#include "gyro/triangle_mesh.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyro::capi::rec {

void RecorderDelete::operator()(Recorder* r) const noexcept { delete r; }

Replayer::~Replayer() {
  for (gyro_mesh* m : meshes) gyro_mesh_destroy(m);
  for (gyro_convex_hull* h : hulls) gyro_convex_hull_destroy(h);
}

namespace {

constexpr int kMeshKind = 0, kHullKind = 1;

/// The geometry payload in r.scratch, stored once: the index of an identical payload stored
/// before, else a new record (opcode op) and a new index.
uint32_t store_geometry(Recorder& r, int kind, uint32_t op) {
  const std::vector<uint8_t>& p = r.scratch;
  const uint64_t h = detail::fnv1a64(p.data(), p.size());
  const auto [first, last] = r.geometry[kind].equal_range(h);
  for (auto it = first; it != last; ++it) {
    const Recorder::Stored& s = it->second;
    if (s.size == p.size() && std::memcmp(r.bytes.data() + s.offset, p.data(), p.size()) == 0) return s.index;
  }
  if (r.geometry_count[kind] == kNoGeometry - 1) throw std::length_error("too many meshes or hulls");
  const std::size_t at = r.begin_record(op);
  const std::size_t offset = r.bytes.size();
  r.w.bytes(p.data(), p.size());
  r.end_record(at);
  const uint32_t index = r.geometry_count[kind];
  r.geometry[kind].emplace(h, Recorder::Stored{index, offset, p.size()});
  ++r.geometry_count[kind];
  return index;
}

void check_u32(std::size_t n) {
  if (n > std::numeric_limits<uint32_t>::max()) throw std::length_error("geometry too large to record");
}

}  // namespace

// Mesh payload: u32 vertex count, u32 triangle count, x[], y[], z[] (f32), indices[] (u32).
uint32_t mesh_ref(Recorder& r, const gyro_mesh* mesh) {
  if (!mesh) return kNoGeometry;
  const TriangleMesh* key = mesh->mesh.get();
  if (const auto it = r.mesh_ids.find(key); it != r.mesh_ids.end()) return it->second.second;
  const MeshData& d = mesh->mesh->data();
  check_u32(d.x.size()), check_u32(d.indices.size() / 3);
  r.scratch.clear();
  Writer w(r.scratch);
  w.u32(uint32_t(d.x.size())), w.u32(uint32_t(d.indices.size() / 3));
  for (const std::vector<float>* a : {&d.x, &d.y, &d.z})
    for (float v : *a) w.f32(v);
  for (uint32_t i : d.indices) w.u32(i);
  const uint32_t index = store_geometry(r, kMeshKind, kOpMesh);
  r.mesh_ids.emplace(key, std::make_pair(mesh->mesh, index));
  return index;
}

// Hull payload: the whole gyro::ConvexHull, so the replayed body gets the same bits:
// u32 n, n vertices (3 f32); u32 f, f + 1 face starts; u32 m, m face vertices; f planes
// (normal 3 f32, distance f32); u32 e, e edge entries (2 per edge).
uint32_t hull_ref(Recorder& r, const gyro_convex_hull* hull) {
  if (!hull) return kNoGeometry;
  const ConvexHull& h = hull->hull;
  check_u32(h.vertices.size()), check_u32(h.planes.size()), check_u32(h.face_vertices.size());
  check_u32(h.edges.size());
  r.scratch.clear();
  Writer w(r.scratch);
  w.u32(uint32_t(h.vertices.size()));
  for (const vec3& v : h.vertices) w.f32(v.x), w.f32(v.y), w.f32(v.z);
  w.u32(uint32_t(h.planes.size()));
  for (std::size_t f = 0; f <= h.planes.size(); ++f) w.u32(f < h.face_start.size() ? h.face_start[f] : 0u);
  w.u32(uint32_t(h.face_vertices.size()));
  for (uint32_t v : h.face_vertices) w.u32(v);
  for (const Plane& p : h.planes) w.f32(p.normal.x), w.f32(p.normal.y), w.f32(p.normal.z), w.f32(p.distance);
  w.u32(uint32_t(h.edges.size()));
  for (uint32_t v : h.edges) w.u32(v);
  return store_geometry(r, kHullKind, kOpHull);
}

}  // namespace gyro::capi::rec

namespace {

using gyro::Status;
using gyro::capi::guarded;
using gyro::capi::require;
using gyro::capi::rec::Reader;
using gyro::capi::rec::Recorder;
using gyro::capi::rec::Replayer;
using gyro::detail::fail;
namespace rec = gyro::capi::rec;

/// gyro_replay_file reads at most this much: a larger file is refused before it is read.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;

Status require_recording(const gyro_world* world) {
  GYRO_TRY(require(world, "world"));
  if (!world->recorder) return fail(Status::invalid_argument, "the world is not recording (gyro_world_record_begin)");
  if (world->recorder->lost)
    return fail(Status::out_of_memory,
                "the recording is incomplete: a call could not be recorded (out of memory); end it and begin again");
  return Status::ok;
}

/// The end record and the checksum that complete the recording's bytes.
std::vector<uint8_t> tail_of(const Recorder& r) {
  std::vector<uint8_t> tail;
  tail.reserve(rec::kTailBytes);
  rec::Writer w(tail);
  w.u32(rec::kOpEnd), w.u32(16), w.u64(r.calls), w.u64(r.steps);
  uint64_t h = gyro::detail::fnv1a64(r.bytes.data(), r.bytes.size());
  h = gyro::detail::fnv1a64(tail.data(), tail.size(), h);
  w.u64(h);
  return tail;
}

// ---- replay

/// Reads a mesh record and creates the mesh through the C ABI (as the caller did).
Status read_mesh(Reader& in, Replayer& rp) {
  const uint32_t nv = in.u32(), nt = in.u32();
  if (!in.fits(nv, 12) || !in.fits(uint64_t(nt) * 3, 4)) return fail(Status::corrupt_data, "recording: mesh size");
  std::vector<float> x(nv), y(nv), z(nv);
  std::vector<uint32_t> indices(std::size_t(nt) * 3);
  for (std::vector<float>* a : {&x, &y, &z})
    for (float& v : *a) in.f32(v);
  for (uint32_t& i : indices) in.u32(i);
  if (!in.ok() || in.remaining() != 0 || nv > uint32_t(INT32_MAX) || nt > uint32_t(INT32_MAX))
    return fail(Status::corrupt_data, "recording: mesh record");
  gyro_mesh_def d = gyro_mesh_def_default();
  d.vertex_count = int32_t(nv), d.triangle_count = int32_t(nt);
  d.x = x.data(), d.y = y.data(), d.z = z.data(), d.indices = indices.data();
  rp.meshes.reserve(rp.meshes.size() + 1);
  gyro_mesh* mesh = nullptr;
  const gyro_status s = gyro_mesh_create(&d, &mesh);
  if (s == GYRO_STATUS_OUT_OF_MEMORY) return Status::out_of_memory;
  if (s != GYRO_OK) return fail(Status::corrupt_data, "recording: mesh %zu is invalid", rp.meshes.size());
  rp.meshes.push_back(mesh);
  return Status::ok;
}

/// Every index GJK, EPA and the clipping follow is in range, every value finite.
bool hull_sound(const gyro::ConvexHull& h) {
  const std::size_t nv = h.vertices.size(), nf = h.planes.size();
  if (nv < 4 || nf < 4 || h.face_start.size() != nf + 1 || h.face_start[0] != 0 ||
      h.face_start[nf] != h.face_vertices.size() || h.edges.size() % 2 != 0 || h.edges.empty())
    return false;
  for (std::size_t f = 0; f < nf; ++f)
    if (h.face_start[f + 1] < h.face_start[f] || h.face_start[f + 1] - h.face_start[f] < 3) return false;
  for (uint32_t v : h.face_vertices)
    if (v >= nv) return false;
  for (uint32_t v : h.edges)
    if (v >= nv) return false;
  using gyro::detail::is_finite;
  for (const gyro::vec3& v : h.vertices)
    if (!is_finite(v.x) || !is_finite(v.y) || !is_finite(v.z)) return false;
  for (const gyro::Plane& p : h.planes)
    if (!is_finite(p.normal.x) || !is_finite(p.normal.y) || !is_finite(p.normal.z) || !is_finite(p.distance))
      return false;
  return true;
}

/// Reads a hull record into a hull handle (the recorded hull itself, not rebuilt).
Status read_hull(Reader& in, Replayer& rp) {
  auto hull = std::make_unique<gyro_convex_hull>();
  gyro::ConvexHull& h = hull->hull;
  const uint32_t nv = in.u32();
  if (!in.fits(nv, 12)) return fail(Status::corrupt_data, "recording: hull size");
  h.vertices.resize(nv);
  for (gyro::vec3& v : h.vertices) in.f32(v.x), in.f32(v.y), in.f32(v.z);
  const uint32_t nf = in.u32();
  if (!in.fits(uint64_t(nf) + 1, 4)) return fail(Status::corrupt_data, "recording: hull size");
  h.face_start.resize(std::size_t(nf) + 1);
  for (uint32_t& v : h.face_start) in.u32(v);
  const uint32_t nfv = in.u32();
  if (!in.fits(nfv, 4)) return fail(Status::corrupt_data, "recording: hull size");
  h.face_vertices.resize(nfv);
  for (uint32_t& v : h.face_vertices) in.u32(v);
  if (!in.fits(nf, 16)) return fail(Status::corrupt_data, "recording: hull size");
  h.planes.resize(nf);
  for (gyro::Plane& p : h.planes) in.f32(p.normal.x), in.f32(p.normal.y), in.f32(p.normal.z), in.f32(p.distance);
  const uint32_t ne = in.u32();
  if (!in.fits(ne, 4)) return fail(Status::corrupt_data, "recording: hull size");
  h.edges.resize(ne);
  for (uint32_t& v : h.edges) in.u32(v);
  if (!in.ok() || in.remaining() != 0 || !hull_sound(h))
    return fail(Status::corrupt_data, "recording: hull %zu is invalid", rp.hulls.size());
  rp.hulls.reserve(rp.hulls.size() + 1);
  rp.hulls.push_back(hull.release());
  return Status::ok;
}

rec::Outcome replay_call(uint32_t op, Reader& in, Replayer& rp, gyro_world* w, bool* known) {
  *known = true;
  switch (op) {
#define GYRO_REC_REPLAY_CASE(code, fn) \
  case code:                           \
    return rec::CallCodec<&fn>::replay(in, rp, w);
    GYRO_RECORDED_CALLS(GYRO_REC_REPLAY_CASE)
#undef GYRO_REC_REPLAY_CASE
    default:
      break;
  }
  *known = false;
  return rec::Outcome::corrupt;
}

struct WorldDelete {
  void operator()(gyro_world* w) const noexcept { gyro_world_destroy(w); }
};

Status replay_bytes(const uint8_t* data, std::size_t size, gyro_replay_report* out) {
  if (size < rec::kHeaderBytes + 8 + rec::kTailBytes)
    return fail(Status::corrupt_data, "recording: truncated (%zu bytes)", size);
  Reader trailer(data + size - 8, 8);
  const uint64_t stored = trailer.u64();
  if (gyro::detail::fnv1a64(data, size - 8) != stored)
    return fail(Status::corrupt_data, "recording: bad checksum (truncated or corrupted)");
  Reader in(data, size - 8);

  const uint8_t* magic = in.take(8);
  if (!magic || std::memcmp(magic, rec::kMagic, 8) != 0)
    return fail(Status::corrupt_data, "recording: not a gyro recording (bad magic)");
  const uint32_t version = in.u32();
  if (version != rec::kFormatVersion)
    return fail(Status::corrupt_data, "recording: format version %u (this library reads version %u)", version,
                rec::kFormatVersion);
  (void)in.u32();  // the recording library's ABI version: information only
  const uint32_t flags = in.u32(), reserved = in.u32();
  if (flags != 0 || reserved != 0) return fail(Status::corrupt_data, "recording: unknown flags");

  const uint64_t snapshot_size = in.u64();
  if (!in.fits(snapshot_size, 1)) return fail(Status::corrupt_data, "recording: the start snapshot is truncated");
  const uint8_t* snapshot = in.take(std::size_t(snapshot_size));
  gyro_world* raw = nullptr;
  const gyro_status created = gyro_world_create_from_snapshot(snapshot, snapshot_size, &raw);
  if (created == GYRO_STATUS_OUT_OF_MEMORY) return Status::out_of_memory;
  if (created != GYRO_OK) {
    const std::string why = gyro_last_error();
    return fail(Status::corrupt_data, "recording: the start snapshot: %s", why.c_str());
  }
  const std::unique_ptr<gyro_world, WorldDelete> world(raw);

  Replayer rp;
  for (uint64_t record = 0;; ++record) {
    const uint32_t op = in.u32(), n = in.u32();
    if (!in.ok())
      return fail(Status::corrupt_data, "recording: truncated after %llu records (no end record)",
                  static_cast<unsigned long long>(record));
    const uint8_t* payload = in.take(n);
    if (!payload && n)
      return fail(Status::corrupt_data, "recording: record %llu (opcode %u) runs past the end",
                  static_cast<unsigned long long>(record), op);
    Reader body(payload, n);
    if (op == rec::kOpEnd) {
      const uint64_t calls = body.u64(), steps = body.u64();
      if (!body.ok() || body.remaining() != 0 || in.remaining() != 0)
        return fail(Status::corrupt_data, "recording: bad end record");
      if (calls != uint64_t(rp.calls) || steps != uint64_t(rp.steps))
        return fail(Status::corrupt_data,
                    "recording: the end record counts %llu calls and %llu steps, the log %lld and %lld",
                    static_cast<unsigned long long>(calls), static_cast<unsigned long long>(steps),
                    static_cast<long long>(rp.calls), static_cast<long long>(rp.steps));
      break;
    }
    if (op == rec::kOpMesh) {
      GYRO_TRY(read_mesh(body, rp));
      continue;
    }
    if (op == rec::kOpHull) {
      GYRO_TRY(read_hull(body, rp));
      continue;
    }
    bool known = false;
    const rec::Outcome o = replay_call(op, body, rp, world.get(), &known);
    if (!known)
      return fail(Status::corrupt_data, "recording: unknown opcode %u at record %llu", op,
                  static_cast<unsigned long long>(record));
    if (o == rec::Outcome::corrupt)
      return fail(Status::corrupt_data, "recording: record %llu (opcode %u) cannot be read",
                  static_cast<unsigned long long>(record), op);
    ++rp.calls;
    if (o == rec::Outcome::differs) rp.diverge(rp.steps, 0, 0);
  }

  uint64_t final_hash = 0;
  gyro_world_hash(world.get(), &final_hash);
  gyro_replay_report r;
  std::memset(&r, 0, sizeof r);
  r.struct_size = sizeof(gyro_replay_report);
  r.diverged = rp.diverged ? 1u : 0u;
  r.steps = rp.steps, r.calls = rp.calls;
  r.first_divergent_step = rp.first_divergent_step;
  r.expected_hash = rp.expected_hash, r.actual_hash = rp.actual_hash;
  r.final_hash = final_hash;
  *out = r;
  return Status::ok;
}

Status check_report(const gyro_replay_report* out) {
  GYRO_TRY(require(out, "out"));
  if (out->struct_size != sizeof(gyro_replay_report))
    return fail(Status::invalid_argument, "out->struct_size = %u: set it to sizeof(gyro_replay_report) (%zu)",
                out->struct_size, sizeof(gyro_replay_report));
  return Status::ok;
}

struct FileClose {
  void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};

}  // namespace

extern "C" {

GYRO_API gyro_status gyro_world_record_begin(gyro_world* world) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(world, "world"));
    if (world->recorder) return fail(Status::invalid_argument, "the world is already recording");
    std::unique_ptr<Recorder, rec::RecorderDelete> r(new Recorder);
    r->w.bytes(rec::kMagic, sizeof rec::kMagic);
    r->w.u32(rec::kFormatVersion), r->w.u32(GYRO_ABI_VERSION), r->w.u32(0), r->w.u32(0);
    uint64_t n = 0;
    gyro_status s = gyro_world_snapshot_size(world, &n);
    if (s != GYRO_OK) return static_cast<Status>(s);
    if (n > uint64_t(std::numeric_limits<std::size_t>::max() / 2))
      return fail(Status::out_of_memory, "the world's snapshot is too large to record");
    r->w.u64(n);
    const std::size_t at = r->bytes.size();
    r->bytes.resize(at + std::size_t(n));
    uint64_t written = 0;
    s = gyro_world_snapshot(world, r->bytes.data() + at, n, &written);
    if (s != GYRO_OK) return static_cast<Status>(s);
    if (written > n) return fail(Status::internal, "gyro_world_snapshot wrote more than its size");
    r->bytes.resize(at + std::size_t(written));
    for (int k = 0; k < 8; ++k) r->bytes[at - 8 + k] = uint8_t(written >> (8 * k));
    world->recorder = std::move(r);
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_record_size(const gyro_world* world, uint64_t* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_recording(world));
    GYRO_TRY(require(out, "out"));
    *out = world->recorder->bytes.size() + rec::kTailBytes;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_record_copy(const gyro_world* world, void* buffer, uint64_t capacity,
                                            uint64_t* out_size) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_recording(world));
    GYRO_TRY(require(buffer, "buffer"));
    GYRO_TRY(require(out_size, "out_size"));
    const Recorder& r = *world->recorder;
    const uint64_t size = r.bytes.size() + rec::kTailBytes;
    if (capacity < size)
      return fail(Status::invalid_count, "capacity = %llu is below the recording's size %llu",
                  static_cast<unsigned long long>(capacity), static_cast<unsigned long long>(size));
    const std::vector<uint8_t> tail = tail_of(r);
    auto* dst = static_cast<uint8_t*>(buffer);
    if (!r.bytes.empty()) std::memcpy(dst, r.bytes.data(), r.bytes.size());
    std::memcpy(dst + r.bytes.size(), tail.data(), tail.size());
    *out_size = size;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_record_save(const gyro_world* world, const char* path) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_recording(world));
    GYRO_TRY(require(path, "path"));
    const Recorder& r = *world->recorder;
    const std::vector<uint8_t> tail = tail_of(r);
    std::unique_ptr<std::FILE, FileClose> f(std::fopen(path, "wb"));
    if (!f) return fail(Status::invalid_argument, "cannot write %s: %s", path, std::strerror(errno));
    bool ok = std::fwrite(r.bytes.data(), 1, r.bytes.size(), f.get()) == r.bytes.size() &&
              std::fwrite(tail.data(), 1, tail.size(), f.get()) == tail.size();
    const int err = errno;
    ok = (std::fclose(f.release()) == 0) && ok;
    if (!ok) {
      std::remove(path);  // no partial recording left behind
      return fail(Status::invalid_argument, "cannot write %s: %s", path, std::strerror(err ? err : EIO));
    }
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_world_record_end(gyro_world* world) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(world, "world"));
    if (!world->recorder) return fail(Status::invalid_argument, "the world is not recording");
    world->recorder.reset();
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_replay(const void* data, uint64_t size, gyro_replay_report* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(data, "data"));
    GYRO_TRY(check_report(out));
    if (size > uint64_t(std::numeric_limits<std::size_t>::max()))
      return fail(Status::corrupt_data, "recording: size does not fit in memory");
    return replay_bytes(static_cast<const uint8_t*>(data), std::size_t(size), out);
  });
}

GYRO_API gyro_status gyro_replay_file(const char* path, gyro_replay_report* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(path, "path"));
    GYRO_TRY(check_report(out));
    std::unique_ptr<std::FILE, FileClose> f(std::fopen(path, "rb"));
    if (!f) return fail(Status::invalid_argument, "cannot open %s: %s", path, std::strerror(errno));
    std::vector<uint8_t> bytes;
    constexpr std::size_t kChunk = std::size_t(1) << 20;
    for (;;) {
      const std::size_t at = bytes.size();
      if (at > kMaxFileBytes)
        return fail(Status::invalid_argument,
                    "%s is larger than gyro_replay_file's limit of %llu bytes (use gyro_replay)", path,
                    static_cast<unsigned long long>(kMaxFileBytes));
      bytes.resize(at + kChunk);
      const std::size_t got = std::fread(bytes.data() + at, 1, kChunk, f.get());
      bytes.resize(at + got);
      if (got < kChunk) break;
    }
    if (std::ferror(f.get())) return fail(Status::invalid_argument, "cannot read %s: %s", path, std::strerror(errno));
    return replay_bytes(bytes.data(), bytes.size(), out);
  });
}

}  // extern "C"
