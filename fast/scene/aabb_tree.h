// Broad phase of a scene: a bounding-volume tree over the instances' world
// boxes, rebuilt top-down when its boxes have drifted and refitted (same
// topology, boxes recomputed bottom-up) when instances move a little.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/vec.h"

namespace revdist {

struct Aabb {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  // Euclidean gap between two boxes: a lower bound on the distance of anything inside them.
  double gap(const Aabb& o) const {
    const Vec3 d = (lo - o.hi).cwiseMax(o.lo - hi).cwiseMax(0.0);
    return d.norm();
  }
  Aabb merged(const Aabb& o) const { return {lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)}; }
  double half_area() const {
    const Vec3 e = hi - lo;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }
};

class AabbTree {
 public:
  // Builds over boxes[0..n): median split of the centres on the widest axis
  // (deterministic, so answers do not depend on history).
  void build(const std::vector<Aabb>& boxes);
  // Same topology, new boxes (same count). Returns false, and rebuilds, when
  // the summed half areas of the internal boxes exceed `rebuild_ratio` times
  // those of a fresh build (moving instances have loosened the tree).
  bool refit(const std::vector<Aabb>& boxes, double rebuild_ratio = 2.0);

  // Every pair i < j of boxes whose gap is <= d, appended in an order that
  // depends on the tree only (not on the number of threads). Returns the CPU
  // seconds of the worker threads besides the caller's (0 on one thread).
  // More than `limit` pairs: stops early, with *over set and out left as it
  // was; a distance that takes in every pair of 20000 boxes would
  // otherwise gather 2e8 pairs (3 GB) before anything could refuse it.
  double pairs_within(double d, std::vector<std::pair<std::int32_t, std::int32_t>>* out, int threads = 1,
                      std::size_t limit = SIZE_MAX, bool* over = nullptr) const;

  // Nodes of the tree (2n - 1 for n boxes); builds done so far (1 + refits that rebuilt).
  std::size_t size() const { return nodes_.size(); }
  long builds() const { return builds_; }

  struct Node {
    Aabb box;
    std::int32_t left = -1, right = -1;  // children; -1 for a leaf
    std::int32_t item = -1;              // the box index at a leaf
    bool leaf() const { return left < 0; }
  };
  const std::vector<Node>& nodes() const { return nodes_; }

 private:
  std::int32_t build_range(const std::vector<Aabb>& boxes, std::int32_t* items, std::int32_t n);
  double internal_area() const;
  void cross(std::int32_t a, std::int32_t b, double d, std::vector<std::pair<std::int32_t, std::int32_t>>* out,
             std::size_t cap) const;

  std::vector<Node> nodes_;  // nodes_[0] is the root
  double built_area_ = 0.0;
  long builds_ = 0;
};

}  // namespace revdist
