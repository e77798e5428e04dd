// Bernstein-basis arithmetic with error bounds and the sign-change isolation
// of the spiral split (paper section 4.1, NOTES section 4).
//
// Error model: u = 2^-53 is the unit roundoff; a sum, difference or product
// of doubles is exact times (1 + d), |d| <= u. Every bound below is the
// first-order propagation of the operands' bounds plus a generous multiple of
// u times the magnitudes involved, so it holds with room for the second-order
// terms (the multiples are at least twice what the operation count needs).
#include "fast/bernstein.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace revdist {

namespace {

constexpr double kU = DBL_EPSILON / 2;
constexpr int kMaxBinomialRow = 256;  // rational degree-32 spans need degree 8*32 - 6 = 250

// Rows 0..kMaxBinomialRow of Pascal's triangle, built once. Exact up to 2^53;
// beyond, row n carries a relative error below n u (one rounding per row),
// which the product's bound allows for.
const double* binomial_row(int n) {
  static const std::vector<double> table = [] {
    std::vector<double> t;
    t.reserve((kMaxBinomialRow + 1) * (kMaxBinomialRow + 2) / 2);
    for (int r = 0; r <= kMaxBinomialRow; ++r) {
      const std::size_t start = t.size();
      for (int k = 0; k <= r; ++k) {
        if (k == 0 || k == r) {
          t.push_back(1.0);
        } else {
          const std::size_t prev = start - r;  // row r - 1 starts r entries before row r
          t.push_back(t[prev + k - 1] + t[prev + k]);
        }
      }
    }
    return t;
  }();
  return table.data() + static_cast<std::size_t>(n) * (n + 1) / 2;
}

// Sign of a coefficient with error bound e: 0 when the bound does not decide it.
int proven_sign(double b, double e) { return b > e ? 1 : (b < -e ? -1 : 0); }

// The largest number of sign variations any choice of signs (or zeros) for the
// undecided coefficients can give: a bound on the true polygon's variations.
int max_variations(const double* b, const double* e, int n) {
  constexpr int kNone = -1000000;
  int pos = kNone, neg = kNone;  // best count with the last non-zero sign + / -
  bool all_zero_so_far = true;   // the empty prefix (every coefficient so far read as 0)
  for (int k = 0; k <= n; ++k) {
    const int s = proven_sign(b[k], e[k]);
    const int start = all_zero_so_far ? 0 : kNone;
    if (s > 0) {
      pos = std::max({pos, neg + 1, start});
      neg = kNone;
      all_zero_so_far = false;
    } else if (s < 0) {
      neg = std::max({neg, pos + 1, start});
      pos = kNone;
      all_zero_so_far = false;
    } else {
      const int p2 = std::max({pos, neg + 1, start}), n2 = std::max({neg, pos + 1, start});
      pos = p2;
      neg = n2;
    }
  }
  return std::max({pos, neg, 0});
}

// p and p' at s in [0, 1] from the coefficients b[0..n] (de Casteljau).
void de_casteljau_eval(const double* b, int n, double s, double* scratch, double* value, double* slope) {
  std::copy(b, b + n + 1, scratch);
  for (int r = n; r >= 1; --r) {
    if (r == 1) *slope = n * (scratch[1] - scratch[0]);
    for (int k = 0; k < r; ++k) scratch[k] = (1 - s) * scratch[k] + s * scratch[k + 1];
  }
  if (n == 0) *slope = 0.0;
  *value = scratch[0];
}

// The simple root of a box's polynomial b (signs sign(b[0]) = -sign(b[n]),
// both proven): Newton kept inside a bracket that bisection shrinks. It runs
// on the coefficients as computed: their root is as good a point as any in
// the uncertainty the error bound leaves, and usually far better than that
// bound's worst case.
double refine_root(const double* b, int n, double* scratch) {
  const int s0 = b[0] > 0 ? 1 : -1;
  double lo = 0.0, hi = 1.0, x = 0.5;
  for (int it = 0; it < 200; ++it) {
    double f = 0.0, d = 0.0;
    de_casteljau_eval(b, n, x, scratch, &f, &d);
    if (f == 0) break;
    if ((f > 0 ? 1 : -1) == s0) lo = x; else hi = x;
    if (hi - lo <= 4 * DBL_EPSILON) break;
    double xn = d != 0 ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    if (std::abs(xn - x) <= 2 * DBL_EPSILON * x) {
      x = xn;
      break;  // Newton's step is below the resolution of x
    }
    x = xn;
  }
  return x;
}

}  // namespace

BernsteinPoly bernstein_mul(const BernsteinPoly& p, const BernsteinPoly& q) {
  const int m = p.degree(), n = q.degree();
  BernsteinPoly r;
  r.b.assign(m + n + 1, 0.0);
  r.err.assign(m + n + 1, 0.0);
  std::vector<double> mag(m + n + 1, 0.0);
  const double* cm = binomial_row(m);
  const double* cn = binomial_row(n);
  const double* cmn = binomial_row(m + n);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      const double w = cm[i] * cn[j];
      r.b[i + j] += w * p.b[i] * q.b[j];
      mag[i + j] += w * std::abs(p.b[i] * q.b[j]);
      r.err[i + j] += w * (std::abs(p.b[i]) * q.err[j] + p.err[i] * std::abs(q.b[j]) + p.err[i] * q.err[j]);
    }
  // The weights C(m,i) C(n,j) / C(m+n,k) of one k sum to 1 (Vandermonde):
  // each coefficient is a convex combination of products, rounded in
  // ~(m + n + 4) operations, binomials included.
  const double g = (4.0 * (m + n) + 8.0) * kU;
  for (int k = 0; k <= m + n; ++k) {
    r.b[k] /= cmn[k];
    r.err[k] = (r.err[k] + g * mag[k]) / cmn[k] * (1 + g);
  }
  return r;
}

BernsteinPoly bernstein_derivative(const BernsteinPoly& p) {
  const int n = p.degree();
  BernsteinPoly r;
  if (n <= 0) {
    r.b.assign(1, 0.0);
    r.err.assign(1, 0.0);
    return r;
  }
  r.b.resize(n);
  r.err.resize(n);
  for (int k = 0; k < n; ++k) {
    r.b[k] = n * (p.b[k + 1] - p.b[k]);
    r.err[k] = n * (p.err[k + 1] + p.err[k]) + 3.0 * n * kU * (std::abs(p.b[k + 1]) + std::abs(p.b[k]));
  }
  return r;
}

BernsteinPoly bernstein_axpy(double a, const BernsteinPoly& p, double c, const BernsteinPoly& q) {
  BernsteinPoly r;
  r.b.resize(p.b.size());
  r.err.resize(p.b.size());
  const double aa = std::abs(a), ac = std::abs(c);
  for (std::size_t k = 0; k < p.b.size(); ++k) {
    r.b[k] = a * p.b[k] + c * q.b[k];
    r.err[k] = aa * p.err[k] + ac * q.err[k] + 4.0 * kU * (aa * std::abs(p.b[k]) + ac * std::abs(q.b[k]));
  }
  return r;
}

bool bernstein_sign_items(const BernsteinPoly& p, double tiny, int max_boxes, std::vector<SignItem>& out) {
  out.clear();
  const int n = p.degree();
  const std::size_t block = 2 * static_cast<std::size_t>(n + 1);  // coefficients, then their bounds
  // Depth-first, left part first, so items come out in increasing t; the
  // blocks of coefficients are a stack too (the top box's block is the last).
  // Halving takes n levels of midpoints: each is an average of two values
  // (so of their bounds) and one rounding of at most u times the result.
  struct Box {
    double t0, t1;
    std::size_t at;  // offset of its block in `store`
  };
  thread_local std::vector<double> store;
  thread_local std::vector<Box> stack;
  thread_local std::vector<double> scratch;
  store.assign(p.b.begin(), p.b.end());
  store.insert(store.end(), p.err.begin(), p.err.end());
  stack.clear();
  stack.push_back({0.0, 1.0, 0});
  scratch.resize(block);
  int boxes = 0;
  bool complete = true;
  auto emit = [&](double t0, double t1, signed char l, signed char r, double root) {
    // Adjacent unknown parts merge: the caller reads runs, not boxes.
    if (l == 0 && r == 0 && !out.empty() && out.back().left == 0 && out.back().right == 0 &&
        out.back().t1 == t0) {
      out.back().t1 = t1;
      return;
    }
    SignItem it;
    it.t0 = t0;
    it.t1 = t1;
    it.left = l;
    it.right = r;
    it.root = root;
    out.push_back(it);
  };
  while (!stack.empty()) {
    const Box box = stack.back();
    stack.pop_back();
    const double* b = store.data() + box.at;
    const double* e = b + n + 1;
    const double w = box.t1 - box.t0;
    int npos = 0, nneg = 0;
    for (int k = 0; k <= n; ++k) {
      const int s = proven_sign(b[k], e[k]);
      npos += s > 0;
      nneg += s < 0;
    }
    if (npos == n + 1 || nneg == n + 1) {
      const signed char s = npos ? 1 : -1;
      emit(box.t0, box.t1, s, s, 0.0);
    } else if (npos + nneg == 0) {
      emit(box.t0, box.t1, 0, 0, 0.0);  // within rounding of 0 throughout
    } else if (max_variations(b, e, n) == 1 && proven_sign(b[0], e[0]) * proven_sign(b[n], e[n]) < 0) {
      // At most one variation and opposite proven ends: exactly one root, simple.
      const double x = refine_root(b, n, scratch.data());
      const signed char l = b[0] > 0 ? 1 : -1;
      emit(box.t0, box.t1, l, static_cast<signed char>(-l), box.t0 + w * x);
    } else if (w <= tiny || !complete) {
      emit(box.t0, box.t1, 0, 0, 0.0);
    } else if (++boxes > max_boxes) {
      complete = false;
      emit(box.t0, box.t1, 0, 0, 0.0);
    } else {
      // de Casteljau halving; the children's blocks replace the parent's.
      std::copy(b, b + block, scratch.begin());
      double* sb = scratch.data();
      double* se = sb + n + 1;
      store.resize(box.at + 2 * block);
      double* R = store.data() + box.at;
      double* L = R + block;
      for (int r = 0; r <= n; ++r) {
        L[r] = sb[0];
        L[n + 1 + r] = se[0];
        R[n - r] = sb[n - r];
        R[n + 1 + n - r] = se[n - r];
        for (int k = 0; k < n - r; ++k) {
          sb[k] = 0.5 * (sb[k] + sb[k + 1]);
          se[k] = 0.5 * (se[k] + se[k + 1]) + 2.0 * kU * std::abs(sb[k]);
        }
      }
      const double tm = box.t0 + 0.5 * w;
      stack.push_back({tm, box.t1, box.at});
      stack.push_back({box.t0, tm, box.at + block});
      continue;
    }
    store.resize(box.at);  // the top box's block is always the last one
  }
  return complete;
}

}  // namespace revdist
