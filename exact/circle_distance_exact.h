// Certified circle-circle distance (paper Appendix A, done exactly): the
// degree-8 binormal polynomial with rational coefficients built from the double
// inputs, real roots isolated with CGAL's algebraic kernel, the distance
// enclosed with MPFI. This header includes no CGAL/GMP header on purpose.
#pragma once
#include <string>

#include "core/circle3.h"

namespace revdist {

enum class ExactStatus {
  ok,               // interval proven to contain the distance, finitely many closest pairs
  infinitely_many,  // interval proven; the closest pairs form a continuum
  not_certified,    // could not certify; see reason. lower/upper are not a guarantee
};

struct ExactCircleResult {
  ExactStatus status = ExactStatus::ok;
  std::string reason;     // why not_certified, empty otherwise
  double lower = 0.0;     // outward-rounded double bounds of the certified interval
  double upper = 0.0;
  double width = 0.0;     // upper end minus lower end of the certified interval, rounded up
  double distance = 0.0;  // nearest double to a point of the interval
  std::string decimal;    // a point of the interval, >= 30 significant digits
  bool contact = false;   // proven exactly: the circles share a point (then lower = upper = 0)
  Vec3 point_a = Vec3::Zero();  // a closest pair, rounded to double
  Vec3 point_b = Vec3::Zero();
  // Binormal lines: segments PQ, P on a, Q on b, normal to both (to a point
  // circle: any direction), counted as fast/ counts them (README, `circles`): a
  // near and a far line at one point of b are two; from a point of b on a's
  // axis, the lines in the plane normal to b there; a near line shorter than
  // fast/'s contact length (64ε·2^e, 2^e just above max(radii, max |C_b - C_a|
  // component)) is a contact point, not a line. -1 when they form a continuum
  // (coaxial circles, Villarceau and meridian pairs, a point on the other's
  // axis). Exact, like the rest: the roots of the binormal polynomial of the
  // given doubles, the branch decided by exact signs.
  int binormals = 0;
};

struct ExactOptions {
  // Target width of the certified interval relative to scale = max(radii, centre distance).
  double relative_width = 1e-30;
  // Upper limit on MPFR precision while refining, in bits.
  int max_precision_bits = 4096;
};

// Certified minimum distance between circles a and b (radius 0 = a point).
// The doubles are read as exact rationals; the result is an interval proven
// to contain the distance, of width <= options.relative_width * scale with
// scale = max(r_a, r_b, |C_a - C_b|) and narrow enough that `distance` (its
// middle) is the nearest double of the distance (both ends round to it, or
// the width is within 2^-80 of the lower end), or status not_certified with
// a reason.
// Contact (distance exactly 0) is decided exactly. Never throws.
// status infinitely_many: the minimum is attained on a continuum (coaxial and
// Villarceau pairs, a point or a closest point on the axis of the other circle).
// When candidates of both kinds tie within the final interval (equal to
// ~1e-30), the kind of the candidate with the smallest upper bound decides.
ExactCircleResult circle3_circle3_distance_exact(const Circle3& a, const Circle3& b,
                                                 const ExactOptions& options = {});

}  // namespace revdist
