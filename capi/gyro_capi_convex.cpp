// The C ABI of convex shapes (ABI 1.4): hull handles and their getters and mass properties,
// and GJK/EPA queries on arrays of pairs, over gyro/convex.hpp (box-box pairs through the
// box-pair batches, GJK over SIMD lanes, since ABI 1.6; the contact call is ABI 1.6).
//
// Whole-call errors (NULL arrays, negative counts) are found before anything is written. A
// pair that cannot be answered is flagged GYRO_CONVEX_INVALID_INPUT by the C layer's own
// per-pair check (so the verdict does not depend on what the C++ query accepts) or by the
// query itself; the other pairs are answered. Pairs run in fixed chunks (parallel_for), each
// result written by one chunk, so the output is the same at every thread count.
#define GYRO_BUILDING 1
#include "gyro.h"

#include "capi_convex.hpp"
#include "capi_support.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "gyro/convex.hpp"
#include "gyro/math_quat.hpp"

#include <bit>
#include <cfloat>
#include <climits>
#include <cstddef>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>

namespace {

using gyro::Status;
using gyro::capi::c_v3;
using gyro::capi::check_count;
using gyro::capi::check_finite;
using gyro::capi::guarded;
using gyro::capi::require;
using gyro::capi::v3;
using gyro::detail::fail;
using gyro::detail::is_finite;

// Plain-data layouts every binding relies on.
static_assert(sizeof(gyro_convex_hull_info) == 16 && sizeof(gyro_convex_plane) == 16 &&
              sizeof(gyro_convex_edge) == 8 && sizeof(gyro_convex_mass) == 100 && sizeof(gyro_convex_pose) == 48 &&
              sizeof(gyro_convex_result) == 48 && sizeof(gyro_convex_type) == 4 && sizeof(gyro_convex_status) == 4);
static_assert(sizeof(void*) != 8 || (sizeof(gyro_convex_shape) == 72 && offsetof(gyro_convex_shape, hull) == 64));
static_assert(offsetof(gyro_convex_shape, reserved) == 60 && offsetof(gyro_convex_result, iterations) == 44);
static_assert(uint32_t(gyro::ConvexType::sphere) == GYRO_CONVEX_SPHERE &&
              uint32_t(gyro::ConvexType::box) == GYRO_CONVEX_BOX &&
              uint32_t(gyro::ConvexType::capsule) == GYRO_CONVEX_CAPSULE &&
              uint32_t(gyro::ConvexType::cylinder) == GYRO_CONVEX_CYLINDER &&
              uint32_t(gyro::ConvexType::triangle) == GYRO_CONVEX_TRIANGLE &&
              uint32_t(gyro::ConvexType::points) == GYRO_CONVEX_HULL);
static_assert(uint32_t(gyro::ConvexStatus::separated) == GYRO_CONVEX_SEPARATED &&
              uint32_t(gyro::ConvexStatus::touching) == GYRO_CONVEX_TOUCHING &&
              uint32_t(gyro::ConvexStatus::intersecting) == GYRO_CONVEX_INTERSECTING &&
              uint32_t(gyro::ConvexStatus::iteration_limit) == GYRO_CONVEX_ITERATION_LIMIT &&
              uint32_t(gyro::ConvexStatus::invalid_input) == GYRO_CONVEX_INVALID_INPUT);
// The C points array is read as gyro::vec3 in place.
static_assert(sizeof(gyro_vec3) == sizeof(gyro::vec3) && alignof(gyro_vec3) == alignof(gyro::vec3) &&
              std::is_standard_layout_v<gyro::vec3>);

/// Pairs per parallel chunk: a function of nothing but this constant, so the chunks (and the
/// results) never depend on the thread count. A query takes about a microsecond; a chunk's
/// box pairs fill one block of the box-pair batches' lanes.
constexpr std::size_t kPairChunk = 128;

/// How far a pose's rotation rows may be from orthonormal (dot products within this of 0 or 1).
constexpr float kRotationTolerance = 1e-3f;

Status require_hull(const gyro_convex_hull* h) { return require(h, "hull"); }

// ---- the copy-out getters: *count = n, the first min(capacity, n) elements written ----

Status check_copy_args(const gyro_convex_hull* hull, const void* out, int32_t capacity, const int32_t* count) {
  GYRO_TRY(require_hull(hull));
  GYRO_TRY(require(count, "count"));
  GYRO_TRY(check_count(capacity, "capacity"));
  if (capacity > 0 && !out) return fail(Status::null_argument, "out is null and capacity = %d", capacity);
  return Status::ok;
}

Status fits_int32(std::size_t n, const char* name) {
  return n <= std::size_t(INT32_MAX) ? Status::ok
                                     : fail(Status::invalid_count, "%s = %zu does not fit an int32_t", name, n);
}

/// Checks, then writes convert(i) to out[i] for i < min(capacity, n) and n to *count.
template <class T, class Convert>
Status copy_out(T* out, int32_t capacity, int32_t* count, std::size_t n, const char* name, Convert&& convert) {
  GYRO_TRY(fits_int32(n, name));
  const std::size_t m = std::size_t(capacity) < n ? std::size_t(capacity) : n;
  for (std::size_t i = 0; i < m; ++i) out[i] = convert(i);
  *count = int32_t(n);
  return Status::ok;
}

// ---- the per-pair check and conversion ----

// The per-pair checks below run once per pair before a query of a few hundred nanoseconds:
// they combine their tests with & (no branch per test) and test finiteness bitwise.
// (0 or 1 as unsigned: & of function results, which clang would warn of for bool.)
unsigned finite_bits(float v) { return unsigned(is_finite(v)); }
unsigned finite3(const gyro_vec3& v) { return finite_bits(v.x) & finite_bits(v.y) & finite_bits(v.z); }
unsigned within(float x, float lo, float hi) { return unsigned(x >= lo) & unsigned(x <= hi); }

/// Why a shape cannot be answered (nullptr: it can), and the C++ shape when it can.
const char* shape_of(const gyro_convex_shape& c, gyro::ConvexShape& out) {
  if (c.reserved != 0) return "reserved is not 0";
  if (c.type > GYRO_CONVEX_HULL) return "unknown type";
  if (c.type == GYRO_CONVEX_HULL) {
    if (!c.hull) return "hull is null";
  } else if (c.hull) {
    return "hull is set for a type other than GYRO_CONVEX_HULL";
  }
  gyro::ConvexShape s;
  s.type = static_cast<gyro::ConvexType>(c.type);
  switch (c.type) {
    case GYRO_CONVEX_SPHERE:
      s.radius = c.radius;
      break;
    case GYRO_CONVEX_BOX:
      s.half_extents = v3(c.half_extents);
      break;
    case GYRO_CONVEX_CAPSULE:
    case GYRO_CONVEX_CYLINDER:
      s.radius = c.radius, s.half_height = c.half_height;
      break;
    case GYRO_CONVEX_TRIANGLE:
      for (int k = 0; k < 3; ++k) s.v[k] = v3(c.triangle[k]);
      break;
    default:  // GYRO_CONVEX_HULL: its vertices were checked finite when it was built
      s = c.hull->hull.shape();
      break;
  }
  const unsigned finite = finite_bits(s.radius) & finite_bits(s.half_height) & finite_bits(s.half_extents.x) &
                      finite_bits(s.half_extents.y) & finite_bits(s.half_extents.z) & finite_bits(s.v[0].x) &
                      finite_bits(s.v[0].y) & finite_bits(s.v[0].z) & finite_bits(s.v[1].x) & finite_bits(s.v[1].y) &
                      finite_bits(s.v[1].z) & finite_bits(s.v[2].x) & finite_bits(s.v[2].y) & finite_bits(s.v[2].z);
  if (!finite) return "a size or corner is NaN or infinite";
  if ((s.radius < 0.0f) | (s.half_height < 0.0f) | (s.half_extents.x < 0.0f) | (s.half_extents.y < 0.0f) |
      (s.half_extents.z < 0.0f))
    return "a size is negative";
  out = s;
  return nullptr;
}

/// 1 when finite rotation rows (x0 y0 z0), (x1 y1 z1), (x2 y2 z2) are orthonormal to
/// kRotationTolerance and right-handed. Plain floats in and out: BoxColumns::check() calls it
/// lane by lane in a loop the compiler vectorizes.
inline unsigned rotation_ok(float x0, float y0, float z0, float x1, float y1, float z1, float x2, float y2, float z2) {
  const float t = kRotationTolerance;
  const float n0 = ((x0 * x0 + y0 * y0) + z0 * z0) - 1.0f, n1 = ((x1 * x1 + y1 * y1) + z1 * z1) - 1.0f;
  const float n2 = ((x2 * x2 + y2 * y2) + z2 * z2) - 1.0f;
  const float o01 = (x0 * x1 + y0 * y1) + z0 * z1, o02 = (x0 * x2 + y0 * y2) + z0 * z2;
  const float o12 = (x1 * x2 + y1 * y2) + z1 * z2;
  // det = r0 . (r1 x r2): +1 for a rotation, -1 for a reflection.
  const float cx = y1 * z2 - z1 * y2, cy = z1 * x2 - x1 * z2, cz = x1 * y2 - y1 * x2;
  const float det = (x0 * cx + y0 * cy) + z0 * cz;
  return within(n0, -2.0f * t, 2.0f * t) & within(n1, -2.0f * t, 2.0f * t) & within(n2, -2.0f * t, 2.0f * t) &
         within(o01, -t, t) & within(o02, -t, t) & within(o12, -t, t) & unsigned(det > 0.0f);
}

/// Why a pose cannot be used (nullptr: it can), and the C++ pose when it can.
const char* pose_of(const gyro_convex_pose& c, gyro::ConvexPose& out) {
  if (!(finite3(c.position) & finite3(c.rotation[0]) & finite3(c.rotation[1]) & finite3(c.rotation[2])))
    return "the pose has a NaN or infinite value";
  const gyro_vec3 &r0 = c.rotation[0], &r1 = c.rotation[1], &r2 = c.rotation[2];
  if (!rotation_ok(r0.x, r0.y, r0.z, r1.x, r1.y, r1.z, r2.x, r2.y, r2.z))
    return "the pose's rotation rows are not orthonormal and right-handed";
  gyro::ConvexPose p;
  p.position = v3(c.position);
  for (int r = 0; r < 3; ++r) {
    p.rotation.m[r][0] = c.rotation[r].x, p.rotation.m[r][1] = c.rotation[r].y, p.rotation.m[r][2] = c.rotation[r].z;
  }
  out = p;
  return nullptr;
}

/// Why pair i cannot be answered, prefixed by which input ("a", "pa", "b", "pb"); nullptr if it can.
const char* pair_of(const gyro_convex_shape& a, const gyro_convex_pose& pa, const gyro_convex_shape& b,
                    const gyro_convex_pose& pb, gyro::ConvexShape& sa, gyro::ConvexPose& qa, gyro::ConvexShape& sb,
                    gyro::ConvexPose& qb, const char** which) {
  const char* why = nullptr;
  if ((why = shape_of(a, sa))) return *which = "a", why;
  if ((why = pose_of(pa, qa))) return *which = "pa", why;
  if ((why = shape_of(b, sb))) return *which = "b", why;
  if ((why = pose_of(pb, qb))) return *which = "pb", why;
  return nullptr;
}

// The C result is the C++ one field for field (the asserts below), so it is one copy.
static_assert(sizeof(gyro_convex_result) == sizeof(gyro::ConvexResult) && sizeof(gyro_convex_status) == 4);
static_assert(offsetof(gyro_convex_result, distance) == offsetof(gyro::ConvexResult, distance) &&
              offsetof(gyro_convex_result, normal) == offsetof(gyro::ConvexResult, normal) &&
              offsetof(gyro_convex_result, point_a) == offsetof(gyro::ConvexResult, point_a) &&
              offsetof(gyro_convex_result, point_b) == offsetof(gyro::ConvexResult, point_b) &&
              offsetof(gyro_convex_result, iterations) == offsetof(gyro::ConvexResult, iterations));
static_assert(uint32_t(gyro::ConvexStatus::separated) == GYRO_CONVEX_SEPARATED &&
              uint32_t(gyro::ConvexStatus::touching) == GYRO_CONVEX_TOUCHING &&
              uint32_t(gyro::ConvexStatus::intersecting) == GYRO_CONVEX_INTERSECTING &&
              uint32_t(gyro::ConvexStatus::iteration_limit) == GYRO_CONVEX_ITERATION_LIMIT &&
              uint32_t(gyro::ConvexStatus::invalid_input) == GYRO_CONVEX_INVALID_INPUT);

gyro_convex_result c_result(const gyro::ConvexResult& r) {
  gyro_convex_result c;
  std::memcpy(&c, &r, sizeof c);
  return c;
}

gyro_convex_result invalid_result() {
  gyro_convex_result c;
  std::memset(&c, 0, sizeof c);
  c.status = GYRO_CONVEX_INVALID_INPUT;
  return c;
}

enum class Query { intersect, distance, penetration, contact };

gyro::ConvexQueryOptions options_of(Query query) {
  gyro::ConvexQueryOptions o;
  o.separated_distance = query != Query::contact;
  return o;
}

gyro::ConvexResult query_pair(Query query, const gyro::ConvexShape& sa, const gyro::ConvexPose& qa,
                              const gyro::ConvexShape& sb, const gyro::ConvexPose& qb,
                              const gyro::ConvexQueryOptions& options) {
  switch (query) {
    case Query::intersect: return gyro::convex_intersect(sa, qa, sb, qb, options);
    case Query::distance: return gyro::convex_distance(sa, qa, sb, qb, options);
    default: return gyro::convex_penetration(sa, qa, sb, qb, options);  // penetration, contact
  }
}

gyro_convex_result c_answer(const gyro::ConvexResult& r) {
  return r.status == gyro::ConvexStatus::invalid_input ? invalid_result() : c_result(r);
}

/// A chunk's box-box pairs in the column form of gyro::ConvexBoxPairs, for the lanes (on the
/// stack, 23 KB, not cleared: the first n of each column are written, and check() pads them
/// with zeros to a multiple of eight). They are staged unchecked and checked in columns:
/// shape_of and pose_of pair by pair had cost as much as the lanes' GJK.
struct BoxColumns {
  float col[30][kPairChunk];  // A's centre, half extents, rotation rows, then B's
  std::size_t index[kPairChunk];  // the pairs' indices in the call
  unsigned valid[kPairChunk];
  gyro::ConvexResult result[kPairChunk];
  std::size_t n = 0;

  /// Two shapes that shape_of would read as boxes (their other fields unread).
  static bool boxes(const gyro_convex_shape& a, const gyro_convex_shape& b) {
    return (a.type == GYRO_CONVEX_BOX) & (b.type == GYRO_CONVEX_BOX) & (a.reserved == 0) & (b.reserved == 0) &
           (a.hull == nullptr) & (b.hull == nullptr);
  }

  void add(std::size_t i, const gyro_convex_shape& a, const gyro_convex_pose& pa, const gyro_convex_shape& b,
           const gyro_convex_pose& pb) {
    const std::size_t k = n++;
    index[k] = i;
    const auto box = [&](int base, const gyro_convex_shape& s, const gyro_convex_pose& q) {
      col[base + 0][k] = q.position.x, col[base + 1][k] = q.position.y, col[base + 2][k] = q.position.z;
      col[base + 3][k] = s.half_extents.x, col[base + 4][k] = s.half_extents.y, col[base + 5][k] = s.half_extents.z;
      for (int r = 0; r < 3; ++r)
        col[base + 6 + 3 * r][k] = q.rotation[r].x, col[base + 7 + 3 * r][k] = q.rotation[r].y,
                       col[base + 8 + 3 * r][k] = q.rotation[r].z;
    };
    box(0, a, pa), box(15, b, pb);
  }

  /// valid[k]: pair k passes shape_of and pose_of (the same tests and expressions, so the
  /// same verdict), eight pairs at a time in loops the compiler turns into vector code (the
  /// columns are padded to a multiple of eight with zeros, which are not read afterwards).
  void check() {
    const std::size_t padded = (n + 7) & ~std::size_t(7);
    for (std::size_t k = n; k < padded; ++k)
      for (auto& c : col) c[k] = 0.0f;
    for (std::size_t k0 = 0; k0 < padded; k0 += 8) {
      unsigned ok[8];
      for (unsigned& o : ok) o = 1;
      // Centres finite; half extents in [0, FLT_MAX] (finite and not negative: NaN fails
      // both compares). The rotations' finiteness is rotation_ok's: a NaN or infinite entry
      // makes its row's squared length minus 1 NaN or infinite, outside the tolerance. So
      // the verdict is pose_of's and shape_of's, each column read once.
      for (int c : {0, 1, 2, 15, 16, 17})
        for (int j = 0; j < 8; ++j) ok[j] &= unsigned((std::bit_cast<uint32_t>(col[c][k0 + j]) & 0x7f800000u) != 0x7f800000u);
      for (int c : {3, 4, 5, 18, 19, 20})
        for (int j = 0; j < 8; ++j) ok[j] &= within(col[c][k0 + j], 0.0f, FLT_MAX);
      for (int base : {6, 21}) {  // the rotations, lane by lane
        const float* r = &col[base][k0];
        const auto at = [&](int q, int j) { return r[std::size_t(q) * kPairChunk + std::size_t(j)]; };
        for (int j = 0; j < 8; ++j)
          ok[j] &= rotation_ok(at(0, j), at(1, j), at(2, j), at(3, j), at(4, j), at(5, j), at(6, j), at(7, j), at(8, j));
      }
      for (int j = 0; j < 8; ++j) valid[k0 + std::size_t(j)] = ok[j];
    }
  }

  gyro::ConvexBoxPairs view() const {
    gyro::ConvexBoxPairs p;
    for (int k = 0; k < 3; ++k) p.a_center[k] = col[k], p.a_half[k] = col[3 + k], p.b_center[k] = col[15 + k], p.b_half[k] = col[18 + k];
    for (int k = 0; k < 9; ++k) p.a_rot[k] = col[6 + k], p.b_rot[k] = col[21 + k];
    return p;
  }
};

// The pairs of chunk [begin, end): box-box pairs through the box-pair batches (GJK over SIMD
// lanes, the scalar query's bits), the others one by one. Nothing escapes the OpenMP thread:
// if the batches cannot allocate their lane state, the box pairs run one by one too.
void run_chunk(const gyro_convex_shape* a, const gyro_convex_pose* pa, const gyro_convex_shape* b,
               const gyro_convex_pose* pb, std::size_t begin, std::size_t end, gyro_convex_result* out, Query query) {
  const gyro::ConvexQueryOptions options = options_of(query);
  BoxColumns boxes;
  for (std::size_t i = begin; i < end; ++i) {
    if (BoxColumns::boxes(a[i], b[i])) {
      boxes.add(i, a[i], pa[i], b[i], pb[i]);
      continue;
    }
    gyro::ConvexShape sa, sb;
    gyro::ConvexPose qa, qb;
    const char* which = nullptr;
    if (pair_of(a[i], pa[i], b[i], pb[i], sa, qa, sb, qb, &which)) out[i] = invalid_result();
    else out[i] = c_answer(query_pair(query, sa, qa, sb, qb, options));
  }
  const std::size_t n = boxes.n;
  if (n == 0) return;
  boxes.check();
  const gyro::ConvexBoxPairs view = boxes.view();
  try {  // the batches make their lane state on a thread's first call
    switch (query) {  // invalid pairs too (the batches answer them; their answers are dropped)
      case Query::intersect: gyro::convex_intersect_batch(view, n, boxes.result, options); break;
      case Query::distance: gyro::convex_distance_batch(view, n, boxes.result, options); break;
      default: gyro::convex_penetration_batch(view, n, boxes.result, options); break;
    }
  } catch (const std::bad_alloc&) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = boxes.index[k];
      gyro::ConvexShape sa, sb;
      gyro::ConvexPose qa, qb;
      const char* which = nullptr;
      if (!pair_of(a[i], pa[i], b[i], pb[i], sa, qa, sb, qb, &which))
        boxes.result[k] = query_pair(query, sa, qa, sb, qb, options);
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    out[boxes.index[k]] = boxes.valid[k] ? c_answer(boxes.result[k]) : invalid_result();
}

gyro_status run_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa, const gyro_convex_shape* b,
                      const gyro_convex_pose* pb, int32_t count, gyro_convex_result* out, Query query) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_count(count, "count"));
    if (count == 0) return Status::ok;
    GYRO_TRY(require(a, "a"));
    GYRO_TRY(require(pa, "pa"));
    GYRO_TRY(require(b, "b"));
    GYRO_TRY(require(pb, "pb"));
    GYRO_TRY(require(out, "out"));
    gyro::detail::parallel_for(std::size_t(count), kPairChunk, [&](std::size_t begin, std::size_t end) {
      run_chunk(a, pa, b, pb, begin, end, out, query);
    });
    // The first invalid pair's reason, on the calling thread (in index order: deterministic).
    for (int32_t i = 0; i < count; ++i) {
      if (out[i].status != GYRO_CONVEX_INVALID_INPUT) continue;
      gyro::ConvexShape sa, sb;
      gyro::ConvexPose qa, qb;
      const char* which = nullptr;
      const char* why = pair_of(a[i], pa[i], b[i], pb[i], sa, qa, sb, qb, &which);
      if (why)
        fail(Status::invalid_argument, "pair %d is GYRO_CONVEX_INVALID_INPUT: %s[%d]: %s", i, which, i, why);
      else
        fail(Status::non_finite, "pair %d is GYRO_CONVEX_INVALID_INPUT: the query overflowed (values too large)", i);
      break;
    }
    return Status::ok;
  });
}

gyro_vec3 row_of(const gyro::mat3& m, int r) { return {m.m[r][0], m.m[r][1], m.m[r][2]}; }

}  // namespace

extern "C" {

GYRO_API gyro_status gyro_convex_hull_create(const gyro_vec3* points, int32_t count, gyro_convex_hull** out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    GYRO_TRY(check_count(count, "count"));
    auto h = std::make_unique<gyro_convex_hull>();
    GYRO_TRY(gyro::build_convex_hull(reinterpret_cast<const gyro::vec3*>(points), std::size_t(count), h->hull));
    *out = h.release();
    return Status::ok;
  });
}

GYRO_API void gyro_convex_hull_destroy(gyro_convex_hull* hull) { delete hull; }

GYRO_API gyro_status gyro_convex_hull_get_info(const gyro_convex_hull* hull, gyro_convex_hull_info* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_hull(hull));
    GYRO_TRY(require(out, "out"));
    const gyro::ConvexHull& h = hull->hull;
    GYRO_TRY(fits_int32(h.vertices.size(), "vertex count"));
    GYRO_TRY(fits_int32(h.face_count(), "face count"));
    GYRO_TRY(fits_int32(h.edge_count(), "edge count"));
    GYRO_TRY(fits_int32(h.face_vertices.size(), "face vertex count"));
    gyro_convex_hull_info info;
    info.vertex_count = int32_t(h.vertices.size());
    info.face_count = int32_t(h.face_count());
    info.edge_count = int32_t(h.edge_count());
    info.face_vertex_count = int32_t(h.face_vertices.size());
    *out = info;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_convex_hull_get_vertices(const gyro_convex_hull* hull, gyro_vec3* out, int32_t capacity,
                                                   int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_copy_args(hull, out, capacity, count));
    const auto& v = hull->hull.vertices;
    return copy_out(out, capacity, count, v.size(), "vertex count", [&](std::size_t i) { return c_v3(v[i]); });
  });
}

GYRO_API gyro_status gyro_convex_hull_get_planes(const gyro_convex_hull* hull, gyro_convex_plane* out,
                                                 int32_t capacity, int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_copy_args(hull, out, capacity, count));
    const auto& p = hull->hull.planes;
    return copy_out(out, capacity, count, p.size(), "face count", [&](std::size_t i) {
      return gyro_convex_plane{c_v3(p[i].normal), p[i].distance};
    });
  });
}

GYRO_API gyro_status gyro_convex_hull_get_face_starts(const gyro_convex_hull* hull, uint32_t* out, int32_t capacity,
                                                      int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_copy_args(hull, out, capacity, count));
    const auto& s = hull->hull.face_start;
    return copy_out(out, capacity, count, s.size(), "face start count", [&](std::size_t i) { return s[i]; });
  });
}

GYRO_API gyro_status gyro_convex_hull_get_face_vertices(const gyro_convex_hull* hull, uint32_t* out, int32_t capacity,
                                                        int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_copy_args(hull, out, capacity, count));
    const auto& f = hull->hull.face_vertices;
    return copy_out(out, capacity, count, f.size(), "face vertex count", [&](std::size_t i) { return f[i]; });
  });
}

GYRO_API gyro_status gyro_convex_hull_get_edges(const gyro_convex_hull* hull, gyro_convex_edge* out,
                                                int32_t capacity, int32_t* count) {
  return guarded([&]() -> Status {
    GYRO_TRY(check_copy_args(hull, out, capacity, count));
    const auto& e = hull->hull.edges;
    return copy_out(out, capacity, count, e.size() / 2, "edge count", [&](std::size_t i) {
      return gyro_convex_edge{e[2 * i], e[2 * i + 1]};
    });
  });
}

GYRO_API gyro_status gyro_convex_hull_mass(const gyro_convex_hull* hull, gyro_convex_mass* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require_hull(hull));
    GYRO_TRY(require(out, "out"));
    gyro::ConvexMass m;
    GYRO_TRY(gyro::convex_hull_mass(hull->hull, m));
    gyro_convex_mass c;
    std::memset(&c, 0, sizeof c);
    c.volume = m.volume;
    c.centroid = c_v3(m.centroid);
    c.principal_moments = c_v3(m.principal_moments);
    for (int r = 0; r < 3; ++r) c.inertia[r] = row_of(m.inertia, r), c.principal_axes[r] = row_of(m.principal_axes, r);
    *out = c;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_convex_pose_from_quat(gyro_vec3 position, gyro_quat orientation, gyro_convex_pose* out) {
  return guarded([&]() -> Status {
    GYRO_TRY(require(out, "out"));
    GYRO_TRY(check_finite(position, "position"));
    const gyro_quat& q = orientation;
    if (!is_finite(q.x) || !is_finite(q.y) || !is_finite(q.z) || !is_finite(q.w))
      return fail(Status::non_finite, "orientation has a NaN or infinite component");
    if (q.x == 0.0f && q.y == 0.0f && q.z == 0.0f && q.w == 0.0f)
      return fail(Status::invalid_argument, "orientation is the zero quaternion");
    const gyro::mat3 m = gyro::to_mat3(gyro::normalized(gyro::quat{q.x, q.y, q.z, q.w}));
    gyro_convex_pose p;
    p.position = position;
    for (int r = 0; r < 3; ++r) p.rotation[r] = row_of(m, r);
    *out = p;
    return Status::ok;
  });
}

GYRO_API gyro_status gyro_convex_intersect_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                 const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                 int32_t count, gyro_convex_result* out) {
  return run_pairs(a, pa, b, pb, count, out, Query::intersect);
}

GYRO_API gyro_status gyro_convex_distance_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                int32_t count, gyro_convex_result* out) {
  return run_pairs(a, pa, b, pb, count, out, Query::distance);
}

GYRO_API gyro_status gyro_convex_penetration_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                                   const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                                   int32_t count, gyro_convex_result* out) {
  return run_pairs(a, pa, b, pb, count, out, Query::penetration);
}

GYRO_API gyro_status gyro_convex_contact_pairs(const gyro_convex_shape* a, const gyro_convex_pose* pa,
                                               const gyro_convex_shape* b, const gyro_convex_pose* pb,
                                               int32_t count, gyro_convex_result* out) {
  return run_pairs(a, pa, b, pb, count, out, Query::contact);
}

}  // extern "C"
