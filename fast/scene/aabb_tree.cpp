// Broad phase: AABB tree build, refit and the self pair query.
#include "fast/scene/aabb_tree.h"

#include <algorithm>
#include <atomic>
#include <numeric>

#include "fast/scene/parallel.h"

namespace revdist {

std::int32_t AabbTree::build_range(const std::vector<Aabb>& boxes, std::int32_t* items, std::int32_t n) {
  const auto id = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  if (n == 1) {
    nodes_[id].box = boxes[items[0]];
    nodes_[id].item = items[0];
    return id;
  }
  Aabb centres{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (std::int32_t i = 0; i < n; ++i) {
    const Vec3 c = boxes[items[i]].lo + boxes[items[i]].hi;
    centres.lo = centres.lo.cwiseMin(c);
    centres.hi = centres.hi.cwiseMax(c);
  }
  int axis = 0;
  (centres.hi - centres.lo).maxCoeff(&axis);
  // Ties broken by index: the same boxes give the same tree.
  std::nth_element(items, items + n / 2, items + n, [&](std::int32_t a, std::int32_t b) {
    const double ca = boxes[a].lo[axis] + boxes[a].hi[axis], cb = boxes[b].lo[axis] + boxes[b].hi[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const std::int32_t l = build_range(boxes, items, n / 2);
  const std::int32_t r = build_range(boxes, items + n / 2, n - n / 2);
  nodes_[id].left = l;
  nodes_[id].right = r;
  nodes_[id].box = nodes_[l].box.merged(nodes_[r].box);
  return id;
}

void AabbTree::build(const std::vector<Aabb>& boxes) {
  nodes_.clear();
  ++builds_;
  if (boxes.empty()) return;
  nodes_.reserve(2 * boxes.size() - 1);
  std::vector<std::int32_t> items(boxes.size());
  std::iota(items.begin(), items.end(), 0);
  build_range(boxes, items.data(), static_cast<std::int32_t>(items.size()));
  built_area_ = internal_area();
}

double AabbTree::internal_area() const {
  double s = 0.0;
  for (const Node& n : nodes_)
    if (!n.leaf()) s += n.box.half_area();
  return s;
}

bool AabbTree::refit(const std::vector<Aabb>& boxes, double rebuild_ratio) {
  if (nodes_.empty() || (nodes_.size() + 1) / 2 != boxes.size()) {
    build(boxes);
    return false;
  }
  // Children are created after their parent, so a reverse sweep is bottom-up.
  for (std::size_t k = nodes_.size(); k-- > 0;) {
    Node& n = nodes_[k];
    n.box = n.leaf() ? boxes[n.item] : nodes_[n.left].box.merged(nodes_[n.right].box);
  }
  if (internal_area() > rebuild_ratio * built_area_) {
    build(boxes);
    return false;
  }
  return true;
}

void AabbTree::cross(std::int32_t a, std::int32_t b, double d, std::vector<std::pair<std::int32_t, std::int32_t>>* out,
                     std::size_t cap) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (out->size() > cap || na.box.gap(nb.box) > d) return;
  if (na.leaf() && nb.leaf()) {
    out->emplace_back(std::min(na.item, nb.item), std::max(na.item, nb.item));
    return;
  }
  // Descend the bigger box (a leaf cannot be split).
  if (nb.leaf() || (!na.leaf() && na.box.half_area() >= nb.box.half_area())) {
    cross(na.left, b, d, out, cap);
    cross(na.right, b, d, out, cap);
  } else {
    cross(a, nb.left, d, out, cap);
    cross(a, nb.right, d, out, cap);
  }
}

double AabbTree::pairs_within(double d, std::vector<std::pair<std::int32_t, std::int32_t>>* out, int threads,
                              std::size_t limit, bool* over) const {
  if (over) *over = false;
  if (nodes_.empty()) return 0.0;
  // Every pair has one lowest common ancestor, whose two subtrees it crosses:
  // one independent task per internal node. Gathered in node order, so the
  // output is the same for any number of threads.
  std::vector<std::int32_t> inner;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    if (!nodes_[k].leaf()) inner.push_back(static_cast<std::int32_t>(k));
  // Tasks in a fixed number of consecutive groups (a vector each, not one per
  // node; the same groups on one thread); the groups are then copied to their
  // places in parallel too.
  const std::size_t groups = std::min<std::size_t>(inner.size(), 64);
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> part(groups);
  // Past the limit every group stops: each checks the running total after
  // each node, and no group's own list grows past the limit.
  std::atomic<std::size_t> total{0};
  double workers = parallel_for(groups, threads, [&](std::size_t g) {
    for (std::size_t i = inner.size() * g / groups; i < inner.size() * (g + 1) / groups; ++i) {
      if (total.load(std::memory_order_relaxed) > limit) return;
      const std::size_t before = part[g].size();
      cross(nodes_[inner[i]].left, nodes_[inner[i]].right, d, &part[g], limit);
      total.fetch_add(part[g].size() - before, std::memory_order_relaxed);
    }
  });
  if (total.load() > limit) {
    if (over) *over = true;
    return workers;
  }
  std::vector<std::size_t> at(groups + 1, out->size());
  for (std::size_t g = 0; g < groups; ++g) at[g + 1] = at[g] + part[g].size();
  out->resize(at[groups]);
  workers += parallel_for(groups, threads, [&](std::size_t g) { std::copy(part[g].begin(), part[g].end(), out->begin() + at[g]); });
  return workers;
}

}  // namespace revdist
