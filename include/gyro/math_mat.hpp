// mat2, mat3, mat4 and the matrix operations of Cookbook chapter 2.
//
// Conventions (the Cookbook's, which are DirectX's):
//  - Row-major storage: m[row][col], and data() is the 16 (9, 4) floats row after row.
//  - Row vectors multiplied on the left: v' = v * M. So the rows of a transform are the
//    images of the basis vectors, the translation is row 3 (m[3][0..2]), and transforms
//    compose left to right in the order they apply: scale * rotation * translation.
//  - A default-constructed matrix is the identity, as in the book (mat4{} == identity);
//    aggregate initialisation sets every element: mat2{{{a, b}, {c, d}}}.
//  - == is exact IEEE equality per element; nearly_equal is the tolerant comparison.
//  - Every sum runs over its index in order (c[i][j] = ((a[i][0]*b[0][j] + a[i][1]*b[1][j])
//    + ...)), so results are bit-identical across compilers and CPUs. determinant() is the
//    cofactor expansion along row 0, with exactly the arithmetic inverse() uses.
#pragma once

#include "gyro/math_scalar.hpp"
#include "gyro/math_vec.hpp"

#include <cmath>
#include <type_traits>

namespace gyro {

/// A 2x2 matrix, row-major.
struct mat2 {
  float m[2][2] = {{1.0f, 0.0f}, {0.0f, 1.0f}};  ///< m[row][col]; the identity unless initialised
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr float* operator[](int r) { return m[r]; }
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr const float* operator[](int r) const { return m[r]; }
  /// The 4 elements row after row.
  constexpr float* data() { return &m[0][0]; }
  /// The 4 elements row after row.
  constexpr const float* data() const { return &m[0][0]; }
  /// Exact per-element equality.
  constexpr bool operator==(const mat2&) const = default;
  /// The identity (also what mat2{} is).
  static constexpr mat2 identity() { return {}; }
  /// All elements zero.
  static constexpr mat2 zero() { return {{{0.0f, 0.0f}, {0.0f, 0.0f}}}; }
};

/// A 3x3 matrix, row-major; as a rotation, its rows are the rotated x, y, z axes.
struct mat3 {
  float m[3][3] = {
      {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};  ///< m[row][col]; the identity unless initialised
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr float* operator[](int r) { return m[r]; }
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr const float* operator[](int r) const { return m[r]; }
  /// The 9 elements row after row.
  constexpr float* data() { return &m[0][0]; }
  /// The 9 elements row after row.
  constexpr const float* data() const { return &m[0][0]; }
  /// Exact per-element equality.
  constexpr bool operator==(const mat3&) const = default;
  /// The identity (also what mat3{} is).
  static constexpr mat3 identity() { return {}; }
  /// All elements zero.
  static constexpr mat3 zero() { return {{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}}}; }
};

/// A 4x4 matrix, row-major; as an affine transform, rows 0-2 are the transformed axes and
/// row 3 the translation, with column 3 = (0, 0, 0, 1).
struct mat4 {
  /// m[row][col]; the identity unless initialised.
  float m[4][4] = {
      {1.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 1.0f}};
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr float* operator[](int r) { return m[r]; }
  /// Row r: M[r][c] is the element at row r, column c.
  constexpr const float* operator[](int r) const { return m[r]; }
  /// The 16 elements row after row.
  constexpr float* data() { return &m[0][0]; }
  /// The 16 elements row after row.
  constexpr const float* data() const { return &m[0][0]; }
  /// Exact per-element equality.
  constexpr bool operator==(const mat4&) const = default;
  /// The identity (also what mat4{} is).
  static constexpr mat4 identity() { return {}; }
  /// All elements zero.
  static constexpr mat4 zero() {
    return {{{0.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}}};
  }
};

static_assert(sizeof(mat2) == 16 && sizeof(mat3) == 36 && sizeof(mat4) == 64);
static_assert(std::is_standard_layout_v<mat4> && std::is_trivially_copyable_v<mat4> && std::is_aggregate_v<mat4>);

/// inverse() calls a matrix singular when |det| <= kSingularRatio * (product of its row
/// lengths). By Hadamard's inequality that ratio is in [0, 1]: 1 for orthogonal rows, 0 for
/// dependent ones, and unchanged when a row is scaled, so a tiny but well-shaped matrix
/// (scale 1e-3) inverts while a nearly rank-deficient one is refused. A 4x4 whose last row
/// is a combination of the others, rounded to float, measured at most 1.2e-7
/// (tests/math/mat_test.cpp, 100,000 cases), so rounding cannot push one past this bound.
inline constexpr float kSingularRatio = 1e-6f;

namespace detail {

/// The order n of an n x n gyro matrix M (0 for anything else).
template <class M>
inline constexpr int kOrder = 0;
template <>
inline constexpr int kOrder<mat2> = 2;
template <>
inline constexpr int kOrder<mat3> = 3;
template <>
inline constexpr int kOrder<mat4> = 4;

/// mat2, mat3 or mat4: the generic operations below are written once for all three.
template <class M>
concept Matrix = kOrder<M> >
0;

/// The vector type with N components.
template <int N>
struct VecOfOrder;
template <>
struct VecOfOrder<2> {
  using type = vec2;
};
template <>
struct VecOfOrder<3> {
  using type = vec3;
};
template <>
struct VecOfOrder<4> {
  using type = vec4;
};
/// The vector type a matrix M multiplies (its row type).
template <Matrix M>
using RowOf = typename VecOfOrder<kOrder<M>>::type;

/// The matrix type of order N (a float for N = 1).
template <int N>
struct MatOfOrder;
template <>
struct MatOfOrder<1> {
  using type = float;
};
template <>
struct MatOfOrder<2> {
  using type = mat2;
};
template <>
struct MatOfOrder<3> {
  using type = mat3;
};
/// The type of M with one row and one column removed.
template <Matrix M>
using CutOf = typename MatOfOrder<kOrder<M> - 1>::type;

}  // namespace detail

/// Builds a matrix from its rows.
constexpr mat2 from_rows(const vec2& r0, const vec2& r1) { return {{{r0.x, r0.y}, {r1.x, r1.y}}}; }
/// Builds a matrix from its rows.
constexpr mat3 from_rows(const vec3& r0, const vec3& r1, const vec3& r2) {
  return {{{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}}};
}
/// Builds a matrix from its rows.
constexpr mat4 from_rows(const vec4& r0, const vec4& r1, const vec4& r2, const vec4& r3) {
  return {{{r0.x, r0.y, r0.z, r0.w}, {r1.x, r1.y, r1.z, r1.w}, {r2.x, r2.y, r2.z, r2.w}, {r3.x, r3.y, r3.z, r3.w}}};
}

/// Row r as a vector.
template <detail::Matrix M>
constexpr detail::RowOf<M> row(const M& a, int r) {
  detail::RowOf<M> v;
  for (int j = 0; j < detail::kOrder<M>; ++j) v[j] = a.m[r][j];
  return v;
}
/// Column c as a vector.
template <detail::Matrix M>
constexpr detail::RowOf<M> column(const M& a, int c) {
  detail::RowOf<M> v;
  for (int i = 0; i < detail::kOrder<M>; ++i) v[i] = a.m[i][c];
  return v;
}

/// The transpose (rows become columns; exact).
template <detail::Matrix M>
constexpr M transpose(const M& a) {
  M t;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) t.m[i][j] = a.m[j][i];
  return t;
}

/// Element-wise sum.
template <detail::Matrix M>
constexpr M operator+(const M& a, const M& b) {
  M c;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) c.m[i][j] = a.m[i][j] + b.m[i][j];
  return c;
}
/// Element-wise difference.
template <detail::Matrix M>
constexpr M operator-(const M& a, const M& b) {
  M c;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) c.m[i][j] = a.m[i][j] - b.m[i][j];
  return c;
}
/// Every element times s.
template <class M, std::enable_if_t<detail::Matrix<M>, int> = 0>
constexpr M operator*(const M& a, float s) {
  M c;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) c.m[i][j] = a.m[i][j] * s;
  return c;
}
/// Every element times s. (Constraints on the float operators: see math_vec.hpp.)
template <class M, std::enable_if_t<detail::Matrix<M>, int> = 0>
constexpr M operator*(float s, const M& a) {
  return a * s;
}

/// The matrix product a * b: with row vectors, v * (a * b) applies a first, then b.
template <detail::Matrix M>
constexpr M operator*(const M& a, const M& b) {
  constexpr int n = detail::kOrder<M>;
  M c;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      float s = a.m[i][0] * b.m[0][j];
      for (int k = 1; k < n; ++k) s = s + a.m[i][k] * b.m[k][j];
      c.m[i][j] = s;
    }
  return c;
}
/// a = a * b.
template <detail::Matrix M>
constexpr M& operator*=(M& a, const M& b) {
  return a = a * b;
}

/// The row vector v times the matrix: v'[j] = sum over k of v[k] * a[k][j].
template <detail::Matrix M>
constexpr detail::RowOf<M> operator*(const detail::RowOf<M>& v, const M& a) {
  constexpr int n = detail::kOrder<M>;
  detail::RowOf<M> r;
  for (int j = 0; j < n; ++j) {
    float s = v[0] * a.m[0][j];
    for (int k = 1; k < n; ++k) s = s + v[k] * a.m[k][j];
    r[j] = s;
  }
  return r;
}
/// v * a for a 3D vector and a 3x3 matrix (the book's MultiplyVector for mat3).
constexpr vec3 multiply(const vec3& v, const mat3& a) { return v * a; }
/// The point p (w = 1) transformed by an affine a: p * upper 3x3 + row 3. Like the book it
/// ignores column 3; for a projection use vec4{p.x, p.y, p.z, 1} * a and divide by w.
constexpr vec3 multiply_point(const vec3& p, const mat4& a) {
  return {p.x * a.m[0][0] + p.y * a.m[1][0] + p.z * a.m[2][0] + a.m[3][0],
          p.x * a.m[0][1] + p.y * a.m[1][1] + p.z * a.m[2][1] + a.m[3][1],
          p.x * a.m[0][2] + p.y * a.m[1][2] + p.z * a.m[2][2] + a.m[3][2]};
}
/// The direction v (w = 0) transformed by a: v * upper 3x3, so translation does not apply.
constexpr vec3 multiply_vector(const vec3& v, const mat4& a) {
  return {v.x * a.m[0][0] + v.y * a.m[1][0] + v.z * a.m[2][0], v.x * a.m[0][1] + v.y * a.m[1][1] + v.z * a.m[2][1],
          v.x * a.m[0][2] + v.y * a.m[1][2] + v.z * a.m[2][2]};
}

/// The upper-left 3x3 of a 4x4 (its rotation and scale for an affine transform).
constexpr mat3 to_mat3(const mat4& a) {
  return {{{a.m[0][0], a.m[0][1], a.m[0][2]}, {a.m[1][0], a.m[1][1], a.m[1][2]}, {a.m[2][0], a.m[2][1], a.m[2][2]}}};
}
/// a as the upper-left 3x3 of a 4x4 with no translation.
constexpr mat4 to_mat4(const mat3& a) {
  return {{{a.m[0][0], a.m[0][1], a.m[0][2], 0.0f},
           {a.m[1][0], a.m[1][1], a.m[1][2], 0.0f},
           {a.m[2][0], a.m[2][1], a.m[2][2], 0.0f},
           {0.0f, 0.0f, 0.0f, 1.0f}}};
}

/// a without row r and column c (the book's Cut). For a mat2 it is the remaining float.
template <detail::Matrix M>
constexpr detail::CutOf<M> cut(const M& a, int r, int c) {
  if constexpr (detail::kOrder<M> == 2) {
    return a.m[1 - r][1 - c];
  } else {
    detail::CutOf<M> s;
    int si = 0;
    for (int i = 0; i < detail::kOrder<M>; ++i) {
      if (i == r) continue;
      int sj = 0;
      for (int j = 0; j < detail::kOrder<M>; ++j)
        if (j != c) s.m[si][sj++] = a.m[i][j];
      ++si;
    }
    return s;
  }
}

template <detail::Matrix M>
constexpr float determinant(const M& a);

namespace detail {
/// (-1)^(r+c) times the minor at (r, c); the sign flip is exact.
template <Matrix M>
constexpr float cofactor_at(const M& a, int r, int c) {
  float minor;
  if constexpr (kOrder<M> == 2)
    minor = cut(a, r, c);
  else
    minor = determinant(cut(a, r, c));
  return ((r + c) & 1) ? -minor : minor;
}
/// sum over j of a[0][j] * cof[0][j]: the one expression determinant() and inverse() share.
template <Matrix M>
constexpr float expand_row0(const M& a, const float* cof_row0) {
  float s = a.m[0][0] * cof_row0[0];
  for (int j = 1; j < kOrder<M>; ++j) s = s + a.m[0][j] * cof_row0[j];
  return s;
}
/// Product of the rows' lengths: Hadamard's bound on |det|.
template <Matrix M>
inline float row_length_product(const M& a) {
  float p = length(row(a, 0));
  for (int i = 1; i < kOrder<M>; ++i) p = p * length(row(a, i));
  return p;
}
}  // namespace detail

/// The determinant: a*d - b*c for a mat2, otherwise the cofactor expansion along row 0
/// (the book's method), with each 3x3 minor expanded the same way.
template <detail::Matrix M>
constexpr float determinant(const M& a) {
  if constexpr (detail::kOrder<M> == 2) {
    return a.m[0][0] * a.m[1][1] - a.m[0][1] * a.m[1][0];
  } else {
    float cof[detail::kOrder<M>];
    for (int j = 0; j < detail::kOrder<M>; ++j) cof[j] = detail::cofactor_at(a, 0, j);
    return detail::expand_row0(a, cof);
  }
}

/// The matrix of minors (the book's Minor): element (r, c) is the determinant of
/// cut(a, r, c). Named in the plural because glibc's <sys/sysmacros.h> defines a macro
/// minor(dev) that would rewrite every call.
template <detail::Matrix M>
constexpr M minors(const M& a) {
  M out;
  for (int r = 0; r < detail::kOrder<M>; ++r)
    for (int c = 0; c < detail::kOrder<M>; ++c) {
      if constexpr (detail::kOrder<M> == 2)
        out.m[r][c] = cut(a, r, c);
      else
        out.m[r][c] = determinant(cut(a, r, c));
    }
  return out;
}
/// The cofactor matrix: the minors with sign (-1)^(r+c).
template <detail::Matrix M>
constexpr M cofactor(const M& a) {
  M out;
  for (int r = 0; r < detail::kOrder<M>; ++r)
    for (int c = 0; c < detail::kOrder<M>; ++c) out.m[r][c] = detail::cofactor_at(a, r, c);
  return out;
}
/// The adjugate, transpose(cofactor(a)): adjugate(a) * a = a * adjugate(a) = det(a) * I.
template <detail::Matrix M>
constexpr M adjugate(const M& a) {
  return transpose(cofactor(a));
}

/// Writes the inverse of a to *out and returns true; for a singular matrix returns false
/// and leaves *out unchanged. Singular means: |det| <= kSingularRatio * (product of the row
/// lengths), or a non-finite element, determinant, row-length product or result. The
/// inverse is the adjugate divided element by element by the determinant (the book's
/// method). out may alias a; a null out makes this a pure invertibility test.
template <detail::Matrix M>
inline bool inverse(const M& a, M* out) {
  const M cof = cofactor(a);
  const float det = detail::expand_row0(a, cof.m[0]);
  const float bound = detail::row_length_product(a);
  if (!std::isfinite(det) || !std::isfinite(bound) || !(std::abs(det) > kSingularRatio * bound)) return false;
  M inv;
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j) {
      inv.m[i][j] = cof.m[j][i] / det;
      if (!std::isfinite(inv.m[i][j])) return false;
    }
  if (out) *out = inv;
  return true;
}

/// The inverse of a rigid transform (rotation, then translation): the transposed rotation
/// and the translation -t * R^T. Exact up to one rounding per element, and far cheaper than
/// inverse(); the caller guarantees that the upper 3x3 is orthonormal and column 3 is
/// (0, 0, 0, 1), otherwise the result is not the inverse.
constexpr mat4 inverse_rigid(const mat4& a) {
  mat4 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[j][i];
  for (int j = 0; j < 3; ++j) r.m[3][j] = -(a.m[3][0] * a.m[j][0] + a.m[3][1] * a.m[j][1] + a.m[3][2] * a.m[j][2]);
  return r;
}

/// Every element nearly_equal(a, b, eps).
template <detail::Matrix M>
inline bool nearly_equal(const M& a, const M& b, float eps = kEpsilon) {
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j)
      if (!nearly_equal(a.m[i][j], b.m[i][j], eps)) return false;
  return true;
}
/// Every element nearly_equal(a, b, abs_tol, rel_tol).
template <detail::Matrix M>
inline bool nearly_equal(const M& a, const M& b, float abs_tol, float rel_tol) {
  for (int i = 0; i < detail::kOrder<M>; ++i)
    for (int j = 0; j < detail::kOrder<M>; ++j)
      if (!nearly_equal(a.m[i][j], b.m[i][j], abs_tol, rel_tol)) return false;
  return true;
}

}  // namespace gyro
