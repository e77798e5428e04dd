// Tests of fast circle binormals: counts on random pairs against a dense
// long-double sign-change count of both branch derivatives, line certificates
// (on both circles, normal to both), and the named degenerate configurations.
// Seed: REVDIST_SEED (printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fast/circle_distance.h"
#include "tests/fast/circle_test_util.h"

namespace revdist {
namespace {

using namespace testing_circles;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Branch derivative ψσ(θ) = L - σR·Qp/ρ (half of f' on the near, σ = +1, or far
// branch) for b's point θ against a, in long double.
LD branch_derivative(const FrameL& b, const FrameL& a, LD th, int sg, LD* rho_out) {
  const LD c = std::cos(th), s = std::sin(th);
  const V3 P = (b.c - a.c) + b.r * (c * b.u + s * b.v), T = b.r * (c * b.v - s * b.u);
  const LD X = dot(P, a.u), Y = dot(P, a.v), Z = dot(P, a.n);
  const LD X1 = dot(T, a.u), Y1 = dot(T, a.v), Z1 = dot(T, a.n);
  const LD rho = std::sqrt(X * X + Y * Y);
  *rho_out = rho;
  return X * X1 + Y * Y1 + Z * Z1 - sg * a.r * (X * X1 + Y * Y1) / rho;
}

// Roots of ψ+ and ψ- located by sign changes over n samples and bisection: one
// line each (a near and a far line at one point Q are two). Misses touching
// roots, which random pairs do not have.
int reference_count(const Circle3& a, const Circle3& b, int n = 20000) {
  const FrameL fa = frame_l(a), fb = frame_l(b);
  const LD two_pi = 2 * 3.141592653589793238462643383279502884L;
  std::vector<LD> roots;
  for (int sg : {1, -1}) {
    LD rho;
    LD prev = branch_derivative(fb, fa, 0, sg, &rho);
    for (int i = 1; i <= n; ++i) {
      const LD cur = branch_derivative(fb, fa, two_pi * i / n, sg, &rho);
      if ((prev < 0) != (cur < 0)) {
        LD lo = two_pi * (i - 1) / n, hi = two_pi * i / n;
        const bool lo_neg = prev < 0;
        for (int it = 0; it < 80; ++it) {
          const LD mid = 0.5L * (lo + hi);
          if ((branch_derivative(fb, fa, mid, sg, &rho) < 0) == lo_neg) lo = mid; else hi = mid;
        }
        roots.push_back(0.5L * (lo + hi));
      }
      prev = cur;
    }
  }
  return static_cast<int>(roots.size());
}

TEST(CircleBinormals, RandomPairsMatchDenseCountAndAreCertified) {
  Rng rng(test_seed());
  int total = 0, hist[10] = {};
  for (int i = 0; i < 300; ++i) {
    const Circle3 a{rng.box(1), rng.unit(), rng.uniform(0.05, 1)}, b{rng.box(1), rng.unit(), rng.uniform(0.05, 1)};
    bool inf = true;
    const auto lines = circle3_circle3_binormals(a, b, &inf);
    EXPECT_FALSE(inf);
    const int ref = reference_count(a, b);
    EXPECT_EQ(static_cast<int>(lines.size()), ref) << "pair #" << i;
    total += static_cast<int>(lines.size());
    ++hist[std::min<int>(9, static_cast<int>(lines.size()))];
    const double scale = pair_scale(a, b);
    // Certificate: endpoints on their circles, segment normal to both tangents.
    // Tolerance: polished to rounding at scale ~1, a few hundred ε with margin.
    for (const auto& l : circle3_circle3_binormal_lines(a, b)) {
      EXPECT_LE(ref_point_circle(l.point_a, a), 256 * kEps * scale);
      EXPECT_LE(ref_point_circle(l.point_b, b), 256 * kEps * scale);
      EXPECT_NEAR((l.point_a - l.point_b).norm(), l.distance, 256 * kEps * scale);
      const Vec3 d = l.point_b - l.point_a;
      const Vec3 ta = a.normal.normalized().cross(l.point_a - a.center);
      const Vec3 tb = b.normal.normalized().cross(l.point_b - b.center);
      EXPECT_LE(std::abs(d.dot(ta)), 1e-9 * scale * scale);
      EXPECT_LE(std::abs(d.dot(tb)), 1e-9 * scale * scale);
    }
  }
  std::printf("binormals: %d lines over 300 pairs; histogram of counts:", total);
  for (int k = 0; k < 10; ++k) std::printf(" %d:%d", k, hist[k]);
  std::printf("\n");
}

TEST(CircleBinormals, MinimumDistanceIsABinormal) {
  Rng rng(test_seed() + 5);
  for (int i = 0; i < 200; ++i) {
    const Circle3 a{rng.box(1), rng.unit(), rng.uniform(0.05, 1)}, b{rng.box(1), rng.unit(), rng.uniform(0.05, 1)};
    const auto r = circle3_circle3_distance(a, b);
    const auto lines = circle3_circle3_binormal_lines(a, b);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& l : lines) best = std::min(best, l.distance);
    EXPECT_NEAR(best, r.distance, 1e-12 * pair_scale(a, b)) << "pair #" << i;
  }
}

TEST(CircleBinormals, NamedInfiniteConfigurations) {
  const Circle3 a{Vec3::Zero(), Vec3::UnitZ(), 1.0};
  bool inf = false;
  // Coaxial.
  EXPECT_TRUE(circle3_circle3_binormals(a, {Vec3(0, 0, 0.5), Vec3(0, 0, -2), 0.3}, &inf).empty());
  EXPECT_TRUE(inf);
  // Villarceau: radius R, centre offset r, plane tilted by asin(r/R).
  const double r = 0.25, s = r, c = std::sqrt(1 - s * s);
  inf = false;
  circle3_circle3_binormals(a, {Vec3(0, r, 0), Vec3(-s, 0, c), 1.0}, &inf);
  EXPECT_TRUE(inf);
  // Meridian circles, inside the tube and past the axis.
  for (double rb : {0.25, 3.0}) {
    inf = false;
    circle3_circle3_binormals(a, {Vec3(1, 0, 0), Vec3::UnitY(), rb}, &inf);
    EXPECT_TRUE(inf) << rb;
  }
  // a a point on b's axis: every point of b is critical.
  inf = false;
  circle3_circle3_binormals({Vec3(0, 0, 2), Vec3::UnitX(), 0.0}, a, &inf);
  EXPECT_TRUE(inf);
}

TEST(CircleBinormals, NamedFiniteConfigurations) {
  const Circle3 a{Vec3::Zero(), Vec3::UnitZ(), 1.0};
  bool inf = true;
  // b a point off the axis: a near and a far line meet b at its single point Q.
  auto l = circle3_circle3_binormals(a, {Vec3(2, 0, 1), Vec3::UnitX(), 0.0}, &inf);
  EXPECT_FALSE(inf);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_NEAR(std::min(l[0].distance, l[1].distance), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(std::max(l[0].distance, l[1].distance), std::sqrt(10.0), 1e-15);
  // b a point on a's axis: a cone of lines, a continuum.
  l = circle3_circle3_binormals(a, {Vec3(0, 0, 1), Vec3::UnitX(), 0.0}, &inf);
  EXPECT_TRUE(inf);
  EXPECT_TRUE(l.empty());
  // a a point off b's axis: b's nearest and farthest points.
  l = circle3_circle3_binormals({Vec3(3, 0, 0), Vec3::UnitX(), 0.0}, a, &inf);
  EXPECT_FALSE(inf);
  EXPECT_EQ(l.size(), 2u);
  // Concentric tilted: extremes of the distance to a's axis on b (4 points of
  // b), each with a near and a far line.
  l = circle3_circle3_binormals(a, {Vec3::Zero(), Vec3(1, 0, 1), 0.5}, &inf);
  EXPECT_FALSE(inf);
  EXPECT_EQ(l.size(), 8u);
  // Coplanar disjoint circles: the line of centres meets b twice, each point
  // with a near and a far line.
  l = circle3_circle3_binormals(a, {Vec3(3, 0, 0), Vec3::UnitZ(), 0.5}, &inf);
  EXPECT_FALSE(inf);
  EXPECT_EQ(l.size(), 4u);
}

}  // namespace
}  // namespace revdist
