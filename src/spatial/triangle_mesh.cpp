// TriangleMesh: validation, the BVH, and every query over it. Raycasts go through the
// per-level BVH kernel (bvh_kernels.cpp), single rays included, so one ray and a batch give
// the same bits. Overlap queries walk the tree with a conservative box test and run the
// scalar triangle tests of gyro/triangle.hpp on the leaves.
#include "gyro/triangle_mesh.hpp"

#include "core/float_env.hpp"
#include "core/parallel.hpp"
#include "core/validate.hpp"
#include "geometry/ray_triangle_lanes.hpp"
#include "geometry/shape_checks.hpp"
#include "gyro/triangle.hpp"
#include "spatial/bvh.hpp"
#include "spatial/bvh_batch.hpp"

#include <algorithm>

namespace gyro {

struct TriangleMesh::Impl {
  MeshData mesh;
  detail::Bvh8 bvh;
};

namespace {

using detail::fail;
namespace lanes = GYRO_ARCH_NS;

constexpr float kInf = __builtin_inff();
constexpr std::size_t kMaxCount = 0x7FFFFFFF;
// Rays per chunk: BVH rays cost about a microsecond each, so chunks this small still balance
// threads well, and large enough that the kernel's sixteen rays in flight rarely run short.
// Rays are walked in input order. Sorting them first (Morton codes of where each enters and
// leaves the mesh's box) sped R2's walk up by 12-13% when all 10^6 were sorted, by 4% when
// sorted in windows of 2^14 (whose gathers stay in the cache), while the keys, the sort and
// the gathers and scatters cost as much as that or more: 3.1-3.7 against 4.1 Mrays/s for
// the batch as a whole, measured side by side (one thread, 2026-12-07).
constexpr std::size_t kRayChunk = 256;

// Normal facing the ray and the barycentric weights of b and c, for the winning triangle
// (the scalar instantiation of the batch's templates: the same bits at every level).
void hit_details(const Triangle& tri, const vec3& o, const vec3& d, vec3& normal, float& u, float& v) {
  const lanes::TriangleL<float> t{{tri.a.x, tri.a.y, tri.a.z}, {tri.b.x, tri.b.y, tri.b.z}, {tri.c.x, tri.c.y, tri.c.z}};
  const lanes::RayL<float> ray{{o.x, o.y, o.z}, {d.x, d.y, d.z}};
  const lanes::V3<float> n = lanes::triangle_normal_facing(t, ray.d);
  float wa, wb, wc;
  lanes::ray_triangle_t(lanes::watertight_ray(ray), t, 0.0f, kInf, wa, wb, wc);
  normal = {n.x, n.y, n.z};
  u = wb, v = wc;
}

void trace(const TriangleMesh::Impl& m, const Ray& ray, float tmin, float tmax, bool any, float& t, uint32_t& id) {
  const BvhRaycastArgs args{&m.bvh, &ray.origin.x, &ray.origin.y, &ray.origin.z, &ray.direction.x,
                            &ray.direction.y, &ray.direction.z, &tmin, &tmax, any, &t, &id};
  detail::FloatEnvGuard env;
  GYRO_DISPATCH(bvh_raycast)(args, 0, 1);
}

// Calls leaf(block, lane) for every triangle in a leaf whose box overlaps [lo, hi] (closed),
// until it returns true; returns whether it did.
template <class Leaf> bool any_in_box(const TriangleMesh::Impl& m, const vec3& lo, const vec3& hi, Leaf&& leaf) {
  const detail::Bvh8& bvh = m.bvh;
  uint32_t stack[detail::kBvhStackSize];
  int sp = 0;
  stack[sp++] = 0;
  const float qlo[3] = {lo.x, lo.y, lo.z}, qhi[3] = {hi.x, hi.y, hi.z};
  while (sp > 0) {
    const uint32_t code = stack[--sp];
    if (code & detail::kLeafBit) {
      const detail::BvhLeaf4& l = bvh.leaves[code & ~detail::kLeafBit];
      for (int k = 0; k < 4; ++k)
        if (l.triangle[k] != detail::kNoTriangle && leaf(l, k)) return true;
      continue;
    }
    const detail::BvhNode8& node = bvh.nodes[code];
    for (int k = 7; k >= 0; --k) {
      if (node.child[k] == detail::kEmptyChild) continue;
      bool in = true;
      for (int a = 0; a < 3; ++a) in = in && node.bounds[2 * a][k] <= qhi[a] && qlo[a] <= node.bounds[2 * a + 1][k];
      if (in) stack[sp++] = node.child[k];
    }
  }
  return false;
}

// The query box of a shape, widened by 2^-20 of its coordinates' magnitude so the rounding
// of c - r or c + r can never drop a triangle the exact test touches.
void widen(vec3& lo, vec3& hi) {
  const float m = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y),
                            std::abs(hi.z), 1e-30f}) * 0x1p-20f;
  lo = lo - vec3{m, m, m};
  hi = hi + vec3{m, m, m};
}

template <class Shape> bool overlaps_any(const TriangleMesh& mesh, const Shape& shape, vec3 lo, vec3 hi) {
  if (mesh.empty()) return false;
  widen(lo, hi);
  const auto& m = *mesh.impl();
  return any_in_box(m, lo, hi,
                    [&](const detail::BvhLeaf4& l, int k) { return overlaps(m.mesh.triangle(l.triangle[k]), shape); });
}

Status run_batch(const TriangleMesh& mesh, const RaysView& rays, std::size_t ray_count, const HitsOut& hits, bool any) {
  if (mesh.empty()) return fail(Status::invalid_argument, "mesh: not created (TriangleMesh::create failed or was not called)");
  if (ray_count > kMaxCount) return fail(Status::invalid_count, "ray count %zu must be below 2^31", ray_count);
  if (ray_count == 0) return Status::ok;
  GYRO_TRY(detail::require_not_null(hits.t, "hits.t"));
  GYRO_TRY(detail::require_not_null(hits.primitive, "hits.primitive"));
  GYRO_TRY(detail::check_hit_columns(hits.nx, hits.ny, hits.nz, hits.u, hits.v));
  const bool normals = hits.nx != nullptr;  // all three, checked above
  GYRO_TRY(detail::check_rays(rays, ray_count, false));  // bad values are flagged per ray

  detail::FloatEnvGuard env;
  const auto& m = *mesh.impl();
  const BvhRaycastArgs args{&m.bvh, rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz, rays.tmin, rays.tmax,
                            any, hits.t, reinterpret_cast<uint32_t*>(hits.primitive)};
  auto* kernel = GYRO_DISPATCH(bvh_raycast);
  const bool details = normals || hits.u != nullptr;
  detail::parallel_for(ray_count, kRayChunk, [&](std::size_t b, std::size_t e) {
    kernel(args, b, e);
    if (!details) return;
    for (std::size_t i = b; i < e; ++i) {
      vec3 n{0.0f, 0.0f, 0.0f};
      float u = 0.0f, v = 0.0f;
      const int32_t k = hits.primitive[i];
      if (k >= 0)
        hit_details(m.mesh.triangle(std::size_t(k)), {rays.ox[i], rays.oy[i], rays.oz[i]},
                    {rays.dx[i], rays.dy[i], rays.dz[i]}, n, u, v);
      if (normals) hits.nx[i] = n.x, hits.ny[i] = n.y, hits.nz[i] = n.z;
      if (hits.u) hits.u[i] = u, hits.v[i] = v;
    }
  });
  return Status::ok;
}

}  // namespace

TriangleMesh::TriangleMesh() = default;
TriangleMesh::~TriangleMesh() = default;
TriangleMesh::TriangleMesh(TriangleMesh&&) noexcept = default;
TriangleMesh& TriangleMesh::operator=(TriangleMesh&&) noexcept = default;

Status TriangleMesh::create(const MeshData& mesh, TriangleMesh& out) {
  GYRO_TRY(validate_mesh(mesh));
  auto impl = std::make_unique<Impl>();
  impl->mesh = mesh;
  impl->bvh = detail::build_bvh8(impl->mesh);
  impl->bvh.stats.bytes += impl->mesh.indices.size() * sizeof(uint32_t) + impl->mesh.x.size() * 3 * sizeof(float);
  out.impl_ = std::move(impl);
  return Status::ok;
}

std::size_t TriangleMesh::triangle_count() const { return impl_ ? impl_->mesh.triangle_count() : 0; }
const MeshData& TriangleMesh::data() const {
  static const MeshData kEmpty;
  return impl_ ? impl_->mesh : kEmpty;
}
Triangle TriangleMesh::triangle(std::size_t i) const { return impl_->mesh.triangle(i); }
AABB TriangleMesh::bounds() const { return impl_ ? impl_->bvh.bounds : AABB{{0, 0, 0}, {0, 0, 0}}; }
BvhStats TriangleMesh::stats() const { return impl_ ? impl_->bvh.stats : BvhStats{}; }

std::size_t TriangleMesh::triangles_overlapping(const AABB& box, uint32_t* out, std::size_t capacity) const {
  if (!impl_) return 0;
  const vec3 lo = aabb_min(box), hi = aabb_max(box);
  std::size_t count = 0;
  // out[0, min(count, capacity)) is a max-heap of the smallest indices found so far, so the
  // kept set, and after sorting the output, does not depend on the traversal order.
  any_in_box(*impl_, lo, hi, [&](const detail::BvhLeaf4& l, int k) {
    for (int a = 0; a < 3; ++a) {
      const float p = l.corner[a][k], q = l.corner[3 + a][k], r = l.corner[6 + a][k];
      if (!(std::min({p, q, r}) <= hi[a] && lo[a] <= std::max({p, q, r}))) return false;
    }
    const uint32_t t = l.triangle[k];
    if (count < capacity) {
      out[count] = t;
      std::push_heap(out, out + count + 1);
    } else if (capacity > 0 && t < out[0]) {
      std::pop_heap(out, out + capacity);
      out[capacity - 1] = t;
      std::push_heap(out, out + capacity);
    }
    ++count;
    return false;
  });
  std::sort_heap(out, out + std::min(count, capacity));
  return count;
}

MeshHit raycast(const TriangleMesh& mesh, const Ray& ray, float tmin, float tmax) {
  MeshHit out;
  if (mesh.empty()) return out;
  float t = kInf;
  uint32_t id = detail::kNoTriangle;
  trace(*mesh.impl(), ray, tmin, tmax, false, t, id);
  if (id == detail::kNoTriangle || id == detail::kInvalidRay) return out;
  out.hit.hit = true;
  out.hit.t = t;
  out.hit.point = ray.origin + ray.direction * t;
  out.triangle = id;
  hit_details(mesh.triangle(id), ray.origin, ray.direction, out.hit.normal, out.u, out.v);
  return out;
}

bool raycast_any(const TriangleMesh& mesh, const Ray& ray, float tmin, float tmax) {
  if (mesh.empty()) return false;
  float t = kInf;
  uint32_t id = detail::kNoTriangle;
  trace(*mesh.impl(), ray, tmin, tmax, true, t, id);
  return id != detail::kNoTriangle && id != detail::kInvalidRay;
}

bool linetest(const TriangleMesh& mesh, const Line& line) {
  if (mesh.empty()) return false;
  if (line.start == line.end) {
    vec3 lo = line.start, hi = line.start;
    widen(lo, hi);
    const auto& m = *mesh.impl();
    return any_in_box(m, lo, hi, [&](const detail::BvhLeaf4& l, int k) {
      return contains(m.mesh.triangle(l.triangle[k]), line.start);
    });
  }
  return raycast_any(mesh, ray_from_points(line.start, line.end), 0.0f, 1.0f);
}

bool overlaps(const TriangleMesh& mesh, const Sphere& s) {
  const vec3 r{s.radius, s.radius, s.radius};
  return overlaps_any(mesh, s, s.center - r, s.center + r);
}

bool overlaps(const TriangleMesh& mesh, const AABB& b) {
  return overlaps_any(mesh, b, aabb_min(b), aabb_max(b));
}

bool overlaps(const TriangleMesh& mesh, const OBB& b) {
  vec3 ext{0.0f, 0.0f, 0.0f};
  const float e[3] = {b.half_extents.x, b.half_extents.y, b.half_extents.z};
  for (int k = 0; k < 3; ++k) {
    const vec3 axis{b.orientation.m[k][0], b.orientation.m[k][1], b.orientation.m[k][2]};
    ext = ext + vec3{std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)} * e[k];
  }
  return overlaps_any(mesh, b, b.center - ext, b.center + ext);
}

bool overlaps(const TriangleMesh& mesh, const Triangle& t) {
  const vec3 lo{std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}), std::min({t.a.z, t.b.z, t.c.z})};
  const vec3 hi{std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}), std::max({t.a.z, t.b.z, t.c.z})};
  return overlaps_any(mesh, t, lo, hi);
}

Status raycast_closest(const TriangleMesh& mesh, const RaysView& rays, std::size_t ray_count, const HitsOut& hits) {
  return run_batch(mesh, rays, ray_count, hits, false);
}

Status raycast_any(const TriangleMesh& mesh, const RaysView& rays, std::size_t ray_count, const HitsOut& hits) {
  return run_batch(mesh, rays, ray_count, hits, true);
}

}  // namespace gyro
