// Closed-form circle-circle lower bound (see the header for the argument).
#include "fast/circle_bound.h"

#include <algorithm>
#include <cmath>

namespace revdist {

CircleBoundAxes::CircleBoundAxes(const Vec3& na, const Vec3& nb) : na_(na), nb_(nb) {
  const double c = na.dot(nb);
  s_ = std::sqrt(std::max(0.0, 1.0 - c * c));
}

double circle3_circle3_lower_bound(const Circle3& a, const Circle3& b) {
  const double la = a.normal.norm(), lb = b.normal.norm();
  if (!(la > 0) || !(lb > 0)) return std::max(0.0, (a.center - b.center).norm() - a.radius - b.radius);
  return CircleBoundAxes(a.normal / la, b.normal / lb)(a.center, a.radius, b.center, b.radius);
}

}  // namespace revdist
