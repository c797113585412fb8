// Embree 3 as a peer (Debian's build: dispatches to the best ISA of the CPU at run time):
// a triangle scene for R2/LIDAR/CAMERA and a sphere-point scene for R1, traced with
// rtcIntersect1 in a loop or rtcIntersect16 packets. Build cost is measured from
// rtcNewScene to the end of rtcCommitScene; memory through the device's memory monitor
// (the vertex/index buffers are shared with the caller, so only Embree's own BVH and
// leaf data are counted).
#include "peers.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#if defined(GYRO_BENCH_HAS_EMBREE)
#include <embree3/rtcore.h>
#endif

namespace gyro::bench {

#if defined(GYRO_BENCH_HAS_EMBREE)

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<float> vertices;    // AoS, padded: Embree may read 16 bytes at the last vertex
  std::vector<uint32_t> indices;  // 3 per triangle, padded likewise
  std::atomic<int64_t> bytes{0}, peak{0};
  RTCGeometry moving = nullptr;  // moving_spheres()' geometry, one reference held here
  bool moving_user = false;      // whether it is user geometry (no vertex buffer)

  ~Impl() {
    if (moving) rtcReleaseGeometry(moving);
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

bool monitor(void* user, ssize_t bytes, bool /*post*/) {
  auto* impl = static_cast<EmbreeScene::Impl*>(user);
  const int64_t now = impl->bytes += bytes;
  int64_t peak = impl->peak.load();
  while (now > peak && !impl->peak.compare_exchange_weak(peak, now)) {
  }
  return true;
}

std::unique_ptr<EmbreeScene::Impl> new_device(uint32_t build_threads) {
  auto impl = std::make_unique<EmbreeScene::Impl>();
  const std::string config = "threads=" + std::to_string(std::max(1u, build_threads));
  impl->device = rtcNewDevice(config.c_str());
  if (!impl->device) return nullptr;
  rtcSetDeviceMemoryMonitorFunction(impl->device, monitor, impl.get());
  return impl;
}

// Commits the geometry into a new scene and times the build; fills `build`.
bool commit(EmbreeScene::Impl& impl, RTCGeometry geom, RTCSceneFlags flags, std::chrono::steady_clock::time_point start,
            PeerBuild& build) {
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl.scene, geom);
  rtcReleaseGeometry(geom);
  rtcSetSceneFlags(impl.scene, flags);
  rtcCommitScene(impl.scene);
  const auto end = std::chrono::steady_clock::now();
  build.ms = std::chrono::duration<double, std::milli>(end - start).count();
  build.bytes = std::size_t(std::max<int64_t>(0, impl.bytes.load()));
  build.peak_bytes = std::size_t(std::max<int64_t>(0, impl.peak.load()));
  return rtcGetDeviceError(impl.device) == RTC_ERROR_NONE;
}

// The rays of the one-ray and the 16-ray calls, as every method traces them.
void set_ray(RTCRay& ray, const testing::RaySet& r, std::size_t i, float tmax) {
  ray.org_x = r.ox[i], ray.org_y = r.oy[i], ray.org_z = r.oz[i], ray.tnear = 0.0f;
  ray.dir_x = r.dx[i], ray.dir_y = r.dy[i], ray.dir_z = r.dz[i], ray.time = 0.0f;
  ray.tfar = tmax, ray.mask = ~0u, ray.id = 0, ray.flags = 0;
}

void set_ray(RTCRay16& ray, int k, const testing::RaySet& r, std::size_t i, float tmax) {
  ray.org_x[k] = r.ox[i], ray.org_y[k] = r.oy[i], ray.org_z[k] = r.oz[i], ray.tnear[k] = 0.0f;
  ray.dir_x[k] = r.dx[i], ray.dir_y[k] = r.dy[i], ray.dir_z[k] = r.dz[i], ray.time[k] = 0.0f;
  ray.tfar[k] = tmax, ray.mask[k] = ~0u, ray.id[k] = unsigned(k), ray.flags[k] = 0;
}

// Occluded: rtcOccluded1 (any hit: Embree sets tfar to -inf on a hit and reports no t or
// primitive, written as t = 0 and primitive 0), else rtcIntersect1.
template <bool Occluded>
void trace_range1(RTCScene scene, const testing::RaySet& r, std::size_t begin, std::size_t end, float tmax,
                  RayResults& out) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t i = begin; i < end; ++i) {
    RTCRayHit rh;
    set_ray(rh.ray, r, i, tmax);
    bool hit;
    if constexpr (Occluded) {
      rtcOccluded1(scene, &context, &rh.ray);
      hit = rh.ray.tfar < 0.0f;
      rh.ray.tfar = 0.0f, rh.hit.primID = 0;
    } else {
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    out.t[i] = hit ? rh.ray.tfar : std::numeric_limits<float>::infinity();
    out.primitive[i] = hit ? int32_t(rh.hit.primID) : -1;
  }
}

// trace_range1 in packets of 16 consecutive rays (rtcOccluded16 or rtcIntersect16).
template <bool Occluded>
void trace_range16(RTCScene scene, const testing::RaySet& r, std::size_t begin, std::size_t end, float tmax,
                   RayResults& out) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t p = begin; p < end; p += 16) {
    alignas(64) int valid[16];
    RTCRayHit16 rh;
    for (int k = 0; k < 16; ++k) {
      const std::size_t i = p + std::size_t(k);
      const bool live = i < end;
      valid[k] = live ? -1 : 0;
      set_ray(rh.ray, k, r, live ? i : begin, tmax);  // a finite ray in the dead lanes
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID, rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    if constexpr (Occluded) rtcOccluded16(valid, scene, &context, &rh.ray);
    else rtcIntersect16(valid, scene, &context, &rh);
    for (int k = 0; k < 16 && p + std::size_t(k) < end; ++k) {
      const std::size_t i = p + std::size_t(k);
      const bool hit = Occluded ? rh.ray.tfar[k] < 0.0f : rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      out.t[i] = !hit ? std::numeric_limits<float>::infinity() : Occluded ? 0.0f : rh.ray.tfar[k];
      out.primitive[i] = !hit ? -1 : Occluded ? 0 : int32_t(rh.hit.primID[k]);
    }
  }
}

}  // namespace

bool embree_available() { return true; }
const char* embree_version() { return RTC_VERSION_STRING; }
bool embree_native_ray16() {
  RTCDevice d = rtcNewDevice("threads=1");
  if (!d) return false;
  const bool native = rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  rtcReleaseDevice(d);
  return native;
}

EmbreeScene::EmbreeScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EmbreeScene::~EmbreeScene() = default;

std::unique_ptr<EmbreeScene> EmbreeScene::triangles(const MeshData& mesh, bool robust, uint32_t build_threads,
                                                    PeerBuild& build) {
  auto impl = new_device(build_threads);
  if (!impl) return nullptr;
  const std::size_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
  impl->vertices.resize(3 * nv + 1);
  for (std::size_t v = 0; v < nv; ++v)
    impl->vertices[3 * v] = mesh.x[v], impl->vertices[3 * v + 1] = mesh.y[v], impl->vertices[3 * v + 2] = mesh.z[v];
  impl->indices.assign(mesh.indices.begin(), mesh.indices.end());
  impl->indices.push_back(0);
  impl->bytes = 0, impl->peak = 0;
  const auto start = std::chrono::steady_clock::now();
  impl->scene = rtcNewScene(impl->device);
  RTCGeometry geom = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, impl->vertices.data(), 0,
                             3 * sizeof(float), nv);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, impl->indices.data(), 0,
                             3 * sizeof(uint32_t), nt);
  if (!commit(*impl, geom, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE, start, build)) return nullptr;
  return std::unique_ptr<EmbreeScene>(new EmbreeScene(std::move(impl)));
}

std::unique_ptr<EmbreeScene> EmbreeScene::spheres(const testing::SphereSet& s, uint32_t build_threads,
                                                  PeerBuild& build) {
  return moving_spheres(s, Update::rebuild, false, build_threads, build);
}

namespace {

// User-geometry spheres: their float4 (x, y, z, r) in the scene's vertex copy.
void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const float* v = static_cast<const float*>(args->geometryUserPtr) + 4 * std::size_t(args->primID);
  RTCBounds& b = *args->bounds_o;
  b.lower_x = v[0] - v[3], b.lower_y = v[1] - v[3], b.lower_z = v[2] - v[3];
  b.upper_x = v[0] + v[3], b.upper_y = v[1] + v[3], b.upper_z = v[2] + v[3];
}

// The roots of ray i against sphere v (float4 x, y, z, r), in binary64 like R1's reference;
// false when it misses the sphere's line. o: the origin relative to the centre.
bool sphere_roots(const float* v, RTCRayN* ray, unsigned N, unsigned i, double o[3], double d[3], float& t0, float& t1) {
  o[0] = RTCRayN_org_x(ray, N, i) - double(v[0]), o[1] = RTCRayN_org_y(ray, N, i) - double(v[1]);
  o[2] = RTCRayN_org_z(ray, N, i) - double(v[2]);
  d[0] = RTCRayN_dir_x(ray, N, i), d[1] = RTCRayN_dir_y(ray, N, i), d[2] = RTCRayN_dir_z(ray, N, i);
  const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
  const double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - double(v[3]) * v[3];
  const double disc = b * b - a * c;
  if (!(disc >= 0.0)) return false;
  const double root = std::sqrt(disc);
  t0 = float((-b - root) / a), t1 = float((-b + root) / a);
  return true;
}

// The nearer root in [tnear, tfar], else the farther (a ray starting inside reports its
// exit, as the sphere-point geometry does).
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const float* v = static_cast<const float*>(args->geometryUserPtr) + 4 * std::size_t(args->primID);
  const unsigned N = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, N);
  for (unsigned i = 0; i < N; ++i) {
    double o[3], d[3];
    float t0, t1;
    if (!args->valid[i] || !sphere_roots(v, ray, N, i, o, d, t0, t1)) continue;
    const float tnear = RTCRayN_tnear(ray, N, i), tfar = RTCRayN_tfar(ray, N, i);
    const float t = t0 >= tnear && t0 <= tfar ? t0 : t1;
    if (!(t >= tnear && t <= tfar)) continue;
    RTCRayN_tfar(ray, N, i) = t;
    for (unsigned k = 0; k < 3; ++k) (&RTCHitN_Ng_x(hit, N, i))[k * N] = float(o[k] + t * d[k]);
    RTCHitN_u(hit, N, i) = 0.0f, RTCHitN_v(hit, N, i) = 0.0f;
    RTCHitN_primID(hit, N, i) = args->primID, RTCHitN_geomID(hit, N, i) = args->geomID;
    RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
  }
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  const float* v = static_cast<const float*>(args->geometryUserPtr) + 4 * std::size_t(args->primID);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    double o[3], d[3];
    float t0, t1;
    if (!args->valid[i] || !sphere_roots(v, args->ray, N, i, o, d, t0, t1)) continue;
    const float tnear = RTCRayN_tnear(args->ray, N, i), tfar = RTCRayN_tfar(args->ray, N, i);
    if ((t0 >= tnear && t0 <= tfar) || (t1 >= tnear && t1 <= tfar)) RTCRayN_tfar(args->ray, N, i) = -INFINITY;
  }
}

}  // namespace

std::unique_ptr<EmbreeScene> EmbreeScene::moving_spheres(const testing::SphereSet& s, Update update, bool user,
                                                         uint32_t build_threads, PeerBuild& build) {
  auto impl = new_device(build_threads);
  if (!impl) return nullptr;
  const std::size_t n = s.size();
  impl->vertices.resize(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    impl->vertices[4 * i] = s.cx[i], impl->vertices[4 * i + 1] = s.cy[i], impl->vertices[4 * i + 2] = s.cz[i],
                       impl->vertices[4 * i + 3] = s.r[i];
  impl->bytes = 0, impl->peak = 0;
  const auto start = std::chrono::steady_clock::now();
  impl->scene = rtcNewScene(impl->device);
  RTCGeometry geom = rtcNewGeometry(impl->device, user ? RTC_GEOMETRY_TYPE_USER : RTC_GEOMETRY_TYPE_SPHERE_POINT);
  if (user) {
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(n));
    rtcSetGeometryUserData(geom, impl->vertices.data());
    rtcSetGeometryBoundsFunction(geom, sphere_bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, sphere_intersect);
    rtcSetGeometryOccludedFunction(geom, sphere_occluded);
  } else {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, impl->vertices.data(), 0,
                               4 * sizeof(float), n);
  }
  RTCSceneFlags flags = RTC_SCENE_FLAG_NONE;
  if (update != Update::rebuild) {
    flags = RTC_SCENE_FLAG_DYNAMIC;
    rtcSetSceneBuildQuality(impl->scene, RTC_BUILD_QUALITY_LOW);
    rtcSetGeometryBuildQuality(geom, update == Update::refit ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_LOW);
  }
  rtcRetainGeometry(geom);  // commit() gives up the creation's reference; move_spheres() keeps using it
  impl->moving = geom, impl->moving_user = user;
  if (!commit(*impl, geom, flags, start, build)) return nullptr;
  return std::unique_ptr<EmbreeScene>(new EmbreeScene(std::move(impl)));
}

double EmbreeScene::move_spheres(const uint32_t* idx, const float* xyz, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) impl_->vertices[4 * std::size_t(idx[k]) + std::size_t(a)] = xyz[3 * k + std::size_t(a)];
  const auto start = std::chrono::steady_clock::now();
  // A user geometry has no vertex buffer: its commit alone marks it changed.
  if (!impl_->moving_user) rtcUpdateGeometryBuffer(impl_->moving, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(impl_->moving);
  rtcCommitScene(impl_->scene);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void EmbreeScene::trace(const testing::RaySet& rays, std::size_t n, float tmax, EmbreeMethod method, uint32_t threads,
                        RayResults& out) const {
  out.resize(n);
  constexpr std::size_t kChunk = 4096;  // a multiple of 16: packets never straddle chunks
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t b; (b = next.fetch_add(kChunk)) < n;) {
      const std::size_t e = std::min(n, b + kChunk);
      switch (method) {
        case EmbreeMethod::intersect1: trace_range1<false>(impl_->scene, rays, b, e, tmax, out); break;
        case EmbreeMethod::intersect16: trace_range16<false>(impl_->scene, rays, b, e, tmax, out); break;
        case EmbreeMethod::occluded1: trace_range1<true>(impl_->scene, rays, b, e, tmax, out); break;
        case EmbreeMethod::occluded16: trace_range16<true>(impl_->scene, rays, b, e, tmax, out); break;
      }
    }
  };
  std::vector<std::thread> pool;
  for (uint32_t k = 1; k < threads; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

#else

struct EmbreeScene::Impl {};
bool embree_available() { return false; }
const char* embree_version() { return "none"; }
bool embree_native_ray16() { return false; }
EmbreeScene::EmbreeScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EmbreeScene::~EmbreeScene() = default;
std::unique_ptr<EmbreeScene> EmbreeScene::triangles(const MeshData&, bool, uint32_t, PeerBuild&) { return nullptr; }
std::unique_ptr<EmbreeScene> EmbreeScene::spheres(const testing::SphereSet&, uint32_t, PeerBuild&) { return nullptr; }
std::unique_ptr<EmbreeScene> EmbreeScene::moving_spheres(const testing::SphereSet&, Update, bool, uint32_t,
                                                         PeerBuild&) {
  return nullptr;
}
double EmbreeScene::move_spheres(const uint32_t*, const float*, std::size_t) { return 0.0; }
void EmbreeScene::trace(const testing::RaySet&, std::size_t n, float, EmbreeMethod, uint32_t, RayResults& out) const {
  out.resize(n);
}

#endif

}  // namespace gyro::bench
