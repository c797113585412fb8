// Convex hull of a point cloud by quickhull (Barber, Dobkin, Huhdanpaa 1996), then
// simplified: coplanar triangles merged into polygons, boundary vertices that lie on a
// straight edge removed, unused points dropped (welded).
//
// Precision: the points are float, the construction runs in binary64 (a hull is built once
// per shape, not per step, and binary64 leaves the tolerance test as the only source of
// doubt). tol = 1e-6 of the cloud's bounding-box diagonal: a point within tol of a face's
// plane counts as on it, so near-duplicates weld and near-coplanar faces merge.
//
// Determinism: only + - * / sqrt and comparisons; points are visited in index order, the
// farthest point of a face is the lowest index among equals, faces are processed in
// creation order, and the output order follows input indices. No pointer-dependent order.
#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/convex.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gyro {
namespace {

struct D3 {
  double x, y, z;
};
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot3(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross3(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double len3(D3 a) { return std::sqrt(dot3(a, a)); }

struct HFace {
  int v[3] = {0, 0, 0};
  int adj[3] = {-1, -1, -1}, adj_edge[3] = {0, 0, 0};  // neighbour across edge v[i] -> v[i+1], and its edge index
  D3 n{0.0, 0.0, 0.0};
  double d = 0.0;
  bool dead = false;
  std::vector<int> conflict;  // points above this face (by more than tol), in index order
};

class Builder {
 public:
  Builder(const std::vector<D3>& p, double tol) : p_(p), tol_(tol) {}

  Status run(ConvexHull& out);

 private:
  const std::vector<D3>& p_;
  double tol_;
  std::vector<HFace> f_;
  bool link_ok_ = true;

  double dist(const HFace& f, int i) const { return dot3(f.n, p_[i]) - f.d; }
  int add_face(int a, int b, int c);
  bool link_new(int from);
  void assign(const std::vector<int>& pts, int from);
  Status initial(int s[4]);
  void add_point(int face);
  Status simplify(ConvexHull& out);
};

int Builder::add_face(int a, int b, int c) {
  HFace f;
  f.v[0] = a, f.v[1] = b, f.v[2] = c;
  f.adj[0] = f.adj[1] = f.adj[2] = -1;
  const D3 n = cross3(p_[b] - p_[a], p_[c] - p_[a]);
  const double l = len3(n);
  f.n = l > 0 ? n * (1.0 / l) : D3{0, 0, 0};
  // The plane through the face's highest corner: rounding never puts a corner above it.
  f.d = std::max(std::max(dot3(f.n, p_[a]), dot3(f.n, p_[b])), dot3(f.n, p_[c]));
  f_.push_back(std::move(f));
  return int(f_.size()) - 1;
}

// Pairs the unlinked edges of faces [from, end) with their reverses among those faces.
bool Builder::link_new(int from) {
  const int end = int(f_.size());
  for (int a = from; a < end; ++a)
    for (int i = 0; i < 3; ++i) {
      if (f_[a].adj[i] >= 0) continue;
      const int u = f_[a].v[i], w = f_[a].v[(i + 1) % 3];
      bool found = false;
      for (int b = from; b < end && !found; ++b)
        for (int j = 0; j < 3 && !found; ++j)
          if (b != a && f_[b].v[j] == w && f_[b].v[(j + 1) % 3] == u) {
            f_[a].adj[i] = b, f_[a].adj_edge[i] = j, f_[b].adj[j] = a, f_[b].adj_edge[j] = i;
            found = true;
          }
      if (!found) return false;
    }
  return true;
}

// Gives each point to the face (of [from, end)) it is farthest above, if above by > tol.
void Builder::assign(const std::vector<int>& pts, int from) {
  for (int i : pts) {
    int best = -1;
    double bd = tol_;
    for (int k = from; k < int(f_.size()); ++k)
      if (!f_[k].dead) {
        const double d = dist(f_[k], i);
        if (d > bd) bd = d, best = k;
      }
    if (best >= 0) f_[best].conflict.push_back(i);
  }
}

Status Builder::initial(int s[4]) {
  const int n = int(p_.size());
  // The two farthest of the six axis-extreme points.
  int ext[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 1; i < n; ++i) {
    const double c[3] = {p_[i].x, p_[i].y, p_[i].z};
    for (int k = 0; k < 3; ++k) {
      const double lo[3] = {p_[ext[0]].x, p_[ext[2]].y, p_[ext[4]].z};
      const double hi[3] = {p_[ext[1]].x, p_[ext[3]].y, p_[ext[5]].z};
      if (c[k] < lo[k]) ext[2 * k] = i;
      if (c[k] > hi[k]) ext[2 * k + 1] = i;
    }
  }
  double best = -1;
  for (int k = 0; k < 3; ++k) {
    const double d = len3(p_[ext[2 * k + 1]] - p_[ext[2 * k]]);
    if (d > best) best = d, s[0] = ext[2 * k], s[1] = ext[2 * k + 1];
  }
  if (!(best > tol_)) return detail::fail(Status::invalid_argument, "convex hull: all points coincide (no volume)");
  const D3 axis = p_[s[1]] - p_[s[0]];
  best = -1;
  for (int i = 0; i < n; ++i) {
    const double d = len3(cross3(p_[i] - p_[s[0]], axis)) / len3(axis);
    if (d > best) best = d, s[2] = i;
  }
  if (!(best > tol_)) return detail::fail(Status::invalid_argument, "convex hull: all points are collinear (no volume)");
  D3 nrm = cross3(axis, p_[s[2]] - p_[s[0]]);
  nrm = nrm * (1.0 / len3(nrm));
  best = -1;
  for (int i = 0; i < n; ++i) {
    const double d = std::abs(dot3(p_[i] - p_[s[0]], nrm));
    if (d > best) best = d, s[3] = i;
  }
  if (!(best > tol_)) return detail::fail(Status::invalid_argument, "convex hull: all points are coplanar (no volume)");
  // Outward faces need a positive volume for (s0, s1, s2, s3) in this face order.
  if (dot3(p_[s[1]] - p_[s[0]], cross3(p_[s[2]] - p_[s[0]], p_[s[3]] - p_[s[0]])) < 0) std::swap(s[1], s[2]);
  add_face(s[0], s[2], s[1]), add_face(s[0], s[1], s[3]), add_face(s[0], s[3], s[2]), add_face(s[1], s[2], s[3]);
  if (!link_new(0)) return detail::fail(Status::internal, "convex hull: initial tetrahedron");
  std::vector<int> rest;
  for (int i = 0; i < n; ++i)
    if (i != s[0] && i != s[1] && i != s[2] && i != s[3]) rest.push_back(i);
  assign(rest, 0);
  return Status::ok;
}

// Adds the farthest conflict point of face `fi`: removes what it sees, fans in new faces.
void Builder::add_point(int fi) {
  int eye = -1;
  double bd = -1;
  for (int i : f_[fi].conflict) {
    const double d = dist(f_[fi], i);
    if (d > bd) bd = d, eye = i;
  }
  // Visible region by a walk over adjacency from fi (one connected patch, one horizon).
  std::vector<std::pair<int, int>> stack, horizon;
  std::vector<int> removed{fi};
  f_[fi].dead = true;
  for (int i = 2; i >= 0; --i) stack.push_back({f_[fi].adj[i], f_[fi].adj_edge[i]});
  while (!stack.empty()) {
    const auto [g, j] = stack.back();
    stack.pop_back();
    if (f_[g].dead) continue;
    if (!(dist(f_[g], eye) > tol_)) {
      horizon.push_back({g, j});
      continue;
    }
    f_[g].dead = true;
    removed.push_back(g);
    stack.push_back({f_[g].adj[(j + 2) % 3], f_[g].adj_edge[(j + 2) % 3]});
    stack.push_back({f_[g].adj[(j + 1) % 3], f_[g].adj_edge[(j + 1) % 3]});
  }
  // A horizon edge whose far face died later (reached first from outside) is interior.
  std::vector<std::pair<int, int>> h2;
  for (const auto& e : horizon)
    if (!f_[e.first].dead) h2.push_back(e);
  const int first = int(f_.size());
  for (const auto& [g, j] : h2) {
    const int a = f_[g].v[j], b = f_[g].v[(j + 1) % 3];
    const int nf = add_face(b, a, eye);
    f_[nf].adj[0] = g, f_[nf].adj_edge[0] = j;
    f_[g].adj[j] = nf, f_[g].adj_edge[j] = 0;
  }
  link_ok_ = link_ok_ && link_new(first);
  std::vector<int> orphans;
  for (int r : removed) {
    for (int i : f_[r].conflict)
      if (i != eye) orphans.push_back(i);
    f_[r].conflict.clear();
    f_[r].conflict.shrink_to_fit();
  }
  std::sort(orphans.begin(), orphans.end());  // unique indices: the order is total
  assign(orphans, first);
}


Status Builder::run(ConvexHull& out) {
  int s[4] = {0, 1, 2, 3};
  GYRO_TRY(initial(s));
  // Faces are appended as they are made, so one pass in creation order visits every face
  // that ever holds a conflict point.
  for (std::size_t i = 0; i < f_.size(); ++i) {
    if (f_[i].dead || f_[i].conflict.empty()) continue;
    add_point(int(i));
    if (!link_ok_) return detail::fail(Status::internal, "convex hull: the horizon is not a single loop");
  }
  return simplify(out);
}

// Merges coplanar triangles into polygons, drops vertices on straight edges, renumbers.
Status Builder::simplify(ConvexHull& out) {
  const int nf = int(f_.size());
  std::vector<int> group(nf, -1);
  std::vector<std::vector<int>> groups;
  for (int t = 0; t < nf; ++t) {
    if (f_[t].dead || group[t] >= 0) continue;
    const int g = int(groups.size());
    groups.push_back({t});
    group[t] = g;
    const D3 n = f_[t].n;
    const double d = f_[t].d;
    for (std::size_t q = 0; q < groups[g].size(); ++q) {
      const int x = groups[g][q];
      for (int i = 0; i < 3; ++i) {
        const int y = f_[x].adj[i];
        if (group[y] >= 0 || !(dot3(f_[y].n, n) > 0)) continue;
        bool flat = true;
        for (int k = 0; k < 3; ++k) flat = flat && std::abs(dot3(n, p_[f_[y].v[k]]) - d) <= tol_;
        if (flat) group[y] = g, groups[g].push_back(y);
      }
    }
  }
  // Boundary loop of each group; a group whose boundary is not one loop stays triangles.
  std::vector<std::vector<int>> loops;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::pair<int, int>> edges;  // (from, to)
    for (int x : groups[g])
      for (int i = 0; i < 3; ++i)
        if (group[f_[x].adj[i]] != int(g)) edges.push_back({f_[x].v[i], f_[x].v[(i + 1) % 3]});
    std::vector<std::pair<int, int>> by_from = edges;
    std::sort(by_from.begin(), by_from.end());
    bool ok = true;
    for (std::size_t i = 1; i < by_from.size(); ++i) ok = ok && by_from[i].first != by_from[i - 1].first;
    std::vector<int> loop;
    if (ok) {
      int at = edges[0].first;
      for (std::size_t k = 0; k < edges.size() && ok; ++k) {
        loop.push_back(at);
        const auto it = std::lower_bound(by_from.begin(), by_from.end(), std::pair<int, int>{at, -1});
        ok = it != by_from.end() && it->first == at;
        if (ok) at = it->second;
      }
      ok = ok && at == edges[0].first;
    }
    if (ok) {
      loops.push_back(std::move(loop));
    } else {
      for (int x : groups[g]) loops.push_back({f_[x].v[0], f_[x].v[1], f_[x].v[2]});
    }
  }
  // A vertex on only two faces lies on the straight edge between them: drop it from both.
  std::vector<int> faces_at(p_.size(), 0);
  for (const auto& l : loops)
    for (int v : l) ++faces_at[v];
  std::vector<int> remap(p_.size(), -1);
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (faces_at[i] >= 3) remap[i] = int(out.vertices.size()), out.vertices.push_back({float(p_[i].x), float(p_[i].y), float(p_[i].z)});
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  out.face_start.push_back(0);
  for (const auto& loop : loops) {
    std::vector<uint32_t> f;
    for (int v : loop)
      if (remap[v] >= 0) f.push_back(uint32_t(remap[v]));
    if (f.size() < 3) return detail::fail(Status::internal, "convex hull: a face lost its corners");
    // Start each face at its lowest vertex so the output is canonical.
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    D3 n{0, 0, 0};
    const D3 c{out.vertices[f[0]].x, out.vertices[f[0]].y, out.vertices[f[0]].z};
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const vec3 a = out.vertices[f[i]], b = out.vertices[f[i + 1]];
      n = n + cross3(D3{a.x, a.y, a.z} - c, D3{b.x, b.y, b.z} - c);
    }
    const double nl = len3(n);
    if (!(nl > 0)) return detail::fail(Status::internal, "convex hull: a face has no area");
    n = n * (1.0 / nl);
    double dmax = -1e300;
    for (uint32_t v : f) dmax = std::max(dmax, dot3(n, D3{out.vertices[v].x, out.vertices[v].y, out.vertices[v].z}));
    out.planes.push_back({vec3{float(n.x), float(n.y), float(n.z)}, float(dmax)});
    for (std::size_t i = 0; i < f.size(); ++i) {
      const uint32_t a = f[i], b = f[(i + 1) % f.size()];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
    out.face_vertices.insert(out.face_vertices.end(), f.begin(), f.end());
    out.face_start.push_back(uint32_t(out.face_vertices.size()));
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size(); i += 2)  // every edge bounds exactly two faces
    if (i + 1 >= edges.size() || edges[i] != edges[i + 1] || (i + 2 < edges.size() && edges[i + 2] == edges[i]))
      return detail::fail(Status::internal, "convex hull: an edge does not join exactly two faces");
  for (std::size_t i = 0; i < edges.size(); i += 2) out.edges.push_back(edges[i].first), out.edges.push_back(edges[i].second);
  const long euler = long(out.vertices.size()) - long(out.edge_count()) + long(out.face_count());
  if (euler != 2) return detail::fail(Status::internal, "convex hull: V - E + F = %ld, not 2", euler);
  return Status::ok;
}

}  // namespace

Status build_convex_hull(const vec3* points, std::size_t count, ConvexHull& out) {
  out = ConvexHull{};
  if (!points && count > 0) return detail::fail(Status::null_argument, "convex hull: points is null");
  if (count < 4) return detail::fail(Status::invalid_count, "convex hull: %zu points, a polyhedron needs at least 4", count);
  if (count > (1u << 24)) return detail::fail(Status::invalid_count, "convex hull: %zu points, at most 2^24", count);
  std::vector<D3> p(count);
  D3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < count; ++i) {
    if (!is_finite(points[i])) return detail::fail(Status::non_finite, "convex hull: points[%zu] is not finite", i);
    p[i] = {points[i].x, points[i].y, points[i].z};
    lo = {std::min(lo.x, p[i].x), std::min(lo.y, p[i].y), std::min(lo.z, p[i].z)};
    hi = {std::max(hi.x, p[i].x), std::max(hi.y, p[i].y), std::max(hi.z, p[i].z)};
  }
  const double tol = 1e-6 * len3(hi - lo);
  if (!(tol > 0)) return detail::fail(Status::invalid_argument, "convex hull: all points coincide (no volume)");
  Builder b(p, tol);
  const Status s = b.run(out);
  if (s != Status::ok) out = ConvexHull{};
  return s;
}

ConvexShape ConvexHull::shape() const {
  ConvexShape s;
  s.type = ConvexType::points;
  s.points = vertices.data();
  s.count = uint32_t(vertices.size());
  return s;
}

}  // namespace gyro
