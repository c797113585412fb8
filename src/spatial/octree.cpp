// The octree (gyro/octree.hpp): build by recursive octant splits, queries by pruning with
// the nodes' content bounds.
//
// Exactness of the pruning: a node's content bounds are the float min / max of the corners
// c - e, c + e of the items stored beneath it, the very values gyro's AABB tests compute. So
//  - AABB region: an item's interval test passing implies the node's, by transitivity of
//    the same float comparisons;
//  - sphere: the clamped per-axis distance from the centre to the node is at most that to
//    the item (clamping is exact), and float subtraction, squaring and addition are
//    monotone; the node test compares against r^2 (1 + 2^-16) so a different summation
//    order in gyro's test cannot matter;
//  - frustum: detail::frustum_may_touch culls only boxes outside a plane by 1e-4 of the
//    magnitudes, 25 times intersects()'s tolerance, and a node's box contains the item's.
// Items are then tested with gyro's own functions, so a query equals the brute-force loop.
#include "gyro/octree.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"
#include "gyro/overlap.hpp"

#include <algorithm>
#include <cmath>

namespace gyro {
namespace {

using detail::fail;

constexpr float kInf = __builtin_inff();
constexpr std::size_t kMaxCount = 0x7FFFFFFF;

Status check_def(const OctreeDef& def) {
  if (def.max_depth < 0 || def.max_depth > kOctreeMaxDepth)
    return fail(Status::invalid_argument, "OctreeDef.max_depth %d is outside [0, %d]", int(def.max_depth),
                int(kOctreeMaxDepth));
  if (def.leaf_capacity < 1 || def.leaf_capacity > (1 << 20))
    return fail(Status::invalid_argument, "OctreeDef.leaf_capacity %d is outside [1, 2^20]", int(def.leaf_capacity));
  return Status::ok;
}


Status check_box(const AABB& b, const char* what, std::size_t i) {
  if (!gyro::is_finite(b.center) || !gyro::is_finite(b.half_extents)) return fail(Status::non_finite, "%s[%zu] is not finite", what, i);
  if (!(b.half_extents.x >= 0.0f && b.half_extents.y >= 0.0f && b.half_extents.z >= 0.0f))
    return fail(Status::invalid_argument, "%s[%zu] has a negative half extent", what, i);
  const vec3 lo = aabb_min(b), hi = aabb_max(b);
  if (!gyro::is_finite(lo) || !gyro::is_finite(hi)) return fail(Status::non_finite, "%s[%zu]'s corners overflow float", what, i);
  return Status::ok;
}

struct Corners {
  float lo[3], hi[3];
};

Corners corners_of(const AABB& b) {
  const vec3 lo = aabb_min(b), hi = aabb_max(b);
  return {{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}};
}

bool box_box(const float alo[3], const float ahi[3], const float blo[3], const float bhi[3]) {
  return alo[0] <= bhi[0] && blo[0] <= ahi[0] && alo[1] <= bhi[1] && blo[1] <= ahi[1] && alo[2] <= bhi[2] &&
         blo[2] <= ahi[2];
}

// Squared distance from c to the box, clamped per axis (see the header comment).
bool sphere_may_touch(const Sphere& s, const float lo[3], const float hi[3]) {
  const float c[3] = {s.center.x, s.center.y, s.center.z};
  float d2 = 0.0f;
  for (int a = 0; a < 3; ++a) {
    const float q = std::min(hi[a], std::max(lo[a], c[a]));
    const float d = c[a] - q;
    d2 = d2 + d * d;
  }
  const float r2 = s.radius * s.radius;
  return d2 <= r2 + r2 * 0x1p-16f;
}

// Recursive builder over item positions (into the id-sorted arrays).
class Builder {
 public:
  Builder(const std::vector<Corners>& c, const OctreeDef& def, std::vector<OctreeNode>& nodes, std::vector<uint32_t>& refs)
      : c_(c), def_(def), nodes_(nodes), refs_(refs) {}

  void node(uint32_t index, std::vector<uint32_t> items) {
    OctreeNode& n = nodes_[index];
    for (int a = 0; a < 3; ++a) n.lo[a] = kInf, n.hi[a] = -kInf;
    for (uint32_t i : items)
      for (int a = 0; a < 3; ++a) n.lo[a] = std::min(n.lo[a], c_[i].lo[a]), n.hi[a] = std::max(n.hi[a], c_[i].hi[a]);
    if (items.size() > std::size_t(def_.leaf_capacity) && n.depth < uint32_t(def_.max_depth)) {
      float mid[3];
      // Halves first: no overflow, and the rounded sum stays within the cell.
      for (int a = 0; a < 3; ++a) mid[a] = n.cell_lo[a] * 0.5f + n.cell_hi[a] * 0.5f;
      std::vector<uint32_t> kids[8];
      bool progress = false;
      for (int k = 0; k < 8; ++k) {
        float lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
          const bool upper = (k >> a) & 1;
          lo[a] = upper ? mid[a] : n.cell_lo[a];
          hi[a] = upper ? n.cell_hi[a] : mid[a];
        }
        for (uint32_t i : items)
          if (box_box(c_[i].lo, c_[i].hi, lo, hi)) kids[k].push_back(i);
        progress = progress || kids[k].size() < items.size();
      }
      if (progress) {
        const uint32_t first = uint32_t(nodes_.size());
        const uint32_t depth = n.depth + 1;
        const OctreeNode parent = n;
        nodes_[index].first_child = first;  // `n` may dangle once nodes_ grows
        nodes_.resize(nodes_.size() + 8);
        for (int k = 0; k < 8; ++k) {
          OctreeNode& child = nodes_[first + k];
          for (int a = 0; a < 3; ++a) {
            const bool upper = (k >> a) & 1;
            child.cell_lo[a] = upper ? mid[a] : parent.cell_lo[a];
            child.cell_hi[a] = upper ? parent.cell_hi[a] : mid[a];
          }
          child.depth = depth;
        }
        items.clear();
        items.shrink_to_fit();
        for (int k = 0; k < 8; ++k) node(first + uint32_t(k), std::move(kids[k]));
        return;
      }
    }
    n.first_child = kOctreeLeaf;
    n.first_item = uint32_t(refs_.size());
    n.item_count = uint32_t(items.size());
    refs_.insert(refs_.end(), items.begin(), items.end());
  }

 private:
  const std::vector<Corners>& c_;
  const OctreeDef& def_;
  std::vector<OctreeNode>& nodes_;
  std::vector<uint32_t>& refs_;
};

}  // namespace

namespace detail {

bool frustum_may_touch(const Frustum& f, const float lo[3], const float hi[3]) {
  float c[3], e[3], mag = 0.0f, ext = 0.0f;
  for (int a = 0; a < 3; ++a) {
    c[a] = lo[a] * 0.5f + hi[a] * 0.5f;
    e[a] = hi[a] * 0.5f - lo[a] * 0.5f;
    mag = std::max(mag, std::abs(c[a]));
    ext = std::max(ext, e[a]);
  }
  for (const Plane& p : f.planes) {
    const float dist = (p.normal.x * c[0] + p.normal.y * c[1]) + p.normal.z * c[2] - p.distance;
    const float r = (e[0] * std::abs(p.normal.x) + e[1] * std::abs(p.normal.y)) + e[2] * std::abs(p.normal.z);
    const float tol = 1e-4f * ((std::abs(p.distance) + mag) + 3.0f * ext) + 1e-30f;
    if ((dist + r) + tol < 0.0f) return false;
  }
  return true;
}

Status check_frustum(const Frustum& f, const char* what) {
  for (int k = 0; k < 6; ++k) {
    const Plane& p = f.planes[k];
    if (!gyro::is_finite(p.normal) || !is_finite(p.distance)) return fail(Status::non_finite, "%s plane %d is not finite", what, k);
  }
  return Status::ok;
}

}  // namespace detail

Status Octree::build(const AABB* boxes, const uint32_t* ids, std::size_t count, const OctreeDef& def) {
  GYRO_TRY(check_def(def));
  if (count >= kMaxCount) return fail(Status::invalid_count, "octree item count %zu must be below 2^31 - 1", count);
  if (count > 0) {
    GYRO_TRY(detail::require_not_null(boxes, "boxes"));
    GYRO_TRY(detail::require_not_null(ids, "ids"));
  }
  for (std::size_t i = 0; i < count; ++i) GYRO_TRY(check_box(boxes[i], "boxes", i));
  std::vector<uint32_t> order(count);
  for (std::size_t i = 0; i < count; ++i) order[i] = uint32_t(i);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return ids[a] < ids[b]; });
  for (std::size_t i = 1; i < count; ++i)
    if (ids[order[i]] == ids[order[i - 1]]) return fail(Status::invalid_argument, "octree id %u appears twice", ids[order[i]]);

  std::vector<uint32_t> sorted_ids(count);
  std::vector<AABB> sorted_boxes(count);
  std::vector<Corners> corners(count);
  for (std::size_t i = 0; i < count; ++i) {
    sorted_ids[i] = ids[order[i]];
    sorted_boxes[i] = boxes[order[i]];
    corners[i] = corners_of(sorted_boxes[i]);
  }
  std::vector<OctreeNode> nodes(1);
  std::vector<uint32_t> refs;
  OctreeNode& root = nodes[0];
  for (int a = 0; a < 3; ++a) root.cell_lo[a] = kInf, root.cell_hi[a] = -kInf;
  for (const Corners& c : corners)
    for (int a = 0; a < 3; ++a)
      root.cell_lo[a] = std::min(root.cell_lo[a], c.lo[a]), root.cell_hi[a] = std::max(root.cell_hi[a], c.hi[a]);
  if (count == 0)
    for (int a = 0; a < 3; ++a) root.cell_lo[a] = root.cell_hi[a] = 0.0f;
  std::vector<uint32_t> all(count);
  for (std::size_t i = 0; i < count; ++i) all[i] = uint32_t(i);
  Builder(corners, def, nodes, refs).node(0, std::move(all));

  def_ = def;
  nodes_ = std::move(nodes);
  refs_ = std::move(refs);
  ids_ = std::move(sorted_ids);
  boxes_ = std::move(sorted_boxes);
  return Status::ok;
}

void Octree::clear() {
  AABB none{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
  build(&none, nullptr, 0, def_);
}

OctreeStats Octree::stats() const {
  OctreeStats s;
  s.items = ids_.size();
  s.nodes = nodes_.size();
  s.references = refs_.size();
  for (const OctreeNode& n : nodes_)
    if (n.first_child == kOctreeLeaf) ++s.leaves, s.max_depth = std::max<std::size_t>(s.max_depth, n.depth);
  s.bytes = nodes_.size() * sizeof(OctreeNode) + refs_.size() * sizeof(uint32_t) +
            ids_.size() * (sizeof(uint32_t) + sizeof(AABB));
  return s;
}

template <class NodeTest, class ItemTest>
void Octree::collect(NodeTest&& node_test, ItemTest&& item_test, std::vector<uint32_t>& out) const {
  out.clear();
  if (nodes_.empty()) return;
  uint32_t stack[8 * (kOctreeMaxDepth + 2)];
  int sp = 0;
  stack[sp++] = 0;
  std::vector<uint32_t> hits;
  while (sp > 0) {
    const OctreeNode& n = nodes_[stack[--sp]];
    if (!(n.lo[0] <= n.hi[0]) || !node_test(n.lo, n.hi)) continue;
    if (n.first_child != kOctreeLeaf) {
      for (uint32_t k = 8; k-- > 0;) stack[sp++] = n.first_child + k;
      continue;
    }
    for (uint32_t r = n.first_item; r < n.first_item + n.item_count; ++r)
      if (item_test(boxes_[refs_[r]])) hits.push_back(refs_[r]);
  }
  // Positions are in ascending id order, so sorting them sorts the ids.
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
  out.reserve(hits.size());
  for (uint32_t h : hits) out.push_back(ids_[h]);
}

Status Octree::query(const AABB& region, std::vector<uint32_t>& out) const {
  out.clear();
  GYRO_TRY(check_box(region, "region", 0));
  const Corners q = corners_of(region);
  collect([&](const float lo[3], const float hi[3]) { return box_box(lo, hi, q.lo, q.hi); },
          [&](const AABB& b) { return overlaps(b, region); }, out);
  return Status::ok;
}

Status Octree::query(const Sphere& sphere, std::vector<uint32_t>& out) const {
  out.clear();
  if (!gyro::is_finite(sphere.center) || !detail::is_finite(sphere.radius)) return fail(Status::non_finite, "sphere is not finite");
  if (!(sphere.radius >= 0.0f)) return fail(Status::invalid_argument, "sphere radius %g is negative", double(sphere.radius));
  collect([&](const float lo[3], const float hi[3]) { return sphere_may_touch(sphere, lo, hi); },
          [&](const AABB& b) { return overlaps(sphere, b); }, out);
  return Status::ok;
}

Status Octree::query(const Frustum& frustum, std::vector<uint32_t>& out) const {
  out.clear();
  GYRO_TRY(detail::check_frustum(frustum, "frustum"));
  collect([&](const float lo[3], const float hi[3]) { return detail::frustum_may_touch(frustum, lo, hi); },
          [&](const AABB& b) { return intersects(frustum, b); }, out);
  return Status::ok;
}

}  // namespace gyro
