// Internal to exact/: a closed interval of doubles with outward rounding, the
// cheap twin of fit_audit_detail::Ia (MPFI) for the solid distance's boxes.
// Every IEEE operation is correctly rounded to nearest, so moving each computed
// end one ulp outward (nextafter) encloses the exact result: a proof, only
// looser (~1e-16 relative) than 128-bit MPFI, and ~50x cheaper (no allocation).
// Requires -ffp-contract=off (the project default): a fused a*b+c would break
// the per-operation rounding argument.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

namespace revdist::exact_detail {

class Di {
 public:
  Di() = default;
  Di(double d) : l_(d), h_(d) {}  // NOLINT: a double is exactly itself
  Di(double lo, double hi) : l_(lo), h_(hi) {}
  static Di entire() { return {-kInf, kInf}; }

  double lo() const { return l_; }
  double hi() const { return h_; }
  bool nonneg() const { return l_ >= 0; }
  bool pos() const { return l_ > 0; }
  bool neg() const { return h_ < 0; }
  bool nonpos() const { return h_ <= 0; }

  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static double dn(double x) { return std::nextafter(x, -kInf); }
  static double up(double x) { return std::nextafter(x, kInf); }
  // The hull of computed ends moved outward; a NaN (0 * inf) means "anything".
  static Di out(double lo, double hi) {
    if (std::isnan(lo) || std::isnan(hi)) return entire();
    return {dn(lo), up(hi)};
  }

 private:
  double l_ = 0.0, h_ = 0.0;
};

inline Di operator+(const Di& a, const Di& b) { return Di::out(a.lo() + b.lo(), a.hi() + b.hi()); }
inline Di operator-(const Di& a, const Di& b) { return Di::out(a.lo() - b.hi(), a.hi() - b.lo()); }
inline Di operator-(const Di& a) { return {-a.hi(), -a.lo()}; }
inline Di operator*(const Di& a, const Di& b) {
  const double p[4] = {a.lo() * b.lo(), a.lo() * b.hi(), a.hi() * b.lo(), a.hi() * b.hi()};
  for (double v : p)
    if (std::isnan(v)) return Di::entire();
  return Di::out(std::min({p[0], p[1], p[2], p[3]}), std::max({p[0], p[1], p[2], p[3]}));
}
inline Di operator/(const Di& a, const Di& b) {
  if (!(b.pos() || b.neg())) return Di::entire();
  const double p[4] = {a.lo() / b.lo(), a.lo() / b.hi(), a.hi() / b.lo(), a.hi() / b.hi()};
  for (double v : p)
    if (std::isnan(v)) return Di::entire();
  return Di::out(std::min({p[0], p[1], p[2], p[3]}), std::max({p[0], p[1], p[2], p[3]}));
}
inline Di abs(const Di& a) {
  if (a.nonneg()) return a;
  if (a.nonpos()) return -a;
  return {0.0, std::max(-a.lo(), a.hi())};
}
inline Di sqr(const Di& a) {
  const Di m = abs(a);
  const double lo = m.lo() * m.lo(), hi = m.hi() * m.hi();
  return {m.lo() > 0 ? Di::dn(lo) : 0.0, Di::up(hi)};  // a square is never below 0
}
// As fit_audit_detail::sqrt_nonneg: a negative part is rounding noise, cut off.
inline Di sqrt_nonneg(const Di& a) {
  const double lo = std::max(a.lo(), 0.0), hi = std::max(a.hi(), 0.0);
  if (std::isnan(lo) || std::isnan(hi)) return Di::entire();
  return {lo > 0 ? Di::dn(std::sqrt(lo)) : 0.0, Di::up(std::sqrt(hi))};
}
// Both enclose the same range; if rounding ever made the meet empty, a is kept.
inline Di meet(const Di& a, const Di& b) {
  const double lo = std::max(a.lo(), b.lo()), hi = std::min(a.hi(), b.hi());
  return lo <= hi ? Di(lo, hi) : a;
}

}  // namespace revdist::exact_detail
