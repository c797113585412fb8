// Bullet 3 (Debian's single-precision build) as a peer: btBoxBoxDetector on N1; ray tests
// (btCollisionWorld::rayTest, closest hit) against a btBvhTriangleMeshShape for the R2
// terrain and against btSphereShape objects for R1.
#include "peers.hpp"

#include <chrono>
#include <limits>

#if defined(GYRO_BENCH_HAS_BULLET)
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btOptimizedBvh.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#endif

namespace gyro::bench {

#if defined(GYRO_BENCH_HAS_BULLET)
namespace {
struct DeepestContact : btDiscreteCollisionDetectorInterface::Result {
  bool hit = false;
  double depth = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar distance) override {
    // Bullet's distance is negative when penetrating.
    if (!hit || -distance > depth) depth = -distance;
    hit = true;
  }
};

btTransform transform_of(const testing::BoxSet& s, std::size_t k) {
  const btMatrix3x3 r(s.r[0][k], s.r[1][k], s.r[2][k], s.r[3][k], s.r[4][k], s.r[5][k], s.r[6][k], s.r[7][k], s.r[8][k]);
  return btTransform(r, btVector3(s.cx[k], s.cy[k], s.cz[k]));
}
}  // namespace

bool bullet_available() { return true; }

void bullet_box_box(const testing::BoxPairs& p, std::size_t n, PairResults& out) {
  out.hit.assign(n, 0);
  out.depth.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    btBoxShape a(btVector3(p.a.hx[i], p.a.hy[i], p.a.hz[i])), b(btVector3(p.b.hx[i], p.b.hy[i], p.b.hz[i]));
    // btBoxShape keeps its margin inside the given half extents; the detector uses the
    // extents with the margin added back, so the boxes are exactly the given ones.
    btBoxBoxDetector detector(&a, &b);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = transform_of(p.a, i);
    input.m_transformB = transform_of(p.b, i);
    DeepestContact result;
    detector.getClosestPoints(input, result, nullptr);
    out.hit[i] = result.hit;
    out.depth[i] = result.hit ? result.depth : 0.0;
  }
}

struct BulletRayWorld::Impl {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &config};
  // Mesh input in the layout Bullet reads (it keeps pointers, copies nothing).
  std::vector<btScalar> vertices;
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> arrays;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;

  ~Impl() {
    for (auto& o : objects) world.removeCollisionObject(o.get());
  }
  void add(std::unique_ptr<btCollisionShape> shape, const btVector3& at, int index) {
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shape.get());
    object->setWorldTransform(btTransform(btMatrix3x3::getIdentity(), at));
    object->setUserIndex(index);
    world.addCollisionObject(object.get());
    shapes.push_back(std::move(shape));
    objects.push_back(std::move(object));
  }
};

namespace {
// Closest hit that also remembers the primitive: the triangle index for a mesh, the
// object's user index (the sphere) otherwise.
struct ClosestWithIndex : btCollisionWorld::ClosestRayResultCallback {
  using btCollisionWorld::ClosestRayResultCallback::ClosestRayResultCallback;
  int index = -1;
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normal_in_world) override {
    index = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : r.m_collisionObject->getUserIndex();
    return ClosestRayResultCallback::addSingleResult(r, normal_in_world);
  }
};

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

BulletRayWorld::BulletRayWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BulletRayWorld::~BulletRayWorld() = default;

std::unique_ptr<BulletRayWorld> BulletRayWorld::triangles(const MeshData& mesh, PeerBuild& build) {
  auto impl = std::make_unique<Impl>();
  const std::size_t nv = mesh.vertex_count();
  impl->vertices.resize(3 * nv);
  for (std::size_t v = 0; v < nv; ++v)
    impl->vertices[3 * v] = mesh.x[v], impl->vertices[3 * v + 1] = mesh.y[v], impl->vertices[3 * v + 2] = mesh.z[v];
  impl->indices.assign(mesh.indices.begin(), mesh.indices.end());
  const auto start = std::chrono::steady_clock::now();
  impl->arrays = std::make_unique<btTriangleIndexVertexArray>(int(mesh.triangle_count()), impl->indices.data(),
                                                              int(3 * sizeof(int)), int(nv), impl->vertices.data(),
                                                              int(3 * sizeof(btScalar)));
  auto shape = std::make_unique<btBvhTriangleMeshShape>(impl->arrays.get(), true, true);
  const btOptimizedBvh* bvh = shape->getOptimizedBvh();
  impl->add(std::move(shape), btVector3(0, 0, 0), 0);
  impl->world.updateAabbs();
  build.ms = ms_since(start);
  build.bytes = bvh ? bvh->calculateSerializeBufferSize() : 0;
  return std::unique_ptr<BulletRayWorld>(new BulletRayWorld(std::move(impl)));
}

std::unique_ptr<BulletRayWorld> BulletRayWorld::spheres(const testing::SphereSet& s, PeerBuild& build) {
  auto impl = std::make_unique<Impl>();
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < s.size(); ++i)
    impl->add(std::make_unique<btSphereShape>(s.r[i]), btVector3(s.cx[i], s.cy[i], s.cz[i]), int(i));
  impl->world.updateAabbs();
  build.ms = ms_since(start);
  build.bytes = 0;
  return std::unique_ptr<BulletRayWorld>(new BulletRayWorld(std::move(impl)));
}

void BulletRayWorld::trace(const testing::RaySet& r, std::size_t n, float tmax, RayResults& out) const {
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const btVector3 from(r.ox[i], r.oy[i], r.oz[i]);
    const btVector3 to = from + btVector3(r.dx[i], r.dy[i], r.dz[i]) * tmax;
    ClosestWithIndex cb(from, to);
    impl_->world.rayTest(from, to, cb);
    const bool hit = cb.hasHit();
    out.t[i] =
        hit ? static_cast<float>(double(cb.m_closestHitFraction) * tmax) : std::numeric_limits<float>::infinity();
    out.primitive[i] = hit ? cb.index : -1;
  }
}

#else
bool bullet_available() { return false; }
void bullet_box_box(const testing::BoxPairs&, std::size_t, PairResults&) {}

struct BulletRayWorld::Impl {};
BulletRayWorld::BulletRayWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BulletRayWorld::~BulletRayWorld() = default;
std::unique_ptr<BulletRayWorld> BulletRayWorld::triangles(const MeshData&, PeerBuild&) { return nullptr; }
std::unique_ptr<BulletRayWorld> BulletRayWorld::spheres(const testing::SphereSet&, PeerBuild&) { return nullptr; }
void BulletRayWorld::trace(const testing::RaySet&, std::size_t n, float, RayResults& out) const { out.resize(n); }
#endif

}  // namespace gyro::bench
