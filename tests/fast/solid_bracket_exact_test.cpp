// Brackets against exact arithmetic, not decimals (issue 10 item 16): the
// distance of two balls of the given doubles, r1 + r2 subtracted from the
// centre distance along an axis, is exact in binary128 (the doubles' exponents
// are close), so lower <= d <= upper is checked without rounding.
#include <gtest/gtest.h>

#include <string>

#include "core/case_io.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist {
namespace {

using Quad = __float128;

// Balls of radius r at the origin and at (t, 0, 0), for several scales: the
// exact distance t - 2r of the doubles t and r.
TEST(SolidBracketExact, BallsAlongAnAxisHoldTheExactDistance) {
  const Case c = read_case(std::string(REVDIST_SOURCE_DIR) + "/cases/regressions/upper_rounded_outward_balls.json");
  const double r = 0.01;
  const double seps[] = {0.03, 0.0300000000000001, 0.021, 0.02000001, 0.5, 3.3};
  const CaseModel m = build_case_model(c, 1e-5);
  for (const double t : seps) {
    PosedSolid a = m.instances[0], b = m.instances[1];
    b.t = Vec3(t, 0, 0);
    for (const double tol : {1e-6, 1e-12}) {
      DistanceOptions o;
      o.tol = tol;
      const SolidDistanceResult res = solid_distance(a, b, o);
      const Quad d = static_cast<Quad>(t) - 2 * static_cast<Quad>(r);
      EXPECT_TRUE(static_cast<Quad>(res.lower) <= d) << "t " << t << " tol " << tol << ": lower above the exact distance";
      EXPECT_TRUE(d <= static_cast<Quad>(res.upper)) << "t " << t << " tol " << tol << " upper " << res.upper
                                                    << " below the exact distance";
      EXPECT_TRUE(res.converged) << res.reason;
      EXPECT_LE(res.upper - res.lower, tol);
    }
  }
}

}  // namespace
}  // namespace revdist
