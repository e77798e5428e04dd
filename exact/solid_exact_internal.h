// Internal to exact/solid_distance_exact*: the profile of a solid as elements
// (segments, arcs of less than a half turn, rational Bezier segments) enclosed
// with MPFI, the rigid map between two solids' frames, and the certified
// point-in-solid test (ray crossing parity against the exact curves).
#pragma once
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/profile.h"
#include "exact/fit_audit_internal.h"

namespace revdist::solid_exact_detail {

using fit_audit_detail::HomSeg;
using fit_audit_detail::Ia;
using fit_audit_detail::P2;
using fit_audit_detail::Poly;

enum class ElemKind { line, arc, curve };

// One element of a profile. `seg` is its exact rational Bezier form (interval
// coefficients, local parameter in [0, 1]); it is used when the element sweeps the
// surface that is parametrised, and for the crossing-parity test. When the element
// is the one measured against (the "target"), only its point set matters:
//   line:  the segment a-b;
//   arc:   the arc of the circle (c, R) from q0 counter-clockwise to q1, turning
//          less than a half turn, so its sector is convex;
//   curve: C(v) = (x(v), y(v)) / w(v), v in [0, 1].
struct Element {
  ElemKind kind = ElemKind::curve;
  int piece = 0;
  HomSeg seg;
  Poly dx, dy, dw;  // derivative coefficients (degree - 1)
  P2 a, b;          // line ends; arc ends q0, q1 (counter-clockwise order)
  P2 c;             // arc centre
  Ia R;             // arc radius
};

// The elements of a profile. Empty with `reason` set when a piece cannot be enclosed.
std::vector<Element> profile_elements(const Profile& profile, std::string* reason);

// y = o + M x: a point x of solid S's local frame in solid E's local frame,
// enclosed from the exact rational rotations M(q)/|q|^2.
struct Frame {
  Ia M[3][3];
  Ia o[3];
};
Frame relative_frame(const Pose& pose_s, const Pose& pose_e);

// True when the two axes are exactly the same line (rational arithmetic): then
// every function of a point of S seen from E is independent of S's rotation angle.
bool exactly_coaxial(const Pose& pose_s, const Pose& pose_e);

// Value of a Bernstein polynomial (coefficients on [0, 1]) at an interval
// parameter: an enclosure of its range there.
Ia bernstein_eval(const Poly& c, const Ia& u);

// (r, z) of the element's exact curve at parameter u, and its derivative.
void elem_point(const Element& e, const Ia& u, Ia& r, Ia& z);
void elem_point_deriv(const Element& e, const Ia& u, Ia& r, Ia& z, Ia& dr, Ia& dz);

// The rotation angle psi about a solid's axis, rationally: s in [0, 2] in two
// charts, t = 2 (s - k) - 1 in [-1, 1] on chart k = 0 ([0, 1]) and k = 1 ([1, 2]),
// (cos psi, sin psi) = (-1)^k ((1 - t^2), 2 t) / (1 + t^2); chart 0 covers
// psi in [-pi/2, pi/2], chart 1 [pi/2, 3pi/2]. For s in [s0, s1] inside one chart:
// enclosures of cos psi, sin psi and of d psi / ds = 4 / (1 + t^2) (> 0).
void rotation_cs(double s0, double s1, Ia& c, Ia& sn, Ia* dpsi_ds = nullptr);
double psi_of(double s);  // the angle in double, for witness points

// The point of S's surface at (u, s) seen in E's frame.
void surface_point(const Element& s_elem, const Frame& f, const Ia& u, double s, Ia y[3]);

enum class Inside { inside, outside, unknown };

// Is the point with meridian coordinates (rho, zeta) of a solid strictly inside
// (or strictly outside) the solid whose profile elements are given? Counts the
// crossings of the ray {(r, zeta) : r > rho} with the exact curves (Bernstein sign
// variations, halving until each part is decided); `unknown` when the point is on
// (or too close to) the boundary or the ray passes through a joint.
Inside point_in_solid(const std::vector<Element>& elems, const Ia& rho, const Ia& zeta);

}  // namespace revdist::solid_exact_detail
