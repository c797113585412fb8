// gyro/frustum.hpp: plane extraction (Gribb and Hartmann, in double precision), the
// frustum's corners, the scalar tests (the float instantiation of frustum_lanes.hpp) and
// the batch culling calls (check, pin the FP environment, run the per-level kernel over
// fixed chunks).
#include "gyro/frustum.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/shape_checks.hpp"
#include "geometry/shapes_public.hpp"
#include "spatial/frustum_batch.hpp"
#include "spatial/frustum_lanes.hpp"

#include <cmath>

namespace gyro {
namespace {

using detail::fail;
namespace lanes = GYRO_ARCH_NS;

static_assert(kFrustumRelTolerance == lanes::kFrustumRelTolerance, "gyro/frustum.hpp and frustum_lanes.hpp must agree");
static_assert(kFrustumAbsTolerance == lanes::kFrustumAbsTolerance, "gyro/frustum.hpp and frustum_lanes.hpp must agree");

constexpr std::size_t kMaxCount = 0x7FFFFFFF;
// Shapes per chunk: a multiple of 16 so every SIMD level runs full batches inside a chunk.
constexpr std::size_t kCullChunk = 1024;

struct Mat4d {
  double m[4][4];
};

Mat4d to_double(const mat4& a) {
  Mat4d d;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d.m[i][j] = a.m[i][j];
  return d;
}

// The plane a x + b y + c z + e >= 0 as a unit normal and distance (dot(n, p) >= distance),
// rounded once to float. A zero or non-finite (a, b, c) culls nothing.
Plane unit_plane(double a, double b, double c, double e) {
  const double len = std::sqrt((a * a + b * b) + c * c);
  if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(e)) return {{0.0f, 0.0f, 0.0f}, 0.0f};
  return {{float(a / len), float(b / len), float(c / len)}, float(-e / len)};
}

// With row vectors clip = (p, 1) * M, so clip component j is column j of M applied to
// (x, y, z, 1). gyro's clip volume is -w <= x <= w, -w <= y <= w, 0 <= z <= w; each bound
// is a sum or difference of two columns (the near plane is column 2 alone).
Frustum extract(const Mat4d& m) {
  auto plane = [&](int j, double sj, int k, double sk) {
    double v[4];
    for (int i = 0; i < 4; ++i) v[i] = sj * m.m[i][j] + sk * m.m[i][k];
    return unit_plane(v[0], v[1], v[2], v[3]);
  };
  Frustum f;
  f.planes[frustum_plane::left] = plane(3, 1.0, 0, 1.0);
  f.planes[frustum_plane::right] = plane(3, 1.0, 0, -1.0);
  f.planes[frustum_plane::bottom] = plane(3, 1.0, 1, 1.0);
  f.planes[frustum_plane::top] = plane(3, 1.0, 1, -1.0);
  f.planes[frustum_plane::near] = plane(2, 1.0, 2, 0.0);
  f.planes[frustum_plane::far] = plane(3, 1.0, 2, -1.0);
  return f;
}

// The same floats the batch calls hand their kernel, through the same splat.
lanes::FrustumL<float> lanes_of(const Frustum& f) {
  float rows[6][4];
  for (int k = 0; k < 6; ++k) {
    const Plane& p = f.planes[k];
    rows[k][0] = p.normal.x, rows[k][1] = p.normal.y, rows[k][2] = p.normal.z, rows[k][3] = p.distance;
  }
  return lanes::splat_frustum<float>(rows);
}

template <class Shape> Containment classify_shape(const Frustum& f, const Shape& s) {
  const auto side = lanes::frustum_side(lanes_of(f), lanes::lanes_of(s));
  return side.outside ? Containment::outside : side.inside ? Containment::inside : Containment::intersecting;
}

template <class Shape> bool visible(const Frustum& f, const Shape& s) {
  return !lanes::frustum_side(lanes_of(f), lanes::lanes_of(s)).outside;
}

Status check_frustum(const Frustum& f) {
  for (int k = 0; k < 6; ++k) {
    const Plane& p = f.planes[k];
    if (!detail::is_finite(p.normal.x) || !detail::is_finite(p.normal.y) || !detail::is_finite(p.normal.z) ||
        !detail::is_finite(p.distance))
      return fail(Status::non_finite, "frustum.planes[%d] is not finite", k);
    const double n2 = (double(p.normal.x) * p.normal.x + double(p.normal.y) * p.normal.y) + double(p.normal.z) * p.normal.z;
    if (!(std::abs(n2 - 1.0) <= 2e-3))
      return fail(Status::invalid_argument, "frustum.planes[%d].normal has length %g: must be unit length", k,
                  std::sqrt(n2));
  }
  return Status::ok;
}

Status cull(const Frustum& f, const ShapeArray& shapes, std::size_t count, uint32_t* visible_out) {
  if (count > kMaxCount) return fail(Status::invalid_count, "count = %zu: must be below 2^31", count);
  if (count == 0) return Status::ok;
  GYRO_TRY(detail::require_not_null(visible_out, "visible_out"));
  GYRO_TRY(check_frustum(f));
  GYRO_TRY(detail::check_shape_array(shapes, count, "shapes", true));

  detail::FloatEnvGuard env;
  FrustumCullArgs args{};
  for (int k = 0; k < 6; ++k) {
    const Plane& p = f.planes[k];
    args.planes[k][0] = p.normal.x, args.planes[k][1] = p.normal.y, args.planes[k][2] = p.normal.z;
    args.planes[k][3] = p.distance;
  }
  args.shapes = shapes;
  args.visible_out = visible_out;
  auto* kernel = GYRO_DISPATCH(frustum_cull_batch);
  detail::parallel_for(count, kCullChunk, [&](std::size_t b, std::size_t e) { kernel(args, b, e); });
  return Status::ok;
}

}  // namespace

Frustum frustum(const mat4& view_projection) { return extract(to_double(view_projection)); }

Frustum frustum(const mat4& view, const mat4& projection) {
  Mat4d vp;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = double(view.m[i][0]) * projection.m[0][j];
      for (int k = 1; k < 4; ++k) s = s + double(view.m[i][k]) * projection.m[k][j];
      vp.m[i][j] = s;
    }
  return extract(vp);
}

Frustum frustum(const Camera& camera) { return frustum(view_matrix(camera), projection_matrix(camera)); }

void frustum_corners(const Frustum& f, vec3 corners[8]) {
  struct V {
    double x, y, z;
  };
  auto vec = [](const vec3& v) { return V{v.x, v.y, v.z}; };
  auto cross = [](const V& a, const V& b) { return V{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; };
  auto dot = [](const V& a, const V& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; };
  for (int k = 0; k < 8; ++k) {
    const Plane& a = f.planes[(k & 1) ? frustum_plane::right : frustum_plane::left];
    const Plane& b = f.planes[(k & 2) ? frustum_plane::top : frustum_plane::bottom];
    const Plane& c = f.planes[(k & 4) ? frustum_plane::far : frustum_plane::near];
    // The point on all three planes n_i . p = d_i: (d_a (n_b x n_c) + d_b (n_c x n_a) +
    // d_c (n_a x n_b)) / (n_a . (n_b x n_c)), Cramer's rule written with cross products.
    const V na = vec(a.normal), nb = vec(b.normal), nc = vec(c.normal);
    const V bc = cross(nb, nc), ca = cross(nc, na), ab = cross(na, nb);
    const double det = dot(na, bc);
    const double da = a.distance, db = b.distance, dc = c.distance;
    const double inv = det != 0.0 ? 1.0 / det : __builtin_nan("");
    corners[k] = {float(((da * bc.x + db * ca.x) + dc * ab.x) * inv), float(((da * bc.y + db * ca.y) + dc * ab.y) * inv),
                  float(((da * bc.z + db * ca.z) + dc * ab.z) * inv)};
  }
}

bool contains(const Frustum& f, const vec3& point) { return visible(f, Sphere{point, 0.0f}); }
bool intersects(const Frustum& f, const Sphere& sphere) { return visible(f, sphere); }
bool intersects(const Frustum& f, const AABB& box) { return visible(f, box); }
bool intersects(const Frustum& f, const OBB& box) { return visible(f, box); }

Containment classify(const Frustum& f, const Sphere& sphere) { return classify_shape(f, sphere); }
Containment classify(const Frustum& f, const AABB& box) { return classify_shape(f, box); }
Containment classify(const Frustum& f, const OBB& box) { return classify_shape(f, box); }

Status frustum_cull(const Frustum& f, const SpheresView& spheres, std::size_t count, uint32_t* visible_out) {
  return cull(f, shape_array(spheres), count, visible_out);
}
Status frustum_cull(const Frustum& f, const AabbsView& boxes, std::size_t count, uint32_t* visible_out) {
  return cull(f, shape_array(boxes), count, visible_out);
}
Status frustum_cull(const Frustum& f, const ObbsView& boxes, std::size_t count, uint32_t* visible_out) {
  return cull(f, shape_array(boxes), count, visible_out);
}

}  // namespace gyro
