// Convex shapes, their support functions, GJK (intersection and distance with witness
// points), EPA (penetration depth, normal and contact points) and convex hulls (quickhull).
//
// Conventions:
//  - A ConvexShape is described in its local frame; a ConvexPose places it in the world with
//    the OBB convention of gyro/shapes.hpp: world = local * rotation + position, the rows of
//    rotation being the shape's local x, y, z axes (a proper rotation, rows unit length).
//  - Capsules and cylinders run along their local y axis, from -half_height to +half_height.
//  - Spheres and capsules are a core (a point, a segment) plus a radius: GJK runs on the
//    cores, so sphere and capsule distances are exact to float rounding, and EPA is only
//    needed when the cores themselves overlap.
//  - Every query works in A's frame (B is brought there with one relative transform), so
//    two shapes far from the origin (1e4) lose no more precision than their offset costs.
//  - normal points from A towards B: moving B by depth * normal separates an intersecting
//    pair; for a separated pair B moves closer along -normal by distance.
//  - Nothing ever returns NaN: a non-finite input gives ConvexStatus::invalid_input, zero
//    outputs and a message in gyro::last_error().
//  - Determinism: only + - * / sqrt and comparisons in a fixed order, fixed-capacity
//    buffers, ties broken by lowest index. Bit-identical across runs, compilers, CPUs.
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_vec.hpp"
#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro {

enum class ConvexType : uint32_t {
  sphere = 0,    ///< radius around the origin
  box = 1,       ///< half_extents around the origin
  capsule = 2,   ///< segment (0, +-half_height, 0) plus radius
  cylinder = 3,  ///< axis (0, +-half_height, 0), radius
  triangle = 4,  ///< corners v[0], v[1], v[2] (a flat shape: it has no inside)
  points = 5,    ///< the convex hull of points[0 .. count): a ConvexHull's vertices or any cloud
};

/// A convex shape in its local frame. Plain data; `points` is not owned (a ConvexHull or
/// the caller's array must outlive the shape). Build with the make_* functions below.
struct ConvexShape {
  ConvexType type = ConvexType::sphere;
  float radius = 0.0f;       ///< sphere, capsule, cylinder
  float half_height = 0.0f;  ///< capsule, cylinder
  vec3 half_extents;         ///< box
  vec3 v[3];                 ///< triangle
  const vec3* points = nullptr;  ///< points: vertex array
  uint32_t count = 0;            ///< points: number of vertices (>= 1)
};

/// Where a shape is: world = local * rotation + position (rows of rotation = local axes).
struct ConvexPose {
  vec3 position;
  mat3 rotation;
};

/// Shape builders: each checks its arguments (finite, sizes >= 0, points non-null and
/// count >= 1) and returns the status, leaving `out` unchanged on failure.
Status make_sphere(float radius, ConvexShape& out);
Status make_box(const vec3& half_extents, ConvexShape& out);
Status make_capsule(float radius, float half_height, ConvexShape& out);
Status make_cylinder(float radius, float half_height, ConvexShape& out);
Status make_triangle(const vec3& a, const vec3& b, const vec3& c, ConvexShape& out);
Status make_convex_points(const vec3* points, std::size_t count, ConvexShape& out);

/// The point of the shape (local frame) furthest along dir (any length; a zero dir gives a
/// point of the shape). Ties go to the lowest vertex index, so the answer is deterministic.
vec3 support(const ConvexShape& shape, const vec3& dir);
/// The same in the world: dir and result in world coordinates.
vec3 support(const ConvexShape& shape, const ConvexPose& pose, const vec3& dir);
/// The support of the Minkowski difference A - B: support(A, d) - support(B, -d).
vec3 support_difference(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b, const ConvexPose& pb,
                        const vec3& dir);

/// How a query ended. iteration_limit is never a verdict of separation: the caller decides.
enum class ConvexStatus : uint32_t {
  separated = 0,        ///< distance > touching tolerance
  touching = 1,         ///< |signed distance| <= touching tolerance (counts as overlapping)
  intersecting = 2,     ///< the shapes overlap by more than the tolerance
  iteration_limit = 3,  ///< no convergence; the fields hold the best estimate so far
  invalid_input = 4,    ///< non-finite shape or pose; every field is zero
};

/// True for touching and intersecting.
constexpr bool overlapping(ConvexStatus s) { return s == ConvexStatus::touching || s == ConvexStatus::intersecting; }

/// Result of a query, in world coordinates.
struct ConvexResult {
  ConvexStatus status = ConvexStatus::separated;
  /// Signed distance: > 0 the gap, <= 0 minus the penetration depth (convex_intersect and
  /// convex_distance give 0 for intersecting pairs; convex_penetration gives -depth).
  float distance = 0.0f;
  vec3 normal;   ///< unit, from A towards B; zero when undefined (e.g. coincident cores)
  vec3 point_a;  ///< witness point on A (closest point, or deepest point of A inside B)
  vec3 point_b;  ///< witness point on B; point_b - point_a = distance * normal
  uint32_t iterations = 0;  ///< GJK plus EPA iterations
};

/// Query options. Tolerances are relative to the pair's size (the largest support vertex
/// distance from A's origin, at least 1e-30), so they hold for tiny and huge shapes alike.
struct ConvexQueryOptions {
  float touch_tolerance = 1e-6f;  ///< |distance| <= this * size is "touching"
  uint32_t max_gjk_iterations = 64;
  uint32_t max_epa_iterations = 64;
  /// convex_penetration only. true: a separated pair gets its exact distance and closest
  /// points (GJK runs to convergence). false: a separated pair stops at the first separating
  /// axis, as convex_intersect does (status separated; distance, normal and witnesses are
  /// those at the exit: the distance is an upper bound). Overlapping pairs get the same bits
  /// either way (no separating axis exists, so GJK's path to the enclosing simplex is the
  /// same); false is for contact generation, which has no use for a gap's size.
  bool separated_distance = true;
};

/// Boolean overlap by GJK: stops at the first separating axis or enclosing simplex. distance,
/// normal and witnesses are those at the exit (exact only when converged). Two boxes first
/// try their six face normals: a pair separated along one (beyond the touching tolerance)
/// stops there with iterations 0, reporting the support point of A - B along that normal
/// (point_a and point_b its vertices or face points on A and B; distance its length, an upper
/// bound of the gap). On random boxes that decides 95-98% of separated pairs, which GJK's
/// first iteration decided 40-65% of. penetration with separated_distance = false does the same.
ConvexResult convex_intersect(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b,
                              const ConvexPose& pb, const ConvexQueryOptions& options = {});
/// Distance and closest points by GJK. Intersecting pairs report distance 0 (no EPA).
ConvexResult convex_distance(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b,
                             const ConvexPose& pb, const ConvexQueryOptions& options = {});
/// Distance when separated; penetration depth, normal and contact points by EPA when not.
ConvexResult convex_penetration(const ConvexShape& a, const ConvexPose& pa, const ConvexShape& b,
                                const ConvexPose& pb, const ConvexQueryOptions& options = {});

/// Many box pairs at once, in structure-of-arrays form: pair i is box A with centre
/// (a_center[0][i], a_center[1][i], a_center[2][i]), half extents a_half[0..2][i] and
/// rotation a_rot[3 * k + c][i] = ConvexPose::rotation.m[k][c] (row k = local axis k), and
/// box B likewise.
struct ConvexBoxPairs {
  const float* a_center[3];
  const float* a_half[3];
  const float* a_rot[9];
  const float* b_center[3];
  const float* b_half[3];
  const float* b_rot[9];
};

/// convex_intersect(box A_i, box B_i).status for i in [0, count), written to out[i]: the
/// same verdict, bit for bit, at every SIMD level (GJK runs over SIMD lanes, one pair per
/// lane, with the scalar query's operations; see the box-pair batches below).
/// Invalid pairs get ConvexStatus::invalid_input (and gyro::last_error() the first one's message).
void convex_intersect_batch(const ConvexBoxPairs& pairs, std::size_t count, ConvexStatus* out,
                            const ConvexQueryOptions& options = {});

/// A convex polyhedron from build_convex_hull: welded vertices, planar faces (coplanar
/// triangles merged, collinear boundary vertices removed) and unique edges.
struct ConvexHull {
  std::vector<vec3> vertices;           ///< hull vertices, in the order of their first input index
  std::vector<uint32_t> face_start;     ///< face f has face_vertices[face_start[f] .. face_start[f+1])
  std::vector<uint32_t> face_vertices;  ///< indices into vertices, counter-clockwise seen from outside
  std::vector<Plane> planes;            ///< per face: outward unit normal and distance
  std::vector<uint32_t> edges;          ///< pairs (a, b) with a < b, sorted
  std::size_t face_count() const { return planes.size(); }
  std::size_t edge_count() const { return edges.size() / 2; }
  /// The hull as a support shape (points into this hull's vertices).
  ConvexShape shape() const;
};

/// Quickhull (Barber, Dobkin, Huhdanpaa 1996) in binary64 from the float points. Points
/// closer than the tolerance (about 1e-6 of the cloud's extent) to a hull plane count as
/// on it; so near-duplicates are welded and near-coplanar faces merged. Failures leave
/// `out` empty: null_argument (points null with count > 0), invalid_count (fewer than 4
/// points), non_finite (a NaN or infinite coordinate), invalid_argument (all points
/// coincide, are collinear or coplanar: no volume; such sets are valid ConvexShapes via
/// make_convex_points, just not polyhedra), internal (a consistency check failed).
Status build_convex_hull(const vec3* points, std::size_t count, ConvexHull& out);

/// Mass properties of a solid ConvexHull of density 1, in the hull's own frame.
struct ConvexMass {
  float volume = 0.0f;
  vec3 centroid;  ///< centre of mass
  /// Inertia tensor about the centroid (axes of the hull's frame), for density 1.
  mat3 inertia;
  /// The principal frame: principal_moments are the eigenvalues of `inertia`, ascending,
  /// and the rows of principal_axes the matching unit eigenvectors, a right-handed
  /// rotation (det +1), so inertia = principal_axes^T diag(moments) principal_axes.
  vec3 principal_moments;
  mat3 principal_axes;
};

/// Volume, centroid and inertia by the divergence theorem over the faces' triangles in
/// binary64 (Mirtich 1996 / Eberly's polyhedral mass properties), principal axes by cyclic
/// Jacobi rotations (a fixed order, + - * / sqrt only: deterministic). Failures leave
/// `out` unchanged: invalid_argument (an empty hull or one with volume <= 0).
Status convex_hull_mass(const ConvexHull& hull, ConvexMass& out);

// ---- box-pair batches: GJK over SIMD lanes (issue 8) ----
//
// convex_intersect_batch above and the three calls below run GJK itself over SIMD lanes, one
// box pair per lane through the whole iteration loop (each lane performs the scalar loop's
// operations, so the lanes leave every pair with the scalar query's simplex, bit for bit);
// the results are then formed, and EPA run where needed, with the scalar query's code (for
// 16 pairs side by side, their supports and face planes over lanes too).
// The pairs are cut into fixed chunks (1,024 pairs) that run over gyro's threads
// (set_thread_count); out[i] is bit-identical to the scalar call on pair i at every SIMD
// level and thread count. The batches allocate their lane state once per thread; where that
// fails, the pairs run one at a time (same bits) and nothing is thrown.
// Invalid pairs get ConvexStatus::invalid_input (and gyro::last_error(), on the calling
// thread, the first invalid pair's message).

/// convex_intersect(box A_i, box B_i) for i in [0, count), the whole result (the distance,
/// normal and witnesses at GJK's exit), written to out[i].
void convex_intersect_batch(const ConvexBoxPairs& pairs, std::size_t count, ConvexResult* out,
                            const ConvexQueryOptions& options = {});
/// convex_distance(box A_i, box B_i) for i in [0, count), written to out[i].
void convex_distance_batch(const ConvexBoxPairs& pairs, std::size_t count, ConvexResult* out,
                           const ConvexQueryOptions& options = {});
/// convex_penetration(box A_i, box B_i) for i in [0, count), written to out[i] (with
/// options.separated_distance false, the separated pairs stop early, as there).
void convex_penetration_batch(const ConvexBoxPairs& pairs, std::size_t count, ConvexResult* out,
                              const ConvexQueryOptions& options = {});

// ---- end of the box-pair batches ----

}  // namespace gyro
