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

// Number of crossings of the ray {(r, q.z) : r > q.r} with the arc, half-open in
// z ([lo, hi) of each z-monotone part) so shared end points count once.
int arc_crossings(const Arc2& a, const Vec2& q) {
  // Split the arc at its z extremes (tangent horizontal) into monotone parts.
  double cuts[4] = {0.0, a.length, a.length, a.length};
  int nc = 2;
  if (!a.straight()) {
    const double theta0 = std::atan2(a.tangent.y(), a.tangent.x());
    // Tangent angle theta0 + k s; horizontal where it is a multiple of pi.
    const double ks_end = a.curvature * a.length;
    const double lo = std::min(0.0, ks_end), hi = std::max(0.0, ks_end);
    for (int m = static_cast<int>(std::ceil((theta0 + lo) / M_PI)); m * M_PI <= theta0 + hi && nc < 4; ++m) {
      const double s = (m * M_PI - theta0) / a.curvature;
      if (s > 0 && s < a.length) cuts[nc++] = s;
    }
    std::sort(cuts, cuts + nc);
  }
  int count = 0;
  for (int i = 0; i + 1 < nc; ++i) {
    const Vec2 p = a.point(cuts[i]), r = a.point(cuts[i + 1]);
    const double zlo = std::min(p.y(), r.y()), zhi = std::max(p.y(), r.y());
    if (!(q.y() >= zlo && q.y() < zhi)) continue;
    // The crossing on this monotone part: bisection on z (robust, off the hot path).
    double s0 = cuts[i], s1 = cuts[i + 1];
    const bool up = r.y() > p.y();
    for (int it = 0; it < 80; ++it) {
      const double sm = 0.5 * (s0 + s1);
      if ((a.point(sm).y() < q.y()) == up) s0 = sm; else s1 = sm;
    }
    if (a.point(0.5 * (s0 + s1)).x() > q.x()) ++count;
  }
  return count;
}

}  // namespace

Side profile_side(const BiarcTree& tree, const Vec2& q, double margin) {
  double dmin = std::numeric_limits<double>::infinity();
  int crossings = 0;
  double eps = 0.0;
  for (const BiarcNode& n : tree.nodes) {
    if (!n.leaf() || n.fit < 0) continue;
    const BiarcFit& f = tree.fits[n.fit];
    eps = std::max(eps, f.eps);
    for (int i = 0; i < f.arcs; ++i) {
      dmin = std::min(dmin, arc_distance(f.arc[i], q));
      crossings += arc_crossings(f.arc[i], q);
    }
  }
  if (!(dmin > margin + eps)) return Side::unknown;
  return crossings % 2 ? Side::inside : Side::outside;
}

}  // namespace revdist
