// Spiral split of a profile (paper section 4.1).
//
// Root finder: dense sampling + sign changes + bisection. Every function we
// split on (r', z', K, N) is available pointwise for any rational B-spline
// through core/curve_eval, so one finder covers all piece types; and only
// *sign changes* matter for the lens hypotheses (a root of even multiplicity
// does not break monotonicity), which is exactly what sign sampling detects.
// Bisection (not Newton) converges to either a root or a knot where the
// function jumps, and never leaves its bracket. The known gap: two sign
// changes inside one sample cell (8(p+1) cells per knot span) are missed; the
// biarc fitter checks Vogt's inequality on every node as a cheap guard, and
// exact/ audits the leaves. A Bernstein-form isolator (NOTES section 4) would
// close the gap at the cost of symbolic products of the homogeneous form.
#include "fast/spiral_split.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/curve_eval.h"
#include "fast/biarc_fit.h"

namespace revdist {

namespace {

constexpr double kPi = 3.14159265358979323846;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Signs of r', z', K and N at u; 0 where the value is rounding noise relative to
// the terms it is made of (10^-9: the terms carry ~16 digits, and a genuine
// value that small only shifts a split point by a negligible amount).
struct SignSample {
  double u = 0.0;
  signed char s[4] = {0, 0, 0, 0};
  double speed = 0.0;
};

signed char sign_of(double v, double scale, double rel) {
  if (!(std::abs(v) > rel * scale)) return 0;
  return v > 0 ? 1 : -1;
}

SignSample sample_signs(const Piece& piece, double u) {
  Vec2 d[4];
  piece_derivatives(piece, u, 3, d);
  SignSample s;
  s.u = u;
  const double r1 = d[1].x(), z1 = d[1].y(), r2 = d[2].x(), z2 = d[2].y();
  const double r3 = d[3].x(), z3 = d[3].y();
  const double speed2 = r1 * r1 + z1 * z1;
  s.speed = std::sqrt(speed2);
  s.s[0] = sign_of(r1, s.speed, 1e-12);
  s.s[1] = sign_of(z1, s.speed, 1e-12);
  const double k = r1 * z2 - r2 * z1;
  s.s[2] = sign_of(k, std::abs(r1 * z2) + std::abs(r2 * z1), 1e-9);
  const double kd = r1 * z3 - r3 * z1;  // K' (the r''z'' terms cancel)
  const double dot12 = r1 * r2 + z1 * z2;
  const double n = kd * speed2 - 3.0 * k * dot12;
  const double n_scale = (std::abs(r1 * z3) + std::abs(r3 * z1)) * speed2 +
                         3.0 * std::abs(k) * (std::abs(r1 * r2) + std::abs(z1 * z2));
  s.s[3] = sign_of(n, n_scale, 1e-9);
  return s;
}

// Bisection for a sign change of function `which` between a (sign sa != 0) and b.
double bisect_sign_change(const Piece& piece, int which, double a, double b, signed char sa) {
  for (int it = 0; it < 80; ++it) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;  // the bracket is one ulp wide
    const signed char sm = sample_signs(piece, m).s[which];
    if (sm == 0) return m;
    if (sm == sa) {
      a = m;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

// Golden-section minimum of the speed on [a, b].
double speed_minimum(const Piece& piece, double a, double b, double* min_speed) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = sample_signs(piece, c).speed, fd = sample_signs(piece, d).speed;
  for (int it = 0; it < 60 && b - a > 1e-15 * (std::abs(a) + std::abs(b) + 1.0); ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = sample_signs(piece, c).speed;
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = sample_signs(piece, d).speed;
    }
  }
  *min_speed = std::min(fc, fd);
  return fc < fd ? c : d;
}

// Scratch reused across calls (rebuilding deformable solids is a hot path).
struct SplitScratch {
  std::vector<double> breaks;   // knot-span boundaries of the piece
  std::vector<double> splits;   // split parameters found so far
  std::vector<SignSample> samples;
};

// Appends to `splits` the sign changes of r', z', K, N and the singular points
// found by sampling [a, b] with `cells` cells per knot span inside it.
void scan_interval(const Piece& piece, double a, double b, int cells, const std::vector<double>& breaks,
                   std::vector<SignSample>& samples, std::vector<double>& splits) {
  samples.clear();
  // The cell ends next to a knot or an end of [a, b] are pulled inside by 1e-7
  // of the cell's span, so each sample sees one polynomial span and no
  // singular end point.
  double sa = a;
  auto k = std::upper_bound(breaks.begin(), breaks.end(), a);
  while (sa < b) {
    const double sb = (k != breaks.end() && *k < b) ? *k++ : b;
    const double h = sb - sa;
    for (int i = 0; i <= cells; ++i) {
      double u = sa + h * i / cells;
      if (i == 0) u = sa + 1e-7 * h;
      if (i == cells) u = sb - 1e-7 * h;
      samples.push_back(sample_signs(piece, u));
    }
    sa = sb;
  }

  // Sign changes of each function between consecutive non-zero samples.
  for (int f = 0; f < 4; ++f) {
    signed char last = 0;
    double last_u = a;
    for (const SignSample& s : samples) {
      if (s.s[f] == 0) continue;
      if (last != 0 && s.s[f] != last) splits.push_back(bisect_sign_change(piece, f, last_u, s.u, last));
      last = s.s[f];
      last_u = s.u;
    }
  }

  // Singular points: interior local minima of the speed that are numerically zero.
  double max_speed = 0.0;
  for (const SignSample& s : samples) max_speed = std::max(max_speed, s.speed);
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    const double v = samples[i].speed;
    if (v <= samples[i - 1].speed && v <= samples[i + 1].speed && v < 1e-3 * max_speed) {
      double vmin = 0.0;
      const double u = speed_minimum(piece, samples[i - 1].u, samples[i + 1].u, &vmin);
      if (vmin <= 1e-8 * max_speed) splits.push_back(u);
    }
  }
}

// Sorts `splits` in (a, b), snapping to knots and dropping duplicates and ends.
void tidy_splits(std::vector<double>& splits, const std::vector<double>& breaks, double a, double b) {
  // A bisection that converged on a jump at a knot stops an ulp or so beside
  // it: snap to the knot, so each side of the split is one polynomial span.
  const double tiny = 1e-12 * (b - a);
  for (double& u : splits) {
    const auto k = std::lower_bound(breaks.begin(), breaks.end(), u);
    if (k != breaks.end() && *k - u <= tiny) u = *k;
    if (k != breaks.begin() && u - *(k - 1) <= tiny) u = *(k - 1);
  }
  std::sort(splits.begin(), splits.end());
  std::size_t kept = 0;
  double prev = a;
  for (double u : splits) {
    if (u - prev <= tiny || b - u <= tiny) continue;
    splits[kept++] = u;
    prev = u;
  }
  splits.resize(kept);
}

// Samples per knot span: 8 per degree of freedom of the span.
int cells_for(const Piece& piece) { return 8 * (piece.degree + 1); }

void collect_curve_splits(const Piece& piece, SplitScratch& sc) {
  const auto [lo, hi] = piece_domain(piece);
  sc.breaks.clear();
  sc.splits.clear();
  sc.breaks.push_back(lo);
  if (piece.kind == PieceKind::bspline) {
    const std::vector<double>& t = piece.knots;
    for (std::size_t i = 0; i < t.size();) {
      std::size_t j = i;
      while (j < t.size() && t[j] == t[i]) ++j;
      const int mult = static_cast<int>(j - i);
      if (t[i] > lo && t[i] < hi) {
        sc.breaks.push_back(t[i]);
        // Not C2 here: the curvature may jump, so monotonicity can break at the knot.
        if (mult > piece.degree - 2) sc.splits.push_back(t[i]);  // C^(p-m), m > p-2
      }
      i = j;
    }
  }
  sc.breaks.push_back(hi);
  scan_interval(piece, lo, hi, cells_for(piece), sc.breaks, sc.samples, sc.splits);
  tidy_splits(sc.splits, sc.breaks, lo, hi);
}

void push_span(std::vector<SpiralSpan>& out, int index, SpanKind kind, double u0, double u1,
               const SpanEnds& ends) {
  if (ends.p0 == ends.p1) return;  // a zero-length part (a degenerate piece)
  SpiralSpan s;
  s.piece = index;
  s.kind = kind;
  s.u0 = u0;
  s.u1 = u1;
  s.ends = ends;
  out.push_back(s);
}

SpanEnds curve_ends(const Piece& piece, double ua, double ub) {
  SpanEnds e;
  e.p0 = piece_tangent(piece, ua, +1, &e.t0, &e.k0);
  e.p1 = piece_tangent(piece, ub, -1, &e.t1, &e.k1);
  return e;
}

// Emits the spans of piece[ua, ub], re-scanning it 8 times finer (up to three
// times) when its end data contradict the spiral hypotheses: turning over 90
// degrees or Vogt's inequality broken mean the coarse scan missed a pair of
// sign changes inside one cell (a near-cusp, a tiny wiggle).
void emit_curve_spans(const Piece& piece, int index, double ua, double ub, const std::vector<double>& breaks,
                      int depth, std::vector<SpiralSpan>& out) {
  const SpanEnds e = curve_ends(piece, ua, ub);
  if (depth < 3 && !lens_bound(e).hypotheses_ok) {
    // Rare path: a local list is fine here.
    std::vector<double> splits;
    std::vector<SignSample> samples;
    int cells = cells_for(piece);
    for (int i = 0; i <= depth; ++i) cells *= 8;
    scan_interval(piece, ua, ub, cells, breaks, samples, splits);
    tidy_splits(splits, breaks, ua, ub);
    if (!splits.empty()) {
      splits.push_back(ub);
      double a = ua;
      for (double b : splits) {
        emit_curve_spans(piece, index, a, b, breaks, depth + 1, out);
        a = b;
      }
      return;
    }
  }
  push_span(out, index, SpanKind::curve, ua, ub, e);
}

}  // namespace

Vec2 piece_tangent(const Piece& piece, double u, int side, Vec2* unit_tangent, double* curvature) {
  const auto [lo, hi] = piece_domain(piece);
  double ue = u;
  // piece_derivatives gives the right limit at a knot; the left limit is the
  // span below, one ulp down (derivatives change by ~1 ulp relative there).
  if (piece.kind == PieceKind::bspline && side < 0 && u > lo && u < hi) {
    ue = std::nextafter(u, -std::numeric_limits<double>::infinity());
  }
  Vec2 d[4];
  piece_derivatives(piece, ue, 3, d);
  const Vec2 p = (ue == u) ? d[0] : piece_point(piece, u);
  const double n1 = d[1].norm(), n2 = d[2].norm(), n3 = d[3].norm();
  // The knot span holding ue: derivatives over it scale like 1/h^k, so C' is
  // rounding noise (a singular point) when it is tiny next to C'' h and C''' h^2.
  double h = hi - lo;
  if (piece.kind == PieceKind::bspline) {
    const std::vector<double>& t = piece.knots;
    auto above = std::upper_bound(t.begin(), t.end(), ue);
    if (above == t.end()) above = std::lower_bound(t.begin(), t.end(), hi);
    const auto first_equal = std::lower_bound(t.begin(), t.end(), *above);
    if (first_equal != t.begin()) h = *above - *(first_equal - 1);
  }
  if (n1 > 1e-10 * (n2 * h + n3 * h * h)) {
    *unit_tangent = d[1] / n1;
    *curvature = cross(d[1], d[2]) / (n1 * n1 * n1);
  } else if (n2 > 1e-10 * n3 * h) {
    // C'(u + s) ~ s C'': forward from above, backward from below.
    *unit_tangent = (side > 0 ? 1.0 : -1.0) * d[2] / n2;
    *curvature = std::numeric_limits<double>::quiet_NaN();
  } else {
    // C'(u + h) ~ h^2 C''' / 2 on both sides.
    *unit_tangent = n3 > 0 ? Vec2(d[3] / n3) : Vec2(1, 0);
    *curvature = std::numeric_limits<double>::quiet_NaN();
  }
  return p;
}

void split_into_spirals(const Profile& profile, std::vector<SpiralSpan>& out) {
  out.clear();
  thread_local SplitScratch sc;
  for (std::size_t i = 0; i < profile.pieces.size(); ++i) {
    const Piece& piece = profile.pieces[i];
    const int index = static_cast<int>(i);
    switch (piece.kind) {
      case PieceKind::line: {
        SpanEnds e;
        e.p0 = piece.points.front();
        e.p1 = piece.points.back();
        if (e.p0 == e.p1) break;
        e.t0 = e.t1 = (e.p1 - e.p0).normalized();
        push_span(out, index, SpanKind::line, 0.0, 1.0, e);
        break;
      }
      case PieceKind::arc: {
        const ArcGeometry g = arc_geometry(piece);
        const double dir = g.sweep > 0 ? 1.0 : -1.0;
        auto ends_at = [&](double u, Vec2* p, Vec2* t) {
          const double th = g.start_angle + u * g.sweep;
          *p = piece_point(piece, u);  // exact at u = 0 and u = 1
          *t = dir * Vec2(-std::sin(th), std::cos(th));
        };
        // r and z extremes: angles that are multiples of 90 degrees.
        sc.splits.clear();
        const double a0 = std::min(g.start_angle, g.start_angle + g.sweep);
        const double a1 = std::max(g.start_angle, g.start_angle + g.sweep);
        for (double q = std::ceil(a0 / (kPi / 2)) * (kPi / 2); q < a1; q += kPi / 2) {
          const double u = (q - g.start_angle) / g.sweep;
          if (u > 1e-12 && u < 1.0 - 1e-12) sc.splits.push_back(u);
        }
        std::sort(sc.splits.begin(), sc.splits.end());
        sc.splits.push_back(1.0);
        double ua = 0.0;
        for (double ub : sc.splits) {
          SpanEnds e;
          ends_at(ua, &e.p0, &e.t0);
          ends_at(ub, &e.p1, &e.t1);
          e.k0 = e.k1 = dir / g.radius;
          push_span(out, index, SpanKind::arc, ua, ub, e);
          ua = ub;
        }
        break;
      }
      case PieceKind::bezier:
      case PieceKind::bspline: {
        collect_curve_splits(piece, sc);
        const auto [lo, hi] = piece_domain(piece);
        sc.splits.push_back(hi);
        double ua = lo;
        for (double ub : sc.splits) {
          emit_curve_spans(piece, index, ua, ub, sc.breaks, 0, out);
          ua = ub;
        }
        break;
      }
    }
  }
}

}  // namespace revdist
