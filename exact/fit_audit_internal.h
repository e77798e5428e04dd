// Internal to exact/fit_audit*: MPFI intervals and interval Bernstein
// polynomials, and the curve part piece[u0, u1] as rational Bezier segments with
// interval control points (the exact curve lies in every enclosure).
#pragma once
#include <mpfi.h>
#include <mpfr.h>

#include <string>
#include <vector>

#include "core/profile.h"

namespace revdist::fit_audit_detail {

// 128 bits: the smallest quantities enclosed are rounding-level gaps (~1e-16 of
// the coordinates) next to terms of size ~1, so 2^-128 leaves 20 digits to spare.
constexpr mpfr_prec_t kPrec = 128;

// An MPFI interval at kPrec. Value-semantic; moves swap, so containers of Ia
// reallocate without re-rounding.
class Ia {
 public:
  Ia() { mpfi_init2(v_, kPrec); mpfi_set_ui(v_, 0); }
  Ia(double d) : Ia() { mpfi_set_d(v_, d); }  // exact: a double is a rational  NOLINT
  Ia(const Ia& o) : Ia() { mpfi_set(v_, o.v_); }
  Ia(Ia&& o) noexcept : Ia() { mpfi_swap(v_, o.v_); }
  Ia& operator=(const Ia& o) {
    mpfi_set(v_, o.v_);
    return *this;
  }
  Ia& operator=(Ia&& o) noexcept {
    mpfi_swap(v_, o.v_);
    return *this;
  }
  ~Ia() { mpfi_clear(v_); }

  mpfi_ptr p() { return v_; }
  mpfi_srcptr p() const { return v_; }
  double lo() const { return mpfr_get_d(&v_->left, MPFR_RNDD); }  // rounded down
  double hi() const { return mpfr_get_d(&v_->right, MPFR_RNDU); }  // rounded up
  bool nonneg() const { return mpfr_sgn(&v_->left) >= 0; }   // every point >= 0
  bool pos() const { return mpfr_sgn(&v_->left) > 0; }       // every point > 0
  bool neg() const { return mpfr_sgn(&v_->right) < 0; }      // every point < 0
  bool nonpos() const { return mpfr_sgn(&v_->right) <= 0; }  // every point <= 0
  // Width right - left, rounded up (lo()/hi() would add an ulp of the value).
  double width() const {
    mpfr_t d;
    mpfr_init2(d, kPrec);
    mpfr_sub(d, &v_->right, &v_->left, MPFR_RNDU);
    const double r = mpfr_get_d(d, MPFR_RNDU);
    mpfr_clear(d);
    return r;
  }

 private:
  mpfi_t v_;
};

#define REVDIST_IA_BINOP(op, fn)                      \
  inline Ia operator op(const Ia& a, const Ia& b) {   \
    Ia r;                                             \
    fn(r.p(), a.p(), b.p());                          \
    return r;                                         \
  }
REVDIST_IA_BINOP(+, mpfi_add)
REVDIST_IA_BINOP(-, mpfi_sub)
REVDIST_IA_BINOP(*, mpfi_mul)
REVDIST_IA_BINOP(/, mpfi_div)
#undef REVDIST_IA_BINOP

#define REVDIST_IA_UNARY(name, fn) \
  inline Ia name(const Ia& a) {    \
    Ia r;                          \
    fn(r.p(), a.p());              \
    return r;                      \
  }
REVDIST_IA_UNARY(operator-, mpfi_neg)
REVDIST_IA_UNARY(sqr, mpfi_sqr)
REVDIST_IA_UNARY(abs, mpfi_abs)
REVDIST_IA_UNARY(cos, mpfi_cos)
REVDIST_IA_UNARY(sin, mpfi_sin)
#undef REVDIST_IA_UNARY

// Square root of a quantity known to be >= 0: a negative part of the enclosure
// is rounding noise and is cut off.
inline Ia sqrt_nonneg(const Ia& a) {
  Ia c = a;
  if (mpfr_sgn(&c.p()->left) < 0) mpfr_set_zero(&c.p()->left, 1);
  if (mpfr_sgn(&c.p()->right) < 0) mpfr_set_zero(&c.p()->right, 1);
  Ia r;
  mpfi_sqrt(r.p(), c.p());
  return r;
}
inline Ia atan2(const Ia& y, const Ia& x) {
  Ia r;
  mpfi_atan2(r.p(), y.p(), x.p());
  return r;
}
inline Ia hull(const Ia& a, const Ia& b) {
  Ia r;
  mpfi_union(r.p(), a.p(), b.p());
  return r;
}
inline Ia pi() {
  Ia r;
  mpfi_const_pi(r.p());
  return r;
}

struct P2 {
  Ia x, y;
};
inline P2 operator+(const P2& a, const P2& b) { return {a.x + b.x, a.y + b.y}; }
inline P2 operator-(const P2& a, const P2& b) { return {a.x - b.x, a.y - b.y}; }
inline P2 operator*(const Ia& s, const P2& a) { return {s * a.x, s * a.y}; }
inline Ia dot(const P2& a, const P2& b) { return a.x * b.x + a.y * b.y; }
inline Ia cross(const P2& a, const P2& b) { return a.x * b.y - a.y * b.x; }
inline P2 perp(const P2& a) { return {-a.y, a.x}; }
inline Ia norm(const P2& a) { return sqrt_nonneg(sqr(a.x) + sqr(a.y)); }

// Bernstein coefficients of a polynomial on the node's parameter interval.
using Poly = std::vector<Ia>;

// De Casteljau at t = 1/2 (halving is exact in binary): the coefficients of the
// two halves. Returns the value at the midpoint (left.back() == right.front()).
void halve(const Poly& c, Poly& left, Poly& right);

// Bernstein coefficients of the product of two polynomials of degree p.
Poly bernstein_product(const Poly& f, const Poly& g);

// One rational Bezier segment in homogeneous form (w x, w y, w), interval
// coefficients, weights' enclosures positive.
struct HomSeg {
  Poly x, y, w;
};

// The curve part piece[u0, u1] (parameters as in core/curve_eval.h) as
// consecutive segments whose union is exactly that part of the curve: bezier and
// bspline pieces by blossoming on the exact knots and control points (one
// segment per knot span met); lines as one segment; arcs, whose exact circle
// goes through the three rational points, uniform in angle, as rational
// quadratics of at most ~86 degrees with enclosed control points. Empty with
// `reason` set when the part cannot be enclosed (collinear arc points, ...).
std::vector<HomSeg> curve_part_segments(const Piece& piece, double u0, double u1, std::string* reason);

}  // namespace revdist::fit_audit_detail
