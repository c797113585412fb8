// View frustums and culling (Cookbook chapter 13): the six planes of a view-projection
// matrix, point / sphere / box tests against them, and batch culling over SoA arrays.
//
// Conventions:
//  - A Frustum is six planes in the order left, right, bottom, top, near, far (the
//    frustum_plane indices). Each normal is unit length and points INTO the frustum: a
//    point p is inside when dot(normal, p) - distance >= 0 for all six planes.
//  - Planes are extracted from the view-projection matrix by Gribb and Hartmann's method
//    for gyro's clip space (row vectors, x and y in [-w, w], depth z in [0, w]), in double
//    precision, and rounded to float once: they are the frustum of the float matrices to
//    within a rounding of each plane coefficient. A degenerate matrix (a plane with a zero
//    or non-finite normal) gives that plane a zero normal and distance, which culls nothing.
//  - The tests are the Cookbook's plane tests: a shape is culled only when it lies
//    entirely on the outer side of one plane (centre distance + projected radius < 0). So
//    a shape that overlaps the frustum is NEVER culled; a shape near a frustum edge or
//    corner, outside every plane's far side but inside each plane on its own, is kept
//    (a false positive, harmless for culling).
//  - Rounding: a shape is culled only when it is outside a plane by more than
//    kFrustumRelTolerance * (|plane distance| + largest |centre coordinate| + projected
//    radius) + kFrustumAbsTolerance. That covers the rounding of the planes and of the
//    test itself, so a shape touching the frustum, or overlapping it by a hair, is kept
//    (tests/spatial/frustum_test.cpp checks 10^5 random shapes of each type against binary64). Inside
//    (classify) likewise means inside every plane by more than that tolerance, so it is
//    certain too.
//  - Point tests are closed, with the same tolerance: a point on a plane is contained.
//  - NaN in a shape never culls it (every comparison with NaN is false).
//  - The scalar functions are the float instantiation of the lane templates the batch
//    kernels run (src/spatial/frustum_lanes.hpp): frustum_cull gives their answers bit for
//    bit at every SIMD level and thread count.
#pragma once

#include "gyro/camera.hpp"
#include "gyro/math_mat.hpp"
#include "gyro/math_vec.hpp"
#include "gyro/shape_arrays.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>

namespace gyro {

/// Six planes with unit normals pointing into the frustum, indexed by frustum_plane.
struct Frustum {
  Plane planes[6];  ///< left, right, bottom, top, near, far
};

/// Indices of Frustum::planes.
namespace frustum_plane {
inline constexpr int left = 0;    ///< clip x >= -w
inline constexpr int right = 1;   ///< clip x <= w
inline constexpr int bottom = 2;  ///< clip y >= -w
inline constexpr int top = 3;     ///< clip y <= w
inline constexpr int near = 4;    ///< clip z >= 0
inline constexpr int far = 5;     ///< clip z <= w
}  // namespace frustum_plane

/// Relative tolerance of the culling tests: about 67 ulps of the magnitudes involved,
/// several times the rounding the planes and a test can carry. Mirrored in
/// src/spatial/frustum_lanes.hpp.
inline constexpr float kFrustumRelTolerance = 4e-6f;
/// Absolute floor of the tolerance, for shapes at the origin whose products are subnormal.
inline constexpr float kFrustumAbsTolerance = 1e-30f;

/// Where a shape lies with respect to a frustum.
enum class Containment : uint32_t {
  outside = 0,       ///< entirely outside one plane (culled)
  intersecting = 1,  ///< neither: it crosses a plane, or lies near an edge or corner outside
  inside = 2,        ///< inside every plane by more than the tolerance
};

/// The frustum of a view-projection matrix (world to clip space, e.g. view * projection).
Frustum frustum(const mat4& view_projection);
/// The frustum of view * projection, the product taken in double precision.
Frustum frustum(const mat4& view, const mat4& projection);
/// The camera's frustum: frustum(view_matrix(camera), projection_matrix(camera)).
Frustum frustum(const Camera& camera);

/// The eight corners, where three planes meet, computed in double precision. Corner k
/// lies on the right plane if bit 0 of k is set (else left), on top if bit 1 (else bottom)
/// and on far if bit 2 (else near). Three planes that do not meet in a point give NaN.
void frustum_corners(const Frustum& frustum, vec3 corners[8]);

/// The point is inside or on the frustum (within the tolerance): intersects() of a sphere
/// of radius 0.
bool contains(const Frustum& frustum, const vec3& point);
/// False only when the sphere lies entirely outside one plane (see the header comment).
bool intersects(const Frustum& frustum, const Sphere& sphere);
/// False only when the box lies entirely outside one plane: its projected radius on the
/// normal, e . |n|, against the centre's distance.
bool intersects(const Frustum& frustum, const AABB& box);
/// False only when the box lies entirely outside one plane: its projected radius
/// sum e_i |u_i . n| against the centre's distance.
bool intersects(const Frustum& frustum, const OBB& box);

/// outside exactly when !intersects; inside when inside every plane by more than the tolerance.
Containment classify(const Frustum& frustum, const Sphere& sphere);
/// outside exactly when !intersects; inside when inside every plane by more than the tolerance.
Containment classify(const Frustum& frustum, const AABB& box);
/// outside exactly when !intersects; inside when inside every plane by more than the tolerance.
Containment classify(const Frustum& frustum, const OBB& box);

/// Batch culling: visible_out[i] = 1 if sphere i intersects the frustum (intersecting or
/// inside), 0 if culled; bit for bit intersects(). Checks everything first and then writes
/// nothing on failure: count >= 2^31 (invalid_count), null pointers (null_argument; with
/// count 0 nothing is read or written), NaN or infinite plane or sphere values
/// (non_finite), a negative radius or a frustum normal that is not unit length to within
/// 1e-3 (invalid_argument; so is the zero normal that frustum() gives a degenerate matrix).
Status frustum_cull(const Frustum& frustum, const SpheresView& spheres, std::size_t count, uint32_t* visible_out);
/// Batch culling of axis-aligned boxes; as the sphere version (negative half extents are
/// invalid_argument).
Status frustum_cull(const Frustum& frustum, const AabbsView& boxes, std::size_t count, uint32_t* visible_out);
/// Batch culling of oriented boxes; as the sphere version. The axes are used as given
/// (unit length is the caller's promise, as for every OBB in gyro).
Status frustum_cull(const Frustum& frustum, const ObbsView& boxes, std::size_t count, uint32_t* visible_out);

}  // namespace gyro
