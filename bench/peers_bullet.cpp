// Bullet 3 (Debian's single-precision build) as a peer: btBoxBoxDetector on N1.
#include "peers.hpp"

#if defined(GYRO_BENCH_HAS_BULLET)
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
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
#else
bool bullet_available() { return false; }
void bullet_box_box(const testing::BoxPairs&, std::size_t, PairResults&) {}
#endif

}  // namespace gyro::bench
