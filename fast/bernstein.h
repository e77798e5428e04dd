// Polynomials on [0, 1] in the Bernstein basis, carried with a bound on the
// rounding error of their coefficients, and a proven isolation of their sign
// changes (Descartes' rule of signs on the control polygon, de Casteljau
// halving, safeguarded Newton): the root finder of the spiral split (paper
// section 4.1, NOTES section 4).
#pragma once
#include <cstdint>
#include <vector>

namespace revdist {

// p(t) = sum_k b[k] C(n, k) t^k (1 - t)^(n - k) on [0, 1], n = b.size() - 1.
// Coefficient k is within err[k] of the coefficient of the exact polynomial it
// stands for (the exact operations on the exact inputs), so |b[k]| > err[k]
// proves its sign. Bounds per coefficient, not one for all: a polynomial whose
// size varies by orders of magnitude over [0, 1] (a span ending near a cusp)
// keeps the relative accuracy of its small end.
struct BernsteinPoly {
  std::vector<double> b;
  std::vector<double> err;  // same size as b
  int degree() const { return static_cast<int>(b.size()) - 1; }
};

// Exact-arithmetic results, rounded, with their error bounds propagated
// (first-order terms plus the rounding of the operation, over-estimated).
BernsteinPoly bernstein_mul(const BernsteinPoly& p, const BernsteinPoly& q);
BernsteinPoly bernstein_derivative(const BernsteinPoly& p);  // d/dt, degree n - 1 (0 for n = 0)
// a p + c q for exactly representable small factors a, c; p and q of one degree.
BernsteinPoly bernstein_axpy(double a, const BernsteinPoly& p, double c, const BernsteinPoly& q);

// One part of [0, 1] as the isolation classified it, in increasing t.
//   proven:  left == right == +-1; p has that sign on all of [t0, t1].
//   root:    left == -right != 0; p has exactly one root in [t0, t1], a simple
//            one, at `root` (to within rounding of p; sign(p(t0)) = left and
//            sign(p(t1)) = right are proven).
//   unknown: left == right == 0; p is within its error bound of 0 on the whole
//            part (then not halved further), or the part is narrower than
//            `tiny` and its coefficients decide nothing (a multiple root, a
//            cluster closer than tiny, a sign change at a halving point).
struct SignItem {
  double t0 = 0.0, t1 = 0.0, root = 0.0;
  signed char left = 0, right = 0;
};

// Covers [0, 1] with sign items, in order, adjacent items sharing end points.
// Work is bounded by `max_boxes` halvings; past it the rest is reported as
// unknown and the function returns false. `tiny` (> 0) is the narrowest part
// that is still halved.
bool bernstein_sign_items(const BernsteinPoly& p, double tiny, int max_boxes, std::vector<SignItem>& out);

}  // namespace revdist
