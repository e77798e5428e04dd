// Biarc of a spiral, its lens bound and its bounding capsule (paper section 4.1;
// the theorem and lemmas are stated in biarc_fit.h).
#include "fast/biarc_fit.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/curve_eval.h"

namespace revdist {

namespace {

constexpr double kHalfPi = 1.57079632679489661923;

Vec2 perp(const Vec2& a) { return Vec2(-a.y(), a.x()); }

// tan(angle(u, t) / 2) for unit u, t: sin / (1 + cos), exact as the angle -> 0.
double half_tan(const Vec2& u, const Vec2& t) { return cross2(u, t) / (1.0 + u.dot(t)); }

}  // namespace

LensBound lens_bound(const SpanEnds& e) {
  LensBound lb;
  const Vec2 v = e.p1 - e.p0;
  const double d = v.norm();
  if (!(d > 0)) {
    lb.hypotheses_ok = false;
    return lb;
  }
  const Vec2 u = v / d;
  lb.alpha = std::atan2(cross2(u, e.t0), u.dot(e.t0));
  lb.beta = std::atan2(cross2(u, e.t1), u.dot(e.t1));
  lb.width = 0.5 * d * std::abs(half_tan(u, e.t0) + half_tan(u, e.t1));
  // 1e-9 rad: the angles come from tangents with ~1e-15 relative error; a real
  // violation (a missed split) is far larger. The chord adds its own rounding:
  // p0 and p1 carry ~ulp of their coordinates, so its direction ~8 u |p| / d.
  const double chord_tol =
      8 * DBL_EPSILON * (e.p0.cwiseAbs().maxCoeff() + e.p1.cwiseAbs().maxCoeff()) / d;
  const double a = std::abs(lb.alpha), b = std::abs(lb.beta);
  bool ok = a <= kHalfPi + 1e-9 + chord_tol && b <= kHalfPi + 1e-9 + chord_tol;
  // Vogt's inequality: along a spiral, |angle to the chord| grows with |curvature|.
  if (std::isfinite(e.k0) && std::isfinite(e.k1)) {
    const double dk = std::abs(e.k1) - std::abs(e.k0);
    const double da = b - a;
    const double k_tol = 1e-7 * (std::abs(e.k0) + std::abs(e.k1));
    const double a_tol = 1e-7 * (a + b) + 1e-12 + 2 * chord_tol;
    if ((dk > k_tol && da < -a_tol) || (dk < -k_tol && da > a_tol)) ok = false;
  }
  lb.hypotheses_ok = ok;
  return lb;
}

Arc2 arc_from_tangent(const Vec2& p, const Vec2& t, const Vec2& q) {
  const Vec2 w = q - p;
  const double l2 = w.squaredNorm();
  Arc2 arc;
  arc.start = p;
  arc.tangent = t;
  if (!(l2 > 0)) return arc;  // zero length
  const double l = std::sqrt(l2);
  const double c = cross2(t, w), dd = t.dot(w);
  arc.curvature = 2.0 * c / l2;
  // Turning = 2 * half; length = l * half / sin(half), sin(half) = c / l.
  const double half = std::atan2(c, dd);
  if (std::abs(half) < 1e-4) {
    arc.length = l * (1.0 + half * half / 6.0);  // series of x / sin x, error ~ x^4 / 360 relative
  } else {
    arc.length = l * half / std::sin(half);
  }
  if (c == 0.0) arc.curvature = 0.0;
  return arc;
}

Vec2 joint_on_circle(const SpanEnds& e, const Vec2& hint) {
  const Vec2 v = e.p1 - e.p0;
  const double d = v.norm();
  const Vec2 u = v / d, n = perp(u);
  // Joint circle: tangent at p0 at the mean angle theta = (alpha - beta) / 2.
  const double alpha = std::atan2(cross2(u, e.t0), u.dot(e.t0));
  const double beta = std::atan2(cross2(u, e.t1), u.dot(e.t1));
  const double theta = 0.5 * (alpha - beta);
  const double k = 2.0 * std::sin(theta) / d;  // signed curvature of the joint circle
  const double x = std::clamp((hint - e.p0).dot(u), 0.0, d);
  const double m = x - 0.5 * d;
  const double y = x * (d - x) * k / (std::sqrt(std::max(0.0, 1.0 - k * k * m * m)) + std::cos(theta));
  return e.p0 + x * u + y * n;
}

Biarc biarc_with_joint(const SpanEnds& e, const Vec2& joint) {
  Biarc b;
  b.arc[0] = arc_from_tangent(e.p0, e.t0, joint);
  // The first arc's end tangent: t0 reflected across its chord.
  const Vec2 w = joint - e.p0;
  const double l2 = w.squaredNorm();
  const Vec2 tj = l2 > 0 ? Vec2(2.0 * w.dot(e.t0) / l2 * w - e.t0) : e.t0;
  b.arc[1] = arc_from_tangent(joint, tj.normalized(), e.p1);
  return b;
}

Biarc fit_curve_biarc(const Piece& piece, double u0, double u1, const SpanEnds& e, const Vec2& mid) {
  const Vec2 v = e.p1 - e.p0;
  const double d2 = v.squaredNorm();
  const Vec2 tau = (e.t0 + (2.0 * v.dot(e.t1) / d2 * v - e.t1)).normalized();  // t0 + reflect(t1)
  const double ctv = cross2(tau, v);
  // g(X) = cross2(tau, X - p0) d^2 - cross2(tau, v) |X - p0|^2 vanishes on the joint circle.
  double u = 0.5 * (u0 + u1);
  Vec2 x = mid;
  for (int it = 0; it < 3; ++it) {
    Vec2 c[2];
    piece_derivatives(piece, u, 1, c);
    x = c[0];
    const Vec2 w = c[0] - e.p0;
    const double g = cross2(tau, w) * d2 - ctv * w.squaredNorm();
    const double dg = (perp(tau) * d2 - 2.0 * ctv * w).dot(c[1]);
    if (!(std::abs(dg) > 0)) break;
    const double un = u - g / dg;
    if (!(un > u0 && un < u1)) break;  // Newton left the span: keep the last point
    if (std::abs(un - u) <= 1e-12 * (u1 - u0)) break;
    u = un;
  }
  return biarc_with_joint(e, joint_on_circle(e, x));
}

Capsule lens_capsule(const SpanEnds& e, const LensBound& lens) {
  const Vec2 v = e.p1 - e.p0;
  const double d = v.norm();
  Capsule c;
  if (!(d > 0)) {
    c.a = c.b = e.p0;
    return c;
  }
  const Vec2 u = v / d, n = perp(u);
  // Peak heights of the two lens arcs over the chord (left of it positive).
  const double s_a = 0.5 * d * std::tan(0.5 * lens.alpha);
  const double s_b = -0.5 * d * std::tan(0.5 * lens.beta);
  const double lo = std::min({0.0, s_a, s_b}), hi = std::max({0.0, s_a, s_b});
  const double mid = 0.5 * (lo + hi);
  c.a = e.p0 + mid * n;
  c.b = e.p1 + mid * n;
  c.radius = 0.5 * (hi - lo);
  return c;
}

Capsule capsule_union(const Capsule& c0, const Capsule& c1) {
  const Vec2 p[4] = {c0.a, c0.b, c1.a, c1.b};
  const double r[4] = {c0.radius, c0.radius, c1.radius, c1.radius};
  const Vec2 m = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  double sxx = 0, sxy = 0, syy = 0;
  for (const Vec2& q : p) {
    const Vec2 w = q - m;
    sxx += w.x() * w.x();
    sxy += w.x() * w.y();
    syy += w.y() * w.y();
  }
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // principal axis
  const Vec2 dir(std::cos(phi), std::sin(phi));
  double tmin = 0, tmax = 0;
  for (int i = 0; i < 4; ++i) {
    const double t = dir.dot(p[i] - m);
    tmin = i == 0 ? t : std::min(tmin, t);
    tmax = i == 0 ? t : std::max(tmax, t);
  }
  Capsule out;
  out.a = m + tmin * dir;
  out.b = m + tmax * dir;
  for (int i = 0; i < 4; ++i) {
    out.radius = std::max(out.radius, point_segment_distance(p[i], out.a, out.b) + r[i]);
  }
  return out;
}

}  // namespace revdist
