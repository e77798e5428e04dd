// Tests of the biarc fit and the lens bound (fast/biarc_fit.h): biarcs are G1
// and end where they should, the joint lies on the joint circle, the lens width
// matches a brute-force width of the lens, exact arcs give W = 0, capsules
// contain the lens arcs.
#include "fast/biarc_fit.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using namespace testing_util;

SpanEnds ends_from_angles(double d, double alpha, double beta) {
  SpanEnds e;
  e.p0 = Vec2(0.3, 0.2);
  e.p1 = e.p0 + Vec2(d, 0);
  e.t0 = Vec2(std::cos(alpha), std::sin(alpha));
  e.t1 = Vec2(std::cos(beta), std::sin(beta));
  e.k0 = e.k1 = std::numeric_limits<double>::quiet_NaN();
  return e;
}

TEST(BiarcFit, BiarcIsG1AndJoinsTheEnds) {
  std::mt19937_64 rng(test_seed(3));
  std::uniform_real_distribution<double> ang(-1.5, 1.5), len(1e-4, 2.0);
  for (int i = 0; i < 1000; ++i) {
    const SpanEnds e = ends_from_angles(len(rng), ang(rng), ang(rng));
    const Vec2 hint = 0.5 * (e.p0 + e.p1) + Vec2(0, 0.1);
    const Vec2 j = joint_on_circle(e, hint);
    const Biarc b = biarc_with_joint(e, j);
    const double d = (e.p1 - e.p0).norm();
    EXPECT_LT((b.arc[0].end() - j).norm(), 1e-13 * (1 + d));
    // (arc[1] starts at j by construction; the checks above and below are the ones that can fail)
    EXPECT_LT((b.arc[0].end_tangent() - b.arc[1].tangent).norm(), 1e-12);
    EXPECT_LT((b.arc[1].end() - e.p1).norm(), 1e-13 * (1 + d));
    EXPECT_LT((b.arc[1].end_tangent() - e.t1).norm(), 1e-9) << "joint off the joint circle";
  }
}

TEST(BiarcFit, LensWidthIsTheLargestSectionOfTheLens) {
  // Brute force: the two lens arcs sampled as graphs over the chord.
  std::mt19937_64 rng(test_seed(4));
  std::uniform_real_distribution<double> ang(0.0, 1.5);
  for (int i = 0; i < 50; ++i) {
    const double a = ang(rng), b = -ang(rng);
    const SpanEnds e = ends_from_angles(1.0, a, b);
    const Arc2 la = arc_from_tangent(e.p0, e.t0, e.p1);
    const Arc2 lb = arc_from_tangent(e.p0, Vec2(std::cos(-b), std::sin(-b)), e.p1);
    double w = 0;
    for (int k = 0; k <= 2000; ++k) {
      const Vec2 p = la.point(la.length * k / 2000);
      // Height of the other arc at the same chord coordinate, by bisection on its length.
      double lo = 0, hi = lb.length;
      for (int it = 0; it < 80; ++it) {
        const double m = 0.5 * (lo + hi);
        (lb.point(m).x() < p.x() ? lo : hi) = m;
      }
      w = std::max(w, std::abs(lb.point(lo).y() - p.y()));
    }
    EXPECT_NEAR(lens_bound(e).width, w, 1e-9);
  }
}

TEST(BiarcFit, ExactArcHasZeroWidth) {
  const SpanEnds e = ends_from_angles(1.0, 0.7, -0.7);
  EXPECT_NEAR(lens_bound(e).width, 0.0, 1e-16);
  EXPECT_TRUE(lens_bound(e).hypotheses_ok);
}

TEST(BiarcFit, TurningOverNinetyDegreesIsRejected) {
  EXPECT_FALSE(lens_bound(ends_from_angles(1.0, 1.7, -0.2)).hypotheses_ok);
}

TEST(BiarcFit, CapsuleContainsBothLensArcs) {
  std::mt19937_64 rng(test_seed(6));
  std::uniform_real_distribution<double> ang(-1.5, 1.5);
  for (int i = 0; i < 300; ++i) {
    const SpanEnds e = ends_from_angles(0.5, ang(rng), ang(rng));
    const LensBound lb = lens_bound(e);
    const Capsule c = lens_capsule(e, lb);
    const Arc2 la = arc_from_tangent(e.p0, e.t0, e.p1);
    const Vec2 tb(e.t1.x(), -e.t1.y());  // t1 reflected across the (horizontal) chord
    const Arc2 arc_b = arc_from_tangent(e.p0, tb, e.p1);
    for (const Arc2* a : {&la, &arc_b}) {
      for (int k = 0; k <= 100; ++k) {
        EXPECT_LE(point_segment_distance(a->point(a->length * k / 100), c.a, c.b), c.radius * (1 + 1e-12) + 1e-15);
      }
    }
  }
}

}  // namespace
}  // namespace revdist
