// A circular arc or straight segment in the meridian plane (r, z), the unit of
// a biarc (paper section 4.1). Stored as start point, unit start tangent,
// signed curvature and arc length: this form stays sane as curvature -> 0, so
// straight input pieces are exact segments, never huge-radius arcs.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/vec.h"

namespace revdist {

struct Arc2 {
  Vec2 start = Vec2::Zero();
  Vec2 tangent = Vec2(1, 0);  // unit
  double curvature = 0.0;     // signed: > 0 turns counter-clockwise in (r, z)
  double length = 0.0;

  // Point at arc length s in [0, length].
  Vec2 point(double s) const {
    const Vec2 normal(-tangent.y(), tangent.x());
    const double ks = curvature * s;
    if (std::abs(ks) < 1e-4) {
      // Series of sin(ks)/k and (1-cos(ks))/k: exact as k -> 0.
      const double a = s * (1.0 - ks * ks / 6.0);
      const double b = s * (ks / 2.0 - ks * ks * ks / 24.0);
      return start + a * tangent + b * normal;
    }
    return start + (std::sin(ks) / curvature) * tangent + ((1.0 - std::cos(ks)) / curvature) * normal;
  }
  Vec2 tangent_at(double s) const {
    const double c = std::cos(curvature * s), sn = std::sin(curvature * s);
    return Vec2(c * tangent.x() - sn * tangent.y(), sn * tangent.x() + c * tangent.y());
  }
  Vec2 end() const { return point(length); }
  Vec2 end_tangent() const { return tangent_at(length); }
  bool straight() const { return curvature == 0.0; }
  // Centre of the circle; only meaningful when !straight().
  Vec2 center() const { return start + Vec2(-tangent.y(), tangent.x()) / curvature; }
  // Distance from q to the arc (or segment): to its circle (line) when q is
  // in the arc's sector (the foot is on the arc), else to the nearer end.
  // Written in the start's tangent and normal, stable as curvature -> 0: a
  // nearly straight arc's centre and radius are far larger than the arc.
  double distance(const Vec2& q) const {
    const Vec2 e = end();
    const double ends = std::min((q - start).norm(), (q - e).norm());
    if (!(length > 0)) return ends;
    const Vec2 v = q - start, te = end_tangent();
    // In the sector: past the start's normal line and before the end's (both
    // for an arc of at most a half turn, either for a longer one).
    const bool after = v.dot(tangent) > 0, before = (q - e).dot(te) < 0;
    const double sweep = std::abs(curvature) * length;
    if (!(sweep >= 2 * M_PI || (sweep > M_PI ? after || before : after && before))) return ends;
    // |q - centre| - radius = (|k| |v|^2 - 2 sgn(k) v.n) / (|k v - n| + 1), n the start's normal.
    const Vec2 n(-tangent.y(), tangent.x());
    const double k = std::abs(curvature), s = curvature < 0 ? -1.0 : 1.0;
    const double circle = std::abs(k * v.squaredNorm() - 2 * s * v.dot(n)) / ((curvature * v - n).norm() + 1.0);
    return std::min(ends, circle);
  }
};

}  // namespace revdist
