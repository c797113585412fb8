// Narrowphase: contact manifolds between pairs of shapes (Cookbook chapter 15, with the
// separating-axis test plus clipping for boxes that Box2D and Bullet use).
//
// Every function follows manifold.hpp's conventions: normal from a to b, points midway
// between the surfaces, separation < 0 when penetrating, points kept while
// separation < margin (margin >= 0), at most 4 points with stable feature ids, count 0 when
// farther apart than margin. Triangles are double-sided; a plane is the boundary of the
// solid half-space behind its normal (a ground), so a shape below it is pushed out along
// +normal. Inputs are finite, sizes >= 0 and rotations orthonormal (the world checks them);
// the outputs are then finite, for zero sizes and degenerate triangles too.
//
// A point's separation is its own gap along the normal (face contacts: each clipped point's
// height above the reference face), or for an edge-edge point the gap along the axis (for a
// gap, a lower bound of the edges' distance). Every reported point has separation < margin.
//
// Feature ids (what the solver matches frame to frame; only equality matters):
//  - sphere-sphere, sphere-box, sphere-plane: 0 (one point, always the same one);
//  - sphere-triangle: the closest feature, 0 face, 1 + j edge j (ab, bc, ca), 4 + k vertex k;
//  - box-plane: the corner index, bit k set for the corner on the negative side of axis k;
//  - a face contact: kFeatureRefB if the reference face is b's, | ref face << 9 |
//    incident face << 6 | the two polygon edges the point lies on (in << 3 | out), where a
//    box face is 2 axis + (1 on the negative side), a triangle's face is 7, an edge code
//    below 4 is an edge of the incident face and 4 + j the reference face's side j;
//  - an edge-edge contact: kFeatureEdge | edge of a << 4 | edge of b, a box edge being
//    4 axis + (bit 0: negative on the next axis, bit 1: negative on the one after) and a
//    triangle edge its index j.
#pragma once

#include "dynamics/manifold.hpp"
#include "gyro/convex.hpp"
#include "gyro/shapes.hpp"

namespace gyro::detail {

void collide_spheres(const Sphere& a, const Sphere& b, float margin, Manifold* out);
/// The centre inside the box gives the normal of the face it is nearest to.
void collide_sphere_box(const Sphere& a, const OBB& b, float margin, Manifold* out);
/// Separating axis over the 15 axes, then the incident face clipped against the reference
/// face's side planes (up to 4 points, the deepest and widest kept); edge-edge gives one point.
/// Face axes are preferred: b's face replaces a's, and an edge axis a face, only when it
/// separates clearly more (see collide_box.cpp), so a resting pair keeps its manifold.
void collide_boxes(const OBB& a, const OBB& b, float margin, Manifold* out);
void collide_sphere_plane(const Sphere& a, const Plane& b, float margin, Manifold* out);
/// Up to 4 of the corners within margin of the plane, the deepest.
void collide_box_plane(const OBB& a, const Plane& b, float margin, Manifold* out);
void collide_sphere_triangle(const Sphere& a, const Triangle& b, float margin, Manifold* out);
/// Separating axis over 13 axes (3 box faces, the triangle's normal, 9 edge pairs), then
/// clipping as for two boxes with the triangle's face (preferred) or a box face as reference.
void collide_box_triangle(const OBB& a, const Triangle& b, float margin, Manifold* out);

/// A shape for the generic path (collide_convex.cpp): sphere, capsule, box, triangle, or a
/// hull (shape.type points with `hull` set: its faces are used for clipping).
struct ConvexCollider {
  ConvexShape shape;
  ConvexPose pose;
  const ConvexHull* hull = nullptr;
};
/// Any pair of convex shapes: GJK/EPA for the normal and depth, then the incident feature
/// (face, capsule segment or point) clipped against the reference face (within ~3 degrees of
/// the normal, a's preferred) or, for parallel capsules, a's segment; else EPA's one point.
/// Up to 4 points (the deepest, then the widest). Feature ids: a's feature << 22 | b's << 12
/// | reference on b << 11 | single point << 10 | clip code.
void collide_convex_shapes(const ConvexCollider& a, const ConvexCollider& b, float margin, Manifold* out);
/// The appendix's arbiter approach, for comparison with clipping: one GJK/EPA point per
/// frame, merged into the points kept from earlier frames (stored as anchors on both bodies,
/// re-measured along the new normal, dropped once they separate beyond the margin or slide
/// apart by 2 cm); a new point within 2 cm of a kept one replaces it and keeps its id; beyond
/// 4 points the new one and the three old ones spanning the most area stay. Ids count up.
void collide_convex_incremental(const ConvexCollider& a, const ConvexCollider& b, float margin, const Manifold* old,
                                const ContactAnchors* old_anchors, Manifold* out, ContactAnchors* anchors);
/// A capsule, hull (or any convex shape) against a ground plane: its vertices (capsule: the
/// segment's ends) within the margin, reduced to 4; feature id = vertex index.
void collide_convex_plane(const ConvexCollider& a, const Plane& b, float margin, Manifold* out);

inline constexpr uint32_t kFeatureRefB = 1u << 12;
inline constexpr uint32_t kFeatureEdge = 1u << 14;
inline constexpr uint32_t kTriangleFace = 7;

// Building blocks the box-box and box-triangle manifolds share (defined in collide_box.cpp).

/// Axis choice: a candidate axis replaces the current one only when its separation exceeds
/// the current's by rel * |current| + abs * size (size: the smaller shape's largest half
/// extent), so that rounding noise and near-ties cannot flip a resting manifold. Faces use
/// Box2D's and Gregorius's 2%; edges the 5% of ODE's and Bullet's box-box.
inline constexpr float kFaceRelTol = 0.02f, kFaceAbsTol = 5e-4f;
inline constexpr float kEdgeRelTol = 0.05f, kEdgeAbsTol = 1e-3f;
/// Edge pairs within about 0.06 degrees of parallel (|u x v|^2 below this times |u|^2 |v|^2)
/// have no usable cross axis: its direction would be mostly rounding; the face axes cover them.
inline constexpr float kParallelSq = 1e-6f;

inline bool clearly_larger(float s, float current, float rel, float abs_tol) {
  return s > current + rel * (current < 0.0f ? -current : current) + abs_tol;
}

/// A box's axes (the rows of its orientation) and half extents, as arrays.
struct BoxAxes {
  vec3 u[3];
  float e[3];
};
inline BoxAxes box_axes(const OBB& b) {
  BoxAxes f;
  for (int k = 0; k < 3; ++k) {
    f.u[k] = {b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]};
    f.e[k] = b.half_extents[k];
  }
  return f;
}
/// The box edge parallel to axis k that supports the box in direction dir: writes its
/// centre relative to the box centre and returns its edge code (see the feature ids).
uint32_t box_support_edge(const BoxAxes& box, int k, const vec3& dir, vec3* center);

/// The reference face: points are origin + x t1 + y t2 + z normal (t1, t2, normal
/// orthonormal, normal the face's outward normal) and the face lies in the plane z = height.
struct FaceFrame {
  vec3 origin, t1, t2, normal;
  float height = 0.0f;
};
/// A vertex of the incident polygon in the face frame, with the codes of the polygon edges
/// that end and start at it (see the feature ids above).
struct ClipVertex {
  float x, y, z;
  uint8_t in, out;
};
/// A side plane of the reference face: keeps the points with nx x + ny y <= d (nx, ny unit).
struct ClipSide {
  float nx, ny, d;
};
/// The frame of the box face with outward normal sign * u[axis] and its four side planes
/// (codes 4 + j: +t1, -t1, +t2, -t2).
FaceFrame box_face_frame(const vec3& center, const BoxAxes& axes, int axis, float sign, ClipSide* sides);
/// The face of a box most opposed to frame.normal (the first of nearly equal ones), as a
/// polygon in the frame with edge codes 0-3, the box centre being `center` relative to
/// frame.origin. Returns the face's index (2 axis + 1 on the negative side).
uint32_t box_incident_face(const BoxAxes& box, const vec3& center, const FaceFrame& frame, ClipVertex* poly);
/// Clips the convex polygon poly[0..count) (count <= 4) against the sides (side_count <= 4),
/// keeps the points with separation z - height < margin, reduces them to at most 4 (the
/// deepest first, then the ones spanning the largest area) and writes them to out with
/// feature_id = id_base | in << 3 | out. Sets out->count; the caller sets out->normal.
void clip_face_contact(const FaceFrame& frame, const ClipVertex* poly, int count, const ClipSide* sides, int side_count,
                       float margin, uint32_t id_base, Manifold* out);
/// One point midway between the closest points of the segments pa +- ha and pb +- hb (given
/// relative to origin), with the given separation and feature id; sets out->count = 1.
void edge_contact(const vec3& origin, const vec3& pa, const vec3& ha, const vec3& pb, const vec3& hb, float separation,
                  uint32_t feature_id, Manifold* out);

}  // namespace gyro::detail
