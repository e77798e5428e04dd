// Point-in-profile test on the biarcs of a tree (ray crossing to r = +inf),
// descending only the capsules near the ray or near the point.
#include "fast/profile_side.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace revdist {

namespace {

// Crossings of the ray q + t d (t > 0) with the arc: 0, 1 or 2, or -1 when the
// ray passes within `tol` of one of its end points or touches it (the count
// would then depend on rounding; the caller tries another direction).
int arc_crossings(const Arc2& a, const Vec2& q, const Vec2& d, double tol) {
  const Vec2 p0 = a.start, p1 = a.end();
  const Vec2 nrm(-d.y(), d.x());
  // End points near the ray: ambiguous.
  for (const Vec2& e : {p0, p1})
    if (std::abs(nrm.dot(e - q)) <= tol && d.dot(e - q) > -tol) return -1;
  if (a.straight()) {
    const double s0 = nrm.dot(p0 - q), s1 = nrm.dot(p1 - q);
    if ((s0 < 0) == (s1 < 0)) return 0;
    const Vec2 x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
    return d.dot(x - q) > 0 ? 1 : 0;
  }
  // Circle of the arc against the line q + t d: |q + t d - c|^2 = R^2.
  const Vec2 c = a.center();
  const double R = 1.0 / std::abs(a.curvature);
  const Vec2 w = q - c;
  const double b = w.dot(d), cc = w.squaredNorm() - R * R;
  const double disc = b * b - cc;
  if (disc < 0) return 0;
  const double sq = std::sqrt(disc);
  if (sq <= tol) return -1;  // tangent: ambiguous
  const Vec2 d0 = a.start - c;
  const double sweep = a.curvature * a.length;
  int count = 0;
  for (double t : {-b - sq, -b + sq}) {
    if (!(t > 0)) continue;
    const Vec2 v = q + t * d - c;
    double phi = std::atan2(d0.x() * v.y() - d0.y() * v.x(), d0.dot(v));
    if (sweep < 0) phi = -phi;
    if (phi < 0) phi += 2 * M_PI;
    if (phi <= std::abs(sweep)) ++count;
  }
  return count;
}

// Distance between the ray q + t d (t >= 0, |d| = 1) and the segment a-b (0 when they meet).
double ray_segment_distance(const Vec2& q, const Vec2& d, const Vec2& a, const Vec2& b) {
  const Vec2 n(-d.y(), d.x());
  const double sa = n.dot(a - q), sb = n.dot(b - q);
  if ((sa <= 0) != (sb <= 0) || sa == 0 || sb == 0) {
    // The segment meets the ray's line at x; on the ray when ahead of q.
    const Vec2 x = sa == sb ? a : a + (sa / (sa - sb)) * (b - a);
    if (d.dot(x - q) >= 0) return 0.0;
  }
  auto to_ray = [&](const Vec2& p) { return (p - (q + std::max(0.0, d.dot(p - q)) * d)).norm(); };
  return std::min({to_ray(a), to_ray(b), point_segment_distance(q, a, b)});
}

}  // namespace

Side profile_side(BiarcTreeView& tree, const Vec2& q, double margin) {
  // The scale of rounding: the root capsule holds every profile point.
  const BiarcNode& root = tree.node(0);
  const double size = std::max(root.seg_a.norm(), root.seg_b.norm()) + (std::isfinite(root.radius) ? root.radius : 0.0);
  const double tol = 1e-12 * std::max(size, q.norm()) + 1e-300;
  // (The thread's stack, kept from call to call: the query tests a few
  // points each, and an allocation a call cost more than a short descent.)
  thread_local std::vector<std::int32_t> stack;
  for (int attempt = 0; attempt < 16; ++attempt) {
    // Directions spread over (-60, 60) degrees around +r, irrational steps.
    const double angle = (attempt == 0 ? 0.1234567 : std::fmod(0.1234567 + attempt * 0.7390851, 2.0) - 1.0) * 1.0471975;
    const Vec2 d(std::cos(angle), std::sin(angle));
    int crossings = 0;
    bool ambiguous = false;
    stack.assign(1, 0);
    while (!stack.empty() && !ambiguous) {
      const std::int32_t i = stack.back();
      stack.pop_back();
      const BiarcNode n = tree.node(i);  // a copy: children() may move the view's nodes
      // A capsule that misses the ray and keeps margin from q: its part of the
      // true curve neither crosses the ray nor comes near q.
      if (ray_segment_distance(q, d, n.seg_a, n.seg_b) - n.radius > tol &&
          point_segment_distance(q, n.seg_a, n.seg_b) - n.radius > margin)
        continue;
      if (!n.leaf()) {
        const std::int32_t c = tree.children(i);
        stack.push_back(c + 1);
        stack.push_back(c);
        continue;
      }
      if (n.fit < 0) return Side::unknown;
      const BiarcFit& f = tree.fit(n.fit);
      for (int k = 0; k < f.arcs; ++k)
        if (!(f.arc[k].distance(q) > margin + f.eps)) return Side::unknown;
      for (int k = 0; k < f.arcs && !ambiguous; ++k) {
        if (f.arc[k].length <= 0) continue;
        const int c = arc_crossings(f.arc[k], q, d, tol);
        if (c < 0) ambiguous = true; else crossings += c;
      }
    }
    if (!ambiguous) return crossings % 2 ? Side::inside : Side::outside;
  }
  return Side::unknown;
}

}  // namespace revdist
