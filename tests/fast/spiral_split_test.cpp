// Tests of the spiral split (fast/spiral_split.h): split points at known
// inflections, curvature extrema and extremes of r and z; lines and arcs kept
// whole or split only at r/z extremes; knots without C2 continuity; poles and
// singular points; the spiral hypotheses hold on every span (dense check).
#include "fast/spiral_split.h"

#include <gtest/gtest.h>

#include <random>

#include "fast/biarc_fit.h"
#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using namespace testing_util;

std::vector<SpiralSpan> split_one(const Piece& p) {
  Profile profile;
  profile.pieces.push_back(p);
  std::vector<SpiralSpan> out;
  split_into_spirals(profile, out);
  return out;
}

// Dense check of the hypotheses on each span: r', z', K, dkappa/du keep one
// sign (up to a small relative noise floor).
void check_spiral_hypotheses(const Piece& piece, const std::vector<SpiralSpan>& spans) {
  for (const SpiralSpan& s : spans) {
    if (s.kind != SpanKind::curve) continue;
    int sign[4] = {0, 0, 0, 0};
    for (int i = 1; i < 400; ++i) {
      const double u = s.u0 + (s.u1 - s.u0) * i / 400;
      Vec2 d[4];
      piece_derivatives(piece, u, 3, d);
      const double sp2 = d[1].squaredNorm();
      const double k = cross2(d[1], d[2]);
      const double n = cross2(d[1], d[3]) * sp2 - 3 * k * d[1].dot(d[2]);
      const double v[4] = {d[1].x(), d[1].y(), k, n};
      const double scale[4] = {std::sqrt(sp2), std::sqrt(sp2), d[1].norm() * d[2].norm(),
                               d[1].norm() * d[3].norm() * sp2 + 3 * std::abs(k) * d[1].norm() * d[2].norm()};
      for (int f = 0; f < 4; ++f) {
        if (std::abs(v[f]) <= 1e-6 * scale[f]) continue;
        const int sg = v[f] > 0 ? 1 : -1;
        if (sign[f] == 0) sign[f] = sg;
        EXPECT_EQ(sign[f], sg) << "function " << f << " changes sign in [" << s.u0 << ", " << s.u1 << "] at " << u;
      }
    }
    EXPECT_TRUE(lens_bound(s.ends).hypotheses_ok);
  }
}

TEST(SpiralSplit, LineIsOneExactSpan) {
  const auto spans = split_one(line_piece({0.5, 0}, {0.5, 2}));
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans[0].kind, SpanKind::line);
  EXPECT_EQ(spans[0].ends.t0, Vec2(0, 1));
}

TEST(SpiralSplit, ArcSplitAtRAndZExtremesOnly) {
  // Semicircle from the south pole to the north pole through (1, 0): a sphere.
  const auto spans = split_one(arc_piece({0, -1}, {1, 0}, {0, 1}));
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_NEAR(spans[0].ends.p1.x(), 1.0, 1e-15);
  EXPECT_NEAR(spans[0].ends.p1.y(), 0.0, 1e-15);
  // Poles: horizontal tangents at r = 0.
  EXPECT_NEAR(spans[0].ends.t0.y(), 0.0, 1e-15);
  EXPECT_NEAR(spans[1].ends.t1.y(), 0.0, 1e-15);
}

TEST(SpiralSplit, CubicWithInflectionSplitsThere) {
  // (0,0), (1,1), (0,1)...: an S-curve symmetric about u = 1/2: inflection there.
  const Piece p = bezier_piece({{0, 0}, {1, 0.3}, {0, 0.7}, {1, 1}});
  const auto spans = split_one(p);
  bool found = false;
  for (const SpiralSpan& s : spans) found |= std::abs(s.u0 - 0.5) < 1e-12;
  EXPECT_TRUE(found);
  check_spiral_hypotheses(p, spans);
}

TEST(SpiralSplit, SingularEndPointUsesHigherDerivative) {
  // Repeated first control point: C'(0) = 0; the tangent comes from C''.
  const Piece p = bezier_piece({{0, 0}, {0, 0}, {1, 0}, {1, 1}});
  const auto spans = split_one(p);
  ASSERT_FALSE(spans.empty());
  EXPECT_NEAR(spans[0].ends.t0.x(), 1.0, 1e-12);
  EXPECT_NEAR(spans[0].ends.t0.y(), 0.0, 1e-12);
  check_spiral_hypotheses(p, spans);
}

TEST(SpiralSplit, QuadraticBsplineSplitsAtEveryKnot) {
  // Degree 2: only C1 at simple knots, the curvature jumps there.
  Piece p;
  p.kind = PieceKind::bspline;
  p.degree = 2;
  p.points = {{0, 0}, {1, 0.2}, {0.5, 1}, {1.2, 1.5}, {0, 2}};
  p.knots = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
  const auto spans = split_one(p);
  for (double k : {0.3, 0.6}) {
    bool found = false;
    for (const SpiralSpan& s : spans) found |= s.u0 == k;
    EXPECT_TRUE(found) << k;
  }
  check_spiral_hypotheses(p, spans);
}

// A cubic whose z' = c((u - m)^2 - d^2) dips below 0 between m - d and m + d,
// both inside one cell of a 32-cell sampling of [0, 1] (cells [k/32, (k+1)/32]):
// the two sign changes of z' have the same sign on either side of the cell,
// so sampling sees neither. The tangent turns below the horizontal there; a
// span across the dip breaks the lens hypotheses (regression for issue 10:
// the sampled split missed both).
TEST(SpiralSplit, FindsSignChangePairInsideOneSampleCell) {
  const double m = 12.5 / 32, d = 0.012, c = 2.0;
  // r = u + 0.1, z(u) = c ((u - m)^3 / 3 - d^2 u) + 1, in the Bernstein basis.
  const double a0 = c * (-m * m * m / 3) + 1, a1 = c * (m * m - d * d), a2 = -c * m, a3 = c / 3;
  const Piece p = bezier_piece({{0.1, a0}, {0.1 + 1.0 / 3, a0 + a1 / 3}, {0.1 + 2.0 / 3, a0 + 2 * a1 / 3 + a2 / 3},
                                {1.1, a0 + a1 + a2 + a3}});
  const auto spans = split_one(p);
  for (double root : {m - d, m + d}) {
    bool found = false;
    for (const SpiralSpan& s : spans) found |= std::abs(s.u1 - root) <= 1e-12;  // a few ulp of the root
    EXPECT_TRUE(found) << "no split at the sign change of z' at u = " << root;
  }
  check_spiral_hypotheses(p, spans);
}

// Weights (1, c, c^2, c^3) re-parametrise a polynomial cubic without changing
// its shape (a Moebius map of the parameter): the rational path (homogeneous
// numerators, degree 3p - 3 and 8p - 6) must split at the same points as the
// polynomial path (degree 2p - 3 and 4p - 6).
TEST(SpiralSplit, RationalReparametrisationSplitsAtTheSamePoints) {
  const std::uint64_t seed = test_seed(5);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(0.5, 2.0);
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    const Piece poly = random_bezier(rng, false);
    const double c = uc(rng);
    Piece rat = poly;
    rat.weights = {1.0, c, c * c, c * c * c};
    const auto a = split_one(poly), b = split_one(rat);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_TRUE(a[i].proven && b[i].proven);
      // A root located to ~1e-15 in the parameter; the point moves with the
      // speed (<= ~10 here), and the Moebius map and its rounding cost a few ulp more.
      EXPECT_LE((a[i].ends.p1 - b[i].ends.p1).norm(), 1e-12);
    }
    check_spiral_hypotheses(rat, b);
  }
}

// A rational quadratic with weights (1, cos 45deg, 1) is a quarter circle:
// N vanishes identically (constant curvature), only to rounding in double,
// and must not be split at; r', z' and K keep one sign.
TEST(SpiralSplit, QuarterCircleConicIsOneSpan) {
  const auto spans = split_one(bezier_piece({{0.35, 0}, {0.4, 0}, {0.4, 0.05}}, {1, std::sqrt(0.5), 1}));
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_TRUE(spans[0].proven);
}

// An ellipse quarter as a rational quadratic, not symmetric: its curvature
// has one extreme inside, where N changes sign once.
TEST(SpiralSplit, ConicSplitsAtItsCurvatureExtreme) {
  const Piece p = bezier_piece({{1, 0}, {1, 2}, {0.2, 2}}, {1, 0.8, 1});
  const auto spans = split_one(p);
  EXPECT_EQ(spans.size(), 2u);
  check_spiral_hypotheses(p, spans);
}

TEST(SpiralSplit, RandomCurvesSatisfyHypotheses) {
  const std::uint64_t seed = test_seed(99);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 40; ++trial) {
    const Piece p = trial % 2 ? random_bezier(rng, trial % 4 == 1) : random_bspline(rng, 3, 7, trial % 4 == 2);
    SCOPED_TRACE(trial);
    const auto spans = split_one(p);
    for (const SpiralSpan& s : spans) EXPECT_TRUE(s.proven);
    check_spiral_hypotheses(p, spans);
  }
}

}  // namespace
}  // namespace revdist
