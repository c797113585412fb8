// libFuzzer target on gyro's C ABI (issue 7).
//
// The input is a program: a header byte (bit 0: start without a world, bit 1: with two),
// then a sequence of operations, each an opcode byte followed by the
// bytes its arguments are read from (a read past the end gives 0). The operations act on a
// few live handles (two worlds with their body and soft-body ids, four meshes, four hulls,
// two scenes with their model ids) and on batch calls with arrays the harness owns. Values
// come through small encodings, so that both sane values and the bad ones (NaN, infinities,
// huge, negative, denormal, raw bits) are one byte away:
//   float:  byte b < 0xF0 gives (b - 120) / 8 (0x78 = 0, 0x80 = 1); 0xF0.. picks a special
//           value (see special_float); 0xFF is followed by 4 raw bytes.
//   int:    byte b < 0xF0 gives b - 8; 0xF0.. picks an extreme (INT_MIN, INT_MAX, 2^24, ...).
//   counts: never more than the array the harness passes (a lying count is a caller bug the
//           ABI cannot see), but negative ones and zero are passed as they are.
//
// Checked after every call (a failed check aborts, so libFuzzer keeps the input):
//   - the status is one of gyro_status's values, and INTERNAL only where documented;
//   - a failed call on a world leaves gyro_world_hash unchanged, and a query never changes it;
//   - a failed call writes nothing through its out pointers (prefilled, compared);
//   - a few documented facts (a created body is valid, a destroyed one is stale, the
//     convex results of unanswerable pairs are all zero, hull topology indices in range);
//   - a snapshot restored or replayed reproduces the world's hash, and steps on to the
//     same hash as the original (when the input did not feed it corrupted state).
// Raw slices of the input also go to gyro_world_restore, gyro_world_create_from_snapshot
// and gyro_replay, as they are and wrapped in a valid snapshot header (so the payload
// parser, not only the checksum, sees them), and valid snapshots and recordings of fuzzed
// worlds are mutated a few bytes at a time before they are restored or replayed.
//
// Reproduce a finding: build-asan/tests/fuzz/gyro-fuzz-capi CRASH_FILE (GYRO_FUZZ_TRACE=1
// prints every call).
#include "gyro.h"

#include "core/byte_stream.hpp"  // checksum64: re-seals mutated snapshots
#include "core/state_hash.hpp"   // fnv1a64: re-seals mutated recordings

#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace {

// ------------------------------------------------------------------ failure reporting

bool g_trace = false;
// GYRO_FUZZ_STRICT_FINITE=1: a body whose position became NaN or infinite through valid calls
// is a failure. Off by default: valid but extreme inputs (dt = FLT_MAX, velocities of 3e9)
// overflow the state today, and that one known finding would hide every other.
bool g_strict_finite = false;

[[noreturn]] void die(const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::fprintf(stderr, "\ngyro-fuzz-capi: CHECK FAILED: ");
  std::vfprintf(stderr, fmt, ap);
  va_end(ap);
  const char* e = gyro_last_error();
  std::fprintf(stderr, "\n  gyro_last_error: %s\n", e ? e : "(null)");
  std::abort();
}

void trace(const char* fmt, ...) {
  if (!g_trace) return;
  va_list ap;
  va_start(ap, fmt);
  std::vfprintf(stderr, fmt, ap);
  va_end(ap);
}

// Statuses a call may return besides OK and its documented failures: INTERNAL is a bug
// everywhere except where a call documents it (quickhull's consistency check).
enum : unsigned { ALLOW_INTERNAL = 1u, ALLOW_UNSUPPORTED = 2u };

gyro_status checked(gyro_status s, const char* call, unsigned allow = 0) {
  trace("  %s -> %d%s%s\n", call, int(s), s ? " " : "", s ? gyro_last_error() : "");
  if (s < GYRO_OK || s > GYRO_STATUS_CORRUPT_DATA) die("%s returned %d, not a gyro_status", call, int(s));
  if (s == GYRO_STATUS_INTERNAL && !(allow & ALLOW_INTERNAL)) die("%s returned GYRO_STATUS_INTERNAL", call);
  if (s == GYRO_STATUS_UNSUPPORTED && !(allow & ALLOW_UNSUPPORTED))
    die("%s returned GYRO_STATUS_UNSUPPORTED in a build that has the feature", call);
  if (s != GYRO_OK) {
    const char* e = gyro_last_error();
    if (!e) die("%s failed and gyro_last_error() is NULL", call);
    (void)std::strlen(e);
  }
  return s;
}

/// Bytes of an out value before a call, to check that a failed call wrote nothing.
template <class T> struct Guard {
  T& v;
  unsigned char before[sizeof(T)];
  explicit Guard(T& x, unsigned char fill = 0xA5) : v(x) {
    std::memset(&v, fill, sizeof(T));
    std::memcpy(before, &v, sizeof(T));
  }
  void untouched_unless(gyro_status s, const char* call) const {
    if (s != GYRO_OK && std::memcmp(before, &v, sizeof(T)) != 0) die("%s failed (%d) and wrote an out value", call, int(s));
  }
};

// ------------------------------------------------------------------ the input

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Input {
  const uint8_t* p;
  size_t n, i = 0;
  bool more() const { return i < n; }
  uint8_t u8() { return i < n ? p[i++] : 0; }
  uint16_t u16() { return uint16_t(u8() | (u8() << 8)); }
  uint32_t raw32() {
    uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= uint32_t(u8()) << (8 * k);
    return v;
  }
  bool flag(unsigned one_in) { return u8() % one_in == 0; }

  float special_float(uint8_t k) {
    switch (k & 15) {
      case 0: return -0.0f;
      case 1: return kNaN;
      case 2: return -std::numeric_limits<float>::signaling_NaN();
      case 3: return kInf;
      case 4: return -kInf;
      case 5: return 1e30f;
      case 6: return -1e30f;
      case 7: return 1e-40f;  // denormal
      case 8: return FLT_MAX;
      case 9: return -FLT_MAX;
      case 10: return FLT_MIN;
      case 11: return 1e4f;
      case 12: return -1e4f;
      case 13: return 1e-7f;
      case 14: return 3e9f;
      default: {
        uint32_t bits = raw32();
        float f;
        std::memcpy(&f, &bits, 4);
        return f;
      }
    }
  }
  float f() {
    const uint8_t b = u8();
    return b < 0xF0 ? float(int(b) - 120) * 0.125f : special_float(b);
  }
  gyro_vec3 v3() {
    gyro_vec3 v;
    v.x = f(), v.y = f(), v.z = f();
    return v;
  }
  gyro_quat q4() {
    gyro_quat q;
    q.x = f(), q.y = f(), q.z = f(), q.w = f();
    return q;
  }
  int32_t i32() {
    const uint8_t b = u8();
    if (b < 0xF0) return int32_t(b) - 8;
    static const int32_t extremes[15] = {INT32_MIN,     INT32_MAX,   -1, 0,       1 << 16, 1 << 24, (1 << 24) + 1,
                                         1 << 25,       1 << 30,     -2, 1 << 12, 4097,    65536,   INT32_MIN + 1,
                                         INT32_MAX - 1};
    if (b == 0xFF) return int32_t(raw32());
    return extremes[b - 0xF0];
  }
  uint32_t u32() { return uint32_t(i32()); }
  /// A count for an array of cap elements: negative and zero pass, larger ones wrap.
  int32_t count(int32_t cap) {
    int32_t v = i32();
    if (v > cap) v = v % (cap + 1);
    return v;
  }
  /// A 0/1 boolean most of the time, sometimes an invalid one.
  uint32_t boolean() {
    const uint8_t b = u8();
    return b < 0xF0 ? (b & 1u) : u32();
  }
};

// ------------------------------------------------------------------ live handles

constexpr int kWorlds = 2, kMeshes = 4, kHulls = 4, kScenes = 2;
constexpr size_t kMaxIds = 48;
constexpr int kMaxLiveBodies = 24;
constexpr int kStepBudget = 10;         // steps per input, all worlds together
constexpr int kSnapshotBudget = 12;     // snapshot round trips and restores per input

struct WorldSlot {
  gyro_world* w = nullptr;
  std::vector<gyro_body_id> bodies;  // live and destroyed (stale) ids
  std::vector<gyro_soft_body_id> softs;
  int live_bodies = 0;
  int particles = 0;         // an upper bound of the soft particles, for the step cost
  bool tainted = false;      // restored from a mutated snapshot: state the API could not have made
  bool recording = false;
  bool record_clean = false; // recording, and every mutating call since began went through the ABI
};

struct SceneSlot {
  gyro_scene* s = nullptr;
  std::vector<gyro_model_id> models;
};

struct State {
  Input in{nullptr, 0};
  WorldSlot worlds[kWorlds];
  gyro_mesh* meshes[kMeshes] = {};
  gyro_convex_hull* hulls[kHulls] = {};
  SceneSlot scenes[kScenes];
  int steps_left = kStepBudget;
  int snapshots_left = kSnapshotBudget;

  ~State() {
    for (auto& w : worlds) gyro_world_destroy(w.w);
    for (auto* m : meshes) gyro_mesh_destroy(m);
    for (auto* h : hulls) gyro_convex_hull_destroy(h);
    for (auto& s : scenes) gyro_scene_destroy(s.s);
  }
};

uint64_t hash_of(const gyro_world* w) {
  uint64_t h = 0;
  if (!w) return 0;
  const gyro_status s = gyro_world_hash(w, &h);
  if (s != GYRO_OK) die("gyro_world_hash on a live world returned %d", int(s));
  return h;
}

/// A call that may change the world: on failure its hash must be as before.
template <class F> gyro_status mutating(gyro_world* w, const char* call, F&& f, unsigned allow = 0) {
  const uint64_t before = hash_of(w);
  const gyro_status s = checked(f(), call, allow);
  if (s != GYRO_OK && w && hash_of(w) != before)
    die("%s failed (%d) and changed the world hash %016llx -> %016llx", call, int(s), (unsigned long long)before,
        (unsigned long long)hash_of(w));
  return s;
}

/// A call that only reads the world: the hash must be as before, whatever the status.
template <class F> gyro_status reading(const gyro_world* w, const char* call, F&& f, unsigned allow = 0) {
  const uint64_t before = hash_of(w);
  const gyro_status s = checked(f(), call, allow);
  if (w && hash_of(w) != before) die("%s (a query) changed the world hash", call);
  return s;
}

WorldSlot* pick_world(State& st, gyro_world** w) {
  const uint8_t b = st.in.u8();
  if (b % 8 == 7) {  // the NULL world
    *w = nullptr;
    return nullptr;
  }
  WorldSlot& slot = st.worlds[b % kWorlds];
  *w = slot.w;
  return slot.w ? &slot : nullptr;
}

template <class Id> Id pick_id(Input& in, const std::vector<Id>& own, const std::vector<Id>& other) {
  const uint8_t b = in.u8();
  Id id{0, 0};
  if (b < 0xE0) {
    const std::vector<Id>& v = (b & 0x80) && !other.empty() ? other : own;
    if (!v.empty()) id = v[(b & 0x7F) % v.size()];
    return id;
  }
  switch (b & 3) {
    case 0: return id;  // null
    case 1: id.index = in.u32(), id.generation = in.u32(); return id;  // garbage
    case 2:  // a live index with another generation
      if (!own.empty()) id = own[in.u8() % own.size()];
      id.generation += 1u + (in.u8() & 3);
      return id;
    default: id.index = 0xFFFFFFFFu, id.generation = 0xFFFFFFFFu; return id;
  }
}

gyro_body_id pick_body(State& st, WorldSlot* slot) {
  static const std::vector<gyro_body_id> none;
  const WorldSlot& other = slot == &st.worlds[0] ? st.worlds[1] : st.worlds[0];
  return pick_id(st.in, slot ? slot->bodies : none, other.bodies);
}

gyro_soft_body_id pick_soft(State& st, WorldSlot* slot) {
  static const std::vector<gyro_soft_body_id> none;
  const WorldSlot& other = slot == &st.worlds[0] ? st.worlds[1] : st.worlds[0];
  return pick_id(st.in, slot ? slot->softs : none, other.softs);
}

template <class Id> void remember(std::vector<Id>& v, Id id) {
  if (v.size() >= kMaxIds) v.erase(v.begin());
  v.push_back(id);
}

/// After a restore the world holds other bodies: take their ids from the body view.
void resync_bodies(WorldSlot& slot) {
  gyro_body_view view;
  if (checked(gyro_world_get_body_view(slot.w, &view), "gyro_world_get_body_view") != GYRO_OK) return;
  slot.live_bodies = view.count;
  for (int32_t i = 0; i < view.count && i < int32_t(kMaxIds); ++i) remember(slot.bodies, view.ids[i]);
  int32_t softs = 0;
  checked(gyro_world_soft_body_count(slot.w, &softs), "gyro_world_soft_body_count");
  slot.particles = softs > 0 ? 1 << 12 : 0;  // unknown: assume large, steps become rare
  for (uint32_t i = 1; i <= uint32_t(softs) + 1 && i < 16; ++i) remember(slot.softs, gyro_soft_body_id{i, 1});
}

gyro_mesh* pick_mesh(State& st) {
  const uint8_t b = st.in.u8();
  return b % 5 == 4 ? nullptr : st.meshes[b % kMeshes];
}
const gyro_convex_hull* pick_hull(State& st) {
  const uint8_t b = st.in.u8();
  return b % 5 == 4 ? nullptr : st.hulls[b % kHulls];
}

// ------------------------------------------------------------------ world and bodies

void op_world_create(State& st) {
  Input& in = st.in;
  WorldSlot& slot = st.worlds[in.u8() % kWorlds];
  gyro_world_def d = gyro_world_def_default();
  for (int e = in.u8() % 6; e > 0; --e) {
    switch (in.u8() % 24) {
      case 0: {
        const uint32_t sizes[] = {uint32_t(sizeof d), uint32_t(offsetof(gyro_world_def, convex_manifold)), 0,
                                  uint32_t(sizeof d) + 4, uint32_t(sizeof d) - 4, in.u32()};
        d.struct_size = sizes[in.u8() % 6];
        break;
      }
      case 1: d.contact_model = in.u8() % 4; break;
      case 2: d.gravity = in.v3(); break;
      case 3: d.substeps = in.u32(); break;
      case 4: d.velocity_iterations = in.u32(); break;
      case 5: d.relax_iterations = in.u32(); break;
      case 6: d.position_iterations = in.u32(); break;
      case 7: d.linear_slop = in.f(); break;
      case 8: d.baumgarte = in.f(); break;
      case 9: d.contact_hertz = in.f(); break;
      case 10: d.contact_damping_ratio = in.f(); break;
      case 11: d.max_push_velocity = in.f(); break;
      case 12: d.restitution_threshold = in.f(); break;
      case 13: d.enable_warm_starting = in.boolean(); break;
      case 14: d.enable_sleep = in.boolean(); break;
      case 15: d.sleep_time = in.f(); break;
      case 16: d.sleep_linear_velocity = in.f(); break;
      case 17: d.sleep_angular_velocity = in.f(); break;
      case 18: d.enable_continuous = in.boolean(); break;
      case 19: {  // more threads than 2 only where they are invalid: valid ones would be slow
        const uint32_t t[] = {0, 1, 2, 1025, 0xFFFFFFFFu};
        d.threads = t[in.u8() % 5];
        break;
      }
      case 20: d.convex_manifold = in.u8() % 3; break;
      case 21: d.substeps = 1 + in.u8() % 4; break;
      case 22: d.velocity_iterations = 1 + in.u8() % 8; break;
      default: d.contact_model = GYRO_CONTACT_BAUMGARTE, d.substeps = 1; break;
    }
  }
  const uint8_t nulls = in.u8() % 16;
  gyro_world* w = nullptr;
  Guard<gyro_world*> g(w);
  const gyro_status s = checked(gyro_world_create(nulls == 1 ? nullptr : &d, nulls == 2 ? nullptr : &w),
                                "gyro_world_create");
  g.untouched_unless(s, "gyro_world_create");
  if (s != GYRO_OK) return;
  if (!w) die("gyro_world_create returned OK and a NULL world");
  int32_t n = -1;
  checked(gyro_world_body_count(w, &n), "gyro_world_body_count");
  if (n != 0) die("a new world has %d bodies", n);
  gyro_world_destroy(slot.w);
  slot = WorldSlot{};
  slot.w = w;
}

void op_world_destroy(State& st) {
  WorldSlot& slot = st.worlds[st.in.u8() % kWorlds];
  gyro_world_destroy(slot.w);
  gyro_world_destroy(nullptr);
  // The old ids stay as ids of no world (stale everywhere).
  std::vector<gyro_body_id> keep = slot.bodies;
  std::vector<gyro_soft_body_id> keep_soft = slot.softs;
  slot = WorldSlot{};
  slot.bodies = keep;
  slot.softs = keep_soft;
}

void op_body_create(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  gyro_body_def d = gyro_body_def_default();
  const uint8_t shape_pick = in.u8();
  switch (shape_pick % 8) {  // a valid start for each shape, then edits
    case 0: d.shape = GYRO_BODY_SHAPE_SPHERE, d.radius = 0.5f; break;
    case 1: d.shape = GYRO_BODY_SHAPE_BOX; break;
    case 2: d.shape = GYRO_BODY_SHAPE_PLANE, d.type = GYRO_BODY_STATIC; break;
    case 3: d.shape = GYRO_BODY_SHAPE_MESH, d.type = GYRO_BODY_STATIC, d.mesh = pick_mesh(st); break;
    case 4: d.shape = GYRO_BODY_SHAPE_CAPSULE, d.radius = 0.25f; break;
    case 5: d.shape = GYRO_BODY_SHAPE_HULL, d.hull = pick_hull(st); break;
    case 6: d.shape = GYRO_BODY_SHAPE_BOX, d.type = GYRO_BODY_STATIC; break;
    default: d.shape = GYRO_BODY_SHAPE_SPHERE, d.type = GYRO_BODY_KINEMATIC; break;
  }
  d.position = {float(int(in.u8() % 9) - 4), float(int(in.u8() % 9)), float(int(in.u8() % 9) - 4)};
  for (int e = in.u8() % 6; e > 0; --e) {
    switch (in.u8() % 28) {
      case 0: {
        const uint32_t sizes[] = {uint32_t(sizeof d), 144, 0, uint32_t(sizeof d) + 8, in.u32()};
        d.struct_size = sizes[in.u8() % 5];
        break;
      }
      case 1: d.type = in.u8() % 4; break;
      case 2: d.shape = in.u8() % 7; break;
      case 3: d.radius = in.f(); break;
      case 4: d.half_extents = in.v3(); break;
      case 5: d.position = in.v3(); break;
      case 6: d.orientation = in.q4(); break;
      case 7: d.linear_velocity = in.v3(); break;
      case 8: d.angular_velocity = in.v3(); break;
      case 9: d.density = in.f(); break;
      case 10: d.mass = in.f(); break;
      case 11: d.friction = in.f(); break;
      case 12: d.restitution = in.f(); break;
      case 13: d.linear_damping = in.f(); break;
      case 14: d.angular_damping = in.f(); break;
      case 15: d.gravity_scale = in.f(); break;
      case 16: d.category = in.u32(); break;
      case 17: d.mask = in.u32(); break;
      case 18: d.allow_sleep = in.boolean(); break;
      case 19: d.awake = in.boolean(); break;
      case 20: d.reserved = in.u32(); break;
      case 21: d.user_data = uint64_t(in.raw32()) << 32 | in.raw32(); break;
      case 22: d.mesh = pick_mesh(st); break;
      case 23: d.half_height = in.f(); break;
      case 24: d.reserved2 = in.u32(); break;
      case 25: d.hull = pick_hull(st); break;
      case 26: d.mass = float(1 + in.u8() % 100); break;
      default: d.orientation = {0, 0, 0, 0}; break;
    }
  }
  if (slot && slot->live_bodies >= kMaxLiveBodies) return;
  trace("  body def: type %u shape %u r %g hh %g he (%g %g %g) p (%g %g %g) q (%g %g %g %g) v (%g %g %g) w (%g %g %g) "
        "m %g rho %g\n", d.type, d.shape, double(d.radius), double(d.half_height), double(d.half_extents.x),
        double(d.half_extents.y), double(d.half_extents.z), double(d.position.x), double(d.position.y),
        double(d.position.z), double(d.orientation.x), double(d.orientation.y), double(d.orientation.z),
        double(d.orientation.w), double(d.linear_velocity.x), double(d.linear_velocity.y), double(d.linear_velocity.z),
        double(d.angular_velocity.x), double(d.angular_velocity.y), double(d.angular_velocity.z), double(d.mass),
        double(d.density));
  const uint8_t nulls = in.u8() % 16;
  gyro_body_id id;
  Guard<gyro_body_id> g(id);
  const gyro_status s = mutating(w, "gyro_body_create", [&] {
    return gyro_body_create(w, nulls == 1 ? nullptr : &d, nulls == 2 ? nullptr : &id);
  });
  g.untouched_unless(s, "gyro_body_create");
  if (s != GYRO_OK) return;
  if ((id.index == 0 && id.generation == 0) || !gyro_body_is_valid(w, id))
    die("gyro_body_create returned OK and id {%u, %u}, which is not valid", id.index, id.generation);
  slot->live_bodies++;
  remember(slot->bodies, id);
  if (slot->recording && d.shape == GYRO_BODY_SHAPE_MESH) {
    // Meshes a call names are stored with the recording: still clean.
  }
}

void op_body_destroy(State& st) {
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const gyro_body_id id = pick_body(st, slot);
  const gyro_status s = mutating(w, "gyro_body_destroy", [&] { return gyro_body_destroy(w, id); });
  if (s != GYRO_OK) return;
  slot->live_bodies--;
  if (gyro_body_is_valid(w, id)) die("body {%u, %u} is still valid after gyro_body_destroy", id.index, id.generation);
  const gyro_status again = checked(gyro_body_destroy(w, id), "gyro_body_destroy (again)");
  if (again != GYRO_STATUS_STALE_ID) die("destroying body {%u, %u} twice gave %d, not STALE_ID", id.index, id.generation, int(again));
}

void op_body_set(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const gyro_body_id id = pick_body(st, slot);
  const uint8_t what = in.u8() % 8;
  const gyro_vec3 a = in.v3(), b = in.v3();
  switch (what) {
    case 0: {
      gyro_quat q = in.q4();
      if (in.flag(3)) q = {0, 0, 0, 1};
      mutating(w, "gyro_body_set_transform", [&] { return gyro_body_set_transform(w, id, a, q); });
      break;
    }
    case 1: mutating(w, "gyro_body_set_velocity", [&] { return gyro_body_set_velocity(w, id, a, b); }); break;
    case 2: mutating(w, "gyro_body_apply_force", [&] { return gyro_body_apply_force(w, id, a, b); }); break;
    case 3: mutating(w, "gyro_body_apply_force_at_center", [&] { return gyro_body_apply_force_at_center(w, id, a); }); break;
    case 4: mutating(w, "gyro_body_apply_torque", [&] { return gyro_body_apply_torque(w, id, a); }); break;
    case 5:
      mutating(w, "gyro_body_apply_linear_impulse", [&] { return gyro_body_apply_linear_impulse(w, id, a, b); });
      break;
    case 6:
      mutating(w, "gyro_body_apply_angular_impulse", [&] { return gyro_body_apply_angular_impulse(w, id, a); });
      break;
    default: {
      const uint32_t awake = in.boolean();
      mutating(w, "gyro_body_set_awake", [&] { return gyro_body_set_awake(w, id, awake); });
      break;
    }
  }
}

void op_body_get(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const gyro_body_id id = pick_body(st, slot);
  const uint8_t what = in.u8() % 16;
  const bool null_a = in.flag(5), null_b = in.flag(5);
  switch (what) {
    case 0: {
      gyro_vec3 p;
      gyro_quat q;
      Guard<gyro_vec3> gp(p);
      Guard<gyro_quat> gq(q);
      const gyro_status s = reading(w, "gyro_body_get_transform", [&] {
        return gyro_body_get_transform(w, id, null_a ? nullptr : &p, null_b ? nullptr : &q);
      });
      gp.untouched_unless(s, "gyro_body_get_transform"), gq.untouched_unless(s, "gyro_body_get_transform");
      if (g_strict_finite && s == GYRO_OK && !slot->tainted && !null_a &&
          !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
        die("body {%u, %u} has a non-finite position (%g, %g, %g)", id.index, id.generation, double(p.x), double(p.y),
            double(p.z));
      break;
    }
    case 1: {
      gyro_vec3 o;
      gyro_quat r;
      Guard<gyro_vec3> go(o);
      Guard<gyro_quat> gr(r);
      const gyro_status s = reading(w, "gyro_body_get_shape_frame", [&] {
        return gyro_body_get_shape_frame(w, id, null_a ? nullptr : &o, null_b ? nullptr : &r);
      });
      go.untouched_unless(s, "gyro_body_get_shape_frame"), gr.untouched_unless(s, "gyro_body_get_shape_frame");
      break;
    }
    case 2: {
      gyro_vec3 l, a;
      Guard<gyro_vec3> gl(l), ga(a);
      const gyro_status s = reading(w, "gyro_body_get_velocity", [&] {
        return gyro_body_get_velocity(w, id, null_a ? nullptr : &l, null_b ? nullptr : &a);
      });
      gl.untouched_unless(s, "gyro_body_get_velocity"), ga.untouched_unless(s, "gyro_body_get_velocity");
      break;
    }
    case 3: {
      float m;
      Guard<float> g(m);
      const gyro_status s =
          reading(w, "gyro_body_get_mass", [&] { return gyro_body_get_mass(w, id, null_a ? nullptr : &m); });
      g.untouched_unless(s, "gyro_body_get_mass");
      if (s == GYRO_OK && !slot->tainted && !(m >= 0.0f && std::isfinite(m))) die("gyro_body_get_mass gave %g", double(m));
      break;
    }
    case 4: {
      gyro_body_type t;
      Guard<gyro_body_type> g(t);
      const gyro_status s =
          reading(w, "gyro_body_get_type", [&] { return gyro_body_get_type(w, id, null_a ? nullptr : &t); });
      g.untouched_unless(s, "gyro_body_get_type");
      if (s == GYRO_OK && !slot->tainted && t > GYRO_BODY_DYNAMIC) die("gyro_body_get_type gave %u", t);
      break;
    }
    case 5: {
      uint64_t u;
      Guard<uint64_t> g(u);
      const gyro_status s =
          reading(w, "gyro_body_get_user_data", [&] { return gyro_body_get_user_data(w, id, null_a ? nullptr : &u); });
      g.untouched_unless(s, "gyro_body_get_user_data");
      break;
    }
    case 6: {
      uint32_t a;
      Guard<uint32_t> g(a);
      const gyro_status s =
          reading(w, "gyro_body_is_awake", [&] { return gyro_body_is_awake(w, id, null_a ? nullptr : &a); });
      g.untouched_unless(s, "gyro_body_is_awake");
      if (s == GYRO_OK && a > 1) die("gyro_body_is_awake gave %u", a);
      break;
    }
    case 7: {
      const uint32_t v = gyro_body_is_valid(w, id);
      if (v > 1) die("gyro_body_is_valid gave %u", v);
      break;
    }
    case 8: {
      int32_t n;
      Guard<int32_t> g(n);
      const gyro_status s =
          reading(w, "gyro_world_body_count", [&] { return gyro_world_body_count(w, null_a ? nullptr : &n); });
      g.untouched_unless(s, "gyro_world_body_count");
      if (s == GYRO_OK && n < 0) die("gyro_world_body_count gave %d", n);
      break;
    }
    case 9: {
      gyro_body_view v;
      Guard<gyro_body_view> g(v);
      const gyro_status s =
          reading(w, "gyro_world_get_body_view", [&] { return gyro_world_get_body_view(w, null_a ? nullptr : &v); });
      g.untouched_unless(s, "gyro_world_get_body_view");
      if (s != GYRO_OK || null_a) break;
      int32_t n = -1;
      checked(gyro_world_body_count(w, &n), "gyro_world_body_count");
      if (v.count != n) die("the body view has %d bodies, gyro_world_body_count %d", v.count, n);
      float sum = 0.0f;
      for (int32_t i = 0; i < v.count; ++i) {
        if (!gyro_body_is_valid(w, v.ids[i])) die("body view slot %d names an invalid id", i);
        sum += v.px[i] + v.py[i] + v.pz[i] + v.qx[i] + v.qy[i] + v.qz[i] + v.qw[i] + v.vx[i] + v.vy[i] + v.vz[i] +
               v.wx[i] + v.wy[i] + v.wz[i];
      }
      (void)sum;
      break;
    }
    case 10: {
      gyro_step_timings t;
      Guard<gyro_step_timings> g(t);
      const gyro_status s =
          reading(w, "gyro_world_get_timings", [&] { return gyro_world_get_timings(w, null_a ? nullptr : &t); });
      g.untouched_unless(s, "gyro_world_get_timings");
      break;
    }
    case 11: {
      gyro_step_stats t;
      Guard<gyro_step_stats> g(t);
      const gyro_status s =
          reading(w, "gyro_world_get_stats", [&] { return gyro_world_get_stats(w, null_a ? nullptr : &t); });
      g.untouched_unless(s, "gyro_world_get_stats");
      break;
    }
    case 12: {
      double ms;
      Guard<double> g(ms);
      const gyro_step_stage stage = in.u8() % 10;
      const gyro_status s = reading(w, "gyro_world_get_stage_time", [&] {
        return gyro_world_get_stage_time(w, stage, null_a ? nullptr : &ms);
      });
      g.untouched_unless(s, "gyro_world_get_stage_time");
      break;
    }
    case 13: {
      gyro_contact_events e;
      Guard<gyro_contact_events> g(e);
      const gyro_status s = reading(w, "gyro_world_get_contact_events", [&] {
        return gyro_world_get_contact_events(w, null_a ? nullptr : &e);
      });
      g.untouched_unless(s, "gyro_world_get_contact_events");
      if (s != GYRO_OK || null_a) break;
      if (e.begin_count < 0 || e.end_count < 0) die("negative contact event counts");
      uint32_t acc = 0;
      for (int32_t i = 0; i < e.begin_count; ++i) acc += e.begin[i].a.index + e.begin[i].b.index;
      for (int32_t i = 0; i < e.end_count; ++i) acc += e.end[i].a.index + e.end[i].b.index;
      (void)acc;
      break;
    }
    case 14: {
      uint64_t h;
      Guard<uint64_t> g(h);
      const gyro_status s = checked(gyro_world_hash(w, null_a ? nullptr : &h), "gyro_world_hash");
      g.untouched_unless(s, "gyro_world_hash");
      break;
    }
    default: {
      int32_t n;
      Guard<int32_t> g(n);
      const gyro_status s = reading(w, "gyro_world_soft_body_count", [&] {
        return gyro_world_soft_body_count(w, null_a ? nullptr : &n);
      });
      g.untouched_unless(s, "gyro_world_soft_body_count");
      break;
    }
  }
}

void op_step(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const uint8_t k = in.u8();
  float dt;
  switch (k % 8) {
    case 0: dt = 1.0f / 60.0f; break;
    case 1: dt = 1.0f / 30.0f; break;
    case 2: dt = 0.0f; break;
    case 3: dt = -1.0f / 60.0f; break;
    case 4: dt = in.f(); break;
    case 5: dt = in.special_float(in.u8()); break;
    case 6: dt = 0.25f; break;
    default: dt = 1.0f / 240.0f; break;
  }
  // A valid step costs time: they are rationed (the invalid ones are free).
  const bool valid = w && std::isfinite(dt) && dt > 0.0f;
  if (valid) {
    const int cost = 1 + (slot ? slot->particles / 256 : 0);
    if (st.steps_left < cost) return;
    st.steps_left -= cost;
  }
  mutating(w, "gyro_world_step", [&] { return gyro_world_step(w, dt); });
}

// ------------------------------------------------------------------ soft bodies

gyro_spring_constants spring(Input& in) {
  gyro_spring_constants c;
  const uint8_t k = in.u8();
  if (k < 0xC0) {
    c.stiffness = float(100 << (k % 8)), c.damping = float(k % 4);
  } else {
    c.stiffness = in.f(), c.damping = in.f();
    if (k == 0xFF) c.stiffness = kInf;
  }
  return c;
}

int32_t grid_count(Input& in) {
  const uint8_t b = in.u8();
  if (b < 0xE0) return 2 + b % 7;  // 2..8
  const int32_t extremes[8] = {INT32_MIN, -1, 0, 1, 1 << 25, INT32_MAX, 1 << 16, -(1 << 16)};
  return extremes[b & 7];
}

void record_soft(WorldSlot* slot, gyro_soft_body_id id, int particles) {
  remember(slot->softs, id);
  slot->particles += particles;
}

void op_soft_create(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const uint8_t kind = in.u8() % 3;
  const uint8_t nulls = in.u8() % 16;
  gyro_soft_body_id id;
  Guard<gyro_soft_body_id> g(id);
  gyro_soft_body_id* out = nulls == 2 ? nullptr : &id;
  gyro_status s;
  int particles = 0;
  if (slot && slot->particles > 400) return;
  if (kind == 0) {
    gyro_cloth_def d = gyro_cloth_def_default();
    d.nx = grid_count(in), d.nz = grid_count(in);
    d.size_x = float(1 + in.u8() % 4), d.size_z = float(1 + in.u8() % 4);
    d.center = {0.0f, float(in.u8() % 6), 0.0f};
    for (int e = in.u8() % 5; e > 0; --e) {
      switch (in.u8() % 12) {
        case 0: {
          const uint32_t sizes[] = {uint32_t(sizeof d), 0, uint32_t(sizeof d) - 4, in.u32()};
          d.struct_size = sizes[in.u8() % 4];
          break;
        }
        case 1: d.size_x = in.f(); break;
        case 2: d.size_z = in.f(); break;
        case 3: d.center = in.v3(); break;
        case 4: d.particle_mass = in.f(); break;
        case 5: d.both_diagonals = in.boolean(); break;
        case 6: d.bend = in.boolean(); break;
        case 7: d.structural = spring(in); break;
        case 8: d.shear = spring(in); break;
        case 9: d.bend_constants = spring(in); break;
        case 10: d.nx = in.i32(); break;
        default: d.nz = in.i32(); break;
      }
    }
    // A valid but huge grid (up to 2^24 particles) would take seconds: only invalid ones pass.
    const int64_t n = int64_t(d.nx) * int64_t(d.nz);
    if (d.nx > 0 && d.nz > 0 && n <= (int64_t(1) << 24) && n > 100) return;
    particles = int(n > 0 && n <= 100 ? n : 0);
    s = mutating(w, "gyro_world_create_cloth",
                 [&] { return gyro_world_create_cloth(w, nulls == 1 ? nullptr : &d, out); });
  } else if (kind == 1) {
    gyro_soft_cube_def d = gyro_soft_cube_def_default();
    d.center = {float(int(in.u8() % 5) - 2), float(in.u8() % 6), 0.0f};
    for (int e = in.u8() % 5; e > 0; --e) {
      switch (in.u8() % 8) {
        case 0: {
          const uint32_t sizes[] = {uint32_t(sizeof d), 0, uint32_t(sizeof d) + 4, in.u32()};
          d.struct_size = sizes[in.u8() % 4];
          break;
        }
        case 1: d.center = in.v3(); break;
        case 2: d.half_extent = in.f(); break;
        case 3: d.particle_mass = in.f(); break;
        case 4: d.structural = spring(in); break;
        case 5: d.shear = spring(in); break;
        case 6: d.bend = spring(in); break;
        default: d.half_extent = 0.0f; break;
      }
    }
    particles = 8;
    s = mutating(w, "gyro_world_create_soft_cube",
                 [&] { return gyro_world_create_soft_cube(w, nulls == 1 ? nullptr : &d, out); });
  } else {
    // A closed octahedron (valid), then edits of vertices, indices and counts.
    float x[12] = {1, -1, 0, 0, 0, 0}, y[12] = {0, 0, 1, -1, 0, 0}, z[12] = {0, 0, 0, 0, 1, -1};
    uint32_t idx[3 * 12] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    gyro_soft_mesh_def d = gyro_soft_mesh_def_default();
    int32_t nv = 6, nt = 8;
    for (int e = in.u8() % 6; e > 0; --e) {
      switch (in.u8() % 10) {
        case 0: {
          const uint32_t sizes[] = {uint32_t(sizeof d), 0, uint32_t(sizeof d) - 8, in.u32()};
          d.struct_size = sizes[in.u8() % 4];
          break;
        }
        case 1: {
          const int v = in.u8() % 12;
          x[v] = in.f(), y[v] = in.f(), z[v] = in.f();
          break;
        }
        case 2: idx[in.u8() % 36] = in.u8() < 0xF0 ? in.u8() % 14 : in.u32(); break;
        case 3: nv = in.count(12); break;
        case 4: nt = in.count(12); break;
        case 5: d.particle_mass = in.f(); break;
        case 6: d.structural = spring(in); break;
        case 7: d.bend = spring(in); break;
        case 8: d.radial = spring(in); break;
        default: std::swap(idx[in.u8() % 36], idx[in.u8() % 36]); break;
      }
    }
    d.vertex_count = nv, d.triangle_count = nt;
    const uint8_t np = in.u8() % 8;
    d.x = np == 1 ? nullptr : x, d.y = np == 2 ? nullptr : y, d.z = np == 3 ? nullptr : z;
    d.indices = np == 4 ? nullptr : idx;
    particles = nv + 1;
    s = mutating(w, "gyro_world_create_soft_mesh",
                 [&] { return gyro_world_create_soft_mesh(w, nulls == 1 ? nullptr : &d, out); });
  }
  g.untouched_unless(s, "gyro_world_create_*soft*");
  if (s != GYRO_OK) return;
  if (!gyro_soft_body_is_valid(w, id)) die("a soft body created OK is not valid");
  record_soft(slot, id, particles);
}

uint32_t particle_index(Input& in) {
  const uint8_t b = in.u8();
  if (b < 0xF0) return b % 72;
  const uint32_t extremes[] = {0xFFFFFFFFu, 1u << 24, (1u << 24) - 1, 0x80000000u, 64, 65, 8, 9, 6, 7, 100, 0, 1, 2, 3, 4};
  return extremes[b & 15];
}

void op_soft_call(State& st) {
  Input& in = st.in;
  gyro_world* w;
  WorldSlot* slot = pick_world(st, &w);
  const gyro_soft_body_id id = pick_soft(st, slot);
  const uint8_t what = in.u8() % 24;
  const uint32_t p = particle_index(in), q = particle_index(in);
  const bool null_out = in.flag(6);
  switch (what) {
    case 0:
      if (mutating(w, "gyro_world_destroy_soft_body", [&] { return gyro_world_destroy_soft_body(w, id); }) == GYRO_OK &&
          gyro_soft_body_is_valid(w, id))
        die("a destroyed soft body is still valid");
      break;
    case 1: {
      gyro_soft_settings s = gyro_soft_settings_default();
      for (int e = in.u8() % 5; e > 0; --e) {
        switch (in.u8() % 12) {
          case 0: {
            const uint32_t sizes[] = {uint32_t(sizeof s), 0, uint32_t(sizeof s) - 4, in.u32()};
            s.struct_size = sizes[in.u8() % 4];
            break;
          }
          case 1: s.model = in.u8() % 3; break;
          case 2: {  // the upper ends of the ranges are valid but slow: they come with 1 of the other
            const uint32_t v[] = {1, 2, 4, 8, 0, 256, 257, 0xFFFFFFFFu};
            s.substeps = v[in.u8() % 8];
            if (s.substeps == 256) s.iterations = 1;
            break;
          }
          case 3: {
            const uint32_t v[] = {1, 2, 3, 0, 64, 65, 0xFFFFFFFFu, 1};
            s.iterations = v[in.u8() % 8];
            if (s.iterations == 64 && s.substeps > 4) s.substeps = 4;
            break;
          }
          case 4: s.gravity = in.v3(); break;
          case 5: s.damping = in.f(); break;
          case 6: s.thickness = in.f(); break;
          case 7: s.friction = in.f(); break;
          case 8: s.response = in.u8() % 3; break;
          case 9: s.penalty_stiffness = in.f(); break;
          case 10: s.model = GYRO_SOFT_MODEL_SPRINGS; break;
          default: s.response = GYRO_COLLISION_PENALTY; break;
        }
      }
      mutating(w, "gyro_soft_body_set_settings",
               [&] { return gyro_soft_body_set_settings(w, id, null_out ? nullptr : &s); });
      break;
    }
    case 2: {
      gyro_soft_settings s = gyro_soft_settings_default();
      if (in.flag(4)) s.struct_size = in.u32();
      const uint32_t size = s.struct_size;
      Guard<gyro_soft_settings> g(s);
      s.struct_size = size;
      std::memcpy(g.before, &s, sizeof s);
      const gyro_status r = reading(w, "gyro_soft_body_get_settings",
                                    [&] { return gyro_soft_body_get_settings(w, id, null_out ? nullptr : &s); });
      g.untouched_unless(r, "gyro_soft_body_get_settings");
      break;
    }
    case 3: {
      const gyro_spring_family fam = in.u8() % 6;
      const gyro_spring_constants c = spring(in);
      mutating(w, "gyro_soft_body_set_family",
               [&] { return gyro_soft_body_set_family(w, id, fam, null_out ? nullptr : &c); });
      break;
    }
    case 4: {
      const gyro_spring_family fam = in.u8() % 6;
      gyro_spring_constants c;
      Guard<gyro_spring_constants> g(c);
      const gyro_status r = reading(w, "gyro_soft_body_get_family",
                                    [&] { return gyro_soft_body_get_family(w, id, fam, null_out ? nullptr : &c); });
      g.untouched_unless(r, "gyro_soft_body_get_family");
      break;
    }
    case 5: {
      const float m = in.f();
      mutating(w, "gyro_soft_body_set_mass", [&] { return gyro_soft_body_set_mass(w, id, m); });
      break;
    }
    case 6: {
      const float m = in.f();
      mutating(w, "gyro_soft_body_set_particle_mass", [&] { return gyro_soft_body_set_particle_mass(w, id, p, m); });
      break;
    }
    case 7: mutating(w, "gyro_soft_body_pin", [&] { return gyro_soft_body_pin(w, id, p); }); break;
    case 8: mutating(w, "gyro_soft_body_unpin", [&] { return gyro_soft_body_unpin(w, id, p); }); break;
    case 9: {
      uint32_t v;
      Guard<uint32_t> g(v);
      const gyro_status r =
          reading(w, "gyro_soft_body_is_pinned", [&] { return gyro_soft_body_is_pinned(w, id, p, null_out ? nullptr : &v); });
      g.untouched_unless(r, "gyro_soft_body_is_pinned");
      if (r == GYRO_OK && v > 1) die("gyro_soft_body_is_pinned gave %u", v);
      break;
    }
    case 10:
    case 11: {
      gyro_vec3 v;
      Guard<gyro_vec3> g(v);
      const bool pos = what == 10;
      const gyro_status r = reading(w, pos ? "gyro_soft_body_get_position" : "gyro_soft_body_get_velocity", [&] {
        return pos ? gyro_soft_body_get_position(w, id, p, null_out ? nullptr : &v)
                   : gyro_soft_body_get_velocity(w, id, p, null_out ? nullptr : &v);
      });
      g.untouched_unless(r, "gyro_soft_body_get_position/velocity");
      break;
    }
    case 12: {
      const gyro_vec3 v = in.v3();
      mutating(w, "gyro_soft_body_set_position", [&] { return gyro_soft_body_set_position(w, id, p, v); });
      break;
    }
    case 13: {
      const gyro_vec3 v = in.v3();
      mutating(w, "gyro_soft_body_set_velocity", [&] { return gyro_soft_body_set_velocity(w, id, p, v); });
      break;
    }
    case 14: {
      uint32_t v;
      Guard<uint32_t> g(v);
      const gyro_status r = reading(w, "gyro_soft_body_cloth_index",
                                    [&] { return gyro_soft_body_cloth_index(w, id, p, q, null_out ? nullptr : &v); });
      g.untouched_unless(r, "gyro_soft_body_cloth_index");
      break;
    }
    case 15: {
      const float rest = in.f();
      uint32_t j;
      Guard<uint32_t> g(j);
      const bool null_j = in.flag(2);
      const gyro_status r = mutating(w, "gyro_soft_body_add_distance_joint", [&] {
        return gyro_soft_body_add_distance_joint(w, id, p, q, rest, null_j ? nullptr : &j);
      });
      g.untouched_unless(r, "gyro_soft_body_add_distance_joint");
      break;
    }
    case 16: mutating(w, "gyro_soft_body_add_ball_joint", [&] { return gyro_soft_body_add_ball_joint(w, id, p, q); }); break;
    case 17: {
      const uint32_t a1 = particle_index(in), b1 = particle_index(in);
      mutating(w, "gyro_soft_body_add_hinge_joint",
               [&] { return gyro_soft_body_add_hinge_joint(w, id, p, q, a1, b1); });
      break;
    }
    case 18: {
      gyro_soft_body_view v;
      Guard<gyro_soft_body_view> g(v);
      const gyro_status r =
          reading(w, "gyro_soft_body_get_view", [&] { return gyro_soft_body_get_view(w, id, null_out ? nullptr : &v); });
      g.untouched_unless(r, "gyro_soft_body_get_view");
      if (r != GYRO_OK || null_out) break;
      if (v.count < 0 || v.triangle_count < 0) die("negative soft body view counts");
      float sum = 0.0f;
      for (int32_t i = 0; i < v.count; ++i)
        sum += v.px[i] + v.py[i] + v.pz[i] + v.vx[i] + v.vy[i] + v.vz[i] + v.inverse_mass[i];
      for (int32_t i = 0; i < 3 * v.triangle_count; ++i)
        if (v.triangles[i] >= uint32_t(v.count)) die("soft body triangle index %u >= %d particles", v.triangles[i], v.count);
      (void)sum;
      break;
    }
    case 19: {
      gyro_soft_body_stats s;
      Guard<gyro_soft_body_stats> g(s);
      const gyro_status r =
          reading(w, "gyro_soft_body_get_stats", [&] { return gyro_soft_body_get_stats(w, id, null_out ? nullptr : &s); });
      g.untouched_unless(r, "gyro_soft_body_get_stats");
      break;
    }
    case 20: {
      uint64_t h;
      Guard<uint64_t> g(h);
      const gyro_status r =
          reading(w, "gyro_soft_body_hash", [&] { return gyro_soft_body_hash(w, id, null_out ? nullptr : &h); });
      g.untouched_unless(r, "gyro_soft_body_hash");
      break;
    }
    case 21: {
      const uint32_t v = gyro_soft_body_is_valid(w, id);
      if (v > 1) die("gyro_soft_body_is_valid gave %u", v);
      break;
    }
    default: {
      const gyro_vec3 v = in.v3();
      mutating(w, "gyro_soft_body_set_position", [&] { return gyro_soft_body_set_position(w, id, p, v); });
      mutating(w, "gyro_soft_body_pin", [&] { return gyro_soft_body_pin(w, id, p); });
      break;
    }
  }
}

// ------------------------------------------------------------------ meshes and hulls

constexpr int kMeshVerts = 16, kMeshTris = 16;

void op_mesh_create(State& st) {
  Input& in = st.in;
  const int slot = in.u8() % kMeshes;
  float x[kMeshVerts], y[kMeshVerts], z[kMeshVerts];
  uint32_t idx[3 * kMeshTris];
  // A valid start: a grid of two rows of vertices, a strip of triangles.
  for (int v = 0; v < kMeshVerts; ++v) x[v] = float(v / 2) - 4.0f, y[v] = 0.0f, z[v] = float(v % 2) * 2.0f - 1.0f;
  for (int t = 0; t < kMeshTris; ++t) {
    const uint32_t a = uint32_t(t % (kMeshVerts - 2));
    idx[3 * t] = a, idx[3 * t + 1] = a + 1 + (t & 1), idx[3 * t + 2] = a + 2 - (t & 1);
  }
  int32_t nv = 4 + in.u8() % (kMeshVerts - 3), nt = 1 + in.u8() % kMeshTris;
  if (nt > nv - 2) nt = nv - 2;
  gyro_mesh_def d = gyro_mesh_def_default();
  for (int e = in.u8() % 6; e > 0; --e) {
    switch (in.u8() % 9) {
      case 0: {
        const uint32_t sizes[] = {uint32_t(sizeof d), 0, uint32_t(sizeof d) - 4, in.u32()};
        d.struct_size = sizes[in.u8() % 4];
        break;
      }
      case 1: nv = in.count(kMeshVerts); break;
      case 2: nt = in.count(kMeshTris); break;
      case 3: {
        const int v = in.u8() % kMeshVerts;
        x[v] = in.f(), y[v] = in.f(), z[v] = in.f();
        break;
      }
      case 4: idx[in.u8() % (3 * kMeshTris)] = in.u8() < 0xF0 ? in.u8() % (kMeshVerts + 2) : in.u32(); break;
      case 5: d.reserved = in.u32(); break;
      case 6: for (int v = 0; v < kMeshVerts; ++v) y[v] = float(int(in.u8() % 9) - 4) * 0.25f; break;
      case 7: idx[in.u8() % (3 * kMeshTris)] = uint32_t(nv); break;
      default: idx[3 * (in.u8() % kMeshTris) + 1] = idx[3 * (in.u8() % kMeshTris)]; break;  // degenerate
    }
  }
  d.vertex_count = nv, d.triangle_count = nt;
  const uint8_t np = in.u8() % 10;
  d.x = np == 1 ? nullptr : x, d.y = np == 2 ? nullptr : y, d.z = np == 3 ? nullptr : z;
  d.indices = np == 4 ? nullptr : idx;
  gyro_mesh* m;
  Guard<gyro_mesh*> g(m);
  const gyro_status s = checked(gyro_mesh_create(np == 5 ? nullptr : &d, np == 6 ? nullptr : &m), "gyro_mesh_create");
  g.untouched_unless(s, "gyro_mesh_create");
  if (s != GYRO_OK) return;
  gyro_mesh_info info;
  checked(gyro_mesh_get_info(m, &info), "gyro_mesh_get_info");
  if (info.triangle_count != nt) die("mesh info: %d triangles, created with %d", info.triangle_count, nt);
  gyro_mesh_destroy(st.meshes[slot]);
  st.meshes[slot] = m;
}

void op_mesh_destroy(State& st) {
  const int slot = st.in.u8() % kMeshes;
  gyro_mesh_destroy(st.meshes[slot]);
  st.meshes[slot] = nullptr;
  gyro_mesh_destroy(nullptr);
}

constexpr int kHullPoints = 24;

void op_hull_create(State& st) {
  Input& in = st.in;
  const int slot = in.u8() % kHulls;
  gyro_vec3 pts[kHullPoints];
  // A valid start: the corners of a box, then points inside and around it, then edits.
  for (int i = 0; i < kHullPoints; ++i) {
    const float s = i < 8 ? 1.0f : 0.5f;
    pts[i] = {(i & 1) ? s : -s, (i & 2) ? s : -s, (i & 4) ? s : -s};
  }
  int32_t n = 8 + in.u8() % (kHullPoints - 7);
  const uint8_t mode = in.u8() % 8;
  if (mode == 1) {  // every point fuzzed
    for (int i = 0; i < kHullPoints; ++i) pts[i] = in.v3();
  } else if (mode == 2) {  // small integer lattice points (coplanar and duplicate sets are likely)
    for (int i = 0; i < kHullPoints; ++i) {
      const uint8_t b = in.u8();
      pts[i] = {float(b & 3), float((b >> 2) & 3), float((b >> 4) & 3)};
    }
  } else if (mode == 3) {  // all on a plane, or nearly
    const float eps = in.flag(2) ? 0.0f : 1e-6f;
    for (int i = 0; i < kHullPoints; ++i) pts[i] = {in.f(), (i == 5) ? eps : 0.0f, in.f()};
  }
  for (int e = in.u8() % 5; e > 0; --e) {
    switch (in.u8() % 4) {
      case 0: n = in.count(kHullPoints); break;
      case 1: pts[in.u8() % kHullPoints] = in.v3(); break;
      case 2: pts[in.u8() % kHullPoints] = pts[in.u8() % kHullPoints]; break;
      default: {
        const int i = in.u8() % kHullPoints;
        pts[i].x *= 1e-7f, pts[i].y += 1e-7f;
        break;
      }
    }
  }
  const uint8_t np = in.u8() % 12, cap_pick = in.u8();
  gyro_convex_hull* h;
  Guard<gyro_convex_hull*> g(h);
  const gyro_status s = checked(gyro_convex_hull_create(np == 1 ? nullptr : pts, n, np == 2 ? nullptr : &h),
                                "gyro_convex_hull_create", ALLOW_INTERNAL);
  g.untouched_unless(s, "gyro_convex_hull_create");
  if (s != GYRO_OK) return;
  // The topology must index what exists.
  gyro_convex_hull_info info;
  checked(gyro_convex_hull_get_info(h, &info), "gyro_convex_hull_get_info");
  if (info.vertex_count < 4 || info.vertex_count > n || info.face_count < 4 || info.edge_count < 6)
    die("hull info: %d vertices (from %d points), %d faces, %d edges", info.vertex_count, n, info.face_count,
        info.edge_count);
  std::vector<uint32_t> starts(size_t(info.face_count) + 1), fv(size_t(info.face_vertex_count));
  std::vector<gyro_convex_edge> edges(size_t(info.edge_count));
  std::vector<gyro_vec3> verts(size_t(info.vertex_count));
  std::vector<gyro_convex_plane> planes(size_t(info.face_count));
  int32_t c = -1;
  const int32_t cap = cap_pick < 0xF0 ? int32_t(cap_pick % (info.vertex_count + 1)) : -1;
  checked(gyro_convex_hull_get_vertices(h, cap > 0 ? verts.data() : nullptr, cap, &c), "gyro_convex_hull_get_vertices");
  checked(gyro_convex_hull_get_vertices(h, verts.data(), info.vertex_count, &c), "gyro_convex_hull_get_vertices");
  if (c != info.vertex_count) die("hull vertices: count %d, info %d", c, info.vertex_count);
  checked(gyro_convex_hull_get_planes(h, planes.data(), info.face_count, &c), "gyro_convex_hull_get_planes");
  checked(gyro_convex_hull_get_face_starts(h, starts.data(), info.face_count + 1, &c), "gyro_convex_hull_get_face_starts");
  if (c != info.face_count + 1) die("hull face starts: count %d, %d faces", c, info.face_count);
  checked(gyro_convex_hull_get_face_vertices(h, fv.data(), info.face_vertex_count, &c),
          "gyro_convex_hull_get_face_vertices");
  checked(gyro_convex_hull_get_edges(h, edges.data(), info.edge_count, &c), "gyro_convex_hull_get_edges");
  if (starts[0] != 0 || starts[size_t(info.face_count)] != uint32_t(info.face_vertex_count))
    die("hull face starts do not cover the face vertices");
  for (int f = 0; f < info.face_count; ++f)
    if (starts[size_t(f) + 1] < starts[size_t(f)] + 3) die("hull face %d has fewer than 3 vertices", f);
  for (uint32_t v : fv)
    if (v >= uint32_t(info.vertex_count)) die("hull face vertex %u out of range", v);
  for (const auto& e : edges)
    if (!(e.a < e.b && e.b < uint32_t(info.vertex_count))) die("hull edge (%u, %u) out of range", e.a, e.b);
  gyro_convex_mass mass;
  checked(gyro_convex_hull_mass(h, &mass), "gyro_convex_hull_mass");
  // Copy-out getters with bad arguments.
  checked(gyro_convex_hull_get_edges(h, nullptr, 1, &c), "gyro_convex_hull_get_edges(NULL, 1)");
  checked(gyro_convex_hull_get_edges(h, nullptr, -1, &c), "gyro_convex_hull_get_edges(-1)");
  checked(gyro_convex_hull_get_edges(h, edges.data(), 0, nullptr), "gyro_convex_hull_get_edges(count NULL)");
  gyro_convex_hull_destroy(st.hulls[slot]);
  st.hulls[slot] = h;
}

void op_hull_destroy(State& st) {
  const int slot = st.in.u8() % kHulls;
  gyro_convex_hull_destroy(st.hulls[slot]);
  st.hulls[slot] = nullptr;
  gyro_convex_hull_destroy(nullptr);
}

gyro_convex_shape convex_shape(State& st) {
  Input& in = st.in;
  gyro_convex_shape s;
  std::memset(&s, 0, sizeof s);
  s.type = in.u8() % 7;
  s.radius = in.u8() < 0xE0 ? 0.5f : in.f();
  s.half_height = in.u8() < 0xE0 ? 0.5f : in.f();
  s.half_extents = {0.5f, 0.5f, 0.5f};
  s.triangle[0] = {0, 0, 0}, s.triangle[1] = {1, 0, 0}, s.triangle[2] = {0, 0, 1};
  if (s.type == GYRO_CONVEX_HULL) s.hull = pick_hull(st);
  switch (in.u8() % 8) {
    case 0: s.half_extents = in.v3(); break;
    case 1: s.triangle[in.u8() % 3] = in.v3(); break;
    case 2: s.reserved = in.u32(); break;
    case 3: s.hull = pick_hull(st); break;
    case 4: s.triangle[1] = s.triangle[2]; break;
    default: break;
  }
  return s;
}

gyro_convex_pose convex_pose(State& st) {
  Input& in = st.in;
  gyro_convex_pose p;
  p.position = {float(int(in.u8() % 9) - 4) * 0.25f, float(int(in.u8() % 9) - 4) * 0.25f, 0.0f};
  const uint8_t k = in.u8() % 4;
  if (k == 0) {  // raw rows: rarely a rotation
    p.rotation[0] = in.v3(), p.rotation[1] = in.v3(), p.rotation[2] = in.v3();
    p.position = in.v3();
    return p;
  }
  gyro_quat q = k == 1 ? gyro_quat{0, 0, 0, 1} : in.q4();
  gyro_convex_pose out;
  Guard<gyro_convex_pose> g(out);
  const gyro_status s = checked(gyro_convex_pose_from_quat(p.position, q, &out), "gyro_convex_pose_from_quat");
  g.untouched_unless(s, "gyro_convex_pose_from_quat");
  if (s == GYRO_OK) return out;
  p.rotation[0] = {1, 0, 0}, p.rotation[1] = {0, 1, 0}, p.rotation[2] = {0, 0, 1};
  return p;
}

void op_convex_pairs(State& st) {
  Input& in = st.in;
  constexpr int kPairs = 6;
  gyro_convex_shape a[kPairs], b[kPairs];
  gyro_convex_pose pa[kPairs], pb[kPairs];
  const int32_t n = in.count(kPairs);
  const int live = n > 0 ? n : 0;
  for (int i = 0; i < live; ++i) a[i] = convex_shape(st), pa[i] = convex_pose(st), b[i] = convex_shape(st), pb[i] = convex_pose(st);
  const uint8_t kind = in.u8() % 4, np = in.u8() % 12;
  gyro_convex_result out[kPairs];
  Guard<gyro_convex_result[kPairs]> g(out);
  const gyro_convex_shape* A = np == 1 ? nullptr : a;
  const gyro_convex_pose* PA = np == 2 ? nullptr : pa;
  const gyro_convex_shape* B = np == 3 ? nullptr : b;
  const gyro_convex_pose* PB = np == 4 ? nullptr : pb;
  gyro_convex_result* O = np == 5 ? nullptr : out;
  const char* name = kind == 0   ? "gyro_convex_intersect_pairs"
                     : kind == 1 ? "gyro_convex_distance_pairs"
                     : kind == 2 ? "gyro_convex_penetration_pairs"
                                 : "gyro_convex_contact_pairs";
  const gyro_status s = checked(kind == 0   ? gyro_convex_intersect_pairs(A, PA, B, PB, n, O)
                                : kind == 1 ? gyro_convex_distance_pairs(A, PA, B, PB, n, O)
                                : kind == 2 ? gyro_convex_penetration_pairs(A, PA, B, PB, n, O)
                                            : gyro_convex_contact_pairs(A, PA, B, PB, n, O),
                                name);
  g.untouched_unless(s, name);
  if (s != GYRO_OK) return;
  for (int i = 0; i < live; ++i) {
    const gyro_convex_result& r = out[i];
    if (r.status > GYRO_CONVEX_INVALID_INPUT) die("%s: pair %d status %u", name, i, r.status);
    if (r.status == GYRO_CONVEX_INVALID_INPUT) {
      gyro_convex_result zero;
      std::memset(&zero, 0, sizeof zero);
      zero.status = GYRO_CONVEX_INVALID_INPUT;
      if (std::memcmp(&zero, &r, sizeof r) != 0) die("%s: pair %d is INVALID_INPUT with non-zero fields", name, i);
    } else if (std::isnan(r.distance)) {
      die("%s: pair %d (status %u) has a NaN distance", name, i, r.status);
    }
  }
}

// ------------------------------------------------------------------ rays, shapes, batch calls

constexpr int kBatch = 8;

struct Rays {
  float ox[kBatch], oy[kBatch], oz[kBatch], dx[kBatch], dy[kBatch], dz[kBatch], tmin[kBatch], tmax[kBatch];
  gyro_ray_soa soa;
  int32_t n;

  void fill(Input& in) {
    n = in.count(kBatch);
    for (int i = 0; i < kBatch; ++i) {
      ox[i] = float(int(in.u8() % 9) - 4), oy[i] = 5.0f, oz[i] = float(int(in.u8() % 9) - 4);
      dx[i] = 0.0f, dy[i] = -1.0f, dz[i] = 0.0f, tmin[i] = 0.0f, tmax[i] = kInf;
    }
    for (int e = in.u8() % 6; e > 0; --e) {
      const int i = in.u8() % kBatch;
      switch (in.u8() % 6) {
        case 0: ox[i] = in.f(), oy[i] = in.f(), oz[i] = in.f(); break;
        case 1: dx[i] = in.f(), dy[i] = in.f(), dz[i] = in.f(); break;
        case 2: tmin[i] = in.f(); break;
        case 3: tmax[i] = in.f(); break;
        case 4: dx[i] = dy[i] = dz[i] = 0.0f; break;
        default: dx[i] = 1e-40f, dy[i] = 0.0f, dz[i] = 0.0f; break;
      }
    }
    const uint8_t np = in.u8() % 12;
    soa = {np == 1 ? nullptr : ox, oy, oz, dx, np == 2 ? nullptr : dy, dz, np == 3 || np == 5 ? nullptr : tmin,
           np == 4 || np == 5 ? nullptr : tmax};
  }
};

struct Hits {
  float t[kBatch], nx[kBatch], ny[kBatch], nz[kBatch], u[kBatch], v[kBatch];
  int32_t prim[kBatch];
  gyro_model_id model[kBatch];
  unsigned char before[sizeof(float) * 6 * kBatch + sizeof(int32_t) * kBatch + sizeof(gyro_model_id) * kBatch];

  gyro_hit_soa soa(uint8_t opt) {
    std::memset(this, 0x5A, offsetof(Hits, before));
    std::memcpy(before, this, sizeof before);
    gyro_hit_soa h{opt == 1 ? nullptr : t, opt == 2 ? nullptr : prim, nx, ny, nz, u, v};
    if (opt == 3) h.nx = h.ny = h.nz = nullptr;
    if (opt == 4) h.u = h.v = nullptr;
    if (opt == 5) h.ny = nullptr;  // partial normal: the header says all three or none
    if (opt == 6) h.v = nullptr;
    return h;
  }
  gyro_scene_hit_soa scene_soa(uint8_t opt) {
    const gyro_hit_soa h = soa(opt);
    return {h.t, opt == 7 ? nullptr : model, h.primitive, h.nx, h.ny, h.nz, h.u, h.v};
  }
  void untouched_unless(gyro_status s, const char* call) const {
    if (s != GYRO_OK && std::memcmp(before, this, sizeof before) != 0) die("%s failed (%d) and wrote hits", call, int(s));
  }
};

/// An array of one type of shape, every component kBatch long.
struct Shapes {
  float c[16][kBatch];
  gyro_shape_soa soa;
  int32_t n;

  void fill(Input& in, bool only_volumes = false) {
    n = in.count(kBatch);
    gyro_shape_type type = in.u8() % 6;
    if (only_volumes) type = 1 + type % 3;
    if (in.flag(16)) type = in.u32();
    std::memset(&soa, 0, sizeof soa);
    soa.type = type;
    if (in.flag(16)) soa.reserved = in.u32();
    for (int i = 0; i < kBatch; ++i) {
      c[0][i] = float(int(in.u8() % 9) - 4), c[1][i] = 0.0f, c[2][i] = float(int(in.u8() % 9) - 4);
      for (int k = 3; k < 16; ++k) c[k][i] = 0.0f;
    }
    // Sizes, unit axes, unit normals, triangle corners: valid defaults per type.
    for (int i = 0; i < kBatch; ++i) {
      switch (type) {
        case GYRO_SHAPE_SPHERE: c[3][i] = 1.0f; break;
        case GYRO_SHAPE_AABB: c[3][i] = c[4][i] = c[5][i] = 0.5f; break;
        case GYRO_SHAPE_OBB:
          c[3][i] = c[4][i] = c[5][i] = 0.5f;
          c[6][i] = 1.0f, c[10][i] = 1.0f, c[14][i] = 1.0f;
          break;
        case GYRO_SHAPE_PLANE: c[0][i] = 0.0f, c[1][i] = 1.0f, c[2][i] = 0.0f, c[3][i] = 0.0f; break;
        case GYRO_SHAPE_TRIANGLE: c[3][i] = c[0][i] + 1.0f, c[8][i] = c[2][i] + 1.0f; break;
        default: break;
      }
    }
    for (int e = in.u8() % 6; e > 0; --e) c[in.u8() % 16][in.u8() % kBatch] = in.f();
    const int null_at = in.u8() % 20;
    auto col = [&](int k) -> const float* { return k == null_at ? nullptr : c[k]; };
    switch (type) {
      case GYRO_SHAPE_SPHERE: soa.as.sphere = {col(0), col(1), col(2), col(3)}; break;
      case GYRO_SHAPE_AABB: soa.as.aabb = {col(0), col(1), col(2), col(3), col(4), col(5)}; break;
      case GYRO_SHAPE_OBB:
        soa.as.obb = {col(0), col(1), col(2),  col(3),  col(4),  col(5),  col(6),  col(7),
                      col(8), col(9), col(10), col(11), col(12), col(13), col(14)};
        break;
      case GYRO_SHAPE_PLANE: soa.as.plane = {col(0), col(1), col(2), col(3)}; break;
      case GYRO_SHAPE_TRIANGLE:
        soa.as.triangle = {col(0), col(1), col(2), col(3), col(4), col(5), col(6), col(7), col(8)};
        break;
      default:  // an unknown type: valid pointers all the same
        soa.as.obb = {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11], c[12], c[13], c[14]};
        break;
    }
  }
};

void check_primitives(const Hits& h, int32_t n, int32_t prims, const char* call, bool rays_may_be_invalid) {
  for (int32_t i = 0; i < n; ++i)
    if (!(h.prim[i] == -1 || (h.prim[i] >= 0 && h.prim[i] < prims) || (rays_may_be_invalid && h.prim[i] == GYRO_RAY_INVALID)))
      die("%s: ray %d got primitive %d of %d", call, i, h.prim[i], prims);
}

void op_batch_raycast(State& st) {
  Input& in = st.in;
  Rays r;
  r.fill(in);
  Shapes s;
  s.fill(in);
  Hits h;
  const uint8_t opt = in.u8() % 9, kind = in.u8() % 3, np = in.u8() % 10;
  const gyro_hit_soa hs = h.soa(opt);
  const gyro_ray_soa* R = np == 1 ? nullptr : &r.soa;
  const gyro_hit_soa* H = np == 2 ? nullptr : &hs;
  gyro_status st_;
  const char* name;
  if (kind == 0) {
    name = "gyro_raycast_closest";
    st_ = checked(gyro_raycast_closest(R, r.n, np == 3 ? nullptr : &s.soa, s.n, H), name);
  } else if (kind == 1) {
    name = "gyro_raycast_any";
    st_ = checked(gyro_raycast_any(R, r.n, np == 3 ? nullptr : &s.soa, s.n, H), name);
  } else {
    name = "gyro_raycast_spheres_closest";
    st_ = checked(gyro_raycast_spheres_closest(R, r.n, np == 3 ? nullptr : &s.soa.as.sphere, s.n, H), name);
  }
  h.untouched_unless(st_, name);
  if (st_ == GYRO_OK && hs.primitive) check_primitives(h, r.n, s.n, name, false);
}

void op_batch_overlap(State& st) {
  Input& in = st.in;
  Shapes a, b;
  a.fill(in);
  b.fill(in);
  const uint8_t kind = in.u8() % 3, np = in.u8() % 10;
  uint32_t flags = in.u8() % 3;
  if (in.flag(16)) flags = in.u32();
  const int32_t n = np == 5 ? in.i32() < 0 ? -1 : 0 : in.count(kBatch);
  uint32_t out[kBatch];
  float sep[kBatch];
  Guard<uint32_t[kBatch]> g(out);
  Guard<float[kBatch]> gs(sep);
  const char* name;
  gyro_status s;
  if (kind == 0) {
    name = "gyro_overlap_pairwise";
    s = checked(gyro_overlap_pairwise(np == 1 ? nullptr : &a.soa, np == 2 ? nullptr : &b.soa, n,
                                      np == 3 ? nullptr : out, flags),
                name);
  } else if (kind == 1) {
    name = "gyro_overlap_one_against_many";
    s = checked(gyro_overlap_one_against_many(np == 1 ? nullptr : &a.soa, np == 2 ? nullptr : &b.soa, n,
                                              np == 3 ? nullptr : out, flags),
                name);
  } else {
    name = "gyro_obb_separation_pairwise";
    s = checked(gyro_obb_separation_pairwise(np == 1 ? nullptr : &a.soa.as.obb, np == 2 ? nullptr : &b.soa.as.obb, n,
                                             np == 3 ? nullptr : sep),
                name);
  }
  g.untouched_unless(s, name), gs.untouched_unless(s, name);
  if (s == GYRO_OK && kind < 2)
    for (int32_t i = 0; i < n; ++i)
      if (out[i] > GYRO_INVALID_INPUT) die("%s: pair %d result %u", name, i, out[i]);
}

void op_mesh_raycast(State& st) {
  Input& in = st.in;
  const gyro_mesh* m = pick_mesh(st);
  Rays r;
  r.fill(in);
  Hits h;
  const uint8_t opt = in.u8() % 9, any = in.u8() & 1, np = in.u8() % 8;
  const gyro_hit_soa hs = h.soa(opt);
  const gyro_ray_soa* R = np == 1 ? nullptr : &r.soa;
  const gyro_hit_soa* H = np == 2 ? nullptr : &hs;
  const char* name = any ? "gyro_mesh_raycast_any" : "gyro_mesh_raycast_closest";
  const gyro_status s = checked(any ? gyro_mesh_raycast_any(m, R, r.n, H) : gyro_mesh_raycast_closest(m, R, r.n, H), name);
  h.untouched_unless(s, name);
  if (s == GYRO_OK && hs.primitive) {
    gyro_mesh_info info;
    checked(gyro_mesh_get_info(m, &info), "gyro_mesh_get_info");
    check_primitives(h, r.n, info.triangle_count, name, true);
  }
}

// ------------------------------------------------------------------ camera, frustum, scenes

gyro_camera camera(Input& in) {
  gyro_camera c = gyro_camera_perspective(in.u8() < 0xE0 ? 1.0f : in.f(), in.u8() < 0xE0 ? 1.5f : in.f(),
                                          in.u8() < 0xE0 ? 0.1f : in.f(), in.u8() < 0xE0 ? 100.0f : in.f());
  const float eye[3] = {float(int(in.u8() % 9) - 4), 5.0f, -10.0f}, target[3] = {0, 0, 0};
  float up[3] = {0, 1, 0};
  const uint8_t k = in.u8() % 6;
  if (k == 1) up[0] = 0, up[1] = 0, up[2] = 0;
  if (k == 2) up[0] = in.f(), up[1] = in.f(), up[2] = in.f();
  gyro_camera before = c;
  const gyro_status s = checked(gyro_camera_look_at(&c, eye, k == 3 ? eye : target, up), "gyro_camera_look_at");
  if (s != GYRO_OK && std::memcmp(&before, &c, sizeof c) != 0) die("gyro_camera_look_at failed and changed the camera");
  if (k == 4) c.mode = in.u8() % 3;
  if (k == 5) c.orientation[in.u8() % 9] = in.f(), c.position[in.u8() % 3] = in.f();
  if (in.flag(8)) c.mode = GYRO_PROJECTION_ORTHOGRAPHIC, c.width = in.f(), c.height = in.f();
  return c;
}

void op_camera(State& st) {
  Input& in = st.in;
  gyro_camera c = camera(in);
  const uint8_t np = in.u8() % 8;
  float m[16];
  Guard<float[16]> gm(m);
  const gyro_status s = checked(gyro_camera_view_projection(np == 1 ? nullptr : &c, np == 2 ? nullptr : m),
                                "gyro_camera_view_projection");
  gm.untouched_unless(s, "gyro_camera_view_projection");
  float o[3], d[3];
  const float sx = in.f() * 10.0f, sy = in.f() * 10.0f, vw = in.u8() < 0xE0 ? 640.0f : in.f(),
              vh = in.u8() < 0xE0 ? 480.0f : in.f();
  Guard<float[3]> go(o), gd(d);
  const gyro_status p = checked(
      gyro_camera_picking_ray(&c, sx, sy, vw, vh, np == 3 ? nullptr : o, np == 4 ? nullptr : d), "gyro_camera_picking_ray");
  go.untouched_unless(p, "gyro_camera_picking_ray"), gd.untouched_unless(p, "gyro_camera_picking_ray");
  gyro_frustum f;
  Guard<gyro_frustum> gf(f);
  gyro_status fs;
  if (s == GYRO_OK && in.flag(2)) {
    if (in.flag(4)) m[in.u8() % 16] = in.f();
    fs = checked(gyro_frustum_from_matrix(np == 5 ? nullptr : m, np == 6 ? nullptr : &f), "gyro_frustum_from_matrix");
  } else {
    fs = checked(gyro_camera_frustum(&c, np == 6 ? nullptr : &f), "gyro_camera_frustum");
  }
  gf.untouched_unless(fs, "gyro_frustum_*");
  if (fs != GYRO_OK) std::memset(&f, 0, sizeof f);
  if (in.flag(4)) f.planes[in.u8() % 6][in.u8() % 4] = in.f();
  Shapes sh;
  sh.fill(in, true);
  uint32_t vis[kBatch];
  Guard<uint32_t[kBatch]> gv(vis);
  const gyro_status cs = checked(gyro_frustum_cull(&f, &sh.soa, sh.n, np == 7 ? nullptr : vis), "gyro_frustum_cull");
  gv.untouched_unless(cs, "gyro_frustum_cull");
  if (cs == GYRO_OK)
    for (int32_t i = 0; i < sh.n; ++i)
      if (vis[i] > 1) die("gyro_frustum_cull: visible[%d] = %u", i, vis[i]);
}

SceneSlot* pick_scene(State& st, gyro_scene** s) {
  const uint8_t b = st.in.u8();
  if (b % 6 == 5) {
    *s = nullptr;
    return nullptr;
  }
  SceneSlot& slot = st.scenes[b % kScenes];
  *s = slot.s;
  return slot.s ? &slot : nullptr;
}

gyro_model_id pick_model(State& st, SceneSlot* slot) {
  static const std::vector<gyro_model_id> none;
  const SceneSlot& other = slot == &st.scenes[0] ? st.scenes[1] : st.scenes[0];
  return pick_id(st.in, slot ? slot->models : none, other.models);
}

gyro_transform transform(Input& in) {
  gyro_transform t = {{float(int(in.u8() % 9) - 4), 0.0f, float(int(in.u8() % 9) - 4)}, {0, 0, 0, 1}, 1.0f};
  switch (in.u8() % 8) {
    case 0: t.position[0] = in.f(), t.position[1] = in.f(), t.position[2] = in.f(); break;
    case 1: for (float& r : t.rotation) r = in.f(); break;
    case 2: t.scale = in.f(); break;
    case 3: t.rotation[3] = 0.0f; break;
    default: break;
  }
  return t;
}

void op_scene(State& st) {
  Input& in = st.in;
  const uint8_t what = in.u8() % 8;
  if (what == 0) {  // create or destroy
    SceneSlot& slot = st.scenes[in.u8() % kScenes];
    gyro_scene_accel accel = in.u8() % 3;
    if (in.flag(16)) accel = in.u32();
    gyro_scene* s;
    Guard<gyro_scene*> g(s);
    const bool null_out = in.flag(10);
    const gyro_status r = checked(gyro_scene_create(accel, null_out ? nullptr : &s), "gyro_scene_create");
    g.untouched_unless(r, "gyro_scene_create");
    gyro_scene_destroy(slot.s);
    gyro_scene_destroy(nullptr);
    slot.s = r == GYRO_OK && !null_out ? s : nullptr;
    return;
  }
  gyro_scene* s;
  SceneSlot* slot = pick_scene(st, &s);
  const int32_t before = gyro_scene_model_count(s);
  if (what == 1 || what == 2) {  // add
    gyro_model_def d = gyro_model_def_default();
    d.shape = in.u8() % 5;
    if (d.shape == GYRO_MODEL_MESH) d.mesh = pick_mesh(st);
    if (d.shape == GYRO_MODEL_PLANE) d.plane[0] = 0, d.plane[1] = 1, d.plane[2] = 0, d.plane[3] = 0;
    d.transform = transform(in);
    if (in.flag(3)) d.parent = pick_model(st, slot);
    for (int e = in.u8() % 4; e > 0; --e) {
      switch (in.u8() % 7) {
        case 0: {
          const uint32_t sizes[] = {uint32_t(sizeof d), 0, uint32_t(sizeof d) - 8, in.u32()};
          d.struct_size = sizes[in.u8() % 4];
          break;
        }
        case 1: d.radius = in.f(); break;
        case 2: d.half_extents[in.u8() % 3] = in.f(); break;
        case 3: d.plane[in.u8() % 4] = in.f(); break;
        case 4: d.mesh = pick_mesh(st); break;
        case 5: d.parent = pick_model(st, slot); break;
        default: d.shape = in.u32(); break;
      }
    }
    const uint8_t np = in.u8() % 10;
    gyro_model_id id;
    Guard<gyro_model_id> g(id);
    const gyro_status r =
        checked(gyro_scene_add_model(s, np == 1 ? nullptr : &d, np == 2 ? nullptr : &id), "gyro_scene_add_model");
    g.untouched_unless(r, "gyro_scene_add_model");
    const int32_t after = gyro_scene_model_count(s);
    if (after != before + (r == GYRO_OK ? 1 : 0))
      die("gyro_scene_add_model returned %d and the model count went %d -> %d", int(r), before, after);
    if (r == GYRO_OK && slot->models.size() < kMaxIds) slot->models.push_back(id);
    return;
  }
  const gyro_model_id id = pick_model(st, slot);
  if (what == 3) {
    const gyro_status r = checked(gyro_scene_remove_model(s, id), "gyro_scene_remove_model");
    const int32_t after = gyro_scene_model_count(s);
    // Removing a model removes its children too? The count falls by at least one on success.
    if (r == GYRO_OK ? !(after < before) : after != before)
      die("gyro_scene_remove_model returned %d and the model count went %d -> %d", int(r), before, after);
    return;
  }
  if (what == 4) {
    const gyro_transform t = transform(in);
    checked(gyro_scene_set_transform(s, id, in.flag(10) ? nullptr : &t), "gyro_scene_set_transform");
    return;
  }
  if (what == 5) {
    if (in.flag(3)) {  // layers (ABI 1.9): any value is valid
      checked(gyro_scene_set_layers(in.flag(12) ? nullptr : s, id, in.u32()), "gyro_scene_set_layers");
      if (gyro_scene_model_count(s) != before) die("gyro_scene_set_layers changed the model count");
      return;
    }
    const gyro_model_id parent = pick_model(st, slot);
    checked(gyro_scene_set_parent(s, id, parent), "gyro_scene_set_parent");
    if (gyro_scene_model_count(s) != before) die("gyro_scene_set_parent changed the model count");
    return;
  }
  if (what == 6) {  // rays
    Rays r;
    r.fill(in);
    Hits h;
    const uint8_t opt = in.u8() % 9, any = in.u8() & 1, np = in.u8() % 8;
    const gyro_scene_hit_soa hs = h.scene_soa(opt);
    const char* name = any ? "gyro_scene_raycast_any" : "gyro_scene_raycast_closest";
    const gyro_ray_soa* R = np == 1 ? nullptr : &r.soa;
    const gyro_scene_hit_soa* H = np == 2 ? nullptr : &hs;
    // Masked calls (ABI 1.9) with one mask per ray (the count the call is given) or none.
    std::vector<uint32_t> masks(r.n > 0 ? std::size_t(r.n) : 0);
    for (uint32_t& m : masks) m = in.flag(2) ? in.u32() : 0xFFFFFFFFu;
    const int masked = in.u8() % 3;  // 0: unmasked call, 1: masks, 2: null masks
    const uint32_t* M = masked == 1 && !masks.empty() ? masks.data() : nullptr;
    if (masked != 0) name = any ? "gyro_scene_raycast_any_masked" : "gyro_scene_raycast_closest_masked";
    const gyro_status rs =
        checked(masked != 0 ? (any ? gyro_scene_raycast_any_masked(s, R, M, r.n, H)
                                   : gyro_scene_raycast_closest_masked(s, R, M, r.n, H))
                            : (any ? gyro_scene_raycast_any(s, R, r.n, H) : gyro_scene_raycast_closest(s, R, r.n, H)),
                name);
    h.untouched_unless(rs, name);
    return;
  }
  // queries and picking
  const uint8_t k = in.u8() % 3;
  gyro_model_id out[16];
  int32_t count;
  const int32_t cap = in.u8() < 0xF0 ? in.u8() % 17 : in.i32() < 0 ? -1 : 0;
  const bool null_out = in.flag(8), null_count = in.flag(10);
  if (k == 0) {
    Shapes sh;
    sh.fill(in, true);
    checked(gyro_scene_query(s, &sh.soa, null_out ? nullptr : out, cap, null_count ? nullptr : &count), "gyro_scene_query");
  } else if (k == 1) {
    gyro_camera c = camera(in);
    gyro_frustum f;
    if (checked(gyro_camera_frustum(&c, &f), "gyro_camera_frustum") != GYRO_OK) std::memset(&f, 0, sizeof f);
    if (in.flag(4)) f.planes[in.u8() % 6][in.u8() % 4] = in.f();
    checked(gyro_scene_query_frustum(s, &f, null_out ? nullptr : out, cap, null_count ? nullptr : &count),
            "gyro_scene_query_frustum");
  } else {
    gyro_camera c = camera(in);
    gyro_scene_hit hit;
    Guard<gyro_scene_hit> g(hit);
    const gyro_status r = checked(gyro_scene_pick(s, &c, in.f() * 20.0f + 320.0f, in.f() * 20.0f + 240.0f, 640.0f, 480.0f,
                                                  null_out ? nullptr : &hit),
                                  "gyro_scene_pick");
    g.untouched_unless(r, "gyro_scene_pick");
    if (r == GYRO_OK && hit.hit > 1) die("gyro_scene_pick: hit = %u", hit.hit);
  }
}

// ------------------------------------------------------------------ snapshots, restore, replay

constexpr size_t kSnapHeader = 32;

uint32_t load32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
uint64_t load64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

/// Re-seals a snapshot whose payload was changed: payload size and checksum in the header.
/// Only when the header looks like the one the checksum was verified on (format known).
void reseal(std::vector<uint8_t>& b) {
  if (b.size() < kSnapHeader || std::memcmp(b.data(), "GYROSNAP", 8) != 0) return;
  const uint64_t payload = b.size() - kSnapHeader;
  const uint64_t sum = gyro::detail::checksum64(b.data() + kSnapHeader, payload);
  std::memcpy(b.data() + 16, &payload, 8);
  std::memcpy(b.data() + 24, &sum, 8);
}

/// The snapshot format this library writes is the one reseal() knows: magic, size, checksum.
bool g_format_known = false;
uint32_t g_format_version = 1;

bool take_snapshot(gyro_world* w, std::vector<uint8_t>& out) {
  uint64_t size = 0;
  if (checked(gyro_world_snapshot_size(w, &size), "gyro_world_snapshot_size", ALLOW_UNSUPPORTED) != GYRO_OK) return false;
  if (size < kSnapHeader || size > (64u << 20)) die("gyro_world_snapshot_size gave %llu", (unsigned long long)size);
  out.assign(size_t(size), 0xEE);
  // Too small a buffer first: INVALID_COUNT, nothing written.
  uint64_t got = 12345;
  const gyro_status small = checked(gyro_world_snapshot(w, out.data(), size - 1, &got), "gyro_world_snapshot(small)");
  if (small != GYRO_STATUS_INVALID_COUNT || got != 12345) die("gyro_world_snapshot with capacity size - 1 gave %d", int(small));
  for (uint8_t c : out)
    if (c != 0xEE) die("gyro_world_snapshot with too small a buffer wrote into it");
  if (checked(gyro_world_snapshot(w, out.data(), size, &got), "gyro_world_snapshot") != GYRO_OK)
    die("gyro_world_snapshot failed with the size gyro_world_snapshot_size gave");
  if (got != size) die("gyro_world_snapshot wrote %llu bytes, size said %llu", (unsigned long long)got, (unsigned long long)size);
  if (!g_format_known && std::memcmp(out.data(), "GYROSNAP", 8) == 0 && load64(out.data() + 16) == size - kSnapHeader &&
      load64(out.data() + 24) == gyro::detail::checksum64(out.data() + kSnapHeader, size - kSnapHeader)) {
    g_format_known = true;
    g_format_version = load32(out.data() + 8);
  }
  return true;
}

/// A world from a snapshot: hash equal to the original's, and one step later still equal.
void op_snapshot_roundtrip(State& st) {
  Input& in = st.in;
  WorldSlot& slot = st.worlds[in.u8() % kWorlds];
  if (!slot.w || st.snapshots_left <= 0) return;
  st.snapshots_left--;
  std::vector<uint8_t> snap;
  if (!take_snapshot(slot.w, snap)) return;
  gyro_world* copy = nullptr;
  const gyro_status s = checked(gyro_world_create_from_snapshot(snap.data(), snap.size(), &copy),
                                "gyro_world_create_from_snapshot", ALLOW_UNSUPPORTED);
  if (s == GYRO_STATUS_UNSUPPORTED) return;
  if (s != GYRO_OK) die("gyro_world_create_from_snapshot failed (%d) on a fresh snapshot", int(s));
  const uint64_t h0 = hash_of(slot.w), h1 = hash_of(copy);
  if (h0 != h1) die("a world created from a snapshot has hash %016llx, the original %016llx", (unsigned long long)h1, (unsigned long long)h0);
  // The same snapshot into the other slot's world (restore over existing state).
  WorldSlot& other = st.worlds[(&slot - st.worlds + 1) % kWorlds];
  if (other.w && in.flag(2)) {
    const gyro_status r = mutating(other.w, "gyro_world_restore", [&] {
      return gyro_world_restore(other.w, snap.data(), snap.size());
    }, ALLOW_UNSUPPORTED);
    if (r == GYRO_OK) {
      if (hash_of(other.w) != h0) die("a restored world's hash differs from the snapshot's world");
      other.bodies = slot.bodies, other.softs = slot.softs;
      other.live_bodies = slot.live_bodies, other.particles = slot.particles;
      other.tainted = slot.tainted;
      other.record_clean = false;
    } else if (r != GYRO_STATUS_UNSUPPORTED && r != GYRO_STATUS_OUT_OF_MEMORY) {
      die("gyro_world_restore of a fresh snapshot failed (%d)", int(r));
    }
  }
  // Step both: the same bits (the determinism contract across a snapshot/restore).
  const float dt = in.flag(2) ? 1.0f / 60.0f : 1.0f / 30.0f;
  const int cost = 2 * (1 + slot.particles / 256);
  if (st.steps_left >= cost && !slot.tainted) {
    st.steps_left -= cost;
    const gyro_status a = checked(gyro_world_step(slot.w, dt), "gyro_world_step");
    const gyro_status b = checked(gyro_world_step(copy, dt), "gyro_world_step (restored copy)");
    if (a != b) die("stepping the original gave %d, the restored copy %d", int(a), int(b));
    if (hash_of(slot.w) != hash_of(copy)) die("after one step, the restored copy's hash differs from the original's");
  }
  gyro_world_destroy(copy);
}

/// Byte edits of a buffer: overwrite, flip, special words, insert, delete, truncate.
void mutate(Input& in, std::vector<uint8_t>& b, size_t protect) {
  for (int k = 1 + in.u8() % 4; k > 0; --k) {
    if (b.size() <= protect) return;
    const size_t span = b.size() - protect;
    size_t at = protect + (size_t(in.u16()) * 4 + (in.u8() & 3)) % span;
    switch (in.u8() % 8) {
      case 0: b[at] = in.u8(); break;
      case 1: b[at] ^= uint8_t(1u << (in.u8() & 7)); break;
      case 2:
      case 3: {  // a word: counts and indices live in 4- and 8-byte fields
        const uint32_t words[] = {0, 0xFFFFFFFFu, 0x7FFFFFFFu, 0x80000000u, 1, 2, 0x7FC00000u, 0x7F800000u,
                                  0xFF800000u, 0x00000001u, 1u << 24, 0x3F800000u, 0xBF800000u, 3, 64, in.raw32()};
        const uint32_t v = words[in.u8() % 16];
        at &= ~size_t(3);
        if (at < protect) at += 4;
        for (int i = 0; i < 4 && at + size_t(i) < b.size(); ++i) b[at + size_t(i)] = uint8_t(v >> (8 * i));
        if (v == 0xFFFFFFFFu && at + 8 <= b.size() && in.flag(2))  // a 64-bit count of all ones
          for (int i = 4; i < 8; ++i) b[at + size_t(i)] = 0xFF;
        break;
      }
      case 4: b.insert(b.begin() + std::ptrdiff_t(at), size_t(1 + in.u8() % 8), in.u8()); break;
      case 5: b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(std::min(b.size(), at + 1 + in.u8() % 8))); break;
      case 6: b.resize(at); break;
      default: std::swap(b[at], b[protect + (at * 7 + in.u8()) % span]); break;
    }
  }
}

/// Restores into world slot dst, creates a world from the bytes, and checks the failure rules.
void feed_snapshot(State& st, WorldSlot& dst, const std::vector<uint8_t>& b, bool from_fuzz) {
  const uint8_t* data = b.empty() ? nullptr : b.data();
  if (dst.w) {
    const gyro_status r = mutating(dst.w, "gyro_world_restore", [&] { return gyro_world_restore(dst.w, data, b.size()); },
                                   ALLOW_UNSUPPORTED);
    if (r == GYRO_OK) {
      if (!data) die("gyro_world_restore accepted a NULL buffer");
      dst.tainted = dst.tainted || from_fuzz;
      dst.record_clean = false;
      resync_bodies(dst);
    } else if (r != GYRO_STATUS_CORRUPT_DATA && r != GYRO_STATUS_UNSUPPORTED && r != GYRO_STATUS_OUT_OF_MEMORY &&
               !(r == GYRO_STATUS_NULL_ARGUMENT && !data) && !(r == GYRO_STATUS_INVALID_COUNT && b.size() > SIZE_MAX)) {
      die("gyro_world_restore of bad bytes returned %d (expected CORRUPT_DATA)", int(r));
    }
  }
  gyro_world* w;
  Guard<gyro_world*> g(w);
  const gyro_status c = checked(gyro_world_create_from_snapshot(data, b.size(), &w), "gyro_world_create_from_snapshot",
                                ALLOW_UNSUPPORTED);
  g.untouched_unless(c, "gyro_world_create_from_snapshot");
  if (c == GYRO_OK) {
    uint64_t h = hash_of(w);
    int32_t n = 0;
    checked(gyro_world_body_count(w, &n), "gyro_world_body_count");
    // Take it into an empty slot, so the program goes on with whatever the bytes made.
    for (auto& slot : st.worlds)
      if (!slot.w) {
        slot = WorldSlot{};
        slot.w = w, slot.tainted = from_fuzz;
        resync_bodies(slot);
        w = nullptr;
        break;
      }
    gyro_world_destroy(w);
    (void)h;
  } else if (c != GYRO_STATUS_CORRUPT_DATA && c != GYRO_STATUS_UNSUPPORTED && c != GYRO_STATUS_OUT_OF_MEMORY &&
             !(c == GYRO_STATUS_NULL_ARGUMENT && !data)) {
    die("gyro_world_create_from_snapshot of bad bytes returned %d (expected CORRUPT_DATA)", int(c));
  }
}

void op_snapshot_mutate(State& st) {
  Input& in = st.in;
  WorldSlot& src = st.worlds[in.u8() % kWorlds];
  WorldSlot& dst = st.worlds[in.u8() % kWorlds];
  if (!src.w || st.snapshots_left <= 0) return;
  st.snapshots_left--;
  std::vector<uint8_t> snap;
  if (!take_snapshot(src.w, snap)) return;
  const uint8_t mode = in.u8() % 4;
  mutate(in, snap, mode == 0 ? 0 : kSnapHeader);
  if (mode >= 2 && g_format_known) reseal(snap);  // past the checksum: the payload parser sees it
  feed_snapshot(st, dst, snap, true);
}

void op_raw_bytes(State& st) {
  Input& in = st.in;
  WorldSlot& dst = st.worlds[in.u8() % kWorlds];
  const uint8_t mode = in.u8() % 4;
  const uint16_t want = in.u16();
  std::vector<uint8_t> b;
  if (mode >= 1 && mode <= 2) {  // a valid header around the bytes
    b.resize(kSnapHeader);
    std::memcpy(b.data(), "GYROSNAP", 8);
    const uint32_t version = mode == 1 ? g_format_version : in.raw32();
    std::memcpy(b.data() + 8, &version, 4);
  }
  const size_t len = std::min<size_t>(want % 2048, in.n - in.i);
  b.insert(b.end(), in.p + in.i, in.p + in.i + len);
  in.i += len;
  if (mode >= 1 && mode <= 2) reseal(b);
  gyro_replay_report rep;
  std::memset(&rep, 0, sizeof rep);
  rep.struct_size = sizeof rep;
  bool null_out = false;
  if (mode == 3) {
    if (in.flag(8)) rep.struct_size = in.u32();
    null_out = in.flag(16);
  }
  if (st.snapshots_left <= 0) return;
  st.snapshots_left--;
  if (mode == 3) {  // replay: the raw bytes, sealed with a valid checksum when they end in 8 zero bytes
    if (b.size() >= 8 && load64(b.data() + b.size() - 8) == 0) {
      const uint64_t h = gyro::detail::fnv1a64(b.data(), b.size() - 8);
      std::memcpy(b.data() + b.size() - 8, &h, 8);
    }
    checked(gyro_replay(b.empty() ? nullptr : b.data(), b.size(), null_out ? nullptr : &rep), "gyro_replay(raw)",
            ALLOW_UNSUPPORTED);
    return;
  }
  feed_snapshot(st, dst, b, true);
}

void op_record(State& st) {
  Input& in = st.in;
  WorldSlot& slot = st.worlds[in.u8() % kWorlds];
  const uint8_t what = in.u8() % 4;
  if (!slot.w) return;
  if (what == 0) {
    const gyro_status s = checked(gyro_world_record_begin(slot.w), "gyro_world_record_begin", ALLOW_UNSUPPORTED);
    if (s == GYRO_OK) {
      if (slot.recording) die("gyro_world_record_begin succeeded while recording");
      slot.recording = slot.record_clean = true;
    } else if (s == GYRO_STATUS_INVALID_ARGUMENT && !slot.recording) {
      die("gyro_world_record_begin said 'already recording' on a world that is not");
    }
    return;
  }
  if (what == 1) {
    const gyro_status s = checked(gyro_world_record_end(slot.w), "gyro_world_record_end", ALLOW_UNSUPPORTED);
    if (s == GYRO_OK) slot.recording = slot.record_clean = false;
    return;
  }
  if (st.snapshots_left <= 0) return;
  st.snapshots_left--;
  uint64_t size = 0;
  if (checked(gyro_world_record_size(slot.w, &size), "gyro_world_record_size", ALLOW_UNSUPPORTED) != GYRO_OK) return;
  if (size > (64u << 20)) die("gyro_world_record_size gave %llu", (unsigned long long)size);
  std::vector<uint8_t> rec(size_t(size), 0);
  uint64_t got = 0;
  if (checked(gyro_world_record_copy(slot.w, rec.data(), size, &got), "gyro_world_record_copy", ALLOW_UNSUPPORTED) != GYRO_OK)
    return;
  if (got != size) die("gyro_world_record_copy wrote %llu bytes, size said %llu", (unsigned long long)got, (unsigned long long)size);
  gyro_replay_report rep;
  std::memset(&rep, 0, sizeof rep);
  rep.struct_size = sizeof rep;
  if (what == 2) {  // as recorded: no divergence, and the world the calls made
    const gyro_status s = checked(gyro_replay(rec.data(), rec.size(), &rep), "gyro_replay", ALLOW_UNSUPPORTED);
    if (s == GYRO_STATUS_UNSUPPORTED) return;
    if (s != GYRO_OK) die("gyro_replay of a fresh recording failed (%d)", int(s));
    if (rep.diverged && !slot.tainted) die("a fresh recording diverged at step %lld", (long long)rep.first_divergent_step);
    if (slot.record_clean && !slot.tainted && rep.final_hash != hash_of(slot.w))
      die("replaying a recording ended at hash %016llx, the world is at %016llx", (unsigned long long)rep.final_hash,
          (unsigned long long)hash_of(slot.w));
    return;
  }
  // A recording ends with the FNV-1a of everything before it: when this one does (the format
  // the harness knows), a mutated copy is re-sealed half of the time, so the parser sees it.
  const bool sealed = rec.size() >= 8 && load64(rec.data() + rec.size() - 8) ==
                                             gyro::detail::fnv1a64(rec.data(), rec.size() - 8);
  const bool reseal_it = in.flag(2);
  mutate(in, rec, in.flag(2) ? 0 : 24);
  if (sealed && reseal_it && rec.size() >= 8) {
    const uint64_t h = gyro::detail::fnv1a64(rec.data(), rec.size() - 8);
    std::memcpy(rec.data() + rec.size() - 8, &h, 8);
  }
  const gyro_status s = checked(gyro_replay(rec.data(), rec.size(), &rep), "gyro_replay(mutated)", ALLOW_UNSUPPORTED);
  if (s != GYRO_OK && s != GYRO_STATUS_CORRUPT_DATA && s != GYRO_STATUS_UNSUPPORTED && s != GYRO_STATUS_OUT_OF_MEMORY)
    die("gyro_replay of a corrupted recording returned %d", int(s));
}

// ------------------------------------------------------------------ process-wide settings

/// Every body's state is finite (the determinism contract covers finite state only).
bool bodies_finite(const gyro_world* w) {
  gyro_body_view v;
  if (gyro_world_get_body_view(w, &v) != GYRO_OK) return false;
  for (int32_t i = 0; i < v.count; ++i) {
    const float c[13] = {v.px[i], v.py[i], v.pz[i], v.qx[i], v.qy[i], v.qz[i], v.qw[i],
                         v.vx[i], v.vy[i], v.vz[i], v.wx[i], v.wy[i], v.wz[i]};
    for (float x : c)
      if (!std::isfinite(x)) return false;
  }
  return true;
}

void op_settings(State& st) {
  Input& in = st.in;
  switch (in.u8() % 6) {
    case 0: {
      gyro_simd_level l = in.u8() % 7;
      if (in.flag(16)) l = in.u32();
      const gyro_status s = checked(gyro_set_simd_level(l), "gyro_set_simd_level", ALLOW_UNSUPPORTED);
      if (s == GYRO_OK && l != GYRO_SIMD_AUTO && gyro_get_simd_level() != l) die("gyro_set_simd_level(%u) did not stick", l);
      if (s == GYRO_OK && !gyro_simd_level_available(l) && l != GYRO_SIMD_AUTO) die("level %u set but not available", l);
      break;
    }
    case 1: {  // a thread count up to 2 (more: invalid ones only, valid ones would be slow)
      const uint32_t t[] = {0, 1, 2, 1};
      checked(gyro_set_thread_count(t[in.u8() % 4]), "gyro_set_thread_count");
      break;
    }
    case 2: {
      const char* n = gyro_status_name(in.i32());
      const char* l = gyro_simd_level_name(in.u32());
      if (!n || !l) die("a name function returned NULL");
      (void)std::strlen(n), (void)std::strlen(l);
      break;
    }
    case 3: {
      const char* e = gyro_last_error();
      const char* v = gyro_version_string();
      if (!e || !v) die("gyro_last_error or gyro_version_string returned NULL");
      (void)std::strlen(e), (void)std::strlen(v);
      if (gyro_abi_version() >> 16 != GYRO_ABI_VERSION >> 16) die("ABI major mismatch");
      (void)gyro_features();
      break;
    }
    default: {  // the determinism contract: scalar and the best level step to the same bits
      WorldSlot& slot = st.worlds[in.u8() % kWorlds];
      const int cost = 2 * (1 + slot.particles / 256);
      if (!slot.w || slot.tainted || st.steps_left < cost || st.snapshots_left <= 0 || !bodies_finite(slot.w)) break;
      std::vector<uint8_t> snap;
      if (!take_snapshot(slot.w, snap)) break;
      gyro_world* copy = nullptr;
      if (checked(gyro_world_create_from_snapshot(snap.data(), snap.size(), &copy), "gyro_world_create_from_snapshot",
                  ALLOW_UNSUPPORTED) != GYRO_OK)
        break;
      st.snapshots_left--, st.steps_left -= cost;
      const gyro_simd_level was = gyro_get_simd_level();
      checked(gyro_set_simd_level(GYRO_SIMD_SCALAR), "gyro_set_simd_level(scalar)");
      const gyro_status a = checked(gyro_world_step(slot.w, 1.0f / 60.0f), "gyro_world_step (scalar)");
      checked(gyro_set_simd_level(GYRO_SIMD_AUTO), "gyro_set_simd_level(auto)");
      const gyro_status b = checked(gyro_world_step(copy, 1.0f / 60.0f), "gyro_world_step (best level)");
      if (a != b || hash_of(slot.w) != hash_of(copy))
        die("a step at the scalar level and at %s differ (status %d/%d)", gyro_simd_level_name(gyro_get_simd_level()),
            int(a), int(b));
      gyro_world_destroy(copy);
      checked(gyro_set_simd_level(was), "gyro_set_simd_level(restore)", ALLOW_UNSUPPORTED);
      break;
    }
  }
}

// ------------------------------------------------------------------ the program

using Op = void (*)(State&);
const Op kOps[] = {
    op_world_create,     // 0
    op_world_destroy,    // 1
    op_body_create,      // 2
    op_body_destroy,     // 3
    op_body_set,         // 4
    op_body_get,         // 5
    op_step,             // 6
    op_soft_create,      // 7
    op_soft_call,        // 8
    op_mesh_create,      // 9
    op_mesh_destroy,     // 10
    op_hull_create,      // 11
    op_hull_destroy,     // 12
    op_convex_pairs,     // 13
    op_batch_raycast,    // 14
    op_batch_overlap,    // 15
    op_mesh_raycast,     // 16
    op_camera,           // 17
    op_scene,            // 18
    op_snapshot_roundtrip,  // 19
    op_snapshot_mutate,  // 20
    op_raw_bytes,        // 21
    op_record,           // 22
    op_settings,         // 23
    op_body_create,      // 24: bodies and steps twice as often
    op_step,             // 25
};
constexpr size_t kOpCount = sizeof kOps / sizeof kOps[0];

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_trace = std::getenv("GYRO_FUZZ_TRACE") != nullptr;
  g_strict_finite = std::getenv("GYRO_FUZZ_STRICT_FINITE") != nullptr;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The same process-wide settings at the start of every input, so an input replays alone.
  gyro_set_simd_level(GYRO_SIMD_AUTO);
  gyro_set_thread_count(1);
  State st;
  st.in = Input{data, size};
  // The first byte is a header: bit 0 set, no world to start with; bit 1 set, a second one.
  // Most programs want a world, so slot 0 starts with a default one.
  const uint8_t header = st.in.u8();
  for (int k = 0; k < kWorlds; ++k)
    if (k == 0 ? !(header & 1) : (header & 2) != 0) {
      const gyro_world_def d = gyro_world_def_default();
      if (gyro_world_create(&d, &st.worlds[k].w) != GYRO_OK) die("gyro_world_create(default) failed");
    }
  size_t ops = 0;
  while (st.in.more() && ops++ < 512) {
    const uint8_t op = st.in.u8();
    trace("op %u at %zu\n", unsigned(op % kOpCount), st.in.i - 1);
    kOps[op % kOpCount](st);
  }
  return 0;
}
