// Batch overlap tests over arrays the caller owns (structure of arrays), with no copy:
// pairwise (a[i] against b[i]) or one against many (a[0] against b[i]). Every pair kind of
// spheres, AABBs, OBBs, planes and triangles. Results are bit-identical at every SIMD
// level and thread count, and equal to the scalar overlaps() of gyro/overlap.hpp.
#pragma once

#include "gyro/shape_arrays.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

enum class ShapeType : uint32_t { sphere = 1, aabb = 2, obb = 3, plane = 4, triangle = 5 };

/// One SoA array of one type of shape; only the view matching `type` is read.
struct ShapeArray {
  ShapeType type = ShapeType::sphere;
  SpheresView spheres;
  AabbsView aabbs;
  ObbsView obbs;
  PlanesView planes;
  TrianglesView triangles;
};

inline ShapeArray shape_array(const SpheresView& v) { ShapeArray a; a.type = ShapeType::sphere; a.spheres = v; return a; }
inline ShapeArray shape_array(const AabbsView& v) { ShapeArray a; a.type = ShapeType::aabb; a.aabbs = v; return a; }
inline ShapeArray shape_array(const ObbsView& v) { ShapeArray a; a.type = ShapeType::obb; a.obbs = v; return a; }
inline ShapeArray shape_array(const PlanesView& v) { ShapeArray a; a.type = ShapeType::plane; a.planes = v; return a; }
inline ShapeArray shape_array(const TrianglesView& v) { ShapeArray a; a.type = ShapeType::triangle; a.triangles = v; return a; }

/// Values written per pair.
enum : uint32_t {
  kSeparated = 0,
  kOverlapping = 1,   ///< touching included
  kInvalidInput = 2,  ///< an input of this pair is NaN or infinite, or a size is negative
};

/// Batch call flags.
enum : uint32_t {
  /// By default a pair with a NaN or infinite input or a negative size gets kInvalidInput
  /// and the rest of the batch is computed; the check is fused into the test, so it is
  /// nearly free. With kFlagStrict the whole input is checked first and any such value
  /// fails the call (Status::non_finite or invalid_argument) with nothing written: a
  /// separate pass over the input that costs about as much as the tests themselves.
  kFlagStrict = 1u << 0,
};

/// out[i] = overlap of a[i] and b[i], i < count. Null pointers, unknown flags and counts
/// of 2^31 or more get a status and nothing is written.
Status overlap_pairwise(const ShapeArray& a, const ShapeArray& b, std::size_t count, uint32_t* out,
                        uint32_t flags = 0);

/// out[i] = overlap of one[0] and many[i], i < count.
Status overlap_one_against_many(const ShapeArray& one, const ShapeArray& many, std::size_t count, uint32_t* out,
                                uint32_t flags = 0);

/// OBB pairs: out[i] = signed separation of a[i] and b[i] over the 15 separating axes
/// (> 0: the gap; <= 0: minus the penetration depth, the minimum translation distance).
Status obb_separation_pairwise(const ObbsView& a, const ObbsView& b, std::size_t count, float* out);

}  // namespace gyro
