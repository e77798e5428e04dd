// Points and derivatives of profile pieces (lines, arcs, rational Bezier and
// NURBS pieces), the evaluation layer under the spiral split of paper section 4.1.
#include "core/curve_eval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace revdist {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Hom = Eigen::Vector3d;  // (w r, w z, w)

// The p + 1 control points and 2p knots that define one non-empty knot span of
// a spline of degree p: the span is [tau[p-1], tau[p]). Bezier pieces are one
// span with knots 0 (p times) and 1 (p times). Differentiating a window gives
// the window of the derivative spline over the same span (degree p - 1), so
// every derivative is evaluated by the same de Boor loop.
struct Window {
  // Fixed storage (the input caps degrees at 32): the distance query maps
  // witness points onto the input curves with a few evaluations each, and
  // the vectors' copies cost as much as the arithmetic.
  static constexpr int kMaxDegree = kMaxPieceDegree;
  int degree = 0;
  int t0 = 0;  // tau's first entry: differentiating drops one knot at each end
  Hom c[kMaxDegree + 1];
  double tau_store[2 * kMaxDegree];
  double tau(int i) const { return tau_store[t0 + i]; }
};

Hom de_boor(const Window& w, double u) {
  const int p = w.degree;
  Hom scratch[Window::kMaxDegree + 1];
  std::copy(w.c, w.c + p + 1, scratch);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double lo = w.tau(j - 1), hi = w.tau(j + p - r);
      // hi > lo inside a non-empty span: lo <= tau[p-1] < tau[p] <= hi.
      const double a = (u - lo) / (hi - lo);
      scratch[j] = (1.0 - a) * scratch[j - 1] + a * scratch[j];
    }
  }
  return scratch[p];
}

// Replaces the window by that of its derivative.
void differentiate(Window& w) {
  const int p = w.degree;
  for (int j = 0; j < p; ++j) {
    const double dt = w.tau(j + p) - w.tau(j);  // > 0 for the same reason as in de_boor
    w.c[j] = (p / dt) * (w.c[j + 1] - w.c[j]);
  }
  if (p >= 1) ++w.t0;  // (and the last knot dropped: the degree bounds the reads)
  w.degree = p - 1;
}

double weight(const Piece& piece, std::size_t i) {
  return piece.weights.empty() ? 1.0 : piece.weights[i];
}

// Fills w with the window of the span holding u.
void make_window(const Piece& piece, double u, Window& w) {
  const int p = piece.degree;
  if (p < 0 || p > Window::kMaxDegree)  // (the windows' storage; the case reader refuses these)
    throw std::invalid_argument("piece of degree " + std::to_string(p) + ": degrees are 0.." +
                                std::to_string(Window::kMaxDegree));
  w.degree = p;
  w.t0 = 0;
  std::size_t first = 0;  // index of the window's first control point
  if (piece.kind == PieceKind::bezier) {
    std::fill(w.tau_store, w.tau_store + p, 0.0);
    std::fill(w.tau_store + p, w.tau_store + 2 * p, 1.0);
  } else {
    // Span k with t_k <= u < t_{k+1}, k in [p, n-1]; at the end of the domain the
    // last non-empty span.
    const std::vector<double>& t = piece.knots;
    const std::size_t n = piece.points.size();
    const auto it = std::upper_bound(t.begin() + p + 1, t.begin() + n, u);
    const std::size_t k = static_cast<std::size_t>(it - t.begin()) - 1;
    first = k - p;
    std::copy(t.begin() + (k - p + 1), t.begin() + (k + p + 1), w.tau_store);
  }
  for (int j = 0; j <= p; ++j) {
    const std::size_t i = first + j;
    const double wi = weight(piece, i);
    w.c[j] = Hom(wi * piece.points[i].x(), wi * piece.points[i].y(), wi);
  }
}

void spline_derivatives(const Piece& piece, double u, int n, Vec2* out) {
  Window w;
  make_window(piece, u, w);
  Hom h[4];
  for (int k = 0; k <= n; ++k) {
    h[k] = w.degree >= 0 ? de_boor(w, u) : Hom::Zero();
    if (w.degree >= 0 && k < n) differentiate(w);
  }
  // Quotient rule on C = A / W: A^(k) = sum_i binom(k, i) W^(i) C^(k-i).
  static const double binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  const double w0 = h[0].z();
  for (int k = 0; k <= n; ++k) {
    Vec2 a = h[k].head<2>();
    for (int i = 1; i <= k; ++i) a -= binom[k][i] * h[i].z() * out[k - i];
    out[k] = a / w0;
  }
}

// The blossom (polar form) of the window's spline at (args[0], ..., args[p-1]): de Boor
// with a different parameter at each level.
Hom blossom(const Window& w, const double* args) {
  const int p = w.degree;
  Hom c[Window::kMaxDegree + 1];
  std::copy(w.c, w.c + p + 1, c);
  for (int r = 1; r <= p; ++r) {
    const double u = args[r - 1];
    for (int j = p; j >= r; --j) {
      const double lo = w.tau(j - 1), hi = w.tau(j + p - r);
      const double a = (u - lo) / (hi - lo);
      c[j] = (1.0 - a) * c[j - 1] + a * c[j];
    }
  }
  return c[p];
}

BezierSegment from_homogeneous(const std::vector<Hom>& h, bool rational, double u0, double u1) {
  BezierSegment s;
  s.u0 = u0;
  s.u1 = u1;
  for (const Hom& q : h) {
    s.points.push_back(q.head<2>() / q.z());
    if (rational) s.weights.push_back(q.z());
  }
  return s;
}

std::vector<Hom> to_homogeneous(const BezierSegment& s) {
  std::vector<Hom> h;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const double w = s.weights.empty() ? 1.0 : s.weights[i];
    h.emplace_back(w * s.points[i].x(), w * s.points[i].y(), w);
  }
  return h;
}

}  // namespace

// The point of arc g at angle a, from its first point p0 along the chord.
static Vec2 arc_point_from_start(const Vec2& p0, const ArcGeometry& g, double a) {
  const double half = 0.5 * (a - g.start_angle), mid = 0.5 * (a + g.start_angle);
  return p0 + 2 * g.radius * std::sin(half) * Vec2(-std::sin(mid), std::cos(mid));
}

std::vector<BezierSegment> piece_bezier_segments(const Piece& piece) {
  std::vector<BezierSegment> out;
  switch (piece.kind) {
    case PieceKind::line:
    case PieceKind::bezier:
      out.push_back({piece.points, piece.weights, 0.0, 1.0});
      break;
    case PieceKind::arc: {
      const ArcGeometry g = arc_geometry(piece);
      const int m = std::max(1, static_cast<int>(std::ceil(std::abs(g.sweep) / (kPi / 2) - 1e-12)));
      const double phi = g.sweep / m;
      const double w = std::cos(phi / 2);  // > 0: |phi| <= 90 degrees
      for (int k = 0; k < m; ++k) {
        const double a0 = g.start_angle + k * phi, a1 = a0 + phi;
        BezierSegment s;
        // Points from p0 along chords (see piece_derivatives: a far centre would
        // cost R * ulp); the middle control point is the tangents' crossing.
        const Vec2 q0 = arc_point_from_start(piece.points[0], g, a0);
        s.points = {q0, q0 + g.radius * std::tan(phi / 2) * Vec2(-std::sin(a0), std::cos(a0)),
                    arc_point_from_start(piece.points[0], g, a1)};
        s.weights = {1.0, w, 1.0};
        s.u0 = static_cast<double>(k) / m;
        s.u1 = static_cast<double>(k + 1) / m;
        out.push_back(std::move(s));
      }
      out.front().points.front() = piece.points.front();
      out.back().points.back() = piece.points.back();
      for (std::size_t k = 1; k < out.size(); ++k) out[k].points.front() = out[k - 1].points.back();
      break;
    }
    case PieceKind::bspline: {
      const int p = piece.degree;
      const std::vector<double>& t = piece.knots;
      const std::size_t n = piece.points.size();
      std::vector<double> args(p);
      for (std::size_t k = p; k < n; ++k) {
        if (!(t[k] < t[k + 1])) continue;
        Window w;
        make_window(piece, t[k], w);
        std::vector<Hom> h(p + 1);
        // Bezier point j of span [a, b] is the blossom at (a, ..., a, b, ..., b) with j b's.
        for (int j = 0; j <= p; ++j) {
          for (int i = 0; i < p; ++i) args[i] = i < j ? t[k + 1] : t[k];
          h[j] = blossom(w, args.data());
        }
        out.push_back(from_homogeneous(h, !piece.weights.empty(), t[k], t[k + 1]));
      }
      for (std::size_t k = 1; k < out.size(); ++k) out[k].points.front() = out[k - 1].points.back();
      out.front().points.front() = piece.points.front();
      out.back().points.back() = piece.points.back();
      break;
    }
  }
  return out;
}

std::pair<BezierSegment, BezierSegment> split_segment(const BezierSegment& s, double t) {
  std::vector<Hom> h = to_homogeneous(s);
  const std::size_t n = h.size();
  std::vector<Hom> left(n), right(n);
  for (std::size_t r = 0; r < n; ++r) {
    left[r] = h[0];
    right[n - 1 - r] = h[n - 1 - r];
    for (std::size_t j = 0; j + 1 < n - r; ++j) h[j] = (1.0 - t) * h[j] + t * h[j + 1];
  }
  const bool rational = !s.weights.empty();
  const double um = (1.0 - t) * s.u0 + t * s.u1;
  std::pair<BezierSegment, BezierSegment> out{from_homogeneous(left, rational, s.u0, um),
                                              from_homogeneous(right, rational, um, s.u1)};
  out.first.points.front() = s.points.front();
  out.second.points.back() = s.points.back();
  out.second.points.front() = out.first.points.back();
  return out;
}

std::pair<double, double> piece_domain(const Piece& piece) {
  if (piece.kind == PieceKind::bspline) return {piece.knots.front(), piece.knots.back()};
  return {0.0, 1.0};
}

ArcGeometry arc_geometry(const Piece& arc) {
  const Vec2& p0 = arc.points[0];
  const Vec2& pm = arc.points[1];
  const Vec2& p1 = arc.points[2];
  // Circumcentre relative to p0, so the formula loses no digits to the position.
  const Vec2 a = pm - p0, b = p1 - p0;
  const double d = 2.0 * (a.x() * b.y() - a.y() * b.x());
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm();
  const Vec2 rel((b.y() * a2 - a.y() * b2) / d, (a.x() * b2 - b.x() * a2) / d);
  ArcGeometry g;
  g.center = p0 + rel;
  g.radius = rel.norm();
  g.start_angle = std::atan2(-rel.y(), -rel.x());
  const Vec2 e = p1 - g.center;
  const double end_angle = std::atan2(e.y(), e.x());
  // d > 0: p0 -> pm -> p1 turns counter-clockwise, so the arc runs counter-clockwise.
  double ccw = end_angle - g.start_angle;  // in (-2pi, 2pi)
  if (d > 0) {
    if (ccw <= 0) ccw += 2 * kPi;
    g.sweep = ccw;
  } else {
    if (ccw >= 0) ccw -= 2 * kPi;
    g.sweep = ccw;
  }
  return g;
}

void piece_derivatives(const Piece& piece, double u, int n, Vec2* out) {
  const auto [u0, u1] = piece_domain(piece);
  u = std::clamp(u, u0, u1);
  switch (piece.kind) {
    case PieceKind::line: {
      const Vec2& p0 = piece.points[0];
      const Vec2& p1 = piece.points[1];
      out[0] = (1.0 - u) * p0 + u * p1;  // exact at both ends
      if (n >= 1) out[1] = p1 - p0;
      for (int k = 2; k <= n; ++k) out[k] = Vec2::Zero();
      break;
    }
    case PieceKind::arc: {
      const ArcGeometry g = arc_geometry(piece);
      const double th = g.start_angle + u * g.sweep;
      const double c = std::cos(th), s = std::sin(th);
      // From p0 along the chord, not centre + R (cos, sin): for a nearly
      // straight arc the centre is far away (R up to 1e7 and more) and the
      // latter would carry R * ulp of error; the chord 2R sin(delta/2) is small
      // and exact to a few ulps of itself.
      out[0] = arc_point_from_start(piece.points[0], g, th);
      // d/du (cos, sin) = sweep (-sin, cos): each derivative rotates by 90 degrees.
      double f = g.radius;
      Vec2 dir(c, s);
      for (int k = 1; k <= n; ++k) {
        f *= g.sweep;
        dir = Vec2(-dir.y(), dir.x());
        out[k] = f * dir;
      }
      break;
    }
    case PieceKind::bezier:
    case PieceKind::bspline:
      spline_derivatives(piece, u, n, out);
      break;
  }
  if (u == u0) out[0] = piece.points.front();
  if (u == u1) out[0] = piece.points.back();
}

Vec2 piece_point(const Piece& piece, double u) {
  Vec2 p;
  piece_derivatives(piece, u, 0, &p);
  return p;
}

double chord_flatness(const std::vector<Vec2>& points) {
  if (points.empty()) return 0.0;
  double e = 0.0;
  for (const Vec2& p : points) e = std::max(e, point_segment_distance(p, points.front(), points.back()));
  return e;
}

}  // namespace revdist
