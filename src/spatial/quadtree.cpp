// The 2D quadtree (gyro/quadtree.hpp).
//
// Exactness of the pruning: an item lives in a node only if item.lo >= node.lo and
// item.hi <= node.hi (float comparisons on the stored corners), so whenever the item
// overlaps a query region the node does too, with the same comparisons: a rectangle
// region's interval tests follow by transitivity, and a circle's clamped distance to the
// node is at most its distance to the item because float subtraction, squaring and
// addition are monotone. Pruning therefore never drops an item that the brute-force test
// would keep, and the items are tested with exactly gyro::overlaps' arithmetic.
#include "gyro/quadtree.hpp"

#include "core/error.hpp"
#include "gyro/math_scalar.hpp"

#include <algorithm>
#include <cmath>

namespace gyro {
namespace {

bool finite(const vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

Status check_rectangle(const Rectangle2D& r, const char* what) {
  if (!finite(r.origin) || !finite(r.size) || !finite(r.origin + r.size))
    return detail::fail(Status::non_finite, "%s is not finite", what);
  if (!(r.size.x >= 0.0f && r.size.y >= 0.0f)) return detail::fail(Status::invalid_argument, "%s has a negative size", what);
  return Status::ok;
}

Status check_def(const QuadtreeDef& def) {
  if (Status s = check_rectangle(def.bounds, "QuadtreeDef.bounds"); s != Status::ok) return s;
  if (def.max_depth < 0 || def.max_depth > kQuadtreeMaxDepth)
    return detail::fail(Status::invalid_argument, "QuadtreeDef.max_depth %d is outside [0, %d]", int(def.max_depth),
                        int(kQuadtreeMaxDepth));
  if (def.split_threshold < 1 || def.split_threshold > (1 << 20))
    return detail::fail(Status::invalid_argument, "QuadtreeDef.split_threshold %d is outside [1, 2^20]",
                        int(def.split_threshold));
  return Status::ok;
}

/// The same comparisons as overlaps(Rectangle2D, Rectangle2D).
bool box_box(const vec2& alo, const vec2& ahi, const vec2& blo, const vec2& bhi) {
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y;
}

/// The same arithmetic as overlaps(Circle, Rectangle2D).
bool circle_box(const vec2& c, float r, const vec2& lo, const vec2& hi) {
  const vec2 d = c - vec2{clamp(c.x, lo.x, hi.x), clamp(c.y, lo.y, hi.y)};
  return dot(d, d) <= r * r;
}

}  // namespace

Quadtree::Quadtree() { reset_nodes(); }

Quadtree::Quadtree(const QuadtreeDef& def) {
  if (check_def(def) == Status::ok) def_ = def;
  reset_nodes();
}

void Quadtree::reset_nodes() {
  nodes_.clear();
  free_blocks_.clear();
  Node root;
  root.lo = def_.bounds.origin;
  root.hi = def_.bounds.origin + def_.bounds.size;
  nodes_.push_back(std::move(root));
}

Status Quadtree::configure(const QuadtreeDef& def) {
  if (Status s = check_def(def); s != Status::ok) return s;
  std::vector<Entry> all;
  gather(0, all);
  // Reinserted in id order; the resulting shape would be the same in any order.
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.id < b.id; });
  def_ = def;
  reset_nodes();
  for (const Entry& e : all) place(0, e);
  return Status::ok;
}

void Quadtree::clear() {
  where_.clear();
  reset_nodes();
}

Status Quadtree::insert(uint32_t id, const Rectangle2D& bounds) {
  if (Status s = check_rectangle(bounds, "quadtree item bounds"); s != Status::ok) return s;
  if (has(id)) return detail::fail(Status::invalid_argument, "quadtree id %u is already in the tree", id);
  place(0, Entry{id, bounds, bounds.origin + bounds.size});
  return Status::ok;
}

Status Quadtree::remove(uint32_t id) {
  if (!has(id)) return detail::fail(Status::stale_id, "quadtree id %u is not in the tree", id);
  erase(id);
  return Status::ok;
}

Status Quadtree::update(uint32_t id, const Rectangle2D& bounds) {
  if (Status s = check_rectangle(bounds, "quadtree item bounds"); s != Status::ok) return s;
  if (!has(id)) return detail::fail(Status::stale_id, "quadtree id %u is not in the tree", id);
  erase(id);
  place(0, Entry{id, bounds, bounds.origin + bounds.size});
  return Status::ok;
}

Status Quadtree::bounds_of(uint32_t id, Rectangle2D* out) const {
  if (!out) return detail::fail(Status::null_argument, "out is null");
  const auto it = where_.find(id);
  if (it == where_.end()) return detail::fail(Status::stale_id, "quadtree id %u is not in the tree", id);
  for (const Entry& e : nodes_[it->second].entries)
    if (e.id == id) {
      *out = e.rect;
      return Status::ok;
    }
  return detail::fail(Status::internal, "quadtree id %u is missing from its node", id);
}

int32_t Quadtree::child_fitting(int32_t node, const Entry& e) const {
  const int32_t first = nodes_[node].children;
  for (int32_t k = 0; k < 4; ++k) {
    const Node& c = nodes_[first + k];
    if (e.rect.origin.x >= c.lo.x && e.hi.x <= c.hi.x && e.rect.origin.y >= c.lo.y && e.hi.y <= c.hi.y)
      return first + k;
  }
  return -1;
}

void Quadtree::place(int32_t node, const Entry& e) {
  for (;;) {
    Node& n = nodes_[node];
    ++n.count;
    const int32_t child = n.children < 0 ? -1 : child_fitting(node, e);
    if (child < 0) {
      n.entries.push_back(e);
      where_[e.id] = node;
      if (n.children < 0 && n.count > uint32_t(def_.split_threshold) && n.depth < def_.max_depth) split(node);
      return;
    }
    node = child;
  }
}

void Quadtree::split(int32_t node) {
  int32_t first;
  if (!free_blocks_.empty()) {
    first = free_blocks_.back();
    free_blocks_.pop_back();
  } else {
    first = int32_t(nodes_.size());
    nodes_.resize(nodes_.size() + 4);
  }
  const vec2 lo = nodes_[node].lo, hi = nodes_[node].hi;
  const vec2 mid = lo + (hi - lo) * 0.5f;
  for (int32_t k = 0; k < 4; ++k) {
    Node& c = nodes_[first + k];
    c.lo = {(k & 1) ? mid.x : lo.x, (k & 2) ? mid.y : lo.y};
    c.hi = {(k & 1) ? hi.x : mid.x, (k & 2) ? hi.y : mid.y};
    c.children = -1;
    c.parent = node;
    c.depth = nodes_[node].depth + 1;
    c.count = 0;
    c.entries.clear();
  }
  nodes_[node].children = first;
  std::vector<Entry> keep;
  for (const Entry& e : nodes_[node].entries) {
    const int32_t c = child_fitting(node, e);
    if (c < 0) {
      keep.push_back(e);
      continue;
    }
    nodes_[c].entries.push_back(e);
    ++nodes_[c].count;
    where_[e.id] = c;
  }
  nodes_[node].entries = std::move(keep);
  for (int32_t k = 0; k < 4; ++k) {
    const Node& c = nodes_[first + k];
    if (c.count > uint32_t(def_.split_threshold) && c.depth < def_.max_depth) split(first + k);
  }
}

void Quadtree::gather(int32_t node, std::vector<Entry>& out) {
  Node& n = nodes_[node];
  out.insert(out.end(), n.entries.begin(), n.entries.end());
  n.entries.clear();
  const int32_t first = n.children;
  if (first < 0) return;
  n.children = -1;
  for (int32_t k = 0; k < 4; ++k) gather(first + k, out);
  free_blocks_.push_back(first);
}

void Quadtree::collapse(int32_t node) {
  std::vector<Entry> all;
  gather(node, all);
  for (const Entry& e : all) where_[e.id] = node;
  nodes_[node].entries = std::move(all);
}

void Quadtree::erase(uint32_t id) {
  const auto it = where_.find(id);
  const int32_t node = it->second;
  where_.erase(it);
  std::vector<Entry>& entries = nodes_[node].entries;
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (entries[i].id == id) {
      entries[i] = entries.back();
      entries.pop_back();
      break;
    }
  // The topmost node on the way up that no longer holds enough items to be split merges
  // its whole subtree back (its descendants hold no more items than it does).
  int32_t top = -1;
  for (int32_t m = node; m >= 0; m = nodes_[m].parent) {
    --nodes_[m].count;
    if (nodes_[m].children >= 0 && nodes_[m].count <= uint32_t(def_.split_threshold)) top = m;
  }
  if (top >= 0) collapse(top);
}

template <class Prune, class Test>
void Quadtree::collect(Prune prune, Test test, std::vector<uint32_t>& out) const {
  std::vector<int32_t> stack{0};  // the root is always visited: it holds items outside its bounds
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    for (const Entry& e : n.entries)
      if (test(e)) out.push_back(e.id);
    if (n.children >= 0)
      for (int32_t k = 3; k >= 0; --k)
        if (prune(nodes_[n.children + k])) stack.push_back(n.children + k);
  }
  std::sort(out.begin(), out.end());
}

Status Quadtree::query(const Rectangle2D& region, std::vector<uint32_t>& out) const {
  out.clear();
  if (Status s = check_rectangle(region, "query rectangle"); s != Status::ok) return s;
  const vec2 lo = region.origin, hi = region.origin + region.size;
  collect([&](const Node& n) { return box_box(n.lo, n.hi, lo, hi); },
          [&](const Entry& e) { return box_box(e.rect.origin, e.hi, lo, hi); }, out);
  return Status::ok;
}

Status Quadtree::query(const Circle& region, std::vector<uint32_t>& out) const {
  out.clear();
  if (!finite(region.center) || !std::isfinite(region.radius))
    return detail::fail(Status::non_finite, "query circle is not finite");
  if (!(region.radius >= 0.0f)) return detail::fail(Status::invalid_argument, "query circle has a negative radius");
  collect([&](const Node& n) { return circle_box(region.center, region.radius, n.lo, n.hi); },
          [&](const Entry& e) { return circle_box(region.center, region.radius, e.rect.origin, e.hi); }, out);
  return Status::ok;
}

std::vector<std::size_t> Quadtree::node_depth_histogram() const {
  std::vector<std::size_t> histogram;
  std::vector<int32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (histogram.size() <= std::size_t(n.depth)) histogram.resize(std::size_t(n.depth) + 1, 0);
    ++histogram[std::size_t(n.depth)];
    if (n.children >= 0)
      for (int32_t k = 0; k < 4; ++k) stack.push_back(n.children + k);
  }
  return histogram;
}

}  // namespace gyro
