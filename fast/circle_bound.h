// A closed-form lower bound on the distance between two circles in space, the
// cheap filter in front of circle3_circle3_distance (an iterative solve) in
// the traversal's node bounds (paper section 4.2: bounds per node pair).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/circle3.h"

namespace revdist {

// A lower bound on dist(a, b) in a few dozen flops and no iteration. In
// cylindrical coordinates about a's axis, |x - y|^2 >= dz^2 + (rho_x - rho_y)^2
// for x on a (dz = height over a's plane, rho = distance from a's axis); over
// circle b the height stays within |h0| -+ R_b sin(angle of the normals) and
// rho within rho0 -+ R_b, which bounds both terms; the same with the roles
// swapped, and the bounding spheres. Exact for coaxial circles; for two
// circles in one plane it is the gap of their disks' rims. Rounding is the
// caller's (a few ulps of the coordinates).
double circle3_circle3_lower_bound(const Circle3& a, const Circle3& b);

// An upper bound on dist(a, b): the distance between a point of a and a point
// of b, found by alternating projection (the nearest point of a to the hint,
// the nearest point of b to that, and so on for `rounds` rounds). Near the
// circles' closest pair (a hint there: a query's witness) it is close to the
// distance. The filter in front of circle3_circle3_distance where only an
// answer at or above some threshold would be used: an upper bound below the
// threshold proves that the iterative solve would not reach it.
// The pair is returned in *pa, *pb when they are given.
double circle3_circle3_upper_bound(const Circle3& a, const Circle3& b, const Vec3& hint, int rounds = 3,
                                   Vec3* pa = nullptr, Vec3* pb = nullptr);

// The same bound for circles whose normals are two fixed unit vectors na, nb
// (the parts of two posed solids, all about their solids' axes): the sine of
// the normals' angle is computed once, a pair costs three square roots.
class CircleBoundAxes {
 public:
  CircleBoundAxes(const Vec3& na, const Vec3& nb);
  // The bound between the circle of centre ca, radius ra about na and the
  // circle of centre cb, radius rb about nb.
  double operator()(const Vec3& ca, double ra, const Vec3& cb, double rb) const {
    const Vec3 d = cb - ca;
    const double dd = d.squaredNorm();
    return std::max({std::sqrt(dd) - ra - rb, seen_from(na_.dot(d), dd, ra, rb), seen_from(nb_.dot(d), dd, rb, ra)});
  }

 private:
  // Seen from the axis of the circle of radius r (height h0 of the other's
  // centre over its plane, dd the squared centre distance): the height gap
  // and the radial gap of the other circle, of radius ro.
  double seen_from(double h0, double dd, double r, double ro) const {
    const double rho0 = std::sqrt(std::max(0.0, dd - h0 * h0));
    const double dz = std::max(0.0, std::abs(h0) - ro * s_);
    const double dr = std::max({0.0, rho0 - ro - r, r - rho0 - ro});
    return std::sqrt(dz * dz + dr * dr);
  }
  Vec3 na_, nb_;
  double s_;
};

}  // namespace revdist
