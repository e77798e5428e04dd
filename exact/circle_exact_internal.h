// Internal to exact/: the rational polynomials of the circle-circle binormal
// condition (paper Appendix A, in square-root-free form) and exact sign
// evaluation at points of circle b. Includes CGAL and GMP: never include this
// from a public header.
#pragma once
#include <CGAL/Algebraic_kernel_d_1.h>
#include <CGAL/Gmpz.h>
#include <gmpxx.h>

#include <array>
#include <functional>
#include <vector>

#include "core/circle3.h"

namespace revdist::exact_detail {

using AK = CGAL::Algebraic_kernel_d_1<CGAL::Gmpz>;
using Poly1Z = AK::Polynomial_1;
using Real1 = AK::Algebraic_real_1;
using Bound = AK::Bound;  // CGAL::Gmpq

using Q3 = std::array<mpq_class, 3>;

// Univariate polynomial with rational coefficients, lowest degree first.
struct UPoly {
  std::vector<mpq_class> c;
  int degree() const;  // -1 for the zero polynomial
  bool is_zero() const { return degree() < 0; }
};
UPoly operator+(const UPoly& p, const UPoly& q);
UPoly operator-(const UPoly& p, const UPoly& q);
UPoly operator*(const UPoly& p, const UPoly& q);
UPoly operator*(const mpq_class& k, const UPoly& p);
mpq_class eval(const UPoly& p, const mpq_class& x);

// Polynomial in (x, y) of total degree <= 4: c[i][j] multiplies x^i y^j.
constexpr int kMaxDeg = 4;
struct BiPoly {
  std::array<std::array<mpq_class, kMaxDeg + 1>, kMaxDeg + 1> c{};
  static BiPoly linear(const mpq_class& c0, const mpq_class& cx, const mpq_class& cy);
  static BiPoly constant(const mpq_class& k) { return linear(k, 0, 0); }
  bool is_zero() const;
};
BiPoly operator+(const BiPoly& p, const BiPoly& q);
BiPoly operator-(const BiPoly& p, const BiPoly& q);
BiPoly operator*(const BiPoly& p, const BiPoly& q);  // asserts total degree <= 4
BiPoly operator*(const mpq_class& k, const BiPoly& p);
using BiVec = std::array<BiPoly, 3>;

// Both circles in rationals, circle b parametrised without square roots:
// P(x, y) = C_b + x·u + y·v, u = e_k × n_b, v = n_b × u, on the ellipse
// alpha·x² + beta·y² = r_b². Everything is relative to C_a (D = C_b − C_a).
struct PairFrame {
  Q3 n;                 // normal of a (not normalised)
  mpq_class n2;         // |n|²
  mpq_class Ra, Ra2;    // radius of a and its square
  Q3 ca;                // centre of a (for witnesses only)
  Q3 nb, D, u, v;       // normal of b, C_b − C_a, ellipse axes
  mpq_class rb, rb2, alpha, beta;
  UPoly s;              // y² on the ellipse as a function of x: (r_b² − alpha x²)/beta

  BiVec delta;          // P(x,y) − C_a
  BiPoly rho2num;       // |n × Δ|² = |n|² ρ²
  BiPoly hnum;          // n·Δ = |n| h (also the plane of a: zero on it)
  BiPoly L;             // (C_b − C_a)·T, T = n_b × (P − C_b)
  BiPoly Qp;            // |n|² L − (Δ·n)(n·T) = |n|²/2 · d(ρ²)
  BiPoly G;             // |n|² |n×Δ|² L² − R_a² Q'²: binormal condition, both branches
  BiPoly sphere;        // |Δ|² − R_a²
  BiPoly axis_test;     // |n|² L² − R_a² |n × T|²: <= 0 where a binormal leaves an axis point
};
PairFrame make_frame(const Circle3& a, const Circle3& b);

// G restricted to the ellipse: G(x, ±√s) = A(x) ± √s B(x).
void reduce_on_ellipse(const BiPoly& p, const UPoly& s, UPoly* A, UPoly* B);

// Clears denominators (positive factor, signs preserved) and removes the content.
Poly1Z to_integer_poly(const UPoly& p);

// A point of circle b, exactly: x algebraic, y = sigma·√s(x), sigma = 0 iff s(x) = 0.
struct PointB {
  Real1 x;
  int sigma = 0;
};

// Exact sign of p at a point of b.
int sign_on_b(const PairFrame& f, const BiPoly& p, const PointB& pt);
// Points of b on the line c0 + c1 x + c2 y = 0 ((c1, c2) != 0).
std::vector<PointB> points_on_line(const PairFrame& f, const mpq_class& c0, const mpq_class& c1,
                                   const mpq_class& c2);
// Points of b on the axis of a (at most 2). `sign` must be an exact sign at
// points of b (a filtered version of sign_on_b is welcome).
using SignOnB = std::function<int(const BiPoly&, const PointB&)>;
std::vector<PointB> axis_crossings(const PairFrame& f, const SignOnB& sign);
bool same_point(const PointB& p, const PointB& q);
int sign_of_s(const PairFrame& f, const Real1& x);

}  // namespace revdist::exact_detail
