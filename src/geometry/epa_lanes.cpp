// epa_lanes.hpp's kernels at this translation unit's SIMD level. Lane k computes what the
// scalar code computes for job k, operation for operation (no FMA, the same association),
// so every level gives the same bits.
#include "geometry/epa_lanes.hpp"

#include "core/lanes.hpp"
#include "geometry/epa_plane_lanes.hpp"

namespace gyro::GYRO_ARCH_NS {
namespace {

// face_plane() (epa_plane_lanes.hpp) for job i onwards.
template <class L> inline void plane(EpaPlaneJobs& j, std::size_t i) {
  const FacePlane<L> f = face_plane(load<L>(j.a[0] + i), load<L>(j.a[1] + i), load<L>(j.a[2] + i), load<L>(j.b[0] + i),
                                    load<L>(j.b[1] + i), load<L>(j.b[2] + i), load<L>(j.c[0] + i), load<L>(j.c[1] + i),
                                    load<L>(j.c[2] + i));
  store(j.n[0] + i, f.nx), store(j.n[1] + i, f.ny), store(j.n[2] + i, f.nz);
  store(j.d + i, f.d), store(j.sliver + i, f.sliver);
}

// signed_by(h, d): h, negated unless d >= 0.
template <class L> inline L signed_by(L h, L d) { return select(d >= L(0.0f), h, -h); }

// PairFrame::support for two boxes (cores): A's vertex along d, B's along -d in B's frame,
// taken to A's frame as lb * rot + pos.
template <class L> inline void box_support(EpaBoxSlots& s, std::size_t i, std::size_t rows) {
  const L dx = load<L>(s.dir[0] + i), dy = load<L>(s.dir[1] + i), dz = load<L>(s.dir[2] + i);
  const L pax = signed_by(load<L>(s.ha[0] + i), dx), pay = signed_by(load<L>(s.ha[1] + i), dy),
          paz = signed_by(load<L>(s.ha[2] + i), dz);
  L r[9];
  for (int q = 0; q < 9; ++q) r[q] = load<L>(s.rot[q] + i);
  const L db0 = -(dx * r[0] + dy * r[1] + dz * r[2]);
  const L db1 = -(dx * r[3] + dy * r[4] + dz * r[5]);
  const L db2 = -(dx * r[6] + dy * r[7] + dz * r[8]);
  const L lx = signed_by(load<L>(s.hb[0] + i), db0), ly = signed_by(load<L>(s.hb[1] + i), db1),
          lz = signed_by(load<L>(s.hb[2] + i), db2);
  const L pbx = (lx * r[0] + ly * r[3]) + lz * r[6] + load<L>(s.pos[0] + i);
  const L pby = (lx * r[1] + ly * r[4]) + lz * r[7] + load<L>(s.pos[1] + i);
  const L pbz = (lx * r[2] + ly * r[5]) + lz * r[8] + load<L>(s.pos[2] + i);
  store(s.a[0] + i, pax), store(s.a[1] + i, pay), store(s.a[2] + i, paz);
  store(s.b[0] + i, pbx), store(s.b[1] + i, pby), store(s.b[2] + i, pbz);
  const L wx = pax - pbx, wy = pay - pby, wz = paz - pbz;
  store(s.w[0] + i, wx), store(s.w[1] + i, wy), store(s.w[2] + i, wz);
  const L nv = load<L>(s.nv + i);
  auto hit = L(0.0f) > L(1.0f);
  for (std::size_t v = 0; v < rows; ++v)
    hit = hit || ((L(float(v)) < nv) && (load<L>(s.vw[0][v] + i) == wx) && (load<L>(s.vw[1][v] + i) == wy) &&
                  (load<L>(s.vw[2][v] + i) == wz));
  store(s.repeat + i, select(hit, L(1.0f), L(0.0f)));
}

}  // namespace

GYRO_FLATTEN void epa_closest(EpaClosest& c, std::size_t rows) {
  // Rows outside, vectors inside: the vectors' min chains are independent, so they overlap.
  constexpr std::size_t kVectors = EpaClosest::kSlots / width_v<Wide>;
  static_assert(EpaClosest::kSlots % width_v<Wide> == 0, "whole vectors");
  Wide nf[kVectors], m[kVectors], at[kVectors];
  for (std::size_t q = 0; q < kVectors; ++q)
    nf[q] = load<Wide>(c.nf + q * width_v<Wide>), m[q] = Wide(__builtin_huge_valf()), at[q] = Wide(-1.0f);
  for (std::size_t f = 0; f < rows; ++f) {
    const Wide row = Wide(float(f));
    for (std::size_t q = 0; q < kVectors; ++q) {
      const Wide k = load<Wide>(c.d[f] + q * width_v<Wide>);
      const auto lt = (row < nf[q]) && (k < m[q]);
      m[q] = select(lt, k, m[q]), at[q] = select(lt, row, at[q]);
    }
  }
  for (std::size_t q = 0; q < kVectors; ++q) store(c.best + q * width_v<Wide>, at[q]);
}

GYRO_FLATTEN void epa_planes(EpaPlaneJobs& j, std::size_t count) {
  for_lanes(0, count, [&](auto tag, std::size_t i) { plane<decltype(tag)>(j, i); });
}

GYRO_FLATTEN void epa_box_support(EpaBoxSlots& s, std::size_t rows) {
  static_assert(EpaBoxSlots::kSlots % width_v<Wide> == 0, "whole vectors");
  for (std::size_t i = 0; i < EpaBoxSlots::kSlots; i += width_v<Wide>) box_support<Wide>(s, i, rows);
}

}  // namespace gyro::GYRO_ARCH_NS
