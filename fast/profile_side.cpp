// Point-in-profile test on the biarcs of a tree (ray crossing to r = +inf).
#include "fast/profile_side.h"

#include <algorithm>
#include <cmath>
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

}  // namespace

Side profile_side(const BiarcTree& tree, const Vec2& q, double margin) {
  double dmin = std::numeric_limits<double>::infinity();
  double eps = 0.0, size = 0.0;
  for (const BiarcNode& n : tree.nodes) {
    if (!n.leaf() || n.fit < 0) continue;
    const BiarcFit& f = tree.fits[n.fit];
    eps = std::max(eps, f.eps);
    for (int i = 0; i < f.arcs; ++i) {
      dmin = std::min(dmin, arc_distance(f.arc[i], q));
      size = std::max({size, f.arc[i].start.norm(), f.arc[i].end().norm()});
    }
  }
  if (!(dmin > margin + eps)) return Side::unknown;
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
    for (const BiarcNode& n : tree.nodes) {
      if (!n.leaf() || n.fit < 0) continue;
      const BiarcFit& f = tree.fits[n.fit];
      for (int i = 0; i < f.arcs && !ambiguous; ++i) {
        if (f.arc[i].length <= 0) continue;
        const int k = arc_crossings(f.arc[i], q, d, tol);
        if (k < 0) ambiguous = true; else crossings += k;
      }
      if (ambiguous) break;
    }
    if (!ambiguous) return crossings % 2 ? Side::inside : Side::outside;
  }
  return Side::unknown;
}

}  // namespace revdist
