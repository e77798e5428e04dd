// Piece evaluation: derivatives against central differences, exact conics, arc geometry.
#include "core/curve_eval.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace revdist {
namespace {

Piece line(Vec2 a, Vec2 b) { return {PieceKind::line, 1, {a, b}, {}, {}}; }
Piece arc(Vec2 a, Vec2 m, Vec2 b) { return {PieceKind::arc, 2, {a, m, b}, {}, {}}; }
Piece bezier(std::vector<Vec2> pts, std::vector<double> w = {}) {
  const int d = static_cast<int>(pts.size()) - 1;
  return {PieceKind::bezier, d, std::move(pts), std::move(w), {}};
}
Piece bspline(int degree, std::vector<double> knots, std::vector<Vec2> pts, std::vector<double> w = {}) {
  return {PieceKind::bspline, degree, std::move(pts), std::move(w), std::move(knots)};
}

// The point of a line, Bezier or B-spline piece, computed without core/: rational
// de Casteljau, and the Cox-de Boor recursion of the basis; arcs by their geometry.
Vec2 reference_point(const Piece& p, double u) {
  const std::size_t n = p.points.size();
  const auto w = [&](std::size_t i) { return p.weights.empty() ? 1.0 : p.weights[i]; };
  if (p.kind == PieceKind::line) return (1 - u) * p.points[0] + u * p.points[1];
  if (p.kind == PieceKind::arc) {
    const ArcGeometry g = arc_geometry(p);
    const double a = std::atan2(p.points[0].y() - g.center.y(), p.points[0].x() - g.center.x()) + u * g.sweep;
    return g.center + g.radius * Vec2(std::cos(a), std::sin(a));
  }
  std::vector<Eigen::Vector3d> h(n);
  for (std::size_t i = 0; i < n; ++i) h[i] = Eigen::Vector3d(w(i) * p.points[i].x(), w(i) * p.points[i].y(), w(i));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  if (p.kind == PieceKind::bezier) {
    for (std::size_t r = 1; r < n; ++r)
      for (std::size_t i = 0; i + r < n; ++i) h[i] = (1 - u) * h[i] + u * h[i + 1];
    sum = h[0];
  } else {
    const std::vector<double>& t = p.knots;
    const auto basis = [&](auto&& self, std::size_t i, int k) -> double {
      if (k == 0) return t[i] <= u && u < t[i + 1] ? 1.0 : 0.0;
      double b = 0;
      if (t[i + k] > t[i]) b += (u - t[i]) / (t[i + k] - t[i]) * self(self, i, k - 1);
      if (t[i + k + 1] > t[i + 1]) b += (t[i + k + 1] - u) / (t[i + k + 1] - t[i + 1]) * self(self, i + 1, k - 1);
      return b;
    };
    for (std::size_t i = 0; i < n; ++i) sum += basis(basis, i, p.degree) * h[i];
  }
  return Vec2(sum.x() / sum.z(), sum.y() / sum.z());
}

// Checks out[k] against central differences of out[k-1], k = 1..3, at interior points
// away from knots. Step h ~ 1e-5 * domain: truncation O(h^2) and rounding O(eps/h)
// both stay below ~1e-7 relative for these O(1) curves.
void expect_derivatives_match_differences(const Piece& p, const std::vector<double>& us) {
  const auto [u0, u1] = piece_domain(p);
  const double h = 1e-5 * (u1 - u0);
  for (double u : us) {
    Vec2 d[4], dm[4], dp[4];
    piece_derivatives(p, u, 3, d);
    piece_derivatives(p, u - h, 3, dm);
    piece_derivatives(p, u + h, 3, dp);
    for (int k = 1; k <= 3; ++k) {
      const Vec2 fd = (dp[k - 1] - dm[k - 1]) / (2 * h);
      const double scale = 1.0 + d[k].norm() + dp[k - 1].norm();
      EXPECT_NEAR((fd - d[k]).norm() / scale, 0.0, 1e-6) << "u=" << u << " k=" << k;
    }
    // The point against an evaluator written independently here (de Casteljau /
    // Cox-de Boor in homogeneous form): a few ulps per level of O(1) values.
    EXPECT_NEAR((d[0] - reference_point(p, u)).norm(), 0.0, 64 * 2.220446049250313e-16) << "u=" << u;
    EXPECT_EQ(piece_point(p, u), d[0]) << "piece_point and piece_derivatives disagree, u=" << u;
  }
}

TEST(CurveEval, LineDerivatives) {
  const Piece p = line({0.5, 0}, {0.5, 2});
  expect_derivatives_match_differences(p, {0.1, 0.5, 0.9});
  EXPECT_EQ(piece_point(p, 0.0), Vec2(0.5, 0));
  EXPECT_EQ(piece_point(p, 1.0), Vec2(0.5, 2));
}

TEST(CurveEval, BezierDerivatives) {
  expect_derivatives_match_differences(bezier({{0, 0}, {1, 0.5}, {1, 1.5}, {0, 2}}), {0.13, 0.5, 0.77});
  expect_derivatives_match_differences(bezier({{0, 0}, {1, 0.5}, {1, 1.5}, {0.2, 1.7}, {0, 2}}, {1, 2, 0.5, 3, 1}),
                                       {0.13, 0.5, 0.77});
}

TEST(CurveEval, BSplineDerivatives) {
  const Piece p = bspline(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0}, {1, 0.2}, {0.4, 1}, {0.9, 1.6}, {0, 2}},
                          {1, 1, 2, 1, 1});
  expect_derivatives_match_differences(p, {0.1, 0.3, 0.6, 0.95});
  const Piece q = bspline(2, {2, 2, 2, 3, 3, 4.5, 5, 5, 5}, {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {1.5, 2}, {0, 2}});
  expect_derivatives_match_differences(q, {2.2, 2.9, 3.4, 4.7});
  EXPECT_EQ(piece_domain(q), std::make_pair(2.0, 5.0));
  EXPECT_EQ(piece_point(q, 2.0), Vec2(0, 0));
  EXPECT_EQ(piece_point(q, 5.0), Vec2(0, 2));
  // At the double knot 3 the quadratic is only C0: the right limit is the span [3, 4.5).
  Vec2 at[2], right[2];
  piece_derivatives(q, 3.0, 1, at);
  piece_derivatives(q, 3.0 + 1e-12, 1, right);
  EXPECT_NEAR((at[1] - right[1]).norm(), 0.0, 1e-9);
  // The knot 3 has multiplicity 2 = degree, so the curve interpolates points[2] there.
  EXPECT_NEAR((at[0] - Vec2(1, 1)).norm(), 0.0, 1e-15);
}

TEST(CurveEval, BezierEqualsItsBSpline) {
  const std::vector<Vec2> pts = {{0, 0}, {1, 0.5}, {2, 1.5}, {0, 2}};
  const std::vector<double> w = {1, 0.5, 2, 1};
  const Piece a = bezier(pts, w);
  const Piece b = bspline(3, {0, 0, 0, 0, 1, 1, 1, 1}, pts, w);
  for (double u : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    Vec2 da[4], db[4];
    piece_derivatives(a, u, 3, da);
    piece_derivatives(b, u, 3, db);
    for (int k = 0; k <= 3; ++k) EXPECT_NEAR((da[k] - db[k]).norm(), 0.0, 1e-12 * (1 + da[k].norm()));
  }
}

// The input caps degrees at 32, and the evaluator's windows hold the 33
// control points and 64 knots of one span of that degree (fixed storage): a
// rational Bezier of degree 32 and the same curve as a clamped B-spline agree
// with the independent de Casteljau evaluation, point and first derivative.
TEST(CurveEval, HighestDegreeFitsTheWindow) {
  std::vector<Vec2> pts;
  std::vector<double> w;
  for (int i = 0; i <= 32; ++i) {
    pts.emplace_back(1 + 0.3 * std::sin(i), 2.0 * i / 32);
    w.push_back(1 + 0.5 * std::cos(0.7 * i));
  }
  std::vector<double> knots(33, 0.0);
  knots.insert(knots.end(), 33, 1.0);
  const Piece a = bezier(pts, w);
  const Piece b = bspline(32, knots, pts, w);
  const double h = 1e-6;
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
    for (const Piece* p : {&a, &b}) {
      Vec2 d[2];
      piece_derivatives(*p, u, 1, d);
      EXPECT_NEAR((d[0] - reference_point(a, u)).norm(), 0.0, 1e-13) << "u=" << u;
      if (u > 0 && u < 1) {
        const Vec2 fd = (reference_point(a, u + h) - reference_point(a, u - h)) / (2 * h);
        EXPECT_NEAR((fd - d[1]).norm() / (1 + d[1].norm()), 0.0, 1e-6) << "u=" << u;
      }
    }
  }
  // One degree more (a piece built by hand: the case reader refuses it) is
  // refused too, not evaluated past the windows' storage.
  pts.emplace_back(1, 2.1);
  EXPECT_THROW(piece_point(bezier(pts), 0.5), std::invalid_argument);
}

TEST(CurveEval, RationalQuarterCircleIsExact) {
  // The quadratic rational Bezier with middle weight cos(45 deg) is the unit quarter circle.
  const Piece p = bezier({{1, 0}, {1, 1}, {0, 1}}, {1, std::sqrt(0.5), 1});
  for (int i = 0; i <= 20; ++i) {
    const double u = i / 20.0;
    Vec2 d[3];
    piece_derivatives(p, u, 2, d);
    // Rounding only: a few ulps per operation on O(1) values.
    EXPECT_NEAR(d[0].norm(), 1.0, 1e-15 * 8);
    EXPECT_NEAR(d[0].dot(d[1]), 0.0, 1e-14);                    // tangent _|_ radius
    EXPECT_NEAR(d[1].squaredNorm() + d[0].dot(d[2]), 0.0, 1e-13);  // derivative of C.C' = 0
  }
  expect_derivatives_match_differences(p, {0.2, 0.5, 0.7});
}

TEST(CurveEval, ArcGeometryAndEndpoints) {
  const Piece ccw = arc({0, -1}, {1, 0}, {0, 1});
  const ArcGeometry g = arc_geometry(ccw);
  EXPECT_NEAR((g.center - Vec2(0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(g.radius, 1.0, 1e-15);
  EXPECT_NEAR(g.sweep, M_PI, 1e-15);
  EXPECT_EQ(piece_point(ccw, 0.0), Vec2(0, -1));
  EXPECT_EQ(piece_point(ccw, 1.0), Vec2(0, 1));
  EXPECT_NEAR((piece_point(ccw, 0.5) - Vec2(1, 0)).norm(), 0.0, 1e-15);
  expect_derivatives_match_differences(ccw, {0.1, 0.5, 0.9});

  // Clockwise, and more than half a turn: from (1,0) through (0,-1) to (0,1) the long way.
  const Piece cw = arc({1, 0}, {0, -1}, {0, 1});
  const ArcGeometry h = arc_geometry(cw);
  EXPECT_NEAR(h.sweep, -1.5 * M_PI, 1e-14);
  EXPECT_NEAR((piece_point(cw, 1.0 / 3.0) - Vec2(0, -1)).norm(), 0.0, 1e-15);
  expect_derivatives_match_differences(cw, {0.1, 0.5, 0.9});

  // Constant speed: |C'| = radius * |sweep| everywhere.
  Vec2 d[2];
  piece_derivatives(cw, 0.37, 1, d);
  EXPECT_NEAR(d[1].norm(), 1.5 * M_PI, 1e-14);

  // Off-origin small arc: the centre is computed relative to p0, so no digits are lost.
  const Piece far = arc({1000.0, 1000.0}, {1000.001, 1000.0 - 1e-3}, {1000.002, 1000.0});
  const ArcGeometry f = arc_geometry(far);
  EXPECT_NEAR(f.radius, 1e-3, 1e-12);
  EXPECT_NEAR((f.center - Vec2(1000.001, 1000.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(f.sweep, M_PI, 1e-9);
}

}  // namespace
}  // namespace revdist
