// A closed-form lower bound on the distance between two circles in space, the
// cheap filter in front of circle3_circle3_distance (an iterative solve) in
// the traversal's node bounds (paper section 4.2: bounds per node pair).
#pragma once
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

}  // namespace revdist
