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
// circles in one plane it is the gap of their disks' rims. Where all of
// these are 0 (circles about axes far from parallel, each reaching past the
// other's plane and cylinder: the closest pairs of crossing surfaces), the
// sphere about each circle's centre through that circle: every point of a
// lies on it, so dist(a, b) >= the gap between that sphere and circle b,
// whose points are between m and M from a's centre (m, M in closed form).
// The distance of the other centre from an axis is the length of its
// component across the axis, not sqrt(dd - h0^2): that difference loses all
// digits for a centre near the axis (nearly coaxial circles 1e-9 off the
// axis, 0.2 apart, got a bound 8e-10 above their distance). Rounding is the
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
// the normals' angle is computed once; a pair costs five square roots, and
// four more where the planes and cylinders leave it at 0.
class CircleBoundAxes {
 public:
  CircleBoundAxes(const Vec3& na, const Vec3& nb);
  // The bound between the circle of centre ca, radius ra about na and the
  // circle of centre cb, radius rb about nb.
  double operator()(const Vec3& ca, double ra, const Vec3& cb, double rb) const {
    const Vec3 d = cb - ca;
    const Cylindrical b_on_a = cylindrical(na_, d), a_on_b = cylindrical(nb_, d);
    const double v = std::max({d.norm() - ra - rb, seen_from(b_on_a, ra, rb), seen_from(a_on_b, rb, ra)});
    if (v > 0) return v;
    return std::max(sphere(a_on_b, ra, rb), sphere(b_on_a, rb, ra));
  }
  // circle3_circle3_upper_bound of the same circles from b's centre, with
  // the unit normals as they are.
  double upper(const Vec3& ca, double ra, const Vec3& cb, double rb, int rounds) const;

 private:
  // A circle centre seen from the other circle's axis: its height over
  // the other's plane (up to sign) and its distance from the axis.
  struct Cylindrical {
    double h, rho;
  };
  static Cylindrical cylindrical(const Vec3& n, const Vec3& d) {
    const double h = n.dot(d);
    return {h, (d - h * n).norm()};
  }
  // Seen from the axis of the circle of radius r (c: the other centre,
  // of radius ro): the height gap and the radial gap of the other circle.
  double seen_from(const Cylindrical& c, double r, double ro) const {
    const double dz = std::max(0.0, std::abs(c.h) - ro * s_);
    const double dr = std::max({0.0, c.rho - ro - r, r - c.rho - ro});
    return std::sqrt(dz * dz + dr * dr);
  }
  // The sphere about one circle's centre through that circle (radius r)
  // against the other circle (radius ro; c: the sphere's centre seen from
  // its axis).
  static double sphere(const Cylindrical& c, double r, double ro) {
    const double m = std::sqrt(c.h * c.h + (c.rho - ro) * (c.rho - ro));
    const double M = std::sqrt(c.h * c.h + (c.rho + ro) * (c.rho + ro));
    return std::max({0.0, m - r, r - M});
  }
  Vec3 na_, nb_;
  double s_;
};

}  // namespace revdist
