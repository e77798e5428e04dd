// Real roots of the small polynomials of the circle kernel (degree <= 8 in
// t = tan(θ/2)): the binormal polynomial of Appendix A and the fallback quartic.
// On the hot path of the patch kernel: isolation in the Bernstein basis, with
// the slower derivative recursion as the fallback.
#include <algorithm>
#include <cmath>

#include "fast/circle_internal.h"

namespace revdist::circle_detail {

namespace {

// The root of a polynomial that is monotone on [lo, hi] with p(lo), p(hi) of
// opposite signs: bisection, accelerated by Newton steps that stay inside.
double monotone_root(const double* a, const double* da, int n, double lo, double hi, double plo) {
  double t = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && hi - lo > 0; ++it) {
    const double p = poly_eval(a, n, t);
    if (p == 0) return t;
    if ((p < 0) == (plo < 0)) lo = t; else hi = t;
    const double d = poly_eval(da, n - 1, t);
    double tn = d != 0 ? t - p / d : 0.5 * (lo + hi);
    if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
    if (tn == t) break;
    // Newton has converged when its step falls below the bracket's resolution.
    if (std::abs(tn - t) <= 4 * kEps * std::max(1.0, std::abs(t))) { t = tn; break; }
    t = tn;
  }
  return t;
}

}  // namespace

// Isolation in the Bernstein basis on [lo, hi] (Descartes' rule of signs on
// the control polygon, de Casteljau halving), each isolated simple root
// refined by Newton safeguarded by bisection. Roots of even multiplicity show
// as intervals whose coefficients come within tol_abs of zero without a sign
// change: they are halved down to a width of kTiny of [lo, hi] and reported
// where |p| <= tol_abs, as the derivative-recursion method reports them at
// critical points. Returns -1 when the work budget runs out or a flat stretch
// (see kFlatBoxes) is found (the caller falls back to the derivative recursion).
static int bernstein_roots(const double* a, int n, double lo, double hi, double tol_abs, double* roots) {
  // Boxes narrower than this (relative to [lo, hi]) are not halved further: a
  // multiple root or a cluster is reported at the box's middle, to be polished
  // by the caller on its unsquared equation; roots closer than two such boxes
  // are one.
  constexpr double kTiny = 1e-8;
  constexpr int kFlatBoxes = 32;
  const double w = hi - lo;
  // q(s) = p(lo + w s): Taylor shift by lo, then scale by w^i.
  double c[9];
  for (int i = 0; i <= n; ++i) c[i] = a[i];
  for (int i = 0; i < n; ++i)
    for (int j = n - 1; j >= i; --j) c[j] += lo * c[j + 1];
  double wp = 1;
  for (int i = 0; i <= n; ++i, wp *= w) c[i] *= wp;
  double dc[8];
  for (int i = 1; i <= n; ++i) dc[i - 1] = i * c[i];
  // The shift, the scaling and the change of basis round: the coefficients
  // bound p only to within a few ulps of the shifted coefficients' size, so
  // "stays away from 0" needs that much more than tol_abs.
  double csum = 0;
  for (int i = 0; i <= n; ++i) csum += std::abs(c[i]);
  const double tol_b = tol_abs + 32 * (n + 1) * kEps * csum;
  // Power to Bernstein: b_k = sum_{i <= k} C(k, i) / C(n, i) c_i.
  // ratio[n][k][i] = C(k, i) / C(n, i), the same quotients computed once.
  struct Ratios {
    double r[9][9][9] = {};
    Ratios() {
      const double binom[9][9] = {
          {1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}, {1, 5, 10, 10, 5, 1}, {1, 6, 15, 20, 15, 6, 1},
          {1, 7, 21, 35, 35, 21, 7, 1}, {1, 8, 28, 56, 70, 56, 28, 8, 1}};
      for (int m = 0; m <= 8; ++m)
        for (int k = 0; k <= m; ++k)
          for (int i = 0; i <= k; ++i) r[m][k][i] = binom[k][i] / binom[m][i];
    }
  };
  static const Ratios ratios;
  const auto& ratio = ratios.r[n];
  struct Box {
    double b[9];
    double s0, s1;
  };
  Box stack[128];
  int top = 0;
  Box& first = stack[top++];
  for (int k = 0; k <= n; ++k) {
    double v = 0;
    for (int i = 0; i <= k; ++i) v += ratio[k][i] * c[i];
    first.b[k] = v;
  }
  first.s0 = 0;
  first.s1 = 1;
  int nr = 0, work = 0, flat = 0;
  auto q = [&](double x) { return poly_eval(c, n, x); };
  while (top > 0) {
    if (++work > 400 || nr > 16) return -1;
    const Box box = stack[--top];
    const double* b = box.b;
    if (b[0] == 0) roots[nr++] = lo + w * box.s0;
    int v = 0, last = 0;
    double mn = std::abs(b[0]);
    for (int k = 0; k <= n; ++k) {
      mn = std::min(mn, std::abs(b[k]));
      if (b[k] == 0) continue;
      const int sg = b[k] > 0 ? 1 : -1;
      if (last != 0 && sg != last) ++v;
      last = sg;
    }
    const double width = box.s1 - box.s0;
    const bool tiny = width < kTiny;
    if (v == 0) {
      if (mn > tol_b) continue;  // no root, and p stays away from 0 here
      // A flat stretch: p within the coefficients' rounding (tol_b, ~1e-9
      // after the shift to [-1.25, 1.25]) of 0 over many boxes, around a
      // near-double root or a close pair that only the evaluation in the
      // original variable resolves. Halving it down to kTiny used up the
      // 400-box budget before the fallback (on 565 of the motion probe's 600
      // queries): fall back after kFlatBoxes such boxes instead.
      if (++flat > kFlatBoxes) return -1;
      if (tiny) {
        const double m = lo + w * 0.5 * (box.s0 + box.s1);
        if (std::abs(poly_eval(a, n, m)) <= tol_abs) roots[nr++] = m;
        continue;
      }
    } else if (v == 1 && b[0] != 0 && b[n] != 0) {
      // Exactly one simple root inside: Newton safeguarded by the bracket.
      double s0 = box.s0, s1 = box.s1, x = 0.5 * (s0 + s1);
      const bool neg0 = b[0] < 0;
      for (int it = 0; it < 100; ++it) {
        const double f = q(x);
        if (f == 0) break;
        if ((f < 0) == neg0) s0 = x; else s1 = x;
        const double d = poly_eval(dc, n - 1, x);
        double xn = d != 0 ? x - f / d : 0.5 * (s0 + s1);
        if (!(xn > s0 && xn < s1)) xn = 0.5 * (s0 + s1);
        if (std::abs(xn - x) <= 4 * kEps * std::max(1.0, std::abs(x)) || s1 - s0 <= 4 * kEps) {
          x = xn;
          break;
        }
        x = xn;
      }
      roots[nr++] = lo + w * x;
      continue;
    } else if (tiny) {
      roots[nr++] = lo + w * 0.5 * (box.s0 + box.s1);  // a cluster or multiple root
      continue;
    }
    if (top + 2 > 128) return -1;
    // de Casteljau halving.
    Box left, right;
    double t[9];
    for (int k = 0; k <= n; ++k) t[k] = b[k];
    for (int r = 0; r <= n; ++r) {
      left.b[r] = t[0];
      right.b[n - r] = t[n - r];
      for (int k = 0; k < n - r; ++k) t[k] = 0.5 * (t[k] + t[k + 1]);
    }
    const double sm = 0.5 * (box.s0 + box.s1);
    left.s0 = box.s0;
    left.s1 = sm;
    right.s0 = sm;
    right.s1 = box.s1;
    stack[top++] = right;
    stack[top++] = left;
  }
  if (q(1.0) == 0) roots[nr++] = hi;
  std::sort(roots, roots + nr);
  nr = static_cast<int>(
      std::unique(roots, roots + nr, [&](double x, double y) { return std::abs(x - y) <= 2 * kTiny * std::abs(w); }) -
      roots);
  return nr;
}

// Isolation by the derivative recursion: the critical points split [lo, hi]
// into monotone pieces. Slower; the fallback of bernstein_roots.
static int recursive_roots(const double* a_in, int n, double lo, double hi, double tol_abs, double* roots) {
  while (n > 0 && a_in[n] == 0) --n;
  if (n == 0) return 0;
  double a[9], da[8];
  for (int i = 0; i <= n; ++i) a[i] = a_in[i];
  for (int i = 1; i <= n; ++i) da[i - 1] = i * a[i];
  // Critical points split [lo, hi] into pieces where p is monotone: at most one
  // simple root in each. The derivative's own roots come from the same routine.
  double crit[10];
  int nc = 0;
  // A touching zero of p' does not break monotonicity: tolerance 0 there.
  if (n >= 2) nc = recursive_roots(da, n - 1, lo, hi, 0.0, crit);
  double brk[12];
  int nb = 0;
  brk[nb++] = lo;
  for (int i = 0; i < nc; ++i)
    if (crit[i] > lo && crit[i] < hi) brk[nb++] = crit[i];
  brk[nb++] = hi;
  int nr = 0;
  double pv[12];
  for (int i = 0; i < nb; ++i) pv[i] = poly_eval(a, n, brk[i]);
  for (int i = 0; i + 1 < nb; ++i) {
    if (pv[i] == 0) {
      roots[nr++] = brk[i];
      continue;
    }
    if ((pv[i] < 0) != (pv[i + 1] < 0) && pv[i + 1] != 0) {
      roots[nr++] = monotone_root(a, da, n, brk[i], brk[i + 1], pv[i]);
    } else if (i > 0 && std::abs(pv[i]) <= tol_abs) {
      // p touches zero at an interior critical point: an even-multiplicity root.
      roots[nr++] = brk[i];
    }
  }
  if (pv[nb - 1] == 0) roots[nr++] = brk[nb - 1];
  std::sort(roots, roots + nr);
  nr = static_cast<int>(std::unique(roots, roots + nr) - roots);
  return nr;
}

int poly_roots_in(const double* a_in, int n, double lo, double hi, double tol_abs, double* roots) {
  // Drop leading coefficients that are exactly zero (a degree drop = roots at infinity).
  while (n > 0 && a_in[n] == 0) --n;
  if (n == 0) return 0;
  double buf[20];
  const int nb = bernstein_roots(a_in, n, lo, hi, tol_abs, buf);
  if (nb >= 0 && nb <= n) {
    std::copy(buf, buf + nb, roots);
    return nb;
  }
  return recursive_roots(a_in, n, lo, hi, tol_abs, roots);
}

// The touching tolerance on |t| <= 1.25: Horner's own rounding (error <=
// 2nε·1.25^n·Σ|a_i|, with margin) plus the coefficients' error, which moves a
// value or a Bernstein coefficient on [lo, hi] ⊂ [-1.25, 1.25] by at most
// Σ_i err_i·1.25^i (the blossom of t^i there is at most 1.25^i).
static double touch_tol(const double* a, int n, double coeff_err) {
  double mag = 0;
  for (int i = 0; i <= n; ++i) mag += std::abs(a[i]);
  return 64 * n * kEps * mag + coeff_err * std::pow(1.25, n);
}

int trig_poly_roots(const double* a, int n, double* th, double coeff_err) {
  const double tol = touch_tol(a, n, coeff_err);
  double r[10], b[9];
  int k = 0;
  // The charts overlap (|t| <= 1.25) so a touching root on the seam |t| = 1 is an
  // interior extremum of one of them; the overlap's duplicates are merged by callers.
  const double lim = 1.25;
  const int n1 = poly_roots_in(a, n, -lim, lim, tol, r);
  for (int i = 0; i < n1; ++i) th[k++] = 2 * std::atan(r[i]);
  for (int j = 0; j <= n; ++j) b[j] = ((n - j) % 2 ? -1 : 1) * a[n - j];  // p(-1/t') t'^n
  const int n2 = poly_roots_in(b, n, -lim, lim, tol, r);
  for (int i = 0; i < n2; ++i) th[k++] = wrap_pi(2 * std::atan(r[i]) + kPi);
  return k;
}

int trig_poly_roots_window(const double* a, int n, double th0, double th1, double* th, int cap, double coeff_err) {
  const double tol = touch_tol(a, n, coeff_err);
  const double lim = 1.25, th_lim = 2 * std::atan(lim);
  double b[9], r[10];
  for (int j = 0; j <= n; ++j) b[j] = ((n - j) % 2 ? -1 : 1) * a[n - j];  // p(-1/t') t'^n
  int k = 0;
  for (int chart = 0; chart < 2; ++chart) {
    const double centre = chart ? kPi : 0.0;
    // The window in the chart's angle, and its copy one turn down (it may wrap).
    const double s = wrap_pi(th0 - centre), e = s + (th1 - th0);
    for (double shift : {0.0, -2 * kPi}) {
      const double x0 = std::max(s + shift, -th_lim), x1 = std::min(e + shift, th_lim);
      if (!(x0 <= x1)) continue;
      const int m = poly_roots_in(chart ? b : a, n, std::tan(0.5 * x0), std::tan(0.5 * x1), tol, r);
      if (k + m > cap) return -1;
      for (int i = 0; i < m; ++i) th[k++] = wrap_pi(2 * std::atan(r[i]) + centre);
    }
  }
  return k;
}

}  // namespace revdist::circle_detail
