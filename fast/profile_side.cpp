// Point-in-profile test on the biarcs of a tree (ray crossing to r = +inf).
#include "fast/profile_side.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace revdist {

namespace {

// Distance from q to an arc or segment.
double arc_distance(const Arc2& a, const Vec2& q) {
  const Vec2 p0 = a.start, p1 = a.end();
  if (a.straight()) {
    const Vec2 d = p1 - p0;
    const double l2 = d.squaredNorm();
    const double s = l2 > 0 ? std::clamp((q - p0).dot(d) / l2, 0.0, 1.0) : 0.0;
    return (q - (p0 + s * d)).norm();
  }
  const Vec2 c = a.center();
  const double rho = 1.0 / std::abs(a.curvature);
  const Vec2 v = q - c, d0 = a.start - c;
  double phi = std::atan2(d0.x() * v.y() - d0.y() * v.x(), d0.dot(v));
  const double sweep = a.curvature * a.length;
  if (sweep < 0) phi = -phi;
  if (phi < 0) phi += 2 * M_PI;
  if (phi <= std::abs(sweep)) return std::abs(v.norm() - rho);
  return std::min((q - p0).norm(), (q - p1).norm());
}

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

double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double s = l2 > 0 ? std::clamp((q - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (q - (a + s * d)).norm();
}

// Distance between the ray q + t d (t >= 0, d unit) and segment [a, b]: 0 when
// they cross, else attained at an end point of one of them.
double ray_segment_distance(const Vec2& q, const Vec2& d, const Vec2& a, const Vec2& b) {
  const Vec2 nrm(-d.y(), d.x());
  const double sa = nrm.dot(a - q), sb = nrm.dot(b - q);
  if ((sa <= 0) != (sb <= 0) || sa == 0 || sb == 0) {
    const double t = sa == sb ? d.dot(a - q) : d.dot(a + (sa / (sa - sb)) * (b - a) - q);
    if (t >= 0) return 0.0;
  }
  auto to_ray = [&](const Vec2& p) {
    const double t = std::max(0.0, d.dot(p - q));
    return (p - (q + t * d)).norm();
  };
  return std::min({to_ray(a), to_ray(b), segment_distance(q, a, b)});
}

// Calls leaf(fit) for every leaf whose node capsule, widened by `pad`, passes
// near(node) (a test that holds for a subtree's capsule whenever it holds for
// any of its leaves' fits); false when the tree is too deep for the stack (the
// caller then scans every leaf).
template <class Near, class Leaf>
bool visit(const BiarcTree& tree, Near near, Leaf leaf) {
  std::int32_t stack[128];
  int n = 0;
  stack[n++] = 0;
  while (n > 0) {
    const BiarcNode& node = tree.nodes[stack[--n]];
    if (!near(node)) continue;
    if (node.leaf()) {
      if (node.fit >= 0 && !leaf(tree.fits[node.fit])) return true;
      continue;
    }
    if (n + 2 > 128) return false;
    stack[n++] = node.child + 1;
    stack[n++] = node.child;
  }
  return true;
}

}  // namespace

Side profile_side(const BiarcTree& tree, const Vec2& q, double margin) {
  if (tree.nodes.empty()) return Side::unknown;
  // Every leaf's biarcs lie within its eps of the profile part its capsule
  // holds, so within capsule radius + max_error of the capsule's segment: the
  // tree is descended only where that can reach q or the ray.
  const double eps = tree.max_error;
  const BiarcNode& root = tree.nodes[0];
  const double size = std::max(root.seg_a.norm(), root.seg_b.norm()) + root.radius + eps;
  const bool descend = std::isfinite(eps) && std::isfinite(size);
  double dmin = std::numeric_limits<double>::infinity();
  auto arcs_distance = [&](const BiarcFit& f) {
    for (int i = 0; i < f.arcs; ++i) dmin = std::min(dmin, arc_distance(f.arc[i], q));
    return true;
  };
  const double reach = margin + eps;  // what must stay clear of q
  const bool visited = descend && visit(tree, [&](const BiarcNode& n) {
    return segment_distance(q, n.seg_a, n.seg_b) - n.radius - eps <= reach;
  }, arcs_distance);
  if (!visited) {
    dmin = std::numeric_limits<double>::infinity();
    for (const BiarcNode& n : tree.nodes)
      if (n.leaf() && n.fit >= 0) arcs_distance(tree.fits[n.fit]);
  }
  if (!(dmin > reach)) return Side::unknown;
  // Parity of a ray's crossings. The ray goes towards larger r (it never meets
  // the axis segment that closes an axis-to-axis profile) in a direction that
  // passes no arc end point and touches no arc within rounding; shared end
  // points of consecutive arcs differ by rounding, so a ray through one could
  // be counted twice or not at all.
  const double tol = 1e-12 * std::max(size, q.norm()) + 1e-300;
  for (int attempt = 0; attempt < 16; ++attempt) {
    // Directions spread over (-60, 60) degrees around +r, irrational steps.
    const double angle = (attempt == 0 ? 0.1234567 : std::fmod(0.1234567 + attempt * 0.7390851, 2.0) - 1.0) * 1.0471975;
    const Vec2 d(std::cos(angle), std::sin(angle));
    int crossings = 0;
    bool ambiguous = false;
    auto cross = [&](const BiarcFit& f) {
      for (int i = 0; i < f.arcs && !ambiguous; ++i) {
        if (f.arc[i].length <= 0) continue;
        const int k = arc_crossings(f.arc[i], q, d, tol);
        if (k < 0) ambiguous = true; else crossings += k;
      }
      return !ambiguous;
    };
    // arc_crossings calls an end point within tol of the ray (from tol
    // behind q) ambiguous: subtrees farther than that from it are skipped.
    const Vec2 q0 = q - tol * d;
    bool ok = descend && visit(tree, [&](const BiarcNode& n) {
      return ray_segment_distance(q0, d, n.seg_a, n.seg_b) - n.radius - eps <= 2 * tol;
    }, cross);
    if (!ok) {
      crossings = 0;
      ambiguous = false;
      for (const BiarcNode& n : tree.nodes)
        if (n.leaf() && n.fit >= 0 && !cross(tree.fits[n.fit])) break;
    }
    if (!ambiguous) return crossings % 2 ? Side::inside : Side::outside;
  }
  return Side::unknown;
}

}  // namespace revdist
