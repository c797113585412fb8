// gyro::overlap_pairwise / overlap_one_against_many / obb_separation_pairwise: check the
// input, order the pair types canonically, run the overlap kernel over fixed chunks.
#include "gyro/batch_overlap.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/overlap_batch.hpp"

#include <utility>

namespace gyro {
namespace {

using detail::fail;

constexpr std::size_t kMaxCount = 0x7FFFFFFF;
constexpr std::size_t kPairChunk = 4096;  // a multiple of every lane width

struct Column {
  const float* p;
  const char* name;
  bool non_negative;
};

// The component arrays of a shape array, in a fixed order; returns how many.
int columns_of(const ShapeArray& s, Column out[15]) {
  int n = 0;
  auto add = [&](const float* p, const char* name, bool nonneg = false) { out[n++] = {p, name, nonneg}; };
  switch (s.type) {
    case ShapeType::sphere:
      add(s.spheres.cx, "cx"), add(s.spheres.cy, "cy"), add(s.spheres.cz, "cz"), add(s.spheres.r, "r", true);
      break;
    case ShapeType::aabb:
      add(s.aabbs.cx, "cx"), add(s.aabbs.cy, "cy"), add(s.aabbs.cz, "cz");
      add(s.aabbs.ex, "ex", true), add(s.aabbs.ey, "ey", true), add(s.aabbs.ez, "ez", true);
      break;
    case ShapeType::obb:
      add(s.obbs.cx, "cx"), add(s.obbs.cy, "cy"), add(s.obbs.cz, "cz");
      add(s.obbs.ex, "ex", true), add(s.obbs.ey, "ey", true), add(s.obbs.ez, "ez", true);
      add(s.obbs.u0x, "u0x"), add(s.obbs.u0y, "u0y"), add(s.obbs.u0z, "u0z");
      add(s.obbs.u1x, "u1x"), add(s.obbs.u1y, "u1y"), add(s.obbs.u1z, "u1z");
      add(s.obbs.u2x, "u2x"), add(s.obbs.u2y, "u2y"), add(s.obbs.u2z, "u2z");
      break;
    case ShapeType::plane:
      add(s.planes.nx, "nx"), add(s.planes.ny, "ny"), add(s.planes.nz, "nz"), add(s.planes.d, "d");
      break;
    case ShapeType::triangle:
      add(s.triangles.ax, "ax"), add(s.triangles.ay, "ay"), add(s.triangles.az, "az");
      add(s.triangles.bx, "bx"), add(s.triangles.by, "by"), add(s.triangles.bz, "bz");
      add(s.triangles.cx, "cx"), add(s.triangles.cy, "cy"), add(s.triangles.cz, "cz");
      break;
  }
  return n;
}

bool known_type(ShapeType t) { return static_cast<uint32_t>(t) >= 1 && static_cast<uint32_t>(t) <= 5; }

// Strict: every element finite and sizes non-negative. Lenient: only pointers.
Status check_array(const ShapeArray& s, std::size_t n, const char* which, bool strict) {
  if (!known_type(s.type)) return fail(Status::invalid_argument, "%s.type = %u is not a shape type", which, unsigned(s.type));
  Column cols[15];
  const int nc = columns_of(s, cols);
  for (int c = 0; c < nc; ++c)
    if (!cols[c].p) return fail(Status::null_argument, "%s.%s is null", which, cols[c].name);
  if (!strict) return Status::ok;
  for (int c = 0; c < nc; ++c) {
    const std::size_t bad = detail::first_non_finite(cols[c].p, n);
    if (bad < n) return fail(Status::non_finite, "%s.%s[%zu] is not finite", which, cols[c].name, bad);
    if (cols[c].non_negative)
      for (std::size_t i = 0; i < n; ++i)
        if (cols[c].p[i] < 0.0f)
          return fail(Status::invalid_argument, "%s.%s[%zu] = %g is negative", which, cols[c].name, i, double(cols[c].p[i]));
  }
  return Status::ok;
}

Status run(const ShapeArray& a_in, bool a_single, const ShapeArray& b_in, bool b_single, std::size_t count, uint32_t* out,
           float* separation, uint32_t flags) {
  if (count > kMaxCount) return fail(Status::invalid_count, "count %zu must be below 2^31", count);
  if (flags & ~kFlagStrict) return fail(Status::invalid_argument, "unknown flags 0x%x", flags);
  if (count == 0) return Status::ok;
  if (!out && !separation) return fail(Status::null_argument, "out is null");
  const bool strict = (flags & kFlagStrict) != 0;
  GYRO_TRY(check_array(a_in, a_single ? 1 : count, "a", strict));
  GYRO_TRY(check_array(b_in, b_single ? 1 : count, "b", strict));

  OverlapArgs args{a_in, b_in, a_single, b_single, out, separation};
  if (args.a.type > args.b.type) {  // every test is symmetric: run it in canonical order
    std::swap(args.a, args.b);
    std::swap(args.a_single, args.b_single);
  }
  if (!overlap_pair_supported(args.a.type, args.b.type))
    return fail(Status::unsupported, "overlap of shape types %u and %u is not available in this build",
                unsigned(args.a.type), unsigned(args.b.type));
  detail::FloatEnvGuard env;
  auto* kernel = GYRO_DISPATCH(overlap_batch);
  detail::parallel_for(count, kPairChunk, [&](std::size_t b, std::size_t e) { kernel(args, b, e); });
  return Status::ok;
}

}  // namespace

Status overlap_pairwise(const ShapeArray& a, const ShapeArray& b, std::size_t count, uint32_t* out, uint32_t flags) {
  return run(a, false, b, false, count, out, nullptr, flags);
}

Status overlap_one_against_many(const ShapeArray& one, const ShapeArray& many, std::size_t count, uint32_t* out,
                                uint32_t flags) {
  return run(one, true, many, false, count, out, nullptr, flags);
}

Status obb_separation_pairwise(const ObbsView& a, const ObbsView& b, std::size_t count, float* out) {
  if (count && !out) return fail(Status::null_argument, "out is null");
  return run(shape_array(a), false, shape_array(b), false, count, nullptr, out, kFlagStrict);
}

}  // namespace gyro
