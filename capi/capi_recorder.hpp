// Record and replay (ABI 1.5): the recording format, the recorder a recording world holds,
// and one codec per argument type that writes an argument when a call is recorded and reads
// it back when the call is replayed. Internal: never installed.
//
// ---- The format (version 1), every value little-endian at a fixed width, floats by their bits
//
//   header    8 bytes  magic "GYROREC" 0x1A
//             u32      format version (kFormatVersion)
//             u32      GYRO_ABI_VERSION of the library that recorded (information only)
//             u32      flags (0), u32 reserved (0)
//   start     u64 n, n bytes: the world's snapshot (gyro_world_snapshot) when recording began
//   records   u32 opcode, u32 payload size, payload; in call order:
//               kOpMesh / kOpHull  a mesh's or hull's geometry, the first time a recorded call
//                                  names it; later calls name it by its index (meshes and
//                                  hulls are numbered separately, from 0, in order of first use)
//               a call (GYRO_RECORDED_CALLS)  its arguments after the world, field by field
//                                  (out arguments: the value the call produced); a step
//                                  also carries the world hash after it
//   end       kOpEnd, payload size 16: u64 calls, u64 steps
//   trailer   u64 FNV-1a 64 of every byte before it
//
// Only calls that succeeded are recorded (a failed call changes nothing).
//
// ---- Recording a new mutating call of the C ABI (one line each, mechanical)
//
//   1. Give it an opcode: one X(code, function) line in GYRO_RECORDED_CALLS (codes are part of
//      the format: never reuse or renumber one).
//   2. In its implementation, keep the status and hand it to the recorder:
//        const gyro_status st = guarded(...);
//        return gyro::capi::rec::recorded<&gyro_new_call>(st, world, arg1, arg2);
//      (the arguments after the world, in order).
//   3. Only for a parameter type no recorded call has used yet: an Arg<T> below (an input
//      struct: a Desc with its fields, see ClothDesc).
//   Replay dispatches on the table, reads the arguments with the same codecs and calls the
//   function again.
#pragma once

#include "gyro.h"

#include "capi_world.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace gyro {
class TriangleMesh;
}

namespace gyro::capi::rec {

inline constexpr uint8_t kMagic[8] = {'G', 'Y', 'R', 'O', 'R', 'E', 'C', 0x1A};
inline constexpr uint32_t kFormatVersion = 1;
inline constexpr std::size_t kHeaderBytes = 24;
/// The end record and the checksum after the records.
inline constexpr std::size_t kTailBytes = 8 + 16 + 8;

/// Records that are not calls.
inline constexpr uint32_t kOpEnd = 0;
inline constexpr uint32_t kOpMesh = 1;
inline constexpr uint32_t kOpHull = 2;
/// A mesh or hull reference meaning "none" (NULL).
inline constexpr uint32_t kNoGeometry = 0xFFFFFFFFu;

// The recorded calls and their opcodes (part of the format).
#define GYRO_RECORDED_CALLS(X)             \
  X(16, gyro_world_step)                   \
  X(17, gyro_world_restore)                \
  X(32, gyro_body_create)                  \
  X(33, gyro_body_destroy)                 \
  X(34, gyro_body_set_transform)           \
  X(35, gyro_body_set_velocity)            \
  X(36, gyro_body_apply_force)             \
  X(37, gyro_body_apply_force_at_center)   \
  X(38, gyro_body_apply_torque)            \
  X(39, gyro_body_apply_linear_impulse)    \
  X(40, gyro_body_apply_angular_impulse)   \
  X(41, gyro_body_set_awake)               \
  X(64, gyro_world_create_cloth)           \
  X(65, gyro_world_create_soft_cube)       \
  X(66, gyro_world_create_soft_mesh)       \
  X(67, gyro_world_destroy_soft_body)      \
  X(68, gyro_soft_body_set_settings)       \
  X(69, gyro_soft_body_set_family)         \
  X(70, gyro_soft_body_set_mass)           \
  X(71, gyro_soft_body_set_particle_mass)  \
  X(72, gyro_soft_body_pin)                \
  X(73, gyro_soft_body_unpin)              \
  X(74, gyro_soft_body_set_position)       \
  X(75, gyro_soft_body_set_velocity)       \
  X(76, gyro_soft_body_add_distance_joint) \
  X(77, gyro_soft_body_add_ball_joint)     \
  X(78, gyro_soft_body_add_hinge_joint)

template <auto Fn>
struct OpOf {
  static constexpr uint32_t value = 0;
};
#define GYRO_REC_OP_OF(code, fn)            \
  template <>                               \
  struct OpOf<&fn> {                        \
    static constexpr uint32_t value = code; \
  };
GYRO_RECORDED_CALLS(GYRO_REC_OP_OF)
#undef GYRO_REC_OP_OF

// ------------------------------------------------------------------ bytes

/// Appends little-endian values to a byte vector (may throw std::bad_alloc).
class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(&out) {}
  void bytes(const void* p, std::size_t n) {
    if (!n) return;
    const std::size_t at = out_->size();
    out_->resize(at + n);
    std::memcpy(out_->data() + at, p, n);
  }
  void u8(const uint8_t& v) { out_->push_back(v); }
  void u32(const uint32_t& v) {
    const uint8_t b[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    bytes(b, 4);
  }
  void u64(const uint64_t& v) {
    u32(uint32_t(v));
    u32(uint32_t(v >> 32));
  }
  void i32(const int32_t& v) { u32(uint32_t(v)); }
  void f32(const float& v) { u32(std::bit_cast<uint32_t>(v)); }
  void v3(const gyro_vec3& v) { f32(v.x), f32(v.y), f32(v.z); }
  void q4(const gyro_quat& q) { f32(q.x), f32(q.y), f32(q.z), f32(q.w); }
  void constants(const gyro_spring_constants& c) { f32(c.stiffness), f32(c.damping); }
  std::size_t size() const { return out_->size(); }
  std::vector<uint8_t>& buffer() { return *out_; }

 private:
  std::vector<uint8_t>* out_;
};

/// Reads little-endian values from a bounded range. It never reads past the end: the first
/// short read marks it failed, and every later read yields zeros.
class Reader {
 public:
  Reader(const uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool ok() const { return ok_; }
  std::size_t remaining() const { return n_; }
  const uint8_t* here() const { return p_; }
  void fail() { ok_ = false, n_ = 0; }
  /// The next n bytes (null and failed when fewer remain).
  const uint8_t* take(std::size_t n) {
    if (!ok_ || n > n_) {
      fail();
      return nullptr;
    }
    const uint8_t* at = p_;
    p_ += n, n_ -= n;
    return at;
  }
  void u8(uint8_t& v) {
    const uint8_t* b = take(1);
    v = b ? b[0] : 0;
  }
  void u32(uint32_t& v) {
    const uint8_t* b = take(4);
    v = b ? uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24 : 0;
  }
  void u64(uint64_t& v) {
    uint32_t lo = 0, hi = 0;
    u32(lo), u32(hi);
    v = uint64_t(lo) | uint64_t(hi) << 32;
  }
  void i32(int32_t& v) {
    uint32_t u = 0;
    u32(u);
    v = std::bit_cast<int32_t>(u);
  }
  void f32(float& v) {
    uint32_t u = 0;
    u32(u);
    v = std::bit_cast<float>(u);
  }
  void v3(gyro_vec3& v) { f32(v.x), f32(v.y), f32(v.z); }
  void q4(gyro_quat& q) { f32(q.x), f32(q.y), f32(q.z), f32(q.w); }
  void constants(gyro_spring_constants& c) { f32(c.stiffness), f32(c.damping); }
  uint32_t u32() {
    uint32_t v = 0;
    u32(v);
    return v;
  }
  uint64_t u64() {
    uint64_t v = 0;
    u64(v);
    return v;
  }
  /// n elements of elem_bytes each must remain (n itself is given, never allocated first).
  bool fits(uint64_t n, std::size_t elem_bytes) {
    if (ok_ && n <= n_ / elem_bytes) return true;
    fail();
    return false;
  }

 private:
  const uint8_t* p_;
  std::size_t n_;
  bool ok_ = true;
};

// ------------------------------------------------------------------ the recorder

/// A recording in progress: the bytes so far (header, start snapshot, records; the end
/// record and the checksum are added when it is copied out) and the geometry already stored.
struct Recorder {
  std::vector<uint8_t> bytes;
  Writer w{bytes};
  uint64_t calls = 0, steps = 0;
  /// A call succeeded but could not be recorded (out of memory): the recording is incomplete
  /// and the record calls say so; nothing more is recorded.
  bool lost = false;

  /// Geometry stored so far, by kind (0 mesh, 1 hull): index and payload position in bytes,
  /// found by the FNV-1a hash of the payload, then compared byte for byte.
  struct Stored {
    uint32_t index;
    std::size_t offset, size;
  };
  std::unordered_multimap<uint64_t, Stored> geometry[2];
  uint32_t geometry_count[2] = {0, 0};
  /// Meshes already stored, by identity: the recorder holds a reference, so an address is
  /// never reused by another mesh while the recording lives.
  std::unordered_map<const TriangleMesh*, std::pair<std::shared_ptr<const TriangleMesh>, uint32_t>> mesh_ids;
  std::vector<uint8_t> scratch;

  Recorder() = default;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Starts a record: its opcode and a payload size patched by end_record.
  std::size_t begin_record(uint32_t op) {
    w.u32(op);
    const std::size_t at = bytes.size();
    w.u32(0);
    return at;
  }
  void end_record(std::size_t at) {
    const uint32_t n = uint32_t(bytes.size() - at - 4);
    for (int k = 0; k < 4; ++k) bytes[at + k] = uint8_t(n >> (8 * k));
  }
};

/// The index of a mesh's or hull's geometry in the recording, written first if new (null:
/// kNoGeometry). Defined in gyro_capi_replay.cpp.
uint32_t mesh_ref(Recorder& r, const gyro_mesh* mesh);
uint32_t hull_ref(Recorder& r, const gyro_convex_hull* hull);

// ------------------------------------------------------------------ replay state

/// A call read back and made again: what happened.
enum class Outcome {
  same,     ///< it succeeded as when recorded (and produced the same ids)
  differs,  ///< it failed, or produced another id: a divergence
  corrupt,  ///< its record cannot be read
};

/// What replay keeps across records: the geometry read so far (handles it destroys) and the
/// findings.
struct Replayer {
  std::vector<gyro_mesh*> meshes;
  std::vector<gyro_convex_hull*> hulls;
  int64_t steps = 0, calls = 0;
  bool diverged = false;
  int64_t first_divergent_step = -1;
  uint64_t expected_hash = 0, actual_hash = 0;

  Replayer() = default;
  Replayer(const Replayer&) = delete;
  Replayer& operator=(const Replayer&) = delete;
  ~Replayer();

  /// The handle a reference names (null for kNoGeometry); false for an index not read yet.
  bool mesh(uint32_t ref, const gyro_mesh** out) const {
    if (ref == kNoGeometry) return *out = nullptr, true;
    if (ref >= meshes.size()) return false;
    return *out = meshes[ref], true;
  }
  bool hull(uint32_t ref, const gyro_convex_hull** out) const {
    if (ref == kNoGeometry) return *out = nullptr, true;
    if (ref >= hulls.size()) return false;
    return *out = hulls[ref], true;
  }
  /// The first divergence wins: at step `step`, with the two hashes (0 when no hash differed).
  void diverge(int64_t step, uint64_t expected, uint64_t actual) {
    if (diverged) return;
    diverged = true;
    first_divergent_step = step, expected_hash = expected, actual_hash = actual;
  }
};

// ------------------------------------------------------------------ argument codecs
//
// Arg<T> for every parameter type of a recorded call (after the world):
//   prepare(r, v)   before the call's record: store geometry v names (meshes, hulls)
//   put(r, v)       write v into the call's record (after a successful call: out arguments
//                   hold what the call produced)
//   Slot            replay's storage for one argument
//   get(in, rp, s)  read it back; false: the record is corrupt
//   arg(s)          the value to pass to the function
//   same(s)         after the replayed call succeeded: whether its outputs match the recording

template <class T>
struct Arg;  // no primary template: a new parameter type needs a codec

/// A plain value passed by value, written with Writer/Reader's member `M`.
template <class T, void (Writer::*W)(const T&), void (Reader::*R)(T&)>
struct ValueArg {
  using Slot = T;
  static void prepare(Recorder&, const T&) {}
  static void put(Recorder& r, const T& v) { (r.w.*W)(v); }
  static bool get(Reader& in, Replayer&, Slot& s) {
    (in.*R)(s);
    return in.ok();
  }
  static T arg(Slot& s) { return s; }
  static bool same(const Slot&) { return true; }
};

template <>
struct Arg<float> : ValueArg<float, &Writer::f32, &Reader::f32> {};
template <>
struct Arg<uint32_t> : ValueArg<uint32_t, &Writer::u32, &Reader::u32> {};
template <>
struct Arg<gyro_vec3> : ValueArg<gyro_vec3, &Writer::v3, &Reader::v3> {};
template <>
struct Arg<gyro_quat> : ValueArg<gyro_quat, &Writer::q4, &Reader::q4> {};

/// Ids by value ({index, generation}: the world's id allocator is in the snapshot, so a
/// replayed world names its objects as the recorded one did).
template <class Id>
struct IdArg {
  using Slot = Id;
  static void prepare(Recorder&, const Id&) {}
  static void put(Recorder& r, const Id& id) { r.w.u32(id.index), r.w.u32(id.generation); }
  static bool get(Reader& in, Replayer&, Slot& s) {
    in.u32(s.index), in.u32(s.generation);
    return in.ok();
  }
  static Id arg(Slot& s) { return s; }
  static bool same(const Slot&) { return true; }
};
template <>
struct Arg<gyro_body_id> : IdArg<gyro_body_id> {};
template <>
struct Arg<gyro_soft_body_id> : IdArg<gyro_soft_body_id> {};

/// An id the call creates (out pointer): recorded, and replay checks it gets the same one.
template <class Id>
struct OutIdArg {
  struct Slot {
    Id expected{}, actual{};
  };
  static void prepare(Recorder&, Id* const&) {}
  static void put(Recorder& r, Id* const& out) { r.w.u32(out->index), r.w.u32(out->generation); }
  static bool get(Reader& in, Replayer&, Slot& s) {
    in.u32(s.expected.index), in.u32(s.expected.generation);
    return in.ok();
  }
  static Id* arg(Slot& s) { return &s.actual; }
  static bool same(const Slot& s) {
    return s.expected.index == s.actual.index && s.expected.generation == s.actual.generation;
  }
};
template <>
struct Arg<gyro_body_id*> : OutIdArg<gyro_body_id> {};
template <>
struct Arg<gyro_soft_body_id*> : OutIdArg<gyro_soft_body_id> {};

/// An optional uint32_t result (a joint's number): u8 present, u32 value.
template <>
struct Arg<uint32_t*> {
  struct Slot {
    uint8_t present = 0;
    uint32_t expected = 0, actual = 0;
  };
  static void prepare(Recorder&, uint32_t* const&) {}
  static void put(Recorder& r, uint32_t* const& out) {
    r.w.u8(out ? 1 : 0);
    r.w.u32(out ? *out : 0u);
  }
  static bool get(Reader& in, Replayer&, Slot& s) {
    in.u8(s.present), in.u32(s.expected);
    return in.ok() && s.present <= 1;
  }
  static uint32_t* arg(Slot& s) { return &s.actual; }
  static bool same(const Slot& s) { return !s.present || s.expected == s.actual; }
};

/// An input struct passed by pointer, described field by field by Desc:
///   static T make()                            the struct with struct_size set
///   template <class Io, class S> io(Io&, S&)   its fields (S is T or const T)
template <class T, class Desc>
struct InStructArg {
  using Slot = T;
  static void prepare(Recorder&, const T* const&) {}
  static void put(Recorder& r, const T* const& v) { Desc::io(r.w, *v); }
  static bool get(Reader& in, Replayer&, Slot& s) {
    s = Desc::make();
    Desc::io(in, s);
    return in.ok();
  }
  static const T* arg(Slot& s) { return &s; }
  static bool same(const Slot&) { return true; }
};

struct ConstantsDesc {
  static gyro_spring_constants make() { return gyro_spring_constants{0.0f, 0.0f}; }
  template <class Io, class S>
  static void io(Io& io, S& c) {
    io.constants(c);
  }
};
template <>
struct Arg<const gyro_spring_constants*> : InStructArg<gyro_spring_constants, ConstantsDesc> {};

struct SettingsDesc {
  static gyro_soft_settings make() { return gyro_soft_settings_default(); }
  template <class Io, class S>
  static void io(Io& io, S& s) {
    io.u32(s.model), io.u32(s.substeps), io.u32(s.iterations), io.v3(s.gravity);
    io.f32(s.damping), io.f32(s.thickness), io.f32(s.friction), io.u32(s.response), io.f32(s.penalty_stiffness);
  }
};
template <>
struct Arg<const gyro_soft_settings*> : InStructArg<gyro_soft_settings, SettingsDesc> {};

struct ClothDesc {
  static gyro_cloth_def make() { return gyro_cloth_def_default(); }
  template <class Io, class S>
  static void io(Io& io, S& d) {
    io.i32(d.nx), io.i32(d.nz), io.f32(d.size_x), io.f32(d.size_z), io.v3(d.center), io.f32(d.particle_mass);
    io.u32(d.both_diagonals), io.u32(d.bend);
    io.constants(d.structural), io.constants(d.shear), io.constants(d.bend_constants);
  }
};
template <>
struct Arg<const gyro_cloth_def*> : InStructArg<gyro_cloth_def, ClothDesc> {};

struct CubeDesc {
  static gyro_soft_cube_def make() { return gyro_soft_cube_def_default(); }
  template <class Io, class S>
  static void io(Io& io, S& d) {
    io.v3(d.center), io.f32(d.half_extent), io.f32(d.particle_mass);
    io.constants(d.structural), io.constants(d.shear), io.constants(d.bend);
  }
};
template <>
struct Arg<const gyro_soft_cube_def*> : InStructArg<gyro_soft_cube_def, CubeDesc> {};

/// A soft mesh: counts, then the vertex arrays and the indices.
template <>
struct Arg<const gyro_soft_mesh_def*> {
  struct Slot {
    gyro_soft_mesh_def def{};
    std::vector<float> x, y, z;
    std::vector<uint32_t> indices;
  };
  static void prepare(Recorder&, const gyro_soft_mesh_def* const&) {}
  static void put(Recorder& r, const gyro_soft_mesh_def* const& d) {
    const std::size_t nv = std::size_t(d->vertex_count), ni = 3 * std::size_t(d->triangle_count);
    r.w.i32(d->vertex_count), r.w.i32(d->triangle_count);
    for (const float* a : {d->x, d->y, d->z})
      for (std::size_t i = 0; i < nv; ++i) r.w.f32(a[i]);
    for (std::size_t i = 0; i < ni; ++i) r.w.u32(d->indices[i]);
    r.w.f32(d->particle_mass), r.w.constants(d->structural), r.w.constants(d->bend), r.w.constants(d->radial);
  }
  static bool get(Reader& in, Replayer&, Slot& s) {
    s.def = gyro_soft_mesh_def_default();
    in.i32(s.def.vertex_count), in.i32(s.def.triangle_count);
    if (!in.ok() || s.def.vertex_count < 0 || s.def.triangle_count < 0) return false;
    const std::size_t nv = std::size_t(s.def.vertex_count), ni = 3 * std::size_t(s.def.triangle_count);
    if (!in.fits(nv, 12) || !in.fits(ni, 4)) return false;
    for (std::vector<float>* a : {&s.x, &s.y, &s.z}) {
      a->resize(nv);
      for (float& v : *a) in.f32(v);
    }
    if (!in.fits(ni, 4)) return false;
    s.indices.resize(ni);
    for (uint32_t& i : s.indices) in.u32(i);
    in.f32(s.def.particle_mass), in.constants(s.def.structural), in.constants(s.def.bend), in.constants(s.def.radial);
    s.def.x = s.x.data(), s.def.y = s.y.data(), s.def.z = s.z.data(), s.def.indices = s.indices.data();
    return in.ok();
  }
  static const gyro_soft_mesh_def* arg(Slot& s) { return &s.def; }
  static bool same(const Slot&) { return true; }
};

/// A body definition: every field, with the mesh and hull as geometry references. An ABI 1.3
/// definition is recorded as the equivalent current one.
template <>
struct Arg<const gyro_body_def*> {
  using Slot = gyro_body_def;
  static gyro_body_def current(const gyro_body_def* d) {
    uint32_t size = 0;
    std::memcpy(&size, d, sizeof size);
    if (size == sizeof(gyro_body_def)) return *d;
    gyro_body_def c = gyro_body_def_default();  // ABI 1.3: read up to mesh, as gyro_body_create did
    std::memcpy(&c, d, offsetof(gyro_body_def, half_height));
    c.struct_size = sizeof(gyro_body_def);
    return c;
  }
  template <class Io, class S>
  static void fields(Io& io, S& d) {
    io.u32(d.type), io.u32(d.shape), io.f32(d.radius), io.v3(d.half_extents), io.v3(d.position);
    io.q4(d.orientation), io.v3(d.linear_velocity), io.v3(d.angular_velocity);
    io.f32(d.density), io.f32(d.mass), io.f32(d.friction), io.f32(d.restitution);
    io.f32(d.linear_damping), io.f32(d.angular_damping), io.f32(d.gravity_scale);
    io.u32(d.category), io.u32(d.mask), io.u32(d.allow_sleep), io.u32(d.awake), io.u32(d.reserved);
    io.u64(d.user_data), io.f32(d.half_height), io.u32(d.reserved2);
  }
  static void prepare(Recorder& r, const gyro_body_def* const& d) {
    const gyro_body_def c = current(d);
    mesh_ref(r, c.mesh);
    hull_ref(r, c.hull);
  }
  static void put(Recorder& r, const gyro_body_def* const& d) {
    const gyro_body_def c = current(d);
    fields(r.w, c);
    r.w.u32(mesh_ref(r, c.mesh));  // stored by prepare: found, not written again
    r.w.u32(hull_ref(r, c.hull));
  }
  static bool get(Reader& in, Replayer& rp, Slot& s) {
    s = gyro_body_def_default();
    fields(in, s);
    const uint32_t mesh = in.u32(), hull = in.u32();
    return in.ok() && rp.mesh(mesh, &s.mesh) && rp.hull(hull, &s.hull);
  }
  static const gyro_body_def* arg(Slot& s) { return &s; }
  static bool same(const Slot&) { return true; }
};

// ------------------------------------------------------------------ calls

template <class... P>
struct Params {};
template <class F>
struct ParamsOf;
template <class... P>
struct ParamsOf<gyro_status (*)(gyro_world*, P...)> {
  using type = Params<P...>;
};

/// A call's record and replay, from its parameter types; specialised for the calls that
/// record more than their arguments (the step's hash) or take a byte range (restore).
template <auto Fn, class L = typename ParamsOf<decltype(Fn)>::type>
struct CallCodec;

template <auto Fn, class... P>
struct CallCodec<Fn, Params<P...>> {
  static void record(Recorder& r, gyro_world&, const P&... args) {
    (Arg<P>::prepare(r, args), ...);
    const std::size_t at = r.begin_record(OpOf<Fn>::value);
    (Arg<P>::put(r, args), ...);
    r.end_record(at);
  }
  static Outcome replay(Reader& in, Replayer& rp, gyro_world* w) {
    std::tuple<typename Arg<P>::Slot...> slots;
    const bool read = std::apply([&](auto&... slot) { return (Arg<P>::get(in, rp, slot) && ... && true); }, slots);
    if (!read || in.remaining() != 0) return Outcome::corrupt;
    const gyro_status status = std::apply([&](auto&... slot) { return Fn(w, Arg<P>::arg(slot)...); }, slots);
    if (status != GYRO_OK) return Outcome::differs;
    const bool same = std::apply([&](auto&... slot) { return (Arg<P>::same(slot) && ... && true); }, slots);
    return same ? Outcome::same : Outcome::differs;
  }
};

/// A step: dt, then the world hash after it (replay compares it).
template <>
struct CallCodec<&gyro_world_step> {
  static void record(Recorder& r, gyro_world& w, const float& dt) {
    const std::size_t at = r.begin_record(OpOf<&gyro_world_step>::value);
    r.w.f32(dt);
    r.w.u64(w.world->hash());
    r.end_record(at);
    ++r.steps;
  }
  static Outcome replay(Reader& in, Replayer& rp, gyro_world* w) {
    float dt = 0.0f;
    uint64_t expected = 0, actual = 0;
    in.f32(dt), in.u64(expected);
    if (!in.ok() || in.remaining() != 0) return Outcome::corrupt;
    const int64_t step = rp.steps++;
    const gyro_status s = gyro_world_step(w, dt);
    if (s == GYRO_OK) gyro_world_hash(w, &actual);
    if (s != GYRO_OK || actual != expected) rp.diverge(step, expected, actual);
    return Outcome::same;  // a divergence here is recorded with its hashes
  }
};

/// A restore: the snapshot's bytes (u64 size, bytes); replay restores the same state.
template <>
struct CallCodec<&gyro_world_restore> {
  static void record(Recorder& r, gyro_world&, const void* const& buffer, const uint64_t& size) {
    const std::size_t at = r.begin_record(OpOf<&gyro_world_restore>::value);
    r.w.u64(size);
    r.w.bytes(buffer, std::size_t(size));
    r.end_record(at);
  }
  static Outcome replay(Reader& in, Replayer&, gyro_world* w) {
    const uint64_t n = in.u64();
    if (!in.fits(n, 1)) return Outcome::corrupt;
    const uint8_t* p = in.take(std::size_t(n));
    if (!in.ok() || in.remaining() != 0) return Outcome::corrupt;
    return gyro_world_restore(w, p, n) == GYRO_OK ? Outcome::same : Outcome::differs;
  }
};

/// Records a successful call (cold: only a recording world gets here). Out of memory while
/// recording leaves the recording as it was before this call and marks it lost.
template <auto Fn, class... A>
[[gnu::cold, gnu::noinline]] void record_call(gyro_world& w, const A&... args) noexcept {
  static_assert(OpOf<Fn>::value != 0, "add the call to GYRO_RECORDED_CALLS");
  Recorder& r = *w.recorder;
  if (r.lost) return;
  const std::size_t mark = r.bytes.size();
  try {
    CallCodec<Fn>::record(r, w, args...);
    ++r.calls;
  } catch (...) {
    r.bytes.resize(mark);
    r.lost = true;
  }
}

/// The hook every mutating call of the C ABI ends with: returns s, and records the call when
/// it succeeded on a recording world. A world that is not recording pays one null check.
template <auto Fn, class... A>
inline gyro_status recorded(gyro_status s, gyro_world* w, const A&... args) noexcept {
  if (s == GYRO_OK && w->recorder) [[unlikely]]
    record_call<Fn>(*w, args...);
  return s;
}

}  // namespace gyro::capi::rec
