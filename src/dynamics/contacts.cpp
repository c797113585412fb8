#include "dynamics/contacts.hpp"

#include "core/parallel.hpp"
#include "dynamics/body_bounds.hpp"
#include "dynamics/box_sat.hpp"
#include "dynamics/narrowphase.hpp"
#include "gyro/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gyro::detail {
namespace {

constexpr uint32_t kMaxMeshManifolds = 16;  // triangles of one mesh touching one body
constexpr std::size_t kPairChunk = 64;  // ~12 us of box-box narrowphase a chunk; the fork is paid once per loop

bool is_mesh(const BodyStore& s, uint32_t slot) { return s.shape[slot] == uint32_t(BodyShape::mesh); }

Sphere sphere_of(const BodyStore& s, uint32_t i) { return {s.position(i), s.radius[i]}; }
OBB box_of(const BodyStore& s, uint32_t i) { return {s.position(i), {s.hx[i], s.hy[i], s.hz[i]}, to_mat3(s.orientation(i))}; }
Plane plane_of(const BodyStore& s, uint32_t i) {
  const vec3 n = rotate(s.orientation(i), vec3{0.0f, 1.0f, 0.0f});
  return {n, dot(n, s.position(i))};
}

void flip(Manifold* m) { m->normal = -m->normal; }

bool is_box(const BodyStore& s, uint32_t slot) { return s.shape[slot] == uint32_t(BodyShape::box); }

// The box-box pairs of a narrowphase chunk, staged for the separating axis kernel: columns
// of kPairChunk floats (box_sat.hpp), padded with zeros to a whole batch at every level.
struct BoxPairBatch {
  static constexpr uint32_t kNone = ~0u;
  static constexpr std::size_t kPad = 16;  // the widest lane
  alignas(64) float in[kSatInputs * kPairChunk];
  alignas(64) float out[kSatOutputs * kPairChunk];
  uint32_t lane[kPairChunk];  // per pair of the chunk: its lane, or kNone
  std::size_t count = 0;

  void stage(const BodyStore& s, uint32_t a, uint32_t b, float margin) {
    const std::size_t k = count++;
    const mat3 ra = to_mat3(s.orientation(a)), rb = to_mat3(s.orientation(b));
    for (uint32_t r = 0; r < 3; ++r)
      for (uint32_t c = 0; c < 3; ++c) {
        in[(kSatUa + 3 * r + c) * kPairChunk + k] = ra.m[r][c];
        in[(kSatUb + 3 * r + c) * kPairChunk + k] = rb.m[r][c];
      }
    const float ea[3] = {s.hx[a], s.hy[a], s.hz[a]}, eb[3] = {s.hx[b], s.hy[b], s.hz[b]};
    const vec3 d = s.position(b) - s.position(a);
    const float dv[3] = {d.x, d.y, d.z};
    for (uint32_t c = 0; c < 3; ++c) {
      in[(kSatEa + c) * kPairChunk + k] = ea[c];
      in[(kSatEb + c) * kPairChunk + k] = eb[c];
      in[(kSatD + c) * kPairChunk + k] = dv[c];
    }
    in[kSatMargin * kPairChunk + k] = margin;
  }
  void run() {
    const std::size_t padded = (count + kPad - 1) / kPad * kPad;
    for (uint32_t c = 0; c < kSatInputs; ++c)
      for (std::size_t k = count; k < padded; ++k) in[c * kPairChunk + k] = 0.0f;
    GYRO_DISPATCH(box_sat_batch)(BoxSatArgs{in, out, kPairChunk}, 0, padded);
  }
  // The manifold of the pair in lane k (slots a, b), as collide_boxes() gives it.
  void finish(const BodyStore& s, uint32_t a, uint32_t b, std::size_t k, Manifold* m) const {
    auto col = [&](uint32_t c) { return c * kPairChunk + k; };
    BoxAxes fa, fb;
    for (uint32_t r = 0; r < 3; ++r) {
      fa.u[r] = {in[col(kSatUa + 3 * r)], in[col(kSatUa + 3 * r + 1)], in[col(kSatUa + 3 * r + 2)]};
      fb.u[r] = {in[col(kSatUb + 3 * r)], in[col(kSatUb + 3 * r + 1)], in[col(kSatUb + 3 * r + 2)]};
      fa.e[r] = in[col(kSatEa + r)], fb.e[r] = in[col(kSatEb + r)];
    }
    BoxSat sat;
    sat.hit = out[col(kSatHit)] != 0.0f;
    sat.sa = out[col(kSatSa)], sat.sb = out[col(kSatSb)], sat.se = out[col(kSatSe)];
    sat.ia = int(out[col(kSatIa)]), sat.jb = int(out[col(kSatJb)]);
    sat.ie = int(out[col(kSatIe)]), sat.je = int(out[col(kSatJe)]);
    sat.edge_normal = {out[col(kSatNormal)], out[col(kSatNormal + 1)], out[col(kSatNormal + 2)]};
    box_manifold(s.position(a), fa, s.position(b), fb, sat, in[col(kSatMargin)], m);
  }
};

bool needs_generic(uint32_t shape) { return shape == uint32_t(BodyShape::capsule) || shape == uint32_t(BodyShape::hull); }

// A body's shape for the generic path, posed in the frame given by (p, q).
ConvexCollider collider_of(const BodyStore& s, uint32_t i, const vec3& p, const quat& q) {
  ConvexCollider c;
  c.pose.position = p;
  c.pose.rotation = to_mat3(q);
  switch (BodyShape(s.shape[i])) {
    case BodyShape::sphere: c.shape.type = ConvexType::sphere, c.shape.radius = s.radius[i]; break;
    case BodyShape::capsule:
      c.shape.type = ConvexType::capsule, c.shape.radius = s.hx[i], c.shape.half_height = s.hy[i];
      break;
    case BodyShape::hull:
      c.shape.type = ConvexType::points;
      c.shape.points = s.hull[i]->hull.vertices.data();
      c.shape.count = uint32_t(s.hull[i]->hull.vertices.size());
      c.hull = &s.hull[i]->hull;
      break;
    default: c.shape.type = ConvexType::box, c.shape.half_extents = {s.hx[i], s.hy[i], s.hz[i]}; break;
  }
  return c;
}
ConvexCollider collider_of(const BodyStore& s, uint32_t i) { return collider_of(s, i, s.position(i), s.orientation(i)); }

// The manifold of a convex pair (no mesh), normal from a to b.
void collide_convex(const BodyStore& s, uint32_t a, uint32_t b, float margin, Manifold* m) {
  const auto sa = BodyShape(s.shape[a]), sb = BodyShape(s.shape[b]);
  const bool swap = uint32_t(sa) > uint32_t(sb);  // canonical order: sphere < box < plane
  const uint32_t p = swap ? b : a, q = swap ? a : b;
  const auto sp = swap ? sb : sa, sq = swap ? sa : sb;
  m->count = 0;
  if (needs_generic(s.shape[a]) || needs_generic(s.shape[b])) {
    // Planes come last in canonical order for these: the shape is p, the plane q.
    const bool plane_first = sa == BodyShape::plane;
    const uint32_t x = plane_first ? b : a, y = plane_first ? a : b;
    if (BodyShape(s.shape[y]) == BodyShape::plane) collide_convex_plane(collider_of(s, x), plane_of(s, y), margin, m);
    else collide_convex_shapes(collider_of(s, x), collider_of(s, y), margin, m);
    if (plane_first) flip(m);
    return;
  }
  if (sp == BodyShape::sphere && sq == BodyShape::sphere) collide_spheres(sphere_of(s, p), sphere_of(s, q), margin, m);
  else if (sp == BodyShape::sphere && sq == BodyShape::box) collide_sphere_box(sphere_of(s, p), box_of(s, q), margin, m);
  else if (sp == BodyShape::box && sq == BodyShape::box) collide_boxes(box_of(s, p), box_of(s, q), margin, m);
  else if (sp == BodyShape::sphere && sq == BodyShape::plane) collide_sphere_plane(sphere_of(s, p), plane_of(s, q), margin, m);
  else if (sp == BodyShape::box && sq == BodyShape::plane) collide_box_plane(box_of(s, p), plane_of(s, q), margin, m);
  if (swap) flip(m);
}

// Manifolds of body `body` (any shape but planes and meshes) against the triangles of mesh
// body `mesh`, computed in the mesh's frame; normals from body to mesh. Returns how many were written (<= cap).
uint32_t collide_mesh(const BodyStore& s, uint32_t body, uint32_t mesh, float margin, ContactRecord* out, uint32_t cap) {
  const quat qm = s.orientation(mesh), qm_inv = conjugate(qm);
  const vec3 pm = s.position(mesh);
  const vec3 p_local = rotate(qm_inv, s.position(body) - pm);
  const quat q_local = qm_inv * s.orientation(body);
  const bool sphere = s.shape[body] == uint32_t(BodyShape::sphere);
  const bool generic = needs_generic(s.shape[body]);
  const OBB box{p_local, {s.hx[body], s.hy[body], s.hz[body]}, to_mat3(q_local)};
  const ConvexCollider shape = generic ? collider_of(s, body, p_local, q_local) : ConvexCollider{};
  const AABB bounds = shape_bounds(s, body, p_local, q_local);
  const vec3 reach = bounds.half_extents + vec3{margin, margin, margin};
  uint32_t tris[kMaxMeshManifolds];
  const std::size_t found = s.mesh[mesh]->triangles_overlapping(AABB{bounds.center, reach}, tris, kMaxMeshManifolds);
  const uint32_t n = uint32_t(std::min<std::size_t>(found, cap));
  uint32_t written = 0;
  for (uint32_t k = 0; k < n; ++k) {
    const Triangle t = s.mesh[mesh]->triangle(tris[k]);
    Manifold m;
    if (generic) {
      ConvexCollider tri;
      tri.shape.type = ConvexType::triangle;
      tri.shape.v[0] = t.a, tri.shape.v[1] = t.b, tri.shape.v[2] = t.c;
      collide_convex_shapes(shape, tri, margin, &m);
    } else if (sphere) {
      collide_sphere_triangle(Sphere{p_local, s.radius[body]}, t, margin, &m);
    } else {
      collide_box_triangle(box, t, margin, &m);
    }
    if (m.count == 0) continue;
    m.normal = rotate(qm, m.normal);
    for (uint32_t j = 0; j < m.count; ++j) m.points[j].position = rotate(qm, m.points[j].position) + pm;
    out[written].manifold = m;
    out[written].sub = tris[k];
    ++written;
  }
  return written;
}

// Last step's record of the convex pair (slots a, b in key order), or null.
const ContactRecord* find_record(const std::vector<ContactRecord>& list, const BodyStore& s, uint32_t a, uint32_t b) {
  const BodyId ia = s.id[a], ib = s.id[b];
  const uint64_t key = (uint64_t{ia.index} << 32) | ib.index;
  const auto it = std::lower_bound(list.begin(), list.end(), key,
                                   [](const ContactRecord& r, uint64_t k) { return r.key < k; });
  if (it == list.end() || it->key != key || it->sub != 0 || it->gen_a != ia.generation || it->gen_b != ib.generation)
    return nullptr;
  return &*it;
}

float motion_margin(const BodyStore& s, uint32_t a, uint32_t b, const ContactSettings& set) {
  if (!set.continuous) return set.speculative_distance;
  const vec3 dv = s.linear_velocity(b) - s.linear_velocity(a);
  const float spin = length(s.angular_velocity(a)) * s.radius[a] + length(s.angular_velocity(b)) * s.radius[b];
  return set.speculative_distance + (length(dv) + spin) * set.dt;
}

// Carries impulses from the old record to points with the same feature id.
void warm_from(const ContactRecord& old, ContactRecord& r) {
  for (uint32_t j = 0; j < r.manifold.count; ++j) {
    for (uint32_t k = 0; k < old.manifold.count; ++k) {
      if (old.manifold.points[k].feature_id != r.manifold.points[j].feature_id) continue;
      r.normal_impulse[j] = old.normal_impulse[k];
      break;
    }
  }
  for (int d = 0; d < 3; ++d) r.friction_impulse[d] = old.friction_impulse[d];
}

bool before(const ContactRecord& x, const ContactRecord& y) {
  return x.key < y.key || (x.key == y.key && x.sub < y.sub);
}

}  // namespace

bool ContactRecord::touching() const {
  for (uint32_t j = 0; j < manifold.count; ++j)
    if (manifold.points[j].separation <= 0.0f) return true;
  return false;
}

void ContactSet::clear() {
  records_.clear();
  touch_new_.clear();
  begin_.clear();
  end_.clear();
}

void ContactSet::remove_body(uint32_t id_index) {
  std::erase_if(records_, [&](const ContactRecord& r) { return r.index_a() == id_index || r.index_b() == id_index; });
  std::erase_if(touch_new_, [&](const TouchKey& t) { return t.event.a.index == id_index || t.event.b.index == id_index; });
}

void ContactSet::remap_slot(uint32_t from, uint32_t to) {
  for (ContactRecord& r : records_) {
    if (r.slot_a == from) r.slot_a = to;
    if (r.slot_b == from) r.slot_b = to;
  }
}

void ContactSet::update(const BodyStore& s, const std::vector<CandidatePair>& pairs, const uint8_t* active,
                        const ContactSettings& set) {
  // 1. Room per pair: one manifold for a convex pair, up to kMaxMeshManifolds against a mesh.
  const std::size_t np = pairs.size();
  pair_first_.resize(np + 1);
  pair_count_.resize(np);
  uint32_t total = 0;
  for (std::size_t i = 0; i < np; ++i) {
    pair_first_[i] = total;
    total += (is_mesh(s, pairs[i].a) || is_mesh(s, pairs[i].b)) ? kMaxMeshManifolds : 1;
  }
  pair_first_[np] = total;
  if (scratch_.size() < total) scratch_.resize(total);

  // 2. Narrowphase, in parallel over fixed chunks of pairs: each pair writes its own range.
  // Box-box pairs run their separating axis tests in lanes first (box_sat.hpp).
  parallel_for(np, kPairChunk, [&](std::size_t begin, std::size_t end) {
    BoxPairBatch boxes;
    for (std::size_t i = begin; i < end; ++i) {
      const uint32_t a = pairs[i].a, b = pairs[i].b;
      boxes.lane[i - begin] = BoxPairBatch::kNone;
      if (!is_box(s, a) || !is_box(s, b)) continue;
      boxes.lane[i - begin] = uint32_t(boxes.count);
      boxes.stage(s, a, b, motion_margin(s, a, b, set));
    }
    if (boxes.count > 0) boxes.run();
    for (std::size_t i = begin; i < end; ++i) {
      const uint32_t a = pairs[i].a, b = pairs[i].b;
      ContactRecord* out = scratch_.data() + pair_first_[i];
      const uint32_t lane = boxes.lane[i - begin];
      const float margin = lane == BoxPairBatch::kNone ? motion_margin(s, a, b, set) : 0.0f;  // staged for boxes
      uint32_t n;
      if (lane != BoxPairBatch::kNone) {
        out->sub = 0;
        boxes.finish(s, a, b, lane, &out->manifold);
        n = out->manifold.count > 0 ? 1 : 0;
      } else if (is_mesh(s, b)) {
        n = collide_mesh(s, a, b, margin, out, kMaxMeshManifolds);
      } else if (is_mesh(s, a)) {
        n = collide_mesh(s, b, a, margin, out, kMaxMeshManifolds);
        for (uint32_t k = 0; k < n; ++k) flip(&out[k].manifold);
      } else if (set.incremental_convex && (needs_generic(s.shape[a]) || needs_generic(s.shape[b])) &&
                 s.shape[a] != uint32_t(BodyShape::plane) && s.shape[b] != uint32_t(BodyShape::plane)) {
        out->sub = 0;
        const ContactRecord* old = find_record(records_, s, a, b);
        collide_convex_incremental(collider_of(s, a), collider_of(s, b), margin, old ? &old->manifold : nullptr,
                                   old ? &old->anchors : nullptr, &out->manifold, &out->anchors);
        n = out->manifold.count > 0 ? 1 : 0;
      } else {
        out->sub = 0;
        collide_convex(s, a, b, margin, &out->manifold);
        n = out->manifold.count > 0 ? 1 : 0;
      }
      const BodyId ia = s.id[a], ib = s.id[b];
      for (uint32_t k = 0; k < n; ++k) {
        ContactRecord& r = out[k];
        r.key = (uint64_t{ia.index} << 32) | ib.index;
        r.gen_a = ia.generation, r.gen_b = ib.generation;
        r.slot_a = a, r.slot_b = b;
        r.friction = std::sqrt(s.friction[a] * s.friction[b]);
        r.restitution = s.restitution[a] > s.restitution[b] ? s.restitution[a] : s.restitution[b];
        for (uint32_t j = 0; j < kMaxManifoldPoints; ++j)
          r.normal_impulse[j] = 0.0f;
        r.friction_impulse[0] = r.friction_impulse[1] = r.friction_impulse[2] = 0.0f;
      }
      pair_count_[i] = n;
    }
  });

  // 3. Merge, in key order: fresh records (warm-started from the old ones) and old records
  // whose bodies are both at rest, carried over.
  old_.swap(records_);
  records_.clear();
  auto live_slot = [&](uint32_t index, uint32_t gen) { return s.ids.slot(Id{index, gen}); };
  auto carried = [&](ContactRecord& r) {
    const uint32_t sa = live_slot(r.index_a(), r.gen_a), sb = live_slot(r.index_b(), r.gen_b);
    if (sa == IdPool::kNoSlot || sb == IdPool::kNoSlot) return false;  // a body was destroyed
    if (active[sa] || active[sb]) return false;  // recomputed (or no longer touching)
    r.slot_a = sa, r.slot_b = sb;
    return true;
  };
  std::size_t o = 0;
  for (std::size_t i = 0; i < np; ++i) {
    for (uint32_t k = 0; k < pair_count_[i]; ++k) {
      ContactRecord& r = scratch_[pair_first_[i] + k];
      for (; o < old_.size() && before(old_[o], r); ++o)
        if (carried(old_[o])) records_.push_back(old_[o]);
      if (o < old_.size() && old_[o].key == r.key && old_[o].sub == r.sub && old_[o].gen_a == r.gen_a &&
          old_[o].gen_b == r.gen_b) {
        warm_from(old_[o], r);
        ++o;
      }
      records_.push_back(r);
    }
  }
  for (; o < old_.size(); ++o)
    if (carried(old_[o])) records_.push_back(old_[o]);

  // 4. Touch events per body pair (any sub-shape touching), both lists sorted by key.
  touch_old_.swap(touch_new_);  // last step's touching pairs (less those of destroyed bodies)
  touching_pairs(records_, touch_new_);
  begin_.clear();
  end_.clear();
  std::size_t x = 0, y = 0;
  while (x < touch_old_.size() || y < touch_new_.size()) {
    if (y == touch_new_.size() || (x < touch_old_.size() && touch_old_[x].key < touch_new_[y].key))
      end_.push_back(touch_old_[x++].event);
    else if (x == touch_old_.size() || touch_new_[y].key < touch_old_[x].key)
      begin_.push_back(touch_new_[y++].event);
    else
      ++x, ++y;
  }
}

void ContactSet::touching_pairs(const std::vector<ContactRecord>& list, std::vector<TouchKey>& keys) {
  keys.clear();
  for (const ContactRecord& r : list)
    if (r.touching() && (keys.empty() || keys.back().key != r.key))
      keys.push_back({r.key, {{r.index_a(), r.gen_a}, {r.index_b(), r.gen_b}}});
}

void ContactSet::set_records(std::vector<ContactRecord>&& records) {
  records_ = std::move(records);
  touching_pairs(records_, touch_new_);
  touch_old_.clear();
  begin_.clear();
  end_.clear();
}

void ContactSet::hash_into(StateHasher& h) const {
  h.add_u64(records_.size());
  for (const ContactRecord& r : records_) {
    h.add_u64(r.key);
    h.add_u64((uint64_t{r.sub} << 32) | r.manifold.count);
    h.add_float(r.manifold.normal.x), h.add_float(r.manifold.normal.y), h.add_float(r.manifold.normal.z);
    for (uint32_t j = 0; j < r.manifold.count; ++j) {
      const ContactPoint& p = r.manifold.points[j];
      h.add_u32(p.feature_id);
      h.add_float(p.separation);
      h.add_float(r.normal_impulse[j]);
    }
    for (float f : r.friction_impulse) h.add_float(f);
  }
}

}  // namespace gyro::detail
