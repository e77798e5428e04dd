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

TEST(SpiralSplit, RandomCurvesSatisfyHypotheses) {
  const std::uint64_t seed = test_seed(99);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 40; ++trial) {
    const Piece p = trial % 2 ? random_bezier(rng, trial % 4 == 1) : random_bspline(rng, 3, 7, trial % 4 == 2);
    SCOPED_TRACE(trial);
    check_spiral_hypotheses(p, split_one(p));
  }
}

}  // namespace
}  // namespace revdist
