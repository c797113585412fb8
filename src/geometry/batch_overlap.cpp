// gyro::overlap_pairwise / overlap_one_against_many / obb_separation_pairwise: check the
// input, order the pair types canonically, run the overlap kernel over fixed chunks.
#include "gyro/batch_overlap.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/overlap_batch.hpp"
#include "geometry/shape_checks.hpp"

#include <utility>

namespace gyro {
namespace {

using detail::fail;

constexpr std::size_t kMaxCount = 0x7FFFFFFF;
constexpr std::size_t kPairChunk = 4096;  // a multiple of every lane width

Status run(const ShapeArray& a_in, bool a_single, const ShapeArray& b_in, bool b_single, std::size_t count, uint32_t* out,
           float* separation, uint32_t flags) {
  if (count > kMaxCount) return fail(Status::invalid_count, "count %zu must be below 2^31", count);
  if (flags & ~kFlagStrict) return fail(Status::invalid_argument, "unknown flags 0x%x", flags);
  if (count == 0) return Status::ok;
  if (!out && !separation) return fail(Status::null_argument, "out is null");
  const bool strict = (flags & kFlagStrict) != 0;
  GYRO_TRY(detail::check_shape_array(a_in, a_single ? 1 : count, "a", strict));
  GYRO_TRY(detail::check_shape_array(b_in, b_single ? 1 : count, "b", strict));

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
