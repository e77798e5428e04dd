// Arc2::distance against the arc sampled densely: minor and major arcs, near
// straight ones, segments, arcs of no length, points on the circle's centre.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/arc2.h"

namespace revdist {
namespace {

// The least distance from q to n + 1 points spaced evenly along the arc, and
// in *spacing their spacing along it: the true distance is within half the
// spacing below it.
double sampled_distance(const Arc2& a, const Vec2& q, int n, double* spacing) {
  double d = INFINITY;
  for (int i = 0; i <= n; ++i) d = std::min(d, (q - a.point(a.length * i / n)).norm());
  *spacing = a.length / n;
  return d;
}

TEST(Arc2Distance, MatchesDenseSamplingOnRandomArcs) {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int k = 0; k < 4000; ++k) {
    Arc2 a;
    a.start = Vec2(u(rng), u(rng));
    const double ang = M_PI * u(rng);
    a.tangent = Vec2(std::cos(ang), std::sin(ang));
    a.length = 0.05 + 2.0 * (0.5 + 0.5 * u(rng));
    switch (k % 5) {
      case 0: a.curvature = 0.0; break;                        // a segment
      case 1: a.curvature = 1e-6 * u(rng); break;              // nearly straight
      case 2: a.curvature = 0.5 * u(rng); break;               // under a half turn
      default: a.curvature = (0.9 * M_PI + 0.95 * M_PI * (0.5 + 0.5 * u(rng))) / a.length * (u(rng) < 0 ? -1 : 1);
    }
    // Points anywhere near, and points at the centre of the circle.
    const Vec2 q = k % 97 == 0 && a.curvature != 0 ? a.center() : Vec2(2 * u(rng), 2 * u(rng));
    double spacing;
    const double sampled = sampled_distance(a, q, 20000, &spacing);
    const double d = a.distance(q);
    const double round = 1e-12 * (1.0 + sampled);  // (the centre of a nearly straight arc is far out)
    EXPECT_LE(d, sampled + round) << "arc " << k;
    EXPECT_GE(d, sampled - 0.5 * spacing - round) << "arc " << k;
    ++checked;
  }
  EXPECT_EQ(checked, 4000);
}

TEST(Arc2Distance, ClosedForms) {
  // The upper unit half circle from (1, 0) to (-1, 0) counter-clockwise.
  Arc2 half;
  half.start = Vec2(1, 0);
  half.tangent = Vec2(0, 1);
  half.curvature = 1.0;
  half.length = M_PI;
  EXPECT_NEAR(half.distance(Vec2(0, 3)), 2.0, 1e-12);            // foot at the top
  EXPECT_NEAR(half.distance(Vec2(0, -3)), std::sqrt(10.0), 1e-12);  // below: the ends
  EXPECT_NEAR(half.distance(Vec2(0, 0)), 1.0, 1e-12);            // the centre
  // Three quarters of the circle, from (1, 0) round to (0, -1).
  Arc2 major = half;
  major.length = 1.5 * M_PI;
  EXPECT_NEAR(major.distance(Vec2(-2, -0.5)), std::sqrt(4.25) - 1.0, 1e-12);  // foot on the third quarter
  EXPECT_NEAR(major.distance(Vec2(2, -2)), std::sqrt(5.0), 1e-12);  // the missing quarter: ends at (1,0) and (0,-1)
  // A segment of length 2 along z.
  Arc2 seg;
  seg.start = Vec2(0, 0);
  seg.tangent = Vec2(0, 1);
  seg.length = 2.0;
  EXPECT_NEAR(seg.distance(Vec2(3, 1)), 3.0, 1e-15);
  EXPECT_NEAR(seg.distance(Vec2(0, 5)), 3.0, 1e-15);
  // No length: the point.
  Arc2 dot = seg;
  dot.length = 0.0;
  EXPECT_NEAR(dot.distance(Vec2(3, 4)), 5.0, 1e-15);
}

}  // namespace
}  // namespace revdist
