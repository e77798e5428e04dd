// Closed-form circle-circle lower bound (see the header for the argument).
#include "fast/circle_bound.h"

#include <algorithm>
#include <cmath>

namespace revdist {

namespace {

// The bound seen from a's axis: height gap and radial gap of circle b.
double axis_bound(const Vec3& ca, const Vec3& na, double ra, const Vec3& cb, const Vec3& nb, double rb) {
  const Vec3 d = cb - ca;
  const double h0 = na.dot(d);
  const double c = na.dot(nb);
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  const double rho0 = std::sqrt(std::max(0.0, d.squaredNorm() - h0 * h0));
  const double dz = std::max(0.0, std::abs(h0) - rb * s);
  const double dr = std::max({0.0, rho0 - rb - ra, ra - rho0 - rb});
  return std::sqrt(dz * dz + dr * dr);
}

}  // namespace

double circle3_circle3_lower_bound(const Circle3& a, const Circle3& b) {
  const double la = a.normal.norm(), lb = b.normal.norm();
  if (!(la > 0) || !(lb > 0)) return std::max(0.0, (a.center - b.center).norm() - a.radius - b.radius);
  const Vec3 na = a.normal / la, nb = b.normal / lb;
  const double sphere = (a.center - b.center).norm() - a.radius - b.radius;
  return std::max({sphere, axis_bound(a.center, na, a.radius, b.center, nb, b.radius),
                   axis_bound(b.center, nb, b.radius, a.center, na, a.radius)});
}

}  // namespace revdist
