// Real roots of the small polynomials of the circle kernel (degree <= 8 in
// t = tan(θ/2)): the binormal polynomial of Appendix A and the fallback quartic.
// Off the hot path; chosen for robustness over speed.
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

int poly_roots_in(const double* a_in, int n, double lo, double hi, double tol_abs, double* roots) {
  // Drop leading coefficients that are exactly zero (a degree drop = roots at infinity).
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
  if (n >= 2) nc = poly_roots_in(da, n - 1, lo, hi, 0.0, crit);
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

int trig_poly_roots(const double* a, int n, double* th) {
  double mag = 0;
  for (int i = 0; i <= n; ++i) mag += std::abs(a[i]);
  const double tol = 64 * n * kEps * mag;  // Horner on |t| <= 1.25: error <= 2nε·1.25^n·Σ|a_i|, with margin
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

}  // namespace revdist::circle_detail
