// Rotating a cosine-sine pair by a step: the descents in angles (the circle
// distance's, the patch pair's) follow their iterates without a libm call
// for the small steps that most of them take.
#pragma once
#include <cmath>

namespace revdist {

// (cos, sin) of th + d from those of th. Small steps (a Newton tail) use the
// Taylor series, exact to rounding for |d| < 1e-2 (next terms d^7/5040, d^8/40320
// are below ε·d and ε), instead of a libm call.
inline void turn(double d, double* c, double* s) {
  double cd, sd;
  if (std::abs(d) < 1e-2) {
    const double d2 = d * d;
    sd = d * (1 - d2 / 6 * (1 - d2 / 20 * (1 - d2 / 42)));
    cd = 1 - d2 / 2 * (1 - d2 / 12 * (1 - d2 / 30));
  } else {
    sd = std::sin(d);
    cd = std::cos(d);
  }
  const double cn = *c * cd - *s * sd;
  *s = *s * cd + *c * sd;
  *c = cn;
}

}  // namespace revdist
