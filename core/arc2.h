// A circular arc or straight segment in the meridian plane (r, z), the unit of
// a biarc (paper section 4.1). Stored as start point, unit start tangent,
// signed curvature and arc length: this form stays sane as curvature -> 0, so
// straight input pieces are exact segments, never huge-radius arcs.
#pragma once
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
};

}  // namespace revdist
