// Test helpers for the spiral split and biarc tree tests: random profile pieces
// (seeded, REVDIST_SEED overrides), exact point-to-arc distances and a dense
// sampled two-sided Hausdorff distance between a curve part and its biarc.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <cstdio>
#include <vector>

#include "core/arc2.h"
#include "core/curve_eval.h"
#include "core/profile.h"

namespace revdist::testing_util {

// Printed, so that a failure can be replayed with REVDIST_SEED.
inline std::uint64_t test_seed(std::uint64_t fallback) {
  const char* s = std::getenv("REVDIST_SEED");
  const std::uint64_t seed = s ? std::strtoull(s, nullptr, 10) : fallback;
  std::printf("[ seed     ] REVDIST_SEED=%llu\n", static_cast<unsigned long long>(seed));
  return seed;
}

// Exact distance from p to the arc (circle part or segment), in a form that
// stays accurate as the curvature -> 0 (no centre far away).
inline double point_arc_distance(const Vec2& p, const Arc2& arc) {
  if (arc.length == 0.0) return (p - arc.start).norm();
  const double k = arc.curvature;
  if (k == 0.0) return point_segment_distance(p, arc.start, arc.end());
  const Vec2 n(-arc.tangent.y(), arc.tangent.x());
  const Vec2 w = p - arc.start;
  const double sk = k > 0 ? 1.0 : -1.0;
  // Directions from the centre, scaled by |k|: to the start and to p.
  const Vec2 a0 = -sk * n, q = std::abs(k) * w - sk * n;
  double ang = std::atan2(cross2(a0, q), a0.dot(q));
  if (k < 0) ang = -ang;
  if (ang < 0) ang += 2 * M_PI;
  if (ang <= std::abs(k) * arc.length) {
    // |p - c| - R = (k |w|^2 - 2 w.n) sign(k) / (|k w - n| + 1)
    return std::abs((k * w.squaredNorm() - 2.0 * w.dot(n)) / ((k * w - n).norm() + 1.0));
  }
  return std::min((p - arc.start).norm(), (p - arc.end()).norm());
}

// Two-sided Hausdorff distance between piece[u0, u1] and the chain of arcs,
// both sampled densely: curve samples to the arcs exactly; arc samples to the
// curve by the nearest curve sample refined with a golden-section search on
// the curve parameter (a polyline alone overestimates by its chordal error).
// A lower estimate of the truth, which the proven bound must cover.
inline double sampled_hausdorff(const Piece& piece, double u0, double u1, const Arc2* arcs, int count,
                                int n = 2000) {
  std::vector<Vec2> curve(n + 1);
  for (int i = 0; i <= n; ++i) curve[i] = piece_point(piece, u0 + (u1 - u0) * i / n);
  double h = 0.0;
  for (const Vec2& p : curve) {
    double d = INFINITY;
    for (int k = 0; k < count; ++k) d = std::min(d, point_arc_distance(p, arcs[k]));
    h = std::max(h, d);
  }
  for (int k = 0; k < count; ++k) {
    for (int i = 0; i <= n / 2; ++i) {
      const Vec2 p = arcs[k].point(arcs[k].length * i / (n / 2));
      int best = 0;
      for (int j = 1; j <= n; ++j) {
        if ((p - curve[j]).squaredNorm() < (p - curve[best]).squaredNorm()) best = j;
      }
      double a = u0 + (u1 - u0) * std::max(best - 1, 0) / n, b = u0 + (u1 - u0) * std::min(best + 1, n) / n;
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      auto f = [&](double u) { return (p - piece_point(piece, u)).norm(); };
      double c = b - g * (b - a), e = a + g * (b - a), fc = f(c), fe = f(e);
      for (int it = 0; it < 60; ++it) {
        if (fc < fe) { b = e; e = c; fe = fc; c = b - g * (b - a); fc = f(c); }
        else { a = c; c = e; fc = fe; e = a + g * (b - a); fe = f(e); }
      }
      h = std::max(h, std::min({fc, fe, (p - curve[best]).norm()}));
    }
  }
  return h;
}

// A random cubic (optionally rational) Bezier in r >= 0, z in [0, 2].
inline Piece random_bezier(std::mt19937_64& rng, bool rational) {
  std::uniform_real_distribution<double> ur(0.0, 1.5), uz(0.0, 2.0), uw(0.3, 3.0);
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = 3;
  for (int i = 0; i < 4; ++i) p.points.emplace_back(ur(rng), uz(rng));
  if (rational) {
    for (int i = 0; i < 4; ++i) p.weights.push_back(i == 0 || i == 3 ? 1.0 : uw(rng));
  }
  return p;
}

// A random clamped B-spline of the given degree with `n` control points.
inline Piece random_bspline(std::mt19937_64& rng, int degree, int n, bool rational) {
  std::uniform_real_distribution<double> ur(0.0, 1.5), uz(0.0, 2.0), uw(0.3, 3.0), uk(0.0, 1.0);
  Piece p;
  p.kind = PieceKind::bspline;
  p.degree = degree;
  for (int i = 0; i < n; ++i) p.points.emplace_back(ur(rng), 2.0 * i / (n - 1) + 0.3 * uz(rng));
  if (rational) {
    for (int i = 0; i < n; ++i) p.weights.push_back(uw(rng));
  }
  std::vector<double> inner;
  for (int i = 0; i < n - degree - 1; ++i) inner.push_back(uk(rng));
  std::sort(inner.begin(), inner.end());
  p.knots.assign(degree + 1, 0.0);
  p.knots.insert(p.knots.end(), inner.begin(), inner.end());
  p.knots.insert(p.knots.end(), degree + 1, 1.0);
  return p;
}

inline Piece line_piece(Vec2 a, Vec2 b) {
  Piece p;
  p.kind = PieceKind::line;
  p.degree = 1;
  p.points = {a, b};
  return p;
}

inline Piece arc_piece(Vec2 a, Vec2 m, Vec2 b) {
  Piece p;
  p.kind = PieceKind::arc;
  p.degree = 2;
  p.points = {a, m, b};
  return p;
}

inline Piece bezier_piece(std::vector<Vec2> pts, std::vector<double> w = {}) {
  Piece p;
  p.kind = PieceKind::bezier;
  p.degree = static_cast<int>(pts.size()) - 1;
  p.points = std::move(pts);
  p.weights = std::move(w);
  return p;
}

}  // namespace revdist::testing_util
