// Certified solid-solid distance (exact/solid_distance_exact.h; SPEC sections 2
// and 6). An oracle for paper section 4.2 that shares nothing with fast/: no
// biarcs, no circle binormals, only the input curves enclosed with MPFI.
//
// Reduction. For a point y in solid E's frame, its distance to E's surface is the
// plane distance from (rho, zeta) = (|(y1, y2)|, y3) to E's profile in the meridian
// half-plane (rotate the profile to y's azimuth). So the surface-surface distance
// is the minimum over pairs (element e_S of one profile, element e_E of the other)
// of  dist((rho, zeta)(X_S(u, psi)), e_E),  X_S(u, psi) the point of e_S's curve at
// u rotated by psi = 2 pi s about S's axis, seen in E's frame. The roles are chosen
// per pair: a line or arc element is the target whenever one of the two is, so the
// distance to it has a closed form and the box is 2-D (u, s); two free-form
// curves give a 3-D box (u, s, v) on g = (rho - r_E(v))^2 + (zeta - z_E(v))^2,
// bounded below by the larger of g's own form (below) and the distance to the
// chord of E's part over [v0, v1] less its control points' distance from it.
//   line a-b (e = b - a):  dist^2 = cross(e, P - a)^2 / |e|^2 + |e|^2 exc(t)^2,
//                          t = e.(P - a) / |e|^2, exc(t) = max(0, -t, t - 1);
//   arc (c, R, q0 -> q1, less than a half turn): dist >= | |P - c| - R |, with
//                          equality inside the (convex) sector; outside it
//                          dist = min(|P - q0|, |P - q1|).
// Bounds over a box. A curve's range over a parameter interval is the hull of
// its Bernstein coefficients restricted to it. Every quantity Q above (cross, t,
// |P - c|, |P - q|^2, g) is enclosed by the mean-value form
// Q(centre) + sum_i G_i [-h_i, h_i], with G_i an interval enclosure of dQ/dx_i
// over the box (chain rule through rho and zeta), intersected with the natural
// enclosure. rho = |v| is only Lipschitz at the axis:
// where the box may reach the axis, d rho/dx_i is enclosed by [-|v_i|, |v_i|],
// which contains every derivative of rho along any segment of the box (Lebourg's
// mean value theorem; rho is absolutely continuous along segments). The same holds
// for |P - c| near the arc's centre. So each box gets a PROVEN lower bound of the
// squared distance over its points, with error O(h^2) (quadratic convergence near
// a non-degenerate minimum; exact along flat continua such as parallel faces,
// where the quantity is affine and its derivative is 0).
// Upper bounds come only from genuine pairs: the box centre is a point of S's true
// surface (enclosed), and the target's value there is an upper bound of its
// distance to a genuine point of E's surface (an end point, the radial foot inside
// the sector, or C(v) at the same azimuth).
// Branch and bound: best-first on the lower bound, halving the dimension with the
// largest term of the mean-value form; boxes whose lower bound exceeds the best
// upper bound are dropped (they cannot hold the minimum). It stops when
// sqrt(UB) - sqrt(min lower) <= relative_width * scale or at the box budget; the
// interval [sqrt(min(min lower, UB)), sqrt(UB)] then contains the surface distance.
// Coaxial solids (decided exactly in rationals): every quantity is independent of
// psi, so s is fixed at 0 (a 1-D or 2-D problem in the common meridian plane).
//
// Solids, not surfaces (SPEC section 2). Both boundaries are connected closed
// surfaces and the complement of each solid is connected, so if the surfaces are
// disjoint (proven lower bound > 0), either one solid contains the other or they
// are disjoint, and one boundary point of each decides which: a point of A's
// surface strictly inside B (certified ray-crossing parity against B's exact
// curves, exact/solid_exact_geometry.cpp) means containment, distance 0. Before
// the branch and bound, sample points of each surface are tested the same way:
// one strictly inside the other solid proves a shared point (overlap = true).
// When the surfaces touch or cross, the lower bound stays 0 and [0, UB] is still
// proven; overlap is then reported only if some point near the closest pair is
// proven strictly inside the other solid.
#include "exact/solid_distance_exact.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "core/curve_eval.h"
#include "core/profile_check.h"
#include "exact/bezier_ray_crossings.h"
#include "exact/circle_distance_exact.h"
#include "exact/double_interval.h"
#include "exact/solid_exact_internal.h"

namespace revdist {

namespace {

using namespace solid_exact_detail;
using fit_audit_detail::pi;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Bernstein coefficients of an element, at most (the reader refuses higher
// degrees). Was 16: a Bezier of degree 16 to 32 left every box unbounded, and
// its queries ended without a finite bracket.
constexpr std::size_t kMaxCoeffs = kMaxPieceDegree + 1;

using exact_detail::Di;

// The interval-generic vocabulary of the box bounds: the same formulas run on Di
// (cheap, ~1e-16 looser) and on Ia (128-bit MPFI, the fallback near contact).
template <class I>
I iv(double lo, double hi);
template <>
Ia iv<Ia>(double lo, double hi) {
  Ia r;
  mpfi_interv_d(r.p(), lo, hi);
  return r;
}
template <>
Di iv<Di>(double lo, double hi) {
  return {lo, hi};
}
template <class I>
I sym(double h) {
  return iv<I>(-h, h);
}
template <class I>
I to(const Ia& x);
template <>
Ia to<Ia>(const Ia& x) {
  return x;
}
template <>
Di to<Di>(const Ia& x) {
  return {x.lo(), x.hi()};  // lo()/hi() round outward
}

// a intersected with b (both enclose the same range, so the meet is not empty;
// if rounding ever made it so, a alone is kept).
Ia meet(const Ia& a, const Ia& b) {
  Ia r;
  mpfi_intersect(r.p(), a.p(), b.p());
  if (mpfi_is_empty(r.p())) return a;
  return r;
}
using exact_detail::meet;
using fit_audit_detail::sqrt_nonneg;
using exact_detail::sqrt_nonneg;

// A lower bound of |x| over the interval, rounded down.
template <class I>
double mig(const I& x) {
  if (x.pos()) return x.lo();
  if (x.neg()) return -x.hi();
  return 0.0;
}
template <class I>
double sq_lo(double m) {
  return (I(m) * I(m)).lo();
}

// An element and a frame with their enclosures converted to I.
template <class I>
struct ElemT {
  ElemKind kind = ElemKind::curve;
  std::vector<I> x, y, w, dx, dy, dw;
  I ax, ay, bx, by, cx, cy, R;
};
template <class I>
ElemT<I> convert(const Element& e) {
  ElemT<I> o;
  o.kind = e.kind;
  auto cv = [](const Poly& p) {
    std::vector<I> v;
    for (const Ia& c : p) v.push_back(to<I>(c));
    return v;
  };
  o.x = cv(e.seg.x), o.y = cv(e.seg.y), o.w = cv(e.seg.w);
  o.dx = cv(e.dx), o.dy = cv(e.dy), o.dw = cv(e.dw);
  o.ax = to<I>(e.a.x), o.ay = to<I>(e.a.y), o.bx = to<I>(e.b.x), o.by = to<I>(e.b.y);
  o.cx = to<I>(e.c.x), o.cy = to<I>(e.c.y), o.R = to<I>(e.R);
  return o;
}
template <class I>
struct FrameT {
  I M[3][3], o[3];
};
template <class I>
FrameT<I> convert(const Frame& f) {
  FrameT<I> o;
  for (int i = 0; i < 3; ++i) {
    o.o[i] = to<I>(f.o[i]);
    for (int j = 0; j < 3; ++j) o.M[i][j] = to<I>(f.M[i][j]);
  }
  return o;
}

// As solid_exact_detail::bernstein_eval, elem_point(_deriv), rotation_cs; bern
// in convex form (see restrict_coeffs): on doubles, rounding would otherwise
// double per degree (4e-7 at degree 32, past the width target).
template <class I>
I bern(const std::vector<I>& c, const I& u) {
  I b[kMaxCoeffs];
  const std::size_t n = c.size();
  if (n > kMaxCoeffs) return I(0.0) * iv<I>(-kInf, kInf);  // unreachable (the reader's degree limit); a valid "anything"
  for (std::size_t j = 0; j < n; ++j) b[j] = c[j];
  const I v = I(1.0) - u;
  for (std::size_t r = 1; r < n; ++r)
    for (std::size_t j = 0; j + r < n; ++j) b[j] = v * b[j] + u * b[j + 1];
  return b[0];
}
template <class I>
void point_of(const ElemT<I>& e, const I& u, I& r, I& z) {
  const I w = bern(e.w, u);
  r = bern(e.x, u) / w;
  z = bern(e.y, u) / w;
}
template <class I>
void point_deriv(const ElemT<I>& e, const I& u, I& r, I& z, I& dr, I& dz) {
  const I w = bern(e.w, u), x = bern(e.x, u), y = bern(e.y, u);
  const I dw = bern(e.dw, u), dx = bern(e.dx, u), dy = bern(e.dy, u);
  r = x / w;
  z = y / w;
  const I w2 = sqr(w);
  dr = (dx * w - x * dw) / w2;
  dz = (dy * w - y * dw) / w2;
}
// The Bernstein coefficients of c restricted to [u0, u1] (0 <= u0 <= u1 <= 1), by
// two de Casteljau splits at point parameters, in `out` (c.size() of them): their
// hull encloses c's range over [u0, u1] within O((u1 - u0)^2) of it. An interval
// parameter in de Casteljau's recurrence instead (bern above) widens with the
// parameter's width at every level: a degree-8 element's boxes never got tight
// enough to leave 0. Each step is the convex combination (1 - t) b_j + t b_j+1:
// written b_j + t (b_j+1 - b_j) it uses b_j twice, and the coefficients'
// widths doubled per degree (2^32 x rounding, ~100, after a degree-32 split).
template <class I>
void restrict_coeffs(const std::vector<I>& c, double u0, double u1, I* out) {
  const std::size_t n = c.size();
  for (std::size_t j = 0; j < n; ++j) out[j] = c[j];
  if (u0 > 0) {  // the part on [u0, 1]: the right edge of de Casteljau's triangle at u0
    const I t(u0), t1 = I(1.0) - I(u0);
    I b[kMaxCoeffs];
    for (std::size_t j = 0; j < n; ++j) b[j] = c[j];
    for (std::size_t r = 1; r < n; ++r) {
      for (std::size_t j = 0; j + r < n; ++j) b[j] = t1 * b[j] + t * b[j + 1];
      out[n - 1 - r] = b[n - 1 - r];
    }
  }
  if (u1 < 1) {  // the part on [0, s] of what is left, s = (u1 - u0) / (1 - u0)
    const I s = u0 > 0 ? (I(u1) - I(u0)) / (I(1.0) - I(u0)) : I(u1), s1 = I(1.0) - s;
    I b[kMaxCoeffs];
    for (std::size_t j = 0; j < n; ++j) b[j] = out[j];
    for (std::size_t r = 1; r < n; ++r) {
      for (std::size_t j = 0; j + r < n; ++j) b[j] = s1 * b[j] + s * b[j + 1];
      out[r] = b[0];
    }
  }
}
template <class I>
I hull_of(const I* c, std::size_t n) {
  double lo = c[0].lo(), hi = c[0].hi();
  for (std::size_t j = 1; j < n; ++j) lo = std::min(lo, c[j].lo()), hi = std::max(hi, c[j].hi());
  return iv<I>(lo, hi);
}
// An element's curve over [u0, u1]: its x, y, w Bernstein coefficients
// restricted to it and, where every weight there is proven positive, the
// projected control points (x / w, y / w), whose hull holds that part of the
// curve. n = 0 when nothing is restricted (a degenerate interval).
template <class I>
struct CurvePart {
  std::size_t n = 0;
  bool projected = false;
  I x[kMaxCoeffs], y[kMaxCoeffs], w[kMaxCoeffs], px[kMaxCoeffs], py[kMaxCoeffs];
};
template <class I>
void curve_part(const ElemT<I>& e, double u0, double u1, CurvePart<I>& out) {
  const std::size_t n = e.x.size();
  out.n = 0;
  if (n > kMaxCoeffs || e.y.size() != n || e.w.size() != n || !(u0 < u1) || u0 < 0 || u1 > 1) return;
  restrict_coeffs(e.x, u0, u1, out.x);
  restrict_coeffs(e.y, u0, u1, out.y);
  restrict_coeffs(e.w, u0, u1, out.w);
  out.n = n;
  out.projected = true;
  for (std::size_t j = 0; j < n && out.projected; ++j) {
    out.projected = out.w[j].pos();
    if (out.projected) out.px[j] = out.x[j] / out.w[j], out.py[j] = out.y[j] / out.w[j];
  }
}
// point_deriv over the whole parameter interval [u0, u1] of `part` (curve_part
// of e over it), from the restricted coefficients' hulls (convex hull
// property; r and z also from the projected control points).
template <class I>
void point_deriv_range(const ElemT<I>& e, double u0, double u1, const CurvePart<I>& part, I& r, I& z, I& dr, I& dz) {
  const std::size_t n = part.n, m = e.dx.size();
  if (n == 0 || e.dy.size() != m || e.dw.size() != m) return point_deriv(e, iv<I>(u0, u1), r, z, dr, dz);
  const I x = hull_of(part.x, n), y = hull_of(part.y, n), w = hull_of(part.w, n);
  r = x / w;
  z = y / w;
  if (part.projected) {
    r = meet(r, hull_of(part.px, n));
    z = meet(z, hull_of(part.py, n));
  }
  if (m == 0) {
    dr = dz = I(0.0);
    return;
  }
  I ex[kMaxCoeffs], ey[kMaxCoeffs], ew[kMaxCoeffs];
  restrict_coeffs(e.dx, u0, u1, ex);
  restrict_coeffs(e.dy, u0, u1, ey);
  restrict_coeffs(e.dw, u0, u1, ew);
  const I dx = hull_of(ex, m), dy = hull_of(ey, m), dw = hull_of(ew, m);
  const I w2 = sqr(w);
  dr = (dx * w - x * dw) / w2;
  dz = (dy * w - y * dw) / w2;
}
template <class I>
void rot_cs(double s0, double s1, I& c, I& sn, I* dpsi_ds) {
  const bool second = s0 >= 1.0;
  const double k = second ? 1.0 : 0.0;
  const I t = I(2.0) * (iv<I>(s0, s1) - I(k)) - I(1.0);
  const I two_q = I(2.0) / (I(1.0) + sqr(t));
  c = two_q - I(1.0);
  sn = two_q * t;
  if (second) {
    c = -c;
    sn = -sn;
  }
  if (dpsi_ds) *dpsi_ds = I(2.0) * two_q;
}

// One pair of elements with its roles: the surface of element s_elem of solid
// s_side (0 = a, 1 = b) measured against element e_elem of the other solid.
struct Job {
  int s_side = 0;
  int s_elem = 0, e_elem = 0;
  bool three_d = false;
};

struct Box {
  double lower = 0.0;  // proven lower bound of the squared distance over the box, rounded down
  int job = 0;
  int split = -1;      // the dimension to halve next
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool operator>(const Box& o) const { return lower > o.lower; }
};

struct Eval {
  double lower = 0.0, upper = kInf;  // squared distance: over the box (down), at the centre (up)
  double rounding = 0.0;              // width of a centre value's enclosure: the arithmetic's own loss
  int split = -1;                     // dimension to halve, -1 when none can be
};

// E's curve over [v0, v1] (`part`) lies in the convex hull of its projected
// control points (positive weights), so within delta of their chord Q0-Qn
// (the delta-neighbourhood of a segment is convex), delta the largest distance
// of a control point from the chord. Then the distance to that part of the curve
// is at least the distance to the chord less delta: E's extent in v costs
// delta = O(h_v^2) in one term, instead of a first-order term coupled to the
// other parameters (g's mean-value form over (u, s, v): near a conformal
// contact its boxes lined a valley of constant g, 666000 boxes for one pair of
// Bezier solids at gap 1e-3). False when the chord is degenerate or a weight's
// sign is not proven; the caller then bounds g itself.
template <class I, class SegmentLower, class AddCost>
bool chord_bound(const CurvePart<I>& part, SegmentLower& segment_lower, AddCost& add_cost, double dist_c, Eval& ev) {
  const std::size_t n = part.n;
  if (n == 0 || !part.projected) return false;
  const I* qx = part.px;
  const I* qy = part.py;
  const I ex = qx[n - 1] - qx[0], ey = qy[n - 1] - qy[0];
  const I e2 = ex * ex + ey * ey;
  if (!e2.pos()) return false;
  // delta: each control point's distance to one point of the chord (its foot,
  // clamped, in double) bounds its distance to the chord from above.
  double delta = 0.0;
  const double exm = 0.5 * (ex.lo() + ex.hi()), eym = 0.5 * (ey.lo() + ey.hi());
  const double e2m = exm * exm + eym * eym;
  for (std::size_t j = 1; j + 1 < n; ++j) {
    const I px = qx[j] - qx[0], py = qy[j] - qy[0];
    const double t = std::clamp((0.5 * (px.lo() + px.hi()) * exm + 0.5 * (py.lo() + py.hi()) * eym) / e2m, 0.0, 1.0);
    delta = std::max(delta, sqrt_nonneg(sqr(px - I(t) * ex) + sqr(py - I(t) * ey)).hi());
  }
  if (!std::isfinite(delta)) return false;
  I up_c;
  const double seg = segment_lower(qx[0], qy[0], qx[n - 1], qy[n - 1], &up_c);
  const double d = (sqrt_nonneg(I(seg)) - I(delta)).lo();
  ev.lower = d > 0 ? sq_lo<I>(d) : 0.0;
  add_cost(2, delta, dist_c);
  return true;
}

// Proven bounds of the squared distance over a box of a job (S's surface patch
// against E's element, E's frame f): see the file comment for the method.
template <class I>
Eval bound_box(const Box& b, const ElemT<I>& S, const ElemT<I>& E, const FrameT<I>& f) {
  double c[3], h[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = 0.5 * (b.lo[i] + b.hi[i]);
    h[i] = std::max(c[i] - b.lo[i], b.hi[i] - c[i]);  // the centre is rounded; h covers both sides
  }
  // Over the box: S's point, its derivatives in u and s, seen in E's frame.
  I r, z, dr, dz;
  {
    CurvePart<I> part;
    curve_part(S, b.lo[0], b.hi[0], part);
    point_deriv_range(S, b.lo[0], b.hi[0], part, r, z, dr, dz);
  }
  I cs, sn, dpsi;
  rot_cs(b.lo[1], b.hi[1], cs, sn, &dpsi);
  I y[3], yu[3], ys[3];
  for (int k = 0; k < 3; ++k) {
    const I ec = cs * f.M[k][0] + sn * f.M[k][1];
    const I es = cs * f.M[k][1] - sn * f.M[k][0];
    y[k] = f.o[k] + r * ec + z * f.M[k][2];
    yu[k] = dr * ec + dz * f.M[k][2];
    ys[k] = dpsi * r * es;
  }
  const I rho = sqrt_nonneg(sqr(y[0]) + sqr(y[1])), zeta = y[2];
  I drho[2], dzeta[2] = {yu[2], ys[2]};
  const I* yd[2] = {yu, ys};
  for (int i = 0; i < 2; ++i) {
    if (rho.pos()) {
      drho[i] = (y[0] * yd[i][0] + y[1] * yd[i][1]) / rho;
    } else {
      const double L = sqrt_nonneg(sqr(yd[i][0]) + sqr(yd[i][1])).hi();
      drho[i] = iv<I>(-L, L);
    }
  }
  // At the centre.
  I rho_c, zeta_c;
  {
    I rc, zc, cc, sc;
    point_of(S, I(c[0]), rc, zc);
    rot_cs(c[1], c[1], cc, sc, static_cast<I*>(nullptr));
    I yc[3];
    for (int k = 0; k < 3; ++k) yc[k] = f.o[k] + rc * (cc * f.M[k][0] + sc * f.M[k][1]) + zc * f.M[k][2];
    rho_c = sqrt_nonneg(sqr(yc[0]) + sqr(yc[1]));
    zeta_c = yc[2];
  }
  const I H[3] = {sym<I>(h[0]), sym<I>(h[1]), sym<I>(h[2])};

  Eval ev;
  // Per dimension, how much the box's extent there lowers the bound of the squared
  // distance below its centre value: the dimension to halve is the one that costs most.
  double cost[3] = {0.0, 0.0, 0.0};
  // A term T (in distance units) of a quantity Q whose square enters the squared
  // distance lowers it by about 2 |Q(centre)| T + T^2; a term of a squared quantity by T.
  auto add_cost = [&](int i, double T, double q_mag) { cost[i] += q_mag < 0 ? T : T * (2.0 * q_mag + T); };
  // The mean-value form of Q given its derivatives with respect to rho and zeta.
  // `weight` converts Q's units to distance; q_mag = |Q(centre)| in distance units,
  // or < 0 when Q is itself a squared distance.
  auto centred = [&](const I& q_c, const I& q_rho, const I& q_zeta, double weight, double q_mag) {
    I out = q_c;
    for (int i = 0; i < 2; ++i) {
      const I g = q_rho * drho[i] + q_zeta * dzeta[i];
      out = out + g * H[i];
      add_cost(i, weight * abs(g).hi() * h[i], q_mag);
    }
    return out;
  };
  auto pick_split = [&]() {
    double best = -1.0;
    for (int i = 0; i < 3; ++i) {
      if (!(b.lo[i] < c[i] && c[i] < b.hi[i])) continue;  // cannot be halved (or frozen)
      // A NaN cost (0 x inf: an enclosure went unbounded, e.g. a rational weight's
      // range reaching 0 over a wide box) means "unknown, large": halve there.
      const double ci = std::isnan(cost[i]) ? kInf : cost[i];
      if (ci > best) {
        best = ci;
        ev.split = i;
      }
    }
  };

  // |P - p|^2 for a point p of the target: over the box (mean-value form) or at the centre.
  auto end_sq = [&](const I& px, const I& py, bool box) {
    const I dr_c = rho_c - px, dz_c = zeta_c - py;
    const I g_c = sqr(dr_c) + sqr(dz_c);
    if (!box) return g_c;
    const I dr_b = rho - px, dz_b = zeta - py;
    return meet(centred(g_c, I(2.0) * dr_b, I(2.0) * dz_b, 1.0, -1.0), sqr(dr_b) + sqr(dz_b));
  };
  // Where the nearest target point is certainly one end, the squared distance is
  // one smooth function and its own mean-value form is tight; a sum of separately
  // bounded terms would not be (their gradients cancel at the minimum).
  // The squared distance to the segment a-b over the box (proven, rounded down);
  // `up_c` gets its value at the centre.
  auto segment_lower = [&](const I& ax, const I& ay, const I& bx, const I& by, I* up_c) {
    const I ex = bx - ax, ey = by - ay;
    const I e2 = ex * ex + ey * ey;
    const I cr_c = ex * (zeta_c - ay) - ey * (rho_c - ax);
    const I t_c = ((rho_c - ax) * ex + (zeta_c - ay) * ey) / e2;
    const I t_nat = ((rho - ax) * ex + (zeta - ay) * ey) / e2;
    const double exc_hi = std::max({0.0, -t_c.lo(), (t_c - I(1.0)).hi()});
    *up_c = sqr(cr_c) / e2 + e2 * sqr(I(exc_hi));
    if (t_nat.neg() || (t_nat - I(1.0)).pos())  // the foot is off the segment: nearest point is an end
      return t_nat.neg() ? std::max(0.0, end_sq(ax, ay, true).lo()) : std::max(0.0, end_sq(bx, by, true).lo());
    const double elen = sqrt_nonneg(e2).lo();
    const I cr = meet(centred(cr_c, -ey, ex, 1.0 / elen, abs(cr_c).hi() / elen), ex * (zeta - ay) - ey * (rho - ax));
    // The tangential part lowers the bound only where the centre's foot is off the segment.
    const I t = meet(centred(t_c, ex / e2, ey / e2, exc_hi > 0 ? elen : 0.0, exc_hi * elen), t_nat);
    const double exc_lo = std::max({0.0, -t.hi(), (t - I(1.0)).lo()});
    return (I(sq_lo<I>(mig(cr))) / e2 + e2 * I(sq_lo<I>(exc_lo))).lo();
  };
  if (E.kind == ElemKind::line) {
    I up_c;
    ev.lower = segment_lower(E.ax, E.ay, E.bx, E.by, &up_c);
    ev.upper = up_c.hi();
    ev.rounding = up_c.hi() - up_c.lo();
    pick_split();
  } else if (E.kind == ElemKind::arc) {
    const I pr = rho - E.cx, pz = zeta - E.cy;
    const I pr_c = rho_c - E.cx, pz_c = zeta_c - E.cy;
    const I q_c = sqrt_nonneg(sqr(pr_c) + sqr(pz_c));
    // The closed sector: cross(q0 - c, P - c) >= 0 and cross(P - c, q1 - c) >= 0.
    const I a0x = E.ax - E.cx, a0y = E.ay - E.cy, b0x = E.bx - E.cx, b0y = E.by - E.cy;
    const I w0 = a0x * pz - a0y * pr, w1 = pr * b0y - pz * b0x;
    const I w0_c = a0x * pz_c - a0y * pr_c, w1_c = pr_c * b0y - pz_c * b0x;
    if (w0.neg() || w1.neg()) {  // outside the sector: the nearest arc point is an end
      const I ga = end_sq(E.ax, E.ay, true), gb = end_sq(E.bx, E.by, true);
      ev.lower = std::max(0.0, std::min(ga.lo(), gb.lo()));
    } else {  // the whole circle is nearer than the arc
      const I q_nat = sqrt_nonneg(sqr(pr) + sqr(pz));
      I q;
      if (q_nat.pos()) {
        q = meet(centred(q_c, pr / q_nat, pz / q_nat, 1.0, abs(q_c - E.R).hi()), q_nat);
      } else {  // the box may reach the centre: |P - c| is 1-Lipschitz in P
        q = q_nat;
        for (int i = 0; i < 2; ++i)
          add_cost(i, sqrt_nonneg(sqr(drho[i]) + sqr(dzeta[i])).hi() * h[i], abs(q_c - E.R).hi());
      }
      ev.lower = sq_lo<I>(mig(q - E.R));
    }
    const I ga_c = end_sq(E.ax, E.ay, false);
    double up = std::min(ga_c.hi(), end_sq(E.bx, E.by, false).hi());
    ev.rounding = ga_c.hi() - ga_c.lo();
    if (w0_c.nonneg() && w1_c.nonneg()) up = std::min(up, sqr(q_c - E.R).hi());
    ev.upper = up;
    pick_split();
  } else {
    I rec, zec;
    point_of(E, I(c[2]), rec, zec);
    const I g_c = sqr(rho_c - rec) + sqr(zeta_c - zec);
    ev.upper = g_c.hi();
    ev.rounding = g_c.hi() - g_c.lo();
    // The chord's bound and g's own mean-value form, the larger (with its split
    // costs): the chord's is the tight one over wide parts of E; over a part so
    // short that its control points' rounding is a fair share of the chord, the
    // chord's direction is lost in it, and g's form is the tight one.
    CurvePart<I> part;  // E over [v0, v1], restricted once for both
    curve_part(E, b.lo[2], b.hi[2], part);
    Eval ch = ev;
    const bool chord = chord_bound(part, segment_lower, add_cost, std::sqrt(g_c.hi()), ch);
    const double chord_cost[3] = {cost[0], cost[1], cost[2]};
    cost[0] = cost[1] = cost[2] = 0.0;
    I re, ze, dre, dze;
    point_deriv_range(E, b.lo[2], b.hi[2], part, re, ze, dre, dze);
    const I dR = rho - re, dZ = zeta - ze;
    const I two(2.0);
    const I gv = two * (dR * dre + dZ * dze);
    cost[2] = abs(gv).hi() * h[2];
    const I g = meet(centred(g_c, two * dR, two * dZ, 1.0, -1.0) - gv * H[2], sqr(dR) + sqr(dZ));
    ev.lower = std::max(0.0, g.lo());
    if (chord && ch.lower > ev.lower) {
      ev.lower = ch.lower;
      std::copy(chord_cost, chord_cost + 3, cost);
    }
    pick_split();
  }
  return ev;
}

// solid_exact_detail::point_in_solid on doubles: the same crossing count of the
// ray {(r, zeta) : r > rho} with each exact curve (Bernstein signs, halving until
// decided), -1 / unknown where outward-rounded doubles cannot decide.
int crossings_di(const std::vector<Di>& x, const std::vector<Di>& y, const std::vector<Di>& w, const Di& rho,
                 const Di& zeta, int depth) {
  if (w.size() > kMaxCoeffs) return -1;
  auto halve_di = [](const std::vector<Di>& c, std::vector<Di>& l, std::vector<Di>& r) {  // halving is exact
    const std::size_t n = c.size();
    std::vector<Di> b = c;
    l.resize(n);
    r.resize(n);
    for (std::size_t m = 0; m < n; ++m) {
      l[m] = b[0];
      r[n - 1 - m] = b[n - 1 - m];
      for (std::size_t j = 0; j + 1 < n - m; ++j) b[j] = (b[j] + b[j + 1]) * Di(0.5);
    }
  };
  return exact_detail::bezier_ray_crossings(x, y, w, rho, zeta, 30, halve_di, depth);
}
Inside point_in_solid_di(const std::vector<ElemT<Di>>& elems, const Di& rho, const Di& zeta) {
  int total = 0;
  for (const ElemT<Di>& e : elems) {
    const int n = crossings_di(e.x, e.y, e.w, rho, zeta, 0);
    if (n < 0) return Inside::unknown;
    total += n;
  }
  return total % 2 == 1 ? Inside::inside : Inside::outside;
}

// Inverse of psi_of (the chart of solid_exact_internal.h), psi in [-pi, pi].
double s_of(double psi) {
  if (std::abs(psi) <= 0.5 * M_PI) return std::clamp(0.5 * (std::tan(0.5 * psi) + 1.0), 0.0, 1.0);
  const double p = psi > 0 ? psi - M_PI : psi + M_PI;
  return std::clamp(1.0 + 0.5 * (std::tan(0.5 * p) + 1.0), 1.0, 2.0);
}

// Closest circle pairs tried per job for a genuine pair (tube_bound).
constexpr std::size_t kTubeTargets = 8;
// A box's double bound is kept when its spread exceeds this many times its
// centre value's rounding (see Solver::evaluate).
constexpr double kDoubleSpread = 64.0;

class Solver {
 public:
  Solver(const std::vector<Element>* elems, const Pose* poses, bool coaxial)
      : elems_(elems), poses_(poses), coaxial_(coaxial) {
    frames_[0] = relative_frame(poses[0], poses[1]);
    frames_[1] = relative_frame(poses[1], poses[0]);
    for (int side = 0; side < 2; ++side) {
      iframes_[side] = convert<Ia>(frames_[side]);
      dframes_[side] = convert<Di>(frames_[side]);
      for (const Element& e : elems_[side]) {
        ielem_[side].push_back(convert<Ia>(e));
        delem_[side].push_back(convert<Di>(e));
      }
    }
  }

  std::vector<Job> jobs;

  void make_jobs() {
    for (std::size_t i = 0; i < elems_[0].size(); ++i)
      for (std::size_t j = 0; j < elems_[1].size(); ++j) {
        Job job;
        const bool a_curve = elems_[0][i].kind == ElemKind::curve;
        const bool b_curve = elems_[1][j].kind == ElemKind::curve;
        if (!b_curve || a_curve) {
          job = {0, static_cast<int>(i), static_cast<int>(j), b_curve};
        } else {
          job = {1, static_cast<int>(j), static_cast<int>(i), false};
        }
        jobs.push_back(job);
      }
  }

  // Meridian coordinates, in the other solid's frame, of S's surface at (u, s).
  void meridian(const Job& job, const Ia& u, double s, Ia& rho, Ia& zeta, Ia y[3]) const {
    surface_point(elems_[job.s_side][job.s_elem], frames_[job.s_side], u, s, y);
    rho = fit_audit_detail::sqrt_nonneg(sqr(y[0]) + sqr(y[1]));
    zeta = y[2];
  }

  // The bounds of a box: on doubles first; on 128-bit MPFI where the double
  // bound may be too loose to matter (squared distances near 0, where rounding
  // of ~1e-16 scale^2 becomes ~1e-8 scale after the square root) and the box is
  // small enough for that rounding to be a part of its spread (upper - lower):
  // a wider box's bound is its extent's, and MPFI (~20x the cost) would not
  // raise it. (Near contact every box went to MPFI before: ~100 us a box.)
  Eval evaluate(const Box& b) const {
    const Job& job = jobs[b.job];
    const Eval ev = bound_box<Di>(b, delem_[job.s_side][job.s_elem], delem_[1 - job.s_side][job.e_elem],
                                  dframes_[job.s_side]);
    // (A centre value computed exactly says nothing of the box's rounding: MPFI then.)
    if (doubles_ && (ev.lower > mpfi_below_ || (ev.rounding > 0 && ev.upper - ev.lower > kDoubleSpread * ev.rounding)))
      return ev;
    ++mpfi_boxes;
    return bound_box<Ia>(b, ielem_[job.s_side][job.s_elem], ielem_[1 - job.s_side][job.e_elem],
                         iframes_[job.s_side]);
  }
  std::size_t circle_pairs() const { return circle_cache_.size(); }  // certified for the tube bounds
  // Doubles where they suffice (above), or MPFI on every box (doubles = false).
  void set_mpfi_below(double squared_distance, bool doubles) {
    mpfi_below_ = squared_distance;
    doubles_ = doubles;
  }
  mutable long mpfi_boxes = 0;

  // World points of the pair realising the centre value of a box: [0] on S, [1] on E.
  void witness(const Box& b, Vec3 out[2]) const {
    const Job& job = jobs[b.job];
    const Element& S = elems_[job.s_side][job.s_elem];
    const Element& E = elems_[1 - job.s_side][job.e_elem];
    double c[3];
    for (int i = 0; i < 3; ++i) c[i] = 0.5 * (b.lo[i] + b.hi[i]);
    Ia r, z;
    elem_point(S, Ia(c[0]), r, z);
    const double psi = psi_of(c[1]);
    const Vec3 local(mid(r) * std::cos(psi), mid(r) * std::sin(psi), mid(z));
    out[0] = poses_[job.s_side].apply(local);
    Ia rho_c, zeta_c, yc[3];
    meridian(job, Ia(c[0]), c[1], rho_c, zeta_c, yc);
    const Vec2 P(mid(rho_c), mid(zeta_c));
    Vec2 Q;
    if (E.kind == ElemKind::line) {
      const Vec2 a(mid(E.a.x), mid(E.a.y)), e = Vec2(mid(E.b.x), mid(E.b.y)) - a;
      Q = a + std::clamp((P - a).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
    } else if (E.kind == ElemKind::arc) {
      const Vec2 cc(mid(E.c.x), mid(E.c.y)), q0(mid(E.a.x), mid(E.a.y)), q1(mid(E.b.x), mid(E.b.y));
      const Vec2 d = P - cc;
      const auto crs = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
      if (d.norm() > 0 && crs(q0 - cc, d) >= 0 && crs(d, q1 - cc) >= 0)
        Q = cc + mid(E.R) * d / d.norm();
      else
        Q = (P - q0).norm() <= (P - q1).norm() ? q0 : q1;
    } else {
      Ia re, ze;
      elem_point(E, Ia(c[2]), re, ze);
      Q = Vec2(mid(re), mid(ze));
    }
    const double phi = std::atan2(mid(yc[1]), mid(yc[0]));
    out[1] = poses_[1 - job.s_side].apply(Vec3(Q.x() * std::cos(phi), Q.x() * std::sin(phi), Q.y()));
  }

  // Is S's surface point at (u, s) of this job strictly inside the other solid?
  // On doubles first (the screen tests hundreds of points); MPFI decides what
  // the doubles leave open.
  Inside test_point(int side, int elem, double u, double s, Vec3* world) const {
    Inside in;
    {
      Di r, z, c, sn, y[3];
      point_of(delem_[side][elem], Di(u), r, z);
      rot_cs(s, s, c, sn, static_cast<Di*>(nullptr));
      const FrameT<Di>& f = dframes_[side];
      for (int k = 0; k < 3; ++k) y[k] = f.o[k] + r * (c * f.M[k][0] + sn * f.M[k][1]) + z * f.M[k][2];
      in = point_in_solid_di(delem_[1 - side], sqrt_nonneg(sqr(y[0]) + sqr(y[1])), y[2]);
    }
    if (in == Inside::unknown) {
      Ia y[3];
      surface_point(elems_[side][elem], frames_[side], Ia(u), s, y);
      const Ia rho = fit_audit_detail::sqrt_nonneg(sqr(y[0]) + sqr(y[1]));
      in = point_in_solid(elems_[1 - side], rho, y[2]);
    }
    if (world) {
      Ia r, z;
      elem_point(elems_[side][elem], Ia(u), r, z);
      const double psi = psi_of(s);
      *world = poses_[side].apply(Vec3(mid(r) * std::cos(psi), mid(r) * std::sin(psi), mid(z)));
    }
    return in;
  }

  bool coaxial() const { return coaxial_; }

  // Tube against tube (paper section 3: a torus is the offset of its major
  // circle). An arc element, or a curve certified to lie within [R_lo, R_hi] of
  // a centre, sweeps a surface inside the solid tube of radius R_hi around the
  // circle its centre sweeps; the distance between two solid tubes is
  // max(0, d(C_S, C_E) - R_S - R_E) (Minkowski sums), so
  //   dist(patch_S, patch_E) >= d(C_S, C_E) - R_S,hi - R_E,hi,
  // with d(C_S, C_E) the certified circle distance (exact/circle_distance_exact).
  // When the closest circle pair's direction lies in both elements' sectors the
  // surface points along it are a genuine pair at that distance (up to R_hi -
  // R_lo): the job is settled without a search, continua of closest pairs
  // included (coaxial, interlocked rings, a sphere around a point).
  // The circles are rounded to doubles for the circle engine; each point of the
  // rounded circle is within delta of the true one, which the bound subtracts.
  struct Tube {
    bool ok = false;
    double lower = 0.0;   // proven lower bound of the job's distance, rounded down
    double upper_sq = kInf;  // squared distance of a genuine pair, rounded up
    Box box;              // the degenerate box of that pair (witness)
  };
  Tube tube_bound(int j, double tol) const {
    Tube t;
    const Job& job = jobs[j];
    const int sides[2] = {job.s_side, 1 - job.s_side};
    const int ids[2] = {job.s_elem, job.e_elem};
    double cr[2], cz[2], R_hi[2], R_lo[2], c_err[2];
    for (int k = 0; k < 2; ++k) {
      auto& memo = circ_memo_[sides[k]];
      if (memo.empty()) memo.resize(elems_[sides[k]].size());
      CircInfo& ci = memo[ids[k]];
      if (ci.state == 0)
        ci.state = circular(elems_[sides[k]][ids[k]], tol, ci.cr, ci.cz, ci.R_lo, ci.R_hi, ci.c_err) ? 1 : 2;
      if (ci.state != 1) return t;
      cr[k] = ci.cr, cz[k] = ci.cz, R_lo[k] = ci.R_lo, R_hi[k] = ci.R_hi, c_err[k] = ci.c_err;
    }
    // In E's frame (E = sides[1]): C_E = ((0, 0, cz_E), e3, cr_E); C_S through the relative frame.
    const Frame& f = frames_[job.s_side];
    Circle3 circ[2];
    double delta[2] = {c_err[0], c_err[1]};
    circ[1].center = Vec3(0, 0, cz[1]);
    circ[1].normal = Vec3::UnitZ();
    circ[1].radius = cr[1];
    circ[0].radius = cr[0];
    double eta = 0.0, cw = 0.0;
    for (int i = 0; i < 3; ++i) {
      const Ia ci = f.o[i] + f.M[i][2] * Ia(cz[0]);
      circ[0].center[i] = 0.5 * (ci.lo() + ci.hi());
      circ[0].normal[i] = 0.5 * (f.M[i][2].lo() + f.M[i][2].hi());
      cw += sqr(Ia(ci.width())).hi();
      eta += sqr(Ia(f.M[i][2].width())).hi();
    }
    // |c - c~| <= |widths|; a unit normal off by eta turns the circle by an angle
    // <= 2 eta (eta << 1), moving its points by <= r * 2 eta.
    eta = std::sqrt(eta) * 1.0001;
    if (!(eta < 1e-3)) return t;
    delta[0] = (Ia(delta[0]) + Ia(std::sqrt(cw) * 1.0001) + Ia(cr[0]) * Ia(2.0 * eta)).hi();
    // Elements of one torus share its circle: certify each circle pair once. A
    // pair within tol / 64 of one certified before takes that one's result, its
    // circles moved: a circle (0, 0, z) of radius r moved to (0, 0, z') of
    // radius r' moves each point by at most |z - z'| + |r - r'| (through the
    // rigid frame too, up to the centre's rounding, counted again). The arcs of
    // one sphere, whose computed centres differ in their last bits, made 10000
    // keys for two 100-arc spheres, each certified apart (minutes).
    const std::array<double, 5> key = {cr[0], cz[0], cr[1], cz[1], static_cast<double>(job.s_side)};
    const ExactCircleResult* hit = nullptr;
    double moved[2] = {0.0, 0.0};
    for (const auto& [k, r] : circle_cache_) {
      if (k[4] != key[4]) continue;
      const double m0 = (Ia(std::abs(k[0] - key[0])) + Ia(std::abs(k[1] - key[1]))).hi();
      const double m1 = (Ia(std::abs(k[2] - key[2])) + Ia(std::abs(k[3] - key[3]))).hi();
      if (m0 == 0 && m1 == 0) {
        hit = &r, moved[0] = moved[1] = 0.0;
        break;
      }
      if (!hit && m0 + m1 <= tol / 64) {
        hit = &r;
        moved[0] = (Ia(m0) * Ia(1.0001) + Ia(std::sqrt(cw) * 1.0001)).hi();
        moved[1] = m1;
      }
    }
    if (!hit) {
      circle_cache_.emplace_back(key, circle3_circle3_distance_exact(circ[0], circ[1]));
      hit = &circle_cache_.back().second;
    }
    delta[0] = (Ia(delta[0]) + Ia(moved[0])).hi();
    delta[1] = (Ia(delta[1]) + Ia(moved[1])).hi();
    const ExactCircleResult cd = *hit;
    if (cd.status == ExactStatus::not_certified) return t;
    const double lb = (Ia(cd.lower) - Ia(delta[0]) - Ia(delta[1]) - Ia(R_hi[0]) - Ia(R_hi[1])).lo();
    if (!(lb > 0)) return t;  // the tubes may meet: nothing gained over the search
    t.ok = true;
    t.lower = lb;
    // A genuine pair along the circles' closest pair, found in doubles and then
    // bounded like any box (so it is a proof whatever the doubles did). Every
    // closest pair certified so far is tried: symmetric configurations have
    // several, and the one in this job's sectors may have come from another job.
    // (This job's own circle pair first, then at most kTubeTargets others: a
    // loop over every entry made the pass quadratic in the jobs.)
    std::vector<const ExactCircleResult*> targets{hit};
    for (const auto& entry : circle_cache_)
      if (&entry.second != hit && targets.size() < kTubeTargets) targets.push_back(&entry.second);
    for (const ExactCircleResult* target : targets) {
      const Vec3 pa = target->point_a, pb = target->point_b;
      if (!((pb - pa).norm() > 0)) continue;
      const Vec3 d = (pb - pa).normalized();
      const Vec3 target_s = pa + d * 0.5 * (R_lo[0] + R_hi[0]);
      const Vec3 target_e = pb - d * 0.5 * (R_lo[1] + R_hi[1]);
      // Target points in each solid's own frame: S's through the inverse frame.
      Vec3 xs;
      for (int i = 0; i < 3; ++i) {
        double acc = 0.0;
        for (int k = 0; k < 3; ++k) acc += mid(f.M[k][i]) * (target_s[k] - mid(f.o[k]));
        xs[i] = acc;
      }
      Box b;
      b.job = j;
      b.lo[0] = b.hi[0] = project(delem_[sides[0]][ids[0]], Vec2(std::hypot(xs.x(), xs.y()), xs.z()));
      b.lo[1] = b.hi[1] = s_of(std::atan2(xs.y(), xs.x()));
      b.lo[2] = b.hi[2] = job.three_d ? project(delem_[sides[1]][ids[1]],
                                                Vec2(std::hypot(target_e.x(), target_e.y()), target_e.z()))
                                      : 0.0;
      const Eval ev = bound_box<Ia>(b, ielem_[sides[0]][ids[0]], ielem_[sides[1]][ids[1]], iframes_[job.s_side]);
      if (ev.upper < t.upper_sq) {
        t.upper_sq = ev.upper;
        t.box = b;
      }
    }
    return t;
  }

 private:
  // Is the element's curve within [R_lo, R_hi] of a centre (cr, cz), proven? Arcs
  // are; a curve is when the Bernstein coefficients of (|C - c|^2 - R^2) w^2
  // over those of w^2 say so within tol / 64 (rational quadratic circles whose
  // weights were rounded, for instance). c_err: how far the true centre may be
  // from (cr, cz) (arcs: the rational circumcentre's enclosure).
  bool circular(const Element& e, double tol, double& cr, double& cz, double& R_lo, double& R_hi,
                double& c_err) const {
    if (e.kind == ElemKind::line) return false;
    if (e.kind == ElemKind::arc) {
      cr = mid(e.c.x);
      cz = mid(e.c.y);
      c_err = std::hypot(e.c.x.width(), e.c.y.width()) * 1.0001;
      R_lo = e.R.lo() - c_err;
      R_hi = e.R.hi() + c_err;
      return cr >= 0 && R_lo > 0;
    }
    // A circle through the curve's ends and middle, in doubles (any centre is
    // sound: the annulus below is what is proven).
    Ia r0, z0, r1, z1, rm, zm;
    elem_point(e, Ia(0.0), r0, z0);
    elem_point(e, Ia(1.0), r1, z1);
    elem_point(e, Ia(0.5), rm, zm);
    const Vec2 p0(mid(r0), mid(z0)), p1(mid(r1), mid(z1)), pm(mid(rm), mid(zm));
    const Vec2 a = pm - p0, b = p1 - p0;
    const double den = 2.0 * (a.x() * b.y() - a.y() * b.x());
    if (!(std::abs(den) > 1e-12 * (a.squaredNorm() + b.squaredNorm()))) return false;
    const Vec2 c = p0 + Vec2(b.y() * a.squaredNorm() - a.y() * b.squaredNorm(),
                             a.x() * b.squaredNorm() - b.x() * a.squaredNorm()) / den;
    if (!(c.x() >= 0)) return false;
    const double R = (p0 - c).norm();
    using fit_audit_detail::bernstein_product;
    const std::size_t n = e.seg.w.size();
    Poly qx(n), qy(n);
    for (std::size_t i = 0; i < n; ++i) {
      qx[i] = e.seg.x[i] - Ia(c.x()) * e.seg.w[i];
      qy[i] = e.seg.y[i] - Ia(c.y()) * e.seg.w[i];
    }
    const Poly xx = bernstein_product(qx, qx), yy = bernstein_product(qy, qy), ww = bernstein_product(e.seg.w, e.seg.w);
    double m = kInf, M = -kInf;
    for (std::size_t i = 0; i < ww.size(); ++i) {
      if (!ww[i].pos()) return false;
      const Ia q = (xx[i] + yy[i]) / ww[i] - sqr(Ia(R));
      m = std::min(m, q.lo());
      M = std::max(M, q.hi());
    }
    const Ia lo2 = sqr(Ia(R)) + Ia(m), hi2 = sqr(Ia(R)) + Ia(M);
    if (!lo2.pos()) return false;
    R_lo = fit_audit_detail::sqrt_nonneg(lo2).lo();
    R_hi = fit_audit_detail::sqrt_nonneg(hi2).hi();
    if (!(R_hi - R_lo <= tol / 64)) return false;
    cr = c.x();
    cz = c.y();
    c_err = 0.0;
    return true;
  }
  // The parameter of the element's point nearest to q, in doubles (sampling,
  // then golden-section search): only a guess; its use is bounded exactly.
  static double project(const ElemT<Di>& e, const Vec2& q) {
    auto dist2 = [&](double u) {
      Di r, z;
      point_of(e, Di(u), r, z);
      return sq2(0.5 * (r.lo() + r.hi()) - q.x()) + sq2(0.5 * (z.lo() + z.hi()) - q.y());
    };
    const int n = 64;
    int best = 0;
    double bd = kInf;
    for (int i = 0; i <= n; ++i) {
      const double v = dist2(static_cast<double>(i) / n);
      if (v < bd) bd = v, best = i;
    }
    double lo = std::max(0.0, (best - 1.0) / n), hi = std::min(1.0, (best + 1.0) / n);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 80 && hi - lo > 1e-17; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (dist2(x1) < dist2(x2))
        hi = x2;
      else
        lo = x1;
    }
    return 0.5 * (lo + hi);
  }
  static double sq2(double x) { return x * x; }

 public:

 private:
  static double mid(const Ia& x) { return 0.5 * (x.lo() + x.hi()); }

  const std::vector<Element>* elems_;
  const Pose* poses_;
  bool coaxial_;
  Frame frames_[2];
  FrameT<Ia> iframes_[2];
  FrameT<Di> dframes_[2];
  std::vector<ElemT<Ia>> ielem_[2];
  std::vector<ElemT<Di>> delem_[2];
  double mpfi_below_ = 0.0;
  bool doubles_ = true;
  mutable std::vector<std::pair<std::array<double, 5>, ExactCircleResult>> circle_cache_;
  struct CircInfo {
    int state = 0;  // 0 not yet asked, 1 circular, 2 not
    double cr = 0, cz = 0, R_lo = 0, R_hi = 0, c_err = 0;
  };
  mutable std::vector<CircInfo> circ_memo_[2];
};

// Size of a profile for the width target: the extent of its curve (profile_box).
double width_size(const Profile& p) {
  if (p.pieces.empty()) return 0.0;
  Vec2 lo, hi;
  profile_box(p, &lo, &hi);
  return std::max(2.0 * std::max(hi.x(), 0.0), hi.y() - lo.y());
}

// Per-thread CPU time: the machine is shared, wall clock would time the neighbours.
double thread_cpu_ms() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double round_down_sqrt(double x) { return x > 0 ? std::nextafter(std::sqrt(x), 0.0) : 0.0; }
double round_up_sqrt(double x) { return std::nextafter(std::sqrt(x), kInf); }

}  // namespace

long exact_elements(const Profile& profile) {
  long n = 0;
  for (const Piece& piece : profile.pieces) n += static_cast<long>(piece_bezier_segments(piece).size());
  return n;
}

ExactSolidResult solid_distance_exact(const Profile& a, const Pose& pose_a, const Profile& b, const Pose& pose_b,
                                      const ExactSolidOptions& options) {
  const double t0 = thread_cpu_ms();
  if (const long na = exact_elements(a), nb = exact_elements(b); na * nb > kMaxExactElementPairs) {
    ExactSolidResult r;
    r.upper = kInf;
    r.reason = std::to_string(na) + " x " + std::to_string(nb) + " profile elements: more than the " +
               std::to_string(kMaxExactElementPairs) + " element pairs a certified query takes";
    r.time_ms = thread_cpu_ms() - t0;
    return r;
  }
  const auto wall0 = std::chrono::steady_clock::now();  // progress is paced in wall time, as users see it
  ExactSolidResult res;
  res.upper = kInf;
  const Solver* solver_ptr = nullptr;
  auto finish = [&]() {
    res.time_ms = thread_cpu_ms() - t0;
    if (solver_ptr) res.mpfi_boxes = solver_ptr->mpfi_boxes;
    if (solver_ptr) res.circle_pairs = static_cast<int>(solver_ptr->circle_pairs());
    return res;
  };
  std::string why;
  std::vector<Element> elems[2];
  elems[0] = profile_elements(a, &why);
  if (elems[0].empty()) {
    res.reason = "solid a: " + why;
    return finish();
  }
  elems[1] = profile_elements(b, &why);
  if (elems[1].empty()) {
    res.reason = "solid b: " + why;
    return finish();
  }
  const Pose poses[2] = {pose_a, pose_b};
  res.scale = std::max({width_size(a), width_size(b), (pose_a.translation - pose_b.translation).norm()});
  const double tol = options.absolute_width > 0 ? options.absolute_width : options.relative_width * res.scale;
  Solver solver(elems, poses, exactly_coaxial(pose_a, pose_b));
  solver_ptr = &solver;
  solver.make_jobs();
  // Below this distance a double bound's rounding (~1e-13 scale^2 in a squared
  // distance, ~1e-13 scale^2 / d after the square root) could exceed tol / 10.
  const double d_mpfi = 1e-12 * res.scale * res.scale / tol;
  solver.set_mpfi_below(d_mpfi * d_mpfi, options.double_bounds);

  auto report_overlap = [&](const Vec3& p) {
    res.certified = true;
    res.overlap = true;
    res.lower = res.upper = 0.0;
    res.width_reached = true;
    res.point_a = res.point_b = p;
    return finish();
  };

  // The CPU budget's shares: the screen below stops at a quarter of it, the
  // tube pass at three quarters (both only save work later), so that the
  // boxes every job needs for a proven bracket fit in the rest. Two
  // degree-32 B-splines of 168 spans each spent 12 s in the screen (every
  // point tested against every element of the other side) and 18 s in the
  // tube pass, then 7 s on the boxes: 37 s for a 30 s budget.
  auto past = [&](double share) {
    return options.max_cpu_s > 0 && thread_cpu_ms() - t0 > share * 1e3 * options.max_cpu_s;
  };
  // Screen: a sampled surface point strictly inside the other solid proves a shared point.
  const int n_psi = solver.coaxial() ? 1 : 8;
  for (int side = 0; side < 2; ++side)
    for (std::size_t e = 0; e < elems[side].size() && !past(0.25); ++e)
      for (double u : {0.5, 0.2, 0.8})
        for (int k = 0; k < n_psi; ++k) {
          Vec3 p;
          if (solver.test_point(side, static_cast<int>(e), u, 2.0 * (k + 0.5) / n_psi, &p) == Inside::inside)
            return report_overlap(p);
        }

  // Branch and bound over the surfaces.
  std::priority_queue<Box, std::vector<Box>, std::greater<Box>> queue;
  std::vector<Box> stuck;  // boxes that cannot be halved further: their lower bounds stay
  double stuck_min = kInf;
  double ub = kInf;
  Box best;
  std::vector<double> floor_sq;  // proven lower bound of each job (tube pairs), squared
  auto consider = [&](Box bx) {
    const Eval ev = solver.evaluate(bx);
    ++res.boxes;
    bx.lower = std::max({ev.lower, floor_sq[bx.job], bx.lower});  // a part is no nearer than its whole
    bx.split = ev.split;
    if (ev.upper < ub) {
      ub = ev.upper;
      best = bx;
    }
    if (bx.lower >= ub) return;  // cannot hold a smaller value than a genuine pair already has
    if (ev.split < 0) {
      stuck.push_back(bx);
      stuck_min = std::min(stuck_min, bx.lower);
    } else
      queue.push(bx);
  };
  // Tube pairs first: settled ones never enter the search, and their genuine
  // pairs give the search an upper bound to prune with from the start.
  floor_sq.assign(solver.jobs.size(), 0.0);
  std::vector<char> settled(solver.jobs.size(), 0);
  std::vector<double> tube_lower(solver.jobs.size(), -1.0);
  // The CPU budget and stop requests cover this pass too (each job may certify
  // a circle pair); past either, the remaining jobs get no tube bound, every
  // job still gets its boxes (so the bracket stays proven), and the search
  // below ends at once.
  const char* ended = nullptr;  // the time budget or a stop request, when either ended the work
  auto out_of_time = [&] {
    if (past(1.0)) ended = "CPU time budget";
    if (options.stop && options.stop()) ended = "stop request";
    return ended != nullptr;
  };
  for (std::size_t j = 0; j < solver.jobs.size() && options.use_structure; ++j) {
    if (j % 16 == 15 && (out_of_time() || past(0.75))) break;
    const Solver::Tube t = solver.tube_bound(static_cast<int>(j), tol);
    if (!t.ok) continue;
    tube_lower[j] = t.lower;
    floor_sq[j] = sq_lo<Ia>(t.lower);
    if (t.upper_sq < ub) {
      ub = t.upper_sq;
      best = t.box;
    }
  }
  double settled_min = kInf;  // the least floor of the settled jobs, squared
  for (std::size_t j = 0; j < solver.jobs.size(); ++j)
    if (tube_lower[j] >= 0 && round_up_sqrt(ub) - tube_lower[j] <= 0.25 * tol) {
      settled[j] = 1;  // no pair of this job is nearer than the bracket's lower end
      settled_min = std::min(settled_min, floor_sq[j]);
      ++res.closed_form_pairs;
    }
  res.element_pairs = static_cast<int>(solver.jobs.size());
  res.searched_pairs = res.element_pairs - res.closed_form_pairs;
  // (Two boxes a job past the budget: the fewest that keep off the seam.)
  const int n_s = solver.coaxial() ? 1 : out_of_time() ? 2 : 4;
  for (std::size_t j = 0; j < solver.jobs.size(); ++j)
    for (int k = 0; k < n_s && !settled[j]; ++k) {
      Box bx;
      bx.job = static_cast<int>(j);
      bx.lo[0] = 0.0;
      bx.hi[0] = 1.0;
      bx.lo[1] = solver.coaxial() ? 0.0 : 2.0 * k / n_s;  // n_s even: no box straddles the charts' seam s = 1
      bx.hi[1] = solver.coaxial() ? 0.0 : 2.0 * (k + 1) / n_s;
      bx.lo[2] = 0.0;
      bx.hi[2] = solver.jobs[j].three_d ? 1.0 : 0.0;
      consider(bx);
    }
  auto min_lower = [&]() {
    double m = std::min({ub, stuck_min, settled_min});
    if (!queue.empty()) m = std::min(m, queue.top().lower);
    return m;
  };
  // A point strictly inside the other solid near the best pair, on its
  // parametrised side: steps of 1e-2 down to 1e-6 in both parameters.
  // (Crossing surfaces keep the lower bound at 0 along a curve; a step off
  // the crossing goes in.)
  auto inside_near_best = [&](Vec3* p) {
    const Job& job = solver.jobs[best.job];
    const double uc = 0.5 * (best.lo[0] + best.hi[0]), sc = 0.5 * (best.lo[1] + best.hi[1]);
    for (double d : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6})
      for (int du = -1; du <= 1; ++du)
        for (int ds = -1; ds <= 1; ++ds) {
          const double u = std::clamp(uc + du * d, 0.0, 1.0), s = std::clamp(sc + ds * d, 0.0, 2.0);
          if (solver.test_point(job.s_side, job.s_elem, u, s, p) == Inside::inside) return true;
        }
    return false;
  };
  long pops = 0;
  bool budget_hit = false;
  const auto interval = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(options.progress_interval_s));
  auto next_progress = wall0 + interval;
  while (!queue.empty() && !ended) {
    const Box top = queue.top();
    if (top.lower >= ub) {  // every remaining box is at least as far
      while (!queue.empty()) queue.pop();
      break;
    }
    if (std::sqrt(ub) - std::sqrt(std::min({top.lower, stuck_min, settled_min})) <= 0.5 * tol) break;
    if (res.boxes >= options.max_boxes) {
      budget_hit = true;
      break;
    }
    if (pops % 256 == 255 && out_of_time()) break;
    queue.pop();
    ++pops;
    if (options.progress && pops % 256 == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_progress) {
        next_progress = now + interval;
        ExactProgress pr;
        pr.boxes = res.boxes;
        pr.lower = round_down_sqrt(std::min({top.lower, stuck_min, settled_min}));
        pr.upper = round_up_sqrt(ub);
        pr.target_width = tol;
        pr.seconds = std::chrono::duration<double>(now - wall0).count();
        options.progress(pr);
      }
    }
    // Crossing surfaces keep the lower bound at 0 along a curve: look for a proof
    // of overlap near the best pair now and then.
    if (top.lower <= 0.0 && pops % 512 == 0) {
      Vec3 p;
      if (inside_near_best(&p)) return report_overlap(p);
    }
    const int i = top.split;
    Box l = top, r = top;
    const double m = 0.5 * (top.lo[i] + top.hi[i]);
    l.hi[i] = m;
    r.lo[i] = m;
    consider(l);
    consider(r);
  }
  const double lsq = min_lower();
  res.certified = true;
  res.lower = round_down_sqrt(lsq);
  res.upper = round_up_sqrt(ub);
  Vec3 w[2];
  solver.witness(best, w);
  const int s_side = solver.jobs[best.job].s_side;
  res.point_a = w[s_side];
  res.point_b = w[1 - s_side];
  if (budget_hit) res.reason = "box budget reached before the width target";
  if (ended) res.reason = std::string(ended) + " reached before the width target";
  if (!stuck.empty() && res.reason.empty()) res.reason = "boxes at rounding size remain";

  // Surfaces that cross at a sharp edge of a profile (a joint of two
  // elements, a table's rim) put every point near the closest pair on the
  // crossing, where no point is strictly inside: the joints of each side's
  // elements on the meridian of that side's witness point, and a little
  // around it, are tested too.
  if (lsq <= 0.0) {
    // Around the best pair once more (a search that ends early never reached the periodic look).
    if (Vec3 p; ub < kInf && inside_near_best(&p)) return report_overlap(p);
    for (int side = 0; side < 2; ++side) {
      const Vec3 l = poses[side].rotation().transpose() * (w[side] - poses[side].translation);
      const double s0 = s_of(std::atan2(l.y(), l.x()));
      for (std::size_t e = 0; e < elems[side].size(); ++e)
        for (double u : {0.0, 1.0})
          for (double ds : {0.0, 1e-6, -1e-6, 1e-4, -1e-4, 1e-2, -1e-2}) {
            Vec3 p;
            if (solver.test_point(side, static_cast<int>(e), u, std::clamp(s0 + ds, 0.0, 2.0), &p) == Inside::inside)
              return report_overlap(p);
          }
    }
  }

  if (res.lower > 0.0) {
    // The surfaces are disjoint: a boundary point of each outside the other solid
    // rules out containment (both boundaries are connected).
    for (int side = 0; side < 2; ++side) {
      Inside decided = Inside::unknown;
      Vec3 p;
      for (std::size_t e = 0; e < elems[side].size() && decided == Inside::unknown; ++e)
        for (double s : {0.0, 0.6283185307179586, 1.4})
          if ((decided = solver.test_point(side, static_cast<int>(e), 0.5, s, &p)) != Inside::unknown) break;
      if (decided == Inside::inside) return report_overlap(p);  // containment (the screen normally finds it first)
      if (decided == Inside::unknown) {
        res.lower = 0.0;
        res.reason = "containment not decided (boundary points too close to the other surface)";
      }
    }
  } else if (res.reason.empty() && res.upper > tol) {
    res.reason = "surfaces touch or cross; overlap not proven";
  }
  res.width_reached = res.upper - res.lower <= tol;
  if (!res.width_reached && res.reason.empty()) res.reason = "width target not reached";
  return finish();
}

}  // namespace revdist
