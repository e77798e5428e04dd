// Internal to exact/: a small RAII wrapper over MPFI intervals, enough to
// enclose point-to-circle distances with outward rounding.
#pragma once
#include <gmpxx.h>
#include <mpfi.h>
#include <mpfr.h>

#include <utility>

namespace revdist::exact_detail {

class Iv {
 public:
  explicit Iv(mpfr_prec_t prec) { mpfi_init2(v_, prec); }
  Iv(mpfr_prec_t prec, const mpq_class& q) : Iv(prec) { mpfi_set_q(v_, q.get_mpq_t()); }
  Iv(const Iv& o) : Iv(mpfi_get_prec(o.v_)) { mpfi_set(v_, o.v_); }
  Iv& operator=(const Iv& o) {
    if (this != &o) {
      mpfi_set_prec(v_, mpfi_get_prec(o.v_));
      mpfi_set(v_, o.v_);
    }
    return *this;
  }
  ~Iv() { mpfi_clear(v_); }
  mpfi_ptr get() { return v_; }
  mpfi_srcptr get() const { return v_; }
  mpfr_prec_t prec() const { return mpfi_get_prec(v_); }

  friend Iv operator+(const Iv& a, const Iv& b) { Iv r(a.prec()); mpfi_add(r.v_, a.v_, b.v_); return r; }
  friend Iv operator-(const Iv& a, const Iv& b) { Iv r(a.prec()); mpfi_sub(r.v_, a.v_, b.v_); return r; }
  friend Iv operator*(const Iv& a, const Iv& b) { Iv r(a.prec()); mpfi_mul(r.v_, a.v_, b.v_); return r; }
  friend Iv operator/(const Iv& a, const Iv& b) { Iv r(a.prec()); mpfi_div(r.v_, a.v_, b.v_); return r; }
  friend Iv sqr(const Iv& a) { Iv r(a.prec()); mpfi_sqr(r.v_, a.v_); return r; }
  friend Iv hypot(const Iv& a, const Iv& b) { Iv r(a.prec()); mpfi_hypot(r.v_, a.v_, b.v_); return r; }
  // Square root of a quantity known to be >= 0: the negative part of the
  // enclosure is rounding noise and is cut off.
  friend Iv sqrt_nonneg(const Iv& a) {
    Iv c = a;
    if (mpfr_sgn(&c.v_->left) < 0) mpfr_set_zero(&c.v_->left, 1);
    if (mpfr_sgn(&c.v_->right) < 0) mpfr_set_zero(&c.v_->right, 1);
    Iv r(a.prec());
    mpfi_sqrt(r.v_, c.v_);
    return r;
  }
  friend Iv neg(const Iv& a) { Iv r(a.prec()); mpfi_neg(r.v_, a.v_); return r; }

 private:
  mpfi_t v_;
};

// An owned MPFR number (for bounds kept across precision changes).
class Fr {
 public:
  explicit Fr(mpfr_prec_t prec = 64) { mpfr_init2(v_, prec); mpfr_set_inf(v_, 1); }
  Fr(const Fr& o) : Fr(mpfr_get_prec(o.v_)) { mpfr_set(v_, o.v_, MPFR_RNDN); }
  Fr& operator=(const Fr& o) {
    if (this != &o) {
      mpfr_set_prec(v_, mpfr_get_prec(o.v_));
      mpfr_set(v_, o.v_, MPFR_RNDN);
    }
    return *this;
  }
  ~Fr() { mpfr_clear(v_); }
  mpfr_ptr get() { return v_; }
  mpfr_srcptr get() const { return v_; }

 private:
  mpfr_t v_;
};

}  // namespace revdist::exact_detail
