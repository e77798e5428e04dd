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
  double distance = 0.0;  // nearest double to a point of the interval
  std::string decimal;    // a point of the interval, >= 30 significant digits
  bool contact = false;   // proven exactly: the circles share a point (then lower = upper = 0)
  Vec3 point_a = Vec3::Zero();  // a closest pair, rounded to double
  Vec3 point_b = Vec3::Zero();
  int binormals = 0;      // number of binormal lines; -1 when infinitely many
};

struct ExactOptions {
  // Target width of the certified interval relative to scale = max(radii, centre distance).
  double relative_width = 1e-30;
  // Upper limit on MPFR precision while refining, in bits.
  int max_precision_bits = 4096;
};

// Certified minimum distance between circles a and b (radius 0 = a point).
ExactCircleResult circle3_circle3_distance_exact(const Circle3& a, const Circle3& b,
                                                 const ExactOptions& options = {});

}  // namespace revdist
