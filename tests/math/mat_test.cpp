// Matrices (include/gyro/math_mat.hpp): layout, exact algebraic identities, and seeded
// random properties against double precision: products, determinants (against a double
// cofactor expansion), adjugate * M = det * I, M * inverse(M) = I, and inverse() refusing
// singular matrices without touching its output. Each property prints its largest error;
// the bounds are about twice the measured maxima (GCC 12, x86-64).
#include "gyro/math.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

namespace gyro {
namespace {

using testing::SplitMix64;

constexpr float kNan = __builtin_nanf("");
constexpr float kInf = __builtin_inff();

// Not inlined: with it inlined, GCC 12 -O3 (its SLP vectoriser) gave mat_test's double
// references values other than the rounded floats the code under test received (an
// adjugate product that is exactly zero came out as 2e-6; clang, and GCC with
// -fno-tree-slp-vectorize, were right). A call hands over the rounded float, once.
[[gnu::noinline]] float uniform(SplitMix64& rng, double lo, double hi) {
  return static_cast<float>(lo + (hi - lo) * rng.u());
}

template <class M>
constexpr int N = detail::kOrder<M>;

/// An n x n double matrix (n <= 4) for the references.
struct DMat {
  int n = 0;
  double a[4][4] = {};
};
template <class M>
DMat to_double(const M& m) {
  DMat d;
  d.n = N<M>;
  for (int i = 0; i < d.n; ++i)
    for (int j = 0; j < d.n; ++j) d.a[i][j] = m.m[i][j];
  return d;
}
DMat dcut(const DMat& m, int r, int c) {
  DMat s;
  s.n = m.n - 1;
  for (int i = 0, si = 0; i < m.n; ++i) {
    if (i == r) continue;
    for (int j = 0, sj = 0; j < m.n; ++j)
      if (j != c) s.a[si][sj++] = m.a[i][j];
    ++si;
  }
  return s;
}
/// Laplace expansion along row 0, in double.
double ddet(const DMat& m) {
  if (m.n == 1) return m.a[0][0];
  double s = 0;
  for (int j = 0; j < m.n; ++j) s += (j % 2 ? -1.0 : 1.0) * m.a[0][j] * ddet(dcut(m, 0, j));
  return s;
}
/// The inverse in double: adjugate / determinant.
DMat dinverse(const DMat& m) {
  DMat r;
  r.n = m.n;
  const double det = ddet(m);
  for (int i = 0; i < m.n; ++i)
    for (int j = 0; j < m.n; ++j) r.a[j][i] = ((i + j) % 2 ? -1.0 : 1.0) * ddet(dcut(m, i, j)) / det;
  return r;
}
// Sums into a local, not with += into the zeroed result: GCC 12's SLP vectoriser
// miscompiles that zero-then-accumulate pattern at -O3 (a known class of GCC bugs, e.g.
// PR 93334), which here produced products rounded to float.
DMat dmul(const DMat& x, const DMat& y) {
  DMat r;
  r.n = x.n;
  for (int i = 0; i < x.n; ++i)
    for (int j = 0; j < x.n; ++j) {
      double s = 0;
      for (int k = 0; k < x.n; ++k) s += x.a[i][k] * y.a[k][j];
      r.a[i][j] = s;
    }
  return r;
}
double max_abs(const DMat& m) {
  double e = 0;
  for (int i = 0; i < m.n; ++i)
    for (int j = 0; j < m.n; ++j) e = std::fmax(e, std::fabs(m.a[i][j]));
  return e;
}
/// Hadamard's bound: the product of the row lengths, in double.
template <class M>
double hadamard(const M& m) {
  double p = 1;
  for (int i = 0; i < N<M>; ++i) {
    double s = 0;
    for (int j = 0; j < N<M>; ++j) s += double(m.m[i][j]) * m.m[i][j];
    p *= std::sqrt(s);
  }
  return p;
}

/// max over i, j of |(a * inv)_ij - delta_ij| / sum over k of |a_ik inv_kj|, in double: the
/// error of a product on the scale of its own terms (a translation row cancels terms as
/// large as |t| |inv|, so a fixed absolute tolerance would not fit every element).
template <class M>
double identity_error(const M& a, const M& inv) {
  double e = 0;
  for (int i = 0; i < N<M>; ++i)
    for (int j = 0; j < N<M>; ++j) {
      double p = 0, scale = 0;
      for (int k = 0; k < N<M>; ++k)
        p += double(a.m[i][k]) * inv.m[k][j], scale += std::fabs(double(a.m[i][k]) * inv.m[k][j]);
      const double d = std::fabs(p - (i == j ? 1.0 : 0.0));
      e = std::fmax(e, scale > 0 ? d / scale : d);
    }
  return e;
}

template <class M>
M random_matrix(SplitMix64& rng, double lo, double hi) {
  M m;
  for (int i = 0; i < N<M>; ++i)
    for (int j = 0; j < N<M>; ++j) m.m[i][j] = uniform(rng, lo, hi);
  return m;
}
/// Entries in [-1, 1] plus n + 1 on the diagonal: strictly diagonally dominant, so every
/// eigenvalue lies in [1, 2n + 1] and the condition number stays small.
template <class M>
M well_conditioned(SplitMix64& rng) {
  M m = random_matrix<M>(rng, -1, 1);
  for (int i = 0; i < N<M>; ++i) m.m[i][i] += static_cast<float>(N<M> + 1);
  return m;
}
quat random_rotation(SplitMix64& rng) {
  return from_axis_angle(vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}, uniform(rng, -4, 4));
}
/// scale in [0.2, 5] per axis, any rotation, translation in [-100, 100]^3.
mat4 random_trs(SplitMix64& rng) {
  const vec3 s{uniform(rng, 0.2, 5), uniform(rng, 0.2, 5), uniform(rng, 0.2, 5)};
  const vec3 t{uniform(rng, -100, 100), uniform(rng, -100, 100), uniform(rng, -100, 100)};
  return transform(s, random_rotation(rng), t);
}

/// The largest error of one property over every sample: printed, then checked against its
/// bound when the property's scope ends, so the printed maximum is the true one even when
/// the check fails. A NaN error is kept as the worst.
struct MaxError {
  const char* what;
  double bound;
  double max = 0.0;
  long worst = -1;
  void add(double e, long sample) {
    if (std::isnan(max)) return;
    if (!(e <= max)) max = e, worst = sample;
  }
  ~MaxError() {
    std::printf("  %-60s max %.3g (bound %.2g)\n", what, max, bound);
    EXPECT_LE(max, bound) << what << ": worst at sample " << worst;
  }
};

TEST(Mat, LayoutIsRowMajorAndDefaultIsIdentity) {
  static_assert(sizeof(mat2) == 16 && sizeof(mat3) == 36 && sizeof(mat4) == 64);
  mat4 m;
  EXPECT_EQ(m, mat4::identity());
  EXPECT_EQ(mat4{}.m[2][2], 1.0f);
  EXPECT_EQ(mat4{}.m[2][3], 0.0f);
  EXPECT_EQ(mat3{}, mat3::identity());
  EXPECT_EQ(mat2{}, mat2::identity());
  for (int i = 0; i < 16; ++i) EXPECT_EQ(mat4::zero().data()[i], 0.0f);
  for (int i = 0; i < 16; ++i) m.data()[i] = static_cast<float>(i);
  EXPECT_EQ(m[1][2], 6.0f);  // row 1, column 2
  EXPECT_EQ(m.m[3][0], 12.0f);
  EXPECT_EQ(row(m, 2), (vec4{8, 9, 10, 11}));
  EXPECT_EQ(column(m, 1), (vec4{1, 5, 9, 13}));
  EXPECT_EQ(from_rows(row(m, 0), row(m, 1), row(m, 2), row(m, 3)), m);
  const mat3 a{{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}};
  EXPECT_EQ(a.data()[5], 6.0f);
  EXPECT_EQ(from_rows(vec3{1, 2, 3}, vec3{4, 5, 6}, vec3{7, 8, 9}), a);
  EXPECT_EQ(from_rows(vec2{1, 2}, vec2{3, 4}), (mat2{{{1, 2}, {3, 4}}}));
  EXPECT_EQ(transpose(a), (mat3{{{1, 4, 7}, {2, 5, 8}, {3, 6, 9}}}));
  EXPECT_EQ(to_mat3(m), (mat3{{{0, 1, 2}, {4, 5, 6}, {8, 9, 10}}}));
  EXPECT_EQ(to_mat3(to_mat4(a)), a);
  EXPECT_EQ(to_mat4(a).m[3][3], 1.0f);
  EXPECT_EQ(to_mat4(a).m[0][3], 0.0f);
}

TEST(Mat, ExactOperationsOnSmallIntegers) {
  const mat2 a{{{1, 2}, {3, 4}}}, b{{{0, 1}, {-1, 5}}};
  EXPECT_EQ(a * b, (mat2{{{-2, 11}, {-4, 23}}}));
  EXPECT_EQ(a + b, (mat2{{{1, 3}, {2, 9}}}));
  EXPECT_EQ(a - b, (mat2{{{1, 1}, {4, -1}}}));
  EXPECT_EQ(a * 2.0f, (mat2{{{2, 4}, {6, 8}}}));
  EXPECT_EQ(2.0f * a, a * 2.0f);
  mat2 c = a;
  c *= b;
  EXPECT_EQ(c, a * b);
  // Row vector on the left: v * M is a combination of M's rows.
  EXPECT_EQ((vec2{1, 1} * a), (vec2{4, 6}));
  const mat3 m{{{1, 0, 2}, {0, 3, 0}, {4, 0, 5}}};
  EXPECT_EQ((vec3{1, 2, 3} * m), (vec3{13, 6, 17}));
  EXPECT_EQ(multiply(vec3{1, 2, 3}, m), (vec3{13, 6, 17}));
  EXPECT_EQ(determinant(a), -2.0f);
  EXPECT_EQ(determinant(m), -9.0f);
  EXPECT_EQ(determinant(mat4{}), 1.0f);
  EXPECT_EQ(determinant(mat4{{{2, 0, 0, 0}, {0, 3, 0, 0}, {0, 0, 4, 0}, {1, 2, 3, 1}}}), 24.0f);
  EXPECT_EQ(minors(a), (mat2{{{4, 3}, {2, 1}}}));
  EXPECT_EQ(cofactor(a), (mat2{{{4, -3}, {-2, 1}}}));
  EXPECT_EQ(adjugate(a), (mat2{{{4, -2}, {-3, 1}}}));
  mat2 inv;
  ASSERT_TRUE(inverse(a, &inv));
  EXPECT_EQ(inv, (mat2{{{-2, 1}, {1.5f, -0.5f}}}));
  EXPECT_EQ(cut(m, 1, 1), (mat2{{{1, 2}, {4, 5}}}));
  EXPECT_EQ(cut(a, 0, 1), 3.0f);
  // multiply_point applies the translation (row 3), multiply_vector does not.
  const mat4 t = mat4{{{2, 0, 0, 0}, {0, 2, 0, 0}, {0, 0, 2, 0}, {0, 0, 0, 1}}} * translation(vec3{10, 20, 30});
  EXPECT_EQ(multiply_point(vec3{1, 2, 3}, t), (vec3{12, 24, 36}));
  EXPECT_EQ(multiply_vector(vec3{1, 2, 3}, t), (vec3{2, 4, 6}));
}

template <class M>
void check_products(uint64_t seed) {
  SplitMix64 rng(seed);
  MaxError err{N<M> == 2   ? "mat2 product: |err| / sum|a_ik b_kj|"
               : N<M> == 3 ? "mat3 product: |err| / sum|a_ik b_kj|"
                           : "mat4 product: |err| / sum|a_ik b_kj|",
               4e-7};
  for (int it = 0; it < 20000; ++it) {
    const M a = random_matrix<M>(rng, -10, 10), b = random_matrix<M>(rng, -10, 10);
    const M c = a * b;
    for (int i = 0; i < N<M>; ++i)
      for (int j = 0; j < N<M>; ++j) {
        double ref = 0, mag = 0;
        for (int k = 0; k < N<M>; ++k)
          ref += double(a.m[i][k]) * b.m[k][j], mag += std::fabs(double(a.m[i][k]) * b.m[k][j]);
        const double e = std::fabs(c.m[i][j] - ref) / mag;
        err.add(e, it);
      }
    // Exact identities: the identity is neutral, and (ab)^T = b^T a^T term by term.
    ASSERT_EQ(M::identity() * a, a);
    ASSERT_EQ(a * M::identity(), a);
    ASSERT_EQ(transpose(a * b), transpose(b) * transpose(a));
    ASSERT_EQ(transpose(transpose(a)), a);
    // A row vector times a matrix is the first row of the product with that vector on top.
    M v_on_top = M::zero();
    for (int j = 0; j < N<M>; ++j) v_on_top.m[0][j] = a.m[1][j];
    ASSERT_EQ(row(a, 1) * b, row(v_on_top * b, 0));
  }
}

TEST(Mat, ProductsAgainstDouble) {
  check_products<mat2>(201);
  check_products<mat3>(202);
  check_products<mat4>(203);
  SplitMix64 rng(204);
  for (int it = 0; it < 10000; ++it) {
    const mat4 m = random_matrix<mat4>(rng, -10, 10);
    const vec3 p{uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10)};
    const vec4 ph = vec4{p.x, p.y, p.z, 1.0f} * m, vh = vec4{p.x, p.y, p.z, 0.0f} * m;
    ASSERT_EQ(multiply_point(p, m), (vec3{ph.x, ph.y, ph.z}));
    ASSERT_EQ(multiply_vector(p, m), (vec3{vh.x, vh.y, vh.z}));
    ASSERT_EQ(multiply(p, to_mat3(m)), multiply_vector(p, m));
  }
}

template <class M>
void check_determinant(uint64_t seed, const char* name) {
  SplitMix64 rng(seed);
  char label[96];
  std::snprintf(label, sizeof label, "%s determinant vs double: |err| / hadamard", name);
  MaxError err{label, 3e-7};
  char label2[96];
  std::snprintf(label2, sizeof label2, "%s adj*M, M*adj - det*I, / hadamard-based scale", name);
  MaxError adj_err{label2, 4e-7};
  for (int it = 0; it < 50000; ++it) {
    const M a = random_matrix<M>(rng, -10, 10);
    const double h = hadamard(a);
    const double e = std::fabs(determinant(a) - ddet(to_double(a))) / h;
    err.add(e, it);
    if constexpr (N<M> == 2) {
      ASSERT_EQ(adjugate(a), (mat2{{{a.m[1][1], -a.m[0][1]}, {-a.m[1][0], a.m[0][0]}}})) << it;
    }
    // adjugate(M) * M = M * adjugate(M) = det(M) * I, the products taken in double. A
    // cofactor C_jk carries about one rounding of the product of the row lengths other than
    // row j's, h / |r_j|. In adjugate * M it meets row j's own entries, so every term is
    // within h; in M * adjugate, element (i, j) meets row i's entries, so the scale there is
    // h |r_i| / |r_j|.
    const float det = determinant(a);
    const DMat da = to_double(a), dadj = to_double(adjugate(a));
    double r[4];
    for (int i = 0; i < N<M>; ++i) r[i] = std::sqrt(double(length_squared(row(a, i))));
    const DMat left = dmul(dadj, da), right = dmul(da, dadj);
    for (int i = 0; i < N<M>; ++i)
      for (int j = 0; j < N<M>; ++j) {
        const double id = i == j ? double(det) : 0.0;
        adj_err.add(std::fmax(std::fabs(left.a[i][j] - id) / h, std::fabs(right.a[i][j] - id) / (h * r[i] / r[j])), it);
      }
    // The determinant is the same expression inverse() divides by.
    const M cof = cofactor(a);
    float s = a.m[0][0] * cof.m[0][0];
    for (int j = 1; j < N<M>; ++j) s = s + a.m[0][j] * cof.m[0][j];
    ASSERT_EQ(determinant(a), s);
    // Minors, cofactors and the adjugate are related exactly.
    const M mi = minors(a);
    for (int i = 0; i < N<M>; ++i)
      for (int j = 0; j < N<M>; ++j) {
        ASSERT_EQ(cof.m[i][j], (i + j) % 2 ? -mi.m[i][j] : mi.m[i][j]);
        if constexpr (N < M >> 2) {
          ASSERT_EQ(mi.m[i][j], determinant(cut(a, i, j)));
        }
      }
    ASSERT_EQ(adjugate(a), transpose(cof));
  }
}

TEST(Mat, DeterminantAndAdjugateAgainstDouble) {
  check_determinant<mat2>(211, "mat2");
  check_determinant<mat3>(212, "mat3");
  check_determinant<mat4>(213, "mat4");
}

template <class M>
void check_inverse(uint64_t seed, const char* name) {
  SplitMix64 rng(seed);
  char l1[96], l2[96];
  std::snprintf(l1, sizeof l1, "%s M * inverse(M) - I (diagonally dominant)", name);
  std::snprintf(l2, sizeof l2, "%s inverse vs double, / max|inverse|", name);
  MaxError id_err{l1, 1e-6}, ref_err{l2, 1e-6};
  for (int it = 0; it < 50000; ++it) {
    const M a = well_conditioned<M>(rng);
    M inv;
    ASSERT_TRUE(inverse(a, &inv)) << it;
    const DMat p = dmul(to_double(a), to_double(inv)), q = dmul(to_double(inv), to_double(a));
    for (const DMat& r : {p, q})
      for (int i = 0; i < N<M>; ++i)
        for (int j = 0; j < N<M>; ++j) {
          const double e = std::fabs(r.a[i][j] - (i == j ? 1.0 : 0.0));
          id_err.add(e, it);
        }
    const DMat ref = dinverse(to_double(a));
    DMat diff = ref;
    for (int i = 0; i < N<M>; ++i)
      for (int j = 0; j < N<M>; ++j) diff.a[i][j] = inv.m[i][j] - ref.a[i][j];
    const double e = max_abs(diff) / max_abs(ref);
    ref_err.add(e, it);
  }
}

TEST(Mat, InverseOfWellConditionedMatricesAgainstDouble) {
  check_inverse<mat2>(221, "mat2");
  check_inverse<mat3>(222, "mat3");
  check_inverse<mat4>(223, "mat4");
}

TEST(Mat, InverseOfRandomTransforms) {
  SplitMix64 rng(224);
  MaxError err{"TRS: M * inverse(M) - I, / sum|m_ik inv_kj|", 1.5e-6},
      rigid{"rigid: inverse_rigid vs inverse (translation / 100)", 2.5e-6};
  for (int it = 0; it < 50000; ++it) {
    const mat4 a = random_trs(rng);
    mat4 inv;
    ASSERT_TRUE(inverse(a, &inv));
    err.add(identity_error(a, inv), it);
    // A rigid transform (no scale) inverts by transposition.
    const vec3 t{uniform(rng, -100, 100), uniform(rng, -100, 100), uniform(rng, -100, 100)};
    const mat4 r = to_mat4(random_rotation(rng)) * translation(t);
    mat4 general;
    ASSERT_TRUE(inverse(r, &general));
    const mat4 fast = inverse_rigid(r);
    for (int i = 0; i < 16; ++i) {
      const double e = std::fabs(fast.data()[i] - general.data()[i]) / (i >= 12 ? 100.0 : 1.0);
      rigid.add(e, it);
    }
    const vec3 back = multiply_point(multiply_point(vec3{1, 2, 3}, r), fast);
    ASSERT_NEAR(back.x, 1.0f, 1e-4f);
    ASSERT_NEAR(back.z, 3.0f, 1e-4f);
  }
}

// The output is left as it was: compared as bytes against a sentinel pattern.
template <class M>
void expect_refused(const M& a, const char* what) {
  M out;
  std::memset(static_cast<void*>(&out), 0x5a, sizeof out);
  M before;
  std::memcpy(static_cast<void*>(&before), &out, sizeof out);
  EXPECT_FALSE(inverse(a, &out)) << what;
  EXPECT_EQ(std::memcmp(&out, &before, sizeof out), 0) << what << ": output was written";
  EXPECT_FALSE(inverse(a, static_cast<M*>(nullptr))) << what;
}

TEST(Mat, InverseRefusesSingularMatricesAndLeavesTheOutputUntouched) {
  expect_refused(mat4::zero(), "zero mat4");
  expect_refused(mat3::zero(), "zero mat3");
  expect_refused(mat2::zero(), "zero mat2");
  expect_refused(scale(vec3{1, 0, 1}), "flattening scale");
  expect_refused(mat2{{{1, 2}, {2, 4}}}, "dependent rows");
  expect_refused(mat2{{{1, 2}, {kNan, 4}}}, "NaN mat2");
  expect_refused(mat3{{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}}, "classic rank 2");
  mat4 m = mat4::identity();
  m.m[1][2] = kNan;
  expect_refused(m, "NaN element");
  m.m[1][2] = kInf;
  expect_refused(m, "infinite element");
  expect_refused(scale(vec3{1e30f, 1e30f, 1e30f}), "determinant overflows");

  SplitMix64 rng(231);
  // Integer rows with one row a combination of the others: every product and sum in the
  // cofactor expansion is exact, so the determinant is exactly 0.
  for (int it = 0; it < 10000; ++it) {
    mat4 a;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) a.m[i][j] = std::floor(uniform(rng, -9, 10));
    const float k0 = std::floor(uniform(rng, -2, 3)), k1 = std::floor(uniform(rng, -2, 3));
    const int dep = static_cast<int>(rng.next() % 4);
    float combo[4];
    for (int j = 0; j < 4; ++j) combo[j] = k0 * a.m[0][j] + k1 * a.m[1][j] + a.m[2][j];
    for (int j = 0; j < 4; ++j) a.m[3][j] = combo[j];
    std::swap(a.m[3], a.m[dep]);
    ASSERT_EQ(determinant(a), 0.0f);
    mat4 out = mat4::zero();
    ASSERT_FALSE(inverse(a, &out)) << it;
    ASSERT_EQ(out, mat4::zero());
  }
  // Random real rows with one row a combination of the others, rounded to float: the
  // float matrix is only nearly singular, and its ratio |det| / hadamard stays far below
  // kSingularRatio.
  MaxError ratio{"rank-deficient after rounding: |det| / hadamard", kSingularRatio / 4};
  for (int it = 0; it < 100000; ++it) {
    mat4 a = random_matrix<mat4>(rng, -10, 10);
    const float k0 = uniform(rng, -2, 2), k1 = uniform(rng, -2, 2), k2 = uniform(rng, -2, 2);
    for (int j = 0; j < 4; ++j) a.m[3][j] = k0 * a.m[0][j] + k1 * a.m[1][j] + k2 * a.m[2][j];
    const double r = std::fabs(determinant(a)) / hadamard(a);
    ratio.add(r, it);
    mat4 out = mat4::zero();
    ASSERT_FALSE(inverse(a, &out)) << it;
    ASSERT_EQ(out, mat4::zero());
    mat3 b = random_matrix<mat3>(rng, -10, 10);
    for (int j = 0; j < 3; ++j) b.m[2][j] = k0 * b.m[0][j] + k1 * b.m[1][j];
    mat3 out3 = mat3::zero();
    ASSERT_FALSE(inverse(b, &out3)) << it;
    ASSERT_EQ(out3, mat3::zero());
  }
}

TEST(Mat, InverseAcceptsTinyAndHugeButWellShapedMatrices) {
  // An absolute threshold on det would refuse these; the Hadamard ratio of each is 1.
  for (float s : {1e-3f, 1e-10f, 1e3f, 1e9f}) {
    const mat4 a = scale(vec3{s, s, s}) * translation(vec3{1, 2, 3});
    mat4 inv;
    ASSERT_TRUE(inverse(a, &inv)) << s;
    EXPECT_TRUE(nearly_equal(inv.m[0][0], 1.0f / s, 0.0f, 1e-6f)) << s;
    EXPECT_TRUE(nearly_equal(inv.m[3][2], -3.0f / s, 0.0f, 1e-6f)) << s;
  }
  mat4 mixed = scale(vec3{1e-4f, 1.0f, 1e4f});
  mat4 inv;
  ASSERT_TRUE(inverse(mixed, &inv));
  EXPECT_TRUE(nearly_equal(inv.m[0][0], 1e4f, 0.0f, 1e-6f));
  EXPECT_TRUE(nearly_equal(inv.m[2][2], 1e-4f, 0.0f, 1e-6f));
  // A projection matrix (column 3 is not (0, 0, 0, 1)) inverts too.
  const mat4 p = perspective(1.0f, 1.5f, 0.01f, 1000.0f);
  ASSERT_TRUE(inverse(p, &inv));
  EXPECT_LE(identity_error(p, inv), 3e-7);
  // In place, and as a pure test.
  SplitMix64 rng(232);
  mat4 a = random_trs(rng);
  const mat4 copy = a;
  ASSERT_TRUE(inverse(a, &inv));
  ASSERT_TRUE(inverse(a, &a));
  EXPECT_EQ(a, inv);
  EXPECT_TRUE(inverse(copy, static_cast<mat4*>(nullptr)));
  mat3 i3;
  ASSERT_TRUE(inverse(mat3{{{0, 2, 0}, {0, 0, 4}, {8, 0, 0}}}, &i3));
  EXPECT_EQ(i3, (mat3{{{0, 0, 0.125f}, {0.5f, 0, 0}, {0, 0.25f, 0}}}));
}

TEST(Mat, NearlyEqual) {
  const mat3 a{{{1, 2, 3}, {4, 5, 6}, {7, 8, 10}}};
  mat3 b = a;
  b.m[2][2] = 10.000001f;
  EXPECT_TRUE(nearly_equal(a, b));
  b.m[2][2] = 10.01f;
  EXPECT_FALSE(nearly_equal(a, b));
  EXPECT_TRUE(nearly_equal(a, b, 0.02f, 0.0f));
  EXPECT_TRUE(nearly_equal(a, b, 0.0f, 1.1e-3f));
  EXPECT_FALSE(nearly_equal(a, b, 0.0f, 0.9e-3f));
}

}  // namespace
}  // namespace gyro
