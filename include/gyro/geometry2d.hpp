// The 2D primitives of Cookbook chapters 4-6 and their tests: point containment, closest
// points, segment tests, pairwise intersection (separating axis theorem), containing
// circle and rectangle, and bounding shapes made of several circles and rectangles.
//
// Conventions:
//  - Point2D is vec2. Line2D is the segment from start to end (the book's Line2D).
//  - Rectangle2D is axis-aligned: origin is its minimum corner and size (>= 0) its extent,
//    so it covers [origin, origin + size] with origin + size rounded to float once, the way
//    every function here computes it. rectangle_from_min_max() rounds the size up so the
//    rectangle covers both corners exactly.
//  - OrientedRectangle: center, half extents (>= 0) and rotation in radians,
//    counter-clockwise (the book uses degrees). Its local x axis is (cos r, sin r) and its
//    local y axis (-sin r, cos r), computed with gyro::sincos, so rotations are
//    deterministic; a float rotation of pi/2 is not exactly a quarter turn (its cosine is
//    -4.4e-8), so such a rectangle is not bit-for-bit an axis-aligned one.
//  - Shapes are solid: a circle contains its interior, and the closest point of a shape to
//    a point inside it is the point itself (the book's circle returns a point on the rim).
//  - Touching counts as overlapping (distance exactly 0, up to float rounding).
//  - Degenerate shapes are valid and get the obvious answer: a circle of radius 0 and a
//    rectangle of size 0 are points, a rectangle with one zero extent is a segment, a
//    segment with start == end is a point.
//  - Invalid input gives a defined answer, never a crash: a NaN or infinite coordinate,
//    or a negative radius, size or half extent, makes a shape or point that contains,
//    overlaps and touches nothing: every test involving it returns false, and closest
//    points involving it are NaN.
//  - Names are the 3D ones (contains, closest_point, linetest, overlaps), overloaded on
//    the 2D types; a pairwise overlaps() is declared for both argument orders and gives
//    the same answer for both (bit-for-bit the same arithmetic).
//  - Determinism: scalar code using only + - * /, sqrt, comparisons and gyro's own
//    sin/cos, each sum in a fixed order; the same inputs give the same bits everywhere.
#pragma once

#include "gyro/math_vec.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace gyro {

/// A 2D point (the book's Point2D).
using Point2D = vec2;

/// A segment from start to end.
struct Line2D {
  vec2 start, end;
};

/// A solid circle.
struct Circle {
  vec2 center;
  float radius = 1.0f;  ///< >= 0
};

/// A solid axis-aligned rectangle covering [origin, origin + size].
struct Rectangle2D {
  vec2 origin;               ///< the minimum corner
  vec2 size{1.0f, 1.0f};     ///< >= 0 per component
};

/// A solid rectangle rotated counter-clockwise by rotation radians about its center.
struct OrientedRectangle {
  vec2 center;
  vec2 half_extents{1.0f, 1.0f};  ///< >= 0 per component, along the local axes
  float rotation = 0.0f;          ///< radians, counter-clockwise
};

/// The union of several circles and rectangles (the book's BoundingShape): a point or a
/// shape is in it or overlaps it when it is in or overlaps any part. An empty
/// BoundingShape contains and overlaps nothing.
struct BoundingShape {
  std::vector<Circle> circles;
  std::vector<Rectangle2D> rectangles;
};

/// The minimum corner of r.
inline vec2 rectangle_min(const Rectangle2D& r) { return r.origin; }
/// The maximum corner of r: origin + size, rounded once (as every test here computes it).
inline vec2 rectangle_max(const Rectangle2D& r) { return r.origin + r.size; }
/// The rectangle from lo to hi (lo <= hi per component). The size is hi - lo, raised by
/// an ulp where rounding left lo + size short of hi, so the result contains both corners
/// exactly.
Rectangle2D rectangle_from_min_max(const vec2& lo, const vec2& hi);

/// Length of the segment.
float length(const Line2D& line);
/// Squared length of the segment.
float length_squared(const Line2D& line);

/// The relative tolerance of contains(Line2D, point): a point is on a segment when its
/// distance to the segment is at most kOnLineTolerance times the largest absolute
/// coordinate of start, end and the point. 2^-20 is 16 float roundings at that magnitude,
/// so a point computed as lerp(start, end, t) in float is on the segment, while a point
/// one part in a million of the coordinates' magnitude away is not.
inline constexpr float kOnLineTolerance = 0x1p-20f;

/// True if point lies on the segment, within kOnLineTolerance (the book's PointOnLine,
/// which compared with y = mx + b and so failed on vertical lines).
bool contains(const Line2D& line, const vec2& point);
/// True if point is inside the circle or on its rim.
bool contains(const Circle& circle, const vec2& point);
/// True if point is inside the rectangle or on its boundary.
bool contains(const Rectangle2D& rectangle, const vec2& point);
/// True if point is inside the oriented rectangle or on its boundary.
bool contains(const OrientedRectangle& rectangle, const vec2& point);
/// True if point is in any part of the shape.
bool contains(const BoundingShape& shape, const vec2& point);

/// The point of the segment closest to point (start for a zero-length segment).
vec2 closest_point(const Line2D& line, const vec2& point);
/// The point of the solid circle closest to point: point itself when inside, else the
/// point of the rim towards it (which rounding may leave an ulp outside the circle).
vec2 closest_point(const Circle& circle, const vec2& point);
/// The point of the solid rectangle closest to point (a per-axis clamp, exactly inside).
vec2 closest_point(const Rectangle2D& rectangle, const vec2& point);
/// The point of the solid oriented rectangle closest to point (clamped in the local frame,
/// then turned back, so it may lie outside by a rounding).
vec2 closest_point(const OrientedRectangle& rectangle, const vec2& point);

/// True if the segment touches the circle (the book's LineCircle).
bool linetest(const Circle& circle, const Line2D& line);
/// True if the segment touches the rectangle, an end inside included (the book's
/// LineRectangle; here a separating axis test, so no division by a zero direction).
bool linetest(const Rectangle2D& rectangle, const Line2D& line);
/// True if the segment touches the oriented rectangle (the book's LineOrientedRectangle).
bool linetest(const OrientedRectangle& rectangle, const Line2D& line);
/// True if the segment touches any part of the shape.
bool linetest(const BoundingShape& shape, const Line2D& line);

/// True if the circles touch or overlap.
bool overlaps(const Circle& a, const Circle& b);
/// True if the circle and the rectangle touch or overlap.
bool overlaps(const Circle& a, const Rectangle2D& b);
/// Same as overlaps(b, a).
bool overlaps(const Rectangle2D& a, const Circle& b);
/// True if the circle and the oriented rectangle touch or overlap.
bool overlaps(const Circle& a, const OrientedRectangle& b);
/// Same as overlaps(b, a).
bool overlaps(const OrientedRectangle& a, const Circle& b);
/// True if the rectangles touch or overlap (interval overlap on x and y).
bool overlaps(const Rectangle2D& a, const Rectangle2D& b);
/// True if the rectangles touch or overlap (separating axis test on x, y and b's axes).
bool overlaps(const Rectangle2D& a, const OrientedRectangle& b);
/// Same as overlaps(b, a).
bool overlaps(const OrientedRectangle& a, const Rectangle2D& b);
/// True if the oriented rectangles touch or overlap (separating axis test on the four
/// axes; overlaps(a, b) and overlaps(b, a) are always equal).
bool overlaps(const OrientedRectangle& a, const OrientedRectangle& b);

/// True if any part of the shape overlaps the circle.
bool overlaps(const BoundingShape& a, const Circle& b);
/// Same as overlaps(b, a).
bool overlaps(const Circle& a, const BoundingShape& b);
/// True if any part of the shape overlaps the rectangle.
bool overlaps(const BoundingShape& a, const Rectangle2D& b);
/// Same as overlaps(b, a).
bool overlaps(const Rectangle2D& a, const BoundingShape& b);
/// True if any part of the shape overlaps the oriented rectangle.
bool overlaps(const BoundingShape& a, const OrientedRectangle& b);
/// Same as overlaps(b, a).
bool overlaps(const OrientedRectangle& a, const BoundingShape& b);
/// True if any part of a overlaps any part of b.
bool overlaps(const BoundingShape& a, const BoundingShape& b);

/// The smallest circle containing every point (the book's ContainingCircle is the far
/// larger circle about the centroid). Welzl's algorithm, made deterministic: the points
/// are put in a canonical order (sorted, then a fixed pseudo-random permutation, which
/// keeps the expected time linear), so the result's bits depend on the set of points
/// only, not on their order in the span. The radius is then raised to the largest float
/// distance from the float center, so contains(result, p) holds for every point. Against
/// a binary64 brute force it exceeds the exact minimum by at most 1.3e-6 of the largest
/// |coordinate| (the float circumcenter's rounding; tests/geometry/geometry2d_test.cpp).
/// No points: a circle of radius 0 at the origin. A NaN or infinite coordinate: a circle
/// with NaN center and radius.
Circle containing_circle(std::span<const vec2> points);
/// The smallest rectangle containing every point (sized as rectangle_from_min_max, so it
/// contains every point exactly). No points: the zero rectangle at the origin. A NaN or
/// infinite coordinate: a rectangle with NaN origin and size.
Rectangle2D containing_rectangle(std::span<const vec2> points);

}  // namespace gyro
