// Exact curve parts for the fit audit (exact/fit_audit.h): a piece restricted to
// [u0, u1] as rational Bezier segments with interval coefficients, evaluated on
// the doubles of the input read as rationals (paper section 4.1 curves).
#include <algorithm>
#include <cmath>

#include "exact/fit_audit_internal.h"

namespace revdist::fit_audit_detail {

void halve(const Poly& c, Poly& left, Poly& right) {
  // In place in `right`: after level r, right[n-1-r] is final and right[0] is
  // left control point r + 1.
  const std::size_t n = c.size();
  right = c;
  left.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    left[r] = right[0];
    for (std::size_t j = 0; j + 1 < n - r; ++j) {
      mpfi_add(right[j].p(), right[j].p(), right[j + 1].p());
      mpfi_div_2ui(right[j].p(), right[j].p(), 1);
    }
  }
}

Poly bernstein_product(const Poly& f, const Poly& g) {
  const int p = static_cast<int>(f.size()) - 1;
  const int q = static_cast<int>(g.size()) - 1;
  // binom(n, k) for n <= 64 fits in 64 bits; degrees are capped by the reader (<= 32).
  auto binom = [](int n, int k) {
    unsigned long r = 1;
    for (int i = 1; i <= k; ++i) r = r * static_cast<unsigned long>(n - k + i) / static_cast<unsigned long>(i);
    return r;
  };
  Poly out(p + q + 1);
  Ia term;
  for (int m = 0; m <= p + q; ++m) {
    for (int j = std::max(0, m - q); j <= std::min(p, m); ++j) {
      mpfi_mul(term.p(), f[j].p(), g[m - j].p());
      mpfi_mul_ui(term.p(), term.p(), binom(p, j));
      mpfi_mul_ui(term.p(), term.p(), binom(q, m - j));
      mpfi_add(out[m].p(), out[m].p(), term.p());
    }
    mpfi_div_ui(out[m].p(), out[m].p(), binom(p + q, m));
  }
  return out;
}

namespace {

struct Hom {
  Ia x, y, w;
};

// The blossom of one knot span's window at (args[0], ..., args[p-1]): de Boor
// with a different parameter at each level, in (w x, w y, w). The window's knots
// tau (2p of them) bracket the span: tau[p-1] < tau[p].
Hom blossom(std::vector<Hom> c, const std::vector<double>& tau, const std::vector<double>& args) {
  const int p = static_cast<int>(c.size()) - 1;
  for (int r = 1; r <= p; ++r) {
    const Ia u(args[r - 1]);
    for (int j = p; j >= r; --j) {
      const Ia lo(tau[j - 1]), hi(tau[j + p - r]);
      const Ia a = u - lo, b = hi - u, d = hi - lo;
      c[j].x = (b * c[j - 1].x + a * c[j].x) / d;
      c[j].y = (b * c[j - 1].y + a * c[j].y) / d;
      c[j].w = (b * c[j - 1].w + a * c[j].w) / d;
    }
  }
  return c[p];
}

// The Bezier form of the window's spline restricted to [a, b]: control point j is
// the blossom at (a, ..., a, b, ..., b) with j b's.
HomSeg restrict_window(const std::vector<Hom>& window, const std::vector<double>& tau, double a, double b) {
  const int p = static_cast<int>(window.size()) - 1;
  HomSeg s;
  std::vector<double> args(p);
  for (int j = 0; j <= p; ++j) {
    for (int i = 0; i < p; ++i) args[i] = i < p - j ? a : b;
    Hom h = blossom(window, tau, args);
    s.x.push_back(std::move(h.x));
    s.y.push_back(std::move(h.y));
    s.w.push_back(std::move(h.w));
  }
  return s;
}

std::vector<Hom> window_of(const Piece& piece, std::size_t first, int p) {
  std::vector<Hom> w(p + 1);
  for (int j = 0; j <= p; ++j) {
    const std::size_t i = first + j;
    const Ia wi(piece.weights.empty() ? 1.0 : piece.weights[i]);
    w[j].x = wi * Ia(piece.points[i].x());
    w[j].y = wi * Ia(piece.points[i].y());
    w[j].w = wi;
  }
  return w;
}

P2 rotate(const Ia& angle, const P2& v) {
  const Ia c = cos(angle), s = sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// The arc through p0, pm, p1 (exact circle of three rational points), uniform in
// angle: C(u) = c + rot(u * sweep) (p0 - c), as in core/curve_eval.cpp.
std::vector<HomSeg> arc_part(const Piece& piece, double u0, double u1, std::string* reason) {
  const P2 p0{piece.points[0].x(), piece.points[0].y()};
  const P2 pm{piece.points[1].x(), piece.points[1].y()};
  const P2 p1{piece.points[2].x(), piece.points[2].y()};
  const P2 a = pm - p0, b = p1 - p0;
  const Ia d = Ia(2.0) * cross(a, b);
  if (!d.pos() && !d.neg()) {
    *reason = "arc points collinear (or nearly: orientation not decided at 128 bits)";
    return {};
  }
  const Ia a2 = dot(a, a), b2 = dot(b, b);
  const P2 rel{(b.y * a2 - a.y * b2) / d, (a.x * b2 - b.x * a2) / d};
  const P2 c = p0 + rel;
  const P2 s{-rel.x, -rel.y};  // p0 - c
  const P2 e = p1 - c;
  // Counter-clockwise angle from s to e in (0, 2 pi]: atan2 of the opposite vector
  // plus pi, whose branch cut sits at angle 0 (p1 = p0), never at a half turn.
  const Ia ccw = atan2(-cross(s, e), -dot(s, e)) + pi();
  const Ia sweep = d.pos() ? ccw : ccw - Ia(2.0) * pi();
  if (!(ccw.width() < 1e-20)) {
    *reason = "arc sweep not enclosed (end points nearly coincide)";
    return {};
  }
  const Ia start = Ia(u0) * sweep, total = Ia(u1) * sweep - start;
  // Parts of at most 1.5 rad, so every weight cos(half) >= cos(0.75) > 0.
  const double turn = std::max(std::abs(total.lo()), std::abs(total.hi()));
  const int m = std::max(1, static_cast<int>(std::ceil(turn / 1.5)));
  std::vector<HomSeg> out;
  for (int k = 0; k < m; ++k) {
    const Ia ta = start + total * Ia(static_cast<double>(k)) / Ia(static_cast<double>(m));
    const Ia tb = start + total * Ia(static_cast<double>(k + 1)) / Ia(static_cast<double>(m));
    const Ia half = (tb - ta) / Ia(2.0);
    const Ia w = cos(half);  // > 0: |half| <= 0.75 rad
    const P2 q0 = c + rotate(ta, s), q2 = c + rotate(tb, s);
    const P2 q1 = w * c + rotate(ta + half, s);  // homogeneous: w * (c + rot(mid) s / w)
    HomSeg seg;
    seg.x = {q0.x, q1.x, q2.x};
    seg.y = {q0.y, q1.y, q2.y};
    seg.w = {Ia(1.0), w, Ia(1.0)};
    out.push_back(std::move(seg));
  }
  return out;
}

}  // namespace

std::vector<HomSeg> curve_part_segments(const Piece& piece, double u0, double u1, std::string* reason) {
  if (!(u0 < u1)) {
    *reason = "empty parameter range";
    return {};
  }
  switch (piece.kind) {
    case PieceKind::line: {
      const P2 p0{piece.points[0].x(), piece.points[0].y()};
      const P2 p1{piece.points[1].x(), piece.points[1].y()};
      const P2 d = p1 - p0;
      const P2 a = p0 + Ia(u0) * d, b = p0 + Ia(u1) * d;
      HomSeg s;
      s.x = {a.x, b.x};
      s.y = {a.y, b.y};
      s.w = {Ia(1.0), Ia(1.0)};
      return {s};
    }
    case PieceKind::arc:
      return arc_part(piece, u0, u1, reason);
    case PieceKind::bezier: {
      const int p = static_cast<int>(piece.points.size()) - 1;
      if (p < 1) {
        *reason = "bezier piece with fewer than two points";
        return {};
      }
      std::vector<double> tau(p, 0.0);
      tau.insert(tau.end(), p, 1.0);
      return {restrict_window(window_of(piece, 0, p), tau, u0, u1)};
    }
    case PieceKind::bspline: {
      const int p = piece.degree;
      const std::vector<double>& t = piece.knots;
      const std::size_t n = piece.points.size();
      if (p < 1 || t.size() != n + p + 1) {
        *reason = "bspline degree, knots and points inconsistent";
        return {};
      }
      std::vector<HomSeg> out;
      for (std::size_t k = p; k < n; ++k) {
        if (!(t[k] < t[k + 1])) continue;
        const double a = std::max(u0, t[k]), b = std::min(u1, t[k + 1]);
        if (!(a < b)) continue;
        const std::vector<double> tau(t.begin() + (k - p + 1), t.begin() + (k + p + 1));
        out.push_back(restrict_window(window_of(piece, k - p, p), tau, a, b));
      }
      if (out.empty()) *reason = "parameter range outside the knot vector";
      return out;
    }
  }
  *reason = "unknown piece kind";
  return {};
}

}  // namespace revdist::fit_audit_detail
