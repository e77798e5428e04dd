// Closed-form circle-circle lower bound (see the header for the argument).
#include "fast/circle_bound.h"

#include <algorithm>
#include <cmath>

namespace revdist {

// The sine of the normals' angle as the length of their cross product:
// sqrt(1 - c^2) loses all digits of a small angle (axes 1e-9 apart gave 0,
// and a height gap 5e-11 above the distance).
CircleBoundAxes::CircleBoundAxes(const Vec3& na, const Vec3& nb) : na_(na), nb_(nb), s_(na.cross(nb).norm()) {}

double circle3_circle3_lower_bound(const Circle3& a, const Circle3& b) {
  const double la = a.normal.norm(), lb = b.normal.norm();
  if (!(la > 0) || !(lb > 0)) return std::max(0.0, (a.center - b.center).norm() - a.radius - b.radius);
  return CircleBoundAxes(a.normal / la, b.normal / lb)(a.center, a.radius, b.center, b.radius);
}

namespace {
// The nearest point of circle c (unit normal n) to x (any point of c when x
// is on its axis).
Vec3 nearest_on(const Circle3& c, const Vec3& n, const Vec3& x) {
  Vec3 v = x - c.center;
  v -= n.dot(v) * n;
  const double len = v.norm();
  if (!(len > 0)) return c.center + c.radius * n.unitOrthogonal();
  return c.center + (c.radius / len) * v;
}
}  // namespace

namespace {
double alternate(const Circle3& a, const Vec3& na, const Circle3& b, const Vec3& nb, const Vec3& hint, int rounds,
                 Vec3* pa_out, Vec3* pb_out) {
  Vec3 pa = nearest_on(a, na, hint), pb = nearest_on(b, nb, pa);
  for (int i = 1; i < rounds; ++i) {
    pa = nearest_on(a, na, pb);
    pb = nearest_on(b, nb, pa);
  }
  if (pa_out) *pa_out = pa;
  if (pb_out) *pb_out = pb;
  return (pa - pb).norm();
}
}  // namespace

double circle3_circle3_upper_bound(const Circle3& a, const Circle3& b, const Vec3& hint, int rounds, Vec3* pa_out,
                                   Vec3* pb_out) {
  // The normals once (the projections use them 2 * rounds times).
  return alternate(a, a.normal.normalized(), b, b.normal.normalized(), hint, rounds, pa_out, pb_out);
}

double CircleBoundAxes::upper(const Vec3& ca, double ra, const Vec3& cb, double rb, int rounds) const {
  return alternate({ca, na_, ra}, na_, {cb, nb_, rb}, nb_, cb, rounds, nullptr, nullptr);
}

}  // namespace revdist
