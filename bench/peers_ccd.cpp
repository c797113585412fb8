// libccd as a peer: GJK and MPR (intersection and penetration) with a box support
// function evaluated in double from the same float inputs.
#include "peers.hpp"

#if defined(GYRO_BENCH_HAS_CCD)
#include <ccd/ccd.h>
#include <ccd/vec3.h>
#endif

namespace gyro::bench {

#if defined(GYRO_BENCH_HAS_CCD)
namespace {
struct Box {
  double c[3], h[3], r[9];  // r row-major, column k = local axis k
};

Box box_of(const testing::BoxSet& s, std::size_t k) {
  Box b{{s.cx[k], s.cy[k], s.cz[k]}, {s.hx[k], s.hy[k], s.hz[k]}, {}};
  for (int e = 0; e < 9; ++e) b.r[e] = s.r[e][k];
  return b;
}

void support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const Box& b = *static_cast<const Box*>(obj);
  double local[3];
  for (int k = 0; k < 3; ++k) {  // R^T dir: component along axis k
    const double d = b.r[k] * dir->v[0] + b.r[3 + k] * dir->v[1] + b.r[6 + k] * dir->v[2];
    local[k] = d >= 0 ? b.h[k] : -b.h[k];
  }
  for (int row = 0; row < 3; ++row)
    out->v[row] = b.c[row] + b.r[3 * row] * local[0] + b.r[3 * row + 1] * local[1] + b.r[3 * row + 2] * local[2];
}

void center(const void* obj, ccd_vec3_t* out) {
  const Box& b = *static_cast<const Box*>(obj);
  out->v[0] = b.c[0], out->v[1] = b.c[1], out->v[2] = b.c[2];
}
}  // namespace

bool ccd_available() { return true; }

void ccd_box_box(const testing::BoxPairs& p, std::size_t n, CcdMethod method, PairResults& out) {
  out.hit.assign(n, 0);
  out.depth.assign(n, 0.0);
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = support;
  ccd.support2 = support;
  ccd.center1 = center;
  ccd.center2 = center;
  ccd.max_iterations = 100;
  ccd.epa_tolerance = 1e-6;
  ccd.mpr_tolerance = 1e-6;
  for (std::size_t i = 0; i < n; ++i) {
    const Box a = box_of(p.a, i), b = box_of(p.b, i);
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    switch (method) {
      case CcdMethod::gjk_intersect: out.hit[i] = ccdGJKIntersect(&a, &b, &ccd) != 0; break;
      case CcdMethod::mpr_intersect: out.hit[i] = ccdMPRIntersect(&a, &b, &ccd) != 0; break;
      case CcdMethod::gjk_epa_penetration: out.hit[i] = ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos) == 0; break;
      case CcdMethod::mpr_penetration: out.hit[i] = ccdMPRPenetration(&a, &b, &ccd, &depth, &dir, &pos) == 0; break;
    }
    out.depth[i] = out.hit[i] ? double(depth) : 0.0;
  }
}
#else
bool ccd_available() { return false; }
void ccd_box_box(const testing::BoxPairs&, std::size_t, CcdMethod, PairResults&) {}
#endif

}  // namespace gyro::bench
