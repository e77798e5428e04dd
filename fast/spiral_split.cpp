// Spiral split of a profile (paper section 4.1).
//
// Root finder: the functions we split on (r', z', K, N, and the squared speed
// for singular points) are polynomials on each Bezier segment of a piece
// (their numerators, for rational pieces), computed in the Bernstein basis
// with a bound on their rounding error; fast/bernstein.h isolates their sign
// changes with proof (Descartes' rule on the control polygon, de Casteljau
// halving, safeguarded Newton). Only sign changes matter for the lens
// hypotheses (a root of even multiplicity does not break monotonicity). What
// the proof leaves open is only parts narrower than 2^-44 of a segment, at
// the split points themselves or where a function touches 0.
#include "fast/spiral_split.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "core/curve_eval.h"
#include "fast/bernstein.h"

namespace revdist {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The functions whose signs the lens hypotheses need, on one rational Bezier
// segment of a piece, as polynomials in the segment's parameter t in [0, 1]
// (u = u0 + t (u1 - u0), so d/dt = (u1 - u0) d/du keeps every sign). With the
// homogeneous form P = (X, Y, W) = (w r, w z, w), C = (X, Y) / W:
//   C'          = A / W^2,  A = (X'W - XW', Y'W - YW')
//   cross2(C',C'') = D / W^3, D = det[P, P', P'']
//   kappa       = D W^3 / |A|^3
//   d kappa/dt  = W^2 N / |A|^5,  N = (D'W + 3DW') |A|^2 - 3DW (A.A')
// so with W > 0 (weights are positive) r', z', the curvature and its
// derivative have the signs of A_x, A_y, D and N, and |A|^2 = 0 marks a
// singular point. For a polynomial segment (W = 1) these reduce to A = C',
// D = cross2(C', C''), N = D'|C'|^2 - 3D (C'.C''), of much lower degree.
// Each term of a sum has the same nominal degree, so no degree elevation.
struct SegmentFunctions {
  BernsteinPoly f[4];  // A_x, A_y, D, N
  BernsteinPoly speed2;
  bool curved = false;  // degree >= 2: D and N exist (else both are 0)
};

// Control points relative to the segment's first point (so magnitudes, and
// the error bounds that scale with them, measure the segment, not its place),
// scaled by powers of two (exact: a uniform scale and a positive factor on W
// change no sign). Input error: a Bezier piece's points are the input; a
// B-spline's segment points come from blossoming (p levels of convex
// combinations, each within ~9u of the window's magnitude, bounded by the
// piece's largest coordinate and weight) and a division and product;
// (12p + 16) u of those magnitudes covers that with room.
void segment_functions(const BezierSegment& seg, bool blossomed, double coord_mag, double weight_mag,
                       SegmentFunctions& out) {
  constexpr double kU = DBL_EPSILON / 2;
  const int p = seg.degree();
  const bool rational = !seg.weights.empty() &&
                        std::any_of(seg.weights.begin(), seg.weights.end(),
                                    [&](double w) { return w != seg.weights.front(); });
  const Vec2 o = seg.points.front();
  BernsteinPoly X, Y, W;
  for (BernsteinPoly* q : {&X, &Y, &W}) {
    q->b.resize(p + 1);
    q->err.resize(p + 1);
  }
  // Blossomed points: within (12p + 16) u of the window's magnitudes (absolute).
  const double c_in = blossomed ? (12.0 * p + 16.0) * kU : 0.0;
  double mx = 0.0, my = 0.0, mw = 0.0;
  for (int i = 0; i <= p; ++i) {
    const double w = rational ? seg.weights[i] : 1.0;
    const Vec2& q = seg.points[i];
    X.b[i] = w * (q.x() - o.x());
    Y.b[i] = w * (q.y() - o.y());
    W.b[i] = w;
    // The difference and the product round (2u of the result); a blossomed
    // point and o each carry the blossom's error, times the weight.
    X.err[i] = 3 * kU * std::abs(X.b[i]) + c_in * (rational ? weight_mag : 1.0) * 3 * coord_mag;
    Y.err[i] = 3 * kU * std::abs(Y.b[i]) + c_in * (rational ? weight_mag : 1.0) * 3 * coord_mag;
    W.err[i] = rational ? c_in * weight_mag : 0.0;
    mx = std::max(mx, std::abs(X.b[i]));
    my = std::max(my, std::abs(Y.b[i]));
    mw = std::max(mw, w);
  }
  // One power of two for X and Y (a uniform scale), another for W.
  auto pow2_inv = [](double m) {
    if (!(m > 0) || !std::isfinite(m)) return 1.0;
    int e;
    std::frexp(m, &e);
    return std::ldexp(1.0, -e);
  };
  const double sxy = pow2_inv(std::max(mx, my)), sw = pow2_inv(mw);
  for (int i = 0; i <= p; ++i) {
    X.b[i] *= sxy;
    X.err[i] *= sxy;
    Y.b[i] *= sxy;
    Y.err[i] *= sxy;
    W.b[i] *= sw;
    W.err[i] *= sw;
  }

  const BernsteinPoly X1 = bernstein_derivative(X), Y1 = bernstein_derivative(Y);
  out.curved = p >= 2;
  if (!rational) {
    out.f[0] = X1;
    out.f[1] = Y1;
    out.speed2 = bernstein_axpy(1, bernstein_mul(X1, X1), 1, bernstein_mul(Y1, Y1));
    if (!out.curved) return;
    const BernsteinPoly X2 = bernstein_derivative(X1), Y2 = bernstein_derivative(Y1);
    const BernsteinPoly D = bernstein_axpy(1, bernstein_mul(X1, Y2), -1, bernstein_mul(X2, Y1));
    const BernsteinPoly dot = bernstein_axpy(1, bernstein_mul(X1, X2), 1, bernstein_mul(Y1, Y2));
    out.f[2] = D;
    out.f[3] = bernstein_axpy(1, bernstein_mul(bernstein_derivative(D), out.speed2), -3, bernstein_mul(D, dot));
    return;
  }
  const BernsteinPoly W1 = bernstein_derivative(W);
  const BernsteinPoly Ax = bernstein_axpy(1, bernstein_mul(X1, W), -1, bernstein_mul(X, W1));
  const BernsteinPoly Ay = bernstein_axpy(1, bernstein_mul(Y1, W), -1, bernstein_mul(Y, W1));
  out.f[0] = Ax;
  out.f[1] = Ay;
  out.speed2 = bernstein_axpy(1, bernstein_mul(Ax, Ax), 1, bernstein_mul(Ay, Ay));
  if (!out.curved) return;
  const BernsteinPoly X2 = bernstein_derivative(X1), Y2 = bernstein_derivative(Y1), W2 = bernstein_derivative(W1);
  // det[P, P', P''] expanded along P.
  const BernsteinPoly m0 = bernstein_axpy(1, bernstein_mul(Y1, W2), -1, bernstein_mul(W1, Y2));
  const BernsteinPoly m1 = bernstein_axpy(1, bernstein_mul(X1, W2), -1, bernstein_mul(W1, X2));
  const BernsteinPoly m2 = bernstein_axpy(1, bernstein_mul(X1, Y2), -1, bernstein_mul(Y1, X2));
  const BernsteinPoly D = bernstein_axpy(
      1, bernstein_axpy(1, bernstein_mul(X, m0), -1, bernstein_mul(Y, m1)), 1, bernstein_mul(W, m2));
  const BernsteinPoly Ax1 = bernstein_derivative(Ax), Ay1 = bernstein_derivative(Ay);
  const BernsteinPoly dot = bernstein_axpy(1, bernstein_mul(Ax, Ax1), 1, bernstein_mul(Ay, Ay1));
  const BernsteinPoly lead = bernstein_axpy(1, bernstein_mul(bernstein_derivative(D), W), 3, bernstein_mul(D, W1));
  out.f[2] = D;
  out.f[3] = bernstein_axpy(1, bernstein_mul(lead, out.speed2), -3, bernstein_mul(bernstein_mul(D, W), dot));
}

// Parts of a segment narrower than this (in t) are not halved further: below
// it a sign change is located to within a few ulp of the parameter anyway.
constexpr double kTinyPart = 0x1p-44;
// Undecided stretches wider than this (relative to a segment) between equal
// signs leave the span unproven (see SignTrack).
constexpr double kWideGap = 0x1p-16;
// Halvings per function and segment; the bundled models need a few dozen.
constexpr int kMaxBoxes = 1 << 14;

// Turns the sign items of one function over consecutive segments into split
// parameters: wherever the proven sign before differs from the proven sign
// after. Between two proven parts lie a proven simple root (split there), or
// undecided parts (split at a knot inside them if there is one, where the
// function may jump, else at their middle), or nothing but a knot.
// An undecided stretch wider than `wide` with the same proven sign on both
// sides may hide a pair of sign changes below the rounding of the computed
// numerators (a sliver near a cusp, say): then nothing is claimed (doubt).
// Touching roots leave undecided stretches of ~sqrt(rounding) ~ 1e-7 of a
// segment, well below `wide`.
struct SignTrack {
  int last = 0;         // last proven sign (0: none yet)
  double gap_lo = 0.0;  // where the last proven information ended
  bool doubt = false;
  void see(int sign, double at, double wide, const std::vector<double>& breaks, std::vector<double>& splits) {
    if (last != 0 && sign != last) {
      const auto k = std::lower_bound(breaks.begin(), breaks.end(), gap_lo);
      splits.push_back(k != breaks.end() && *k <= at ? *k : 0.5 * (gap_lo + at));
    } else if (last != 0 && at - gap_lo > wide) {
      doubt = true;
    }
    last = sign;
  }
};

// Scratch reused across calls (rebuilding deformable solids is a hot path).
struct SplitScratch {
  std::vector<double> breaks;   // knot-span boundaries of the piece
  std::vector<double> splits;   // split parameters found so far
  std::vector<SignItem> items;
  SegmentFunctions fn;
};

// Appends to `splits` the sign changes of r', z', K and N and the singular
// points of the piece, from the proven isolation on each Bezier segment.
// Returns false when the work bound stopped an isolation or an undecided
// stretch could hide sign changes (the spans are then not proven spirals).
bool isolate_splits(const Piece& piece, SplitScratch& sc) {
  const std::vector<BezierSegment> segs = piece_bezier_segments(piece);
  double coord_mag = 0.0, weight_mag = 1.0;
  // (The segments' control points: an arc's three points may lie far inside its circle.)
  for (const BezierSegment& g : segs)
    for (const Vec2& q : g.points) coord_mag = std::max({coord_mag, std::abs(q.x()), std::abs(q.y())});
  for (double w : piece.weights) weight_mag = std::max(weight_mag, w);
  const bool blossomed = piece.kind == PieceKind::bspline;
  SignTrack track[4];
  // Singular points: interior runs where |A|^2 is not proven positive.
  bool in_run = false, seen_positive = false;
  double run_lo = 0.0;
  bool complete = true;
  for (const BezierSegment& seg : segs) {
    segment_functions(seg, blossomed, coord_mag, weight_mag, sc.fn);
    const double u0 = seg.u0, h = seg.u1 - seg.u0;
    auto at = [&](double t) { return t == 1.0 ? seg.u1 : u0 + h * t; };
    for (int f = 0; f < 4; ++f) {
      if (f >= 2 && !sc.fn.curved) continue;
      complete &= bernstein_sign_items(sc.fn.f[f], kTinyPart, kMaxBoxes, sc.items);
      for (const SignItem& it : sc.items) {
        if (it.left == 0) continue;
        track[f].see(it.left, at(it.t0), kWideGap * h, sc.breaks, sc.splits);
        if (it.right != it.left) {
          sc.splits.push_back(at(it.root));
          track[f].last = it.right;
        }
        track[f].gap_lo = at(it.t1);
      }
    }
    complete &= bernstein_sign_items(sc.fn.speed2, kTinyPart, kMaxBoxes, sc.items);
    for (const SignItem& it : sc.items) {
      if (it.left == 0) {
        if (!in_run) {
          in_run = true;
          run_lo = at(it.t0);
        }
        continue;
      }
      if (in_run && seen_positive) {
        // A cusp is a sign change of r' or z' inside the run, found exactly:
        // the run's middle only stands for a singular point with no other split.
        const double run_hi = at(it.t0);
        bool covered = false;
        for (double u : sc.splits) covered |= u >= run_lo && u <= run_hi;
        if (!covered) {
          const auto k = std::lower_bound(sc.breaks.begin(), sc.breaks.end(), run_lo);
          sc.splits.push_back(k != sc.breaks.end() && *k <= run_hi ? *k : 0.5 * (run_lo + run_hi));
        }
      }
      in_run = false;
      seen_positive = true;
    }
  }
  for (const SignTrack& t : track) complete &= !t.doubt;
  return complete;
}

// Sorts `splits` in (a, b), snapping to knots and dropping duplicates and ends.
void tidy_splits(std::vector<double>& splits, const std::vector<double>& breaks, double a, double b) {
  // A root within rounding of a knot is the knot: each side of the split is
  // then one polynomial span.
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

bool collect_curve_splits(const Piece& piece, SplitScratch& sc) {
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
  const bool complete = isolate_splits(piece, sc);
  tidy_splits(sc.splits, sc.breaks, lo, hi);
  return complete;
}

void push_span(std::vector<SpiralSpan>& out, int index, SpanKind kind, double u0, double u1,
               const SpanEnds& ends, bool proven = true) {
  if (ends.p0 == ends.p1) return;  // a zero-length part (a degenerate piece)
  SpiralSpan s;
  s.piece = index;
  s.kind = kind;
  s.u0 = u0;
  s.u1 = u1;
  s.ends = ends;
  s.proven = proven;
  out.push_back(s);
}

SpanEnds curve_ends(const Piece& piece, double ua, double ub) {
  SpanEnds e;
  e.p0 = piece_tangent(piece, ua, +1, &e.t0, &e.k0);
  e.p1 = piece_tangent(piece, ub, -1, &e.t1, &e.k1);
  return e;
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
    *curvature = cross2(d[1], d[2]) / (n1 * n1 * n1);
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
        const bool proven = collect_curve_splits(piece, sc);
        const auto [lo, hi] = piece_domain(piece);
        sc.splits.push_back(hi);
        double ua = lo;
        for (double ub : sc.splits) {
          push_span(out, index, SpanKind::curve, ua, ub, curve_ends(piece, ua, ub), proven);
          ua = ub;
        }
        break;
      }
    }
  }
}

}  // namespace revdist
