// Tests of the Bernstein-basis isolation (fast/bernstein.h): polynomials with
// known roots (simple, double, at the ends of [0, 1], pairs closer than any
// sampling), the zero polynomial, and the error bounds of the arithmetic
// against a long double reference on random inputs.
#include "fast/bernstein.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>

#include "tests/fast/biarc_test_util.h"

namespace revdist {
namespace {

using testing_util::test_seed;

// t - r in the degree-1 Bernstein basis (exact for dyadic r).
BernsteinPoly linear(double r) { return BernsteinPoly{{-r, 1.0 - r}, {0.0, 0.0}}; }

BernsteinPoly product_of_roots(std::initializer_list<double> roots) {
  BernsteinPoly p{{1.0}, {0.0}};
  for (double r : roots) p = bernstein_mul(p, linear(r));
  return p;
}

// The parameters where the proven sign changes, read as the spiral split
// reads the items: a root item, or a proven sign differing from the last one
// (then the middle of what lies between).
std::vector<double> sign_changes(const std::vector<SignItem>& items) {
  std::vector<double> out;
  int last = 0;
  double gap_lo = 0.0;
  for (const SignItem& it : items) {
    if (it.left == 0) continue;
    if (last != 0 && it.left != last) out.push_back(0.5 * (gap_lo + it.t0));
    last = it.left;
    if (it.right != it.left) {
      out.push_back(it.root);
      last = it.right;
    }
    gap_lo = it.t1;
  }
  return out;
}

std::vector<double> isolate(const BernsteinPoly& p, bool* complete = nullptr) {
  std::vector<SignItem> items;
  const bool ok = bernstein_sign_items(p, 0x1p-44, 1 << 14, items);
  if (complete) *complete = ok;
  // The items tile [0, 1] in order.
  EXPECT_FALSE(items.empty());
  if (!items.empty()) {
    EXPECT_EQ(items.front().t0, 0.0);
    EXPECT_EQ(items.back().t1, 1.0);
  }
  for (std::size_t i = 1; i < items.size(); ++i) EXPECT_EQ(items[i].t0, items[i - 1].t1);
  return sign_changes(items);
}

// Root positions: the polynomials below have |p'| >= ~1e-12 at their roots and
// coefficients of size ~1, so rounding moves a root by at most ~1e4 ulp of 1
// in the worst (near-tangent) case; simple well-separated roots are within a
// few ulp.
constexpr double kRootTol = 1e4 * DBL_EPSILON;

TEST(Bernstein, SimpleRootsFound) {
  // Dyadic roots: the linear factors, hence the polynomial, are exact.
  const auto ch = isolate(product_of_roots({0.125, 0.3125, 0.71875, 0.90625}));
  ASSERT_EQ(ch.size(), 4u);
  const double want[4] = {0.125, 0.3125, 0.71875, 0.90625};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(ch[i], want[i], 8 * DBL_EPSILON) << i;
}

TEST(Bernstein, DoubleRootIsNoSignChange) {
  // (t - 0.3)^2 (t - 0.7): touches 0 at 0.3, crosses at 0.7.
  const auto ch = isolate(product_of_roots({0.3, 0.3, 0.7}));
  ASSERT_EQ(ch.size(), 1u);
  EXPECT_NEAR(ch[0], 0.7, 8 * DBL_EPSILON);
  // A triple root is a sign change.
  const auto ch3 = isolate(product_of_roots({0.4, 0.4, 0.4}));
  ASSERT_EQ(ch3.size(), 1u);
  EXPECT_NEAR(ch3[0], 0.4, 1e-4);  // a cube flattens: |p| <= 1e-16 within ~5e-6 of the root
}

TEST(Bernstein, RootsAtTheEndsAreNotInteriorChanges) {
  const auto ch = isolate(product_of_roots({0.0, 0.5, 1.0}));
  ASSERT_EQ(ch.size(), 1u);
  EXPECT_NEAR(ch[0], 0.5, 8 * DBL_EPSILON);
}

TEST(Bernstein, RootAtAHalvingPoint) {
  // 0.5 and 0.25 are where de Casteljau halves: the boxes beside them have a
  // coefficient that is 0; the change is still found, at the halving point.
  const auto ch = isolate(product_of_roots({0.25, 0.5}));
  ASSERT_EQ(ch.size(), 2u);
  EXPECT_NEAR(ch[0], 0.25, kRootTol);
  EXPECT_NEAR(ch[1], 0.5, kRootTol);
}

TEST(Bernstein, NearTangentPairBothFound) {
  // (t - m)^2 - d^2 with d ~ 1e-6: two sign changes 2e-6 apart, far inside
  // any cell a sampling would use; the polynomial dips only to -1e-12.
  const double m = 0.6180339887, d = 0x1p-20;  // m^2 - d^2 rounds: the roots move by ~u m^2 / (2d) ~ 1e-11
  BernsteinPoly sq = bernstein_mul(linear(m), linear(m));
  const BernsteinPoly dd{{d * d, d * d, d * d}, {0.0, 0.0, 0.0}};
  const auto ch = isolate(bernstein_axpy(1, sq, -1, dd));
  ASSERT_EQ(ch.size(), 2u);
  EXPECT_NEAR(ch[0], m - d, 1e-10);
  EXPECT_NEAR(ch[1], m + d, 1e-10);
}

TEST(Bernstein, ZeroPolynomialIsOneUnknownPart) {
  std::vector<SignItem> items;
  EXPECT_TRUE(bernstein_sign_items(BernsteinPoly{{0, 0, 0, 0}, {0, 0, 0, 0}}, 0x1p-44, 16, items));
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].left, 0);
}

TEST(Bernstein, WorkBoundIsReported) {
  // A cluster of four roots within 1e-9: halving to 2^-44 takes more than 8 boxes.
  bool complete = false;
  const auto ch = isolate(product_of_roots({0.5, 0.5 + 1e-9, 0.5 + 2e-9, 0.5 + 3e-9}), &complete);
  EXPECT_TRUE(complete);
  // Within 3e-9 the polynomial is below its rounding (~1e-16): the cluster is
  // undecided, and the same sign on both sides means an even count of changes.
  EXPECT_EQ(ch.size() % 2, 0u);
  std::vector<SignItem> items;
  EXPECT_FALSE(bernstein_sign_items(product_of_roots({0.5, 0.5 + 1e-9, 0.5 + 2e-9, 0.5 + 3e-9}), 0x1p-44, 8, items));
}

// Random polynomials through mul, derivative and axpy, against the same
// operations in long double (64-bit mantissa: 2^11 times finer, so its own
// error is negligible next to the bounds): every coefficient within its err.
// Then every proven sign claim is checked at points of its part.
TEST(Bernstein, ErrorBoundsHoldAndSignsAreRight) {
  const std::uint64_t seed = test_seed(7);
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  using LPoly = std::vector<long double>;
  auto binom = [](int n, int k) {
    long double r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
  };
  auto lmul = [&](const LPoly& a, const LPoly& b) {
    const int m = static_cast<int>(a.size()) - 1, n = static_cast<int>(b.size()) - 1;
    LPoly r(m + n + 1, 0);
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= n; ++j) r[i + j] += binom(m, i) * binom(n, j) / binom(m + n, i + j) * a[i] * b[j];
    return r;
  };
  auto lder = [](const LPoly& a) {
    const int n = static_cast<int>(a.size()) - 1;
    LPoly r(n);
    for (int k = 0; k < n; ++k) r[k] = n * (a[k + 1] - a[k]);
    return r;
  };
  auto leval = [](LPoly b, long double t) {
    for (std::size_t r = b.size(); r-- > 1;)
      for (std::size_t k = 0; k < r; ++k) b[k] = (1 - t) * b[k] + t * b[k + 1];
    return b[0];
  };
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const int da = 1 + trial % 5, db = 2 + trial % 4;
    BernsteinPoly a, b;
    LPoly la, lb;
    for (int i = 0; i <= da; ++i) a.b.push_back(coef(rng)), a.err.push_back(0.0), la.push_back(a.b.back());
    for (int i = 0; i <= db; ++i) b.b.push_back(coef(rng)), b.err.push_back(0.0), lb.push_back(b.b.back());
    // Products of derivatives: the shape of the split's numerators.
    const BernsteinPoly ab = bernstein_mul(bernstein_derivative(a), b);
    const BernsteinPoly ab2 = bernstein_mul(a, bernstein_derivative(bernstein_derivative(b)));
    const LPoly lab = lmul(lder(la), lb), lab2 = lmul(la, lder(lder(lb)));
    ASSERT_EQ(ab.b.size(), ab2.b.size() + 1);
    const BernsteinPoly q = bernstein_mul(ab, ab2);
    const LPoly lq = lmul(lab, lab2);
    ASSERT_EQ(q.b.size(), lq.size());
    for (std::size_t k = 0; k < q.b.size(); ++k)
      EXPECT_LE(std::abs(static_cast<long double>(q.b[k]) - lq[k]), static_cast<long double>(q.err[k])) << k;
    // The homogeneous-derivative shape a'b - a b' (equal degrees), through axpy.
    const BernsteinPoly h = bernstein_axpy(1, ab, -1, bernstein_mul(a, bernstein_derivative(b)));
    const LPoly lab1 = lmul(la, lder(lb));
    for (std::size_t k = 0; k < h.b.size(); ++k)
      EXPECT_LE(std::abs(static_cast<long double>(h.b[k]) - (lab[k] - lab1[k])), static_cast<long double>(h.err[k])) << k;
    std::vector<SignItem> items;
    bernstein_sign_items(q, 0x1p-44, 1 << 14, items);
    for (const SignItem& it : items) {
      if (it.left == 0) continue;
      for (int i = 0; i <= 8; ++i) {
        const long double t = it.t0 + (it.t1 - it.t0) * i / 8.0L;
        const long double v = leval(lq, t);
        if (it.left == it.right) {
          EXPECT_TRUE(it.left > 0 ? v >= 0 : v <= 0) << "proven sign " << int(it.left) << " at " << (double)t;
        } else if (i == 0 || i == 8) {
          const int want = i == 0 ? it.left : it.right;
          EXPECT_TRUE(want > 0 ? v >= 0 : v <= 0) << "root part end sign at " << (double)t;
        }
      }
    }
  }
}

}  // namespace
}  // namespace revdist
