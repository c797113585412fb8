// EPA, the expanding polytope algorithm (van den Bergen 2001): from a simplex around the
// origin, grow a polytope inside A - B towards the face closest to the origin until the
// support along that face's normal adds nothing; that face gives the penetration depth,
// normal and (through the barycentric weights of the origin's projection) the contact
// points on A and B.
//
// Robustness choices:
//  - GJK may exit with 1 to 3 points (touching shapes, symmetric pairs whose simplex passes
//    through the origin). The simplex is blown up to a tetrahedron with supports along
//    directions orthogonal to it; if A - B has no extent that way (two coplanar triangles,
//    two segments) it is flat: depth 0 along its normal, reported as such.
//  - The visible region is found by a walk over face adjacency from the closest face (the
//    silhouette walk), so the horizon is always one connected loop, and new faces are
//    linked to each other by matching their edge endpoints, never by assumed order.
//  - Sliver faces (sine of the corner angle below 1e-6) get no trusted normal: they are
//    never chosen as closest.
//  - Fixed capacity (128 vertices, 256 faces), no heap per call (epa_boxes' 16 slots, about
//    0.5 MB, are made once per thread and touched only as far as used); on exhaustion or the iteration
//    limit the best face so far is returned with converged = false.
//
// Determinism: + - * / sqrt and comparisons in a fixed order; ties go to the lowest face
// index.
//
// Side by side (epa_boxes, the box-pair batches): the loop is written as two halves, select
// the closest face and expand towards the support along its normal, which epa() runs in
// turn for one polytope and epa_boxes for up to 16 at once. There the supports, the repeat
// test, the new faces' planes and the closest-face search run over SIMD lanes across the
// polytopes (epa_lanes.cpp, the same operations as the scalar code), while the walk and
// the linking stay per polytope: each polytope sees the operations epa() performs, so the
// bits are the same. Measured on N1's overlapping pairs: 4.5 expansions and 21 faces per
// pair, with add_face alone about a third of the scalar EPA's instructions.
#include "core/float_order.hpp"
#include "geometry/convex_support.hpp"
#include "geometry/epa_lanes.hpp"
#include "geometry/epa_plane_lanes.hpp"

#include <memory>

namespace gyro::detail {
namespace {

constexpr int kMaxVerts = 128;
constexpr int kMaxFaces = 256;
constexpr float kInf = __builtin_huge_valf();
// The closest-face key of a distance d (not NaN): its bits in the float's order, -0 made +0
// first so the two zeros tie as they do in a float compare.
inline uint32_t face_key(float d) { return sortable_bits(d + 0.0f); }
constexpr uint32_t kNone = 0xff800000u;  // sortable_bits(+inf): no face's key
// (j + 1) % 3 and (j + 2) % 3 without a division.
constexpr int kNext[3] = {1, 2, 0}, kPrev[3] = {2, 0, 1};

struct Face {
  int v[3];
  int adj[3];       // the face across edge i (v[i] -> v[i+1])
  int adj_edge[3];  // that face's index for the same edge
  vec3 n;
  float d;
  bool dead;
  bool sliver;
};

struct Polytope {
  SupportPoint vert[kMaxVerts];
  // The vertices' w again, in columns: faces are built from them, and the repeat test
  // compares a new support point with all of them in one loop the compiler vectorises.
  float wx[kMaxVerts], wy[kMaxVerts], wz[kMaxVerts];
  Face face[kMaxFaces];
  // The closest-face search key: face_key(d), an integer that orders as the float d does,
  // for a live face with
  // a trusted normal and a finite distance; kNone for the others (dead, sliver,
  // overflowed). The search is a min over one dense array of integers with no
  // data-dependent branch (the face scan's compound test mispredicted about 23 times per
  // EPA call, and float selects became branches).
  uint32_t key[kMaxFaces + 3];
  // epa_boxes: the slot's column of EpaClosest's distances (stride kSlots), kept instead of
  // key; null in epa().
  float* lane_key = nullptr;
  // epa_boxes: the slot's column of EpaBoxSlots' vertices (vw), kept beside wx, wy, wz for
  // the lanes' repeat test; null in epa().
  float* lane_w = nullptr;
  int nv = 0, nf = 0;
  int horizon_face[kMaxFaces], horizon_edge[kMaxFaces];
  int nh = 0;

  void set_column(int i) {
    wx[i] = vert[i].w.x, wy[i] = vert[i].w.y, wz[i] = vert[i].w.z;
    if (lane_w) {
      constexpr int kCoord = int(EpaBoxSlots::kVerts * EpaBoxSlots::kSlots), kRow = int(EpaBoxSlots::kSlots);
      lane_w[i * kRow] = vert[i].w.x, lane_w[kCoord + i * kRow] = vert[i].w.y, lane_w[2 * kCoord + i * kRow] = vert[i].w.z;
    }
  }
  void push_vertex(const SupportPoint& s) { vert[nv] = s, set_column(nv), ++nv; }

  // A face with its corners and no neighbours yet; its plane comes from add_face or, for
  // epa_boxes, from the lanes (set_plane).
  int add_topology(int a, int b, int c) {
    Face& f = face[nf];
    f.v[0] = a, f.v[1] = b, f.v[2] = c;
    f.adj[0] = f.adj[1] = f.adj[2] = -1;
    f.dead = false;
    return nf++;
  }

  // The lanes' plane for face g (epa_boxes only: the distance goes to lane_key, +inf where
  // add_face's key is kNone, which orders the faces as the keys do).
  void set_plane(int g, const vec3& n, float d, bool sliver) {
    Face& f = face[g];
    f.n = n, f.d = d, f.sliver = sliver;
    lane_key[g * int(EpaClosest::kSlots)] = !sliver && d < kInf ? d : kInf;
  }

  // The face's plane from the columns: face_plane()'s float instantiation, the expressions
  // epa_lanes.cpp evaluates over lanes for epa_boxes.
  int add_face(int a, int b, int c) {
    const int g = add_topology(a, b, c);
    Face& f = face[g];
    const GYRO_ARCH_NS::FacePlane<float> pl =
        GYRO_ARCH_NS::face_plane(wx[a], wy[a], wz[a], wx[b], wy[b], wz[b], wx[c], wy[c], wz[c]);
    f.n = {pl.nx, pl.ny, pl.nz}, f.d = pl.d, f.sliver = pl.sliver != 0.0f;
    key[g] = !f.sliver && f.d < kInf ? face_key(f.d) : kNone;
    return g;
  }

  void kill(int g) {
    face[g].dead = true, key[g] = kNone;
    if (lane_key) lane_key[g * int(EpaClosest::kSlots)] = kInf;
  }

  // The live, trusted face closest to the origin; ties go to the lowest index (-0 and +0
  // tie, as they would in a float scan). -1 if none. Four interleaved scans (faces f with
  // f % 4 == c), each keeping its first least key, so the loop is not one chain of
  // dependent selects (masks, not selects: the compiler made selects branches); of their
  // four the least key wins, the lowest index among equal keys. The keys past the last
  // face are set to kNone first, so the scans need no tail.
  int closest() {
    key[nf] = key[nf + 1] = key[nf + 2] = kNone;
    uint32_t m[4] = {kNone, kNone, kNone, kNone};
    int32_t at[4] = {-1, -1, -1, -1};
    for (int f = 0; f < nf; f += 4)
      for (int c = 0; c < 4; ++c) {
        const uint32_t k = key[f + c];
        const int32_t lt = -int32_t(k < m[c]);
        at[c] ^= (at[c] ^ (f + c)) & lt;
        m[c] ^= (m[c] ^ k) & uint32_t(lt);
      }
    uint32_t least = m[0];
    int32_t best = at[0];
    for (int c = 1; c < 4; ++c) {  // an unset at[c] has key kNone, which never wins
      const int32_t take = -int32_t((m[c] < least) | ((m[c] == least) & (uint32_t(at[c]) < uint32_t(best))));
      best ^= (best ^ at[c]) & take;
      least ^= (least ^ m[c]) & uint32_t(take);
    }
    return best;
  }

  // Whether any vertex is s (all three coordinates equal).
  bool has_vertex(const vec3& s) const {
    int hit = 0;
    for (int i = 0; i < nv; ++i) hit |= (wx[i] == s.x) & (wy[i] == s.y) & (wz[i] == s.z);
    return hit != 0;
  }

  // A sliver's normal and distance are zero, so it is never visible (0 - 0 > 0 is false).
  bool visible(const Face& f, const vec3& w) const { return dot(f.n, w) - f.d > 0.0f; }

  // Van den Bergen's silhouette walk: g was reached across its edge j.
  void walk(int g, int j, const vec3& w) {
    Face& f = face[g];
    if (f.dead) return;
    if (!visible(f, w)) {
      horizon_face[nh] = g, horizon_edge[nh] = j, ++nh;
      return;
    }
    kill(g);
    walk(f.adj[kNext[j]], f.adj_edge[kNext[j]], w);
    walk(f.adj[kPrev[j]], f.adj_edge[kPrev[j]], w);
  }
};

// Links every unlinked edge of faces [from, nf) with its reverse among those faces;
// false if some edge finds no partner (the polytope is no longer a closed surface).
bool link(Polytope& p, int from) {
  for (int f = from; f < p.nf; ++f)
    for (int i = 0; i < 3; ++i) {
      if (p.face[f].adj[i] >= 0) continue;
      const int a = p.face[f].v[i], b = p.face[f].v[(i + 1) % 3];
      bool found = false;
      for (int g = from; g < p.nf && !found; ++g)
        for (int j = 0; j < 3 && !found; ++j)
          if (g != f && p.face[g].v[j] == b && p.face[g].v[(j + 1) % 3] == a) {
            p.face[f].adj[i] = g, p.face[f].adj_edge[i] = j;
            p.face[g].adj[j] = f, p.face[g].adj_edge[j] = i;
            found = true;
          }
      if (!found) return false;
    }
  return true;
}

// link() for the fan of new faces [from, nf) around the new vertex: face (s, t, w) has edge
// 0 on the horizon (linked already), edge 1 t -> w and edge 2 w -> s, so edge 1 pairs with
// edge 2 of the face starting at t, and edge 2 with edge 1 of the face ending at s. When no
// vertex starts or ends two fan faces, every edge has exactly one partner, and this finds
// what link() finds (link() would fail exactly where a partner is missing). Otherwise it
// leaves the fan to link().
bool link_fan(Polytope& p, int from) {
  static thread_local int start_of[kMaxVerts], end_of[kMaxVerts], stamp_s[kMaxVerts], stamp_e[kMaxVerts];
  static thread_local int stamp = 0;
  if (++stamp == 0x7fffffff) {
    for (int i = 0; i < kMaxVerts; ++i) stamp_s[i] = stamp_e[i] = 0;
    stamp = 1;
  }
  for (int f = from; f < p.nf; ++f) {
    const int s = p.face[f].v[0], t = p.face[f].v[1];
    if (stamp_s[s] == stamp || stamp_e[t] == stamp || p.face[f].adj[1] >= 0 || p.face[f].adj[2] >= 0)
      return link(p, from);
    stamp_s[s] = stamp_e[t] = stamp, start_of[s] = f, end_of[t] = f;
  }
  for (int f = from; f < p.nf; ++f) {
    Face& fa = p.face[f];
    const int s = fa.v[0], t = fa.v[1];
    if (stamp_s[t] != stamp || stamp_e[s] != stamp) return false;
    const int g1 = start_of[t], g2 = end_of[s];
    if (g1 == f || g2 == f) return link(p, from);
    fa.adj[1] = g1, fa.adj_edge[1] = 2;
    fa.adj[2] = g2, fa.adj_edge[2] = 1;
  }
  return true;
}

float dist_to_line(const vec3& p, const vec3& o, const vec3& d) {
  const float dd = dot(d, d);
  if (!(dd > 0.0f)) return length(p - o);
  return length(cross(p - o, d)) / std::sqrt(dd);
}

// A unit vector orthogonal to d (d non-zero): cross with the axis d is least aligned with.
vec3 orthogonal(const vec3& d) {
  const float ax = d.x < 0 ? -d.x : d.x, ay = d.y < 0 ? -d.y : d.y, az = d.z < 0 ? -d.z : d.z;
  const vec3 axis = (ax <= ay && ax <= az) ? vec3{1, 0, 0} : (ay <= az ? vec3{0, 1, 0} : vec3{0, 0, 1});
  return normalized(cross(d, axis));
}

// Grows 1-3 points to 4 with supports off their span; false if A - B is flat that way.
// On false, flat_normal is a unit normal of the flat set (or of the span).
bool blow_up(Polytope& p, const PairFrame& pair, float eps, vec3& flat_normal) {
  if (p.nv == 1) {
    static const vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const vec3& d : dirs) {
      const SupportPoint s = pair.support(d);
      if (length(s.w - p.vert[0].w) > eps) {
        p.vert[p.nv++] = s;
        break;
      }
    }
    if (p.nv == 1) {
      flat_normal = {0, 1, 0};
      return false;
    }
  }
  if (p.nv == 2) {
    const vec3 d = p.vert[1].w - p.vert[0].w;
    const vec3 e1 = orthogonal(d), e2 = normalized(cross(d, e1));
    const vec3 dirs[4] = {e1, -e1, e2, -e2};
    for (const vec3& dir : dirs) {
      const SupportPoint s = pair.support(dir);
      if (dist_to_line(s.w, p.vert[0].w, d) > eps) {
        p.vert[p.nv++] = s;
        break;
      }
    }
    if (p.nv == 2) {
      flat_normal = e1;
      return false;
    }
  }
  if (p.nv == 3) {
    const vec3 n = normalized(cross(p.vert[1].w - p.vert[0].w, p.vert[2].w - p.vert[0].w));
    const SupportPoint s1 = pair.support(n), s2 = pair.support(-n);
    const float h1 = dot(s1.w - p.vert[0].w, n), h2 = -dot(s2.w - p.vert[0].w, n);
    if (!(h1 > eps) && !(h2 > eps)) {
      // Point the flat normal from A towards B, by B's position in A's frame.
      flat_normal = dot(n, pair.pos_b) < 0.0f ? -n : n;
      if (dot(flat_normal, flat_normal) == 0.0f) flat_normal = {0, 1, 0};
      return false;
    }
    p.vert[p.nv++] = h1 >= h2 ? s1 : s2;
  }
  return true;
}

// Barycentric weights of q (on the plane of a, b, c) by areas in the best projection,
// clamped to the triangle. Returns whether q was inside (nothing clamped).
bool barycentric(const vec3& a, const vec3& b, const vec3& c, const vec3& q, float l[3]) {
  const vec3 n = cross(b - a, c - a);
  const float ax = n.x < 0 ? -n.x : n.x, ay = n.y < 0 ? -n.y : n.y, az = n.z < 0 ? -n.z : n.z;
  const int k = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  const int u = (k + 1) % 3, w = (k + 2) % 3;
  auto area = [&](const vec3& p0, const vec3& p1, const vec3& p2) {
    return (p1[u] - p0[u]) * (p2[w] - p0[w]) - (p1[w] - p0[w]) * (p2[u] - p0[u]);
  };
  float c0 = area(q, b, c), c1 = area(a, q, c), c2 = area(a, b, q);
  const float total = n[k];
  if (total < 0.0f) c0 = -c0, c1 = -c1, c2 = -c2;
  const bool inside = c0 >= 0.0f && c1 >= 0.0f && c2 >= 0.0f;
  c0 = c0 > 0.0f ? c0 : 0.0f, c1 = c1 > 0.0f ? c1 : 0.0f, c2 = c2 > 0.0f ? c2 : 0.0f;
  const float s = (c0 + c1) + c2;
  if (!(s > 0.0f)) {
    l[0] = 1.0f, l[1] = 0.0f, l[2] = 0.0f;
    return false;
  }
  l[0] = c0 / s, l[1] = c1 / s, l[2] = c2 / s;
  return inside;
}

// Spheres and capsules are curved only with their margins, which EPA on cores leaves out.
bool curved(const ConvexShape& s, bool core) {
  return s.type == ConvexType::cylinder ||
         (!core && (s.type == ConvexType::sphere || s.type == ConvexType::capsule) && s.radius > 0.0f);
}

// One EPA run's loop state. The loop is split into its two halves (select the closest face;
// expand towards a support point) so that epa_boxes can run many polytopes side by side with
// the supports and the planes in lanes, through the same code as epa().
struct Run {
  int best = -1;
  uint32_t it = 0;
  bool converged = false;
  float tol = 0.0f;
  vec3 flat_normal{0.0f, 1.0f, 0.0f};
};

// GJK's simplex grown to an outward tetrahedron; false if A - B is flat (see blow_up).
// add(a, b, c) makes a face (add_face, or its topology with the plane pending).
template <class AddFace>
bool begin(Polytope& p, const PairFrame& pair, const Simplex& start, Run& r, AddFace&& add) {
  p.nv = p.nf = p.nh = 0;
  // GJK's simplex; with 4 points it already encloses the origin.
  for (int i = 0; i < start.n; ++i) p.vert[p.nv++] = start.p[i];
  const float eps = 1e-6f * pair.scale;
  if (!blow_up(p, pair, eps, r.flat_normal)) return false;
  // Orient the tetrahedron so its faces point outwards.
  const vec3 v0 = p.vert[0].w;
  if (dot(p.vert[1].w - v0, cross(p.vert[2].w - v0, p.vert[3].w - v0)) < 0.0f) {
    const SupportPoint t = p.vert[1];
    p.vert[1] = p.vert[2], p.vert[2] = t;
  }
  for (int i = 0; i < 4; ++i) p.set_column(i);
  add(0, 2, 1), add(0, 1, 3), add(0, 3, 2), add(1, 2, 3);
  // Their adjacency, as link() finds it (every edge of a tetrahedron has one reverse).
  static constexpr int kAdj[4][3] = {{2, 3, 1}, {0, 3, 2}, {1, 3, 0}, {0, 2, 1}};
  static constexpr int kAdjEdge[4][3] = {{2, 0, 0}, {2, 2, 0}, {2, 1, 0}, {1, 1, 1}};
  for (int f = 0; f < 4; ++f)
    for (int i = 0; i < 3; ++i) p.face[f].adj[i] = kAdj[f][i], p.face[f].adj_edge[i] = kAdjEdge[f][i];
  // Curved supports approach their surface only quadratically: ask less of them.
  r.tol = (curved(*pair.a, pair.core) || curved(*pair.b, pair.core) ? 1e-4f : 1e-6f) * pair.scale;
  return true;
}

// The loop's first half, given the closest face (p.closest() once every plane is set).
// false: the loop ends here.
bool select_face(int best, Run& r, uint32_t max_iterations) {
  r.best = best;
  return r.best >= 0 && r.it < max_iterations;  // best < 0 only where every face is a sliver or overflowed
}

// The second half: s is the support along the closest face's normal. Adds the vertex and
// the fan of new faces (planes through add); false: the loop ends (converged or stuck).
// repeat: whether s.w is a vertex already (p.has_vertex).
template <class AddFace> bool expand(Polytope& p, Run& r, const SupportPoint& s, bool repeat, AddFace&& add) {
  const Face& bf = p.face[r.best];
  if (dot(s.w, bf.n) - bf.d <= r.tol) {
    r.converged = true;
    return false;
  }
  if (repeat) {  // nothing new in this direction: the face is on the boundary
    r.converged = true;
    return false;
  }
  if (p.nv >= kMaxVerts || p.nf + 64 > kMaxFaces) return false;
  const int wi = p.nv;
  p.push_vertex(s);
  p.nh = 0;
  Face& start_face = p.face[r.best];
  p.kill(r.best);
  for (int i = 0; i < 3; ++i) p.walk(start_face.adj[i], start_face.adj_edge[i], s.w);
  if (p.nf + p.nh > kMaxFaces) return false;
  // The silhouette walk lists the horizon in loop order: each new face (s, t, w) starts
  // where the one before it ended. Where that holds and no vertex starts two faces, the
  // partners of a new face's edges 1 (t -> w) and 2 (w -> s) are its neighbours in the
  // list, linked here as the faces are made; otherwise link_fan() searches.
  const int first = p.nf, nh = p.nh;
  uint64_t seen[2] = {0, 0};
  bool loop = nh >= 3;
  int prev_t = -1;
  for (int h = 0; h < nh; ++h) {
    Face& g = p.face[p.horizon_face[h]];
    const int j = p.horizon_edge[h];
    const int sv = g.v[kNext[j]], tv = g.v[j];
    const int nfi = add(sv, tv, wi);
    Face& fa = p.face[nfi];
    fa.adj[0] = p.horizon_face[h], fa.adj_edge[0] = j;
    fa.adj[1] = first + (h + 1 == nh ? 0 : h + 1), fa.adj_edge[1] = 2;
    fa.adj[2] = first + (h == 0 ? nh - 1 : h - 1), fa.adj_edge[2] = 1;
    g.adj[j] = nfi, g.adj_edge[j] = 0;
    const uint64_t bit = uint64_t(1) << (sv & 63);
    loop = loop & (h == 0 || sv == prev_t) & ((seen[sv >> 6] & bit) == 0);
    seen[sv >> 6] |= bit;
    prev_t = tv;
  }
  if (!(loop && p.face[first].v[0] == prev_t)) {
    for (int f = first; f < p.nf; ++f) p.face[f].adj[1] = p.face[f].adj[2] = -1;
    // A horizon that is not one loop means rounding broke the surface: stop with the
    // closest face of the last closed polytope (`best`, whose record is intact).
    if (!link_fan(p, first)) return false;
  }
  ++r.it;
  return true;
}

// The outcome once the loop has ended (every plane set).
EpaOutcome outcome(const Polytope& p, const Run& r) {
  EpaOutcome out;
  out.converged = r.converged;
  out.iterations = r.it;
  if (r.best < 0) {
    // Degenerate beyond repair (every face a sliver): report the flat answer.
    out.flat = true;
    out.normal = r.flat_normal;
    return out;
  }
  const Face& bf = p.face[r.best];
  const float tol = r.tol;
  float l[3];
  const vec3 q = bf.n * bf.d;
  // A flat side of the Minkowski difference is several coplanar triangles at the same
  // distance, and the closest by a rounding error need not be the one holding q: clamping q
  // onto it would put the witnesses metres off on a 100:1 pair. Take the first coplanar
  // live face that holds q.
  int chosen = r.best;
  if (!barycentric(p.vert[bf.v[0]].w, p.vert[bf.v[1]].w, p.vert[bf.v[2]].w, q, l)) {
    for (int g = 0; g < p.nf; ++g) {
      const Face& h = p.face[g];
      if (g == r.best || h.dead || h.sliver || !(h.d - bf.d <= tol && bf.d - h.d <= tol) || dot(h.n, bf.n) < 0.9999f)
        continue;
      float m[3];
      if (barycentric(p.vert[h.v[0]].w, p.vert[h.v[1]].w, p.vert[h.v[2]].w, q, m)) {
        chosen = g, l[0] = m[0], l[1] = m[1], l[2] = m[2];
        break;
      }
    }
  }
  const Face& f = p.face[chosen];
  for (int i = 0; i < 3; ++i) out.point_a += p.vert[f.v[i]].a * l[i], out.point_b += p.vert[f.v[i]].b * l[i];
  out.normal = bf.n;  // the closest face's normal and depth; the chosen one only places the witnesses
  out.depth = bf.d > 0.0f ? bf.d : 0.0f;  // the origin a rounding error outside: touching
  return out;
}

// No volume: the depth is 0 and the contact is GJK's closest point.
EpaOutcome flat_outcome(const Simplex& start, const Run& r) {
  EpaOutcome out;
  out.converged = out.flat = true;
  out.normal = r.flat_normal;
  for (int i = 0; i < start.n; ++i) out.point_a += start.p[i].a * start.lambda[i], out.point_b += start.p[i].b * start.lambda[i];
  return out;
}

}  // namespace

EpaOutcome epa(const PairFrame& pair, const Simplex& start, uint32_t max_iterations) {
  // One polytope per thread, reused: its 18 KB are never zeroed, and only what this call
  // writes is read, so reuse cannot change a result.
  thread_local Polytope p;
  Run r;
  auto add = [&](int a, int b, int c) { return p.add_face(a, b, c); };
  if (!begin(p, pair, start, r, add)) return flat_outcome(start, r);
  while (select_face(p.closest(), r, max_iterations)) {
    const SupportPoint s = pair.support(p.face[r.best].n);
    if (!expand(p, r, s, p.has_vertex(s.w), add)) break;
  }
  return outcome(p, r);
}

namespace {

// epa_boxes' state: a polytope per slot, the slots' frames and support requests, and the
// faces whose planes are pending.
struct BoxSlots {
  static constexpr int kSlots = int(EpaBoxSlots::kSlots);
  static_assert(kSlots < 32, "slot sets are 32-bit masks");
  Polytope poly[kSlots];
  Run run[kSlots];
  int job[kSlots];  // the pair in a busy slot
  EpaBoxSlots lanes;
  EpaPlaneJobs planes;
  EpaClosest closest;
  int pending = 0;
  int16_t plane_slot[EpaPlaneJobs::kMax];
  int16_t plane_face[EpaPlaneJobs::kMax];

  // Face (a, b, c) of slot k with its plane pending.
  int add(int k, int a, int b, int c) {
    Polytope& p = poly[k];
    const int g = p.add_topology(a, b, c);
    const int j = pending++;
    planes.a[0][j] = p.wx[a], planes.a[1][j] = p.wy[a], planes.a[2][j] = p.wz[a];
    planes.b[0][j] = p.wx[b], planes.b[1][j] = p.wy[b], planes.b[2][j] = p.wz[b];
    planes.c[0][j] = p.wx[c], planes.c[1][j] = p.wy[c], planes.c[2][j] = p.wz[c];
    plane_slot[j] = int16_t(k), plane_face[j] = int16_t(g);
    return g;
  }

  void flush(epa_planes_fn* kernel) {
    if (pending == 0) return;
    kernel(planes, std::size_t(pending));
    for (int j = 0; j < pending; ++j)
      poly[plane_slot[j]].set_plane(plane_face[j], vec3{planes.n[0][j], planes.n[1][j], planes.n[2][j]}, planes.d[j],
                                    planes.sliver[j] != 0.0f);
    pending = 0;
  }
};

}  // namespace

void epa_boxes(const PairFrame* const* pairs, const Simplex* starts, std::size_t count, uint32_t max_iterations,
               EpaOutcome* out) {
  thread_local std::unique_ptr<BoxSlots> state;
  if (!state) state = std::make_unique<BoxSlots>();
  BoxSlots& S = *state;
  epa_planes_fn* const planes = GYRO_DISPATCH(epa_planes);
  epa_box_support_fn* const support = GYRO_DISPATCH(epa_box_support);
  epa_closest_fn* const closest = GYRO_DISPATCH(epa_closest);
  for (int k = 0; k < BoxSlots::kSlots; ++k) S.poly[k].lane_key = &S.closest.d[0][k], S.poly[k].lane_w = &S.lanes.vw[0][0][k];
  constexpr int kSlots = BoxSlots::kSlots;
  // A slot's faces number at most kMaxFaces; flushing before a slot could overflow the list
  // keeps every pending plane in it.
  static_assert(EpaPlaneJobs::kMax >= 2 * kMaxFaces, "room for one more slot's faces");
  static_assert(EpaClosest::kFaces >= kMaxFaces && EpaBoxSlots::kVerts >= kMaxVerts, "a row per face and vertex");
  S.pending = 0;
  std::size_t next = 0;
  // Slot sets as bit masks, walked lowest slot first: the loops run over the slots in a set
  // instead of testing every slot (those tests mispredicted as the occupancy changed).
  uint32_t busy = 0, ended = 0;
  auto each = [](uint32_t set, auto&& body) {
    for (; set != 0; set &= set - 1u) body(__builtin_ctz(set));
  };
  for (;;) {
    // Fill free slots with the next pairs (a simplex of fewer than 4 points runs epa()).
    each(~busy & ((1u << kSlots) - 1u), [&](int k) {
      while (next < count && starts[next].n < 4) out[next] = epa(*pairs[next], starts[next], max_iterations), ++next;
      if (next == count) return;
      const std::size_t i = next++;
      const PairFrame& f = *pairs[i];
      if (S.pending + 4 > int(EpaPlaneJobs::kMax) - kMaxFaces) S.flush(planes);
      S.run[k] = Run{};
      begin(S.poly[k], f, starts[i], S.run[k], [&](int a, int b, int c) { return S.add(k, a, b, c); });
      for (int c = 0; c < 3; ++c) {
        S.lanes.ha[c][k] = f.a->half_extents[c], S.lanes.hb[c][k] = f.b->half_extents[c];
        S.lanes.pos[c][k] = f.pos_b[c];
        for (int r = 0; r < 3; ++r) S.lanes.rot[3 * r + c][k] = f.rot_b.m[r][c];
      }
      S.job[k] = int(i), busy |= 1u << k;
    });
    if (busy == 0) break;
    S.flush(planes);
    // Every plane is set: ended slots give their outcome; the others select a face and ask
    // for a support along its normal.
    each(ended, [&](int k) { out[S.job[k]] = outcome(S.poly[k], S.run[k]); });
    busy &= ~ended, ended = 0;
    int rows = 0;
    for (int k = 0; k < kSlots; ++k) {
      const int nf = S.poly[k].nf & -int(busy >> k & 1u);  // 0 for a free slot
      S.closest.nf[k] = float(nf), rows = nf > rows ? nf : rows;
    }
    closest(S.closest, std::size_t(rows));
    each(busy, [&](int k) {
      Polytope& p = S.poly[k];
      if (select_face(int(S.closest.best[k]), S.run[k], max_iterations)) {
        const vec3& n = p.face[S.run[k].best].n;
        S.lanes.dir[0][k] = n.x, S.lanes.dir[1][k] = n.y, S.lanes.dir[2][k] = n.z;
        return;
      }
      out[S.job[k]] = outcome(p, S.run[k]);
      busy &= ~(1u << k);
    });
    if (busy == 0) continue;
    int verts = 0;
    for (int k = 0; k < kSlots; ++k) {
      const int nv = S.poly[k].nv & -int(busy >> k & 1u);
      S.lanes.nv[k] = float(nv), verts = nv > verts ? nv : verts;
    }
    support(S.lanes, std::size_t(verts));
    each(busy, [&](int k) {
      const SupportPoint s{{S.lanes.w[0][k], S.lanes.w[1][k], S.lanes.w[2][k]},
                           {S.lanes.a[0][k], S.lanes.a[1][k], S.lanes.a[2][k]},
                           {S.lanes.b[0][k], S.lanes.b[1][k], S.lanes.b[2][k]}};
      if (S.pending > int(EpaPlaneJobs::kMax) - kMaxFaces) S.flush(planes);
      const bool more = expand(S.poly[k], S.run[k], s, S.lanes.repeat[k] != 0.0f,
                               [&](int a, int b, int c) { return S.add(k, a, b, c); });
      ended |= uint32_t(!more) << k;
    });
  }
}

}  // namespace gyro::detail
